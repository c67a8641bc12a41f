"""The hand-written RTL has one flop idiom (docs/handoff.md, "RTL style"): control state in
`always_ff @(posedge clk_i or negedge rst_ni) begin if (!rst_ni) ...`, datapath flops without a
reset in `always_ff @(posedge clk_i) begin`, a synchronous clear only through msr_clr_reg (the
MSR_CLR_REG macros), always begin/end; no latch, no other clock or reset. The generated register
block (rtl/regs/) is not hand-written."""
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
ASYNC = "@(posedge clk_i or negedge rst_ni)"
PLAIN = "@(posedge clk_i)"
# The assertion macros sample on their clock argument (simulation and formal only); msr_clr_reg
# is the clear register the macros name, the one place its reset-then-clear form is written.
EXEMPT = {"rtl/prim/msr_assert.svh", "rtl/prim/msr_clr_reg.sv"}
# Files still to be brought to the idiom (none: every hand-written file is in it).
PENDING: set[str] = set()


def hand_written():
    for p in sorted((ROOT / "rtl").rglob("*.sv*")):
        rel = str(p.relative_to(ROOT))
        if p.suffix in (".sv", ".svh") and not rel.startswith("rtl/regs/") and rel not in EXEMPT:
            yield rel, p.read_text()


def block(text: str, start: int) -> str:
    """The begin .. end block that opens at start, nesting counted."""
    depth, pos = 0, start
    for m in re.compile(r"\b(begin|end)\b").finditer(text, start):
        depth += 1 if m.group(1) == "begin" else -1
        pos = m.end()
        if depth == 0:
            break
    return text[start:pos]


def flop_findings(rel: str, text: str) -> list[str]:
    text = re.sub(r"//[^\n]*|/\*.*?\*/", "", text, flags=re.S)
    out = []
    line = lambda i: text.count("\n", 0, i) + 1      # noqa: E731
    for m in re.finditer(r"\balways(_ff|_latch|_comb)?\b\s*(@\s*\([^)]*\))?\s*(\w+)?", text):
        kind, sens, first = m.group(1), re.sub(r"\s+", " ", m.group(2) or ""), m.group(3)
        where = f"{rel}:{line(m.start())}"
        if kind == "_comb":
            continue
        if kind != "_ff":
            out.append(f"{where}: always{kind or ''} (a latch or an untyped process)")
            continue
        if sens not in (ASYNC, PLAIN):
            out.append(f"{where}: always_ff {sens}: another clock or reset")
            continue
        if first != "begin":
            out.append(f"{where}: a one-line always_ff")
            continue
        body = block(text, m.start(3))
        if sens == ASYNC:
            if not re.match(r"begin\s*if\s*\(\s*!\s*rst_ni\s*\)", body):
                out.append(f"{where}: an asynchronous block that does not open with if (!rst_ni)")
            if re.search(r"\belse\s+if\s*\(\s*(clear|clr)\w*\s*\)", body):
                out.append(f"{where}: a synchronous clear by hand (MSR_CLR_REG)")
        elif re.search(r"\b(rst\w*|\w*reset\w*|clear\w*|clr\w*)\b", body):
            out.append(f"{where}: a reset or clear in a block without one (datapath flops have none)")
    return out


def test_one_flop_idiom():
    findings = [f for rel, text in hand_written() if rel not in PENDING for f in flop_findings(rel, text)]
    assert not findings, "\n".join(findings)


def test_pending_files_still_need_it():
    """A file brought to the idiom leaves PENDING, so the list says what is left."""
    done = [rel for rel, text in hand_written() if rel in PENDING and not flop_findings(rel, text)]
    assert not done, f"{done}: in the idiom now, take them off PENDING"


def test_the_checker_sees_each_other_form():
    bad = {
        "always_ff @(posedge clk_i) q <= d;": "one-line",
        "always_ff @(posedge clk) begin q <= d; end": "another clock",
        "always_ff @(posedge clk_i or posedge rst_i) begin if (rst_i) q <= 0; end": "another clock",
        "always_ff @(posedge clk_i) begin if (!rst_ni) q <= 0; else q <= d; end": "reset or clear",
        "always_ff @(posedge clk_i) begin if (clear_i) q <= 0; else q <= d; end": "reset or clear",
        "always_latch begin if (en) q <= d; end": "latch",
        "always @(posedge clk_i) q <= d;": "untyped",
        "always_ff @(posedge clk_i or negedge rst_ni) begin if (!rst_ni) q <= 0; "
        "else if (clear_i) q <= 0; else q <= d; end": "synchronous clear",
    }
    for src, what in bad.items():
        found = flop_findings("x.sv", src)
        assert len(found) == 1 and what in found[0], (src, found)
    good = ("always_ff @(posedge clk_i or negedge rst_ni) begin\n  if (!rst_ni) begin q <= 0; end\n"
            "  else begin q <= d; end\nend\nalways_ff @(posedge clk_i) begin if (en) r <= d; end")
    assert flop_findings("x.sv", good) == []
