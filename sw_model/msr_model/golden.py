"""Vectorised golden model: the whole frame, all tiles at once, one numpy step per pass.

Tiles are independent (claim 11) and every tile's positions are the product of an x plan
and a y plan, so each pass of the spec is one Cartesian product over the whole frame:
(rows final before the pass) x (new columns) for H, (final columns) x (new rows) for V.
The decision itself is a rule (rules.py) applied to the pass's PassView, the patent's by
default. The per-tile step form in tile_model.py gives the same pixels one decision at a time.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from . import spec
from .passview import PassView
from .renderer import render_checked
from .rules import DEFAULT_RULE, get_rule
from .spec import Params


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
    plans = {}
    known = [[] for _ in range(levels + 1)]
    known_tile = [[] for _ in range(levels + 1)]
    new = [[[], [], [], []] for _ in range(levels)]
    for t, (origin, n) in enumerate(spec.axis_spans(n_total, tile)):
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
    cx, cy = spec.gaze_centre(params, ntx, nty)
    return [np.asarray(spec.foveated_threshold(t, tx, ty, cx, cy, params.fov_gain), dtype=np.int32)
            for t in params.thr]


def select(renderer, width: int, height: int, params: Params, rule=DEFAULT_RULE,
           progress=None) -> FrameResult:
    """Run the multi-level selective render of a whole frame; ask `renderer` only for traced
    pixels. `rule`: a contract rule name (rules.RULES) or a function of a PassView."""
    spec.check_frame_size(width, height)
    spec.check_gaze(params.gaze, width, height)
    rule_name, decide = get_rule(rule)
    ntx, nty = spec.tile_counts(width, height, params.tile)
    frame, source, per_level = select_region(renderer, width, height, params, decide,
                                             threshold_maps(params, ntx, nty), progress)
    return FrameResult(frame, source, params, frame_stats(source, params, per_level, rule_name))


def select_region(renderer, width: int, height: int, params: Params, decide, thr_maps,
                  progress=None) -> tuple[np.ndarray, np.ndarray, dict]:
    """Every pass over a width x height region cut into tiles from its top-left, with the
    per-tile thresholds `thr_maps` (list over k of (tile rows, tile columns) arrays): the
    region's frame, source codes and traced / interpolated counts per level. select() runs
    it on the whole frame; the ray-budget mode (budget.py) on one tile row at a time."""
    T, L = params.tile, params.levels
    ax, ay = frame_axis(width, T, L), frame_axis(height, T, L)

    frame = np.zeros((height, width, 3), dtype=np.uint8)
    source = np.full((height, width), spec.SRC_UNSET, dtype=np.uint8)
    per_level = {"initial": 0}

    # Initial sampling: G0(w) x G0(h) of every tile, all traced.
    yy, xx = np.meshgrid(ay.known[0], ax.known[0], indexing="ij")
    frame[yy, xx] = render_checked(renderer, xx, yy).reshape(yy.shape + (3,))
    source[yy, xx] = spec.SRC_INITIAL
    per_level["initial"] = yy.size
    if progress:
        progress(0)

    for k in range(1, L + 1):
        for _, view, interp, values in decided_passes(frame, source, params, k, ax, ay, thr_maps[k - 1], decide):
            ty, tx = view.ys, view.xs
            n_traced = int((~interp).sum())
            if n_traced:
                values[~interp] = render_checked(renderer, tx[~interp], ty[~interp])
            frame[ty, tx] = values
            source[ty, tx] = np.where(interp, spec.source_code_interp(k), spec.source_code_traced(k))
            per_level[f"t{k}"] = per_level.get(f"t{k}", 0) + n_traced
            per_level[f"i{k}"] = per_level.get(f"i{k}", 0) + int(interp.sum())
        if progress:
            progress(k)

    assert not (source == spec.SRC_UNSET).any(), "every pixel is final after level L"
    return frame, source, per_level


def frame_stats(source: np.ndarray, params: Params, per_level: dict, rule_name: str) -> dict:
    """STATS.json's counts of a finished frame (contracts.md)."""
    height, width = source.shape
    L = params.levels
    traced = int((source < spec.SRC_INTERP_BASE).sum())
    total = width * height
    return {
        "width": width, "height": height, "pixels": total,
        "traced": traced, "interpolated": total - traced,
        "traced_fraction": traced / total,
        "traced_initial": per_level["initial"],
        **{f"traced_level{k}": per_level.get(f"t{k}", 0) for k in range(1, L + 1)},
        **{f"interpolated_level{k}": per_level.get(f"i{k}", 0) for k in range(1, L + 1)},
        "rule": rule_name,
        "gaze": list(params.gaze or spec.default_gaze(width, height, params.tile)),
        "params": params.as_dict(),
    }


def decided_passes(frame, source, params: Params, k: int, ax, ay, thr_map, decide):
    """Level k's two passes, horizontal then vertical, over the frame as it stands: per pass
    with positions, (horizontal, view, interp, values): the rule's decisions and every
    position's colour were it interpolated. A generator: the caller writes a pass's pixels
    before the next pass is read."""
    for horizontal in (True, False):
        view = pass_view(frame, source, params, k, horizontal, ax, ay, thr_map)
        if view is not None:
            yield horizontal, view, decide_pass(decide, view), interpolated_values(decide, view)


def interpolated_values(decide, view: PassView) -> np.ndarray:
    """The colour of every decision of the pass were it interpolated: the spec's weighted mean
    of A and B (algorithm.md), or the rule's own reconstruction where the rule has one (a
    function attribute `interpolate(view, linear) -> (F, M, 3) uint8`, given the spec's
    values to start from), checked."""
    values = spec.interpolate(view.A, view.B, view.a, view.b, view.m)
    own = getattr(decide, "interpolate", None)
    if own is None:
        return values
    out = np.asarray(own(view, values.copy()))
    if out.shape != values.shape or out.dtype != np.uint8:
        raise RuntimeError(f"rule's interpolate returned {out.dtype} {out.shape}, want uint8 {values.shape}")
    return out


def decide_pass(decide, view: PassView) -> np.ndarray:
    """The rule's answer for every decision of the pass, checked: a bool array (F, M)."""
    ok = np.asarray(decide(view))
    if ok.shape != view.shape or ok.dtype != bool:
        raise RuntimeError(f"rule returned {ok.dtype} {ok.shape} for a pass of shape {view.shape}")
    return ok


def pass_view(frame, source, params: Params, k: int, horizontal: bool, ax: FrameAxis, ay: FrameAxis,
              thr: np.ndarray) -> PassView | None:
    """The H (horizontal) or V pass of level k over the whole frame, as a PassView; None when
    the pass has no decision. `thr` is the (nty, ntx) map of thr_k'."""
    if horizontal:   # lines: rows of G_y(k-1); new positions: level-k columns
        line, line_tile = ay.known[k - 1], ay.known_tile[k - 1]
        m, a, b, m_tile = ax.new_m[k - 1], ax.new_a[k - 1], ax.new_b[k - 1], ax.new_tile[k - 1]
        line_a = line_b = np.full(len(line), -1, np.int32)
    else:            # lines: columns of G_x(k); new positions: level-k rows
        line, line_tile = ax.known[k], ax.known_tile[k]
        m, a, b, m_tile = ay.new_m[k - 1], ay.new_a[k - 1], ay.new_b[k - 1], ay.new_tile[k - 1]
        lut_a = np.full(frame.shape[1], -1, np.int32)
        lut_b = np.full(frame.shape[1], -1, np.int32)
        lut_a[ax.new_m[k - 1]] = ax.new_a[k - 1]
        lut_b[ax.new_m[k - 1]] = ax.new_b[k - 1]
        line_a, line_b = lut_a[line], lut_b[line]
    if len(m) == 0 or len(line) == 0:
        return None
    F, M = line[:, None], m[None, :]
    shape = (len(line), len(m))
    Aa, Bb = a[None, :], b[None, :]
    if horizontal:
        ys, xs = np.broadcast_to(F, shape), np.broadcast_to(M, shape)
        A, B = frame[F, Aa], frame[F, Bb]
        thr_pos = thr[line_tile[:, None], m_tile[None, :]]
    else:
        ys, xs = np.broadcast_to(M, shape), np.broadcast_to(F, shape)
        A, B = frame[Aa, F], frame[Bb, F]
        thr_pos = thr[m_tile[None, :], line_tile[:, None]]
    return PassView(level=k, horizontal=horizontal, metric=params.metric, nominal=params.nominal_gap(k),
                    tile=params.tile, A=A, B=B, a=Aa, b=Bb, m=M, gap=Bb - Aa, line=F,
                    line_tile=line_tile[:, None], line_a=line_a[:, None], line_b=line_b[:, None],
                    thr=thr_pos, ys=ys, xs=xs, frame=frame, final=source != spec.SRC_UNSET)
