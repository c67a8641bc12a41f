"""One picture of one run (`make sim` summary.png, `select --overview PNG`).

    RTL frame (or the golden model's) | full reference        | absolute error + colour bar
    source map (palette) + legend     | traced % per tile + bar | (legend, counts)

with a title of the run's parameters and results. Panels share one scale: frames larger than
640 pixels wide are reduced by an integer factor d (frames: box average; error map: block
maximum, so a single wrong pixel still shows; source map: nearest, so codes are never mixed),
small frames are enlarged by an integer factor (nearest). `layout()` gives every box, so a
test can find the panels in the written PNG.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from . import spec
from .metrics import format_db, psnr, ssim
from .palette import draw_legend, font, legend_boxes, legend_entries, legend_size, source_rgb

MAX_PANEL_W = 640            # frames wider than this are reduced by an integer factor
MIN_PANEL_W = 480            # narrower ones enlarged by an integer factor (nearest)
BG = (255, 255, 255)
INK = (0, 0, 0)
ERROR_CMAP = "inferno"
TRACED_CMAP = "viridis"


@dataclass
class RunInfo:
    """What the title line says about a run (None: not known for this run, e.g. cycles of select)."""
    scene: str
    params: spec.Params
    rule: str = "patent"
    psnr_db: float | None = None          # inf with identical frames: shown as "identical"
    ssim: float | None = None
    cycles: int | None = None
    bit_exact: bool | None = None
    frame_label: str = "RTL frame"
    budget: int = 0                       # ray budget in pixels (docs/budget.md); 0 = off
    scale_per_row: list | None = None     # with a budget: the scale u of every tile row (1.0 = 256)


@dataclass
class Layout:
    width: int                 # frame W, H
    height: int
    down: int                  # reduction factor (1: none)
    up: int                    # enlargement factor (1: none)
    panel: tuple[int, int]     # panel size (w, h)
    size: tuple[int, int]      # figure size (w, h)
    boxes: dict                # name -> (x0, y0, x1, y1), x1/y1 exclusive
    title_y: int

    def frame_xy(self, px: int, py: int) -> tuple[int, int]:
        """The frame pixel a panel pixel (relative to the panel's corner) shows (nearest)."""
        if self.down > 1:
            return px * self.down, py * self.down
        return px // self.up, py // self.up


PANELS = ("frame", "reference", "error", "source", "traced")
TITLE_SIZE, TEXT_SIZE, CAPTION_SIZE = 20, 15, 16
MARGIN, GAP, BAR_W, BAR_ROOM, LEGEND_ROOM = 16, 24, 18, 96, 320
STRIP_W = 120                 # the budget's scale-per-row strip beside the traced map


def layout(width: int, height: int, strip: bool = False) -> Layout:
    down = math.ceil(width / MAX_PANEL_W) if width > MAX_PANEL_W else 1
    up = max(1, MIN_PANEL_W // width) if down == 1 else 1
    pw = -(-width // down) * up
    ph = -(-height // down) * up
    cell_w = pw + BAR_ROOM
    title_h = 2 * (TITLE_SIZE + 10) + 8
    cap_h = CAPTION_SIZE + 12
    row_h = cap_h + ph + GAP
    boxes = {}
    for i, name in enumerate(PANELS):
        r, c = divmod(i, 3)
        x0 = MARGIN + c * (cell_w + GAP)
        y0 = MARGIN + title_h + r * row_h + cap_h
        boxes[name] = (x0, y0, x0 + pw, y0 + ph)
    for name in ("error", "traced"):
        x0, y0, x1, y1 = boxes[name]
        boxes[name + "_bar"] = (x1 + 12, y0, x1 + 12 + BAR_W, y1)
    lx0 = MARGIN + 2 * (cell_w + GAP)
    extra = 0
    if strip:
        # the scale per tile row, rows at the traced map's heights, between it and the legend
        x0, y0, _, y1 = boxes["traced_bar"]
        sx0 = x0 + BAR_ROOM - 12
        boxes["scale"] = (sx0, y0, sx0 + STRIP_W - GAP, y1)
        extra = max(0, sx0 + STRIP_W - lx0)
        lx0 += extra
    boxes["legend"] = (lx0, boxes["traced"][1], lx0 + cell_w, boxes["traced"][3])
    w = MARGIN + 3 * cell_w + 2 * GAP + MARGIN + extra
    h = MARGIN + title_h + 2 * row_h - GAP + MARGIN
    h = max(h, boxes["legend"][1] + LEGEND_ROOM)     # a flat frame still has room for the legend
    return Layout(width, height, down, up, (pw, ph), (max(w, 900), h), boxes, MARGIN)


# --- panel pictures ---------------------------------------------------------------------------

def _pad_to(a: np.ndarray, d: int, mode="edge") -> np.ndarray:
    h, w = a.shape[:2]
    ph, pw = -(-h // d) * d - h, -(-w // d) * d - w
    pad = ((0, ph), (0, pw)) + ((0, 0),) * (a.ndim - 2)
    return np.pad(a, pad, mode=mode)


def _reduce(a: np.ndarray, lay: Layout, how: str) -> np.ndarray:
    """One panel's pixels from a frame-sized array: 'mean' (frames), 'max' (error), 'nearest'."""
    if lay.down > 1:
        d = lay.down
        if how == "nearest":
            return a[::d, ::d]
        b = _pad_to(a, d)
        h, w = b.shape[0] // d, b.shape[1] // d
        blocks = b.reshape((h, d, w, d) + b.shape[2:])
        if how == "max":
            return blocks.max(axis=(1, 3))
        return (blocks.astype(np.float32).mean(axis=(1, 3)) + 0.5).astype(a.dtype)
    if lay.up > 1:
        return np.repeat(np.repeat(a, lay.up, axis=0), lay.up, axis=1)
    return a


def _cmap(name: str, values: np.ndarray) -> np.ndarray:
    """values in 0..1 -> uint8 RGB through a matplotlib colour map."""
    import matplotlib
    lut = (matplotlib.colormaps[name](np.linspace(0, 1, 256))[:, :3] * 255 + 0.5).astype(np.uint8)
    return lut[np.clip(np.asarray(values) * 255 + 0.5, 0, 255).astype(np.uint8)]


def abs_error(frame: np.ndarray, reference: np.ndarray) -> np.ndarray:
    """Per pixel, the largest |frame - reference| over R, G, B (0..255)."""
    return np.abs(frame.astype(np.int16) - reference.astype(np.int16)).max(axis=2).astype(np.uint8)


def psnr_ssim(reference: np.ndarray, frame: np.ndarray) -> tuple[float, float | None]:
    """PSNR in dB (inf for identical frames) and SSIM (None below 7x7) of frame against reference."""
    return psnr(reference, frame), ssim(reference, frame)


def error_scale(err: np.ndarray) -> int:
    """Top of the error colour bar: the 99.9th percentile rounded up to a multiple of 8
    (at least 8, at most 255); larger errors show in the top colour."""
    if not err.size:
        return 8
    p = float(np.percentile(err, 99.9))
    return int(min(255, max(8, 8 * math.ceil(p / 8))))


def traced_per_tile(source: np.ndarray, tile: int) -> np.ndarray:
    """(nty, ntx) fraction of traced pixels (code < 16) in each tile."""
    h, w = source.shape
    ntx, nty = spec.tile_counts(w, h, tile)
    traced = (source < spec.SRC_INTERP_BASE).astype(np.float64)
    sums = np.add.reduceat(np.add.reduceat(traced, np.arange(0, h, tile), axis=0), np.arange(0, w, tile), axis=1)
    ys, xs = spec.axis_spans(h, tile), spec.axis_spans(w, tile)
    area = np.outer([e for _, e in ys], [e for _, e in xs])
    return sums / area


# --- the figure -------------------------------------------------------------------------------

def title_lines(info: RunInfo, width: int, height: int, traced_fraction: float) -> tuple[str, str]:
    p = info.params
    fov = f"fov gain {p.fov_gain}" if p.fov_gain else "no foveation (fov gain 0)"
    first = (f"{info.scene}  {width}x{height}   T {p.tile}   L {p.levels}   thr {','.join(map(str, p.thr))}   "
             f"metric {p.metric}   {fov}   rule {info.rule}")
    parts = [f"traced {100 * traced_fraction:.1f} %", f"PSNR {format_db(info.psnr_db)}"]
    if info.ssim is not None:
        parts.append(f"SSIM {info.ssim:.4f}")
    if info.cycles is not None:
        parts.append(f"{info.cycles:,} cycles ({info.cycles / (width * height):.3f}/pixel)".replace(",", " "))
    if info.bit_exact is not None:
        parts.append("bit exact with the golden model" if info.bit_exact else "NOT bit exact with the golden model")
    if info.budget:
        traced = traced_fraction * width * height
        parts.insert(1, f"budget {info.budget} ({100 * info.budget / (width * height):.1f} %, "
                        f"{100 * (traced - info.budget) / info.budget:+.2f} %)")
    return first, "   ".join(parts)


def _scale_strip(draw, box, lay: Layout, tile: int, scales, f):
    """The budget's scale u of each tile row as a bar from the 1.0 line (log scale, 1/8 .. 5.7: a
    first frame's rows reach U_MIN_FIRST), at the height of the row in the traced map."""
    from .budget import U_MAX, U_MIN_FIRST
    x0, y0, x1, y1 = box
    lo, hi = math.log(U_MIN_FIRST / 256), math.log(U_MAX / 256)
    xs = lambda u: x0 + round((math.log(u / 256) - lo) / (hi - lo) * (x1 - x0))   # noqa: E731
    draw.rectangle((x0 - 1, y0 - 1, x1, y1), outline=INK)
    for r, u in enumerate(scales):
        ya = y0 + round(r * tile / lay.height * (y1 - y0))
        yb = max(y0 + round(min((r + 1) * tile, lay.height) / lay.height * (y1 - y0)) - 1, ya)
        a, b = sorted((xs(256), xs(u)))
        draw.rectangle((a, ya, max(b, a + 1), yb), fill=(68, 1, 84) if u >= 256 else (53, 183, 121))
    draw.line((xs(256), y0, xs(256), y1), fill=INK)
    for u, text in ((U_MIN_FIRST, "/8"), (256, "1"), (U_MAX, "x5.7")):
        draw.text((xs(u), y1 + 4), text, fill=INK, font=f, anchor="mt")


def _colour_bar(im, draw, box, cmap, labels, f):
    """Vertical bar, top = 1; labels: [(fraction 0..1, text)] written to its right."""
    from PIL import Image
    x0, y0, x1, y1 = box
    n = y1 - y0
    ramp = _cmap(cmap, np.linspace(1, 0, n))[:, None, :].repeat(x1 - x0, axis=1)
    im.paste(Image.fromarray(np.ascontiguousarray(ramp)), (x0, y0))
    draw.rectangle((x0 - 1, y0 - 1, x1, y1), outline=INK)
    for frac, text in labels:
        y = y1 - 1 - round(frac * (n - 1))
        draw.line((x1, y, x1 + 4, y), fill=INK)
        draw.text((x1 + 7, y), text, fill=INK, font=f, anchor="lm")


def legend_swatches(lay: Layout, levels: int, source=None) -> dict[int, tuple]:
    """{code: swatch box} of the summary's legend (as drawn by summary_image)."""
    lx0, ly0, _, _ = lay.boxes["legend"]
    return legend_boxes((lx0, ly0 + 4), legend_entries(levels, source), TEXT_SIZE)


def summary_image(frame, reference, source, info: RunInfo):
    """The summary as a PIL image, with its Layout."""
    from PIL import Image, ImageDraw
    frame, reference, source = np.asarray(frame), np.asarray(reference), np.asarray(source)
    H, W = source.shape
    if frame.shape != (H, W, 3) or reference.shape != (H, W, 3):
        raise spec.SpecError(f"summary: frame {frame.shape}, reference {reference.shape} and source map "
                             f"{source.shape} differ in size")
    lay = layout(W, H, strip=info.scale_per_row is not None)
    im = Image.new("RGB", lay.size, BG)
    d = ImageDraw.Draw(im)
    f_title, f_cap, f_text = font(TITLE_SIZE), font(CAPTION_SIZE), font(TEXT_SIZE)
    traced_fraction = float((source < spec.SRC_INTERP_BASE).mean())
    l1, l2 = title_lines(info, W, H, traced_fraction)
    d.text((MARGIN, lay.title_y), l1, fill=INK, font=f_title)
    d.text((MARGIN, lay.title_y + TITLE_SIZE + 10), l2, fill=INK, font=f_title)

    err = abs_error(frame, reference)
    vmax = error_scale(err)
    fr = spec.tile_counts(W, H, info.params.tile)
    per_tile = traced_per_tile(source, info.params.tile)
    ty = np.minimum(np.arange(H) // info.params.tile, fr[1] - 1)
    tx = np.minimum(np.arange(W) // info.params.tile, fr[0] - 1)
    scale = f"1:{lay.down}" if lay.down > 1 else (f"{lay.up}:1" if lay.up > 1 else "1:1")
    panels = {
        "frame": (_reduce(frame, lay, "mean"), f"{info.frame_label} ({scale})"),
        "reference": (_reduce(reference, lay, "mean"), "full reference (every pixel traced)"),
        "error": (_cmap(ERROR_CMAP, _reduce(err, lay, "max") / vmax),
                  "absolute error, max over R,G,B" + (f" (block max {lay.down}x{lay.down})" if lay.down > 1 else "")),
        "source": (source_rgb(_reduce(source, lay, "nearest")), "source map (nearest)"),
        "traced": (_cmap(TRACED_CMAP, _reduce(per_tile[ty][:, tx], lay, "nearest")),
                   f"traced fraction per {info.params.tile}x{info.params.tile} tile"),
    }
    for name, (pix, caption) in panels.items():
        x0, y0, x1, y1 = lay.boxes[name]
        pix = np.ascontiguousarray(pix[: y1 - y0, : x1 - x0])
        im.paste(Image.fromarray(pix), (x0, y0))
        d.text((x0, y0 - 6), caption, fill=INK, font=f_cap, anchor="ld")

    ticks = [(v / vmax, str(v)) for v in range(0, vmax + 1, max(1, vmax // 4))]
    if err.max() > vmax:
        ticks[-1] = (1.0, f">={vmax}")
    elif ticks[-1][0] < 1:
        ticks.append((1.0, str(vmax)))
    _colour_bar(im, d, lay.boxes["error_bar"], ERROR_CMAP, ticks, f_text)
    _colour_bar(im, d, lay.boxes["traced_bar"], TRACED_CMAP, [(v / 4, f"{25 * v} %") for v in range(5)], f_text)
    if info.scale_per_row is not None:
        _scale_strip(d, lay.boxes["scale"], lay, info.params.tile, info.scale_per_row, f_text)
        sx0, sy0 = lay.boxes["scale"][:2]
        d.text((sx0, sy0 - 6), "scale u / row", fill=INK, font=f_cap, anchor="ld")

    entries = legend_entries(info.params.levels, source)
    lx0, ly0, _, _ = lay.boxes["legend"]
    d.text((lx0, ly0 - 6), "source codes (pixels)", fill=INK, font=f_cap, anchor="ld")
    swatches = draw_legend(d, (lx0, ly0 + 4), entries, TEXT_SIZE, total=W * H)
    lay.boxes.update({f"legend_{c}": b for c, b in swatches.items()})
    ly = ly0 + 4 + legend_size(entries, TEXT_SIZE)[1] + 12
    for line in (f"err > 0 in {100 * float((err > 0).mean()):.2f} % of pixels, max {int(err.max())}",
                 f"{fr[0]}x{fr[1]} tiles of {info.params.tile}x{info.params.tile}"):
        d.text((lx0, ly), line, fill=INK, font=f_text)
        ly += TEXT_SIZE + 8
    return im, lay


def write_summary(path, frame, reference, source, info: RunInfo):
    im, lay = summary_image(frame, reference, source, info)
    im.save(path, format="PNG")
    return lay
