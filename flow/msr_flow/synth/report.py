"""The report model: build/synth/report.json assembled from the runs' results (the top's rows
composed bottom-up, its seeds folded into one row with its pixel rate), and the merge of a
unit run's rows into the committed whole-design report (docs/synthesis.json)."""
from __future__ import annotations

import json
import subprocess
import sys
import time

from msr_flow.filelist import rtl_digest

from .config import ECP5_DEVICE, ECP5_DP16KD, ENGINE, FLOORPLAN_PNG, ROOT, TOOLS, TOP
from .ecp5 import combine_seeds
from .floorplan import floorplan_picture
from .sources import Design
from .yosys import compose

# Pixels per clock of the default top (4 engines) for the pixel rate per LUT4: taken from
# `make bench` (out/bench/report.json, 4 engines at render latency 256) when it exists, else
# this figure (3.79 on 640x480 cornell, docs/performance.md).
BENCH_REPORT = ROOT / "out" / "bench" / "report.json"
DEFAULT_PIXELS_PER_CLOCK = 3.8
# The default top's figures that outside tools read (report.json's "top_ecp5")
TOP_ECP5_KEYS = ("device", "params", "luts", "device_luts", "lut_utilisation", "flip_flops", "block_rams",
                 "dsp_mult18", "fmax_mhz", "fmax_seeds", "fmax_best", "fmax_median", "fmax_worst",
                 "pixels_per_clock", "pixels_per_second_per_lut4")


def pixels_per_clock() -> tuple[float, str]:
    """Pixels per clock of the default top and where the figure comes from. A bench report taken
    on other RTL (its `rtl_digest` differs from the RTL's now) is still used, but said to be
    stale, here and on stderr: rerun `make bench` for a figure of this RTL."""
    try:
        rep = json.loads(BENCH_REPORT.read_text())
        goal = rep["goals"]["pixels_per_clock_4_engines_latency_256"]
        if goal.get("measured"):
            where = str(BENCH_REPORT.relative_to(ROOT) if BENCH_REPORT.is_relative_to(ROOT) else BENCH_REPORT)
            measured_on, now = rep.get("rtl_digest"), rtl_digest()
            if measured_on != now:
                where += (f", measured on other RTL (digest {measured_on}, now {now}): stale, rerun make bench"
                          if measured_on else ", no RTL digest recorded: may be stale, rerun make bench")
                print(f"synth: pixels per clock from {where}", file=sys.stderr)
            return float(goal["measured"]), where
    except (OSError, ValueError, KeyError, TypeError):
        pass
    return DEFAULT_PIXELS_PER_CLOCK, "constant (no out/bench/report.json)"


def add_pixel_rate(row: dict) -> dict:
    """Pixels per second per LUT4 = Fmax x pixels per clock / LUT4 (the default top's figure)."""
    ppc, source = pixels_per_clock()
    row["pixels_per_clock"] = ppc
    row["pixels_per_clock_source"] = source
    if row.get("fmax_mhz") and row.get("luts"):
        row["pixels_per_second"] = round(row["fmax_mhz"] * 1e6 * ppc)
        row["pixels_per_second_per_lut4"] = round(row["fmax_mhz"] * 1e6 * ppc / row["luts"], 1)
    return row


def generic_rows(results: dict, design: Design, mods: list[str], glue_only: bool, failures: list[str]) -> dict:
    """The generic rows by module (file-list order) and kind; the top's are composed from its
    glue and engine runs. A composition that fails is added to `failures`."""
    rows = {}
    for m in design.units:
        if m == TOP and TOP in mods:
            glue = results[("generic", (TOP, "glue"))]
            runs = {"glue": glue}
            for kind in (() if glue_only else ("inferred", "black box")):
                eng = results[("generic", (ENGINE, kind))]
                try:
                    runs[kind] = (compose(glue, eng, design.n_engines, kind)
                                  if "error" not in glue and "error" not in eng else {"error": "a part failed"})
                except RuntimeError as e:
                    runs[kind] = {"error": str(e)}
                    failures.append(str(e))
            rows[TOP] = runs
        elif m == ENGINE and (ENGINE in mods or (TOP in mods and not glue_only)):
            rows[ENGINE] = {k: results[("generic", (ENGINE, k))] for k in ("inferred", "black box")}
        elif m in mods and m not in (ENGINE, TOP):
            rows[m] = {"inferred": results[("generic", (m, "inferred"))]}
    return rows


def top_row(results: dict, seeds: tuple, failures: list[str]) -> dict | None:
    """The flat top's row over its seeds (None if it was not placed), with the picture of the
    median seed's placement; the routed netlists (large) are deleted."""
    seed_rows = [{"seed": s, **results[("ecp5", f"{TOP}@{s}")]} for s in seeds if ("ecp5", f"{TOP}@{s}") in results]
    if not seed_rows:
        return None
    row = combine_seeds(seed_rows)
    failures += [f"{TOP} ECP5 seed {x['seed']}: {x['error']}" for x in row.get("fmax_seeds", []) if "error" in x]
    if "error" in row:
        failures.append(f"{TOP} ECP5: {row['error']}")
    elif row.get("routed_netlist"):
        try:
            row["floorplan_picture"] = str(FLOORPLAN_PNG.relative_to(ROOT))
            row["floorplan_cells"] = floorplan_picture(
                ROOT / row["routed_netlist"], FLOORPLAN_PNG,
                f"msr_top on the {ECP5_DEVICE[2]}, seed {row['seed']} (the median of "
                f"{len(seed_rows)}), {row['fmax_mhz']} MHz")
        except (OSError, ValueError, KeyError) as e:
            row["floorplan_picture_error"] = str(e)
    for r in seed_rows:
        if r.get("routed_netlist"):
            (ROOT / r["routed_netlist"]).unlink(missing_ok=True)
    return row


def assemble(results: dict, failures: list[str], design: Design, mods: list[str], seeds: tuple,
             glue_only: bool, t0: float) -> dict:
    """build/synth/report.json's content from the runs' results; adds what fails (latches, a
    failed seed) to `failures`."""
    report = {"tools": dict(TOOLS), "top_params": design.top_params, "engine_params": design.engine_params,
              "generic": generic_rows(results, design, mods, glue_only, failures), "ecp5": {}}
    top = top_row(results, seeds, failures)
    if top is not None:
        report["ecp5"][TOP] = top
    for m in [TOP, f"{TOP}_glue", ENGINE] + design.units:
        if ("ecp5", m) in results and m not in report["ecp5"]:
            report["ecp5"][m] = results[("ecp5", m)]
    if "luts" in report["ecp5"].get(TOP, {}):
        row = add_pixel_rate(report["ecp5"][TOP])
        report["top_ecp5"] = {k: row.get(k) for k in TOP_ECP5_KEYS}
        report["top_ecp5"]["dp16kd"] = row.get("block_rams")
        report["top_ecp5"]["device_dp16kd"] = ECP5_DP16KD
        row["dp16kd"] = row.get("block_rams")
    # composed rows (the top) repeat their parts' latches: count and report each run once
    runs_done = [(mod, kind, r) for mod, runs in report["generic"].items() for kind, r in runs.items()
                 if "method" not in r]
    failures += [f"{mod} ({kind}): {r['latches']} latches" for mod, kind, r in runs_done if r.get("latches")]
    report["latches_total"] = sum(r.get("latches", 0) for _, _, r in runs_done)
    report["seconds"] = round(time.time() - t0, 1)
    report["failures"] = failures
    return report


def run_commit() -> str:
    """The commit a run measured: HEAD, marked dirty only when the synthesised sources (rtl/)
    differ from it (uncommitted docs do not change a netlist)."""
    try:
        commit = subprocess.run(["git", "describe", "--always"], cwd=ROOT, capture_output=True,
                                text=True, check=True).stdout.strip()
        changed = subprocess.run(["git", "status", "--porcelain", "--", "rtl"], cwd=ROOT,
                                 capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown commit"
    return commit + ("-dirty" if changed else "")


def merge_rows(full: dict, unit: dict, mods: list[str]) -> dict:
    """The whole design's report with the rows of `mods` taken from a unit run (`--modules
    ... --merge`): each merged row names the run (`unit run at <commit>` in its kind), so the
    report says which rows are newer than the rest."""
    out = json.loads(json.dumps(full))
    tag = f"unit run at {run_commit()}"
    for m in mods:
        if m in unit["generic"]:
            out["generic"][m] = {f"{kind} ({tag})": r for kind, r in unit["generic"][m].items()}
        if m in unit["ecp5"]:
            out["ecp5"][m] = {**unit["ecp5"][m], "merged_from": tag}
    if TOP in mods and "top_ecp5" in unit:     # the summary follows the top's row it repeats
        out["top_ecp5"] = unit["top_ecp5"]
    return out


def json_text(report: dict) -> str:
    return json.dumps(report, indent=2) + "\n"
