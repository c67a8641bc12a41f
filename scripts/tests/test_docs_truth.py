"""Figures the documents state that the RTL also holds: each is read from the code and from
the document, and the test fails when they part (docs true to the code).

A figure is read from what the hardware is built from (a parameter's default, an enum's
members, the register stages of a pipeline), not from a comment, and from the document by
the phrase that states it. When a design change moves one, change the document with it."""
from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
RTL = ROOT / "rtl"
DOCS = ROOT / "docs"


def rtl_text(*names: str) -> str:
    """The source of the named files under rtl/ (found in any folder)."""
    out = []
    for n in names:
        hits = list(RTL.rglob(n))
        assert len(hits) == 1, f"{n}: {len(hits)} files"
        out.append(hits[0].read_text())
    return "\n".join(out)


def engine_units() -> str:
    return "\n".join(p.read_text() for p in sorted((RTL / "engine").glob("*.sv")))


def param_default(text: str, name: str) -> int:
    # A declaration may list several names: `localparam int unsigned A = 1, B = 2;`.
    m = re.search(rf"\b(?:parameter|localparam)\s+int\s+unsigned\s+(?:\w+\s*=\s*\d+\s*,\s*)*"
                  rf"{name}\s*=\s*(\d+)", text)
    assert m, f"no parameter {name}"
    return int(m.group(1))


def decision_stages() -> int:
    """Register stages of msr_decision_pipe: one valid flag per inner stage (s<k>_valid_q)
    and the output register behind the last of them."""
    inner = set(re.findall(r"\bs(\d)_valid_q\b", rtl_text("msr_decision_pipe.sv")))
    assert inner == {str(k) for k in range(len(inner))}, f"stage flags {sorted(inner)} not 0..n-1"
    return len(inner) + 1


def level_setup_cycles() -> int:
    """Set-up states the level controller passes through at the start of every pass."""
    return len(set(re.findall(r"\bWS_SETUP\d\b", rtl_text("msr_level_ctrl.sv"))))


def check_clocks() -> int:
    """Clocks from START to the configuration decision: SAMPLE, then CHECK steps 0..STEP_END."""
    return 1 + param_default(rtl_text("msr_cfg_ctrl.sv"), "STEP_END") + 1


def doc_number(doc: str, pattern: str) -> int:
    text = re.sub(r"\s+", " ", (DOCS / doc).read_text())
    m = re.search(pattern, text)
    assert m, f"docs/{doc}: no phrase matching {pattern!r}"
    return int(m.group(1))


FACTS = [
    # (what, from the code, document, phrase in it)
    ("decision pipeline stages", decision_stages, "architecture.md", r"in one (\d+)-stage pipeline"),
    ("level controller set-up cycles per pass", level_setup_cycles, "architecture.md",
     r"Each pass starts with (\d+) set-up cycles"),
    ("engine output buffer entries", lambda: param_default(engine_units(), "OUT_DEPTH_RD1"),
     "architecture.md", r"the (\d+)-entry output buffer"),
    ("tile contexts per engine (the top's default)",
     lambda: param_default(rtl_text("msr_top.sv"), "NUM_CTX"), "architecture.md",
     r"NUM_CTX contexts \(default (\d+) in the top"),
    ("render requests in flight per engine (tags)",
     lambda: param_default(rtl_text("msr_top.sv"), "MAX_OUTSTANDING"), "architecture.md",
     r"(\d+) tags per engine"),
    ("configuration check clocks", check_clocks, "system.md", r"checked from registers in `msr_cfg_ctrl` \((\d+) clocks"),
    ("AXI4-Lite response FIFO entries", lambda: param_default(rtl_text("msr_axil_cpuif.sv"), "RSP_DEPTH"),
     "system.md", r"a (\d+)-entry response FIFO"),
    ("render mux request queue entries",
     lambda: int(re.search(r"\.DEPTH\((\d+)\)\)\s*u_req_fifo", rtl_text("msr_render_mux.sv")).group(1)),
     "system.md", r"a (\d+)-entry request queue per engine"),
]


@pytest.mark.parametrize("what,from_code,doc,phrase", FACTS, ids=[f[0] for f in FACTS])
def test_document_states_what_the_rtl_builds(what, from_code, doc, phrase):
    assert doc_number(doc, phrase) == from_code(), f"docs/{doc} and the RTL disagree on the {what}"


def test_checker_binding_target_is_what_the_binds_name():
    """docs/verification.md names the modules the checkers bind to; the binds file decides."""
    binds = (RTL / "checkers" / "msr_checker_binds.sv").read_text()
    targets = set(re.findall(r"^\s*bind\s+(\w+)", binds, re.M))
    text = (DOCS / "verification.md").read_text()
    m = re.search(r"holds the two `bind` statements \(to the modules ([^)]*)\)", re.sub(r"\s+", " ", text))
    assert m, "docs/verification.md: the binding paragraph moved"
    named = set(re.findall(r"`(msr_\w+)`", m.group(1)))
    assert named == targets, f"docs say {sorted(named)}, the binds file binds {sorted(targets)}"


def test_every_engine_unit_is_in_the_architecture_table():
    """docs/architecture.md's engine table has a row for every module under rtl/engine/ (a
    unit split out of the engine is documented where a reader looks for it)."""
    mods = set()
    for p in (RTL / "engine").glob("*.sv"):
        mods |= set(re.findall(r"^module\s+(\w+)", p.read_text(), re.M))
    text = (DOCS / "architecture.md").read_text()
    rows = set(re.findall(r"^\| `(msr_\w+)`", text, re.M))
    missing = sorted(mods - rows)
    assert not missing, f"docs/architecture.md has no row for {missing}"
