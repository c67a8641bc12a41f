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


PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
PNG_COLOUR_TYPES = {0: "grey", 2: "RGB", 3: "palette", 4: "grey+alpha", 6: "RGBA"}


def png_header(path: str | Path) -> tuple[int, int, int, int] | None:
    """(width, height, bit depth, colour type) from a PNG's IHDR chunk, None if not a PNG.
    Reads 33 bytes, so a frame can be refused before anything is decoded."""
    with open(path, "rb") as f:
        head = f.read(33)
    if not head.startswith(PNG_SIGNATURE):
        return None
    if len(head) < 33 or head[12:16] != b"IHDR":
        raise spec.SpecError(f"cannot read image {path}: truncated PNG header")
    w, h = int.from_bytes(head[16:20], "big"), int.from_bytes(head[20:24], "big")
    return w, h, head[24], head[25]


def check_image(path: str | Path) -> None:
    """Refuse, from the header alone, a picture the rendering unit cannot stand for: a frame
    above MAX_FRAME x MAX_FRAME, or a PNG with 16-bit channels (not silently cut to 8 bits)."""
    p = Path(path)
    if not p.is_file():
        raise spec.SpecError(f"cannot read image {path}: no such file")
    try:
        hdr = png_header(p)
    except OSError as e:
        raise spec.SpecError(f"cannot read image {path}: {e.strerror or e}") from None
    if hdr is None:
        return
    w, h, depth, colour = hdr
    if colour not in PNG_COLOUR_TYPES:
        raise spec.SpecError(f"image {path}: PNG colour type {colour} is not valid")
    if depth > 8:
        raise spec.SpecError(f"image {path}: {depth}-bit {PNG_COLOUR_TYPES[colour]} PNG; "
                             "only 8-bit channels are taken (convert it to 8-bit first)")
    if not (1 <= w <= spec.MAX_FRAME and 1 <= h <= spec.MAX_FRAME):
        raise spec.SpecError(f"image {path} is {w}x{h}: a frame is at most {spec.MAX_FRAME}x{spec.MAX_FRAME}")


def load_rgb(path: str | Path) -> np.ndarray:
    """Read an 8-bit PNG (RGB, RGBA with alpha dropped, grey or palette) as (H, W, 3) uint8.
    The size and the bit depth are checked from the header before anything is decoded."""
    from PIL import Image, UnidentifiedImageError

    check_image(path)
    try:
        with Image.open(path) as im:
            spec.check_frame_size(*im.size)           # other formats: the size from the header too
            if im.mode not in ("RGB", "RGBA", "L", "LA", "P", "1"):
                raise spec.SpecError(f"image {path}: mode {im.mode} is not an 8-bit RGB/RGBA image")
            im.load()
            rgb = np.asarray(im.convert("RGB"), dtype=np.uint8)
    except (UnidentifiedImageError, OSError, SyntaxError, Image.DecompressionBombError) as e:
        raise spec.SpecError(f"cannot read image {path}: {e}") from None
    return rgb


def save_png(path: str | Path, array: np.ndarray, format: str | None = None) -> None:
    """An (H, W, 3) array as 8-bit RGB, an (H, W) array as 8-bit grey; `format` when the
    name does not say it (a temporary file)."""
    from PIL import Image

    Path(path).parent.mkdir(parents=True, exist_ok=True)
    Image.fromarray(np.ascontiguousarray(array)).save(path, format=format)
