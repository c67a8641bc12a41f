"""The comparison against the converged reference (msr_eval.reference): head-to-head
summaries, the section that leads docs/results.md, a page of its own (--conv-page) and the
per-scene Pareto-front plots. Docs code only: the record cache does not depend on this file."""
from __future__ import annotations

from .metrics import TARGETS_DB, capped, fraction_for, pareto, rule_comparison
from .present import db, finish_scene_grid, needed_cell, pct, scene_grid, scene_panel, small_png
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


# --- the docs section (docs/results.md leads with it) -------------------------------------------

NAMES = {"full": "full render (every pixel)", "dacs": "DACS (variance threshold)",
         "vrs_T8": "VRS-like, 8x8 tiles", "vrs_T16": "VRS-like, 16x16 tiles", "checkerboard": "checkerboard",
         "multi_L3_T16": "patent, L=3, T=16", "multi_L3_T32": "patent, L=3, T=32",
         "multi_L3_T16_dilate": "**new** dilate, L=3, T=16", "multi_L3_T16_lindilate": "**new** lindilate, L=3, T=16",
         "multi_L3_T32_lindilate": "**new** lindilate, L=3, T=32"}
H2H = ("full", "multi_L3_T16", "multi_L3_T32", "multi_L3_T16_dilate", "multi_L3_T16_lindilate",
       "multi_L3_T32_lindilate", "dacs", "vrs_T8", "vrs_T16", "checkerboard")


def _cell(b):
    return "not reached" if b is None else f"{pct(b[1], b[2])} ({NAMES.get(b[0], b[0]).replace('**', '')})"


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


def _db_or_dash(p):
    return "-" if p is None else f"{p:.2f}"


def comparisons(records, modes):
    """Where DACS or the VRS-like baseline beats the patent's rule or ours: per mode and scene,
    their fractions for 35 and 40 dB side by side, and the PSNR difference at equal traced
    fraction (metrics.rule_comparison on the converged scores)."""
    conv = as_conv(records)
    out = {}
    for base in ("multi_L3_T16", "multi_L3_T32_lindilate"):
        out[base] = rule_comparison(conv, base=base, others=("dacs", "vrs_T8", "vrs_T16", "checkerboard"))
    return out


def docs_lines(result: dict, figs: list) -> list[str]:
    cfg, conv = result["config"], result["converged"]
    needed = conv["needed_fraction"]
    recs = result["records"]
    scenes = cfg["scenes"]
    # the modes that have a converged reference (at full size the heavy renderer alone)
    modes = [m for m in cfg["modes"] if any(r["mode"] == m and "psnr_conv" in r for r in recs)]
    L = []
    w = L.append
    w("## Against the converged reference\n")
    w("The evaluation leads with these numbers. The renderer's own full render is not the truth: in heavy "
      "mode it carries the noise of 16 samples per pixel, so scored against it an interpolated pixel "
      "(a local average, nearer the noise-free image) counts as error and a traced pixel's noise counts "
      "as exact. The **converged reference** is the same renderer, scene, view and size with many "
      "samples per pixel: per scene and mode the first of "
      + "; ".join(f"{m} mode {' / '.join(str(g * g) for g in gs)}" for m, gs in conv["conv_grids"].items())
      + f" samples per pixel whose render has a PSNR of at least {conv['target_two_seeds_db']:g} dB against "
      "a second render with another seed (else the largest count)"
      + " (`msr_eval.reference`; heavy: one area-light point and one AO ray per sample; fast: the same "
      "noise-free shading, antialiased, so the fast mode's aliasing shows). How the sample counts were "
      "chosen: [dacs.md](dacs.md#the-converged-reference). The scores against the full render follow "
      "further down, unchanged.\n")
    w("### The references\n")
    w("`two seeds`: PSNR between the reference and a second render with another seed (each one's own "
      "error against the noise-free image is then about 3 dB better); `top 1 %`: the share of that "
      "difference's squared error held by the worst 1 % of pixels. `full render`: the renderer's plain "
      "full render (16 samples heavy, 1 fast) scored against the converged reference.\n")
    w("| scene | mode | spp | two seeds dB | worst 32x32 tile, two seeds | top 1 % | full render PSNR | SSIM | FLIP | worst 32x32 tile |")
    w("|---|---|---|---|---|---|---|---|---|---|")
    tried = []
    for fr in result["full_render"]:
        c = fr.get("converged")
        if not c:
            continue
        r = next((r for r in recs if r["scene"] == fr["scene"] and r["mode"] == fr["mode"] and r["family"] == "full"), None)
        if r is None:
            continue
        two = c.get("psnr_two_seeds")
        w(f"| {fr['scene']} | {fr['mode']} | {c['spp']} | {db(two) if 'psnr_two_seeds' in c else '-'} | "
          f"{c['tile_min_psnr_two_seeds']:.2f} | {100 * c.get('mse_share_top1pct', 0):.0f} % | "
          if "tile_min_psnr_two_seeds" in c else
          f"| {fr['scene']} | {fr['mode']} | {c['spp']} | - | - | - | ")
        L[-1] += (f"{db(r['psnr_conv'])} | {r['ssim_conv']:.4f} | " if "ssim_conv" in r else f"{db(r['psnr_conv'])} | - | ")
        L[-1] += (f"{r['flip_conv']:.4f} | " if "flip_conv" in r else "- | ") + f"{r['tile32_min_psnr_conv']:.2f} |"
        if len(c.get("tried", [])) > 1:
            tried.append(f"{fr['scene']} {fr['mode']}: " + ", ".join(
                f"{t['spp']} spp {db(t['psnr_two_seeds'])} dB" for t in c["tried"]))
    w("")
    if tried:
        w("Scenes that needed more than the first count (two-seed PSNR per count tried): " + "; ".join(tried) + ".\n")
    for mode in modes:
        w(f"### Head to head, {mode} renderer: traced % for 40 dB (35 dB) against the converged reference\n")
        w("Per scene the cheapest family of each group (interpolated on its Pareto front, as below). "
          "Patent = the patent's rule (L=3, T=16 or T=32); ours = the new dilate / lindilate rules; "
          "VRS-like = 8x8 or 16x16 rate tiles. `not reached`: no setting of the group gets there.\n")
        w("| scene | patent 40 (35) | ours 40 (35) | DACS 40 (35) | VRS-like 40 (35) | checkerboard 40 (35) | full render |")
        w("|---|---|---|---|---|---|---|")
        h40 = head_to_head(needed, scenes, mode, "40")
        h35 = head_to_head(needed, scenes, mode, "35")
        worst = {k: [] for k in ("patent", "ours", "dacs", "vrs", "checkerboard")}
        for a, b in zip(h40, h35):
            full = next((r for r in recs if r["scene"] == a["scene"] and r["mode"] == mode and r["family"] == "full"), None)
            cells = []
            for k in worst:
                x, y = a[k], b[k]
                worst[k].append((a["scene"], x[1] if x else None))
                cells.append(f"{pct(x[1], x[2]) if x else 'not reached'} ({pct(y[1], y[2]) if y else 'not reached'})")
            w(f"| {a['scene']} | " + " | ".join(cells) + f" | {db(full['psnr_conv']) + ' dB' if full else '-'} |")
        cells = []
        for k, v in worst.items():
            miss = [s for s, f in v if f is None]
            if miss:
                cells.append(f"not reached on {len(miss)} ({', '.join(miss[:3])}{', ...' if len(miss) > 3 else ''})")
            elif v:
                s, f = max(v, key=lambda t: t[1])
                cells.append(f"{100 * f:.1f} ({s})")
            else:
                cells.append("-")
        w("| **worst scene** | " + " | ".join(cells) + " | |")
        w("")
        w(f"Worst 32x32 tile ({mode} renderer): the PSNR of the worst 32x32 tile against the converged "
          "reference at the group's cheapest setting reaching 40 dB (`*`: none does; its setting with "
          "the best PSNR), with that setting's traced %.\n")
        w("| scene | patent | ours | DACS | VRS-like | checkerboard |")
        w("|---|---|---|---|---|---|")
        for sc in scenes:
            cells = []
            for fams in (PATENT, OURS, ("dacs",), ("vrs_T8", "vrs_T16"), ("checkerboard",)):
                picks = [pick_near_conv(recs, sc, mode, f, 40.0) for f in fams]
                picks = [r for r in picks if r is not None]
                ok = [r for r in picks if capped(r["psnr_conv"]) >= 40.0]
                r = (min(ok, key=lambda r: r["traced_fraction"]) if ok else
                     max(picks, key=lambda r: capped(r["psnr_conv"])) if picks else None)
                cells.append("-" if r is None else f"{r['tile32_min_psnr_conv']:.1f} dB at "
                             f"{100 * r['traced_fraction']:.1f} %{'' if ok else ' *'}")
            w(f"| {sc} | " + " | ".join(cells) + " |")
        w("")
    for mode in modes:
        w(f"### PSNR against the converged reference at 10 % and 20 % traced, {mode} renderer\n")
        w("Each group's Pareto front (best of its families) interpolated at the fraction; `-` where the "
          "group's settings do not span it. Comparable even where 40 dB is out of reach.\n")
        w("| scene | patent 10 % / 20 % | ours 10 % / 20 % | DACS 10 % / 20 % | VRS-like 10 % / 20 % | checkerboard (50 %) |")
        w("|---|---|---|---|---|---|")
        for s in scenes:
            rs = [r for r in recs if r["scene"] == s and r["mode"] == mode and "psnr_conv" in r]
            cells = []
            for fams in (PATENT, OURS, ("dacs",), ("vrs_T8", "vrs_T16")):
                pts = [(r["traced_fraction"], capped(r["psnr_conv"])) for r in rs if r["family"] in fams]
                cells.append(" / ".join(_db_or_dash(psnr_at(pts, f)) for f in (0.10, 0.20)))
            cb = [r for r in rs if r["family"] == "checkerboard"]
            cells.append(db(cb[0]["psnr_conv"]) if cb else "-")
            w(f"| {s} | " + " | ".join(cells) + " |")
        w("")
    notes = result.get("_conv_notes")             # hand-written findings (docs/results_converged_notes.md)
    if notes:
        w(notes)
    cmp_ = comparisons(recs, modes)
    w("### DACS and VRS-like against the patent's rule and ours, at equal traced fraction\n")
    w("Mean PSNR difference (against the converged reference) of the peer minus the base, at the "
      "peer's settings that fall inside the base's curve (the base interpolated on its Pareto front); "
      "positive = the peer is better there. Base: the patent's rule (L=3, T=16) and our lindilate "
      "rule (L=3, T=32).\n")
    for base, per in cmp_.items():
        for fam in ("dacs", "vrs_T8", "vrs_T16", "checkerboard"):
            for mode, sc in per.get(fam, {}).items():
                w(f"- {NAMES[fam]} vs {NAMES[base].replace('**', '')}, {mode}: " + "; ".join(
                    f"{s} {v['mean_delta_db']:+.2f} dB (min {v['min_delta_db']:+.2f}, max {v['max_delta_db']:+.2f}, n={v['n']})"
                    if v["n"] else f"{s} no overlap" for s, v in sorted(sc.items())))
    w("")
    for mode in modes:
        w(f"### Traced fraction for 35 / 40 dB against the converged reference, {mode} renderer\n")
        w("| method | " + " | ".join(f"{s} 35 / 40" for s in scenes) + " | worst scene 40 |")
        w("|---" * (len(scenes) + 2) + "|")
        fams = []
        for r in recs:
            if r["mode"] == mode and r["family"] not in fams:
                fams.append(r["family"])
        for f in fams:
            cells, w40 = [], []
            for s in scenes:
                d = needed.get(s, {}).get(mode, {}).get(f)
                if d is None:
                    cells.append("-")
                    continue
                cells.append(needed_cell(d))
                w40.append((s, d["40"]["fraction"]))
            miss = [s for s, x in w40 if x is None]
            worst = (f"not reached on {len(miss)}" if miss else
                     (lambda t: f"{100 * t[1]:.1f} ({t[0]})")(max(w40, key=lambda t: t[1])) if w40 else "-")
            w(f"| {NAMES.get(f, f)} | " + " | ".join(cells) + f" | {worst} |")
        w("")
        w(f"### At the cheapest setting for 40 dB against the converged reference, {mode} renderer\n")
        w("Per scene and family, the cheapest setting reaching 40 dB against the converged reference "
          "(else its best there): traced %, PSNR / SSIM / FLIP against the converged reference, the "
          "worst 32x32 tile's PSNR (the local failure a mean hides), and the PSNR of the same frame "
          "against the renderer's full render.\n")
        w("| scene | method | setting | traced % | PSNR conv | worst 32x32 tile | SSIM conv | FLIP conv | PSNR vs full render |")
        w("|---|---|---|---|---|---|---|---|---|")
        for s in scenes:
            for f in H2H:
                r = pick_near_conv(recs, s, mode, f, 40.0)
                if r is None:
                    continue
                ss = f"{r['ssim_conv']:.4f}" if "ssim_conv" in r else "-"
                fl = f"{r['flip_conv']:.4f}" if "flip_conv" in r else "-"
                w(f"| {s} | {NAMES.get(f, f)} | {r['label']} | {100 * r['traced_fraction']:.1f} | {db(r['psnr_conv'])} | "
                  f"{r['tile32_min_psnr_conv']:.2f} | {ss} | {fl} | {db(r['psnr'])} |")
        w("")
    for mode, path in figs:
        w(f"Pareto fronts against the converged reference, {mode} renderer (patent, ours, DACS, VRS-like, "
          f"checkerboard; x = the plain full render):\n\n![fronts {mode}]({path})\n")
    return L


def _rel(path):
    from pathlib import Path
    try:
        return str(Path(path).resolve().relative_to(Path(__file__).resolve().parents[2]))
    except ValueError:
        return str(path)


def write_page(result: dict, out, docs, name: str = "results_converged.md"):
    """A page of its own with the converged comparison only (docs/NAME, figures in docs/img/):
    for a run whose size differs from docs/results.md's (the quick run)."""
    from pathlib import Path
    out, docs = Path(out), Path(docs)
    cfg = result["config"]
    figs = []
    for mode in cfg["modes"]:
        src = out / f"fronts_conv_{mode}.png"
        if src.is_file():
            rel = f"img/conv_fronts_{cfg['width']}x{cfg['height']}_{mode}.png"
            small_png(src, docs / rel, 900)
            figs.append((mode, rel))
    head = [f"# Against the converged reference, {cfg['width']}x{cfg['height']}\n",
            f"Generated by `scripts/eval.py [--report-only] --out {_rel(out)} --conv-page {name}` (run of "
            f"{cfg['date_utc']}, commit "
            f"{cfg['git']}), {cfg['width']}x{cfg['height']}, renderer library {cfg['renderer_lib']}, modes "
            f"{', '.join(cfg['modes'])}, {len(cfg['scenes'])} scenes, run time {cfg['runtime_s'] / 60:.0f} min. "
            "The same section leads [results.md](results.md) once a full run (`make eval FULL=1`) has "
            "produced it at 1920x1080. Methods and choices: [dacs.md](dacs.md).\n"]
    notes = docs / "results_converged_notes.md"
    lines = docs_lines({**result, "_conv_notes": notes.read_text() if notes.is_file() else None}, figs)
    lines = [ln.replace(" The scores against the full render follow further down, unchanged.",
                        " The scores of the same run against the full render: its results.json.") for ln in lines]
    (docs / name).write_text("\n".join(head + lines[1:]) + "\n")
