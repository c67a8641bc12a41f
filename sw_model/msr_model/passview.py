"""One pass of one level, as a decision rule sees it (algorithm.md section 3).

A decision rule is a function `rule(view: PassView) -> bool array (F, M)`: True where the
new pixel is interpolated, False where it is traced. Every array of the view is shaped
(F, M) or broadcasts to it: F lines of the pass (rows of G_y(k-1) in the H pass, columns of
G_x(k) in the V pass, in increasing order) by M new positions on a line (level-k positions
of the other axis, in increasing order). Coordinates are frame coordinates.

The view lets a rule read only what the spec allows: pixels of the decision's own tile
that were final before the pass began (`read`), so any rule written against it keeps the
tiles independent and the decisions of one pass independent of their order.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import spec


@dataclass(frozen=True)
class PassView:
    level: int                 # k
    horizontal: bool           # True: H pass (lines are rows), False: V pass (lines are columns)
    metric: str                # "max" or "sum"
    nominal: int               # n_k = S >> (k-1)
    tile: int                  # T
    A: np.ndarray              # (F, M, 3) uint8: neighbour at a
    B: np.ndarray              # (F, M, 3) uint8: neighbour at b
    a: np.ndarray              # (1, M) position of A on the line
    b: np.ndarray              # (1, M) position of B on the line
    m: np.ndarray              # (1, M) the new position
    gap: np.ndarray            # (1, M) g = b - a
    line: np.ndarray           # (F, 1) coordinate of each line (y in the H pass, x in the V pass)
    line_tile: np.ndarray      # (F, 1) tile index of each line along its axis
    line_a: np.ndarray         # (F, 1) a line new at this level: the line before it it was split from, else -1
    line_b: np.ndarray         # (F, 1) ... and the line after it, else -1
    thr: np.ndarray            # (F, M) thr_k' of the tile of each decision
    ys: np.ndarray             # (F, M) target pixel of each decision: row
    xs: np.ndarray             # (F, M) ... and column
    frame: np.ndarray          # (H, W, 3) the frame before the pass (read through `read`)
    final: np.ndarray          # (H, W) bool: pixels final before the pass

    @property
    def shape(self) -> tuple[int, int]:
        return self.thr.shape

    def diff(self, c1=None, c2=None) -> np.ndarray:
        """Colour difference of the spec's metric; of A and B unless two colour arrays are given."""
        return spec.color_diff(self.A if c1 is None else c1, self.B if c2 is None else c2, self.metric)

    def below_threshold(self, d) -> np.ndarray:
        """The patent's test applied to a difference d: d * n_k < thr_k' * g (gap-weighted)."""
        return np.broadcast_to(spec.interpolate_ok(d, self.thr, self.gap, self.nominal), self.shape)

    def read(self, pos, line=None) -> tuple[np.ndarray, np.ndarray]:
        """Colours at line position `pos` on line `line` (default: each decision's own line),
        both broadcast to (F, M), and where they may be read: inside the frame, inside the
        tile of the decision, and final before the pass. Colours where not readable are 0."""
        pos = np.broadcast_to(np.asarray(pos), self.shape)
        line = np.broadcast_to(self.line if line is None else np.asarray(line), self.shape)
        h, w = self.final.shape
        n_pos, n_line = (w, h) if self.horizontal else (h, w)
        T = self.tile
        ok = ((pos >= 0) & (pos < n_pos) & (line >= 0) & (line < n_line)
              & (pos // T == self.m // T) & (line // T == self.line // T))
        p, q = np.where(ok, pos, 0), np.where(ok, line, 0)
        ys, xs = (q, p) if self.horizontal else (p, q)
        ok &= self.final[ys, xs]
        cols = np.where(ok[..., None], self.frame[ys, xs], 0).astype(np.uint8)
        return cols, ok
