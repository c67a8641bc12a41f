"""Deferred Adaptive Compute Shading (Mallett and Yuksel, HPG 2018) as a method of the evaluation.

The frame is filled coarse to fine in five passes over 4x4 blocks (the paper's Figure 2 order;
`block=8` is our extension, two more passes in front, see passes_for):

    pass 0  (0,0) of every block                      traced, always
    pass 1  (2,2)             neighbours (+-2, +-2)   diagonal, 2 apart
    pass 2  (2,0), (0,2)      neighbours (+-2, 0), (0, +-2)
    pass 3  (1,1), (3,1), (1,3), (3,3)   neighbours (+-1, +-1)
    pass 4  the other 8       neighbours (+-1, 0), (0, +-1)

Every pixel of passes 1-4 sits at the centre of four pixels that earlier passes made final
(traced or interpolated). From those neighbours' colours the pixel gets a statistic; at or
below the threshold it is interpolated (the rounded mean of the neighbours), above it is
traced. The passes run over the whole frame (no tiles: a GPU compute shader reads any earlier
pixel), so DACS has no tile independence, unlike the patent's method.

Choices the paper leaves open, or that we could not take from it (docs/dacs.md):
- statistic `metric`: "var" (default) the population variance of each RGB channel over the
  neighbours, the largest of the three (8-bit sRGB units squared); "lumvar" the variance of
  the Rec. 709 luma; "range" the largest per-channel max - min (the patent's kind of test);
- exact arithmetic: every statistic is a fraction num / den of integers (the luma in fixed
  point, 10^4 times the Rec. 709 sum, which is exact), the threshold a multiple of 1/16, and
  the test 16 num <= (16 thr) den runs in integers: no rounding decides a tie;
- frame edges: neighbours outside the frame are left out, and a pixel is interpolated only
  if at least one opposite pair of its neighbours (left and right, up and down, or two
  opposite corners) lies inside the frame, so nothing is extrapolated: beyond the last grid
  row or column (a frame size not 1 more than a multiple of 4) pixels are traced, as the
  evaluation's grids trace their last row and column;
- the test is `stat <= thr` (a tie interpolates), so thr = 0 interpolates only between
  identical neighbours and a negative thr traces everything. Four 8-bit neighbours have a
  variance in steps of 1/16 (3/16 for one neighbour 1 off): the sweep's thresholds below 1
  come in those steps.
"""
from __future__ import annotations

from fractions import Fraction

import numpy as np

from msr_model import spec

from .methods import SRC_INTERP, SRC_TRACED, CountingRenderer, MethodResult

BLOCKS = (4, 8)          # 4: the paper's; 8: our extension (a first pass of one pixel in 64)


def passes_for(block: int = 4) -> tuple:
    """(positions in a block x block block as (dx, dy), neighbour offsets) for the passes after
    pass 0: per level s = block/2, block/4, .., 1, the centres of the squares of side 2s
    (diagonal neighbours s apart), then the centres of their edges (axial neighbours s apart).
    block = 4 gives the paper's four passes; block = 8 (an extension, labelled so in the
    evaluation) puts two more levels in front with a first pass of one pixel in 64."""
    if block not in BLOCKS:
        raise spec.SpecError(f"DACS block must be one of {BLOCKS}, got {block!r}")
    out = []
    s = block // 2
    while s >= 1:
        cells = [(x, y) for y in range(block) for x in range(block)]
        diag = tuple((x, y) for x, y in cells if x % (2 * s) == s and y % (2 * s) == s)
        axial = tuple((x, y) for x, y in cells if (x % (2 * s), y % (2 * s)) in ((s, 0), (0, s)))
        out.append((diag, ((-s, -s), (s, -s), (-s, s), (s, s))))
        out.append((axial, ((-s, 0), (s, 0), (0, -s), (0, s))))
        s //= 2
    return tuple(out)


# (positions in a 4x4 block as (dx, dy), neighbour offsets) for passes 1..4
PASSES = passes_for(4)
METRICS = ("var", "lumvar", "range")
LUMA = np.array([0.2126, 0.7152, 0.0722])
LUMA_FIXED = np.array([2126, 7152, 722], np.int64)     # LUMA x 10^4: the luma in exact integers
LUMA_SCALE = 10_000
THR_STEPS = 16                                          # thresholds are multiples of 1/16
# 16 thr beyond which every statistic passes (16 x 127.5^2 < 2^20): keeps the products in int64
_THR16_CAP = 1 << 20


def thr_sixteenths(thr) -> int:
    """The threshold as a whole number of sixteenths (-1 for any negative threshold: trace
    everything). SpecError unless it is a multiple of 1/16 (floats are read exactly)."""
    try:
        if isinstance(thr, (str, bytes, bool)):      # Fraction reads "1"; a flag is no threshold
            raise TypeError
        f = Fraction(thr)
    except (TypeError, ValueError, OverflowError):
        raise spec.SpecError(f"DACS threshold must be a number, got {thr!r}") from None
    if f < 0:
        return -1
    q = f * THR_STEPS
    if q.denominator != 1:
        raise spec.SpecError(f"DACS threshold must be a multiple of 1/{THR_STEPS}, got {thr!r}")
    return int(min(q, _THR16_CAP))


def pass_of(width: int, height: int, block: int = 4) -> np.ndarray:
    """(H, W) int: the pass (0 .. 2 log2(block)) that decides each pixel."""
    yy, xx = np.mgrid[0:height, 0:width]
    out = np.full((height, width), -1, np.int8)
    out[(xx % block == 0) & (yy % block == 0)] = 0
    for k, (pos, _) in enumerate(passes_for(block), start=1):
        for dx, dy in pos:
            out[(xx % block == dx) & (yy % block == dy)] = k
    assert (out >= 0).all()
    return out


def stat_parts(xs4, vs4, metric: str):
    """xs4: the four neighbours' colours, each (..., 3) int64 and 0 where not valid; vs4: their
    validity, each (...) bool. (num, den), int64 arrays (...) with the statistic over the valid
    neighbours = num / den exactly (population variance: (n S2 - S1^2) / n^2)."""
    n = np.maximum(vs4[0].astype(np.int64) + vs4[1] + vs4[2] + vs4[3], 1)
    if metric == "range":
        hi = np.maximum.reduce([np.where(v[..., None], x, -1) for x, v in zip(xs4, vs4)])
        lo = np.minimum.reduce([np.where(v[..., None], x, 256) for x, v in zip(xs4, vs4)])
        return np.maximum(hi - lo, 0).max(axis=-1), np.ones_like(n)
    if metric == "lumvar":
        ys = [x @ LUMA_FIXED for x in xs4]                  # 10^4 luma, 0 where not valid
        s1, s2 = ys[0] + ys[1] + ys[2] + ys[3], ys[0] * ys[0] + ys[1] * ys[1] + ys[2] * ys[2] + ys[3] * ys[3]
        return n * s2 - s1 * s1, n * n * (LUMA_SCALE * LUMA_SCALE)
    s1 = xs4[0] + xs4[1] + xs4[2] + xs4[3]
    s2 = xs4[0] * xs4[0] + xs4[1] * xs4[1] + xs4[2] * xs4[2] + xs4[3] * xs4[3]
    return (n[..., None] * s2 - s1 * s1).max(axis=-1), n * n    # one n^2 for the three channels


def within(num, den, thr16: int):
    """stat <= thr, in integers: 16 num <= (16 thr) den (a tie passes)."""
    return THR_STEPS * num <= thr16 * den


def statistic(nb: np.ndarray, valid: np.ndarray, metric: str) -> np.ndarray:
    """nb: (..., 4, 3) neighbour colours, valid: (..., 4) bool. The per-pixel statistic (...)
    over the valid neighbours only, as a float (for reading; decisions use stat_parts and within)."""
    x = nb.astype(np.int64) * valid[..., None]
    num, den = stat_parts([x[..., k, :] for k in range(4)], [valid[..., k] for k in range(4)], metric)
    return num / den


def dacs(renderer, width: int, height: int, thr: float, metric: str = "var", block: int = 4) -> MethodResult:
    """DACS on the whole frame with threshold `thr` on `metric` over `block` x `block` blocks
    (module docstring; block 8 is our extension)."""
    spec.check_frame_size(width, height)
    if metric not in METRICS:
        raise spec.SpecError(f"DACS metric must be one of {', '.join(METRICS)}, got {metric!r}")
    thr16 = thr_sixteenths(thr)
    order = passes_for(block)
    B = block
    c = CountingRenderer(renderer, width, height)
    P = B // 2                                        # padding: neighbours up to B/2 pixels off the frame
    F = np.zeros((height + 2 * P, width + 2 * P, 3), np.uint8)     # the frame, padded
    V = np.zeros((height + 2 * P, width + 2 * P), bool)            # final (inside the frame only)
    source = np.full((height, width), spec.SRC_UNSET, np.uint8)
    ys, xs = np.arange(0, height, B), np.arange(0, width, B)
    yy, xx = np.meshgrid(ys, xs, indexing="ij")
    F[P:P + height:B, P:P + width:B] = c.render(xx.ravel(), yy.ravel()).reshape(yy.shape + (3,))
    V[P:P + height:B, P:P + width:B] = True
    source[0::B, 0::B] = SRC_TRACED
    for pos, offs in order:
        for dx, dy in pos:                            # each position class is a regular sub-grid
            ny, nx = len(range(dy, height, B)), len(range(dx, width, B))
            if ny == 0 or nx == 0:
                continue
            sl = [(slice(P + dy + oy, P + dy + oy + B * (ny - 1) + 1, B),
                   slice(P + dx + ox, P + dx + ox + B * (nx - 1) + 1, B)) for ox, oy in offs]
            xs4 = [F[a, b].astype(np.int64) * V[a, b][..., None] for a, b in sl]   # 0 where not valid
            vs4 = [V[a, b] for a, b in sl]
            nvalid = vs4[0].astype(np.int64) + vs4[1] + vs4[2] + vs4[3]
            s1 = xs4[0] + xs4[1] + xs4[2] + xs4[3]                    # (ny, nx, 3), exact
            num, den = stat_parts(xs4, vs4, metric)
            # offsets come as two opposite pairs (0, 3), (1, 2) diagonal or (0, 1), (2, 3) axial
            pairs = ((0, 3), (1, 2)) if offs[0][0] and offs[0][1] else ((0, 1), (2, 3))
            between = (vs4[pairs[0][0]] & vs4[pairs[0][1]]) | (vs4[pairs[1][0]] & vs4[pairs[1][1]])
            ok = between & within(num, den, thr16)
            cnt = np.maximum(nvalid, 1)[..., None]
            val = ((s1 + cnt // 2) // cnt).astype(np.uint8)            # rounded mean of the valid ones
            ty, tx = np.nonzero(~ok)
            if ty.size:
                val[ty, tx] = c.render(dx + B * tx, dy + B * ty)
            F[P + dy:P + dy + B * (ny - 1) + 1:B, P + dx:P + dx + B * (nx - 1) + 1:B] = val
            V[P + dy:P + dy + B * (ny - 1) + 1:B, P + dx:P + dx + B * (nx - 1) + 1:B] = True
            source[dy::B, dx::B] = np.where(ok, SRC_INTERP, SRC_TRACED)
    assert V[P:P + height, P:P + width].all() and not (source == spec.SRC_UNSET).any(), "every pixel is final"
    frame = np.ascontiguousarray(F[P:P + height, P:P + width])
    name = "dacs" if B == 4 else f"dacs_B{B}"
    return MethodResult(frame, source, c.requests, name, {"thr": thr, "metric": metric, "block": B})
