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


RATES_TIER2 = ((4, 4), (4, 2), (2, 4), (2, 2), (2, 1), (1, 2), (1, 1))   # every rate VRS tier 2 has
ANCHORS = ("centre", "top-left")


def tile_directions(pre: np.ndarray, width: int, height: int, tile: int) -> tuple[np.ndarray, np.ndarray]:
    """(gx, gy) per tile: the largest per-channel difference between horizontally (gx) and
    vertically (gy) adjacent pre-pass samples in the same window as tile_contrast. A tile whose
    colour changes less along x than along y is coarsened along x first (4x2, 2x1), else along y."""
    ntx, nty = -(-width // tile), -(-height // tile)
    k = tile // COARSE
    p = pre.astype(np.int32)
    p = np.pad(p, ((0, max(0, nty * k + 1 - p.shape[0])), (0, max(0, ntx * k + 1 - p.shape[1])), (0, 0)),
               mode="edge")
    dx = np.abs(np.diff(p, axis=1)).max(axis=2)       # (rows, cols-1)
    dy = np.abs(np.diff(p, axis=0)).max(axis=2)       # (rows-1, cols)
    gx = np.zeros((nty, ntx), np.int32)
    gy = np.zeros((nty, ntx), np.int32)
    for oy in range(k + 1):
        for ox in range(k):
            np.maximum(gx, dx[oy:oy + k * (nty - 1) + 1:k, ox:ox + k * (ntx - 1) + 1:k], out=gx)
    for oy in range(k):
        for ox in range(k + 1):
            np.maximum(gy, dy[oy:oy + k * (nty - 1) + 1:k, ox:ox + k * (ntx - 1) + 1:k], out=gy)
    return gx, gy


def rate_index_tier2(contrast: np.ndarray, gx: np.ndarray, gy: np.ndarray, s: float) -> np.ndarray:
    """Index into RATES_TIER2: contrast <= s: 4x4; <= 2s: 4x2 (gx <= gy) or 2x4; <= 4s: 2x2;
    <= 8s: 2x1 (gx <= gy) or 1x2; else 1x1."""
    wide = gx <= gy
    return np.select([contrast <= s, contrast <= 2 * s, contrast <= 4 * s, contrast <= 8 * s],
                     [0, np.where(wide, 1, 2), 3, np.where(wide, 4, 5)], 6).astype(np.int8)


def vrs_tier2(renderer, width: int, height: int, thr: float, tile: int = 8, rates: str = "basic",
              anchor: str = "top-left") -> MethodResult:
    """The VRS-like baseline with threshold scale `thr` and `tile` x `tile` rate tiles.

    rates "basic": 4x4, 2x2, 2x1, 1x1 (rate_index); "tier2": every rate of VRS tier 2
    (rate_index_tier2, the direction from tile_directions). anchor "top-left": each coarse
    pixel shows its top-left pixel and the pre-pass samples (4i, 4j); "centre": the pixel at
    (w/2, h/2) of the coarse pixel (the one right of and below its centre, the nearest whole
    pixel to where hardware shades it) and the pre-pass samples (4i+2, 4j+2), so a 4x4 coarse
    pixel reuses its pre-pass sample."""
    spec.check_frame_size(width, height)
    if tile not in (8, 16, 32):
        raise spec.SpecError(f"VRS tile must be 8, 16 or 32, got {tile}")
    if rates not in ("basic", "tier2"):
        raise spec.SpecError(f"VRS rates must be 'basic' or 'tier2', got {rates!r}")
    if anchor not in ANCHORS:
        raise spec.SpecError(f"VRS anchor must be one of {', '.join(ANCHORS)}, got {anchor!r}")
    c = CountingRenderer(renderer, width, height)
    frame = np.zeros((height, width, 3), np.uint8)
    known = np.zeros((height, width), bool)
    off = COARSE // 2 if anchor == "centre" else 0
    ys, xs = np.mgrid[0:height:COARSE, 0:width:COARSE]
    ys, xs = np.minimum(ys + off, height - 1), np.minimum(xs + off, width - 1)
    pre = c.render(xs.ravel(), ys.ravel()).reshape(ys.shape + (3,))
    frame[ys, xs] = pre
    known[ys, xs] = True
    contrast = tile_contrast(pre, width, height, tile)
    if rates == "basic":
        table, rate = RATES, rate_index(contrast, thr)
    else:
        table, rate = RATES_TIER2, rate_index_tier2(contrast, *tile_directions(pre, width, height, tile), thr)
    # the rate of every pixel, and the pixel that stands for its coarse pixel
    yy, xx = np.mgrid[0:height, 0:width]
    r = rate[yy // tile, xx // tile]
    rw = np.array([w for w, _ in table])[r]
    rh = np.array([h for _, h in table])[r]
    ox, oy = (xx // tile) * tile, (yy // tile) * tile
    bx = ox + ((xx - ox) // rw) * rw                  # the coarse pixel's top-left corner
    by = oy + ((yy - oy) // rh) * rh
    if anchor == "centre":                            # clipped to the frame (a partial tile)
        ax, ay = np.minimum(bx + rw // 2, width - 1), np.minimum(by + rh // 2, height - 1)
    else:
        ax, ay = bx, by
    anchor_px = (ax == xx) & (ay == yy)
    need = anchor_px & ~known
    ny, nx = np.nonzero(need)
    if nx.size:
        frame[ny, nx] = c.render(nx, ny)
    traced = known | anchor_px
    out = frame[ay, ax]
    # a traced pixel shows its own colour: a centred pre-pass sample that is not its coarse
    # pixel's anchor (at 2x2 and finer) is still a ray the unit paid for
    out[known] = frame[known]
    frame = out
    source = np.where(traced, SRC_TRACED, SRC_INTERP).astype(np.uint8)
    res = MethodResult(frame, source, c.requests, f"vrs_T{tile}", {"thr": thr, "tile": tile, "rates": rates,
                                                                    "anchor": anchor})
    res.rates = rate                     # per tile: index into the rate table (for tests and pictures)
    return res
