#!/usr/bin/env python3
"""Ray-budget laws tried in milliseconds: per tile row response curves, then any law.

Tiles never read each other and a tile row's thresholds are its scale u alone, so a frame's
traced count and squared error under any per-row schedule of scales is the sum over rows of
that row's count and error at its own u. `curves` renders each scene once per scale of a
quarter-octave ladder (u = 32 .. 1448, fixed for the whole frame, the golden model's
select_budget with fixed_scale) and stores per row the traced pixels and the squared error
against the full render; `law` then runs the controller of docs/budget.md (or a variant) over
those curves, row by row, reading a row at an off-ladder u linearly in log u: a sequence of
frames per scene and budget without rendering again. The figures are an approximation of
`scripts/eval_budget.py` (same renderer, settings and fixed-threshold comparison; off-ladder
scales interpolated): use it to rank laws, and eval_budget.py to measure the one adopted.

    python scripts/budget_lab.py curves --width 960 --height 540      # ~40 s for the set
    python scripts/budget_lab.py law --width 960 --height 540 --prior-shift 3
"""
from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

import numpy as np

from msr_model import ImageRenderer, Params
from msr_model import budget as BG
from msr_model.metrics import capped, psnr_of_mse

REPO = Path(__file__).resolve().parents[2]
PARAMS = Params(tile=16, levels=3, thr=(8, 16, 32))          # as eval_budget.py
LADDER = sorted({max(BG.U_MIN_FIRST, min(BG.U_MAX, round(256 * 2 ** (k / 4)))) for k in range(-13, 11)} | {BG.U_MIN})


def curves(width: int, height: int, scenes: list[str], out: Path) -> None:
    from msr_model.scenes import scene_id
    from .budget_eval import reference
    cache = REPO / "out" / "budget" / f"{width}x{height}" / "cache"
    cache.mkdir(parents=True, exist_ok=True)
    out.mkdir(parents=True, exist_ok=True)
    T = PARAMS.tile
    nty = -(-height // T)
    for sc in scenes:
        ref = reference(sc, width, height, "fast", cache)
        traced, sse = np.zeros((len(LADDER), nty)), np.zeros((len(LADDER), nty))
        for i, u in enumerate(LADDER):
            r = BG.select_budget(ImageRenderer(ref), width, height, PARAMS, BG.BudgetConfig(0), fixed_scale=u,
                                 fixed_dither=True)      # dithered as a budget frame's rows
            traced[i] = r.stats["budget_control"]["traced_per_row"]
            rows = ((ref.astype(np.float64) - r.frame.astype(np.float64)) ** 2).sum(axis=(1, 2))
            sse[i] = [rows[k * T:(k + 1) * T].sum() for k in range(nty)]
        grid = [BG.row_grid(width, min(T, height - k * T), PARAMS) for k in range(nty)]
        np.savez(out / f"{scene_id(sc)}.npz", U=np.array(LADDER), traced=traced, sse=sse, grid=grid)
        print(f"curves: {scene_id(sc)}", flush=True)


class Curves:
    """One scene's per-row curves."""

    def __init__(self, path: Path, width: int, height: int):
        z = np.load(path)
        self.lu, self.traced, self.sse, self.grid = np.log(z["U"].astype(float)), z["traced"], z["sse"], z["grid"]
        self.width, self.height, self.nty = width, height, self.traced.shape[1]

    def row(self, r: int, u: int) -> tuple[int, float]:
        x = math.log(min(max(u, BG.U_MIN_FIRST), BG.U_MAX))
        t = int(round(np.interp(x, self.lu, self.traced[:, r])))
        return max(t, int(self.grid[r])), float(np.interp(x, self.lu, self.sse[:, r]))

    def psnr(self, sse: float) -> float:
        """Capped (msr_model.metrics.capped): the curve is interpolated and differenced."""
        return capped(psnr_of_mse(sse / (self.width * self.height * 3)))

    def fixed_psnr(self, traced: int) -> float:
        """PSNR of one scale for the whole frame at this traced count (linear in log traced)."""
        t = self.traced.sum(1)
        p = np.array([self.psnr(s) for s in self.sse.sum(1)])
        o = np.argsort(t)
        return float(np.interp(math.log(traced), np.log(t[o]), p[o]))


def sequence(c: Curves, budget: int, frames: int, controller=BG.Controller, prior_shift=None,
             first_seed: str = "auto") -> list[dict]:
    """Frames of one scene at one budget: the first with the driver's seed (first_frame_config;
    "256": the registers' reset values), each later one seeded by the one before. prior_shift
    overrides the first frame's PRIOR_SHIFT."""
    from .budget_eval import first_config
    first = first_config(c.width, c.height, budget, PARAMS, first_seed, prior_shift)
    out, seed, prof, prof_u, prior_shift = [], first.scale_init, None, None, first.prior_shift
    for _ in range(frames):
        ctl = controller(c.width, c.height, PARAMS,
                         BG.BudgetConfig(budget, scale_init=seed, prior_shift=prior_shift, profile=prof,
                                        profile_scales=prof_u))
        traced, sse = 0, 0.0
        for j, r in enumerate(ctl.order):                  # the dispatch order (docs/budget.md 2)
            t, s = c.row(r, ctl.scales[j])
            traced, sse = traced + t, sse + s
            ctl.finish_row(t)
        out.append({"error_pct": 100 * (traced - ctl.budget) / ctl.budget,
                    "db_vs_fixed": c.psnr(sse) - c.fixed_psnr(traced), "scales": list(ctl.scales)})
        seed, prof, prof_u = ctl.scale_out, ctl.activity, ctl.scale_of_rows()
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("what", choices=("curves", "law"))
    ap.add_argument("--width", type=int, default=960)
    ap.add_argument("--height", type=int, default=540)
    ap.add_argument("--scenes", default=None, help="comma-separated (default: the evaluation set)")
    ap.add_argument("--budgets", default="5,10,20")
    ap.add_argument("--frames", type=int, default=3)
    ap.add_argument("--prior-shift", type=int, default=None, help="the first frame's (default: --first-seed's)")
    ap.add_argument("--first-seed", choices=("auto", "256"), default="auto",
                    help="the first frame: the driver's seed (first_frame_config) or the reset values")
    a = ap.parse_args(argv)
    from msr_eval.scenes import MODEL_FILES
    scenes = a.scenes.split(",") if a.scenes else ["cornell", "showcase", "bunny", "duck", "teapots", "engine",
                                                   *MODEL_FILES]
    d = REPO / "out" / "budget_lab" / f"{a.width}x{a.height}"
    if a.what == "curves":
        curves(a.width, a.height, scenes, d)
        return 0
    files = sorted(d.glob("*.npz"))
    if not files:
        print(f"budget_lab: no curves in {d}: run `budget_lab.py curves` first", file=sys.stderr)
        return 2
    for b in (int(x) for x in a.budgets.split(",")):
        runs = [sequence(Curves(f, a.width, a.height), a.width * a.height * b // 100, a.frames,
                         prior_shift=a.prior_shift, first_seed=a.first_seed) for f in files]
        for k in range(a.frames):
            e = [abs(r[k]["error_pct"]) for r in runs]
            db = [r[k]["db_vs_fixed"] for r in runs]
            print(f"budget {b:2d} % frame {k + 1}: |error| mean {np.mean(e):5.2f} max {np.max(e):5.2f}, "
                  f"within 1 % {sum(x <= 1 for x in e):2d}/{len(e)}; dB vs fixed mean {np.mean(db):+.2f} "
                  f"median {np.median(db):+.2f} min {np.min(db):+.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
