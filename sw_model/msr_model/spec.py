"""The spec's arithmetic, one function per rule of docs/spec/algorithm.md.

Everything here works on Python ints and on numpy integer arrays alike, so the vectorised
frame model (golden.py), the per-tile step model (tile_model.py) and the cocotb tests all
share one definition of each rule.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

MAX_FRAME = 4096
TILE_SIZES = (8, 16, 32)
LEVEL_RANGE = (1, 2, 3)
# An evaluation-only extension (docs/rules.md "L = 4"): a fourth level, initial grid
# stride 16. algorithm.md and the RTL stop at 3; a Params with extension=True may use 4.
EXT_LEVEL_RANGE = (1, 2, 3, 4)
METRICS = ("max", "sum")
# Default per-level thresholds when none are given: thr_k = 8 * 2^(k-1), cut to L levels.
DEFAULT_THR = (8, 16, 32)


def default_thresholds(levels: int) -> tuple[int, ...]:
    """The thresholds every tool uses when the user gives none: DEFAULT_THR cut to `levels`."""
    return DEFAULT_THR[:levels]

# Source codes (spec section 4).
SRC_INITIAL = 0
SRC_TRACED_BASE = 0        # traced at level k -> k
SRC_INTERP_BASE = 16       # interpolated at level k -> 16 + k
SRC_REUSED_BASE = 32       # reused from the previous frame at level k -> 32 + k (spec/reuse.md)
SRC_UNSET = 255            # never written (only visible if the model had a bug)


class SpecError(ValueError):
    """A parameter outside the spec's legal range."""


@dataclass(frozen=True)
class Params:
    """Run-time parameters of one frame (the register file of the accelerator)."""

    tile: int = 16
    levels: int = 2
    thr: tuple[int, ...] = (8, 16)
    metric: str = "max"
    fov_gain: int = 0
    extension: bool = False      # evaluation only: allows L = 4 (EXT_LEVEL_RANGE); no register has it
    gaze: tuple[int, int] | None = None   # (X, Y) in pixels; None: the default, the frame centre

    def __post_init__(self) -> None:
        if self.tile not in TILE_SIZES:
            raise SpecError(f"tile must be one of {TILE_SIZES}, got {self.tile}")
        if self.levels not in (EXT_LEVEL_RANGE if self.extension else LEVEL_RANGE):
            allowed = "1 to 4 (the L = 4 extension)" if self.extension else "1, 2 or 3"
            raise SpecError(f"levels must be {allowed}, got {self.levels}")
        thr = tuple(int(t) for t in self.thr)
        if len(thr) != self.levels:
            raise SpecError(f"need exactly {self.levels} thresholds (one per level), got {len(thr)}")
        for t in thr:
            if not 0 <= t <= 255:
                raise SpecError(f"threshold {t} outside 0..255")
        object.__setattr__(self, "thr", thr)
        if self.metric not in METRICS:
            raise SpecError(f"metric must be 'max' or 'sum', got {self.metric!r}")
        if not 0 <= int(self.fov_gain) <= 255:
            raise SpecError(f"fov_gain {self.fov_gain} outside 0..255")
        if self.gaze is not None:
            gaze = tuple(int(v) for v in self.gaze)
            if len(gaze) != 2 or min(gaze) < 0:
                raise SpecError(f"gaze must be two pixel coordinates X,Y >= 0, got {self.gaze!r}")
            object.__setattr__(self, "gaze", gaze)

    @property
    def stride(self) -> int:
        return 1 << self.levels

    def nominal_gap(self, k: int) -> int:
        """n_k = S >> (k-1): the gap of a normal (non-border) pair at level k."""
        return self.stride >> (k - 1)

    def as_dict(self) -> dict:
        out = {"tile": self.tile, "levels": self.levels, "thr": list(self.thr),
               "metric": self.metric, "fov_gain": self.fov_gain}
        if self.gaze is not None:
            out["gaze"] = list(self.gaze)
        return {**out, "extension": True} if self.extension else out


def check_frame_size(width: int, height: int) -> None:
    for name, v in (("width", width), ("height", height)):
        if not 1 <= int(v) <= MAX_FRAME:
            raise SpecError(f"frame {name} {v} outside 1..{MAX_FRAME}")


# --- Terms: the tiles of a frame -------------------------------------------------------------

def tile_counts(width: int, height: int, tile: int) -> tuple[int, int]:
    return (width + tile - 1) // tile, (height + tile - 1) // tile


def axis_spans(n: int, tile: int) -> list[tuple[int, int]]:
    """(origin, extent) of every tile along one axis of n pixels; the last may be shorter."""
    return [(o, min(tile, n - o)) for o in range(0, n, tile)]


class Tile(NamedTuple):
    """One tile of the frame: indices (tx, ty), top-left pixel (x0, y0), size w x h."""

    tx: int
    ty: int
    x0: int
    y0: int
    w: int
    h: int


def frame_tiles(width: int, height: int, tile: int) -> list[Tile]:
    """Every tile of the frame, row-major from the top-left (the one tile enumeration)."""
    xs, ys = axis_spans(width, tile), axis_spans(height, tile)
    return [Tile(tx, ty, x0, y0, w, h) for ty, (y0, h) in enumerate(ys) for tx, (x0, w) in enumerate(xs)]


# --- Section 1: per-tile thresholds -------------------------------------------------------


def default_gaze(width: int, height: int, tile: int) -> tuple[int, int]:
    """The gaze when none is given: (ntx*T / 2, nty*T / 2), the centre of the tile grid."""
    ntx, nty = tile_counts(width, height, tile)
    return ntx * tile // 2, nty * tile // 2


def check_gaze(gaze, width: int, height: int) -> None:
    """A given gaze must be a pixel of the frame: 0 <= X < W, 0 <= Y < H."""
    if gaze is None:
        return
    x, y = gaze
    if not (0 <= x < width and 0 <= y < height):
        raise SpecError(f"gaze {x},{y} outside the {width}x{height} frame (0 <= X < {width}, 0 <= Y < {height})")


def gaze_centre(params: Params, ntx: int, nty: int) -> tuple[int, int]:
    """(cx, cy), the gaze in half tiles: ((2X + T div 2) div T, (2Y + T div 2) div T). The
    default gaze (ntx*T / 2, nty*T / 2) gives (ntx, nty) for either parity of the counts."""
    if params.gaze is None:
        return ntx, nty
    T = params.tile
    return (2 * params.gaze[0] + T // 2) // T, (2 * params.gaze[1] + T // 2) // T


def foveated_threshold(thr_k, tx, ty, cx: int, cy: int, fov_gain: int):
    """thr_k' = min(255, thr_k + ((fov_gain * r2) >> 4)), r2 = max(|2tx + 1 - cx|, |2ty + 1 - cy|)
    in half tiles from the gaze (cx, cy) (gaze_centre; cx = ntx, cy = nty is the frame centre)."""
    r2 = np.maximum(np.abs(2 * np.asarray(tx) + 1 - int(cx)), np.abs(2 * np.asarray(ty) + 1 - int(cy)))
    out = np.minimum(255, np.asarray(thr_k) + ((int(fov_gain) * r2) >> 4))
    return int(out) if np.ndim(out) == 0 else out


def tile_thresholds(params: Params, tx: int, ty: int, ntx: int, nty: int) -> tuple[int, ...]:
    """The per-level thresholds of tile (tx, ty): what the tile generation unit hands out."""
    cx, cy = gaze_centre(params, ntx, nty)
    return tuple(foveated_threshold(t, tx, ty, cx, cy, params.fov_gain) for t in params.thr)


# --- Sections 2 and 3: the sample positions along one axis --------------------------------

def initial_grid(n: int, stride: int) -> list[int]:
    """G0: 0, S, 2S, ... below n, plus n-1 (the far corner) if not already in."""
    g = list(range(0, n, stride))
    if g[-1] != n - 1:
        g.append(n - 1)
    return g


def level_splits(grid: list[int]) -> list[tuple[int, int, int]]:
    """New positions of the next level: (m, a, b) for every neighbour pair with b - a >= 2."""
    return [(a + (b - a) // 2, a, b) for a, b in zip(grid, grid[1:]) if b - a >= 2]


@dataclass(frozen=True)
class AxisPlan:
    """Positions of one axis of one tile: G(k) for k = 0..L and the splits of each level."""

    grids: tuple[tuple[int, ...], ...]                        # grids[k] = G(k), sorted
    splits: tuple[tuple[tuple[int, int, int], ...], ...]      # splits[k-1] = level-k (m, a, b)


def axis_plan(n: int, levels: int) -> AxisPlan:
    grid = initial_grid(n, 1 << levels)
    grids, splits = [tuple(grid)], []
    for _ in range(levels):
        new = level_splits(grid)
        splits.append(tuple(new))
        grid = sorted(grid + [m for m, _, _ in new])
        grids.append(tuple(grid))
    assert grid == list(range(n)), "after level L every position is in"
    return AxisPlan(tuple(grids), tuple(splits))


# --- Section 3: the decision and the interpolation ---------------------------------------

def color_diff(a, b, metric: str):
    """Colour difference of two RGB values (last axis = channel), metric 'max' or 'sum'."""
    diff = np.abs(np.asarray(a, dtype=np.int32) - np.asarray(b, dtype=np.int32))
    d = diff.max(axis=-1) if metric == "max" else diff.sum(axis=-1)
    return int(d) if np.ndim(d) == 0 else d


def interpolate_ok(d, thr, gap, nominal: int):
    """Interpolate iff d * n_k < thr * g (strict; the border region is weighted by its gap)."""
    ok = np.asarray(d) * nominal < np.asarray(thr) * np.asarray(gap)
    return bool(ok) if np.ndim(ok) == 0 else ok


def interpolate(a_col, b_col, a, b, m):
    """C = ((b-m)*A + (m-a)*B + floor(g/2)) // g per channel, rounded half up."""
    a_col = np.asarray(a_col, dtype=np.int32)
    b_col = np.asarray(b_col, dtype=np.int32)
    a, b, m = (np.asarray(v, dtype=np.int32) for v in (a, b, m))
    g = b - a
    if a_col.ndim > g.ndim:  # broadcast the positions over the channel axis
        g, a, b, m = (v[..., None] for v in (g, a, b, m))
    out = ((b - m) * a_col + (m - a) * b_col + g // 2) // g
    return out.astype(np.uint8)


def source_code_traced(level: int) -> int:
    return SRC_TRACED_BASE + level


def source_code_interp(level: int) -> int:
    return SRC_INTERP_BASE + level
