"""The comparison against the converged reference (msr_eval.reference): head-to-head
summaries, the numbers of docs/results/converged.md, a page of its own (--conv-page) and the
per-scene Pareto-front plots. Docs code only: the record cache does not depend on this file."""
from __future__ import annotations

from .metrics import TARGETS_DB, capped, fraction_for, pareto, rule_comparison
from .present import FAMILY_NAMES, finish_scene_grid, render, scene_grid, scene_panel, small_png
from .reference import as_conv, pick_near_conv


# --- the comparison's families ----------------------------------------------------------------

PATENT = ("multi_L3_T16", "multi_L3_T32")                       # the patent's rule
OURS = ("multi_L3_T16_dilate", "multi_L3_T16_lindilate", "multi_L3_T32_lindilate")  # our best rules
PEERS = {"dacs": "DACS", "vrs_T8": "VRS-like 8x8", "vrs_T16": "VRS-like 16x16", "checkerboard": "checkerboard"}


def needed_conv(records):
    """{scene: {mode: {family: {"35": {...}, "40": {...}}}}} against the converged reference."""
    pts = {}
    for r in records:
        if "psnr_conv" in r:
            pts.setdefault(r["scene"], {}).setdefault(r["mode"], {}).setdefault(r["family"], []).append(
                (r["traced_fraction"], capped(r["psnr_conv"])))
    return {s: {m: {f: {str(int(t)): dict(zip(("fraction", "how"), fraction_for(p, t))) for t in TARGETS_DB}
                    for f, p in fams.items()} for m, fams in ms.items()} for s, ms in pts.items()}


def best_of(need_scene_mode: dict, fams, target="40"):
    """The family among `fams` that needs the least for the target: (family, fraction, how)."""
    best = None
    for f in fams:
        d = need_scene_mode.get(f, {}).get(target)
        if d is None or d["fraction"] is None:
            continue
        if best is None or d["fraction"] < best[1]:
            best = (f, d["fraction"], d["how"])
    return best


def head_to_head(needed: dict, scenes, mode, target="40"):
    """Per scene: the fraction for `target` dB of the patent's rule (best of PATENT), ours (best
    of OURS), DACS, VRS-like (best of the two tiles) and checkerboard; None when not reached."""
    rows = []
    for s in scenes:
        nm = needed.get(s, {}).get(mode, {})
        row = {"scene": s, "patent": best_of(nm, PATENT, target), "ours": best_of(nm, OURS, target),
               "dacs": best_of(nm, ("dacs",), target), "vrs": best_of(nm, ("vrs_T8", "vrs_T16"), target),
               "checkerboard": best_of(nm, ("checkerboard",), target)}
        rows.append(row)
    return rows


def plot_scene_fronts(records, mode, path, title):
    """Per scene, the Pareto fronts against the converged reference of the patent's rule, ours,
    DACS, the VRS-like baseline and checkerboard (plus the plain full render as a point)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    groups = [("patent (L3, T16/T32)", PATENT, "tab:blue", "o"), ("ours (dilate / lindilate)", OURS, "tab:red", "*"),
              ("DACS", ("dacs",), "tab:green", "s"), ("VRS-like 8x8", ("vrs_T8",), "tab:purple", "D"),
              ("VRS-like 16x16", ("vrs_T16",), "violet", "d"), ("checkerboard", ("checkerboard",), "tab:brown", "^")]
    scenes = sorted({r["scene"] for r in records if r["mode"] == mode and "psnr_conv" in r})
    if not scenes:
        return
    fig, axes = scene_grid(plt, len(scenes))
    for ax, sc in zip(axes.ravel(), scenes):
        rs = [r for r in records if r["mode"] == mode and r["scene"] == sc and "psnr_conv" in r]
        for lab, fams, col, mk in groups:
            front = pareto([(r["traced_fraction"], capped(r["psnr_conv"])) for r in rs if r["family"] in fams])
            if front:
                ax.plot([100 * f for f, _ in front], [p for _, p in front], marker=mk, color=col, lw=0.9, ms=3.5,
                        label=lab)
        full = [r for r in rs if r["family"] == "full"]
        if full:
            ax.plot([100], [capped(full[0]["psnr_conv"])], marker="x", color="k", ls="", ms=5,
                    label="full render (every pixel)")
        scene_panel(ax, sc, 102, 50)
        ax.axhline(35, color="k", lw=0.3, ls=":")
    finish_scene_grid(plt, fig, axes, len(scenes), "PSNR against the converged reference (dB)", title, path)


# --- the pages' tables (docs/results/converged.md) ------------------------------------------------

NAMES = {"full": "full render (every pixel)", "dacs": "DACS (variance threshold)",
         "vrs_T8": "VRS-like, 8x8 tiles", "vrs_T16": "VRS-like, 16x16 tiles", "checkerboard": "checkerboard",
         "multi_L3_T16": "patent, L=3, T=16", "multi_L3_T32": "patent, L=3, T=32",
         "multi_L3_T16_dilate": "**new** dilate, L=3, T=16", "multi_L3_T16_lindilate": "**new** lindilate, L=3, T=16",
         "multi_L3_T32_lindilate": "**new** lindilate, L=3, T=32"}
H2H = ("full", "multi_L3_T16", "multi_L3_T32", "multi_L3_T16_dilate", "multi_L3_T16_lindilate",
       "multi_L3_T32_lindilate", "dacs", "vrs_T8", "vrs_T16", "checkerboard")


def psnr_at(points, fraction):
    """PSNR of a family's Pareto front at a traced fraction (linear between front points; the
    front's best PSNR at or below the fraction is kept where the front is flat); None outside."""
    front = pareto(points)
    if not front or fraction < front[0][0]:
        return None
    best = None
    for (f1, p1), (f2, p2) in zip(front, front[1:]):
        if f1 <= fraction <= f2:
            return p1 + (fraction - f1) / (f2 - f1) * (p2 - p1) if f2 > f1 else max(p1, p2)
    if fraction >= front[-1][0]:
        best = front[-1][1]
    return best


def comparisons(records, modes):
    """Where DACS or the VRS-like baseline beats the patent's rule or ours: per mode and scene,
    their fractions for 35 and 40 dB side by side, and the PSNR difference at equal traced
    fraction (metrics.rule_comparison on the converged scores)."""
    conv = as_conv(records)
    out = {}
    for base in ("multi_L3_T16", "multi_L3_T32_lindilate"):
        out[base] = rule_comparison(conv, base=base, others=("dacs", "vrs_T8", "vrs_T16", "checkerboard"))
    return out


def context(result: dict) -> dict:
    """The numbers of the converged detail tables (templates/results/converged.md.j2): the
    references, per family the fractions for 35 / 40 dB, the cheapest setting for 40 dB of the
    head-to-head families, and the peers against the patent's rule and ours at equal traced
    fraction. Nothing here is formatted; the template does that."""
    cfg, conv = result["config"], result["converged"]
    needed = conv["needed_fraction"]
    recs = result["records"]
    scenes = cfg["scenes"]
    modes = [m for m in cfg["modes"] if any(r["mode"] == m and "psnr_conv" in r for r in recs)]
    full = {(r["scene"], r["mode"]): r for r in recs if r["family"] == "full" and "psnr_conv" in r}
    refs, tried = [], []
    for fr in result["full_render"]:
        c = fr.get("converged")
        r = full.get((fr["scene"], fr["mode"]))
        if not c or r is None:
            continue
        refs.append({"scene": fr["scene"], "mode": fr["mode"], "spp": c["spp"], "two": c.get("psnr_two_seeds"),
                     "tile_two": c.get("tile_min_psnr_two_seeds"), "top1": c.get("mse_share_top1pct"),
                     "psnr": r["psnr_conv"], "ssim": r.get("ssim_conv"), "flip": r.get("flip_conv"),
                     "tile": r.get("tile32_min_psnr_conv")})
        if len(c.get("tried", [])) > 1:
            tried.append({"scene": fr["scene"], "mode": fr["mode"], "tried": c["tried"]})
    per_mode = []
    for mode in modes:
        fams = list(dict.fromkeys(r["family"] for r in recs if r["mode"] == mode))
        rows = []
        for f in fams:
            cells = [needed.get(s, {}).get(mode, {}).get(f) for s in scenes]
            w40 = [(s, d["40"]["fraction"]) for s, d in zip(scenes, cells) if d is not None]
            miss = [s for s, x in w40 if x is None]
            worst = max(w40, key=lambda t: t[1]) if w40 and not miss else None
            rows.append({"family": NAMES.get(f, FAMILY_NAMES.get(f, f)), "cells": cells, "missed": len(miss),
                         "worst": worst})
        cheapest = []
        for s in scenes:
            for f in H2H:
                r = pick_near_conv(recs, s, mode, f, 40.0)
                if r is not None:
                    cheapest.append({"scene": s, "family": NAMES.get(f, f), "r": r})
        per_mode.append({"mode": mode, "rows": rows, "cheapest": cheapest})
    cmp_ = []
    for base, per in comparisons(recs, modes).items():
        for fam in ("dacs", "vrs_T8", "vrs_T16", "checkerboard"):
            for mode, sc in per.get(fam, {}).items():
                cmp_.append({"peer": NAMES[fam], "base": NAMES[base].replace("**", ""), "mode": mode,
                             "scenes": [{"scene": k, **v} for k, v in sorted(sc.items())]})
    return {"scenes": scenes, "refs": refs, "tried": tried, "per_mode": per_mode, "cmp": cmp_,
            "conv_grids": conv["conv_grids"], "target_db": conv["target_two_seeds_db"]}


def write_page(result: dict, out, docs, name: str = "results_converged.md"):
    """The converged detail alone as docs/NAME, figures in docs/img/: for a run whose size
    differs from the committed pages' (the quick run's --conv-page)."""
    from pathlib import Path
    out, docs = Path(out), Path(docs)
    cfg = result["config"]
    figs = []
    for mode in cfg["modes"]:
        src = out / f"fronts_conv_{mode}.png"
        if src.is_file():
            rel = f"img/conv_fronts_{cfg['width']}x{cfg['height']}_{mode}.png"
            small_png(src, docs / rel, 900)
            figs.append({"mode": mode, "path": rel})
    (docs / name).write_text(render("results/converged.md.j2", cfg=cfg, c=context(result), h=None, figs=figs,
                                    up=""))
