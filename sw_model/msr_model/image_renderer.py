"""Image-as-renderer: a ground-truth picture stands in for the ray tracer (spec "Terms")."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from . import spec


class ImageRenderer:
    """Answers render(x, y) from an (H, W, 3) uint8 image; counts the pixels it was asked for."""

    def __init__(self, image: np.ndarray):
        image = np.asarray(image)
        if image.ndim != 3 or image.shape[2] != 3 or image.dtype != np.uint8:
            raise ValueError(f"need an (H, W, 3) uint8 image, got {image.shape} {image.dtype}")
        self.image = image
        self.height, self.width = image.shape[:2]
        self.calls = 0
        self.pixels_traced = 0

    def render(self, xs, ys) -> np.ndarray:
        xs, ys = np.asarray(xs), np.asarray(ys)
        self.calls += 1
        self.pixels_traced += xs.size
        return self.image[ys, xs]


def load_rgb(path: str | Path) -> np.ndarray:
    """Read an 8-bit PNG (RGB, RGBA with alpha dropped, grey or palette) as (H, W, 3) uint8."""
    from PIL import Image, UnidentifiedImageError

    p = Path(path)
    if not p.is_file():
        raise spec.SpecError(f"cannot read image {path}: no such file")
    try:
        with Image.open(p) as im:
            im.load()
            if im.mode not in ("RGB", "RGBA", "L", "LA", "P", "1"):
                raise spec.SpecError(f"image {path}: mode {im.mode} is not an 8-bit RGB/RGBA image")
            rgb = np.asarray(im.convert("RGB"), dtype=np.uint8)
    except (UnidentifiedImageError, OSError, SyntaxError) as e:
        raise spec.SpecError(f"cannot read image {path}: {e}") from None
    spec.check_frame_size(rgb.shape[1], rgb.shape[0])
    return rgb


def save_png(path: str | Path, array: np.ndarray) -> None:
    from PIL import Image

    Path(path).parent.mkdir(parents=True, exist_ok=True)
    Image.fromarray(np.ascontiguousarray(array)).save(path)
