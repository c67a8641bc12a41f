"""make lint: every RTL module of rtl/msr.f through three linters, zero warnings allowed.

- Verilator 5.048 --lint-only -Wall, one run per module as top (with the package and the
  modules it instantiates); waivers are lint_off/lint_on comments per signal in the RTL.
- Verible lint per file with rtl/verible.rules; waivers are `verilog_lint: waive` comments.
- pyslang (slang) full elaboration per module as top, every warning an error.
The generated register block (rtl/regs/, PeakRDL-regblock) is not edited by hand: its
findings are waived per rule and signal, with reasons, in rtl/regs/msr_regs.vlt (Verilator)
and rtl/regs/verible.waiver (Verible).
Exit status 1 on any warning or error; one line per finding."""
from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

from msr_flow.filelist import rtl_sources, with_macros

ROOT = Path(__file__).resolve().parents[1]


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


def run(cmd) -> tuple[int, str]:
    p = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    return p.returncode, (p.stdout + p.stderr)


# Waivers for the generated register block (PeakRDL-regblock output is not edited by hand).
VERILATOR_WAIVERS = ROOT / "rtl" / "regs" / "msr_regs.vlt"
VERIBLE_WAIVERS = ROOT / "rtl" / "regs" / "verible.waiver"


def verilator(files, top) -> list[str]:
    rc, out = run(["verilator", "--lint-only", "-Wall", "-Irtl/prim", "--top-module", top, str(VERILATOR_WAIVERS),
                   *map(str, files)])
    bad = [ln for ln in out.splitlines() if ln.startswith("%")]
    return bad if bad or rc == 0 else [f"verilator exit {rc}"]


def verible(files) -> list[str]:
    rc, out = run(["verible-verilog-lint", "--rules_config=rtl/verible.rules",
                   f"--waiver_files={VERIBLE_WAIVERS.relative_to(ROOT)}", *map(str, files)])
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


def slang(files, top) -> list[str]:
    args = ["slang", "--top", top, "-I", "rtl/prim", "-Wextra", "-Wno-case-redundant-default", "--error-limit=100",
            *map(str, files)]
    p = subprocess.run([sys.executable, "-c", SLANG_CHILD, *args], cwd=ROOT, capture_output=True, text=True)
    bad = [ln for ln in (p.stdout + p.stderr).splitlines() if re.search(r"(warning|error):", ln)]
    return bad if bad or p.returncode == 0 else [f"slang exit {p.returncode}"]


def main() -> int:
    files = rtl_sources()
    missing = [f for f in files if not f.exists()]
    if missing:
        print(f"lint: {missing[0]} listed in rtl/msr.f does not exist")
        return 1
    findings = []
    findings += [f"verible: {x}" for x in verible(files)]
    for top, top_file in modules(files):
        own = closure(files, top_file)
        findings += [f"verilator[{top}]: {x}" for x in verilator(own, top)]
        findings += [f"slang[{top}]: {x}" for x in slang(own, top)]
    n_mod = len(modules(files))
    for f in findings:
        print(f)
    print(f"lint: {n_mod} modules, {len(files)} files: "
          f"{'clean' if not findings else f'{len(findings)} findings'}")
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
