"""Deferred Adaptive Compute Shading (Mallett and Yuksel, HPG 2018) as a method of the evaluation.

The frame is filled coarse to fine in five passes over 4x4 blocks (the paper's Figure 2 order):

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
- neighbours outside the frame are left out; a pixel with fewer than `min_neighbours` (2)
  neighbours inside the frame is traced;
- the test is `stat <= thr`, so thr = 0 interpolates only between identical neighbours and a
  negative thr traces everything.
"""
from __future__ import annotations

import numpy as np

from msr_model import spec

from .methods import SRC_INTERP, SRC_TRACED, CountingRenderer, MethodResult

# (positions in a 4x4 block as (dx, dy), neighbour offsets) for passes 1..4
PASSES = (
    (((2, 2),), ((-2, -2), (2, -2), (-2, 2), (2, 2))),
    (((2, 0), (0, 2)), ((-2, 0), (2, 0), (0, -2), (0, 2))),
    (((1, 1), (3, 1), (1, 3), (3, 3)), ((-1, -1), (1, -1), (-1, 1), (1, 1))),
    (((1, 0), (3, 0), (0, 1), (2, 1), (1, 2), (3, 2), (0, 3), (2, 3)), ((-1, 0), (1, 0), (0, -1), (0, 1))),
)
METRICS = ("var", "lumvar", "range")
LUMA = np.array([0.2126, 0.7152, 0.0722])


def pass_of(width: int, height: int) -> np.ndarray:
    """(H, W) int: the pass (0..4) that decides each pixel."""
    yy, xx = np.mgrid[0:height, 0:width]
    out = np.full((height, width), -1, np.int8)
    out[(xx % 4 == 0) & (yy % 4 == 0)] = 0
    for k, (pos, _) in enumerate(PASSES, start=1):
        for dx, dy in pos:
            out[(xx % 4 == dx) & (yy % 4 == dy)] = k
    assert (out >= 0).all()
    return out


def statistic(nb: np.ndarray, valid: np.ndarray, metric: str) -> np.ndarray:
    """nb: (N, 4, 3) neighbour colours, valid: (N, 4) bool. The per-pixel statistic (N,) over the
    valid neighbours only."""
    v = valid[:, :, None].astype(np.float64)
    n = np.maximum(valid.sum(axis=1), 1).astype(np.float64)
    x = nb.astype(np.float64)
    if metric == "range":
        hi = np.where(valid[:, :, None], x, -np.inf).max(axis=1)
        lo = np.where(valid[:, :, None], x, np.inf).min(axis=1)
        return (hi - lo).max(axis=1)
    if metric == "lumvar":
        x = (x @ LUMA)[:, :, None]
        v = v[:, :, :1]
    mean = (x * v).sum(axis=1) / n[:, None]
    var = (((x - mean[:, None, :]) ** 2) * v).sum(axis=1) / n[:, None]
    return var.max(axis=1)


def dacs(renderer, width: int, height: int, thr: float, metric: str = "var",
         min_neighbours: int = 2) -> MethodResult:
    """DACS on the whole frame with threshold `thr` on `metric` (module docstring)."""
    spec.check_frame_size(width, height)
    if metric not in METRICS:
        raise spec.SpecError(f"DACS metric must be one of {', '.join(METRICS)}, got {metric!r}")
    if not 1 <= min_neighbours <= 4:
        raise spec.SpecError(f"min_neighbours must be 1..4, got {min_neighbours}")
    c = CountingRenderer(renderer, width, height)
    frame = np.zeros((height, width, 3), np.uint8)
    source = np.full((height, width), spec.SRC_UNSET, np.uint8)
    final = np.zeros((height, width), bool)
    ys, xs = np.mgrid[0:height:4, 0:width:4]
    frame[ys, xs] = c.render(xs.ravel(), ys.ravel()).reshape(ys.shape + (3,))
    source[ys, xs] = SRC_TRACED
    final[ys, xs] = True
    for pos, offs in PASSES:
        px, py = [], []
        for dx, dy in pos:
            yy, xx = np.mgrid[dy:height:4, dx:width:4]
            px.append(xx.ravel())
            py.append(yy.ravel())
        px, py = np.concatenate(px), np.concatenate(py)
        if px.size == 0:
            continue
        nx = px[:, None] + np.array([o[0] for o in offs])[None, :]
        ny = py[:, None] + np.array([o[1] for o in offs])[None, :]
        valid = (nx >= 0) & (nx < width) & (ny >= 0) & (ny < height)
        cx, cy = np.clip(nx, 0, width - 1), np.clip(ny, 0, height - 1)
        assert final[cy, cx][valid].all(), "a neighbour is not final yet"
        nb = frame[cy, cx]                                     # (N, 4, 3)
        stat = statistic(nb, valid, metric)
        nvalid = valid.sum(axis=1)
        ok = (nvalid >= min_neighbours) & (stat <= thr)
        if ok.any():
            cnt = nvalid[ok][:, None]
            s = (nb[ok].astype(np.int64) * valid[ok][:, :, None]).sum(axis=1)
            frame[py[ok], px[ok]] = ((s + cnt // 2) // cnt).astype(np.uint8)
            source[py[ok], px[ok]] = SRC_INTERP
        if (~ok).any():
            frame[py[~ok], px[~ok]] = c.render(px[~ok], py[~ok])
            source[py[~ok], px[~ok]] = SRC_TRACED
        final[py, px] = True
    assert final.all() and not (source == spec.SRC_UNSET).any(), "every pixel is final"
    return MethodResult(frame, source, c.requests, "dacs", {"thr": thr, "metric": metric})
