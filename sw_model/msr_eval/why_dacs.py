"""Why DACS wins where it wins : per 32x32 tile, where a rule's error against
the converged image exceeds DACS's at the same traced fraction, and what those tiles hold.

For one scene (heavy renderer, converged reference from data/converged/ or rendered), two
methods are run at settings with nearly the same traced fraction (each family's setting
closest to a target fraction). Per tile: the squared error against the converged image of
each, the 16-spp full render's own error there (its noise), the converged image's gradient
energy (its structure: edges, texture) and each method's traced pixels. Tiles are grouped by
noise and by structure (quartiles over the frame); per group the share of the frame's extra
squared error that the rule has over DACS is reported, and where each method spends its
traced pixels (the rule per level, DACS per pass).

    python -m msr_eval.why_dacs --scene duck --width 1920 --height 1080 --fraction 0.3 --json out.json
"""
from __future__ import annotations

import argparse
import json
import sys

import numpy as np

from msr_model import ImageRenderer, Params, spec

from . import dacs as D
from . import methods as M
from .metrics import psnr
from .reference import CONV_SEEDS

TILE = 32


def tile_sums(x: np.ndarray, tile: int = TILE) -> np.ndarray:
    """Per tile sums of an (H, W) array (partial tiles at the right and bottom included; the
    tiling of reference.tile_psnrs, the worst-tile figure)."""
    h, w = x.shape
    ty, tx = -(-h // tile), -(-w // tile)
    pad = np.zeros((ty * tile, tx * tile))
    pad[:h, :w] = x
    return pad.reshape(ty, tile, tx, tile).sum(axis=(1, 3))


def structure(conv: np.ndarray) -> np.ndarray:
    """Per pixel gradient energy of the converged image (max over channels of the squared
    forward differences), what interpolation has to get right."""
    c = conv.astype(np.float64)
    gx = np.zeros_like(c)
    gy = np.zeros_like(c)
    gx[:, :-1] = c[:, 1:] - c[:, :-1]
    gy[:-1] = c[1:] - c[:-1]
    return (gx ** 2 + gy ** 2).max(axis=2)


def _closest(run, settings, target):
    best = None
    for s in settings:
        res = run(s)
        f = res.traced / res.source.size
        if best is None or abs(f - target) < abs(best[1] - target):
            best = (s, f, res)
    return best


def compare(ref: np.ndarray, conv: np.ndarray, rule: str = "lindilate2d", tile: int = 32, levels: int = 3,
            target: float = 0.3, dacs_block: int = 4, dacs_metric: str = "var") -> dict:
    """The per-tile comparison at about `target` traced (module docstring)."""
    H, W = ref.shape[:2]
    scales = (0.25, 0.5, 1, 1.5, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64, 96)

    def run_rule(s):
        thr = tuple(min(255, max(1, int(s * (1 << k)))) for k in range(levels))
        return M.multi_level(ImageRenderer(ref), W, H, Params(tile=tile, levels=levels, thr=thr), rule=rule)

    def run_dacs(t):
        return D.dacs(ImageRenderer(ref), W, H, thr=t, metric=dacs_metric, block=dacs_block)

    rs, rf, rres = _closest(run_rule, scales, target)
    ds, df, dres = _closest(run_dacs, (0, 1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64, 96, 128, 192, 256, 384, 512,
                                       768, 1024, 2048, 4096), target)
    c = conv.astype(np.float64)
    se = {k: ((r.frame.astype(np.float64) - c) ** 2).sum(axis=2) for k, r in (("rule", rres), ("dacs", dres))}
    noise = ((ref.astype(np.float64) - c) ** 2).sum(axis=2)
    st = structure(conv)
    t_rule, t_dacs = tile_sums(se["rule"]), tile_sums(se["dacs"])
    t_noise, t_struct = tile_sums(noise), tile_sums(st)
    traced_rule = tile_sums((rres.source < 16).astype(np.float64))
    traced_dacs = tile_sums((dres.source < 16).astype(np.float64))
    extra = t_rule - t_dacs                                  # > 0: the rule is worse there
    total = float(extra.sum())
    out = {"rule": {"setting": rs, "traced_fraction": rf, "psnr_conv": psnr(conv, rres.frame)},
           "dacs": {"setting": ds, "block": dacs_block, "metric": dacs_metric, "traced_fraction": df,
                    "psnr_conv": psnr(conv, dres.frame)},
           "full_psnr_conv": psnr(conv, ref), "tiles": int(extra.size),
           "extra_se_total": total, "tiles_rule_worse": int((extra > 0).sum())}
    for name, feat in (("noise", t_noise), ("structure", t_struct)):
        # quartiles by rank (stable), so ties (many empty background tiles) still split evenly
        rank = np.empty(feat.size, np.int64)
        rank[np.argsort(feat.ravel(), kind="stable")] = np.arange(feat.size)
        groups = (4 * rank // feat.size).reshape(feat.shape)
        rows = []
        for g in range(4):
            m = groups == g
            rows.append({"quartile": g + 1, "tiles": int(m.sum()),
                         "extra_se_share": float(extra[m].sum() / abs(total)) if total else 0.0,
                         "rule_se": float(t_rule[m].sum()), "dacs_se": float(t_dacs[m].sum()),
                         "traced_rule": float(traced_rule[m].sum()), "traced_dacs": float(traced_dacs[m].sum())})
        out[f"by_{name}"] = rows
    # where the traced pixels go: the rule by level (source codes), DACS by pass
    codes = rres.source
    out["rule_traced_by_level"] = {f"level {k}": int((codes == k).sum()) for k in range(levels + 1)}
    passes = D.pass_of(W, H, dacs_block)
    out["dacs_traced_by_pass"] = {f"pass {k}": int(((passes == k) & (dres.source < 16)).sum())
                                  for k in range(int(passes.max()) + 1)}
    # interpolated pixels' error: how much of each method's error sits in interpolated pixels,
    # and in traced ones (noise it kept)
    for k, r in (("rule", rres), ("dacs", dres)):
        interp = r.source >= 16
        out[k]["se_interpolated"] = float(se[k][interp].sum())
        out[k]["se_traced"] = float(se[k][~interp].sum())
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scene", required=True)
    ap.add_argument("--width", type=int, default=1920)
    ap.add_argument("--height", type=int, default=1080)
    ap.add_argument("--fraction", type=float, default=0.3)
    ap.add_argument("--rule", default="lindilate2d")
    ap.add_argument("--tile", type=int, default=32)
    ap.add_argument("--dacs-block", type=int, default=4)
    ap.add_argument("--dacs-metric", default="var")
    ap.add_argument("--json", default=None)
    a = ap.parse_args(argv)
    from msr_model import embree
    from . import conv_store as CS
    from .scenes import scene_id
    with embree.open_renderer(a.scene, a.width, a.height, "heavy") as r:
        ref = r.render_full(progress=False)
    hit = CS.Store(a.width, a.height).load_ref(scene_id(a.scene), "heavy", CS.frame_sha(ref),
                                               CS.ladder_grid(scene_id(a.scene)) or 16, CONV_SEEDS[0])
    if hit is None:
        sys.exit(f"why_dacs: no committed converged reference for {a.scene} at {a.width}x{a.height} "
                 "(make eval FULL=1 writes them)")
    try:
        res = compare(ref, hit[0], a.rule, a.tile, 3, a.fraction, a.dacs_block, a.dacs_metric)
    except spec.SpecError as e:
        sys.exit(f"why_dacs: {e}")
    text = json.dumps(res, indent=1)
    if a.json:
        with open(a.json, "w") as f:
            f.write(text)
    print(text)


if __name__ == "__main__":
    main()
