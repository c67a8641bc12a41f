"""The rendering unit as the golden model sees it: one protocol and one checked render call.

Anything with `width`, `height` and `render(xs, ys)` is a rendering unit: the Embree binding
(embree.py), a picture (image_renderer.py) or a wrapper of either (the evaluation's counting
renderer). Every caller asks for pixels through `render_checked`, so a wrong answer (shape,
type) is caught in one place.
"""
from __future__ import annotations

from typing import Protocol, runtime_checkable

import numpy as np


@runtime_checkable
class Renderer(Protocol):
    """A rendering unit: the colour of any pixel of the frame, deterministically (spec "Terms")."""

    width: int
    height: int

    def render(self, xs: np.ndarray, ys: np.ndarray) -> np.ndarray:
        """Colours (N, 3) uint8 of the pixels (xs[i], ys[i]), any order, any batch split."""
        ...


def render_checked(renderer: Renderer, xs, ys) -> np.ndarray:
    """Ask `renderer` for the pixels (xs[i], ys[i]); return their colours as (N, 3) uint8.

    Raises RuntimeError when the answer is not one RGB triple per pixel."""
    xs = np.asarray(xs, dtype=np.int32).ravel()
    ys = np.asarray(ys, dtype=np.int32).ravel()
    if xs.size == 0:
        return np.zeros((0, 3), dtype=np.uint8)
    cols = np.asarray(renderer.render(xs, ys))
    if cols.shape != (xs.size, 3):
        raise RuntimeError(f"renderer returned shape {cols.shape} for {xs.size} pixels")
    return cols.astype(np.uint8, copy=False)
