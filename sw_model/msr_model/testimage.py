"""A built-in procedural test picture: smooth gradients, hard edges, texture and flat areas,
so every branch of the decision (interpolate, trace, border) is exercised without any file."""
from __future__ import annotations

import numpy as np


def test_image(width: int = 320, height: int = 240) -> np.ndarray:
    y, x = np.mgrid[0:height, 0:width].astype(np.float64)
    u, v = x / max(width - 1, 1), y / max(height - 1, 1)
    img = np.empty((height, width, 3))
    img[..., 0] = 40 + 160 * u                       # sky-like gradient
    img[..., 1] = 60 + 120 * v
    img[..., 2] = 200 - 100 * u * v
    # a shaded disc with a hard silhouette
    cx, cy, r = 0.35 * width, 0.55 * height, 0.25 * min(width, height)
    dist = np.hypot(x - cx, y - cy)
    disc = dist < r
    shade = np.clip(1.0 - dist / r, 0, 1) ** 0.5
    img[disc] = np.stack([220 * shade, 90 * shade + 30, 40 + 0 * shade], -1)[disc]
    # a checkerboard floor in the lower right
    floor = (u > 0.6) & (v > 0.55)
    checker = ((x // 12 + y // 12) % 2).astype(bool)
    img[floor & checker] = (235, 235, 235)
    img[floor & ~checker] = (25, 25, 25)
    # fine texture band (high frequency: traced densely)
    band = (v > 0.1) & (v < 0.2)
    img[band, 1] += 40 * np.sin(x[band] * 1.3) * np.cos(y[band] * 0.9)
    return np.clip(np.rint(img), 0, 255).astype(np.uint8)
