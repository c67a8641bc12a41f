"""What the evaluation's pages and plots share: the family names, the formats of a traced
fraction and a PSNR, the downscaled figures of docs/img/ and the per-scene grid of small
plots. Used by report, conv_report, headline and textured; imports none of them."""
from __future__ import annotations

from pathlib import Path

from msr_model.metrics import format_db

FAMILY_NAMES = {
    "full": "full render", "grid2": "uniform grid, every 2nd pixel, bilinear",
    "grid4": "uniform grid, every 4th pixel, bilinear", "checkerboard": "checkerboard (4-neighbour mean)",
    "single_traced": "single level, stride 4, tile borders traced (Fig. 4/5b)",
    "single_borrowed": "single level, stride 4, borders borrowed (Fig. 5 [0068], serial)",
    "multi_L1_T16": "patent, L=1, T=16", "multi_L2_T16": "patent, L=2, T=16", "multi_L2_T32": "patent, L=2, T=32",
    "multi_L3_T16": "patent, L=3, T=16", "multi_L3_T32": "patent, L=3, T=32",
    "multi_L3_T16_fov": "patent, L=3, T=16, foveated (+~16 at the edge)",
    "multi_L3_T16_dilate": "**new** dilate rule, L=3, T=16", "multi_L3_T16_linear": "**new** linear rule, L=3, T=16",
    "multi_L3_T16_lindilate": "**new** lindilate rule, L=3, T=16", "multi_L3_T16_diag": "**new** diag rule, L=3, T=16",
    "multi_L3_T32_lindilate": "**new** lindilate rule, L=3, T=32",
    "dacs": "DACS (Mallett and Yuksel 2018), variance threshold", "vrs_T8": "VRS-like (tier 2), 8x8 rate tiles",
    "vrs_T16": "VRS-like (tier 2), 16x16 rate tiles",
    "multi_L3_T16_gbuf": "**new** G-buffer rule (gbuf), L=3, T=16",
    "multi_L3_T16_gbuflindilate": "**new** G-buffer + lindilate (gbuflindilate), L=3, T=16",
}


# --- numbers in the tables --------------------------------------------------------------------

def pct(f, how=None):
    """A traced fraction in % (one decimal); `<= x` when even the cheapest setting reaches the
    target (metrics.fraction_for's "at_or_below"); `not reached` for None."""
    if f is None:
        return "not reached"
    s = f"{100 * f:.1f}"
    return f"<= {s}" if how == "at_or_below" else s


def needed_cell(d):
    """A `35 / 40` cell: the fractions of a needed-fraction entry ({"35": ..., "40": ...}), `-` for None."""
    if d is None:
        return "-"
    return f"{pct(d['35']['fraction'], d['35']['how'])} / {pct(d['40']['fraction'], d['40']['how'])}"


def db(p):
    """A PSNR in dB for a table cell (two decimals, no unit); "identical" for identical frames."""
    return format_db(p).removesuffix(" dB")


# --- figures ------------------------------------------------------------------------------------

def small_png(src: Path, dst: Path, max_w: int, colors: int | None = 128):
    """Downscaled PNG; plots are palette-quantised, example frames are not (banding)."""
    from PIL import Image
    im = Image.open(src).convert("RGB")
    if im.width > max_w:
        im = im.resize((max_w, round(im.height * max_w / im.width)), Image.LANCZOS)
    if colors:
        im = im.quantize(colors=colors, method=Image.Quantize.MEDIANCUT)
    dst.parent.mkdir(parents=True, exist_ok=True)
    im.save(dst, optimize=True)


def scene_grid(plt, nscenes):
    """The figure of a per-scene plot (report.plot_curves, conv_report.plot_scene_fronts,
    headline.plot_fronts): one small panel a scene, four a row. Returns (fig, axes), axes 2-D."""
    ncol = min(4, nscenes)
    nrow = -(-nscenes // ncol)
    return plt.subplots(nrow, ncol, figsize=(max(6.4, 3.2 * ncol), 2.6 * nrow + 0.9), squeeze=False)


def scene_panel(ax, scene, xmax, ymax):
    """One scene's panel of a scene grid: its name over it, traced pixels 0..xmax %, PSNR
    20..ymax dB, a dotted line at 40 dB."""
    ax.axhline(40, color="k", lw=0.4, ls=":")
    ax.set_title(scene, fontsize=8)
    ax.set_xlim(0, xmax)
    ax.set_ylim(20, ymax)
    ax.tick_params(labelsize=6)


def finish_scene_grid(plt, fig, axes, nscenes, ylabel, title, path):
    """Blank the panels past the last scene, label the axes (traced pixels against `ylabel`),
    one legend under the grid (the first panel's lines), the title; write `path`, close."""
    for ax in axes.ravel()[nscenes:]:
        ax.axis("off")
    fig.supxlabel("traced pixels (%)", fontsize=8)
    fig.supylabel(ylabel, fontsize=8)
    h, lab = axes[0, 0].get_legend_handles_labels()
    fig.legend(h, lab, fontsize=6, loc="lower center", ncol=4, frameon=False)
    fig.suptitle(title, fontsize=9)
    fig.tight_layout(rect=(0, 0.12 if axes.shape[0] == 1 else 0.08, 1, 1))
    fig.savefig(path, dpi=70)
    plt.close(fig)


# --- pages: Jinja2 templates (msr_eval/templates/) ---------------------------------------------

TEMPLATES = Path(__file__).resolve().parent / "templates"


def need(d, bold: bool = False):
    """A needed-fraction entry ({"fraction", "how"}) as a cell: `x`, `<= x` (even the cheapest
    setting gets there), `not reached`; `-` for None (no such family)."""
    if d is None:
        return "-"
    s = pct(d["fraction"], d.get("how"))
    return f"**{s}**" if bold and d["fraction"] is not None else s


def num(v, digits: int = 2, unit: str = ""):
    """A number with `digits` decimals (and a unit), `-` for None."""
    return "-" if v is None else f"{v:.{digits}f}{unit}"


def pc(f, digits: int = 1, signed: bool = False):
    """A fraction in % (digits decimals, optionally signed), `-` for None."""
    return "-" if f is None else (f"{100 * f:+.{digits}f}" if signed else f"{100 * f:.{digits}f}")


def family(f):
    """A family's name on the pages (FAMILY_NAMES, else the key)."""
    return FAMILY_NAMES.get(f, f)


def render(name: str, **ctx) -> str:
    """Render the template `name` (msr_eval/templates/) with `ctx`; undefined names fail."""
    import jinja2
    env = jinja2.Environment(loader=jinja2.FileSystemLoader(str(TEMPLATES)), undefined=jinja2.StrictUndefined,
                             trim_blocks=True, lstrip_blocks=True, keep_trailing_newline=True,
                             autoescape=False)
    env.filters.update(pct=pct, need=need, db=db, num=num, pc=pc, family=family, needed_cell=needed_cell)
    text = env.get_template(name).render(**ctx)
    while "\n\n\n" in text:                       # one blank line between blocks, whatever the loops left
        text = text.replace("\n\n\n", "\n\n")
    return text.rstrip("\n") + "\n"
