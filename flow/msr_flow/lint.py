"""make lint: every RTL module of rtl/msr.f through three linters, zero warnings allowed.

- Verilator 5.048 --lint-only -Wall, one run per module as top (with the package and the
  modules it instantiates); waivers are lint_off/lint_on comments per signal in the RTL.
- Verible lint per file with rtl/verible.rules; waivers are `verilog_lint: waive` comments.
- pyslang (slang) full elaboration per module as top, every warning an error.
The generated register block (rtl/regs/, PeakRDL-regblock) is not edited by hand: its
findings are waived per rule and signal, with reasons, in rtl/regs/msr_regs.vlt (Verilator)
and rtl/regs/verible.waiver (Verible).
Exit status 1 on any warning or error; one line per finding. Each tool run has a time limit
(--timeout) that ends it and every process it started."""
from __future__ import annotations

import argparse
import re
import sys

from . import proc
from .filelist import rtl_incdirs, rtl_sources, with_macros

from .filelist import ROOT


def modules(files):
    """(module name, file) of every module defined in the file list."""
    out = []
    for f in files:
        for m in re.finditer(r"^\s*module\s+(\w+)", f.read_text(), re.M):
            out.append((m.group(1), f))
    return out


def closure(files, top_file):
    """The files one module needs, in file-list order: the packages and modules it names,
    recursively. So every module is linted by itself, not with unrelated neighbours."""
    defs = {}
    for f in files:
        for m in re.finditer(r"^\s*(?:module|package)\s+(\w+)", f.read_text(), re.M):
            defs[m.group(1)] = f
    need, todo = {top_file}, [top_file]
    while todo:
        text = with_macros(re.sub(r"//.*", "", todo.pop().read_text()))
        for name, f in defs.items():
            if f not in need and re.search(rf"\b{name}\b", text):
                need.add(f)
                todo.append(f)
    return [f for f in files if f in need]


TIMEOUT_S = 600.0          # per tool run (--timeout)


def run(cmd, timeout: float = TIMEOUT_S) -> tuple[int, str]:
    p = proc.run(cmd, cwd=ROOT, timeout=timeout)
    if p.timed_out:
        return 124, p.output + f"\n%Error: {cmd[0]} TIMEOUT after {timeout:.0f} s"
    return p.returncode, p.output


# Waivers for the generated register block (PeakRDL-regblock output is not edited by hand).
VERILATOR_WAIVERS = ROOT / "rtl" / "regs" / "msr_regs.vlt"
VERIBLE_WAIVERS = ROOT / "rtl" / "regs" / "verible.waiver"


def verilator(files, top, timeout: float = TIMEOUT_S) -> list[str]:
    rc, out = run(["verilator", "--lint-only", "-Wall", *[f"-I{d}" for d in rtl_incdirs()], "--top-module", top, str(VERILATOR_WAIVERS),
                   *map(str, files)], timeout)
    bad = [ln for ln in out.splitlines() if ln.startswith("%")]
    return bad if bad or rc == 0 else [f"verilator exit {rc}"]


def verible(files, timeout: float = TIMEOUT_S) -> list[str]:
    rc, out = run(["verible-verilog-lint", "--rules_config=rtl/verible.rules",
                   f"--waiver_files={VERIBLE_WAIVERS.relative_to(ROOT)}", *map(str, files)], timeout)
    bad = [ln for ln in out.splitlines() if ln.strip()]
    return bad if bad or rc == 0 else [f"verible exit {rc}"]


# pyslang's driver prints some diagnostics straight to the process's stdout instead of its
# text client, so slang runs in a child process and everything it prints is searched.
SLANG_CHILD = """
import sys, pyslang
d = pyslang.driver.Driver()
d.addStandardArgs()
if not d.parseCommandLine(" ".join(sys.argv[1:]), pyslang.driver.CommandLineOptions()) or not d.processOptions():
    print("error: bad slang command line"); sys.exit(1)
if not d.parseAllSources():
    print("error: parse errors"); sys.exit(1)
comp = d.createCompilation()
for diag in comp.getAllDiagnostics():
    d.diagEngine.issue(diag)
print(d.textDiagClient.getString())
"""


def slang(files, top, timeout: float = TIMEOUT_S) -> list[str]:
    args = ["slang", "--top", top, *[a for d in rtl_incdirs() for a in ("-I", str(d))], "-Wextra", "-Wno-case-redundant-default", "--error-limit=100",
            *map(str, files)]
    rc, out = run([sys.executable, "-c", SLANG_CHILD, *args], timeout)
    bad = [ln for ln in out.splitlines() if re.search(r"(warning|error):", ln)]
    return bad if bad or rc == 0 else [f"slang exit {rc}"]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--timeout", type=float, default=TIMEOUT_S, help="seconds per tool run")
    timeout = ap.parse_args(argv).timeout
    files = rtl_sources()
    missing = [f for f in files if not f.exists()]
    if missing:
        print(f"lint: {missing[0]} listed in rtl/msr.f does not exist")
        return 1
    findings = []
    findings += [f"verible: {x}" for x in verible(files, timeout)]
    for top, top_file in modules(files):
        own = closure(files, top_file)
        findings += [f"verilator[{top}]: {x}" for x in verilator(own, top, timeout)]
        findings += [f"slang[{top}]: {x}" for x in slang(own, top, timeout)]
    n_mod = len(modules(files))
    for f in findings:
        print(f)
    print(f"lint: {n_mod} modules, {len(files)} files: "
          f"{'clean' if not findings else f'{len(findings)} findings'}")
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
