"""The contract's decision rules: `select --rule NAME`, golden.select(rule=...), run_tile(rule=...).

A rule is a function of one PassView (passview.py) returning True where a new pixel is
interpolated. Two rules are part of the contract:

- "patent": algorithm.md section 3, d * n_k < thr_k' * g (the default; the RTL implements it).
- "lindilate": docs/rules.md. The patent's test, or else the four samples A', A, B, B' of
  the line lie on a straight line within the threshold (second differences); then a gap is
  traced anyway when the same gap fails that test on the previous or the next line of the
  pass inside the same tile.

Both read only pixels of the decision's own tile that are final before the pass. The
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


def second_difference_ok(v: PassView) -> np.ndarray:
    """A', A, B, B' on a straight line within the threshold: with A' at a - g and B' at b + g,
    c2 = max over the outer samples that exist of d(A' - 2A + B) resp. d(A - 2B + B') (per
    channel, then the spec's metric), and c2 * n_k < thr_k' * g. False where neither outer
    sample can be read (outside the tile, or not final before the pass)."""
    g = v.gap
    A, B = v.A.astype(np.int32), v.B.astype(np.int32)
    c2 = np.zeros(v.shape, np.int32)
    any_outer = np.zeros(v.shape, bool)
    for pos, near, far in ((v.a - g, A, B), (v.b + g, B, A)):
        P, ok = v.read(pos)
        c = spec.color_diff(P.astype(np.int32) - 2 * near + far, 0, v.metric)
        c2 = np.where(ok, np.maximum(c2, c), c2)
        any_outer |= ok
    return any_outer & v.below_threshold(c2)


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


RULES: dict[str, Rule] = {"patent": patent, "lindilate": lindilate}
DEFAULT_RULE = "patent"


def get_rule(rule: Union[str, Rule]) -> tuple[str, Rule]:
    """(name, function) of a rule given by contract name or as a function of a PassView."""
    if callable(rule):
        return getattr(rule, "__name__", "custom"), rule
    if rule not in RULES:
        raise spec.SpecError(f"unknown rule {rule!r}: one of {', '.join(RULES)}")
    return rule, RULES[rule]
