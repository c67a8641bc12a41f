"""The converged head-to-head that leads docs/results.md (issue 30): per scene, the traced
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


def docs_lines(analysis: dict, cfg: dict, fig: str | None = None, conv_info: dict | None = None,
               heldout: dict | None = None) -> list[str]:
    """The section that leads docs/results.md (and, when given, the held-out scenes' tables)."""
    L = _tables(analysis, cfg, fig, conv_info, f"## The head-to-head at {cfg['width']}x{cfg['height']} against "
                "the converged image (read this first)", True)
    if heldout:
        hc = heldout["config"]
        L += _tables(heldout["head_to_head"], hc, None, heldout.get("head_to_head_references"),
                     f"## Held-out scenes at {hc['width']}x{hc['height']}: the same comparison on models outside the set",
                     False, "Scenes that no rule was designed or tuned on: " +
                     ", ".join(f"`{s}`" for s in hc.get("scene_sources", hc["scenes"])) +
                     f"; converged references of {hc.get('conv_spp', 256)} samples per pixel, one seed "
                     f"(`scripts/eval.py --heldout`, run {hc.get('date_utc', '')}, {hc.get('runtime_s', 0) / 60:.0f} min).\n")
    return L


def _tables(analysis: dict, cfg: dict, fig, conv_info, title: str, intro: bool, lead: str = "") -> list[str]:
    L = []
    w = L.append
    names = {k: n for k, n, *_ in GROUPS}
    scenes = list(analysis)
    w(title + "\n")
    if lead:
        w(lead)
    if not intro:
        return L + _body(analysis, scenes, names, None, conv_info, w_level="###")
    w_level = "###"
    w("The question a user asks: **to get a frame as close to the noise-free image as tracing every "
      "pixel gets, what fraction of the pixels must each method trace?** Heavy renderer (16 samples "
      "per pixel, area light and ambient occlusion); the converged reference is the same renderer with "
      "256 or 1024 samples per pixel, the count the quick-size ladder chose per scene "
      "([converged/ladder.json](converged/ladder.json), two-seed figures there). `eq` is the full "
      "render's own PSNR against it; a method may get there below 100 % (interpolation averages "
      "noise). Every family can trace everything (threshold 0), so its front ends at (100 %, eq). "
      "Each group's figure is its best family's, each family read on its own Pareto front, "
      "peers included: DACS over both block statistics (largest channel variance, luma "
      "variance), VRS over both tile sizes, the patent's rule and ours over L = 2 and 3 and T = 16 "
      "and 32, threshold shapes s, 2s, 4s to s, 8s, 64s, and at L = 4 with T = 32 (an extension: "
      "a stride-16 initial grid, beyond algorithm.md's L <= 3). Methods: "
      "[dacs.md](dacs.md); the new rule: [rules.md](rules.md#lindilate2d), its L = 4 grid: "
      "[rules.md](rules.md#the-l--4-extension-a-stride-16-initial-grid).\n")
    return L + _body(analysis, scenes, names, fig, conv_info, w_level)


def _body(analysis, scenes, names, fig, conv_info, w_level: str) -> list[str]:
    L = []
    w = L.append
    cols = [k for k, *_ in GROUPS]
    w(f"{w_level} Traced % at the equal-quality point (as close to the converged image as the full render)\n")
    w("| scene | eq (dB) | " + " | ".join(names[k] for k in cols) + " | best peer - best ours |")
    w("|---|---:|" + "---:|" * len(cols) + "---:|")
    for sc in scenes:
        a = analysis[sc]
        ours, peer = _best_of(a, OURS), _best_of(a, PEERS)
        diff = None if ours[0] is None or peer[0] is None else peer[0] - ours[0]
        cells = []
        for k in cols:
            v = _need(a, k)
            s = _pct(v)
            if v is not None and a["groups"][k]["needed"]["eq"]["how"] == "at_or_below":
                s = f"<= {s}"            # even the group's cheapest setting is that good
            if k == ours[1] or k == peer[1]:
                s = f"**{s}**"
            cells.append(s)
        w(f"| {sc} | {a['eq']:.2f} | " + " | ".join(cells) + f" | {'-' if diff is None else f'{100 * diff:+.1f}'} |")
    means = {k: [_need(analysis[s], k) for s in scenes] for k in cols}
    w("| **mean** | | " + " | ".join(_pct(sum(v) / len(v)) if v and None not in v else "-" for v in means.values())
      + " | |")
    w("")
    w("`<= x`: the group's cheapest setting (its floor: the initial grid and tile borders) is "
      "already as close to the converged image as the full render, so the point lies at or below "
      "x; on such scenes the comparison is between the methods' floors.\n")
    w("Ours against the best DACS (4x4 or 8x8, either statistic), scene by scene: fewer traced "
      "pixels (by more than 0.1 % of the frame), the same, more; and the mean traced % of each.\n")
    w("| point | ours fewer | same | DACS fewer | mean, best of ours | mean, best DACS |")
    w("|---|---:|---:|---:|---:|---:|")
    for t, label in (("eq", "equal quality"), ("eq-1", "1 dB below"), ("eq-3", "3 dB below")):
        o = [_best_of(analysis[s], OURS, t)[0] for s in scenes]
        p = [_best_of(analysis[s], PEERS, t)[0] for s in scenes]
        pairs = [(a, b) for a, b in zip(o, p) if a is not None and b is not None]
        fewer = sum(1 for a, b in pairs if a < b - 1e-3)
        more = sum(1 for a, b in pairs if a > b + 1e-3)
        mo = sum(a for a, _ in pairs) / len(pairs) if pairs else None
        mp = sum(b for _, b in pairs) / len(pairs) if pairs else None
        w(f"| {label} | {fewer} | {len(pairs) - fewer - more} | {more} | {_pct(mo)} | {_pct(mp)} |")
    w("")
    for t, title in (("eq-1", "1 dB below the full render"), ("eq-3", "3 dB below the full render"),
                     ("40", "40 dB"), ("35", "35 dB")):
        w(f"{w_level} Traced % for {title}\n")
        w("| scene | " + " | ".join(names[k] for k in cols) + " |")
        w("|---|" + "---:|" * len(cols))
        for sc in scenes:
            a = analysis[sc]
            cells = []
            for k in cols:
                g = a["groups"].get(k)
                if g is None:
                    cells.append("-")
                    continue
                n = g["needed"][t]
                cells.append("not reached" if n["fraction"] is None else
                             (f"<= {_pct(n['fraction'])}" if n["how"] == "at_or_below" else _pct(n["fraction"])))
            w(f"| {sc} | " + " | ".join(cells) + " |")
        w("")
    w(f"{w_level} At the equal-quality point: SSIM, FLIP and the worst 32x32 tile\n")
    w("Of each group's cheapest recorded setting reaching `eq` (the full render itself where none does "
      "below 100 %); SSIM and FLIP against the converged reference; the worst tile's PSNR shows the "
      "local failures that a frame's mean hides.\n")
    w("| scene | " + " | ".join(f"{names[k]} SSIM / FLIP / worst tile" for k in EQ_KEYS) + " |")
    w("|---|" + "---|" * len(EQ_KEYS))
    for sc in scenes:
        a = analysis[sc]
        cells = []
        for k in EQ_KEYS:
            at = a["groups"].get(k, {}).get("at_eq") or a["full"]
            ss, fl, tl = at.get("ssim_conv"), at.get("flip_conv"), at.get("tile32_min_psnr_conv")
            cells.append(" / ".join("-" if v is None else f"{v:.4f}" if i < 2 else f"{v:.1f} dB"
                                    for i, v in enumerate((ss, fl, tl))))
        w(f"| {sc} | " + " | ".join(cells) + " |")
    w("")
    w(f"{w_level} PSNR against the converged image on a common grid of traced fractions (mean over the scenes)\n")
    w("Each group's front read at the same traced fractions; `-` where a group cannot trace that few "
      "(DACS 4x4 traces at least its first pass, one pixel in 16).\n")
    w("| group | " + " | ".join(f"{int(100 * f)} %" for f in GRID) + " | " +
      " | ".join(f"band {int(100 * lo)}-{int(100 * hi)} %" for lo, hi in BANDS) + " |")
    w("|---|" + "---:|" * (len(GRID) + len(BANDS)))
    for k in cols:
        vals = []
        for f in GRID:
            v = [analysis[s]["groups"].get(k, {}).get("grid", {}).get(f"{f:.2f}") for s in scenes]
            vals.append(None if not v or None in v else sum(v) / len(v))
        bands = []
        for lo, hi in BANDS:
            v = [analysis[s]["groups"].get(k, {}).get("bands", {}).get(f"{int(100 * lo)}-{int(100 * hi)}")
                 for s in scenes]
            bands.append(None if not v or None in v else sum(v) / len(v))
        w(f"| {names[k]} | " + " | ".join("-" if v is None else f"{v:.2f}" for v in vals + bands) + " |")
    w("")
    if fig:
        w(f"![Pareto fronts per scene against the converged image]({fig})\n")
    if conv_info:
        w(f"{w_level} The converged references of this run\n")
        w("| scene | samples per pixel | render time (s) | from | two seeds at 192x108 (ladder) |")
        w("|---|---:|---:|---|---|")
        for sc in scenes:
            ci = conv_info.get(sc) or {}
            lad = ci.get("ladder") or {}
            w(f"| {sc} | {ci.get('spp', '-')} | {ci.get('render_s', 0):.0f} | {ci.get('from', 'rendered')} | "
              + ", ".join(f"{k} spp {v:.2f} dB" for k, v in lad.items()) + " |")
        w("")
    return L


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
