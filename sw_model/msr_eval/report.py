"""Pictures and docs of an eval run: curves, set Pareto plots, example strips, and
docs/results.md with docs/img/ (scripts/eval.py --docs).

The hand-written discussion lives in docs/results_notes.md and is pasted in after the
headline, so a re-run refreshes every number and figure without losing the text.
"""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
from PIL import Image

from msr_model.palette import legend_image, source_rgb

from .metrics import capped, flip, pareto

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


HOW_TO_RERUN = """## How to rerun

    make eval                                  # quick run: 192x108, every scene, fast and heavy -> out/eval/
    make eval FULL=1                           # this page: 1920x1080, every scene, both modes, + docs/
    make eval FULL=1 EVAL_ARGS="--modes heavy" # the converged head-to-head alone (heavy renderer)
    make eval FULL=1 EVAL_ARGS="--conv-check"  # also the second-seed render of each converged reference
    make eval FULL=1 DASK_SCHEDULER=tcp://host:8786   # the sweep's tasks on an existing Dask cluster
    make eval DASK_SCHEDULER=serial            # everything in one process
    .venv/bin/python scripts/eval.py --report-only --docs   # only rewrite this page from out/eval/results.json
    make eval EVAL_ARGS="--conv-grid 16"       # converged references at one sample count (--no-conv: none)

The sweep (scenes x modes x methods x settings) runs as tasks on Dask distributed
(`msr_eval.sweep`): by default a LocalCluster with one worker per CPU; `DASK_SCHEDULER=` or the
environment variable `MSR_DASK_SCHEDULER` names an existing scheduler (its workers need this
repository's `sw_model` installed, `pip install -e sw_model`, and the renderer library at the
same path or `MSR_RENDER_LIB`). The records are the same, bit for bit, as a serial run's
(`scripts/tests/test_eval.py` compares a two-worker LocalCluster with the serial sweep); only
the wall-time fields differ. References and records are cached per scene and mode under
`out/eval/cache/` (keyed by the renderer library and the code); a scene and mode's records
are written as soon as its settings and key metrics are in (the key metrics run ahead of later
pairs' settings), so an interrupted run keeps every finished pair and resumes from there. At
full size the converged references and every finished scene's records are also written to
`docs/converged/` (committed; [converged/README.md](converged/README.md)), and a run on another
machine takes them back where they are provably the same computation, so the two-hour run can
be finished in parts. The speed-up table is measured afterwards in the main process, alone. Code:
`scripts/eval.py` (command line), `msr_eval.metrics`, `msr_eval.sweep`, `msr_eval.report`.
"""


def _pct(f, how=None):
    if f is None:
        return "not reached"
    s = f"{100 * f:.1f}"
    return f"<= {s}" if how == "at_or_below" else s


def _db(p):
    return "exact" if p is None else f"{p:.2f}"


def _small_png(src: Path, dst: Path, max_w: int, colors: int | None = 128):
    """Downscaled PNG; plots are palette-quantised, example frames are not (banding)."""
    im = Image.open(src).convert("RGB")
    if im.width > max_w:
        im = im.resize((max_w, round(im.height * max_w / im.width)), Image.LANCZOS)
    if colors:
        im = im.quantize(colors=colors, method=Image.Quantize.MEDIANCUT)
    dst.parent.mkdir(parents=True, exist_ok=True)
    im.save(dst, optimize=True)


def write_docs(result: dict, out: Path, docs: Path):
    cfg = result["config"]
    img = docs / "img"
    img.mkdir(parents=True, exist_ok=True)
    figs = []
    for mode in cfg["modes"]:
        for kind in ("pareto", "curves"):
            src = out / f"{kind}_{mode}.png"
            if src.is_file():
                _small_png(src, img / f"eval_{kind}_{mode}.png", 900)
                figs.append((kind, mode, f"img/eval_{kind}_{mode}.png"))
    for ex in result["examples"]:
        _small_png(out / ex["file"], img / f"eval_{ex['file']}", 968, None)
        ex["doc_file"] = f"img/eval_{ex['file']}"

    L = []
    w = L.append
    w("# Image quality against traced pixels\n")
    w(f"Generated by `make eval FULL=1` (scripts/eval.py) on {cfg['date_utc']}, commit {cfg['git']}, "
      f"{cfg['width']}x{cfg['height']}, renderer backend `{cfg['backend']}` (library {cfg['renderer_lib']}), "
      f"modes {', '.join(cfg['modes'])}, run time {cfg['runtime_s'] / 60:.0f} min. Raw numbers: "
      "`out/eval/results.json` (every scene x method x setting; copied to docs/results.json).\n")
    w(f"Scene set ({len(cfg['scenes'])}): " + ", ".join(f"`{s}`" for s in cfg["scene_sources"]) + "\n")
    notes = docs / "results_notes.md"
    if result.get("head_to_head"):                # the converged head-to-head leads (msr_eval.headline)
        from .headline import docs_lines as head_lines
        fig = None
        src = out / "fronts_headline.png"
        if src.is_file():
            _small_png(src, img / "eval_fronts_headline.png", 1100)
            fig = "img/eval_fronts_headline.png"
        heldout = None
        hfs = sorted((docs / "converged").glob("heldout_*.json"))
        if hfs:                                   # scripts/eval.py --heldout
            heldout = json.loads(hfs[-1].read_text())
        L.extend(head_lines(result["head_to_head"], cfg, fig, result.get("head_to_head_references"), heldout))
        hnotes = docs / "results_headline_notes.md"       # hand-written findings, pasted in
        if hnotes.is_file():
            w(hnotes.read_text())
    w(HOW_TO_RERUN)
    if result.get("converged"):                   # the converged comparison leads (msr_eval.reference)
        from .conv_report import docs_lines
        cfigs = []
        for mode in cfg["modes"]:
            src = out / f"fronts_conv_{mode}.png"
            if src.is_file():
                _small_png(src, img / f"eval_fronts_conv_{mode}.png", 900)
                cfigs.append((mode, f"img/eval_fronts_conv_{mode}.png"))
        cnotes = docs / "results_converged_notes.md"      # hand-written findings, pasted in
        L.extend(docs_lines({**result, "_conv_notes": cnotes.read_text() if cnotes.is_file() else None}, cfigs))
        w("## Against the renderer's own full render\n")
        w("Everything below scores against the renderer's full render of the same mode (the "
          "evaluation's original reference), as before.\n")

    w("## Headline\n")
    for mode, h in result["headline"].items():
        b, c = h["best_psnr_at_most_15pct"], h["cheapest_40db_mean"]
        line = f"- **{mode}** renderer: "
        if b:
            line += (f"best mean PSNR with <= 15 % traced: **{b['psnr_mean']:.2f} dB** (worst scene "
                     f"{b['psnr_min']:.2f} dB) at {100 * b['traced_fraction']:.1f} % traced, "
                     f"{FAMILY_NAMES.get(b['family'], b['family'])}, {b['label']}. ")
        if c:
            line += (f"Cheapest setting with >= 40 dB mean: {100 * c['traced_fraction']:.1f} % traced "
                     f"({FAMILY_NAMES.get(c['family'], c['family'])}, {c['label']}, worst scene {c['psnr_min']:.2f} dB).")
        w(line)
    w("")
    if notes.is_file():
        w(notes.read_text())

    w("## Traced fraction needed for 35 dB and 40 dB\n")
    w("Per scene and method: the traced fraction (%) at which the method's PSNR first reaches the "
      "target. Taken on the method's Pareto front over its threshold sweep (settings sorted by "
      "traced fraction, keeping only those that beat every cheaper one), linearly interpolated in "
      "(fraction, PSNR) between the two front points around the target. `<= x`: even the cheapest "
      "setting of the sweep reaches it (x is that setting's fraction); `not reached`: no setting "
      "does. Single-setting methods (grids, checkerboard) give their own fraction or `not reached`.\n")
    needed = result["needed_fraction"]
    scenes = cfg["scenes"]
    for mode in cfg["modes"]:
        fams = [f for f in FAMILY_NAMES if any(f in needed[s].get(mode, {}) for s in scenes) and f != "full"]
        w(f"### {mode} renderer\n")
        w("| method | " + " | ".join(f"{s} 35 / 40" for s in scenes) + " | set mean 35 / 40 |")
        w("|---" * (len(scenes) + 2) + "|")
        setn = result["headline"].get(mode, {}).get("set_needed", {})
        for f in fams:
            cells = []
            for s in scenes:
                d = needed[s].get(mode, {}).get(f)
                cells.append("-" if d is None else
                             f"{_pct(d['35']['fraction'], d['35']['how'])} / {_pct(d['40']['fraction'], d['40']['how'])}")
            d = setn.get(f)
            cells.append("-" if d is None else
                         f"{_pct(d['35']['fraction'], d['35']['how'])} / {_pct(d['40']['fraction'], d['40']['how'])}")
            w(f"| {FAMILY_NAMES[f]} | " + " | ".join(cells) + " |")
        w("")

    from .textured import section as textured_section  # noqa: PLC0415 - it imports this module
    L.extend(textured_section(result))

    w("## New decision rules against the patent's rule\n")
    w("PSNR of the rule minus the PSNR of the patent's rule (L=3, T=16, same threshold scales) at "
      "the same traced fraction, the patent's value interpolated along its Pareto front; over the "
      "rule's settings that fall inside the patent curve's range. Positive = the new rule is better.\n")
    rc = result["rule_vs_patent"]
    for fam in ("multi_L3_T16_dilate", "multi_L3_T16_linear", "multi_L3_T16_lindilate", "multi_L3_T16_diag"):
        if fam not in rc:
            continue
        for mode, per in rc[fam].items():
            w(f"- {FAMILY_NAMES[fam]}, {mode}: " + "; ".join(
                f"{s} {v['mean_delta_db']:+.2f} dB (min {v['min_delta_db']:+.2f}, max {v['max_delta_db']:+.2f}, n={v['n']})"
                if v["n"] else f"{s} no overlap" for s, v in sorted(per.items())))
    w("")

    w("## Quality at the key settings (PSNR / SSIM / FLIP)\n")
    w("For each scene, mode and method, the cheapest setting of its sweep that reaches 40 dB "
      "(or its best setting if none does). FLIP: NVIDIA FLIP (flip-evaluator, LDR, 67 ppd), mean "
      "error, lower is better.\n")
    for mode in cfg["modes"]:
        w(f"### {mode} renderer\n")
        w("| scene | method | setting | traced % | PSNR dB | SSIM | FLIP |")
        w("|---|---|---|---|---|---|---|")
        for s in scenes:
            for f in FAMILY_NAMES:
                if f == "full":
                    continue
                rs = [r for r in result["records"] if r["scene"] == s and r["mode"] == mode and r["family"] == f]
                if not rs:
                    continue
                ok = [r for r in rs if r["psnr"] is None or r["psnr"] >= 40]
                r = min(ok, key=lambda r: r["traced_fraction"]) if ok else max(rs, key=lambda r: r["psnr"] or 1e9)
                ss = f"{r['ssim']:.4f}" if "ssim" in r else "-"
                fl = f"{r['flip']:.4f}" if "flip" in r else "-"
                w(f"| {s} | {FAMILY_NAMES[f]} | {r['label']} | {100 * r['traced_fraction']:.1f} | "
                  f"{_db(r['psnr'])} | {ss} | {fl} |")
        w("")

    if result["speedup"]:
        w("## Wall-time speedup on the live renderer\n")
        w("Selective render (decisions included, the renderer asked pass by pass as the golden model "
          "does) against the full render, same renderer object type, same frame size; the setting is "
          "the cheapest of the family that reaches 40 dB on that scene. `bit-equal`: the live run gave "
          "the same frame as the run on the cached reference.\n")
        w("| scene | mode | method | setting | traced % | full s | selective s | speedup | bit-equal |")
        w("|---|---|---|---|---|---|---|---|---|")
        for s in result["speedup"]:
            w(f"| {s['scene']} | {s['mode']} | {FAMILY_NAMES.get(s['family'], s['family'])} | {s['label']} | "
              f"{100 * s['traced_fraction']:.1f} | {s['full_render_s']:.2f} | {s['selective_s']:.2f} | "
              f"{s['speedup']:.2f}x | {s['bit_equal_to_cached_run']} |")
        w("")

    w("## Figures\n")
    for kind, mode, path in figs:
        what = "Mean over the scene set (Pareto front)" if kind == "pareto" else "Per scene"
        w(f"{what}, {mode} renderer:\n\n![{kind} {mode}]({path})\n")
    if result["examples"]:
        w("Examples (frame | source map in the palette of `msr_model.palette`, the same as `make sim`'s "
          "summary.png, legend under each strip | FLIP error map, magma, black = no error):\n")
        for ex in result["examples"]:
            w(f"- `{ex['scene']}`, {ex['mode']}, {FAMILY_NAMES.get(ex['family'], ex['family'])} {ex['label']}: "
              f"{100 * ex['traced_fraction']:.1f} % traced, {_db(ex['psnr'])} dB\n\n  ![{ex['scene']}]({ex['doc_file']})\n")
    L.extend(appendices(docs))
    (docs / "results.md").write_text("\n".join(L) + "\n")
    # compact copy for the repository: floats to 5 significant digits, no indentation
    (docs / "results.json").write_text(json.dumps(_round(result), separators=(",", ":")))


# Earlier runs kept on the same page (issue 30, one results page): (file under docs/appendix/,
# title). Their own headings move two levels down; links into docs/ are rebased.
APPENDICES = (
    ("quick_converged.md", "Appendix A: the converged comparison at the quick size (192x108, 13 scenes, both modes)"),
    ("fast_16spp_1080p.md", "Appendix B: the complete 1920x1080 run against the 16-spp full render, both modes "
                            "(2026-11-30, 13 scenes, textured ones included)"),
)


def appendices(docs: Path) -> list[str]:
    """The appendix sections of results.md from docs/appendix/ (missing files are skipped)."""
    import re
    out = []
    for name, title in APPENDICES:
        f = docs / "appendix" / name
        if not f.is_file():
            continue
        out.append(f"## {title}\n")
        out.append(f"Kept as generated (source: [appendix/{name}](appendix/{name})).\n")
        for line in f.read_text().splitlines():
            if line.startswith("#"):
                line = "##" + line if not line.startswith("# ") else "### " + line[2:]
            line = re.sub(r"\]\((?!https?:|#)([^)]+)\)", lambda m: f"]({_rebase(m.group(1), name)})", line)
            out.append(line)
        out.append("")
    return out


def _rebase(link: str, name: str) -> str:
    """A relative link of an appendix page (written for docs/ or docs/eval_1080p/) as seen from docs/."""
    if not name.startswith("fast_16spp"):         # written in docs/: its links hold as they are
        return link
    if link.startswith("img/"):
        return "appendix/" + link
    return link[3:] if link.startswith("../") else "appendix/" + link


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


def scene_grid(plt, nscenes):
    """The figure of a per-scene plot (plot_curves, conv_report.plot_scene_fronts): one small
    panel a scene, four a row. Returns (fig, axes), axes 2-D."""
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
