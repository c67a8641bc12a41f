#!/usr/bin/env python3
"""Ray-budget goals (docs/budget.md): traced count against the budget, and image quality
against the fixed-threshold setting that traces as many pixels, on the evaluation scenes.

    python scripts/eval_budget.py --width 960 --height 540            # every scene of the set
    python scripts/eval_budget.py --width 1920 --height 1080 --docs    # + docs/img/budget_*.png

Per scene: the renderer's full render (Embree, cached as PNG under OUT/cache) is the rendering
unit and the reference (the renderer is deterministic, so each method still asks only for the
pixels it traces). Per budget: a sequence of FRAMES frames of the same view, the first with
the driver's seed (budget.first_frame_config, or the registers' reset values with
--first-seed 256), each later one with the previous frame's SCALE_OUT and row activities.
The fixed-threshold curve: the same thresholds at one scale u for the whole frame, u on a
half-octave ladder, refined by bisection down to adjacent scales around every frame's traced
count; PSNR at a traced count is read off that curve linearly in log(traced). Output: OUT/results.json, OUT/*.png.
"""
from __future__ import annotations

import argparse
import json
import math
import time
from pathlib import Path

import numpy as np

from msr_model import ImageRenderer, Params, load_rgb, save_png
from msr_model import budget as BG
from msr_model.metrics import capped, psnr
from msr_model.scenes import scene_id

REPO = Path(__file__).resolve().parents[2]
from msr_eval.scenes import MODEL_FILES   # the evaluation set's model files, besides the built-ins
LADDER = (BG.U_MIN_FIRST, BG.U_MIN) + tuple(int(round(256 * 2 ** (k / 2))) for k in range(-4, 6))   # u = 32, 45, 64 .. 1448


def reference(scene: str, w: int, h: int, mode: str, cache: Path) -> np.ndarray:
    p = cache / f"{scene_id(scene)}_{mode}_{w}x{h}.png"
    if not p.exists():
        from msr_model import embree
        with embree.open_renderer(scene, w, h, quality=mode) as r:
            save_png(p, np.asarray(r.render_full(), dtype=np.uint8))
    return load_rgb(p)


def run(ref, params, rule, cfg=None, fixed=None, fixed_dither=False) -> dict:
    h, w = ref.shape[:2]
    r = BG.select_budget(ImageRenderer(ref), w, h, params, cfg or BG.BudgetConfig(0), rule=rule, fixed_scale=fixed,
                         fixed_dither=fixed_dither)
    bc = r.stats["budget_control"]
    return {"traced": r.stats["traced"], "psnr": psnr(ref, r.frame), "scale_per_row": bc["scale_per_row"],
            "traced_per_row": bc["traced_per_row"], "activity_per_row": bc["activity_per_row"],
            "scale_out": bc["scale_out"], "source": r.source}


def curve_psnr(curve: dict, traced: int) -> float | None:
    """PSNR of the fixed-threshold curve at `traced`, linear in log(traced) between neighbours."""
    pts = sorted((v["traced"], capped(v["psnr"])) for v in curve.values())     # finite: interpolated
    for (t0, p0), (t1, p1) in zip(pts, pts[1:]):
        if t0 <= traced <= t1:
            return p0 if t1 == t0 else p0 + (p1 - p0) * (math.log(traced) - math.log(t0)) / (math.log(t1) - math.log(t0))
    return None


def first_config(w, h, B, params, first_seed="auto", prior_shift=None) -> BG.BudgetConfig:
    """A sequence's first frame: the driver's seed (first_frame_config), or the registers' reset
    values (SCALE_INIT 1.0, PRIOR_SHIFT 6) with first_seed "256"; prior_shift overrides either."""
    cfg = BG.first_frame_config(w, h, B, params) if first_seed == "auto" else BG.BudgetConfig(B)
    return cfg if prior_shift is None else BG.BudgetConfig(B, cfg.scale_init, prior_shift)


def evaluate_scene(ref, params, rule, budgets, frames, log, fixed_dither=False, first_seed="auto",
                   prior_shift=None) -> dict:
    h, w = ref.shape[:2]
    total = w * h
    curve = {u: run(ref, params, rule, fixed=u, fixed_dither=fixed_dither) for u in LADDER}
    out = {"budgets": {}}
    for pct in budgets:
        B = total * pct // 100
        seq, cfg = [], first_config(w, h, B, params, first_seed, prior_shift)
        for _ in range(frames):
            f = run(ref, params, rule, cfg)
            seq.append(f)
            cfg = BG.BudgetConfig(B, f["scale_out"], BG.PRIOR_SHIFT, tuple(f["activity_per_row"]),
                                  tuple(f["scale_per_row"]))
        # Refine the curve around every frame's traced count by bisection, down to adjacent
        # scales: the fixed setting "at the same count" is then read between the two fixed
        # settings a user can actually choose on either side of it, whichever points other
        # frames added (one midpoint, as before 2026-12-05, left brackets of up to 10 scales, and
        # rounded thresholds jump inside them: cornell at 20 % from 368 038 to 574 478 traced).
        for f in seq:
            while True:
                us = sorted(curve)
                tr = [curve[u]["traced"] for u in us]          # falls with u
                br = [(a, b) for a, b, ta, tb in zip(us, us[1:], tr, tr[1:])
                      if tb <= f["traced"] <= ta and b - a > 1 and ta != tb]
                if not br:
                    break
                a, b = br[0]
                curve[(a + b) // 2] = run(ref, params, rule, fixed=(a + b) // 2, fixed_dither=fixed_dither)
        rec = []
        for k, f in enumerate(seq):
            fixed = curve_psnr(curve, f["traced"])
            rec.append({"frame": k + 1, "traced": f["traced"], "error_pct": 100 * (f["traced"] - B) / B,
                        "psnr": f["psnr"], "psnr_fixed": fixed,
                        "psnr_delta": None if fixed is None else capped(f["psnr"]) - fixed,
                        "scale_per_row": f["scale_per_row"], "traced_per_row": f["traced_per_row"],
                        "scale_out": f["scale_out"]})
        out["budgets"][pct] = {"budget": B, "frames": rec}
        log("   " + f"{pct:>2}%: " + "  ".join(
            f"f{r['frame']} {r['error_pct']:+6.2f}% " + ("  n/a" if r["psnr_delta"] is None else f"{r['psnr_delta']:+5.2f}") + " dB"
            for r in rec))
    out["curve"] = {str(u): {"traced": v["traced"], "psnr": v["psnr"]} for u, v in sorted(curve.items())}
    out["example_source"] = None
    return out


def plots(result: dict, out: Path, example: dict | None):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    scenes = list(result["scenes"])
    budgets = result["config"]["budgets"]
    frames = result["config"]["frames"]
    x = np.arange(len(scenes))
    # traced-count error per scene, budget, frame
    fig, axes = plt.subplots(1, len(budgets), figsize=(5 * len(budgets), 4), sharey=True)
    for ax, pct in zip(np.atleast_1d(axes), budgets):
        wbar = 0.8 / frames
        for k in range(frames):
            errs = [result["scenes"][s]["budgets"][str(pct)]["frames"][k]["error_pct"] for s in scenes]
            ax.bar(x + (k - (frames - 1) / 2) * wbar, errs, wbar, label=f"frame {k + 1}" + (" (seed 1.0)" if k == 0 else " (seeded)"))
        for lim, style in ((3, ":"), (1, "--")):
            ax.axhline(lim, color="k", ls=style, lw=0.8)
            ax.axhline(-lim, color="k", ls=style, lw=0.8)
        ax.set_title(f"budget {pct} %")
        ax.set_xticks(x, scenes, rotation=70, fontsize=7)
        ax.set_ylim(-12, 12)
        ax.grid(axis="y", alpha=0.3)
    np.atleast_1d(axes)[0].set_ylabel("traced - budget (% of budget)")
    np.atleast_1d(axes)[0].legend(fontsize=7)
    fig.suptitle(f"Traced count against the budget, {result['config']['width']}x{result['config']['height']}")
    fig.tight_layout()
    fig.savefig(out / "budget_error.png", dpi=90)
    plt.close(fig)
    # PSNR against the fixed-threshold curve at the same traced count
    fig, axes = plt.subplots(1, len(budgets), figsize=(5 * len(budgets), 4), sharey=True)
    for ax, pct in zip(np.atleast_1d(axes), budgets):
        wbar = 0.8 / frames
        for k in range(frames):
            d = [result["scenes"][s]["budgets"][str(pct)]["frames"][k]["psnr_delta"] for s in scenes]
            ax.bar(x + (k - (frames - 1) / 2) * wbar, [np.nan if v is None else v for v in d], wbar, label=f"frame {k + 1}")
        ax.axhline(-0.2, color="k", ls=":", lw=0.8)
        ax.axhline(0, color="k", lw=0.5)
        ax.set_title(f"budget {pct} %")
        ax.set_xticks(x, scenes, rotation=70, fontsize=7)
        ax.grid(axis="y", alpha=0.3)
    np.atleast_1d(axes)[0].set_ylabel("PSNR(budget) - PSNR(fixed, same traced) (dB)")
    np.atleast_1d(axes)[0].legend(fontsize=7)
    fig.suptitle("Quality at the budget against fixed thresholds tracing as many pixels")
    fig.tight_layout()
    fig.savefig(out / "budget_psnr.png", dpi=90)
    plt.close(fig)
    if example is None:
        return
    # one scene: scale per tile row beside the traced map, frames 1 and 2
    fig, axes = plt.subplots(1, 3, figsize=(14, 4), gridspec_kw={"width_ratios": [3, 1, 1]})
    src = example["source"]
    axes[0].imshow(src < 16, cmap="gray_r", interpolation="nearest", aspect="auto")
    axes[0].set_title(f"{example['scene']}, budget {example['pct']} %, frame 1: traced pixels (black)")
    axes[0].axis("off")
    for k, f in enumerate(example["frames"]):
        rows = np.arange(len(f["scale_per_row"]))
        axes[1].plot(np.asarray(f["scale_per_row"]) / 256, rows, label=f"frame {k + 1}")
        axes[2].plot(100 * np.asarray(f["traced_per_row"]) / example["row_pixels"], rows, label=f"frame {k + 1}")
    for ax, t in ((axes[1], "scale u per tile row (1.0 = 256)"), (axes[2], "traced % per tile row")):
        ax.invert_yaxis()
        ax.set_title(t, fontsize=9)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    axes[1].set_xscale("log", base=2)
    axes[2].axvline(example["pct"], color="k", ls=":", lw=0.8)
    fig.tight_layout()
    fig.savefig(out / "budget_rows.png", dpi=90)
    plt.close(fig)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--width", type=int, default=960)
    ap.add_argument("--height", type=int, default=540)
    ap.add_argument("--scenes", help="comma-separated scene names / model files (default: the evaluation set)")
    ap.add_argument("--mode", default="fast", help="renderer mode (fast|heavy)")
    ap.add_argument("--budgets", default="5,10,20", help="percentages of the frame")
    ap.add_argument("--frames", type=int, default=3, help="frames per sequence (the first unseeded)")
    ap.add_argument("--tile", type=int, default=16)
    ap.add_argument("--levels", type=int, default=3)
    ap.add_argument("--thr", default="8,16,32")
    ap.add_argument("--rule", default="patent")
    ap.add_argument("--example", default="teapots", help="scene of the per-row picture")
    ap.add_argument("--out", default=None, help="default out/budget/WxH")
    ap.add_argument("--docs", action="store_true", help="also copy the plots to docs/img/budget_*.png")
    ap.add_argument("--first-seed", choices=("auto", "256"), default="auto",
                    help="a sequence's first frame: auto, the driver's seed (msr_model.budget.first_frame_config: "
                         "SCALE_INIT from the frame size, budget and thresholds, PRIOR_SHIFT 3), as the CLI "
                         "and make sim write it; or 256, the registers' reset values (SCALE_INIT 1.0, PRIOR_SHIFT 6)")
    ap.add_argument("--prior-shift", type=int, default=None,
                    help="PRIOR_SHIFT of a sequence's first frame instead of the --first-seed choice's "
                         "(the seeded frames do not use the prior)")
    ap.add_argument("--fixed-dither", action="store_true",
                    help="the fixed-threshold curve with the budget frames' dither (a uniform scale as the "
                         "controller's rows see it) instead of rounded thresholds (a user's fixed setting)")
    a = ap.parse_args(argv)
    W, H = a.width, a.height
    out = Path(a.out or REPO / f"out/budget/{W}x{H}")
    out.mkdir(parents=True, exist_ok=True)
    cache = REPO / "out/budget/cache"
    cache.mkdir(parents=True, exist_ok=True)
    params = Params(tile=a.tile, levels=a.levels, thr=tuple(int(t) for t in a.thr.split(",")))
    budgets = [int(b) for b in a.budgets.split(",")]
    if a.scenes:
        scenes = [s.strip() for s in a.scenes.split(",") if s.strip()]
    else:
        from msr_model import embree
        scenes = embree.scene_names() + [m for m in MODEL_FILES if Path(m).is_file()]
    log = lambda s: print(s, flush=True)  # noqa: E731
    grid = BG.grid_count(W, H, params)
    log(f"eval_budget: {W}x{H}, T {a.tile}, L {a.levels}, thr {params.thr}, rule {a.rule}, initial grid "
        f"{grid} = {100 * grid / (W * H):.2f} % of the frame, budgets {budgets} %, {len(scenes)} scenes")
    result = {"config": {"width": W, "height": H, "mode": a.mode, "params": params.as_dict(), "rule": a.rule,
                         "budgets": budgets, "frames": a.frames, "grid": grid,
                         "prior_shift": first_config(W, H, W * H * budgets[0] // 100, params, a.first_seed,
                                                     a.prior_shift).prior_shift,
                         "ladder": list(LADDER), "fixed_dither": a.fixed_dither, "first_seed": a.first_seed},
              "scenes": {}}
    t0 = time.perf_counter()
    example = None
    for sc in scenes:
        sid = scene_id(sc)
        ref = reference(sc, W, H, a.mode, cache)
        log(f"{sid} ({time.perf_counter() - t0:.0f} s)")
        res = evaluate_scene(ref, params, a.rule, budgets, a.frames, log, a.fixed_dither, a.first_seed,
                             a.prior_shift)
        res["budgets"] = {str(k): v for k, v in res["budgets"].items()}
        result["scenes"][sid] = res
        if sid == a.example:
            pct = budgets[len(budgets) // 2]
            f1 = run(ref, params, a.rule, first_config(W, H, W * H * pct // 100, params, a.first_seed,
                                                       a.prior_shift))
            example = {"scene": sid, "pct": pct, "source": f1["source"], "row_pixels": W * a.tile,
                       "frames": res["budgets"][str(pct)]["frames"][:2]}
        (out / "results.json").write_text(json.dumps(result, indent=1) + "\n")
    result["config"]["runtime_s"] = round(time.perf_counter() - t0, 1)
    (out / "results.json").write_text(json.dumps(result, indent=1) + "\n")
    plots(result, out, example)
    summary(result, log)
    if a.docs:
        img = REPO / "docs/img"
        img.mkdir(parents=True, exist_ok=True)
        for name in ("budget_error.png", "budget_psnr.png", "budget_rows.png"):
            if (out / name).exists():
                (img / name).write_bytes((out / name).read_bytes())
    return result


def summary(result: dict, log):
    """The markdown table of docs/budget.md: error per frame and PSNR delta, per scene and budget."""
    budgets = result["config"]["budgets"]
    frames = result["config"]["frames"]
    head = "| scene | " + " | ".join(f"{p} %: error f1 / f2 / f3 (%) | {p} %: dB vs fixed f1 / f2" for p in budgets) + " |"
    log(head)
    log("|---" * (1 + 2 * len(budgets)) + "|")
    for sid, res in result["scenes"].items():
        cells = []
        for p in budgets:
            fr = res["budgets"][str(p)]["frames"]
            cells.append(" / ".join(f"{f['error_pct']:+.2f}" for f in fr[:frames]))
            cells.append(" / ".join("n/a" if f["psnr_delta"] is None else f"{f['psnr_delta']:+.2f}" for f in fr[:2]))
        log(f"| {sid} | " + " | ".join(cells) + " |")
    for p in budgets:
        for k in range(frames):
            e = [abs(r["budgets"][str(p)]["frames"][k]["error_pct"]) for r in result["scenes"].values()]
            d = [r["budgets"][str(p)]["frames"][k]["psnr_delta"] for r in result["scenes"].values()]
            d = [v for v in d if v is not None]
            log(f"budget {p} % frame {k + 1}: |error| mean {np.mean(e):.2f} % max {np.max(e):.2f} %; "
                f"dB vs fixed mean {np.mean(d) if d else float('nan'):+.2f} min {np.min(d) if d else float('nan'):+.2f}")


if __name__ == "__main__":
    main()
