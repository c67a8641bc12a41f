"""The one palette of source codes for people (algorithm.md section 4), and its legend.

The contract's source map PNG stores the codes as grey levels 0..19, which look black. Every
picture made for a person (the `make sim` / `select --overview` summary, the eval's example
strips) colours the codes with `source_rgb` and explains them with `legend_entries` /
`draw_legend`, so the colours mean the same thing everywhere.

Colours: the Okabe-Ito set (distinguishable with the common colour-vision deficiencies).
Traced pixels are warm (black for the initial grid), interpolated pixels are blues and green.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from . import spec

# code -> (R, G, B)
SOURCE_COLOURS: dict[int, tuple[int, int, int]] = {
    spec.SRC_INITIAL: (0, 0, 0),                          # initial grid: black
    spec.source_code_traced(1): (230, 159, 0),            # traced at level 1: orange
    spec.source_code_traced(2): (213, 94, 0),             # traced at level 2: vermilion
    spec.source_code_traced(3): (204, 121, 167),          # traced at level 3: reddish purple
    spec.source_code_interp(1): (86, 180, 233),           # interpolated at level 1: sky blue
    spec.source_code_interp(2): (0, 114, 178),            # interpolated at level 2: blue
    spec.source_code_interp(3): (0, 158, 115),            # interpolated at level 3: bluish green
    spec.SRC_INTERP_BASE: (170, 200, 220),                # interpolated by a one-level method of
                                                          # the evaluation (msr_eval): pale blue
    spec.SRC_UNSET: (255, 0, 255),                        # never written (a model bug): magenta
}
OTHER_COLOUR = (128, 128, 128)                            # any other code (not in the spec): grey

_LUT = np.array([SOURCE_COLOURS.get(c, OTHER_COLOUR) for c in range(256)], dtype=np.uint8)


def source_label(code: int) -> str:
    if code == spec.SRC_INITIAL:
        return "initial grid (traced)"
    if spec.SRC_TRACED_BASE < code < spec.SRC_INTERP_BASE:
        return f"traced at level {code - spec.SRC_TRACED_BASE}"
    if spec.SRC_INTERP_BASE < code < spec.SRC_INTERP_BASE + 16:
        return f"interpolated at level {code - spec.SRC_INTERP_BASE}"
    if code == spec.SRC_INTERP_BASE:
        return "interpolated (one-level method)"
    if code == spec.SRC_UNSET:
        return "never written"
    return f"code {code} (not in the spec)"


def source_rgb(source) -> np.ndarray:
    """(H, W) source codes -> (H, W, 3) uint8 colours of this palette."""
    return _LUT[np.asarray(source, dtype=np.uint8)]


class LegendEntry(NamedTuple):
    code: int
    colour: tuple[int, int, int]
    label: str
    count: int | None          # pixels with this code (None: not counted)


def levels_in(source) -> int:
    """The highest level k whose codes (k or 16+k) occur in `source` (0: none, as in the
    evaluation's one-level methods, whose codes are 0 traced and 16 interpolated)."""
    present = np.unique(np.asarray(source, dtype=np.uint8))
    ks = [int(c) - spec.SRC_TRACED_BASE for c in present if spec.SRC_TRACED_BASE < c < spec.SRC_INTERP_BASE]
    ks += [int(c) - spec.SRC_INTERP_BASE for c in present if spec.SRC_INTERP_BASE < c < spec.SRC_INTERP_BASE + 16]
    return max(ks, default=0)


def legend_entries(levels: int, source=None) -> list[LegendEntry]:
    """The codes of an L-level run in legend order (initial, traced 1..L, interpolated 1..L),
    plus any other code present in `source`; with `source`, each entry's pixel count.
    levels 0: a one-level method of the evaluation (0 traced, 16 interpolated)."""
    if levels == 0:
        codes = [spec.SRC_INITIAL, spec.SRC_INTERP_BASE]
    else:
        codes = ([spec.SRC_INITIAL] + [spec.source_code_traced(k) for k in range(1, levels + 1)]
                 + [spec.source_code_interp(k) for k in range(1, levels + 1)])
    counts = None
    if source is not None:
        counts = np.bincount(np.asarray(source, dtype=np.uint8).ravel(), minlength=256)
        codes += [int(c) for c in np.flatnonzero(counts) if c not in codes]
    labels = {spec.SRC_INITIAL: "traced"} if levels == 0 else {}
    return [LegendEntry(c, tuple(int(v) for v in _LUT[c]), labels.get(c, source_label(c)),
                        None if counts is None else int(counts[c])) for c in codes]


# --- drawing (Pillow) -------------------------------------------------------------------------

def font(size: int):
    """A scalable sans font (DejaVu Sans from matplotlib when present, else Pillow's own)."""
    from PIL import ImageFont
    try:
        from matplotlib import font_manager
        return ImageFont.truetype(font_manager.findfont("DejaVu Sans"), size)
    except Exception:  # noqa: BLE001 - any missing font falls back to Pillow's built-in one
        return ImageFont.load_default(size=size)


SWATCH = (28, 18)           # legend swatch size in pixels (w, h)


def legend_size(entries, size: int = 15) -> tuple[int, int]:
    f = font(size)
    row = max(SWATCH[1], size) + 8
    text_w = max((int(f.getlength(_entry_text(e))) for e in entries), default=0)
    return SWATCH[0] + 10 + text_w + 4, row * len(entries)


def _entry_text(e: LegendEntry, total: int | None = None) -> str:
    if e.count is None or not total:
        return e.label
    return f"{e.label}: {100 * e.count / total:.1f} %"


def legend_boxes(xy, entries, size: int = 15) -> dict[int, tuple]:
    """{code: swatch box (x0, y0, x1, y1), x1/y1 exclusive} of a legend drawn at xy."""
    x, y = xy
    row = max(SWATCH[1], size) + 8
    return {e.code: (x, y + i * row, x + SWATCH[0], y + i * row + SWATCH[1]) for i, e in enumerate(entries)}


def draw_legend(draw, xy, entries, size: int = 15, total: int | None = None) -> dict[int, tuple]:
    """Draw the legend with its top-left corner at xy; returns `legend_boxes` (so a test can
    find the swatch colours)."""
    f = font(size)
    boxes = legend_boxes(xy, entries, size)
    for e in entries:
        box = boxes[e.code]
        y0 = box[1]
        x = box[0]
        draw.rectangle((box[0] - 1, box[1] - 1, box[2], box[3]), fill=e.colour, outline=(90, 90, 90))
        draw.rectangle(box[:2] + (box[2] - 1, box[3] - 1), fill=e.colour)
        draw.text((x + SWATCH[0] + 10, y0 + SWATCH[1] // 2), _entry_text(e, total), fill=(0, 0, 0),
                  font=f, anchor="lm")
    return boxes


def legend_image(levels: int | None, source=None, size: int = 13):
    """The legend alone as a PIL image (white background) in columns: initial grid, traced
    levels, interpolated levels (and any other code); used under the eval's example strips.
    levels None: the levels present in `source` (`levels_in`)."""
    from PIL import Image, ImageDraw
    entries = legend_entries(levels_in(source) if levels is None else levels, source)
    groups = [[e for e in entries if e.code == spec.SRC_INITIAL],
              [e for e in entries if spec.SRC_TRACED_BASE < e.code < spec.SRC_INTERP_BASE],
              [e for e in entries if spec.SRC_INTERP_BASE <= e.code < spec.SRC_INTERP_BASE + 16]]
    groups.append([e for e in entries if not any(e in g for g in groups)])
    groups = [g for g in groups if g]
    sizes = [legend_size(g, size) for g in groups]
    w = sum(s[0] + 16 for s in sizes) + 8
    h = max(s[1] for s in sizes) + 8
    im = Image.new("RGB", (w, h), (255, 255, 255))
    d = ImageDraw.Draw(im)
    x = 8
    for g, s in zip(groups, sizes):
        draw_legend(d, (x, 6), g, size)
        x += s[0] + 16
    return im
