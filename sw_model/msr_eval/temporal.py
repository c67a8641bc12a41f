"""Sequences: image quality over a moving camera, and flicker.

A still cannot show selective rendering's own temporal failure: a pixel interpolated in one
frame and traced in the next changes although the scene did not. Each scene of the sequence
set is seen along an orbit (its own view swung about the vertical axis through its target,
msr_model.camera_path), and every method renders every frame against that frame's full render:

- per frame, the PSNR against the full render and the traced fraction;
- flicker: the frame-to-frame change of the error, rms over the pixels and channels of
  (frame_k - full_k) - (frame_{k-1} - full_{k-1}), in 8-bit units. The full render's own
  change from frame to frame is the camera's motion and costs nothing here; what a method adds
  to it is what a viewer sees as shimmer.

Methods: the patent's rule and lindilate (L = 3, T = 16), DACS (4x4, largest channel
variance), the VRS-like tier-2 baseline (8x8) and checkerboard, at two settings each, the same
settings on every frame (no budget: the ray budget's own sequence behaviour is make sim
FRAMES= BUDGET=).
"""
from __future__ import annotations

import json
import math
import time
from pathlib import Path

import numpy as np

from msr_model import Params
from msr_model.metrics import capped, flicker, psnr
from msr_model.scenes import scene_id

from .sweep_space import Setting

# The sequence set: five scenes, two of them textured (duck: COLLADA with a TGA map,
# CesiumMilkTruck: glTF with an embedded-URI PNG).
SEQ_SCENES = ("cornell", "bunny", "duck", "/usr/share/glmark2/models/horse.3ds",
              "/usr/share/assimp/models/glTF/CesiumMilkTruck/CesiumMilkTruck.gltf")
QUICK_SCENES = ("cornell", "duck")
ORBIT_DEG = 30.0          # the camera swings +-15 degrees about the target's vertical axis
KEY_EVERY = 5             # path keys every 5 frames (linear between them: a polygon of the arc)


def settings() -> list[Setting]:
    """Two settings per family: a sparse one and a dense one."""
    out = []
    for rule in ("patent", "lindilate"):
        fam = "multi_L3_T16" + ("" if rule == "patent" else "_lindilate")
        for thr in ((8, 16, 32), (2, 4, 8)):
            p = Params(tile=16, levels=3, thr=thr)
            out.append(Setting(fam, f"thr={','.join(map(str, thr))}", "multi_level", {"params": p, "rule": rule},
                               {**p.as_dict(), "rule": rule}))
    for t in (512, 32):
        kw = {"thr": t, "metric": "var", "block": 4}
        out.append(Setting("dacs", f"var<={t}", "msr_eval.dacs:dacs", kw, kw))
    for t in (16, 4):
        kw = {"thr": t, "tile": 8, "rates": "tier2", "anchor": "centre"}
        out.append(Setting("vrs_T8", f"s={t}", "msr_eval.vrs:vrs_tier2", kw, kw))
    out.append(Setting("checkerboard", "checkerboard", "checkerboard"))
    return out


def orbit_path(view, frames: int, degrees: float = ORBIT_DEG):
    """A CameraPath: the view's eye swung about the vertical axis through its target, from
    -degrees/2 to +degrees/2 over the frames (keys every KEY_EVERY frames)."""
    from msr_model.camera_path import CameraPath
    eye, target, fov = view
    dx, dz = eye[0] - target[0], eye[2] - target[2]
    keys = []
    last = max(1, frames - 1)
    for k in sorted(set(list(range(0, frames, KEY_EVERY)) + [last])):
        a = math.radians(-degrees / 2 + degrees * k / last)
        c, s = math.cos(a), math.sin(a)
        keys.append({"frame": k, "eye": [target[0] + c * dx + s * dz, eye[1], target[2] - s * dx + c * dz],
                     "target": list(target), "fov": fov})
    return CameraPath.from_dict({"keys": keys}, source="orbit")


def task_scene(scene: str, width: int, height: int, cameras: list[str], sweep: list[Setting]) -> dict:
    """One scene's sequence: per frame its full render and every setting on it; only the last
    frame's errors are kept (for the flicker of the next)."""
    from msr_model import ImageRenderer
    from msr_model.embree import open_renderer
    out = {f"{st.family}|{st.label}": {"psnr": [], "traced": [], "flicker": []} for st in sweep}
    prev = {}
    for cam in cameras:
        with open_renderer(scene, width, height, quality="fast", camera=cam) as r:
            full = r.render_full(progress=False)
        for st in sweep:
            key = f"{st.family}|{st.label}"
            res = st.run(ImageRenderer(full), width, height)
            err = res.frame.astype(np.int16) - full.astype(np.int16)
            out[key]["psnr"].append(psnr(full, res.frame))
            out[key]["traced"].append(res.traced / (width * height))
            if key in prev:
                out[key]["flicker"].append(flicker(prev[key], err))
            prev[key] = err
    return out


def run(scenes, frames: int, width: int, height: int, executor=None, log=print) -> dict:
    """Every scene's sequence; returns the per-frame and per-method figures (JSON-ready)."""
    from msr_model.embree import open_renderer
    from .executors import SerialExecutor
    ex = executor or SerialExecutor()
    sweep = settings()
    t0 = time.perf_counter()
    result = {"width": width, "height": height, "frames": frames, "orbit_deg": ORBIT_DEG,
              "settings": [{"family": s.family, "label": s.label, "setting": s.setting} for s in sweep],
              "scenes": {}}
    cams = {}
    for scene in scenes:
        with open_renderer(scene, width, height) as r:
            path = orbit_path(r.view(), frames)
        cams[scene] = [path.camera(k) for k in range(frames)]
    futs = [ex.submit(task_scene, scene, width, height, cams[scene], sweep) for scene in scenes]
    for scene, per in zip(scenes, ex.results(futs)):
        sc = {"cameras": cams[scene], "methods": {}}
        for st in sweep:
            key = f"{st.family}|{st.label}"
            m = per[key]
            sc["methods"][key] = {
                "family": st.family, "label": st.label, **m,
                "psnr_mean": float(np.mean([capped(p) for p in m["psnr"]])), "psnr_worst": capped(min(m["psnr"])),
                "traced_mean": float(np.mean(m["traced"])),
                "flicker_mean": float(np.mean(m["flicker"])) if m["flicker"] else 0.0,
                "flicker_worst": float(np.max(m["flicker"])) if m["flicker"] else 0.0}
        result["scenes"][scene] = sc
        log(f"temporal: {scene}: {frames} frames, {len(sweep)} settings")
    result["seconds"] = round(time.perf_counter() - t0, 1)
    return result


def plot(result: dict, path: Path) -> None:
    """Per scene, PSNR and flicker over the frames, one line per setting."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    scenes = list(result["scenes"])
    fig, axes = plt.subplots(2, len(scenes), figsize=(3.6 * len(scenes), 6), squeeze=False)
    colours = {"multi_L3_T16": "tab:blue", "multi_L3_T16_lindilate": "tab:orange", "dacs": "tab:green",
               "vrs_T8": "tab:red", "checkerboard": "tab:purple"}
    for j, scene in enumerate(scenes):
        for key, m in result["scenes"][scene]["methods"].items():
            ls = "-" if m["label"] in ("thr=8,16,32", "var<=512", "s=16", "checkerboard") else "--"
            lab = f"{m['family']} {m['label']}"
            axes[0][j].plot(m["psnr"], ls, color=colours.get(m["family"], "k"), lw=1, label=lab)
            axes[1][j].plot(range(1, 1 + len(m["flicker"])), m["flicker"], ls, color=colours.get(m["family"], "k"),
                            lw=1)
        axes[0][j].set_title(scene_id(scene), fontsize=10)
        axes[1][j].set_xlabel("frame")
    axes[0][0].set_ylabel("PSNR vs full render (dB)")
    axes[1][0].set_ylabel("flicker (rms change of error)")
    axes[0][-1].legend(fontsize=6, loc="lower right")
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=90)
    plt.close(fig)


def markdown(result: dict, img_rel: str) -> str:
    """The temporal section of docs/results.md."""
    lines = [f"## Sequences: quality over a moving camera, and flicker",
             "",
             f"{len(result['scenes'])} scenes, {result['frames']} frames each at {result['width']}x{result['height']}, "
             f"the camera swung {result['orbit_deg']:.0f} degrees about each scene's target "
             f"(`msr_eval.temporal`, part of `make eval`; `scripts/eval.py --temporal-only` adds it to a run; "
             f"{result['seconds']:.0f} s). Per method and setting: "
             "mean traced fraction, mean and worst frame PSNR against the frame's full render, and flicker, the rms "
             "frame-to-frame change of the error in 8-bit units (mean and worst over the frames): what a method "
             "adds to the motion that the full render has.",
             ""]
    keys = [f"{s['family']}|{s['label']}" for s in result["settings"]]
    head = "| setting | " + " | ".join(scene_id(s) for s in result["scenes"]) + " | mean |"
    lines += ["### Mean traced % / mean PSNR (dB) / worst PSNR (dB) / mean flicker / worst flicker", "",
              head, "|---|" + "---|" * (len(result["scenes"]) + 1)]
    for key in keys:
        cells, fl = [], []
        for scene in result["scenes"]:
            m = result["scenes"][scene]["methods"][key]
            cells.append(f"{100 * m['traced_mean']:.1f} / {m['psnr_mean']:.2f} / {m['psnr_worst']:.2f} / "
                         f"{m['flicker_mean']:.2f} / {m['flicker_worst']:.2f}")
            fl.append(m["flicker_mean"])
        fam, lab = key.split("|")
        lines.append(f"| {fam} {lab} | " + " | ".join(cells) + f" | flicker {np.mean(fl):.2f} |")
    lines += ["", f"![PSNR and flicker over the frames]({img_rel})", ""]
    return "\n".join(lines)


def write(result: dict, out: Path) -> None:
    out.mkdir(parents=True, exist_ok=True)
    (out / "temporal.json").write_text(json.dumps(result, indent=1) + "\n")
