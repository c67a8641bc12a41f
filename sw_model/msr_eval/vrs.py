"""A variable-rate-shading baseline in the manner of VRS tier 2 (a screen-space shading-rate
image, one rate per tile, as games use it).

1. Coarse pre-pass: the pixel (4i, 4j) of every 4x4 block is traced (1/16 of the frame). A game
   would read last frame's image instead; we have no last frame, so the pre-pass stands in.
2. Per `tile` x `tile` tile (8 or 16), its contrast: the largest per-channel max - min (8-bit
   units) over the pre-pass samples in the tile and the first pre-pass row and column of the
   next tiles (the samples that bracket the tile; clipped to the frame).
3. The rate from the contrast and the threshold s: contrast <= s: 4x4; <= 2s: 2x2;
   <= 4s: 2x1 (2 wide, 1 tall); else 1x1.
4. Shading: per coarse pixel (blocks of the rate, aligned to the tile) its top-left pixel is
   traced (the pre-pass sample is reused where it is that pixel) and its colour replicated over
   the block, as coarse shading does (no interpolation). Hardware shades the coarse pixel at its
   centre, between pixels; our rendering unit traces whole pixels, so the top-left pixel stands
   in (a shift of up to 1.5 pixels at 4x4).
"""
from __future__ import annotations

import numpy as np

from msr_model import spec

from .methods import SRC_INTERP, SRC_TRACED, CountingRenderer, MethodResult

RATES = ((4, 4), (2, 2), (2, 1), (1, 1))     # (width, height) of a coarse pixel, coarsest first
COARSE = 4                                  # pre-pass pitch


def tile_contrast(pre: np.ndarray, width: int, height: int, tile: int) -> np.ndarray:
    """(tiles_y, tiles_x) contrast from the pre-pass samples pre (ceil(H/4), ceil(W/4), 3): per
    tile, the largest per-channel max - min over the (k+1) x (k+1) samples from its first one
    (k = tile / 4), clipped to the frame."""
    ntx, nty = -(-width // tile), -(-height // tile)
    k = tile // COARSE
    p = pre.astype(np.int32)
    # edge rows/columns repeated: a clipped window holds the last real sample, so copies of it
    # change neither its max nor its min
    p = np.pad(p, ((0, max(0, nty * k + 1 - p.shape[0])), (0, max(0, ntx * k + 1 - p.shape[1])), (0, 0)),
               mode="edge")
    hi = np.full((nty, ntx, 3), -1, np.int32)
    lo = np.full((nty, ntx, 3), 256, np.int32)
    for dy in range(k + 1):
        for dx in range(k + 1):
            v = p[dy:dy + k * (nty - 1) + 1:k, dx:dx + k * (ntx - 1) + 1:k]
            np.maximum(hi, v, out=hi)
            np.minimum(lo, v, out=lo)
    return (hi - lo).max(axis=2)


def rate_index(contrast: np.ndarray, s: float) -> np.ndarray:
    """Index into RATES: 0 (4x4) for contrast <= s, 1 (2x2) <= 2s, 2 (2x1) <= 4s, else 3 (1x1)."""
    return np.select([contrast <= s, contrast <= 2 * s, contrast <= 4 * s], [0, 1, 2], 3).astype(np.int8)


def vrs_tier2(renderer, width: int, height: int, thr: float, tile: int = 8) -> MethodResult:
    """The VRS-like baseline with threshold scale `thr` and `tile` x `tile` rate tiles."""
    spec.check_frame_size(width, height)
    if tile not in (8, 16, 32):
        raise spec.SpecError(f"VRS tile must be 8, 16 or 32, got {tile}")
    c = CountingRenderer(renderer, width, height)
    frame = np.zeros((height, width, 3), np.uint8)
    known = np.zeros((height, width), bool)
    ys, xs = np.mgrid[0:height:COARSE, 0:width:COARSE]
    pre = c.render(xs.ravel(), ys.ravel()).reshape(ys.shape + (3,))
    frame[ys, xs] = pre
    known[ys, xs] = True
    rate = rate_index(tile_contrast(pre, width, height, tile), thr)
    # the rate of every pixel, and the top-left pixel of its coarse pixel
    yy, xx = np.mgrid[0:height, 0:width]
    r = rate[yy // tile, xx // tile]
    rw = np.array([w for w, _ in RATES])[r]
    rh = np.array([h for _, h in RATES])[r]
    ox, oy = (xx // tile) * tile, (yy // tile) * tile
    ax = ox + ((xx - ox) // rw) * rw
    ay = oy + ((yy - oy) // rh) * rh
    anchor = (ax == xx) & (ay == yy)
    need = anchor & ~known
    ny, nx = np.nonzero(need)
    if nx.size:
        frame[ny, nx] = c.render(nx, ny)
    frame = frame[ay, ax]
    source = np.where(anchor, SRC_TRACED, SRC_INTERP).astype(np.uint8)
    source[known] = SRC_TRACED
    res = MethodResult(frame, source, c.requests, f"vrs_T{tile}", {"thr": thr, "tile": tile})
    res.rates = rate                     # per tile: index into RATES (for tests and pictures)
    return res
