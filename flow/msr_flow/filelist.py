"""The one reader of the source-of-truth file list rtl/msr.f: sources in order, include
folders, the RTL's content digest and the macro bodies of its headers. Every flow (cocotb,
the Verilator harness, lint, synthesis, the standard-cell flow, equivalence) gets its
sources here; run as `python -m msr_flow.filelist` it prints the list with its options for
the Makefiles (`MSR_RTL_FILES`), and `--core` writes msr.core from it."""
from __future__ import annotations

import functools
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
RTL = ROOT / "rtl"
FILE_LIST = RTL / "msr.f"


def rtl_entries(file_list: Path = FILE_LIST) -> list[str]:
    """Every entry of rtl/msr.f in order, as written: tool options ('+incdir+...', '-...') and
    source files relative to the repository; '//' and '#' start comments."""
    out = []
    for line in file_list.read_text().splitlines():
        out += line.split("//")[0].split("#")[0].split()
    return out


@functools.lru_cache(maxsize=1)
def macro_bodies() -> dict[str, str]:
    """Every `define of the RTL's headers (rtl/*/*.svh): name -> body. A unit that writes its
    flops or bus ports through a macro (msr_flops.svh, msr_axi_ports.svh) names the modules
    inside the body only there; readers that find a unit's submodules by name in its text
    (lint's closure, the ASIC flow's hierarchy) add the bodies of the macros it uses. Read once
    a process: those readers ask for every file and module."""
    out = {}
    for h in sorted(RTL.glob("*/*.svh")):
        text = h.read_text()
        for m in re.finditer(r"^`define\s+(\w+)(.*?)(?<!\\)$", text, re.M | re.S):
            out[m.group(1)] = m.group(2)
    return out


def with_macros(text: str, bodies: dict[str, str] | None = None) -> str:
    """text and, appended, the bodies of the macros it uses (transitively)."""
    bodies = macro_bodies() if bodies is None else bodies
    seen, todo, extra = set(), [text], []
    while todo:
        for name in re.findall(r"`(\w+)", todo.pop()):
            if name in bodies and name not in seen:
                seen.add(name)
                extra.append(bodies[name])
                todo.append(bodies[name])
    return "\n".join([text, *extra])


def rtl_sources(file_list: Path = FILE_LIST) -> list[Path]:
    """Source files of rtl/msr.f in order (package first), as absolute paths."""
    return [ROOT / e for e in rtl_entries(file_list) if not e.startswith(("+", "-"))]


def rtl_incdirs(file_list: Path = FILE_LIST) -> list[Path]:
    """Include folders named by `+incdir+DIR` lines of rtl/msr.f, as absolute paths."""
    return [ROOT / d for e in rtl_entries(file_list) if e.startswith("+incdir+")
            for d in e[len("+incdir+"):].split("+") if d]


def rtl_digest(file_list: Path = FILE_LIST) -> str:
    """A short content hash of the RTL that rtl/msr.f names (its sources and the headers of its
    include folders). A measured figure records it (make bench), so a later reader (make synth's
    pixels per clock) can tell whether the figure was taken on the RTL it is combined with."""
    import hashlib
    h = hashlib.sha256()
    files = rtl_sources(file_list) + sorted(p for d in rtl_incdirs(file_list) for p in d.glob("*.svh"))
    for p in files:
        h.update(str(p.relative_to(ROOT)).encode() + b"\0" + p.read_bytes() + b"\0")
    return h.hexdigest()[:12]


def core_text(file_list: Path = FILE_LIST, core: Path = ROOT / "msr.core") -> str:
    """msr.core with its `rtl` fileset generated from rtl/msr.f (the same files, the same
    order); the rest of the core (targets, parameters, the harness fileset) is kept."""
    files = "".join(f"      - {p.relative_to(ROOT)}\n" for p in rtl_sources(file_list))
    text = core.read_text()
    return re.sub(r"^(  rtl:\n    files:\n)(?:      - .*\n)+", lambda m: m.group(1) + files, text,
                  count=1, flags=re.M)


if __name__ == "__main__":
    import sys
    if sys.argv[1:] == ["--core"]:
        (ROOT / "msr.core").write_text(core_text())
    else:
        print(" ".join(rtl_entries()))
