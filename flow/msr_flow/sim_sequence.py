"""`make sim FRAMES=N [CAMERA_PATH=FILE]`: a sequence of frames through the RTL in one harness run.

The harness programs the registers before each frame as a driver would (with a ray budget:
each frame after the first seeded with the last frame's SCALE_OUT and activity memory, the
driver sequence of docs/budget.md, msr_model.sequence.next_budget) and moves the camera
between frames: frame k's view of the camera path, or without one the scene's default orbit
(msr_model.camera_path.scene_views, the views `msr_model sequence` takes too). Every frame is
compared with the golden model on the same view. Writes into OUT:

- frame_KKKK.png and source_map_KKKK.png (read back from the RTL's memory);
- sequence.json: `reuse` (false: reuse is not in the hardware yet), `frames` (per frame: frame,
  bit_exact, traced, reused, traced_fraction, psnr_db, identical, ssim, cycles, flicker, and
  with a budget the scale the frame ended with), the sequence's `flicker`, the run's set-up and
  the verdict;
- sequence.webp and sequence.gif (the frames, playable), summary_strip.png (the RTL frame,
  its source map and its error against the full render, a row per frame, the error on one
  scale for the whole sequence).
"""
from __future__ import annotations

import json
import time
from pathlib import Path

import numpy as np

from msr_model import save_png, spec
from msr_model.clitools import RunFailed, UsageError, int_in
from .harness import GoldenFrames, HarnessRun, compare

STRIP_ROWS, STRIP_W = 8, 240


def views_of(a, W: int, H: int, n: int, params) -> tuple[list[str], list, str]:
    """The view and the parameters (a path key's gaze point) of each of n frames, and where the
    views come from (the path file or the orbit)."""
    from msr_model.camera_path import scene_views
    from msr_model.sequence import params_per_frame
    if a.camera:
        raise UsageError("give CAMERA or CAMERA_PATH for a sequence, not both")
    path = Path(a.camera_path) if str(a.camera_path).strip() else None
    try:
        views = scene_views(a.scene, W, H, path, a.quality)
        cams = views.cameras(n)
    except spec.SpecError as e:
        raise UsageError(str(e)) from None
    return cams, params_per_frame(params, views, n, W, H), views.source


def _thumb(img: np.ndarray) -> np.ndarray:
    from PIL import Image
    h, w = img.shape[:2]
    th = max(1, round(h * STRIP_W / w))
    return np.asarray(Image.fromarray(img).resize((STRIP_W, th), Image.NEAREST))


def write_strip(path: Path, rows: list[tuple[int, np.ndarray, np.ndarray, np.ndarray]], vmax: int) -> None:
    """The key panels over time: per row (frame k) the RTL frame, its source map, its error, the
    error on one scale for the whole sequence (0 .. vmax, written in the caption), so rows
    compare."""
    from PIL import Image, ImageDraw
    from msr_model.overview import ERROR_CMAP, _cmap, abs_error, font, source_rgb
    vmax = max(1, int(vmax))
    cells = []
    for k, frame, source, reference in rows:
        err = abs_error(frame, reference)
        cells.append((k, [_thumb(frame), _thumb(source_rgb(source)),
                          _thumb(_cmap(ERROR_CMAP, np.minimum(err, vmax) / vmax))]))
    th = cells[0][1][0].shape[0]
    pad, label = 8, 70
    W = label + 3 * (STRIP_W + pad) + pad
    H = 30 + len(cells) * (th + pad) + pad
    im = Image.new("RGB", (W, H), (255, 255, 255))
    d = ImageDraw.Draw(im)
    f = font(14)
    for j, cap in enumerate(("RTL frame", "source map", f"abs error, 0..{vmax} (all frames)")):
        d.text((label + pad + j * (STRIP_W + pad), 8), cap, fill=(0, 0, 0), font=f)
    for i, (k, pics) in enumerate(cells):
        y = 30 + i * (th + pad)
        d.text((8, y + th // 2), f"frame {k}", fill=(0, 0, 0), font=f, anchor="lm")
        for j, pic in enumerate(pics):
            im.paste(Image.fromarray(np.ascontiguousarray(pic)), (label + pad + j * (STRIP_W + pad), y))
    im.save(path, format="PNG")


def write_animation(out: Path, frames: list[np.ndarray]) -> list[str]:
    """sequence.webp (lossless) and sequence.gif, 10 frames per second, looping."""
    from PIL import Image
    ims = [Image.fromarray(f) for f in frames]
    ims[0].save(out / "sequence.webp", save_all=True, append_images=ims[1:], duration=100, loop=0, lossless=True)
    ims[0].save(out / "sequence.gif", save_all=True, append_images=ims[1:], duration=100, loop=0)
    return ["sequence.webp", "sequence.gif"]


def run_sequence(a, W: int, H: int, params, rule: str, budget, harness: Path, out: Path) -> int:
    from msr_model.metrics import format_db, ssim
    from msr_model.overview import abs_error
    from msr_model.sequence import Flicker, frame_entry, next_budget, summary
    n = int_in(a.frames or "1", "FRAMES", 1, 10000)
    t0 = time.perf_counter()
    cams, fparams, path_file = views_of(a, W, H, n, params)   # opens the scene: a bad model is exit 2 here
    gazes = [p.gaze for p in fparams] if fparams[0] is not params else None
    out.mkdir(parents=True, exist_ok=True)
    sim = HarnessRun(harness, a.scene, W, H, params, rule=rule, quality=a.quality, latency=a.rnd_latency,
                     jitter=a.rnd_jitter, budget=budget, cameras=cams, gazes=gazes).start()
    goldens, refs = [], []
    try:
        cfg = budget
        for cam, fp in zip(cams, fparams):
            gf = GoldenFrames(a.scene, W, H, quality=a.quality, camera=cam)
            g = gf.frame(fp, rule, cfg)
            goldens.append(g)
            refs.append(gf.reference)
            cfg = next_budget(cfg, g.stats)     # the driver's sequence: seeded with the last frame's scale
    finally:
        rtl = sim.wait()
    if budget is not None and not rtl[0].build.get("budget_en"):
        raise RunFailed(f"BUDGET={a.budget}: the harness {harness} is a top without the budget controller")
    entries, frames, fl = [], [], Flicker()
    for k, (r, g, ref) in enumerate(zip(rtl, goldens, refs)):
        if r.stats.get("gaze") != (None if fparams[k].gaze is None else list(fparams[k].gaze)):
            raise RunFailed(f"frame {k}: the harness wrote GAZE {r.stats.get('gaze')}, not {fparams[k].gaze} "
                            "(rebuild it: make sim)")
        v = compare(r, g)
        e = {**frame_entry(k, r.frame, r.source, ref, cams[k]), "bit_exact": v["bit_exact"],
             "ssim": ssim(ref, r.frame), "cycles": r.stats["cycles"],
             "mismatched_pixels": v["mismatched_pixels"], "mismatched_codes": v["mismatched_codes"],
             "gaze": list(fparams[k].gaze or spec.default_gaze(W, H, fparams[k].tile))}
        e["flicker"] = fl.add(r.frame, ref)
        if budget is not None:
            bc = g.stats["budget_control"]
            hw = r.stats.get("budget", {})
            e.update(budget_error=(e["traced"] - budget.budget) / budget.budget, scale_init=bc["scale_init"],
                     scale_out=bc["scale_out"], scale_out_rtl=hw.get("scale_out"),
                     scale_out_equal=bool(hw.get("scale_out_valid")) and hw.get("scale_out") == bc["scale_out"])
        entries.append(e)
        frames.append(r.frame)
        save_png(out / f"frame_{k:04d}.png", r.frame)
        save_png(out / f"source_map_{k:04d}.png", r.source)
    pics = write_animation(out, frames)
    pick = sorted({round(i * (n - 1) / max(1, min(n, STRIP_ROWS) - 1)) for i in range(min(n, STRIP_ROWS))})
    err_max = max(int(abs_error(r.frame, ref).max()) for r, ref in zip(rtl, refs))
    write_strip(out / "summary_strip.png", [(k, rtl[k].frame, rtl[k].source, refs[k]) for k in pick], err_max)
    ok = all(e["bit_exact"] for e in entries) and all(e.get("scale_out_equal", True) for e in entries)
    seq = {"bit_exact": ok, "reuse": False, "frames": entries, **fl.summary(), **summary(entries),
           "scene": a.scene, "width": W, "height": H, "rule": rule,
           "params": params.as_dict(), "quality": a.quality, "camera_path": path_file,
           "budget": 0 if budget is None else budget.budget, "num_frames": n,
           "cycles_total": sum(e["cycles"] for e in entries), "strip_error_max": err_max,
           "pictures": pics + ["summary_strip.png"], "wall_seconds": round(time.perf_counter() - t0, 2)}
    (out / "sequence.json").write_text(json.dumps(seq, indent=2) + "\n")
    print(f"make sim: {a.scene} {W}x{H}, {n} frames on {path_file}, rule {rule}"
          + (f", budget {budget.budget} pixels" if budget is not None else ""))
    for e in entries:
        extra = f", scale out {e['scale_out_rtl']} ({e['budget_error']:+.2%} off the budget)" if budget is not None else ""
        print(f"  frame {e['frame']:4d}: {'bit exact' if e['bit_exact'] else 'NOT bit exact'}, traced "
              f"{e['traced_fraction']:.1%}, PSNR {format_db(e['psnr_db'])}, "
              f"{e['cycles']} cycles{extra}")
    print(f"  flicker {seq['flicker']:.3f} (rms change of the error, frame to frame)")
    print(f"  outputs: {out}/ (sequence.json, frame_KKKK.png, sequence.webp, sequence.gif, summary_strip.png)",
          flush=True)
    if not ok:
        bad = [e["frame"] for e in entries if not e["bit_exact"] or not e.get("scale_out_equal", True)]
        raise RunFailed(f"frames {bad} differ from the golden model (report: {out / 'sequence.json'})")
    print(f"make sim: passed: {n} frames bit exact with the golden model (rule {rule})")
    return 0
