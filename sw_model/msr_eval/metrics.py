"""The analysis of a sweep's records: Pareto fronts, the traced fraction needed for a target
PSNR, set means, rule against patent. The metrics themselves (PSNR, SSIM, FLIP, flicker) are
msr_model.metrics, re-exported here."""
from __future__ import annotations

import numpy as np

from msr_model.metrics import PSNR_CAP, capped, flicker, flip, format_db, psnr, psnr_of_mse, ssim  # noqa: F401

TARGETS_DB = (35.0, 40.0)


def pareto(points):
    """Lower-left front of (fraction, psnr): sorted by fraction, psnr strictly rising."""
    front = []
    for f, p in sorted(points, key=lambda t: (t[0], -t[1])):
        if not front or p > front[-1][1]:
            front.append((f, p))
    return front


def fraction_for(points, target):
    """Traced fraction at which a family first reaches `target` dB: linear interpolation in
    (fraction, PSNR) between the two Pareto points around the target. Returns (value, how):
    how = "interp", "at_or_below" (even the cheapest setting reaches it: value is that
    setting's fraction, an upper bound) or "not_reached" (value None)."""
    front = pareto(points)
    if not front:
        return None, "not_reached"
    if front[0][1] >= target:
        return front[0][0], "at_or_below"
    for (f1, p1), (f2, p2) in zip(front, front[1:]):
        if p1 < target <= p2:
            return f1 + (target - p1) / (p2 - p1) * (f2 - f1), "interp"
    return None, "not_reached"


def summarise(records, modes):
    """Per scene/mode/family: traced fraction for 35 and 40 dB; over the set: mean curves."""
    need = {}
    for r in records:
        need.setdefault(r["scene"], {}).setdefault(r["mode"], {}).setdefault(r["family"], []).append(
            (r["traced_fraction"], capped(r["psnr"])))
    needed = {s: {m: {f: {str(int(t)): dict(zip(("fraction", "how"), fraction_for(pts, t)))
                          for t in TARGETS_DB}
                      for f, pts in fams.items()} for m, fams in ms.items()} for s, ms in need.items()}
    # set means per setting (same setting on every scene)
    sets = {}
    for r in records:
        key = (r["mode"], r["family"], r["label"])
        sets.setdefault(key, []).append(r)
    n_scenes = len(need)
    set_curves = {}
    for (mode, fam, label), rs in sets.items():
        if len(rs) != n_scenes:
            continue
        set_curves.setdefault(mode, {}).setdefault(fam, []).append({
            "label": label,
            "traced_fraction": float(np.mean([r["traced_fraction"] for r in rs])),
            "psnr_mean": float(np.mean([capped(r["psnr"]) for r in rs])),
            "psnr_min": float(np.min([capped(r["psnr"]) for r in rs])),
            "setting": rs[0]["setting"]})
    headline = {}
    for mode, fams in set_curves.items():
        best_at_15, cheapest_40 = None, None
        for fam, pts in fams.items():
            for p in pts:
                if p["traced_fraction"] <= 0.15 and (best_at_15 is None or p["psnr_mean"] > best_at_15["psnr_mean"]):
                    best_at_15 = {**p, "family": fam}
                if p["psnr_mean"] >= 40 and (cheapest_40 is None or p["traced_fraction"] < cheapest_40["traced_fraction"]):
                    cheapest_40 = {**p, "family": fam}
        headline[mode] = {"best_psnr_at_most_15pct": best_at_15, "cheapest_40db_mean": cheapest_40,
                          "set_needed": {fam: {str(int(t)): dict(zip(("fraction", "how"), fraction_for(
                              [(p["traced_fraction"], p["psnr_mean"]) for p in pts], t))) for t in TARGETS_DB}
                              for fam, pts in fams.items()}}
    return needed, set_curves, headline


def rule_comparison(records, base="multi_L3_T16", others=("multi_L3_T16_dilate", "multi_L3_T16_linear",
                                                           "multi_L3_T16_lindilate", "multi_L3_T16_diag",
                                                           "multi_L3_T16_gbuf", "multi_L3_T16_gbuflindilate")):
    """PSNR of each rule minus the patent's at equal traced fraction (interpolated along the
    patent's Pareto front), per scene and mode, at every setting of the rule that lies inside
    the patent curve's fraction range."""
    out = {}
    by = {}
    for r in records:
        by.setdefault((r["scene"], r["mode"], r["family"]), []).append((r["traced_fraction"], capped(r["psnr"])))
    for (scene, mode, fam), pts in by.items():
        if fam not in others or (scene, mode, base) not in by:
            continue
        front = pareto(by[(scene, mode, base)])
        fx = np.array([f for f, _ in front])
        py = np.array([p for _, p in front])
        deltas = []
        for f, p in pts:
            if fx[0] <= f <= fx[-1] and p < PSNR_CAP:
                deltas.append((f, p - float(np.interp(f, fx, py))))
        out.setdefault(fam, {}).setdefault(mode, {})[scene] = {
            "n": len(deltas),
            "mean_delta_db": float(np.mean([d for _, d in deltas])) if deltas else None,
            "min_delta_db": float(np.min([d for _, d in deltas])) if deltas else None,
            "max_delta_db": float(np.max([d for _, d in deltas])) if deltas else None,
            "points": deltas}
    return out


def pick_near(records, scene, mode, fam, target):
    """The cheapest setting of a family on a scene that reaches `target` dB (else its best)."""
    rs = [r for r in records if r["scene"] == scene and r["mode"] == mode and r["family"] == fam]
    ok = [r for r in rs if capped(r["psnr"]) >= target]
    if ok:
        return min(ok, key=lambda r: r["traced_fraction"])
    return max(rs, key=lambda r: capped(r["psnr"])) if rs else None

