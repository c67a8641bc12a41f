"""Converged references: what every method is scored against besides the renderer's own full
render (docs/results.md, "Against the converged reference").

The heavy renderer's full render has the noise of 16 samples per pixel: scored against it, an
interpolated pixel (a local average, closer to the noise-free image) counts as error and a
traced pixel's own noise counts as exact. The converged reference is the same renderer, same
scene, view and size, with CONV_GRID[mode]^2 stratified samples per pixel
(`msr_render_create_spp`, seed CONV_SEEDS[0]). The fast renderer has no Monte Carlo noise (one
sample at the pixel centre, noise-free light probes); its converged reference is the same
shading with the same number of antialiasing samples, so against it the fast mode's own
aliasing shows.

How converged: a second render with another seed (CONV_SEEDS[1]); the PSNR between the two
independent renders is recorded per scene and mode (`psnr_two_seeds`). Each one's own error
against the noise-free image is then about 3 dB better than that (independent errors add).
docs/dacs.md gives the study that chose the counts.

Scoring helpers: PSNR / SSIM / FLIP against the converged frame, the worst 32x32 tile's PSNR
(the local failures a mean hides). The comparison's summaries, tables and plots are in
msr_eval.conv_report (kept apart: the record cache is keyed by this file, not by the docs code).
"""
from __future__ import annotations

import time

import numpy as np

from .metrics import capped, psnr, psnr_of_mse

# The sample counts tried, smallest first (antialiasing grids: 16 = 256 samples per pixel, 32 =
# 1024): the first whose two-seed PSNR reaches CONV_TARGET_DB is the reference (else the last).
CONV_GRIDS = {"heavy": (16, 32), "fast": (16,)}
CONV_TARGET_DB = 47.0                     # two seeds 47 dB: each about 50 dB from the noise-free image
CONV_SEEDS = (0x5EED0001, 0x5EED0002)     # reference, check (neither is the modes' own seed)
TILE = 32                                  # the local-failure tile


def conv_grids_for(mode: str, override: int | None = None, ladder_grid: int | None = None) -> tuple:
    """The grids tried for a mode: just `override` if given; else, in heavy mode, the one grid
    that the quick-size ladder chose for the scene (`ladder_grid`, data/converged/ladder.json,
    used by the full-size run); else CONV_GRIDS[mode]."""
    if override:
        return (int(override),)
    if ladder_grid and mode == "heavy":
        return (int(ladder_grid),)
    return CONV_GRIDS.get(mode, (16,))


def conv_key(mode: str, override: int | None, check: bool, ladder_grid: int | None = None) -> str:
    g = conv_grids_for(mode, override, ladder_grid)
    return "g" + "-".join(map(str, g)) + (f"_t{CONV_TARGET_DB:g}" if check and len(g) > 1 else "") + \
        ("_c" if check else "")


def task_converged(backend: str, scene: str, mode: str, width: int, height: int, grids, check: bool):
    """The converged reference of one scene and mode, and its info (grid, spp, seeds, the
    two-seed PSNR of every grid tried when `check`, wall times). With `check`, the grids are
    tried smallest first and the first whose two-seed PSNR reaches CONV_TARGET_DB is kept
    (else the last); without, the last grid is rendered once. The test-picture backend has no
    noise: its reference is the picture itself."""
    from msr_model.testimage import test_image
    if backend == "image":
        return test_image(width, height), {"grid": 0, "spp": 1, "psnr_two_seeds": None,
                                           "note": "test picture: no noise, the picture itself"}
    from msr_model import embree

    def render(g, seed):
        with embree.open_renderer(scene, width, height, mode, grid=g, seed=seed) as r:
            return r.render_full(progress=False)

    grids = tuple(grids)
    tried = []
    for g in (grids if check else grids[-1:]):
        t0 = time.perf_counter()
        frame = render(g, CONV_SEEDS[0])
        info = {"grid": g, "spp": g * g, "seeds": list(CONV_SEEDS[:2 if check else 1]),
                "render_s": time.perf_counter() - t0}
        if not check:
            break
        other = render(g, CONV_SEEDS[1])
        info["psnr_two_seeds"] = psnr(frame, other)
        info["tile_min_psnr_two_seeds"] = tile_min_psnr(frame, other)
        d = ((frame.astype(np.int32) - other.astype(np.int32)) ** 2).sum(axis=2).ravel()
        top = np.sort(d)[::-1][:max(1, d.size // 100)]
        info["mse_share_top1pct"] = float(top.sum() / d.sum()) if d.sum() else 0.0
        tried.append({"spp": g * g, "psnr_two_seeds": info["psnr_two_seeds"]})
        if info["psnr_two_seeds"] >= CONV_TARGET_DB:
            break
    if check:
        info["tried"] = tried
        info["target_db"] = CONV_TARGET_DB
    return frame, info


def tile_psnrs(ref, img, tile: int = TILE) -> np.ndarray:
    """PSNR of every tile x tile tile (partial tiles at the right and bottom count; inf where
    the tile is identical)."""
    h, w = ref.shape[:2]
    d = (ref.astype(np.float64) - img.astype(np.float64)) ** 2
    ty, tx = -(-h // tile), -(-w // tile)
    pad = np.zeros((ty * tile, tx * tile, 3))
    cnt = np.zeros((ty * tile, tx * tile))
    pad[:h, :w] = d
    cnt[:h, :w] = 3
    s = pad.reshape(ty, tile, tx, tile, 3).sum(axis=(1, 3, 4))
    n = cnt.reshape(ty, tile, tx, tile).sum(axis=(1, 3))
    return psnr_of_mse(s / n)


def tile_min_psnr(ref, img, tile: int = TILE) -> float:
    return float(tile_psnrs(ref, img, tile).min())


def score(conv, frame, all_metrics: bool) -> dict:
    """The record fields against the converged reference."""
    from .metrics import flip, ssim
    out = {"psnr_conv": psnr(conv, frame), "tile32_min_psnr_conv": tile_min_psnr(conv, frame)}
    if all_metrics:
        out["ssim_conv"] = ssim(conv, frame)
        out["flip_conv"] = flip(conv, frame)
    return out


def as_conv(records):
    """The records with psnr (and ssim, flip) against the converged reference in place of the
    ones against the full render (for metrics.summarise and friends)."""
    out = []
    for r in records:
        if "psnr_conv" not in r:
            continue
        c = {**r, "psnr": r["psnr_conv"]}
        for k in ("ssim", "flip"):
            c.pop(k, None)
            if f"{k}_conv" in r:
                c[k] = r[f"{k}_conv"]
        out.append(c)
    return out


def pick_near_conv(records, scene, mode, fam, target):
    """The cheapest setting of a family reaching `target` dB against the converged reference
    (else its best by that PSNR)."""
    rs = [r for r in records if r["scene"] == scene and r["mode"] == mode and r["family"] == fam
          and "psnr_conv" in r]
    ok = [r for r in rs if capped(r["psnr_conv"]) >= target]
    if ok:
        return min(ok, key=lambda r: r["traced_fraction"])
    return max(rs, key=lambda r: capped(r["psnr_conv"])) if rs else None
