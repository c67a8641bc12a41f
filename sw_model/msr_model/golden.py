"""Vectorised golden model: the whole frame, all tiles at once, one numpy step per pass.

Tiles are independent (claim 11) and every tile's positions are the product of an x plan
and a y plan, so each pass of the spec is one Cartesian product over the whole frame:
(rows final before the pass) x (new columns) for H, (final columns) x (new rows) for V.
The per-tile step form in tile_model.py gives the same pixels one decision at a time.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from . import spec
from .spec import Params


class Renderer:
    """A rendering unit: the colour of any pixel of the frame, deterministically."""

    width: int
    height: int

    def render(self, xs: np.ndarray, ys: np.ndarray) -> np.ndarray:
        """Colours (N, 3) uint8 of the pixels (xs[i], ys[i])."""
        raise NotImplementedError  # interface; see ImageRenderer and the Embree binding


@dataclass
class FrameAxis:
    """One axis of the whole frame, tile by tile, in global coordinates."""

    known: list[np.ndarray]          # known[k]: G(k) of every tile, concatenated
    known_tile: list[np.ndarray]     # tile index of each entry of known[k]
    new_m: list[np.ndarray]          # new_m[k-1]: level-k positions
    new_a: list[np.ndarray]
    new_b: list[np.ndarray]
    new_tile: list[np.ndarray]


def frame_axis(n_total: int, tile: int, levels: int) -> FrameAxis:
    n_tiles = (n_total + tile - 1) // tile
    plans = {}
    known = [[] for _ in range(levels + 1)]
    known_tile = [[] for _ in range(levels + 1)]
    new = [[[], [], [], []] for _ in range(levels)]
    for t in range(n_tiles):
        origin = t * tile
        n = min(tile, n_total - origin)
        plan = plans.get(n) or plans.setdefault(n, spec.axis_plan(n, levels))
        for k, grid in enumerate(plan.grids):
            known[k].extend(origin + g for g in grid)
            known_tile[k].extend([t] * len(grid))
        for k, splits in enumerate(plan.splits):
            for m, a, b in splits:
                new[k][0].append(origin + m)
                new[k][1].append(origin + a)
                new[k][2].append(origin + b)
                new[k][3].append(t)
    arr = lambda v: np.asarray(v, dtype=np.int32)  # noqa: E731
    return FrameAxis(
        known=[arr(v) for v in known], known_tile=[arr(v) for v in known_tile],
        new_m=[arr(v[0]) for v in new], new_a=[arr(v[1]) for v in new],
        new_b=[arr(v[2]) for v in new], new_tile=[arr(v[3]) for v in new])


@dataclass
class FrameResult:
    frame: np.ndarray                  # (H, W, 3) uint8
    source: np.ndarray                 # (H, W) uint8 source codes
    params: Params
    stats: dict = field(default_factory=dict)


def threshold_maps(params: Params, ntx: int, nty: int) -> list[np.ndarray]:
    """thr_k' for every tile: list over k of (nty, ntx) int32 arrays."""
    ty, tx = np.mgrid[0:nty, 0:ntx]
    return [np.asarray(spec.foveated_threshold(t, tx, ty, ntx, nty, params.fov_gain), dtype=np.int32)
            for t in params.thr]


def select(renderer, width: int, height: int, params: Params, progress=None) -> FrameResult:
    """Run the multi-level selective render of a whole frame; ask `renderer` only for traced pixels."""
    spec.check_frame_size(width, height)
    T, L = params.tile, params.levels
    ntx, nty = spec.tile_counts(width, height, T)
    ax, ay = frame_axis(width, T, L), frame_axis(height, T, L)
    thr_maps = threshold_maps(params, ntx, nty)

    frame = np.zeros((height, width, 3), dtype=np.uint8)
    source = np.full((height, width), spec.SRC_UNSET, dtype=np.uint8)
    per_level = {"initial": 0}

    def trace(xs, ys):
        cols = np.asarray(renderer.render(xs.astype(np.int32), ys.astype(np.int32)), dtype=np.uint8)
        if cols.shape != (len(xs), 3):
            raise RuntimeError(f"renderer returned shape {cols.shape} for {len(xs)} pixels")
        return cols

    # Initial sampling: G0(w) x G0(h) of every tile, all traced.
    yy, xx = np.meshgrid(ay.known[0], ax.known[0], indexing="ij")
    frame[yy, xx] = trace(xx.ravel(), yy.ravel()).reshape(yy.shape + (3,))
    source[yy, xx] = spec.SRC_INITIAL
    per_level["initial"] = yy.size
    if progress:
        progress(0)

    for k in range(1, L + 1):
        nominal = params.nominal_gap(k)
        thr = thr_maps[k - 1]
        # H pass: rows of G_y(k-1), new columns of level k.
        _pass(frame, source, trace, params, k, nominal,
              fixed=ay.known[k - 1], fixed_tile=ay.known_tile[k - 1],
              m=ax.new_m[k - 1], a=ax.new_a[k - 1], b=ax.new_b[k - 1], m_tile=ax.new_tile[k - 1],
              thr=thr, horizontal=True, counts=per_level)
        # V pass: columns of G_x(k), new rows of level k.
        _pass(frame, source, trace, params, k, nominal,
              fixed=ax.known[k], fixed_tile=ax.known_tile[k],
              m=ay.new_m[k - 1], a=ay.new_a[k - 1], b=ay.new_b[k - 1], m_tile=ay.new_tile[k - 1],
              thr=thr, horizontal=False, counts=per_level)
        if progress:
            progress(k)

    assert not (source == spec.SRC_UNSET).any(), "every pixel is final after level L"
    traced = int((source < spec.SRC_INTERP_BASE).sum())
    total = width * height
    stats = {
        "width": width, "height": height, "pixels": total,
        "traced": traced, "interpolated": total - traced,
        "traced_fraction": traced / total,
        "traced_initial": per_level["initial"],
        **{f"traced_level{k}": per_level.get(f"t{k}", 0) for k in range(1, L + 1)},
        **{f"interpolated_level{k}": per_level.get(f"i{k}", 0) for k in range(1, L + 1)},
        "params": params.as_dict(),
    }
    return FrameResult(frame, source, params, stats)


def _pass(frame, source, trace, params, k, nominal, *, fixed, fixed_tile, m, a, b, m_tile,
          thr, horizontal, counts):
    """One H or V pass: every (fixed line) x (new position) decision at once."""
    if len(m) == 0 or len(fixed) == 0:
        return
    if horizontal:   # index arrays shaped (rows, cols)
        ys, xm = np.meshgrid(fixed, m, indexing="ij")
        xa, xb = np.meshgrid(fixed, a, indexing="ij")[1], np.meshgrid(fixed, b, indexing="ij")[1]
        A, B = frame[ys, xa], frame[ys, xb]
        thr_pos = thr[fixed_tile[:, None], m_tile[None, :]]
        pos_a, pos_b, pos_m = xa, xb, xm
        tgt = (ys, xm)                                   # (y, x) of each decision
    else:            # shaped (new rows, cols)
        ym, xs = np.meshgrid(m, fixed, indexing="ij")
        ya, yb = np.meshgrid(a, fixed, indexing="ij")[0], np.meshgrid(b, fixed, indexing="ij")[0]
        A, B = frame[ya, xs], frame[yb, xs]
        thr_pos = thr[m_tile[:, None], fixed_tile[None, :]]
        pos_a, pos_b, pos_m = ya, yb, ym
        tgt = (ym, xs)

    gap = pos_b - pos_a
    d = spec.color_diff(A, B, params.metric)
    interp = spec.interpolate_ok(d, thr_pos, gap, nominal)
    values = spec.interpolate(A, B, pos_a, pos_b, pos_m)

    ty, tx = tgt
    n_traced = int((~interp).sum())
    if n_traced:
        values[~interp] = trace(tx[~interp], ty[~interp])
    frame[ty, tx] = values
    source[ty, tx] = np.where(interp, spec.source_code_interp(k), spec.source_code_traced(k))
    counts[f"t{k}"] = counts.get(f"t{k}", 0) + n_traced
    counts[f"i{k}"] = counts.get(f"i{k}", 0) + int(interp.sum())
