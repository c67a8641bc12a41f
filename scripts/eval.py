#!/usr/bin/env python3
"""Image quality against traced pixels, on real scenes, against the alternatives (issue 7).

    python scripts/eval.py                 # quick run: small frames (make eval)
    python scripts/eval.py --full          # 1920x1080, every scene, fast and heavy (make eval FULL=1)

For every scene and renderer mode the reference is the full render (cached as PNG under
out/eval/cache). The renderer is deterministic (same pixel, same colour), so the methods are
then run against the cached reference as the rendering unit: every method still asks the
unit only for the pixels it traces, and the traced count is what the unit was asked for.
The wall-time speedup is measured separately on the live Embree renderer (heavy mode),
where the selective frame is also checked to be bit-equal to the cached run.

Output: out/eval/results.json, out/eval/*.png plots and example images; with --docs also
docs/results.md and small figures in docs/img/.
"""
from __future__ import annotations

import argparse
import hashlib
import json
import math
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "sw_model"))

from msr_model import ImageRenderer, Params, load_rgb, save_png  # noqa: E402
from msr_model import methods as M  # noqa: E402
from msr_model.testimage import test_image  # noqa: E402

# Debian-packaged real models (glmark2-data, assimp-testmodels) used besides the built-ins.
MODEL_FILES = [
    "/usr/share/glmark2/models/horse.3ds",
    "/usr/share/glmark2/models/cat.3ds",
    "/usr/share/glmark2/models/asteroid-high.3ds",
    "/usr/share/assimp/models/OBJ/WusonOBJ.obj",
]
TARGETS_DB = (35.0, 40.0)
PSNR_CAP = 100.0            # an identical frame (infinite PSNR) counts as 100 dB in means
# Threshold scales s: the patent's families use thr = (s, 2s, 4s)[:L] (at least 1 each).
# Main families get the dense list, the others the sparse one (1080p costs ~0.6 s a setting).
FULL_SCALES = (0.25, 0.5, 1, 2, 3, 4, 6, 8, 16, 64)
SPARSE_SCALES = (0.5, 2, 8, 32)
QUICK_SCALES = (0.25, 1, 2, 4, 8, 16, 64)
MAIN_FAMILIES = ("multi_L3_T16", "multi_L3_T32", "multi_L3_T16_dilate", "multi_L3_T16_lindilate",
                 "multi_L3_T32_lindilate")
# SSIM and FLIP (FLIP ~6 s per 1080p frame) are computed for these families' key settings.
KEY_FAMILIES = ("grid2", "grid4", "checkerboard", "single_traced", "single_borrowed", "multi_L1_T16",
                "multi_L2_T16", "multi_L3_T16", "multi_L3_T32", "multi_L3_T16_fov", "multi_L3_T16_dilate",
                "multi_L3_T16_lindilate", "multi_L3_T32_lindilate")
# FLIP in the full run only for these (the quick run: all key families)
FLIP_FAMILIES_FULL = ("grid2", "checkerboard", "single_borrowed", "multi_L3_T16", "multi_L3_T16_dilate",
                      "multi_L3_T16_lindilate")


# --- scenes and renderers ------------------------------------------------------------------

class Backend:
    """The rendering unit: the Embree binding if it is built, else the built-in test picture."""

    def __init__(self, want: str):
        self.embree = None
        if want in ("auto", "embree"):
            try:
                from msr_model import embree  # noqa: PLC0415
                _close(embree.open_renderer(self._scenes(embree)[0], 8, 8, quality="fast"))  # built?
                self.embree = embree
                self.lib_hash = _lib_hash(embree)
            except Exception as e:  # noqa: BLE001 - any failure to load means "not built"
                if want == "embree":
                    raise SystemExit(f"eval: Embree renderer not available: {e}")
        self.name = "embree" if self.embree else "image"
        if not self.embree:
            self.lib_hash = "testimage"

    @staticmethod
    def _scenes(mod) -> list[str]:
        for attr in ("BUILTIN_SCENES", "SCENES", "builtin_scenes", "scene_names"):
            v = getattr(mod, attr, None)
            if v is not None:
                v = v() if callable(v) else v
                v = list(v.keys() if isinstance(v, dict) else v.split(",") if isinstance(v, str) else v)
                return v
        return ["cornell"]

    def builtin_scenes(self) -> list[str]:
        return self._scenes(self.embree) if self.embree else ["testimage"]

    def open(self, scene: str, width: int, height: int, mode: str):
        if not self.embree:
            return ImageRenderer(test_image(width, height))
        return self.embree.open_renderer(scene, width, height, quality=mode)


def _lib_hash(embree_mod) -> str:
    """Content hash of the renderer library (so a rebuilt renderer invalidates the cache)."""
    cand = [REPO / "build/renderer/libmsr_render.so"]
    p = getattr(embree_mod, "library_path", None) or getattr(embree_mod, "LIB_PATH", None)
    p = p() if callable(p) else p
    if p:
        cand.insert(0, Path(p))
    for c in cand:
        if Path(c).is_file():
            return hashlib.sha1(Path(c).read_bytes()).hexdigest()[:10]
    return "nolib"


def scene_id(scene: str) -> str:
    return Path(scene).stem.replace(" ", "_") if ("/" in scene or "." in scene) else scene


def _close(r):
    close = getattr(r, "close", None)
    if close:
        close()


def reference(backend, scene, mode, width, height, cache: Path):
    """Full render, cached as PNG with its wall time in a side file."""
    key = f"{scene_id(scene)}_{mode}_{width}x{height}_{backend.lib_hash}"
    png, meta = cache / f"{key}.png", cache / f"{key}.json"
    if png.is_file() and meta.is_file():
        return load_rgb(png), json.loads(meta.read_text())
    r = backend.open(scene, width, height, mode)
    try:
        t0 = time.perf_counter()
        res = M.full_render(r, width, height)
        dt = time.perf_counter() - t0
    finally:
        _close(r)
    save_png(png, res.frame)
    info = {"full_render_s": dt, "traced": res.traced}
    meta.write_text(json.dumps(info))
    return res.frame, info


# --- metrics -----------------------------------------------------------------------------

def psnr(ref, img):
    mse = np.mean((ref.astype(np.float64) - img.astype(np.float64)) ** 2)
    return None if mse == 0 else float(10 * np.log10(255.0 ** 2 / mse))


def ssim(ref, img):
    from skimage.metrics import structural_similarity
    return float(structural_similarity(ref, img, channel_axis=2, data_range=255))


def flip(ref, img, want_map=False):
    import flip_evaluator
    emap, mean, _ = flip_evaluator.evaluate(ref.astype(np.float32) / 255, img.astype(np.float32) / 255,
                                            "LDR", applyMagma=False)
    return (float(mean), np.asarray(emap)[..., 0]) if want_map else float(mean)


def capped(p):
    return PSNR_CAP if p is None else min(p, PSNR_CAP)


# --- the sweep ---------------------------------------------------------------------------

def fov_gain_for(width, height, tile, edge_add=16):
    """fov_gain that raises the thresholds of the outermost tiles by about `edge_add`."""
    ntx, nty = -(-width // tile), -(-height // tile)
    r2max = max(ntx - 1, nty - 1, 1)
    return int(min(255, max(1, round(edge_add * 16 / r2max))))


def level_thr(levels, s):
    """Per-level thresholds for a scale s: s, 2s, 4s (claim 2: rising with the level), >= 1."""
    return tuple(min(255, max(1, int(s * (1 << k)))) for k in range(levels))


def _fmt(s):
    return f"{s:g}"


def families(width, height, scales, quick):
    """(family, label, callable(renderer) -> MethodResult) for every setting of the sweep."""
    W, H = width, height
    sparse = scales if quick else SPARSE_SCALES
    out = [("full", "full", lambda r: M.full_render(r, W, H), {}),
           ("grid2", "grid 2", lambda r: M.coarse_grid(r, W, H, 2), {"step": 2}),
           ("grid4", "grid 4", lambda r: M.coarse_grid(r, W, H, 4), {"step": 4}),
           ("checkerboard", "checkerboard", lambda r: M.checkerboard(r, W, H), {})]
    for s in sparse:
        t = min(255, max(1, int(2 * s)))   # one level of stride 4: between the patent's L=2 thresholds
        out.append(("single_traced", f"t={t}",
                    (lambda t: lambda r: M.single_level(r, W, H, t, 4, "traced", 16))(t),
                    {"thr": t, "stride": 4, "tile": 16}))
        out.append(("single_borrowed", f"t={t}",
                    (lambda t: lambda r: M.single_level(r, W, H, t, 4, "borrowed"))(t),
                    {"thr": t, "stride": 4}))
    multi = [("L1_T16", 16, 1, 0, "patent"), ("L2_T16", 16, 2, 0, "patent"),
             ("L3_T16", 16, 3, 0, "patent"), ("L3_T32", 32, 3, 0, "patent"),
             ("L3_T16_fov", 16, 3, 16, "patent"),
             ("L3_T16_dilate", 16, 3, 0, "dilate"), ("L3_T16_linear", 16, 3, 0, "linear"),
             ("L3_T16_lindilate", 16, 3, 0, "lindilate"), ("L3_T16_diag", 16, 3, 0, "diag"),
             ("L3_T32_lindilate", 32, 3, 0, "lindilate")]
    for name, tile, levels, fov_edge, rule in multi:
        gain = fov_gain_for(W, H, tile, fov_edge) if fov_edge else 0
        fam = f"multi_{name}"
        for s in (scales if fam in MAIN_FAMILIES else sparse):
            p = Params(tile=tile, levels=levels, thr=level_thr(levels, s), fov_gain=gain)
            out.append((fam, f"thr={','.join(map(str, p.thr))}",
                        (lambda p, rule: lambda r: M.multi_level(r, W, H, p, rule=rule))(p, rule),
                        {**p.as_dict(), "rule": rule}))
    return out


def _sweep_signature(W, H, scales, quick, all_metrics) -> str:
    """Changes whenever the sweep or the code that computes a record changes."""
    h = hashlib.sha1()
    for fam, label, _, setting in families(W, H, scales, quick):
        h.update(f"{fam}|{label}|{sorted(setting.items())}".encode())
    for f in ("sw_model/msr_model/golden.py", "sw_model/msr_model/spec.py", "sw_model/msr_model/rules.py",
              "sw_model/msr_model/methods.py", "scripts/eval.py"):
        h.update((REPO / f).read_bytes())
    h.update(repr((all_metrics, KEY_FAMILIES, FLIP_FAMILIES_FULL, TARGETS_DB)).encode())
    return h.hexdigest()[:10]


def run_scene(backend, scene, mode, W, H, cache, scales, quick, all_metrics, log):
    """Every setting on one scene and mode, plus SSIM/FLIP for the key settings; records are
    cached per scene and mode (keyed by the renderer library and the sweep's code), so an
    interrupted full run resumes where it stopped."""
    ref, info = reference(backend, scene, mode, W, H, cache)
    sig = _sweep_signature(W, H, scales, quick, all_metrics)
    rfile = cache / f"records_{scene_id(scene)}_{mode}_{W}x{H}_{backend.lib_hash}_{sig}.json"
    if rfile.is_file():
        recs = json.loads(rfile.read_text())
        log(f"  {scene_id(scene)}/{mode}: {len(recs)} settings (cached)")
        return ref, info, recs
    t_scene = time.perf_counter()
    recs = []
    for fam, label, fn, setting in families(W, H, scales, quick):
        rr = ImageRenderer(ref)
        t0 = time.perf_counter()
        res = fn(rr)
        dt = time.perf_counter() - t0
        if rr.pixels_traced != res.traced:
            raise RuntimeError(f"{fam}: method count {res.traced} != renderer count {rr.pixels_traced}")
        rec = {"scene": scene_id(scene), "mode": mode, "family": fam, "method": res.method,
               "label": label, "setting": setting, "traced": res.traced,
               "traced_fraction": res.traced / (W * H), "psnr": psnr(ref, res.frame),
               "decide_s": dt, "key_setting": False}
        if all_metrics:
            rec["ssim"] = ssim(ref, res.frame)
            rec["flip"] = flip(ref, res.frame)
        recs.append(rec)
    # key settings: the cheapest of each key family reaching the targets on this scene
    sid = scene_id(scene)
    for fam in KEY_FAMILIES:
        for t in (TARGETS_DB if quick else (40.0,)):
            r = pick_near(recs, sid, mode, fam, t)
            if r is None:
                continue
            r["key_setting"] = True
            if "ssim" not in r:
                res = rerun(ref, W, H, r, scales, quick)
                r["ssim"] = ssim(ref, res.frame)
                if quick or fam in FLIP_FAMILIES_FULL:
                    r["flip"] = flip(ref, res.frame)
    rfile.write_text(json.dumps(recs))
    log(f"  {sid}/{mode}: {len(recs)} settings, full render {info['full_render_s']:.2f} s, "
        f"sweep {time.perf_counter() - t_scene:.0f} s")
    return ref, info, recs


def rerun(ref, W, H, rec, scales, quick):
    """Run one recorded setting again on the reference (for images and late metrics)."""
    for fam, label, fn, setting in families(W, H, scales, quick):
        if fam == rec["family"] and label == rec["label"]:
            return fn(ImageRenderer(ref))
    raise KeyError(rec["family"], rec["label"])


# --- analysis ----------------------------------------------------------------------------

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
                                                           "multi_L3_T16_lindilate", "multi_L3_T16_diag")):
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
}


def plot_curves(records, mode, path, title):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    scenes = sorted({r["scene"] for r in records if r["mode"] == mode})
    if not scenes:
        return
    ncol = min(4, len(scenes))
    nrow = -(-len(scenes) // ncol)
    fig, axes = plt.subplots(nrow, ncol, figsize=(max(6.4, 3.2 * ncol), 2.6 * nrow + 0.9), squeeze=False)
    for ax, sc in zip(axes.ravel(), scenes):
        for fam, (lab, mk, col) in FAMILY_STYLE.items():
            pts = sorted((r["traced_fraction"], capped(r["psnr"])) for r in records
                         if r["mode"] == mode and r["scene"] == sc and r["family"] == fam)
            if pts:
                ax.plot([100 * f for f, _ in pts], [p for _, p in pts], marker=mk, color=col, lw=0.8,
                        ms=4, label=lab)
        ax.axhline(40, color="k", lw=0.4, ls=":")
        ax.axvline(15, color="k", lw=0.4, ls=":")
        ax.set_title(sc, fontsize=8)
        ax.set_xlim(0, 60)
        ax.set_ylim(20, 60)
        ax.tick_params(labelsize=6)
    for ax in axes.ravel()[len(scenes):]:
        ax.axis("off")
    fig.supxlabel("traced pixels (%)", fontsize=8)
    fig.supylabel("PSNR (dB)", fontsize=8)
    h, lab = axes[0, 0].get_legend_handles_labels()
    fig.legend(h, lab, fontsize=6, loc="lower center", ncol=4, frameon=False)
    fig.suptitle(title, fontsize=9)
    fig.tight_layout(rect=(0, 0.12 if nrow == 1 else 0.08, 1, 1))
    fig.savefig(path, dpi=70)
    plt.close(fig)


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


def source_rgb(source):
    """Source map for people: traced white (initial) / orange (levels), interpolated dark blue."""
    out = np.zeros(source.shape + (3,), np.uint8)
    out[source == 0] = (255, 255, 255)
    for k, col in ((1, (255, 170, 0)), (2, (230, 90, 0)), (3, (180, 0, 0))):
        out[source == k] = col
    for k, col in ((17, (20, 40, 110)), (18, (30, 60, 150)), (19, (40, 80, 190))):
        out[source == k] = col
    out[source == 16] = (30, 60, 150)
    return out


def example_strip(ref, res, panel_w):
    """frame | source map | error map (FLIP, magma), each downscaled to panel_w wide."""
    from PIL import Image
    import matplotlib
    _, emap = flip(ref, res.frame, want_map=True)
    err = (matplotlib.colormaps["magma"](np.clip(emap, 0, 1))[..., :3] * 255).astype(np.uint8)
    panels = [res.frame, source_rgb(res.source), err]
    h, w = ref.shape[:2]
    ph = max(1, round(panel_w * h / w))
    ims = [Image.fromarray(p).resize((panel_w, ph), Image.NEAREST if i == 1 else Image.BILINEAR)
           for i, p in enumerate(panels)]
    strip = Image.new("RGB", (3 * panel_w + 8, ph), (255, 255, 255))
    for i, im in enumerate(ims):
        strip.paste(im, (i * (panel_w + 4), 0))
    return strip


# --- the run -------------------------------------------------------------------------------

def speedup(backend, scene, mode, W, H, rec, ref, info, scales, quick):
    """Wall time of the selective render on the live renderer against the full render."""
    r = backend.open(scene, W, H, mode)
    try:
        for fam, label, fn, setting in families(W, H, scales, quick):
            if fam == rec["family"] and label == rec["label"]:
                t0 = time.perf_counter()
                res = fn(r)
                dt = time.perf_counter() - t0
                break
        else:
            raise KeyError(rec["label"])
    finally:
        _close(r)
    cached = rerun(ref, W, H, rec, scales, quick)
    return {"scene": scene_id(scene), "mode": mode, "family": rec["family"], "label": rec["label"],
            "traced_fraction": res.traced / (W * H), "psnr": rec["psnr"],
            "full_render_s": info["full_render_s"], "selective_s": dt,
            "speedup": info["full_render_s"] / dt if dt > 0 else None,
            "bit_equal_to_cached_run": bool((res.frame == cached.frame).all())}


def pick_near(records, scene, mode, fam, target):
    """The cheapest setting of a family on a scene that reaches `target` dB (else its best)."""
    rs = [r for r in records if r["scene"] == scene and r["mode"] == mode and r["family"] == fam]
    ok = [r for r in rs if capped(r["psnr"]) >= target]
    if ok:
        return min(ok, key=lambda r: r["traced_fraction"])
    return max(rs, key=lambda r: capped(r["psnr"])) if rs else None


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--full", action="store_true", help="1920x1080, every scene, fast and heavy")
    ap.add_argument("--width", type=int)
    ap.add_argument("--height", type=int)
    ap.add_argument("--scenes", help="comma-separated scene names / model paths (default: the set)")
    ap.add_argument("--max-scenes", type=int, default=0, help="keep only the first N scenes (time-boxed runs)")
    ap.add_argument("--modes", help="comma-separated renderer modes (default fast,heavy)")
    ap.add_argument("--backend", choices=("auto", "embree", "image"), default="auto")
    ap.add_argument("--out", default=str(REPO / "out/eval"))
    ap.add_argument("--docs", action="store_true", help="also write docs/results.md and docs/img/")
    ap.add_argument("--docs-dir", default=str(REPO / "docs"), help="where --docs writes")
    ap.add_argument("--report-only", action="store_true",
                    help="only rewrite the docs from an existing OUT/results.json (no rendering)")
    ap.add_argument("--no-speedup", action="store_true")
    ap.add_argument("--all-metrics", action="store_true",
                    help="SSIM and FLIP for every setting (default: only the key settings)")
    a = ap.parse_args(argv)

    if a.report_only:
        from eval_report import write_docs  # noqa: PLC0415
        result = json.loads((Path(a.out) / "results.json").read_text())
        write_docs(result, Path(a.out), Path(a.docs_dir))
        return result
    full = a.full
    W = a.width or (1920 if full else 192)
    H = a.height or (1080 if full else 108)
    quick = not full
    scales = FULL_SCALES if full else QUICK_SCALES
    backend = Backend(a.backend)
    if a.scenes:
        scenes = [s.strip() for s in a.scenes.split(",") if s.strip()]
    else:
        scenes = backend.builtin_scenes()
        if backend.embree:
            scenes += [m for m in MODEL_FILES if Path(m).is_file()]
    if a.max_scenes:
        scenes = scenes[:a.max_scenes]
    modes = a.modes.split(",") if a.modes else (["fast", "heavy"] if backend.embree else ["image"])
    out = Path(a.out)
    cache = out / "cache"
    cache.mkdir(parents=True, exist_ok=True)
    log = lambda s: print(s, flush=True)  # noqa: E731
    log(f"eval: {W}x{H}, backend {backend.name}, scenes {[scene_id(s) for s in scenes]}, modes {modes}")

    t_start = time.perf_counter()
    records, refs, infos = [], {}, {}
    for scene in scenes:
        for mode in modes:
            ref, info, recs = run_scene(backend, scene, mode, W, H, cache, scales, quick,
                                        all_metrics=a.all_metrics, log=log)
            refs[(scene, mode)] = ref
            infos[(scene, mode)] = info
            records += recs

    needed, set_curves, headline = summarise(records, modes)
    rules_cmp = rule_comparison(records)

    speed = []
    if backend.embree and not a.no_speedup:
        smode = "heavy" if "heavy" in modes else modes[0]
        for scene in scenes:
            for fam in ("multi_L3_T16", "multi_L3_T16_lindilate"):
                r = pick_near(records, scene_id(scene), smode, fam, 40.0)
                if r is not None:
                    s = speedup(backend, scene, smode, W, H, r, refs[(scene, smode)], infos[(scene, smode)],
                                scales, quick)
                    speed.append(s)
                    log(f"  speedup {s['scene']}/{smode} {fam} {s['label']}: {s['speedup']:.2f}x "
                        f"at {100 * s['traced_fraction']:.1f} % traced, bit-equal {s['bit_equal_to_cached_run']}")

    # plots and examples
    for mode in modes:
        plot_curves(records, mode, out / f"curves_{mode}.png", f"PSNR against traced pixels, {mode} renderer, {W}x{H}")
        plot_set(set_curves, mode, out / f"pareto_{mode}.png", f"Mean over the scene set, {mode} renderer, {W}x{H}")
    examples = []
    ex_mode = "heavy" if "heavy" in modes else modes[0]
    for scene in scenes[:2] + ([scenes[-1]] if len(scenes) > 2 else []):
        hb = headline.get(ex_mode, {}).get("best_psnr_at_most_15pct")
        fam = hb["family"] if hb else "multi_L3_T16"
        lab = hb["label"] if hb else None
        rs = [r for r in records if r["scene"] == scene_id(scene) and r["mode"] == ex_mode and r["family"] == fam
              and (lab is None or r["label"] == lab)]
        if not rs:
            continue
        r = rs[0]
        res = rerun(refs[(scene, ex_mode)], W, H, r, scales, quick)
        strip = example_strip(refs[(scene, ex_mode)], res, panel_w=min(320, W))
        name = f"example_{scene_id(scene)}_{ex_mode}.png"
        strip.save(out / name, optimize=True)
        examples.append({"scene": scene_id(scene), "mode": ex_mode, "family": fam, "label": r["label"],
                         "traced_fraction": r["traced_fraction"], "psnr": r["psnr"], "file": name})

    try:
        commit = subprocess.run(["git", "-C", str(REPO), "rev-parse", "--short", "HEAD"], capture_output=True,
                                text=True).stdout.strip()
    except OSError:
        commit = ""
    result = {
        "config": {"width": W, "height": H, "full": full, "backend": backend.name, "renderer_lib": backend.lib_hash,
                   "scenes": [scene_id(s) for s in scenes], "scene_sources": scenes, "modes": modes,
                   "threshold_scales": list(scales), "psnr_cap_db": PSNR_CAP, "git": commit,
                   "date_utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
                   "runtime_s": time.perf_counter() - t_start,
                   "metrics_note": ("PSNR for every setting; SSIM and FLIP for every setting with --all-metrics, "
                                    "else for the key settings: the cheapest setting of each of KEY_FAMILIES "
                                    "that reaches 40 dB (and 35 dB in the quick run) on the scene; in the full "
                                    "run FLIP only for FLIP_FAMILIES_FULL"),
                   "key_families": list(KEY_FAMILIES), "flip_families_full": list(FLIP_FAMILIES_FULL)},
        "full_render": [{"scene": scene_id(s), "mode": m, **infos[(s, m)]} for s in scenes for m in modes],
        "records": records,
        "needed_fraction": needed,
        "set_curves": set_curves,
        "headline": headline,
        "rule_vs_patent": rules_cmp,
        "speedup": speed,
        "examples": examples,
    }
    (out / "results.json").write_text(json.dumps(result, indent=1))
    log(f"eval: wrote {out / 'results.json'} ({len(records)} records) in {time.perf_counter() - t_start:.0f} s")
    for mode, h in headline.items():
        b, c = h["best_psnr_at_most_15pct"], h["cheapest_40db_mean"]
        if b:
            log(f"  {mode}: best mean PSNR at <= 15 % traced: {b['psnr_mean']:.2f} dB at "
                f"{100 * b['traced_fraction']:.1f} % ({b['family']} {b['label']})")
        if c:
            log(f"  {mode}: cheapest >= 40 dB mean: {100 * c['traced_fraction']:.1f} % ({c['family']} {c['label']})")
    if a.docs:
        from eval_report import write_docs  # noqa: PLC0415
        write_docs(result, out, Path(a.docs_dir))
    return result


if __name__ == "__main__":
    main()
