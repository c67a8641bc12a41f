"""Rendering methods compared by the evaluation: what a user would otherwise pick.

Every method is a function `method(renderer, width, height, ...) -> MethodResult`. It asks the
renderer only for the pixels it traces, and the traced count in the result is what the
renderer was actually asked for (a `CountingRenderer` wraps the renderer), never the
method's own bookkeeping.

- full_render:         every pixel traced (the reference).
- coarse_grid:         every `step`-th pixel in x and y (plus the last row/column, so nothing
                       is extrapolated), the rest bilinear.
- checkerboard:        pixels with (x + y) even traced, the others the rounded mean of their
                       (up to 4) traced edge neighbours.
- single_level:        conventional selective rendering (patent Fig. 4): grid every `stride`
                       pixels, one decision per gap: interpolate all `stride - 1` pixels between
                       two samples or trace them all. `border="traced"`: tiles are processed on
                       their own and the border region after a tile's last grid line is
                       fully traced (Fig. 5b); `border="borrowed"`: one frame-wide grid, so a
                       tile borrows the next tile's first grid line (Fig. 5, [0068]; the tiles
                       then depend on each other and cannot run in parallel).
- multi_level:         the patent's method, exactly msr_model.select; with rule= another
                       decision test (msr_eval.rules).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from msr_model import Params, render_checked, select, spec

from .rules import rule_function

# Source codes of the non-patent methods (the multi-level method keeps the spec's codes).
SRC_TRACED = 0
SRC_INTERP = 16


class CountingRenderer:
    """Wraps a renderer; counts and marks every pixel it is asked for."""

    def __init__(self, renderer, width: int, height: int):
        self.inner = renderer
        self.width, self.height = width, height
        self.requests = 0                       # pixels asked for, duplicates included
        self.mask = np.zeros((height, width), dtype=bool)

    def render(self, xs, ys) -> np.ndarray:
        xs = np.asarray(xs, dtype=np.int32).ravel()
        ys = np.asarray(ys, dtype=np.int32).ravel()
        if xs.size == 0:
            return np.zeros((0, 3), dtype=np.uint8)
        if xs.min() < 0 or ys.min() < 0 or xs.max() >= self.width or ys.max() >= self.height:
            raise ValueError("pixel request outside the frame")
        self.requests += xs.size
        self.mask[ys, xs] = True
        return render_checked(self.inner, xs, ys)


@dataclass
class MethodResult:
    frame: np.ndarray              # (H, W, 3) uint8
    source: np.ndarray             # (H, W) uint8: < 16 traced, >= 16 interpolated
    traced: int                    # pixels the renderer was asked for (duplicates included)
    method: str
    settings: dict = field(default_factory=dict)

    @property
    def traced_fraction(self) -> float:
        h, w = self.source.shape
        return self.traced / (w * h)


def _check(width, height):
    spec.check_frame_size(width, height)


def _result(counter, frame, source, method, settings):
    return MethodResult(frame, source, counter.requests, method, settings)


# --- full render ------------------------------------------------------------------------

def full_render(renderer, width: int, height: int, rows_per_call: int = 256) -> MethodResult:
    _check(width, height)
    c = CountingRenderer(renderer, width, height)
    frame = np.empty((height, width, 3), dtype=np.uint8)
    for y0 in range(0, height, rows_per_call):  # bounded batches keep memory flat at 4K
        y1 = min(height, y0 + rows_per_call)
        yy, xx = np.mgrid[y0:y1, 0:width]
        frame[y0:y1] = c.render(xx.ravel(), yy.ravel()).reshape(y1 - y0, width, 3)
    return _result(c, frame, np.full((height, width), SRC_TRACED, np.uint8), "full", {})


# --- uniform coarse grid ----------------------------------------------------------------

def grid_positions(n: int, step: int) -> np.ndarray:
    """0, step, 2*step, ... below n, plus n-1: the last row/column is traced (no extrapolation)."""
    return np.asarray(spec.initial_grid(n, step), dtype=np.int64)


def _bracket(n: int, grid: np.ndarray):
    """For every position 0..n-1: index of the grid interval holding it and the weight of its right end."""
    pos = np.arange(n)
    i = np.clip(np.searchsorted(grid, pos, side="right") - 1, 0, max(len(grid) - 2, 0))
    if len(grid) == 1:
        return i, np.zeros(n)
    a, b = grid[i], grid[i + 1]
    return i, (pos - a) / (b - a)


def coarse_grid(renderer, width: int, height: int, step: int) -> MethodResult:
    """Trace every `step`-th pixel (and the last row/column), reconstruct bilinearly."""
    _check(width, height)
    if step < 1:
        raise spec.SpecError(f"grid step must be >= 1, got {step}")
    c = CountingRenderer(renderer, width, height)
    gx, gy = grid_positions(width, step), grid_positions(height, step)
    yy, xx = np.meshgrid(gy, gx, indexing="ij")
    samples = c.render(xx.ravel(), yy.ravel()).reshape(len(gy), len(gx), 3).astype(np.float64)
    ix, wx = _bracket(width, gx)
    iy, wy = _bracket(height, gy)
    jx = np.minimum(ix + 1, len(gx) - 1)
    jy = np.minimum(iy + 1, len(gy) - 1)
    # separable bilinear: along x on the sampled rows, then along y
    rows = samples[:, ix] * (1 - wx)[None, :, None] + samples[:, jx] * wx[None, :, None]
    full = rows[iy] * (1 - wy)[:, None, None] + rows[jy] * wy[:, None, None]
    frame = np.clip(np.floor(full + 0.5), 0, 255).astype(np.uint8)
    frame[yy, xx] = samples.astype(np.uint8)       # traced pixels exactly as rendered
    source = np.full((height, width), SRC_INTERP, np.uint8)
    source[yy, xx] = SRC_TRACED
    return _result(c, frame, source, f"grid{step}", {"step": step})


# --- checkerboard -----------------------------------------------------------------------

def checkerboard(renderer, width: int, height: int) -> MethodResult:
    """Trace (x + y) even; every other pixel is the rounded mean of its traced 4-neighbours."""
    _check(width, height)
    c = CountingRenderer(renderer, width, height)
    yy, xx = np.mgrid[0:height, 0:width]
    even = (xx + yy) % 2 == 0
    frame = np.zeros((height, width, 3), dtype=np.uint8)
    frame[even] = c.render(xx[even], yy[even])
    f = frame.astype(np.int32)
    acc = np.zeros((height, width, 3), np.int32)
    cnt = np.zeros((height, width), np.int32)
    # every 4-neighbour of an odd pixel is even, so only traced pixels are summed
    acc[:, 1:] += f[:, :-1]
    cnt[:, 1:] += 1
    acc[:, :-1] += f[:, 1:]
    cnt[:, :-1] += 1
    acc[1:] += f[:-1]
    cnt[1:] += 1
    acc[:-1] += f[1:]
    cnt[:-1] += 1
    odd = ~even
    if odd.any():  # a 1x1 frame has no odd pixel (and no neighbours)
        n = cnt[odd][:, None]
        frame[odd] = ((acc[odd] + n // 2) // n).astype(np.uint8)
    source = np.where(even, SRC_TRACED, SRC_INTERP).astype(np.uint8)
    return _result(c, frame, source, "checkerboard", {})


# --- conventional single-level selective rendering ---------------------------------------

@dataclass
class _Axis:
    grid: np.ndarray        # sampled positions
    m: np.ndarray           # positions decided between two grid neighbours
    a: np.ndarray
    b: np.ndarray
    border: np.ndarray      # positions always traced (tile border region, Fig. 5b)


def _single_axis(n: int, stride: int, tile: int | None) -> _Axis:
    grid, m, a, b, border = [], [], [], [], []
    spans = [(0, n)] if tile is None else spec.axis_spans(n, tile)
    for origin, w in spans:
        if tile is None:
            g = spec.initial_grid(w, stride)          # frame-wide grid incl. the last column
        else:
            g = list(range(0, w, stride))             # a tile sees only its own pixels
            border += [origin + p for p in range(g[-1] + 1, w)]
        grid += [origin + p for p in g]
        for p, q in zip(g, g[1:]):
            for x in range(p + 1, q):
                m.append(origin + x)
                a.append(origin + p)
                b.append(origin + q)
    arr = lambda v: np.asarray(v, dtype=np.int64)  # noqa: E731
    return _Axis(arr(grid), arr(m), arr(a), arr(b), arr(border))


def single_level(renderer, width: int, height: int, thr: int, stride: int = 4,
                 border: str = "traced", tile: int = 16, metric: str = "max") -> MethodResult:
    """Conventional single-level selective rendering (patent Fig. 4).

    Grid every `stride` pixels traced. H pass on the grid rows, then V pass on every column:
    for each gap between two samples A, B (gap g <= stride) all g-1 pixels between are either
    interpolated linearly (if d * stride < thr * g, the same gap-weighted test as the spec)
    or all traced. `border` as in the module docstring.
    """
    _check(width, height)
    if border not in ("traced", "borrowed"):
        raise spec.SpecError(f"border must be 'traced' or 'borrowed', got {border!r}")
    if stride < 2:
        raise spec.SpecError(f"stride must be >= 2, got {stride}")
    if metric not in spec.METRICS:
        raise spec.SpecError(f"metric must be 'max' or 'sum', got {metric!r}")
    if not 0 <= thr <= 255 * (3 if metric == "sum" else 1) + 1:
        raise spec.SpecError(f"threshold {thr} out of range")
    c = CountingRenderer(renderer, width, height)
    t = tile if border == "traced" else None
    ax, ay = _single_axis(width, stride, t), _single_axis(height, stride, t)
    frame = np.zeros((height, width, 3), dtype=np.uint8)
    source = np.full((height, width), spec.SRC_UNSET, dtype=np.uint8)

    def trace_mask(mask):
        ys, xs = np.nonzero(mask)
        frame[ys, xs] = c.render(xs, ys)
        source[ys, xs] = SRC_TRACED

    # samples, and (Fig. 5b) every pixel in a tile's border region
    first = np.zeros((height, width), bool)
    first[np.ix_(ay.grid, ax.grid)] = True
    first[:, ax.border] = True
    first[ay.border, :] = True
    trace_mask(first)

    def decide(A, B, g):
        d = spec.color_diff(A, B, metric)
        return d * stride < thr * g

    # H pass: grid rows x decided columns
    if len(ax.m) and len(ay.grid):
        ys = ay.grid[:, None]
        A, B = frame[ys, ax.a[None, :]], frame[ys, ax.b[None, :]]
        g = (ax.b - ax.a)[None, :]
        ok = decide(A, B, g)
        val = spec.interpolate(A, B, ax.a[None, :], ax.b[None, :], ax.m[None, :])
        yy, xx = np.broadcast_to(ys, ok.shape), np.broadcast_to(ax.m[None, :], ok.shape)
        frame[yy[ok], xx[ok]] = val[ok]
        source[yy[ok], xx[ok]] = SRC_INTERP
        if (~ok).any():
            frame[yy[~ok], xx[~ok]] = c.render(xx[~ok], yy[~ok])
            source[yy[~ok], xx[~ok]] = SRC_TRACED
    # V pass: every non-border column x decided rows
    cols = np.setdiff1d(np.arange(width), ax.border)
    if len(ay.m) and len(cols):
        xs = cols[None, :]
        A, B = frame[ay.a[:, None], xs], frame[ay.b[:, None], xs]
        g = (ay.b - ay.a)[:, None]
        ok = decide(A, B, g)
        val = spec.interpolate(A, B, ay.a[:, None], ay.b[:, None], ay.m[:, None])
        yy, xx = np.broadcast_to(ay.m[:, None], ok.shape), np.broadcast_to(xs, ok.shape)
        frame[yy[ok], xx[ok]] = val[ok]
        source[yy[ok], xx[ok]] = SRC_INTERP
        if (~ok).any():
            frame[yy[~ok], xx[~ok]] = c.render(xx[~ok], yy[~ok])
            source[yy[~ok], xx[~ok]] = SRC_TRACED
    assert not (source == spec.SRC_UNSET).any(), "every pixel is final"
    name = "single_traced" if border == "traced" else "single_borrowed"
    settings = {"thr": thr, "stride": stride, "metric": metric}
    if border == "traced":
        settings["tile"] = tile
    return _result(c, frame, source, name, settings)


# --- the patent's multi-level method ------------------------------------------------------

def multi_level(renderer, width: int, height: int, params: Params, rule: str = "patent") -> MethodResult:
    """The patent's method (msr_model.select); another `rule` (msr_eval.rules) runs the same
    passes with a different decision test."""
    c = CountingRenderer(renderer, width, height)
    r = select(c, width, height, params, rule=rule_function(rule))
    if rule == "patent":
        return _result(c, r.frame, r.source, "multi", params.as_dict())
    return _result(c, r.frame, r.source, f"multi_{rule}", {**params.as_dict(), "rule": rule})
