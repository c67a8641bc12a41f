"""`make sim`: one frame through the RTL (Verilator harness + DPI Embree) and the golden model.

    python scripts/run_sim.py --harness build/sim/fast/Vmsr_sim_top --scene cornell \
        --width 640 --height 480 [--tile 16 --levels 2 --thr 8,16 --metric max --fov-gain 0 --gaze X,Y]
        [--rule patent] [--camera EX,EY,EZ,TX,TY,TZ,FOV] [--out DIR]
        [--waves [--wave-tile TX,TY | --wave-cycles FROM,TO]]

Writes frame.png, source_map.png (read back from the RTL's memory), golden.png,
golden_source_map.png, reference.png and report.json into DIR (default out/sim/<scene>/)
(docs/spec/contracts.md, "Full simulation"), summary.png (the run in one picture,
msr_model.overview) and prints a one-screen summary.

Exit status and last line (msr_model.clitools): 0 and "make sim: passed: ..." when the RTL
is bit exact with the golden model; 2 and "make sim: error: ..." on bad input (arguments,
a model file that cannot be read, a rule that is not one of the RTL's), nothing run; 1 and
"make sim: failed: ..." when the simulation fails or is not bit exact.
"""
from __future__ import annotations

import json
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

from msr_model import Params, RULES, metrics, save_png, spec
from msr_model.scenes import scene_id
from msr_model.clitools import Parser, RunFailed, UsageError, int_in, int_list, run_main, gaze_of
from .harness import RTL_RULES, GoldenFrames, HarnessRun, compare

from .filelist import ROOT


def parse(argv):
    ap = Parser(prog="make sim", description=__doc__.splitlines()[0])
    ap.add_argument("--harness", required=True, help="the Verilator harness binary")
    ap.add_argument("--scene", default="cornell")
    ap.add_argument("--width", default="640")
    ap.add_argument("--height", default="480")
    ap.add_argument("--tile", default="16")
    ap.add_argument("--levels", default="2")
    ap.add_argument("--thr", default="")
    ap.add_argument("--metric", default="max")
    ap.add_argument("--fov-gain", default="0")
    ap.add_argument("--gaze", default="", help="X,Y: the gaze point in pixels (GAZE= of make sim; empty: "
                    "the default, the centre of the tile grid)")
    ap.add_argument("--rule", default="", help="decision rule (default patent; RULE= of make sim)")
    ap.add_argument("--budget", default="", help="ray budget: N traced pixels or P%% of the frame "
                    "(docs/budget.md; BUDGET= of make sim; empty or 0: off)")
    ap.add_argument("--frames", default="", help="a sequence of N frames in one harness run (FRAMES= of make sim)")
    ap.add_argument("--camera-path", default="", help="camera path file of the sequence (CAMERA_PATH=; default: "
                    "the scene's default orbit, msr_model.camera_path)")
    ap.add_argument("--reuse", default="", help="REUSE= of make sim: 1 reuses the previous frame (not in the "
                    "hardware yet: refused); empty or 0: off")
    ap.add_argument("--depth", action="store_true", help="DEPTH=1 of make sim: the engines' depth channel "
                    "(a DEPTH_EN harness): every pixel's inverse depth compared with the golden model's")
    ap.add_argument("--out", default="")
    ap.add_argument("--quality", default="fast")
    ap.add_argument("--camera", default="", help="EX,EY,EZ,TX,TY,TZ,FOV (model units, degrees); empty: the scene's view")
    ap.add_argument("--waves", action="store_true", help="FST of a window (harness built with tracing)")
    ap.add_argument("--wave-tile", default="", help="TX,TY: trace one tile's life (default: the centre tile)")
    ap.add_argument("--wave-cycles", default="", help="FROM,TO: trace a cycle range instead")
    ap.add_argument("--rnd-latency", type=int, default=4, help="render latency in cycles")
    ap.add_argument("--rnd-jitter", type=int, default=8, help="extra random latency (reorders responses)")
    return ap.parse_args(argv)


def params_of(a) -> tuple[int, int, Params]:
    w = int_in(a.width, "WIDTH", 1, spec.MAX_FRAME)
    h = int_in(a.height, "HEIGHT", 1, spec.MAX_FRAME)
    tile = int_in(a.tile, "TILE", 1, 4096)
    levels = int_in(a.levels, "LEVELS", 1, 3)
    thr = int_list(a.thr, "THR") if a.thr else spec.default_thresholds(levels)
    if len(thr) != levels:
        raise UsageError(f"THR has {len(thr)} values but LEVELS is {levels}: give one per level")
    gain = int_in(a.fov_gain, "FOV_GAIN", 0, 255)
    gaze = gaze_of(getattr(a, "gaze", None), "GAZE", w, h)
    return w, h, Params(tile=tile, levels=levels, thr=thr, metric=a.metric, fov_gain=gain, gaze=gaze)


def rule_of(a) -> str:
    rule = a.rule or "patent"
    if rule not in RULES:
        raise UsageError(f"RULE {rule!r} is not a decision rule: one of {', '.join(RULES)}")
    if rule not in RTL_RULES:
        raise UsageError(f"RULE={rule}: the RTL does not implement this rule (CONFIG.RULE has "
                         f"{', '.join(RTL_RULES)}); the golden model has it: python -m msr_model select --rule {rule}")
    return rule


def budget_of(a, width: int, height: int, params: Params):
    """The frame's budget registers (msr_model.budget.first_frame_config: a first frame with the
    driver's seed from the frame size, budget and thresholds),
    or None without a budget; a budget below the frame's initial grid is refused here, as START
    would refuse it (STATUS.ERROR 14)."""
    from msr_model import budget as BG
    if not str(a.budget).strip():
        return None
    try:
        pixels = BG.budget_pixels(BG.parse_budget(a.budget), width, height)
    except ValueError as e:
        raise UsageError(f"BUDGET={a.budget}: {e}") from None
    if pixels == 0:
        return None
    cfg = BG.first_frame_config(width, height, pixels, params)     # the driver's seed (SCALE_INIT, PRIOR_SHIFT)
    try:
        BG.Controller(width, height, params, cfg)
    except BG.BudgetRefused as e:
        raise UsageError(f"BUDGET={a.budget}: {e}") from None
    return cfg


def reuse_of(a) -> bool:
    """REUSE=: empty, 0 or 1. Reuse across frames is not in the hardware yet: 1 is refused."""
    text = str(a.reuse).strip().lower()
    if text in ("", "0", "no", "false"):
        return False
    if text not in ("1", "yes", "true"):
        raise UsageError(f"REUSE must be 0 or 1, got {a.reuse!r}")
    raise UsageError("REUSE=1: reuse across frames is not in the hardware yet")


def run(a) -> int:
    reuse_of(a)
    W, H, params = params_of(a)
    rule = rule_of(a)
    budget = budget_of(a, W, H, params)
    harness = Path(a.harness)
    if not harness.is_file():
        raise UsageError(f"harness {harness} not built (run make sim)")
    out = Path(a.out or ROOT / "out" / "sim" / scene_id(a.scene))
    if out.exists() and not out.is_dir():
        raise UsageError(f"OUT {out} is not a folder")
    if a.depth and (budget is not None or str(a.frames).strip() or str(a.camera_path).strip()):
        raise UsageError("DEPTH=1 runs one frame without a ray budget (not with BUDGET= or FRAMES=)")
    if str(a.frames).strip() or str(a.camera_path).strip():
        from .sim_sequence import run_sequence
        return run_sequence(a, W, H, params, rule, budget, harness, out)

    # The scene must open in Python before anything runs: a bad model file is exit status 2.
    from msr_model.embree import open_renderer
    t0 = time.perf_counter()
    renderer = open_renderer(a.scene, W, H, quality=a.quality, camera=a.camera or None)
    out.mkdir(parents=True, exist_ok=True)
    depth = None
    if a.depth:
        # The driver's exponent, and the whole frame's colours and inverse depths (the renderer is
        # deterministic: the golden model's traces are answered from them).
        from msr_model.reuse import choose_invz_exp
        if not hasattr(renderer, "render_invz"):
            raise UsageError(f"DEPTH=1: scene {a.scene} has no depth (a picture scene)")
        invz_exp = choose_invz_exp(renderer)
        yy, xx = np.mgrid[0:H, 0:W]
        rgb_all, invz_all = renderer.render_invz(xx.ravel().astype(np.int32), yy.ravel().astype(np.int32), invz_exp)
        depth = (invz_exp, np.asarray(rgb_all, np.uint8).reshape(H, W, 3), np.asarray(invz_all, np.uint16).reshape(H, W))

    extra = []
    if a.waves:
        ntx, nty = spec.tile_counts(W, H, params.tile)
        extra += ["--waves", str(out / "waves.fst")]
        extra += (["--wave-cycles", a.wave_cycles] if a.wave_cycles
                  else ["--wave-tile", a.wave_tile or f"{ntx // 2},{nty // 2}"])
    # The RTL runs in its own process while this one renders the reference and the golden frame.
    sim = HarnessRun(harness, a.scene, W, H, params, rule=rule, quality=a.quality, camera=a.camera or None,
                     latency=a.rnd_latency, jitter=a.rnd_jitter, budget=budget, extra=extra,
                     invz_exp=None if depth is None else depth[0]).start()
    try:
        golden_frames = GoldenFrames(a.scene, W, H, renderer=renderer)
        t_ref = time.perf_counter() - t0
        golden = golden_frames.frame(params, rule, budget)
    finally:
        rtl = sim.wait()
    reference = golden_frames.reference

    if a.waves:
        fst = out / "waves.fst"
        if not fst.is_file():
            raise RunFailed("the harness wrote no waves.fst (was the window ever reached?)")
        subprocess.run([sys.executable, "-m", "msr_flow.waves", str(fst), str(out / "waves.gtkw")],
                       check=True)
        last = ROOT / "build" / "sim" / "last_waves"      # make waves opens this run by default
        last.parent.mkdir(parents=True, exist_ok=True)
        last.write_text(f"{out.resolve()}\n")

    frame, source = rtl.frame, rtl.source
    # The rule the harness wrote to CONFIG.RULE (its stats file), against the one compared with.
    written = rtl.stats.get("params", {}).get("rule")
    if written is not None and written != RTL_RULES.index(rule):
        raise RunFailed(f"the harness wrote CONFIG.RULE = {written}, not {RTL_RULES.index(rule)} ({rule})")
    if rtl.stats.get("gaze", None) != (None if params.gaze is None else list(params.gaze)):
        raise RunFailed(f"the harness wrote GAZE {rtl.stats.get('gaze')}, not {params.gaze} (rebuild it: make sim)")
    if budget is not None and not rtl.build.get("budget_en"):
        raise RunFailed(f"BUDGET={a.budget}: the harness {harness} is a top without the budget controller "
                        f"(build it with make sim BUDGET=...)")
    if depth is not None and not rtl.build.get("depth_en"):
        raise RunFailed(f"DEPTH=1: the harness {harness} is a top without the depth channel (make sim DEPTH=1)")
    verdict = compare(rtl, golden)
    if depth is not None:
        from msr_model.reuse import PlaneRenderer, select_with_reuse
        g_depth, _ = select_with_reuse(PlaneRenderer(depth[1], depth[2]), W, H, params, rule, reuse=False)
        bad = int((rtl.invz != g_depth.invz).sum())
        verdict.update({"depth_equal": bad == 0, "mismatched_depths": bad, "invz_exp": depth[0]})
        verdict["bit_exact"] = verdict["bit_exact"] and bad == 0
        from PIL import Image
        Image.fromarray(rtl.invz.astype(np.uint16)).save(out / "depth.png")      # 16-bit grey
    psnr = metrics.psnr(reference, frame)         # inf for identical frames
    ssim = metrics.ssim(reference, frame)         # None below 7x7: not defined there

    save_png(out / "frame.png", frame)
    save_png(out / "source_map.png", source)
    save_png(out / "golden.png", golden.frame)
    save_png(out / "golden_source_map.png", golden.source)
    save_png(out / "reference.png", reference)

    st = rtl.stats
    pixels = W * H
    traced = int((source < spec.SRC_INTERP_BASE).sum())
    counters_ok = (rtl.traced_counted == traced and st["traced_initial"] == golden.stats["traced_initial"])
    report = {
        **verdict,
        "traced_fraction": traced / pixels,
        "traced": traced,
        "interpolated": pixels - traced,
        "psnr_db": psnr,
        "ssim": ssim,
        "cycles": st["cycles"],
        "pixels": pixels,
        "cycles_per_pixel": st["cycles"] / pixels,
        "sim_cycles_per_second": st["sim_cycles_per_second"],
        "sim_seconds": st["sim_seconds"],
        "rtl_wall_seconds": rtl.wall_seconds,
        "reference_seconds": round(t_ref, 3),
        "perf_counters": {k: v for k, v in st.items() if k.startswith(("traced_", "interpolated_", "render_", "memory_"))},
        "perf_counters_match_source_map": counters_ok,
        "scene": a.scene,
        "camera": a.camera or None,
        "width": W,
        "height": H,
        "rule": rule,
        "gaze": list(params.gaze or spec.default_gaze(W, H, params.tile)),
        "params": params.as_dict(),
        "quality": a.quality,
        "render_latency": a.rnd_latency,
        "render_jitter": a.rnd_jitter,
        "num_engines": rtl.build["num_engines"],         # from the harness build (its stats file)
        "budget": 0 if budget is None else budget.budget,
    }
    if budget is not None:
        bc, hw = golden.stats["budget_control"], st.get("budget", {})
        report["budget_control"] = {
            **{k: bc[k] for k in ("scale_init", "prior_shift", "seeded", "grid", "scale_per_row",
                                  "thr_multiplier_per_row", "traced_per_row", "scale_out")},
            "budget_error": (traced - budget.budget) / budget.budget,
            "scale_out_rtl": hw.get("scale_out") if hw.get("scale_out_valid") else None,
            "scale_out_equal": bool(hw.get("scale_out_valid")) and hw.get("scale_out") == bc["scale_out"],
        }
    (out / "report.json").write_text(json.dumps(report, indent=2) + "\n")
    from msr_model.overview import RunInfo, write_summary
    write_summary(out / "summary.png", frame, reference, source,
                  RunInfo(scene=scene_id(a.scene), params=params, rule=rule, psnr_db=report["psnr_db"], ssim=ssim,
                          cycles=st["cycles"], bit_exact=report["bit_exact"],
                          budget=0 if budget is None else budget.budget,
                          scale_per_row=None if budget is None else report["budget_control"]["scale_per_row"]))

    p = params
    print(f"make sim: {a.scene} {W}x{H}, tile {p.tile}, levels {p.levels}, thr {','.join(map(str, p.thr))}, "
          f"metric {p.metric}, fov gain {p.fov_gain}, gaze {','.join(map(str, p.gaze or spec.default_gaze(W, H, p.tile)))}"
          f"{'' if p.gaze else ' (default)'}, rule {rule}")
    print(f"  bit exact vs golden model : {'yes' if report['bit_exact'] else 'NO'}"
          f" (frame {'=' if verdict['frame_equal'] else '!='}, source map {'=' if verdict['source_map_equal'] else '!='})")
    if depth is not None:
        print(f"  inverse depth (DEPTH=1)   : {'= golden model' if verdict['depth_equal'] else 'NOT equal'}"
              f" ({verdict['mismatched_depths']} pixels differ; INVZ_EXP {depth[0]}; {out / 'depth.png'})")
    print(f"  traced                    : {traced} of {pixels} pixels ({traced / pixels:.1%})")
    if budget is not None:
        bc = report["budget_control"]
        print(f"  ray budget                : {budget.budget} pixels, traced {bc['budget_error']:+.2%} off it; "
              f"SCALE_OUT {bc['scale_out_rtl']} (golden {bc['scale_out']})")
    print(f"  quality vs full render    : PSNR {metrics.format_db(psnr)}, "
          f"SSIM {'not defined below 7x7' if ssim is None else f'{ssim:.4f}'}")
    print(f"  RTL cycles                : {st['cycles']} ({st['cycles'] / pixels:.3f} cycles/pixel)")
    print(f"  simulation speed          : {st['sim_cycles_per_second'] / 1e6:.2f} Mcycles/s, "
          f"RTL run {rtl.wall_seconds:.1f} s, reference render {t_ref:.1f} s")
    if a.waves:
        print(f"  waves                     : {out / 'waves.fst'} (make waves)")
    print(f"  summary picture           : {out / 'summary.png'}")
    print(f"  outputs                   : {out}/", flush=True)
    if budget is not None and not report["budget_control"]["scale_out_equal"]:
        raise RunFailed(f"SCALE_OUT {report['budget_control']['scale_out_rtl']} read from the RTL, the golden "
                        f"model's is {report['budget_control']['scale_out']}")
    if not report["bit_exact"]:
        raise RunFailed(f"not bit exact: {verdict['mismatched_pixels']} pixels, {verdict['mismatched_codes']} "
                        f"source codes and {verdict.get('mismatched_depths', 0)} depths differ from the golden "
                        f"model (report: {out / 'report.json'})")
    print(f"make sim: passed: bit exact with the golden model (rule {rule})")
    return 0


def main(argv=None) -> int:
    return run_main("make sim", lambda: run(parse(argv)), unexpected_is_failure=True)


if __name__ == "__main__":
    sys.exit(main())
