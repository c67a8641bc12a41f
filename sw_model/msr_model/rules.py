"""The contract's decision rules: `select --rule NAME`, golden.select(rule=...), run_tile(rule=...).

A rule is a function of one PassView (passview.py) returning True where a new pixel is
interpolated. Two rules are part of the contract:

- "patent": algorithm.md section 3, d * n_k < thr_k' * g (the default; the RTL implements it).
- "lindilate": docs/rules.md. The patent's test, or else the four samples A', A, B, B' of
  the line lie on a straight line within the threshold (second differences); then a gap is
  traced anyway when the same gap fails that test on the previous or the next line of the
  pass inside the same tile.

- "lindilate2d" (evaluation only, not in the RTL): lindilate's decisions; at the last level's V
  pass an interpolated pixel is the mean of six final neighbours (its two and the four
  diagonal corners) where they agree within the threshold (`diagonal_smooth`). A rule may
  carry such a reconstruction as its `interpolate` attribute (golden.interpolated_values).

All read only pixels of the decision's own tile that are final before the pass. The
building blocks (`second_difference_ok`, `dilate`) are public so research rules can be
composed from them without copying.
"""
from __future__ import annotations

from typing import Callable, Union

import numpy as np

from . import spec
from .passview import PassView

Rule = Callable[[PassView], np.ndarray]


def patent(v: PassView) -> np.ndarray:
    """Interpolate iff d(A, B) * n_k < thr_k' * g."""
    return v.below_threshold(v.diff())


def second_difference_test(outer_a, ok_a, A, B, outer_b, ok_b, thr, gap, nominal: int, metric: str):
    """Q of docs/rules.md on sample values (what the RTL's msr_base_decision computes): with
    e_A' = d(A' - 2A + B) and e_B' = d(A - 2B + B') (per channel, then the metric), c2 = the
    larger over the outer samples that exist, Q = (one exists) and c2 * n_k < thr * g.
    Colours: (..., 3) arrays; ok_a / ok_b: where A' / B' exist; broadcast together."""
    A, B = np.asarray(A, np.int32), np.asarray(B, np.int32)
    ok_a, ok_b = np.asarray(ok_a, bool), np.asarray(ok_b, bool)
    c2 = np.zeros(np.broadcast_shapes(ok_a.shape, ok_b.shape, A.shape[:-1]), np.int32)
    for outer, near, far, ok in ((outer_a, A, B, ok_a), (outer_b, B, A, ok_b)):
        c = spec.color_diff(np.asarray(outer, np.int32) - 2 * near + far, 0, metric)
        c2 = np.where(ok, np.maximum(c2, c), c2)
    return (ok_a | ok_b) & np.asarray(spec.interpolate_ok(c2, thr, gap, nominal))


def second_difference_ok(v: PassView) -> np.ndarray:
    """A', A, B, B' on a straight line within the threshold: with A' at a - g and B' at b + g,
    c2 = max over the outer samples that exist of d(A' - 2A + B) resp. d(A - 2B + B') (per
    channel, then the spec's metric), and c2 * n_k < thr_k' * g. False where neither outer
    sample can be read (outside the tile, or not final before the pass)."""
    g = v.gap
    (outer_a, ok_a), (outer_b, ok_b) = v.read(v.a - g), v.read(v.b + g)
    return np.broadcast_to(second_difference_test(outer_a, ok_a, v.A, v.B, outer_b, ok_b,
                                                  v.thr, g, v.nominal, v.metric), v.shape)


def dilate(v: PassView, ok: np.ndarray) -> np.ndarray:
    """Trace a gap also when the same gap fails on the previous or the next line of the pass
    that lies in the same tile (lines in the order of the pass: rows of G_y(k-1), columns
    of G_x(k)). Uses the failures of `ok` as they were before this step."""
    ok = np.array(ok, dtype=bool)
    bad = ~ok
    same = (v.line_tile[1:, 0] == v.line_tile[:-1, 0])[:, None]
    ok[1:] &= ~(bad[:-1] & same)
    ok[:-1] &= ~(bad[1:] & same)
    return ok


def lindilate(v: PassView) -> np.ndarray:
    """docs/rules.md: (patent or second differences), then dilated across the lines."""
    return dilate(v, patent(v) | second_difference_ok(v))


def diagonal_smooth(v: PassView, linear: np.ndarray) -> np.ndarray:
    """lindilate2d's reconstruction (docs/rules.md): in the V pass of the last level (n_k = 2),
    a new pixel (x, m) between A = (x, m-1) and B = (x, m+1) also reads the four diagonal
    corners (x-1, m-1), (x+1, m-1), (x-1, m+1), (x+1, m+1), all final (rows of G_y(L-1)).
    Where all four lie in the tile and the six samples' colour range passes the level's test,

        C = (2 (A + B) + corners + 4) >> 3          per channel

    (exact on a linear ramp; a traced pixel's noise variance is cut to 12/64 instead of the
    midpoint's 1/2). Elsewhere C is the spec's interpolation (`linear`)."""
    if v.horizontal or v.nominal != 2:
        return linear
    x = v.line
    cols, ok = [], (v.b - v.a) == 2
    for dx in (-1, 1):
        for pos in (v.a, v.b):
            c, readable = v.read(pos, x + dx)
            cols.append(c.astype(np.int32))
            ok = ok & readable
    A, B = v.A.astype(np.int32), v.B.astype(np.int32)
    six = np.stack([*cols, np.broadcast_to(A, cols[0].shape), np.broadcast_to(B, cols[0].shape)])
    rng = spec.color_diff(six.max(axis=0), six.min(axis=0), v.metric)
    ok = np.broadcast_to(ok, v.shape) & v.below_threshold(rng)
    smooth = (2 * (A + B) + cols[0] + cols[1] + cols[2] + cols[3] + 4) >> 3
    return np.where(ok[..., None], smooth, linear).astype(np.uint8)


def lindilate2d(v: PassView) -> np.ndarray:
    """lindilate's decisions with diagonal_smooth's reconstruction at the last level."""
    return lindilate(v)


lindilate2d.interpolate = diagonal_smooth

RULES: dict[str, Rule] = {"patent": patent, "lindilate": lindilate, "lindilate2d": lindilate2d}
DEFAULT_RULE = "patent"


def get_rule(rule: Union[str, Rule]) -> tuple[str, Rule]:
    """(name, function) of a rule given by contract name or as a function of a PassView."""
    if callable(rule):
        return getattr(rule, "__name__", "custom"), rule
    if rule not in RULES:
        raise spec.SpecError(f"unknown rule {rule!r}: one of {', '.join(RULES)}")
    return rule, RULES[rule]
