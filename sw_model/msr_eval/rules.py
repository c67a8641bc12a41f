"""Decision rules compared by the evaluation, each a function of msr_model's PassView.

Same passes, same positions, same tile independence (a rule reads only pixels of its own
tile that were final before the pass, through PassView.read), only the interpolate-or-trace
test changes. "patent" and "lindilate" are the contract's (msr_model.rules, docs/rules.md);
the others are research variants:

- "dilate": the patent's test, and a gap is also traced when the same gap on the previous
  or the next line of the pass (same tile) fails it. Edges are continuous, so a detection
  next door says a feature may have slipped between this pair's two samples.
- "linear": also interpolate when A', A, B, B' lie on a straight line within the threshold
  (msr_model.rules.second_difference_ok): exact on a linear ramp, so a smooth gradient
  steeper than the threshold no longer forces traces.
- "diag": the patent's test, and for a centre pixel (new on both axes; decided in the V pass)
  also the four diagonal corners (a_x, a_y), (b_x, a_y), (a_x, b_y), (b_x, b_y) that claim 8
  lets it read: their colour range must pass the same test.
"""
from __future__ import annotations

import numpy as np

from msr_model import RULES as CONTRACT_RULES
from msr_model import PassView, SpecError
from msr_model.rules import dilate as _dilate
from msr_model.rules import patent, second_difference_ok


def dilate(v: PassView) -> np.ndarray:
    return _dilate(v, patent(v))


def linear(v: PassView) -> np.ndarray:
    return patent(v) | second_difference_ok(v)


def diag(v: PassView) -> np.ndarray:
    ok = np.array(patent(v))
    centre = (v.line_a[:, 0] >= 0)            # lines new at this level: V pass only
    if v.horizontal or not centre.any():
        return ok
    corners = [v.read(pos, line)[0] for pos in (v.a, v.b) for line in (v.line_a, v.line_b)]
    cols = np.stack(corners).astype(np.int32)
    rng = cols.max(axis=0) - cols.min(axis=0)
    rd = rng.max(axis=-1) if v.metric == "max" else rng.sum(axis=-1)
    ok[centre] &= v.below_threshold(rd)[centre]
    return ok


RULES = {**CONTRACT_RULES, "dilate": dilate, "linear": linear, "diag": diag}


def rule_function(name: str):
    """The rule called `name`: a contract rule or one of this module's."""
    if name not in RULES:
        raise SpecError(f"rule must be one of {', '.join(RULES)}, got {name!r}")
    return RULES[name]
