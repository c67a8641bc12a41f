"""Hardware throughput of the whole accelerator (msr_top) from simulation: `make bench-hw`.

    python scripts/bench_hw.py [--configs "e1_mo16 e1_mo64 e2_mo64 e4_mo64"] [--scene cornell]
        [--width 640 --height 480] [--latencies 0,64,256] [--tiles 8,16,32] [--levels 1,2,3]
        [--tl-engines 4] [--tl-latencies 0,256] [--out out/bench] [--no-tile-sweep]
        [--rule patent|lindilate]   (default: $MSR_BENCH_RULE, else patent)

Each point runs one frame through the Verilator harness (sim/harness.cpp) built per
(NUM_ENGINES, MAX_OUTSTANDING) into build/bench/hw_e<N>_mo<M>/ by mk/bench.mk; the rendering
unit is Embree over DPI-C (render_dpi.sv) answering every request exactly `latency` cycles
after it was taken (+rnd_latency, no jitter). Every RTL frame and source map is compared with
the golden model (same scene, same renderer, same decision rule: CONFIG.RULE and the golden
model's `rule`), so each point also says whether it is bit exact.

Reported per point: cycles from START to DONE (PERF_CYCLES), pixels per clock = W*H / cycles,
traced fraction (perf counters), render-port and memory stall counters, and three lower bounds
on the cycles (what would limit the frame if nothing else did): the writer (its 256-bit AXI W
channel carries eight pixels, or 32 source codes, per beat and clock), the tags (traced * latency / (NUM_ENGINES * MAX_OUTSTANDING): each request
holds one tag for at least the latency) and the shared render port (one request per clock).
Writes out/bench/report.json (merging out/bench/engine.json from bench_engine.py when present)
and out/bench/pixels_per_clock.png. Bad arguments: one line on stderr, exit status 2.
"""
from __future__ import annotations

import json
import os
import sys
import time
from pathlib import Path

from msr_model import Params, spec
from msr_model.clitools import EXIT_BAD_INPUT, Parser, RunFailed, UsageError, int_list, run_main
from ..harness import RTL_RULES, GoldenFrames, HarnessRun, compare
from ..filelist import rtl_digest   # what RTL the figures were measured on

from ..filelist import ROOT

GOAL_DECISIONS = 0.95          # decisions per clock per engine inside a pass
GOAL_PIXELS = 3.6              # pixels per clock, 4 engines, latency 256
GOAL_ENGINES, GOAL_LATENCY = 4, 256


def parse_cfg(name: str) -> tuple[int, int, int | None]:
    """'e4_mo16' -> (NUM_ENGINES 4, MAX_OUTSTANDING 16, None: msr_top's NUM_CTX);
    'e4_mo64_c6' -> (4, 64, NUM_CTX 6) (mk/bench.mk builds it with -GNUM_CTX=6)."""
    try:
        e, mo = name.split("_mo")
        mo, _, ctx = mo.partition("_c")
        if not e.startswith("e") or (_ and not ctx):
            raise ValueError
        return int(e[1:]), int(mo), (int(ctx) if ctx else None)
    except ValueError:
        raise UsageError(f"harness config {name!r} is not e<engines>_mo<outstanding>[_c<contexts>] "
                         "(e.g. e4_mo16, e4_mo64_c6)") from None


def parse(argv):
    ap = Parser(prog="bench_hw", description=__doc__.splitlines()[0])
    ap.add_argument("--configs", default="e1_mo16 e1_mo64 e2_mo64 e4_mo64",
                    help="harness builds e<NUM_ENGINES>_mo<MAX_OUTSTANDING>[_c<NUM_CTX>], space separated")
    ap.add_argument("--build-dir", default=str(ROOT / "build" / "bench"))
    ap.add_argument("--scene", default="cornell")
    ap.add_argument("--width", type=int, default=640)
    ap.add_argument("--height", type=int, default=480)
    ap.add_argument("--latencies", default="0,64,256")
    ap.add_argument("--tile", type=int, default=16, help="T of the engines x latency sweep")
    ap.add_argument("--levels-main", type=int, default=2, help="L of the engines x latency sweep")
    ap.add_argument("--tiles", default="8,16,32", help="T values of the cycles-per-tile sweep")
    ap.add_argument("--levels", default="1,2,3", help="L values of the cycles-per-tile sweep")
    ap.add_argument("--tl-engines", type=int, default=4, help="NUM_ENGINES of the cycles-per-tile sweep")
    ap.add_argument("--tl-latencies", default="0,256")
    ap.add_argument("--no-tile-sweep", action="store_true")
    ap.add_argument("--out", default=str(ROOT / "out" / "bench"))
    ap.add_argument("--engine-json", default=str(ROOT / "out" / "bench" / "engine.json"))
    ap.add_argument("--no-plot", action="store_true")
    ap.add_argument("--no-progress", action="store_true")
    ap.add_argument("--rule", default=os.environ.get("MSR_BENCH_RULE") or "patent",
                    help=f"decision rule, one of {', '.join(RTL_RULES)} (default: $MSR_BENCH_RULE, else patent)")
    a = ap.parse_args(argv)
    if a.rule not in RTL_RULES:
        raise UsageError(f"rule {a.rule!r} (--rule or MSR_BENCH_RULE) is not one of the RTL's: {', '.join(RTL_RULES)}")
    a.cfgs = [parse_cfg(c) for c in a.configs.split()]
    if not a.cfgs:
        raise UsageError("no harness configs given")
    a.latencies = list(int_list(a.latencies, "--latencies"))
    a.tiles = list(int_list(a.tiles, "--tiles"))
    a.levels = list(int_list(a.levels, "--levels"))
    a.tl_latencies = list(int_list(a.tl_latencies, "--tl-latencies"))
    for v in a.latencies + a.tl_latencies:
        if not 0 <= v <= 100000:
            raise UsageError(f"render latency {v} outside 0..100000")
    if not (1 <= a.width <= 4096 and 1 <= a.height <= 4096):
        raise UsageError(f"frame {a.width}x{a.height} outside 1..4096")
    return a


def harness_path(build_dir: Path, engines: int, mo: int, ctx: int | None = None) -> Path:
    return Path(build_dir) / (f"hw_e{engines}_mo{mo}" + (f"_c{ctx}" if ctx else "")) / "Vmsr_sim_top"


def params_for(tile: int, levels: int) -> Params:
    return Params(tile=tile, levels=levels, thr=spec.default_thresholds(levels), metric="max", fov_gain=0)


def run_point(harness: Path, engines: int, mo: int, scene: str, w: int, h: int, tile: int, levels: int,
              latency: int, golden: GoldenFrames | None, rule: str = "patent", ctx: int | None = None,
              rd_lat: int | None = None, tile_limit: int | None = None, buf_cycle: int | None = None) -> dict:
    """One frame through the harness; returns the measured point. ctx, rd_lat, tile_limit,
    buf_cycle: the NUM_CTX, RD_LAT, TILE_LIMIT and BUF_CYCLE the build must have (None: any)."""
    p = params_for(tile, levels)
    rtl = HarnessRun(harness, scene, w, h, p, rule=rule, latency=latency, jitter=0, quiet=True).run()
    st = rtl.stats
    built = (rtl.build["num_engines"], rtl.build["max_outstanding"])
    if built != (engines, mo) or (ctx is not None and rtl.build.get("num_ctx") != ctx):
        raise RunFailed(f"{harness} is a build of NUM_ENGINES {built[0]}, MAX_OUTSTANDING {built[1]}, "
                        f"NUM_CTX {rtl.build.get('num_ctx')}, not e{engines}_mo{mo}" + (f"_c{ctx}" if ctx else ""))
    if rd_lat is not None and rtl.build.get("rd_lat", 1) != rd_lat:
        raise RunFailed(f"{harness} is a build of RD_LAT {rtl.build.get('rd_lat', 1)}, not {rd_lat}")
    if tile_limit is not None and rtl.build.get("tile_limit", 32) != tile_limit:
        raise RunFailed(f"{harness} is a build of TILE_LIMIT {rtl.build.get('tile_limit', 32)}, not {tile_limit}")
    if buf_cycle is not None and rtl.build.get("buf_cycle", 1) != buf_cycle:
        raise RunFailed(f"{harness} is a build of BUF_CYCLE {rtl.build.get('buf_cycle', 1)}, not {buf_cycle}")
    pixels = w * h
    traced = rtl.traced_counted
    cycles = st["cycles"]
    ntx, nty = spec.tile_counts(w, h, tile)
    tiles = ntx * nty
    beats = rtl.w_beats(tile)
    pt = {
        "num_engines": engines, "max_outstanding": mo, "render_latency": latency,
        "num_ctx": rtl.build.get("num_ctx"), "num_ctx_overridden": ctx is not None,
        "rd_lat": rtl.build.get("rd_lat", 1), "tile_limit": rtl.build.get("tile_limit", 32),
        "buf_cycle": rtl.build.get("buf_cycle", 1),
        "tile": tile, "levels": levels, "thr": list(p.thr),
        "cycles": cycles, "pixels": pixels, "tiles": tiles,
        "pixels_per_clock": pixels / cycles,
        "pixels_per_clock_per_engine": pixels / cycles / engines,
        "cycles_per_tile": cycles / tiles,                       # frame cycles / tiles (all engines)
        "cycles_per_tile_per_engine": cycles * engines / tiles,  # what one engine spends on a tile
        "traced": traced, "traced_fraction": traced / pixels,
        "pixels_counted": traced + rtl.interpolated_counted,
        "render_stall_cycles": st["render_stall_cycles"],
        "memory_stall_cycles": st["memory_stall_cycles"],
        # Lower bounds on the frame's cycles, one per shared resource (see the module docstring).
        "axi_w_beats": beats,
        "axi_beat_bits": 8 * rtl.build["axi_beat_bytes"],       # the harness build's W channel
        "bound_writer_cycles": beats,
        "bound_tags_cycles": traced * latency / (engines * mo),
        "bound_render_port_cycles": traced,
        "bound_decisions_cycles": pixels / engines,
        # A tile buffer whose macro port takes an address once per BUF_CYCLE clocks: each of an
        # engine's (BUF_CYCLE + 1) // 2 streamers reads two pixels (the buffer's two copies) per
        # BUF_CYCLE clocks, the engine's stream takes one a clock (msr_ctx_drain).
        "bound_streamer_cycles": pixels / engines / min(1.0, 2 * ((cyc + 1) // 2) / cyc)
                                 if (cyc := rtl.build.get("buf_cycle", 1)) > 1 else pixels / engines,
        "sim_seconds": st["sim_seconds"], "wall_seconds": rtl.wall_seconds,
    }
    if golden is not None:
        v = compare(rtl, golden.frame(p, rule))
        pt["bit_exact"] = v["bit_exact"]
        pt["mismatched_pixels"] = v["mismatched_pixels"] + v["mismatched_codes"]
    return pt


def bottleneck(pt: dict) -> str:
    """The resource whose lower bound comes closest to the measured cycles."""
    bounds = {f"frame-buffer writer AXI W ({pt['axi_beat_bits']}-bit beats: pixels + source codes)":
              pt["bound_writer_cycles"],
              "render tags (MAX_OUTSTANDING per engine)": pt["bound_tags_cycles"],
              "shared render port (1 request/clock)": pt["bound_render_port_cycles"],
              "engine decisions (1 position/clock/engine)": pt["bound_decisions_cycles"]}
    if pt.get("buf_cycle", 1) > 1:
        bounds[f"tile streamers ({(pt['buf_cycle'] + 1) // 2} per engine, 2 pixels per {pt['buf_cycle']} "
               f"clocks each: BUF_CYCLE)"] = \
            pt["bound_streamer_cycles"]
    name, val = max(bounds.items(), key=lambda kv: kv[1])
    return f"{name}: bound {val:.0f} of {pt['cycles']} cycles ({val / pt['cycles']:.0%})"


def analysis(pts: list[dict]) -> dict:
    """Ceilings behind the measured numbers, from the sweep itself."""
    if not pts:
        return {}
    p0 = pts[0]
    out = {
        # The writer's W channel moves one beat (axi_beat_bits) per clock.
        "writer_limit_pixels_per_clock": p0["pixels"] / p0["axi_w_beats"],
        "w_beats_per_pixel": p0["axi_w_beats"] / p0["pixels"],
        "w_beats_per_clock_needed_for_goal": GOAL_PIXELS * p0["axi_w_beats"] / p0["pixels"],
        # One request per clock on the shared render port: only the traced pixels count.
        "render_port_limit_pixels_per_clock": p0["pixels"] / max(p0["traced"], 1),
    }
    # A lone engine is not writer bound at long latencies: N engines with an ideal writer could
    # at best do N times its rate (they share nothing else but the render port).
    for p in pts:
        if p["num_engines"] == 1 and p["cycles"] > 1.05 * p["axi_w_beats"]:
            out[f"engine_limit_1_engine_mo{p['max_outstanding']}_latency{p['render_latency']}"] = {
                "pixels_per_clock": p["pixels_per_clock"],
                "cycles_per_16x16_equivalent_tile": p["cycles"] / (p["pixels"] / 256),
                "times_4_engines_ideal_writer": 4 * p["pixels_per_clock"]}
    return out


def load_engine_bench(path: Path) -> dict | None:
    if not path.is_file():
        return None
    data = json.loads(path.read_text())
    res = data.get("results", [])
    lat0 = [r for r in res if r["latency"] == 0 and r.get("decisions_per_clock_in_pass") is not None]
    best = min((r["decisions_per_clock_in_pass"] for r in lat0), default=None)
    return {"source": str(path.relative_to(ROOT)) if path.is_relative_to(ROOT) else str(path),
            "setup": data.get("setup"),
            "decisions_per_clock_in_pass_latency0_min": best,
            "results": res}


def plot(report: dict, path: Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    pts = report["engines_x_latency"]
    fig, ax = plt.subplots(figsize=(6.4, 4.0), dpi=100)
    def key(p):
        return p["num_engines"], p["max_outstanding"], p.get("num_ctx") if p.get("num_ctx_overridden") else None
    for e, mo, ctx in sorted({key(p) for p in pts}, key=lambda k: (k[0], k[1], k[2] or 0)):
        row = sorted((p for p in pts if key(p) == (e, mo, ctx)), key=lambda p: p["render_latency"])
        ax.plot([p["render_latency"] for p in row], [p["pixels_per_clock"] for p in row],
                "o-" if mo == 16 else "s--",
                label=f"{e} engine{'s' if e > 1 else ''}, MAX_OUTSTANDING {mo}" + (f", NUM_CTX {ctx}" if ctx else ""))
    ax.axhline(GOAL_PIXELS, color="grey", ls="--", lw=1, label=f"goal {GOAL_PIXELS} (4 engines, latency 256)")
    wl = pts[0]["pixels"] / pts[0]["bound_writer_cycles"]
    ax.axhline(wl, color="red", ls=":", lw=1, label=f"frame-buffer writer limit ({wl:.2f} pixels/clock, "
               f"{pts[0]['axi_beat_bits']}-bit AXI)")
    s = report["setup"]
    ax.set_title(f"msr_top, {s['scene']} {s['width']}x{s['height']}, T={s['tile']} L={s['levels']} "
                 f"thr {','.join(map(str, s['thr']))}{rule_note(s)}", fontsize=10)
    ax.set_xlabel("render latency (cycles)")
    ax.set_ylabel("pixels per clock")
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path)
    plt.close(fig)


def run(a) -> int:
    from tqdm import tqdm
    build = Path(a.build_dir)
    for e, mo, ctx in a.cfgs:
        if not harness_path(build, e, mo, ctx).is_file():
            raise UsageError(f"harness {harness_path(build, e, mo, ctx)} not built (make bench-hw-build)")
    tl_cfg = next(((e, mo, ctx) for e, mo, ctx in a.cfgs if e == a.tl_engines and ctx is None), None)
    if not a.no_tile_sweep and tl_cfg is None:
        raise UsageError(f"--tl-engines {a.tl_engines} has no harness among --configs {a.configs!r}")

    jobs = [("main", e, mo, ctx, a.tile, a.levels_main, lat) for e, mo, ctx in a.cfgs for lat in a.latencies]
    if not a.no_tile_sweep:
        jobs += [("tl", tl_cfg[0], tl_cfg[1], tl_cfg[2], t, l, lat)
                 for t in a.tiles for l in a.levels for lat in a.tl_latencies]
    golden = GoldenFrames(a.scene, a.width, a.height)
    t0 = time.perf_counter()
    main_pts, tl_pts = [], []
    bar = tqdm(jobs, desc="bench_hw", unit="sim", disable=True if a.no_progress else None,
               file=sys.stderr)  # None: a bar only on a terminal
    for kind, e, mo, ctx, t, l, lat in bar:
        bar.set_postfix_str(f"E={e} MO={mo}{f' CTX={ctx}' if ctx else ''} T={t} L={l} lat={lat}")
        pt = run_point(harness_path(build, e, mo, ctx), e, mo, a.scene, a.width, a.height, t, l, lat, golden, a.rule,
                       ctx)
        pt["bottleneck"] = bottleneck(pt)
        (main_pts if kind == "main" else tl_pts).append(pt)
    bar.close()

    engine = load_engine_bench(Path(a.engine_json))
    # The goal is judged on msr_top's defaults (MAX_OUTSTANDING 64, its NUM_CTX), else the most
    # tags swept; builds with NUM_CTX overridden (e4_mo64_c6) are reported but never judged.
    goal_cands = [p for p in main_pts if p["num_engines"] == GOAL_ENGINES and p["render_latency"] == GOAL_LATENCY
                  and not p["num_ctx_overridden"]]
    goal_pt = max(goal_cands, key=lambda p: (p["max_outstanding"] == 64, p["max_outstanding"]), default=None)
    dec = engine["decisions_per_clock_in_pass_latency0_min"] if engine else None
    report = {
        "setup": {"scene": a.scene, "renderer": "Embree over DPI-C (render_dpi.sv), quality fast",
                  "width": a.width, "height": a.height, "tile": a.tile, "levels": a.levels_main,
                  "thr": list(spec.default_thresholds(a.levels_main)), "metric": "max", "fov_gain": 0,
                  "rule": a.rule,
                  "render_jitter": 0, "source_map": "enabled (SRC_CTRL.ENABLE, as make sim)",
                  "memory": "AXI slave always ready (--mem-pause 0)",
                  "pixels_per_clock": "W*H / PERF_CYCLES (START to DONE)",
                  "cycles_per_tile_sweep": {"num_engines": a.tl_engines, "latencies": a.tl_latencies,
                                            "thr": "8,16,32 truncated to L"}},
        "engines_x_latency": main_pts,
        "cycles_per_tile": tl_pts,
        "engine_bench": engine,
        "bit_exact": all(p.get("bit_exact", False) for p in main_pts + tl_pts),
        "goals": {
            "decisions_per_clock_per_engine_in_pass": {
                "goal": GOAL_DECISIONS, "measured": dec,
                "met": (dec >= GOAL_DECISIONS) if dec is not None else None,
                "where": "tile_engine alone, latency 0, min over MAX_OUTSTANDING and thresholds (bench_engine.py)",
                # The same rate at longer latencies, so the reader sees where it drops.
                "by_point": [{"max_outstanding": x.get("max_outstanding"), "thr": x.get("thr"),
                              "latency": x["latency"], "decisions_per_clock": x.get("decisions_per_clock_in_pass")}
                             for x in (engine["results"] if engine else [])]},
            "pixels_per_clock_4_engines_latency_256": {
                "goal": GOAL_PIXELS, "measured": goal_pt["pixels_per_clock"] if goal_pt else None,
                "met": (goal_pt["pixels_per_clock"] >= GOAL_PIXELS) if goal_pt else None,
                "max_outstanding": goal_pt["max_outstanding"] if goal_pt else None,
                "bottleneck": goal_pt["bottleneck"] if goal_pt else None},
        },
        "analysis": analysis(main_pts),
        "rtl_digest": rtl_digest(),
        "bench_seconds": round(time.perf_counter() - t0, 1),
    }
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "report.json").write_text(json.dumps(report, indent=1) + "\n")
    if not a.no_plot:
        plot(report, out / "pixels_per_clock.png")
    print_tables(report)
    print(f"written {out / 'report.json'}" + ("" if a.no_plot else f" and {out / 'pixels_per_clock.png'}"))
    return 0 if report["bit_exact"] else 1


def rule_note(setup: dict) -> str:
    """', rule lindilate' for a rule other than the default (the default output stays as it was)."""
    rule = setup.get("rule", "patent")
    return "" if rule == "patent" else f", rule {rule}"


def print_tables(r: dict) -> None:
    s = r["setup"]
    print(f"\nPixels per clock, {s['scene']} {s['width']}x{s['height']}, T={s['tile']} L={s['levels']} "
          f"thr {','.join(map(str, s['thr']))}{rule_note(s)} (traced fraction, cycles):")
    print("| engines | MAX_OUTSTANDING | latency | cycles | pixels / clock | traced | render stall | "
          "memory stall | bound | bit exact |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for p in r["engines_x_latency"]:
        eng = f"{p['num_engines']}" + (f" (NUM_CTX {p['num_ctx']})" if p.get("num_ctx_overridden") else "")
        print(f"| {eng} | {p['max_outstanding']} | {p['render_latency']} | {p['cycles']} "
              f"| {p['pixels_per_clock']:.3f} | {p['traced_fraction']:.3f} | {p['render_stall_cycles']} "
              f"| {p['memory_stall_cycles']} | {p['bottleneck']} | {p.get('bit_exact')} |")
    if r["cycles_per_tile"]:
        e = r["setup"]["cycles_per_tile_sweep"]["num_engines"]
        print(f"\nCycles per tile ({e} engines; frame cycles / tiles, and x{e} = per engine):")
        print("| T | L | latency | tiles | cycles / tile | per engine | pixels / clock | traced | bit exact |")
        print("|---|---|---|---|---|---|---|---|---|")
        for p in r["cycles_per_tile"]:
            print(f"| {p['tile']} | {p['levels']} | {p['render_latency']} | {p['tiles']} "
                  f"| {p['cycles_per_tile']:.1f} | {p['cycles_per_tile_per_engine']:.0f} "
                  f"| {p['pixels_per_clock']:.3f} | {p['traced_fraction']:.3f} | {p.get('bit_exact')} |")
    for k, g in r["goals"].items():
        print(f"goal {k}: {g['goal']} measured {g['measured']} -> {'met' if g['met'] else 'NOT met'}")


def main(argv=None) -> int:
    return run_main("bench_hw", lambda: run(parse(argv)))


if __name__ == "__main__":
    sys.exit(main())
