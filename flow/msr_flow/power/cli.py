"""make power: python -m msr_flow.power (scripts/power.py). Maps (or reuses) the engine and the
top's glue, runs a small frame per decision rule through the traced harness, prices its activity
and writes build/asic/power.json, docs/img/power_balance.png and the power section of
docs/asic.md (data in docs/asic.json under `power`)."""
from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

from ..asic.config import DATA, OUT, TARGET_MHZ, AsicError, rel
from ..filelist import ROOT
from .liberty import read_liberty
from .netlist import read_netlist
from .report import PLOT, build, plot

POWER_JSON = OUT / "power.json"
DOC_KEYS = ("modules", "pj_per_decision", "pj_per_decision_logic_only", "pj_per_pixel", "activity_coverage",
            "headline_rule", "scaled", "rules", "raycore", "balance", "method", "seconds")


def parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="python -m msr_flow.power", description=__doc__)
    ap.add_argument("--harness", default="build/power/harness/Vmsr_sim_top", help="the traced harness (make power builds it)")
    ap.add_argument("--width", type=int, default=160, help="activity frame width (default 160)")
    ap.add_argument("--height", type=int, default=120, help="activity frame height (default 120)")
    ap.add_argument("--rules", default="patent,lindilate", help="decision rules, comma-separated")
    ap.add_argument("--clock-mhz", type=float, default=TARGET_MHZ, help="clock of the power figures (make asic's goal)")
    ap.add_argument("--doc-only", action="store_true", help="only the page's power section from docs/asic.json")
    return ap


def write_doc(power: dict | None) -> None:
    from ..asic.page import write_doc as render
    report = json.loads(DATA.read_text())
    if power is not None:
        report["power"] = {k: power[k] for k in DOC_KEYS if k in power}
        DATA.write_text(json.dumps(report, indent=2) + "\n")
    render(report)


def run(a) -> int:
    if a.doc_only:
        write_doc(None)
        print(f"power: docs/asic.md rewritten from {rel(DATA)}", file=sys.stderr)
        return 0
    from .designs import map_designs
    from .run import power_of_rule
    t0 = time.time()
    harness = (ROOT / a.harness) if not Path(a.harness).is_absolute() else Path(a.harness)
    if not harness.is_file():
        raise AsicError(f"no traced harness {a.harness} (make power builds it)")
    d = map_designs()
    lib_path = OUT / "osu018_stdcells.lib"
    lib = read_liberty(lib_path)
    engine = read_netlist(d.engine.netlist.read_text())["msr_tile_engine"]
    glue = read_netlist(d.glue.netlist.read_text())["msr_top"]
    results = {}
    for rule in [r.strip() for r in a.rules.split(",") if r.strip()]:
        results[rule] = power_of_rule(harness, rule, a.width, a.height, engine, glue, lib, lib_path, a.clock_mhz)
    power = build(results, {"seconds": round(time.time() - t0, 1)})
    POWER_JSON.write_text(json.dumps(power, indent=2) + "\n")
    plot(power["balance"])
    write_doc(power)
    m = power["modules"]
    print(f"power: engine {m['msr_tile_engine']['dynamic_mw']} mW dynamic, {m['msr_tile_engine']['leakage_mw']} mW "
          f"leakage; top {m['msr_top']['dynamic_mw']} mW, {m['msr_top']['leakage_mw']} mW; "
          f"{power['pj_per_decision']} pJ/decision, {power['pj_per_pixel']} pJ/pixel; activity found for "
          f"{power['activity_coverage']:.1%} of the flip-flops", file=sys.stderr)
    print(f"power: {rel(POWER_JSON)}, {rel(PLOT)}, docs/asic.md", file=sys.stderr)
    return 0


def main(argv: list[str] | None = None) -> int:
    try:
        return run(parser().parse_args(argv))
    except AsicError as e:
        print(f"power: {e}", file=sys.stderr)
        return 2
