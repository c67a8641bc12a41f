"""Per-tile, step-by-step golden model: one decision at a time, in the hardware's order.

The level processing controller in rtl/ walks exactly `tile_schedule`; the cocotb tests
compare its position stream, its render requests and its tile-buffer writes with this.

Order inside each pass (binding for the RTL, documented in docs/architecture.md):
- initial: the tile's corners first (0,0), (w-1,0), (0,h-1), (w-1,h-1) (duplicates of a
  1-wide or 1-high tile dropped), then the rest of G0(w) x G0(h) row-major;
- H pass of level k: rows y of G_y(k-1) top to bottom, and inside a row the new x from
  left to right, so the right neighbour of one decision is the left of the next;
- V pass of level k: columns x of G_x(k) left to right, and inside a column the new y
  from top to bottom (the same neighbour reuse, down the column).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable, Iterable, Sequence

import numpy as np

from . import spec
from .golden import decide_pass, frame_axis, interpolated_values, pass_view
from .renderer import render_checked
from .reuse import lerp_invz, pass_neighbours
from .rules import DEFAULT_RULE, get_rule
from .spec import Params


@dataclass(frozen=True)
class Step:
    """One position of one pass, tile-local coordinates."""

    level: int                 # 0 = initial sample, else 1..L
    direction: str             # "init", "H" or "V"
    x: int
    y: int
    ax: int = -1               # neighbour A (left/top); -1 for initial samples
    ay: int = -1
    bx: int = -1               # neighbour B (right/bottom)
    by: int = -1
    gap: int = 0               # b - a
    nominal: int = 0           # n_k

    @property
    def m_offset(self) -> int:
        """m - a: where the new position sits inside its gap."""
        return (self.x - self.ax) if self.direction == "H" else (self.y - self.ay)


@dataclass(frozen=True)
class Pass:
    level: int
    direction: str
    steps: tuple[Step, ...]


def initial_order(w: int, h: int, levels: int) -> list[tuple[int, int]]:
    gx = spec.initial_grid(w, 1 << levels)
    gy = spec.initial_grid(h, 1 << levels)
    corners = []
    for p in ((0, 0), (w - 1, 0), (0, h - 1), (w - 1, h - 1)):
        if p not in corners:
            corners.append(p)
    rest = [(x, y) for y in gy for x in gx if (x, y) not in corners]
    return corners + rest


def tile_schedule(w: int, h: int, levels: int) -> list[Pass]:
    """Every pass of a w x h tile in order: initial, then H and V of each level."""
    px, py = spec.axis_plan(w, levels), spec.axis_plan(h, levels)
    stride = 1 << levels
    passes = [Pass(0, "init", tuple(Step(0, "init", x, y) for x, y in initial_order(w, h, levels)))]
    for k in range(1, levels + 1):
        nominal = stride >> (k - 1)
        h_steps = tuple(Step(k, "H", m, y, a, y, b, y, b - a, nominal)
                        for y in py.grids[k - 1] for m, a, b in px.splits[k - 1])
        v_steps = tuple(Step(k, "V", x, m, x, a, x, b, b - a, nominal)
                        for x in px.grids[k] for m, a, b in py.splits[k - 1])
        passes += [Pass(k, "H", h_steps), Pass(k, "V", v_steps)]
    return passes


@dataclass
class Decision:
    step: Step
    diff: int                  # colour difference d
    interpolate: bool
    value: tuple[int, int, int]


@dataclass
class TileResult:
    x0: int
    y0: int
    pixels: np.ndarray                      # (h, w, 3) uint8
    codes: np.ndarray                       # (h, w) uint8
    requests: list[tuple[int, int]] = field(default_factory=list)      # global (x, y), in order
    decisions: list[Decision] = field(default_factory=list)
    writes: list[tuple[int, int, tuple[int, int, int], int]] = field(default_factory=list)
    invz: np.ndarray | None = None          # (h, w) uint16 inverse depth (run_tile's render_invz), else None

    def output_stream(self) -> list[tuple[int, int, tuple[int, int, int], int]]:
        """The finished tile as the engine emits it: row-major global (x, y, rgb, code)."""
        h, w = self.codes.shape
        return [(self.x0 + x, self.y0 + y, tuple(int(c) for c in self.pixels[y, x]), int(self.codes[y, x]))
                for y in range(h) for x in range(w)]


RenderFn = Callable[[int, int], Sequence[int]]
InvzFn = Callable[[int, int], int]


def run_tile(render: RenderFn, x0: int, y0: int, w: int, h: int, params: Params,
             thr_tile: Sequence[int], rule=DEFAULT_RULE, *, render_invz: InvzFn | None = None) -> TileResult:
    """Process one tile one step at a time. `render(x, y)` takes global coordinates.

    The tile is its own w x h frame here: the rule (a contract name or a function of a
    PassView) sees nothing of any other tile, so this form also checks tile independence.

    render_invz(x, y) (global coordinates, 0..65535), when given, is the traced pixel's
    inverse depth: the result's `invz` plane holds it for traced pixels and, for
    interpolated ones, reuse.lerp_invz of the two neighbours the colour was interpolated
    from, read from the plane as it was when the pass began (the depth channel of the
    engine's DEPTH_EN build). Without it `invz` is None."""
    if len(thr_tile) != params.levels:
        raise spec.SpecError("one threshold per level")
    if not (1 <= w <= params.tile and 1 <= h <= params.tile):
        raise spec.SpecError(f"tile {w}x{h} larger than T = {params.tile}")
    _, decide = get_rule(rule)
    pix = np.zeros((h, w, 3), dtype=np.uint8)
    codes = np.full((h, w), spec.SRC_UNSET, dtype=np.uint8)
    res = TileResult(x0, y0, pix, codes)
    if render_invz is not None:
        res.invz = np.zeros((h, w), dtype=np.uint16)
    ax, ay = frame_axis(w, params.tile, params.levels), frame_axis(h, params.tile, params.levels)

    def trace(x, y, code):
        res.requests.append((x0 + x, y0 + y))
        rgb = tuple(int(c) for c in render(x0 + x, y0 + y))
        pix[y, x] = rgb
        codes[y, x] = code
        res.writes.append((x, y, rgb, code))
        if res.invz is not None:
            res.invz[y, x] = int(render_invz(x0 + x, y0 + y))

    for p in tile_schedule(w, h, params.levels):
        if p.level == 0:
            for s in p.steps:
                trace(s.x, s.y, spec.SRC_INITIAL)
            continue
        # A pass reads only pixels final before it began: decide everything, then write.
        thr = np.full((1, 1), thr_tile[p.level - 1], dtype=np.int32)
        view = pass_view(pix, codes, params, p.level, p.direction == "H", ax, ay, thr)
        if view is None:   # a 1-wide or 1-high tile: this pass has no decision
            assert not p.steps
            continue
        ok = decide_pass(decide, view)
        diff = view.diff()
        values = interpolated_values(decide, view)
        if res.invz is not None:   # every position's lerp, taken where the pass interpolates
            wm = lerp_invz(*pass_neighbours(res.invz, view, p.direction == "H"), view.a, view.b, view.m)
        at = {(int(y), int(x)): (i, j) for (i, j), y, x in zip(np.ndindex(*view.shape), view.ys.ravel(),
                                                               view.xs.ravel())}
        for s in p.steps:
            i, j = at[(s.y, s.x)]
            if ok[i, j]:
                val = tuple(int(c) for c in values[i, j])
                pix[s.y, s.x] = val
                codes[s.y, s.x] = spec.source_code_interp(p.level)
                if res.invz is not None:
                    res.invz[s.y, s.x] = wm[i, j]
                res.writes.append((s.x, s.y, val, int(codes[s.y, s.x])))
            else:
                trace(s.x, s.y, spec.source_code_traced(p.level))
                val = tuple(int(c) for c in pix[s.y, s.x])
            res.decisions.append(Decision(s, int(diff[i, j]), bool(ok[i, j]), val))
    assert not (codes == spec.SRC_UNSET).any()
    return res


def frame_tiles(width: int, height: int, tile: int) -> list[spec.Tile]:
    """(tx, ty, x0, y0, w, h) of every tile, row-major from the top-left (spec.frame_tiles)."""
    return spec.frame_tiles(width, height, tile)


def select_tiled(renderer, width: int, height: int, params: Params,
                 order: Iterable[int] | None = None, rule=DEFAULT_RULE):
    """The whole frame through run_tile, tiles in any `order` (indices into frame_tiles)."""
    spec.check_frame_size(width, height)
    spec.check_gaze(params.gaze, width, height)
    tiles = spec.frame_tiles(width, height, params.tile)
    ntx, nty = spec.tile_counts(width, height, params.tile)
    frame = np.zeros((height, width, 3), dtype=np.uint8)
    source = np.full((height, width), spec.SRC_UNSET, dtype=np.uint8)

    def render(x, y):
        return render_checked(renderer, [x], [y])[0]

    for i in (range(len(tiles)) if order is None else order):
        tx, ty, x0, y0, w, h = tiles[i]
        r = run_tile(render, x0, y0, w, h, params, spec.tile_thresholds(params, tx, ty, ntx, nty), rule=rule)
        frame[y0:y0 + h, x0:x0 + w] = r.pixels
        source[y0:y0 + h, x0:x0 + w] = r.codes
    return frame, source
