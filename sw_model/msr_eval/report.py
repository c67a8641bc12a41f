"""Pictures and pages of an eval run: curves, set Pareto plots, example strips, and the
results pages (docs/results.md, docs/results/*.md) rendered from the Jinja2 templates in
msr_eval/templates/ with the numbers of the run's records (data/results.json).

    python -m msr_eval.report                      # the pages from data/results.json (no rendering)
    python -m msr_eval.report --from-records out/eval/results.json --docs-dir /tmp/docs

Every number on the pages comes from the records; the templates hold the words only.
"""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from msr_model.palette import legend_image, source_rgb

from . import conv_report as CR
from . import headline as HL
from .metrics import capped, flip, pareto
from .present import FAMILY_NAMES, finish_scene_grid, render, scene_grid, scene_panel, small_png
from .textured import section as textured_section


REPO = Path(__file__).resolve().parents[2]

# The generated pages beside results.md: (file, template, what; {mode} expands per mode)
PAGES = (
    ("converged.md", "results/converged.md.j2", "every table against the converged image at full size: 40 and 35 dB, "
     "SSIM / FLIP / worst tile at the equal-quality point, the common grid of traced fractions, the references, "
     "every family's fractions and cheapest setting for 40 dB, the peers at equal traced fraction"),
    ("heldout.md", "results/heldout.md.j2", "every table of the held-out scenes"),
    ("full_render.md", "results/full_render.md.j2", "scores against the renderer's own full render, both modes: set "
     "means, every family's fractions for 35 / 40 dB, the new rules against the patent's, textured scenes and the "
     "G-buffer rule, the wall-time speed-up, sequences (flicker), figures and example frames"),
    ("key_settings_{mode}.md", "results/key_settings.md.j2", "PSNR / SSIM / FLIP at the key settings, {mode} renderer"),
)


def write_docs(result: dict, out: Path, docs: Path, data: Path | None = None):
    """The results pages: docs/results.md and docs/results/*.md, rendered from the templates
    (msr_eval/templates/) with the numbers of `result`; the figures of the run in `out` (if
    any) downscaled into docs/img/; `result` itself, floats to 5 significant digits, to
    DATA/results.json (default: data/ beside docs/). The pages are rendered from that rounded
    copy, so `python -m msr_eval.report` on the committed file gives the same pages."""
    docs, out = Path(docs), Path(out)
    data = Path(data) if data is not None else docs.parent / "data"
    cfg = result["config"]
    img = docs / "img"
    for mode in cfg["modes"]:
        for kind in ("pareto", "curves"):
            src = out / f"{kind}_{mode}.png"
            if src.is_file():
                small_png(src, img / f"eval_{kind}_{mode}.png", 900)
    for ex in result.get("examples") or []:
        if (out / ex["file"]).is_file():
            small_png(out / ex["file"], img / f"eval_{ex['file']}", 968, None)
        ex["doc_file"] = f"img/eval_{ex['file']}"
    for mode in cfg["modes"]:
        if (out / f"fronts_conv_{mode}.png").is_file():
            small_png(out / f"fronts_conv_{mode}.png", img / f"eval_fronts_conv_{mode}.png", 900)
    for src, dst, w in (("fronts_headline.png", "eval_fronts_headline.png", 1100),
                        ("temporal.png", "eval_temporal.png", 1100)):
        if (out / src).is_file():
            small_png(out / src, img / dst, w)
    data.mkdir(parents=True, exist_ok=True)
    result = _round(result)
    (data / "results.json").write_text(json.dumps(result, separators=(",", ":")))
    write_pages(result, docs, data)


def _heldout(data: Path):
    """(file name, head-to-head context, config) of the newest held-out run under DATA/converged/."""
    hfs = sorted((data / "converged").glob("heldout_*.json"))
    if not hfs:
        return None
    d = _round(json.loads(hfs[-1].read_text()))
    hc = {"scene_sources": d["config"].get("scenes", []), "conv_spp": 256, "date_utc": "", **d["config"]}
    return hfs[-1].name, HL.context(d["head_to_head"], d.get("head_to_head_references")), hc


def write_pages(result: dict, docs: Path, data: Path) -> list[Path]:
    """Render every page from `result` (as stored in DATA/results.json) and the held-out record;
    returns the files written."""
    docs, data = Path(docs), Path(data)
    cfg = result["config"]
    recs = result["records"]
    if any("psnr_conv" in r and r["mode"] == "heavy" for r in recs):
        analysis = HL.analyse(recs, "heavy")            # from the stored records, the code of now
    else:
        analysis = result.get("head_to_head") or {}
    h = HL.context(analysis, result.get("head_to_head_references")) if analysis else None
    ho = _heldout(data)
    (docs / "results").mkdir(parents=True, exist_ok=True)
    pages = []
    for f, _, what in PAGES:
        if f == "heldout.md" and not ho:
            continue
        if f == "converged.md" and not result.get("converged"):
            continue
        for m in (cfg["modes"] if "{mode}" in f else [None]):
            pages.append({"file": f.format(mode=m), "what": what.format(mode=m)})
    written = []

    def put(path: Path, text: str):
        path.write_text(text)
        written.append(path)

    s = h["summary"] if h else [None] * 3
    put(docs / "results.md", render("results.md.j2", cfg=cfg, h=h, s0=s[0], s1=s[1], s3=s[2],
                                    ho=ho[1] if ho else None, ho_cfg=ho[2] if ho else None, pages=pages))
    figs = [{"mode": m, "path": f"img/eval_fronts_conv_{m}.png"} for m in cfg["modes"]
            if (docs / "img" / f"eval_fronts_conv_{m}.png").is_file()]
    if result.get("converged"):
        put(docs / "results" / "converged.md", render("results/converged.md.j2", cfg=cfg, h=h, c=CR.context(result),
                                                      figs=figs, up="../"))
    if ho:
        put(docs / "results" / "heldout.md", render("results/heldout.md.j2", cfg=ho[2], h=ho[1], file=ho[0]))
    put(docs / "results" / "full_render.md", render("results/full_render.md.j2", **_full_render(result, docs)))
    keys = set(cfg.get("key_families") or FAMILY_NAMES)
    for mode in cfg["modes"]:
        rows = []
        for sc in cfg["scenes"]:
            for f in FAMILY_NAMES:
                if f == "full" or f not in keys:
                    continue
                rs = [r for r in recs if r["scene"] == sc and r["mode"] == mode and r["family"] == f]
                if not rs:
                    continue
                ok = [r for r in rs if r["psnr"] is None or r["psnr"] >= 40]
                rows.append(min(ok, key=lambda r: r["traced_fraction"]) if ok else
                            max(rs, key=lambda r: r["psnr"] or 1e9))
        put(docs / "results" / f"key_settings_{mode}.md",
            render("results/key_settings.md.j2", cfg=cfg, mode=mode, rows=rows))
    return written


def _full_render(result: dict, docs: Path) -> dict:
    """The context of results/full_render.md.j2."""
    cfg = result["config"]
    needed = result["needed_fraction"]
    scenes = cfg["scenes"]
    headline = [{"mode": m, "best": hd.get("best_psnr_at_most_15pct"), "cheap": hd.get("cheapest_40db_mean")}
                for m, hd in result["headline"].items()]
    need = []
    for mode in cfg["modes"]:
        setn = result["headline"].get(mode, {}).get("set_needed", {})
        fams = [f for f in FAMILY_NAMES if f != "full" and any(f in needed[s].get(mode, {}) for s in scenes)]
        need.append({"mode": mode, "rows": [{"family": f, "cells": [needed[s].get(mode, {}).get(f) for s in scenes],
                                             "set": setn.get(f)} for f in fams]})
    rules = []
    for fam, per in result["rule_vs_patent"].items():
        for mode, sc in per.items():
            rules.append({"family": fam, "mode": mode, "scenes": [{"scene": k, **v} for k, v in sorted(sc.items())]})
    temporal = None
    if result.get("temporal"):
        from .temporal import markdown
        temporal = markdown(result["temporal"], "../img/eval_temporal.png")
    figs = [{"kind": k, "mode": m, "path": f"img/eval_{k}_{m}.png"} for m in cfg["modes"] for k in ("pareto", "curves")
            if (docs / "img" / f"eval_{k}_{m}.png").is_file()]
    return {"cfg": cfg, "headline": headline, "needed": need, "rules": rules,
            "textured": "\n".join(textured_section(result)).strip(), "speedup": result.get("speedup") or [],
            "temporal": temporal.strip() if temporal else None, "figs": figs,
            "examples": result.get("examples") or []}


def main(argv=None):
    """Rewrite the results pages from the committed records: no rendering, no sweep."""
    import argparse
    ap = argparse.ArgumentParser(description=main.__doc__)
    ap.add_argument("--from-records", default=str(REPO / "data" / "results.json"), metavar="JSON",
                    help="the run's records (default data/results.json)")
    ap.add_argument("--docs-dir", default=str(REPO / "docs"))
    ap.add_argument("--data-dir", default=None, help="where the held-out record is read (default: the JSON's folder)")
    a = ap.parse_args(argv)
    src = Path(a.from_records)
    result = json.loads(src.read_text())
    for f in write_pages(result, Path(a.docs_dir), Path(a.data_dir) if a.data_dir else src.parent):
        print(f)


def _round(v):
    if isinstance(v, float):
        return float(f"{v:.5g}")
    if isinstance(v, dict):
        return {k: _round(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_round(x) for x in v]
    return v


# --- pictures ----------------------------------------------------------------------------

FAMILY_STYLE = {
    "grid2": ("grid 2 (bilinear)", "s", "tab:gray"), "grid4": ("grid 4 (bilinear)", "D", "tab:gray"),
    "checkerboard": ("checkerboard", "^", "tab:brown"),
    "single_traced": ("single level, borders traced (Fig. 5b)", "x", "tab:olive"),
    "single_borrowed": ("single level, borders borrowed ([0068])", "+", "tab:cyan"),
    "multi_L1_T16": ("patent L1 T16", ".", "tab:pink"), "multi_L2_T16": ("patent L2 T16", ".", "tab:purple"),
    "multi_L2_T32": ("patent L2 T32", ".", "tab:purple"),
    "multi_L3_T16": ("patent L3 T16", "o", "tab:blue"), "multi_L3_T32": ("patent L3 T32", "o", "navy"),
    "multi_L3_T16_fov": ("patent L3 T16 foveated", "v", "tab:green"),
    "multi_L3_T16_dilate": ("new rule: dilate, L3 T16", "P", "tab:orange"),
    "multi_L3_T16_linear": ("new rule: linear, L3 T16", "1", "chocolate"),
    "multi_L3_T16_lindilate": ("new rule: lindilate, L3 T16", "*", "tab:red"),
    "multi_L3_T16_diag": ("new rule: diag, L3 T16", "2", "gold"),
    "multi_L3_T32_lindilate": ("new rule: lindilate, L3 T32", "*", "darkred"),
    "dacs": ("DACS", "s", "tab:green"), "vrs_T8": ("VRS-like 8x8", "D", "tab:purple"),
    "vrs_T16": ("VRS-like 16x16", "d", "violet"),
    "multi_L3_T16_gbuf": ("new rule: G-buffer, L3 T16", "X", "teal"),
    "multi_L3_T16_gbuflindilate": ("new rule: G-buffer + lindilate, L3 T16", "X", "darkcyan"),
}


def plot_curves(records, mode, path, title):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    scenes = sorted({r["scene"] for r in records if r["mode"] == mode})
    if not scenes:
        return
    fig, axes = scene_grid(plt, len(scenes))
    for ax, sc in zip(axes.ravel(), scenes):
        for fam, (lab, mk, col) in FAMILY_STYLE.items():
            pts = sorted((r["traced_fraction"], capped(r["psnr"])) for r in records
                         if r["mode"] == mode and r["scene"] == sc and r["family"] == fam)
            if pts:
                ax.plot([100 * f for f, _ in pts], [p for _, p in pts], marker=mk, color=col, lw=0.8,
                        ms=4, label=lab)
        scene_panel(ax, sc, 60, 60)
        ax.axvline(15, color="k", lw=0.4, ls=":")
    finish_scene_grid(plt, fig, axes, len(scenes), "PSNR (dB)", title, path)


def plot_set(set_curves, mode, path, title):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fams = set_curves.get(mode, {})
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    allpts = []
    for fam, (lab, mk, col) in FAMILY_STYLE.items():
        pts = sorted((p["traced_fraction"], p["psnr_mean"]) for p in fams.get(fam, []))
        if pts:
            ax.plot([100 * f for f, _ in pts], [p for _, p in pts], marker=mk, color=col, lw=0.8, ms=4, label=lab)
            allpts += pts
    front = pareto(allpts)
    ax.plot([100 * f for f, _ in front], [p for _, p in front], color="k", lw=2, alpha=0.3, label="Pareto front (all)")
    ax.axhline(40, color="k", lw=0.4, ls=":")
    ax.axvline(15, color="k", lw=0.4, ls=":")
    ax.set_xlim(0, 60)
    ax.set_ylim(20, 60)
    ax.set_xlabel("mean traced pixels over the scene set (%)", fontsize=8)
    ax.set_ylabel("mean PSNR over the scene set (dB)", fontsize=8)
    ax.set_title(title, fontsize=9)
    ax.tick_params(labelsize=7)
    ax.legend(fontsize=6, ncol=2)
    fig.tight_layout()
    fig.savefig(path, dpi=70)
    plt.close(fig)


def example_strip(ref, res, panel_w):
    """frame | source map | error map (FLIP, magma), each downscaled to panel_w wide, and under
    them the source-code legend (the palette of msr_model.palette, as in make sim's summary)."""
    from PIL import Image
    import matplotlib
    _, emap = flip(ref, res.frame, want_map=True)
    err = (matplotlib.colormaps["magma"](np.clip(emap, 0, 1))[..., :3] * 255).astype(np.uint8)
    panels = [res.frame, source_rgb(res.source), err]
    h, w = ref.shape[:2]
    ph = max(1, round(panel_w * h / w))
    ims = [Image.fromarray(p).resize((panel_w, ph), Image.NEAREST if i == 1 else Image.BILINEAR)
           for i, p in enumerate(panels)]
    legend = legend_image(None, res.source)      # the levels present in the map
    strip = Image.new("RGB", (max(3 * panel_w + 8, legend.width), ph + legend.height), (255, 255, 255))
    for i, im in enumerate(ims):
        strip.paste(im, (i * (panel_w + 4), 0))
    strip.paste(legend, (0, ph))
    return strip


if __name__ == "__main__":
    main()
