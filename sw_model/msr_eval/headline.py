"""The converged head-to-head that leads docs/results.md: per scene, the traced
fraction at which each group of methods is as close to the converged image as tracing every
pixel is, and the same 1 and 3 dB below that, beside the 40 and 35 dB points.

The equal-quality point. The heavy renderer's full render (16 samples per pixel) has its own
PSNR against the converged reference, `eq`. A method's frame mixes traced pixels (that noise)
with interpolated ones (local means: less noise, some bias), so it may reach `eq` below 100 %
traced. Every family can trace everything (threshold 0), so each family's front is closed by
the full render's point (100 %, eq): a family that never gets there below that reports 100 %.

Groups (one palette and one set of names for every table and plot of the page): each group's
front is its best family's figure (each family's own Pareto front), so a peer gets its best per
scene as ours does (DACS over both statistics; VRS-like over both tile sizes; the patent's rule and
ours over L = 2 and 3, T = 16 and 32, and three threshold shapes (s, 2s, 4s; s, 4s, 16s; s, 8s, 64s)). Docs code only: the record cache does not depend on this file.
"""
from __future__ import annotations

from .conv_report import psnr_at
from .metrics import capped, fraction_for, pareto
from .present import finish_scene_grid, scene_grid, scene_panel

# (key, name, families, colour, marker): the page's one palette
GROUPS = (
    ("patent", "patent (L2, L3; T16, T32)", ("multi_L3_T16", "multi_L3_T32", "multi_L2_T16", "multi_L2_T32",
                                                   "multi_L3_T32_r4", "multi_L3_T32_r8"),
     "tab:blue", "o"),
    ("lindilate", "ours: lindilate (L2, L3; T16, T32)", ("multi_L3_T16_lindilate", "multi_L3_T32_lindilate",
                                                         "multi_L2_T16_lindilate", "multi_L2_T32_lindilate",
                                                         "multi_L3_T32_lindilate_r4", "multi_L3_T32_lindilate_r8"),
     "tab:red", "*"),
    ("dilate", "ours: dilate (T16)", ("multi_L3_T16_dilate",), "salmon", "P"),
    ("lindilate2d", "new: lindilate2d (L2, L3; T16, T32)",
     ("multi_L3_T16_lindilate2d", "multi_L3_T32_lindilate2d", "multi_L2_T16_lindilate2d", "multi_L2_T32_lindilate2d",
      "multi_L3_T32_lindilate2d_r4", "multi_L3_T32_lindilate2d_r8", "multi_L2_T32_lindilate2d_r4"),
     "darkred", "X"),
    # the L = 4 extension (stride-16 initial grid, evaluation only; docs/rules.md "L = 4"): with
    # the patent's test it shows what the sparser grid alone gives
    ("lindilate2d4", "new: lindilate2d, L4 extension (T32)", ("multi_L4_T32_lindilate2d",), "darkorange", "v"),
    ("patent4", "patent's test, L4 extension (T32)", ("multi_L4_T32",), "tab:cyan", "<"),
    ("dacs", "DACS 4x4 (var, luma var)", ("dacs", "dacs_lumvar"), "tab:green", "s"),
    ("dacs8", "DACS 8x8, extension (var, luma var)", ("dacs_B8", "dacs_B8_lumvar"), "olive", "D"),
    ("vrs", "VRS-like tier 2 (8x8, 16x16)", ("vrs_T8", "vrs_T16"), "tab:purple", "d"),
    ("checkerboard", "checkerboard", ("checkerboard",), "tab:brown", "^"),
)
OURS = ("lindilate", "dilate", "lindilate2d", "lindilate2d4")
PEERS = ("dacs", "dacs8")
EQ_KEYS = ("patent", "lindilate2d", "lindilate2d4", "dacs", "dacs8", "vrs")   # the SSIM / FLIP table's groups
GRID = (0.05, 0.10, 0.15, 0.20, 0.30, 0.40, 0.50, 0.60, 0.80)          # the common traced-fraction grid
BANDS = ((0.0, 0.10), (0.10, 0.25), (0.25, 0.50), (0.50, 1.0))


def _front(recs, fams, eq):
    pts = [(r["traced_fraction"], capped(r["psnr_conv"])) for r in recs if r["family"] in fams]
    if not pts:
        return []
    return pareto(pts + [(1.0, eq)])                  # threshold 0: every family can trace everything


def _at(recs, fams, target):
    """The cheapest recorded setting of the group reaching `target` (for SSIM, FLIP, worst tile)."""
    ok = [r for r in recs if r["family"] in fams and capped(r["psnr_conv"]) >= target - 1e-9]
    return min(ok, key=lambda r: r["traced_fraction"]) if ok else None


def analyse(records, mode: str = "heavy") -> dict:
    """{scene: {"eq": dB, "full": {...}, "groups": {key: {...}}}} from the records scored against
    the converged reference."""
    out = {}
    for sc in dict.fromkeys(r["scene"] for r in records if r["mode"] == mode and "psnr_conv" in r):
        recs = [r for r in records if r["scene"] == sc and r["mode"] == mode and "psnr_conv" in r]
        full = [r for r in recs if r["family"] == "full"]
        if not full:
            continue
        eq = capped(full[0]["psnr_conv"])
        targets = {"eq": eq, "eq-1": eq - 1, "eq-3": eq - 3, "40": 40.0, "35": 35.0}
        groups = {}
        for key, _, fams, _, _ in GROUPS:
            # each family's own front (a segment between two families' settings is no setting
            # of either); the group's figure is its best family's
            fronts = {f: _front(recs, (f,), eq) for f in fams}
            fronts = {f: fr for f, fr in fronts.items() if fr}
            if not fronts:
                continue
            grid = {}
            for f in GRID:
                vals = [p for p in (psnr_at(fr, f) for fr in fronts.values()) if p is not None]
                grid[f"{f:.2f}"] = max(vals) if vals else None
            g = {"needed": {}, "grid": grid}
            for t, v in targets.items():
                best = None
                for fam, fr in fronts.items():
                    frac, how = fraction_for(fr, v)
                    if frac is not None and (best is None or frac < best["fraction"]):
                        best = {"fraction": frac, "how": how, "family": fam}
                g["needed"][t] = best or {"fraction": None, "how": "not_reached"}
            best = _at(recs, fams, eq)
            if best is not None:
                g["at_eq"] = {k: best.get(k) for k in ("family", "label", "traced_fraction", "psnr_conv",
                                                       "ssim_conv", "flip_conv", "tile32_min_psnr_conv")}
            bands = {}
            for lo, hi in BANDS:
                vals = [p for f, p in ((float(k), v) for k, v in g["grid"].items()) if lo <= f < hi and p is not None]
                bands[f"{int(100 * lo)}-{int(100 * hi)}"] = sum(vals) / len(vals) if vals else None
            g["bands"] = bands
            groups[key] = g
        out[sc] = {"eq": eq, "full": {k: full[0].get(k) for k in ("ssim_conv", "flip_conv", "tile32_min_psnr_conv")},
                   "groups": groups}
    return out


def _need(a, key, t="eq"):
    g = a["groups"].get(key)
    return None if g is None else g["needed"][t]["fraction"]


def _best_of(a, keys, t="eq"):
    vals = [(_need(a, k, t), k) for k in keys if _need(a, k, t) is not None]
    return min(vals) if vals else (None, None)


def _pct(f):
    return "-" if f is None else f"{100 * f:.1f}"


TARGETS = (("eq", "equal quality"), ("eq-1", "1 dB below"), ("eq-3", "3 dB below"))


def context(analysis: dict, conv_info: dict | None = None) -> dict:
    """The numbers of the head-to-head tables (templates/_headline.j2) from `analyse`'s output:
    per scene and group the needed-fraction entries, ours against the best DACS, SSIM / FLIP /
    worst tile at the equal-quality point, the common grid and the references. Nothing here is
    formatted; the templates do that."""
    scenes = list(analysis)
    groups = [{"key": k, "name": n} for k, n, *_ in GROUPS]
    rows = []
    for sc in scenes:
        a = analysis[sc]
        ours, peer = _best_of(a, OURS), _best_of(a, PEERS)
        cells = {}
        for k, *_ in GROUPS:
            g = a["groups"].get(k)
            cells[k] = None if g is None else g["needed"]
        rows.append({"scene": sc, "eq": a["eq"], "needed": cells, "best_ours": ours[1], "best_peer": peer[1],
                     "peer_minus_ours": None if ours[0] is None or peer[0] is None else peer[0] - ours[0]})
    means = {}
    for k, *_ in GROUPS:
        v = [_need(analysis[s], k) for s in scenes]
        means[k] = sum(v) / len(v) if v and None not in v else None
    summary = []
    for t, label in TARGETS:
        o = [_best_of(analysis[s], OURS, t)[0] for s in scenes]
        p = [_best_of(analysis[s], PEERS, t)[0] for s in scenes]
        pairs = [(x, y) for x, y in zip(o, p) if x is not None and y is not None]
        fewer = [s for s, x, y in zip(scenes, o, p) if x is not None and y is not None and x < y - 1e-3]
        more = [s for s, x, y in zip(scenes, o, p) if x is not None and y is not None and x > y + 1e-3]
        summary.append({"target": t, "label": label, "fewer": fewer, "more": more,
                        "same": len(pairs) - len(fewer) - len(more),
                        "mean_ours": sum(x for x, _ in pairs) / len(pairs) if pairs else None,
                        "mean_dacs": sum(y for _, y in pairs) / len(pairs) if pairs else None})
    at_eq = []
    for sc in scenes:
        a = analysis[sc]
        cells = []
        for k in EQ_KEYS:
            at = a["groups"].get(k, {}).get("at_eq") or a["full"]
            cells.append({"ssim": at.get("ssim_conv"), "flip": at.get("flip_conv"),
                          "tile": at.get("tile32_min_psnr_conv")})
        at_eq.append({"scene": sc, "cells": cells})
    grid = []
    for k, n, *_ in GROUPS:
        vals = []
        for f in GRID:
            v = [analysis[s]["groups"].get(k, {}).get("grid", {}).get(f"{f:.2f}") for s in scenes]
            vals.append(None if not v or None in v else sum(v) / len(v))
        for lo, hi in BANDS:
            v = [analysis[s]["groups"].get(k, {}).get("bands", {}).get(f"{int(100 * lo)}-{int(100 * hi)}")
                 for s in scenes]
            vals.append(None if not v or None in v else sum(v) / len(v))
        grid.append({"name": n, "vals": vals})
    all_full = [sc for sc in scenes
                if all((g["needed"]["eq"]["fraction"] or 1.0) >= 1.0 - 1e-9 for g in analysis[sc]["groups"].values())]
    refs = [{"scene": sc, **(conv_info or {}).get(sc, {})} for sc in scenes] if conv_info else []
    return {"scenes": scenes, "groups": groups, "rows": rows, "means": means, "summary": summary,
            "eq_keys": [{"key": k, "name": dict((g["key"], g["name"]) for g in groups)[k]} for k in EQ_KEYS],
            "at_eq": at_eq, "grid_cols": [f"{int(100 * f)} %" for f in GRID] +
            [f"band {int(100 * lo)}-{int(100 * hi)} %" for lo, hi in BANDS], "grid": grid,
            "eq_min": min(analysis[s]["eq"] for s in scenes) if scenes else None,
            "eq_max": max(analysis[s]["eq"] for s in scenes) if scenes else None,
            "all_full": all_full, "refs": refs}


def plot_fronts(records, path, title, mode: str = "heavy"):
    """Per scene, every group's Pareto front against the converged reference (closed at 100 %)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    scenes = list(dict.fromkeys(r["scene"] for r in records if r["mode"] == mode and "psnr_conv" in r))
    if not scenes:
        return
    fig, axes = scene_grid(plt, len(scenes))
    for ax, sc in zip(axes.ravel(), scenes):
        rs = [r for r in records if r["mode"] == mode and r["scene"] == sc and "psnr_conv" in r]
        full = [r for r in rs if r["family"] == "full"]
        eq = capped(full[0]["psnr_conv"]) if full else None
        for _, name, fams, col, mk in GROUPS:
            front = _front(rs, fams, eq) if eq is not None else []
            if front:
                ax.plot([100 * f for f, _ in front], [p for _, p in front], marker=mk, color=col, lw=0.9, ms=3,
                        label=name)
        if eq is not None:
            ax.axhline(eq, color="k", lw=0.5, ls="--")
            ax.plot([100], [eq], marker="x", color="k", ls="", ms=5, label="full render (eq)")
        scene_panel(ax, sc, 102, max(50, (eq or 40) + 3))
    finish_scene_grid(plt, fig, axes, len(scenes), "PSNR against the converged image (dB)", title, path)
