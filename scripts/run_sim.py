"""`make sim`: one frame through the RTL (Verilator harness + DPI Embree) and the golden model.

    python scripts/run_sim.py --harness build/sim/fast/Vmsr_sim_top --scene cornell \
        --width 640 --height 480 [--tile 16 --levels 2 --thr 8,16 --metric max --fov-gain 0]
        [--out DIR] [--waves [--wave-tile TX,TY | --wave-cycles FROM,TO]]

Writes frame.png, source_map.png (read back from the RTL's memory), golden.png,
golden_source_map.png, reference.png and report.json into DIR (default out/sim/<scene>/)
and prints a one-screen summary (../shared/spec/contracts.md, "Full simulation").
Bad arguments or a model file that cannot be read: one line on stderr, exit status 2.
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

from msr_model import ImageRenderer, Params, SpecError, save_png, select
from msr_model import spec

EXIT_BAD_INPUT = 2
ROOT = Path(__file__).resolve().parents[1]


class UsageError(Exception):
    pass


class _Parser(argparse.ArgumentParser):
    def error(self, message):
        raise UsageError(message)


def parse(argv):
    ap = _Parser(prog="make sim", description=__doc__.splitlines()[0])
    ap.add_argument("--harness", required=True, help="the Verilator harness binary")
    ap.add_argument("--scene", default="cornell")
    ap.add_argument("--width", default="640")
    ap.add_argument("--height", default="480")
    ap.add_argument("--tile", default="16")
    ap.add_argument("--levels", default="2")
    ap.add_argument("--thr", default="")
    ap.add_argument("--metric", default="max")
    ap.add_argument("--fov-gain", default="0")
    ap.add_argument("--out", default="")
    ap.add_argument("--quality", default="fast")
    ap.add_argument("--camera", default="", help="EX,EY,EZ,TX,TY,TZ,FOV (model units, degrees); empty: the scene's view")
    ap.add_argument("--waves", action="store_true", help="FST of a window (harness built with tracing)")
    ap.add_argument("--wave-tile", default="", help="TX,TY: trace one tile's life (default: the centre tile)")
    ap.add_argument("--wave-cycles", default="", help="FROM,TO: trace a cycle range instead")
    ap.add_argument("--rnd-latency", type=int, default=4, help="render latency in cycles")
    ap.add_argument("--rnd-jitter", type=int, default=8, help="extra random latency (reorders responses)")
    return ap.parse_args(argv)


def as_int(text, what, lo, hi):
    try:
        v = int(str(text), 0)
    except ValueError:
        raise UsageError(f"{what} must be an integer, got {text!r}") from None
    if not lo <= v <= hi:
        raise UsageError(f"{what} {v} outside {lo}..{hi}")
    return v


def params_of(a) -> tuple[int, int, Params]:
    w = as_int(a.width, "WIDTH", 1, spec.MAX_FRAME)
    h = as_int(a.height, "HEIGHT", 1, spec.MAX_FRAME)
    tile = as_int(a.tile, "TILE", 1, 4096)
    levels = as_int(a.levels, "LEVELS", 1, 3)
    thr_text = a.thr or ",".join(str(t) for t in (8, 16, 32)[:levels])
    try:
        thr = tuple(int(t.strip(), 0) for t in thr_text.split(","))
    except ValueError:
        raise UsageError(f"THR must be a comma-separated list of integers, got {thr_text!r}") from None
    if len(thr) != levels:
        raise UsageError(f"THR has {len(thr)} values but LEVELS is {levels}: give one per level")
    gain = as_int(a.fov_gain, "FOV_GAIN", 0, 255)
    return w, h, Params(tile=tile, levels=levels, thr=thr, metric=a.metric, fov_gain=gain)


def scene_label(scene: str) -> str:
    p = Path(scene)
    return p.stem if (p.suffix or os.sep in scene) else scene


def read_pnm(path: Path) -> np.ndarray:
    from PIL import Image
    with Image.open(path) as im:
        return np.asarray(im)


def run(a) -> int:
    W, H, params = params_of(a)
    harness = Path(a.harness)
    if not harness.is_file():
        raise UsageError(f"harness {harness} not built (run make sim)")
    out = Path(a.out or ROOT / "out" / "sim" / scene_label(a.scene))
    if out.exists() and not out.is_dir():
        raise UsageError(f"OUT {out} is not a folder")

    # The scene must open in Python before anything runs: a bad model file is exit status 2.
    from msr_model.embree import open_renderer
    t0 = time.perf_counter()
    renderer = open_renderer(a.scene, W, H, quality=a.quality, camera=a.camera or None)
    out.mkdir(parents=True, exist_ok=True)

    thr3 = list(params.thr) + [0] * (3 - params.levels)
    cmd = [str(harness), "--width", str(W), "--height", str(H), "--tile", str(params.tile),
           "--levels", str(params.levels), "--thr", ",".join(map(str, thr3)), "--metric", params.metric,
           "--fov-gain", str(params.fov_gain), "--frame", str(out / "rtl_frame.ppm"),
           "--source", str(out / "rtl_source.pgm"), "--stats", str(out / "rtl_stats.json"),
           f"+scene={a.scene}", f"+width={W}", f"+height={H}",
           f"+quality={0 if a.quality == 'fast' else 1}",
           f"+rnd_latency={a.rnd_latency}", f"+rnd_jitter={a.rnd_jitter}"]
    if a.camera:
        cmd.append(f"+camera={a.camera}")  # read by sim/msr_dpi.cpp, passed to the library unchanged
    if a.waves:
        ntx, nty = spec.tile_counts(W, H, params.tile)
        cmd += ["--waves", str(out / "waves.fst")]
        if a.wave_cycles:
            cmd += ["--wave-cycles", a.wave_cycles]
        else:
            cmd += ["--wave-tile", a.wave_tile or f"{ntx // 2},{nty // 2}"]
    # The RTL runs in its own process while this one renders the reference and the golden frame.
    t_rtl = time.perf_counter()
    proc = subprocess.Popen(cmd)
    try:
        reference = renderer.render_full(progress=False)
    finally:
        renderer.close()
    t_ref = time.perf_counter() - t0
    # The renderer is deterministic (spec "Terms"), so the full render answers the golden
    # model's trace requests with exactly the pixels the renderer would give.
    golden = select(ImageRenderer(reference), W, H, params)
    rc = proc.wait()
    t_rtl = time.perf_counter() - t_rtl
    if rc != 0:
        print(f"make sim: error: the RTL simulation failed (exit status {rc})", file=sys.stderr)
        return 1

    if a.waves:
        fst = out / "waves.fst"
        if not fst.is_file():
            print("make sim: error: the harness wrote no waves.fst (was the window ever reached?)", file=sys.stderr)
            return 1
        subprocess.run([sys.executable, str(ROOT / "scripts" / "gen_gtkw.py"), str(fst), str(out / "waves.gtkw")],
                       check=True)

    frame = read_pnm(out / "rtl_frame.ppm")
    source = read_pnm(out / "rtl_source.pgm")
    rtl = json.loads((out / "rtl_stats.json").read_text())
    for f in ("rtl_frame.ppm", "rtl_source.pgm", "rtl_stats.json"):
        (out / f).unlink()

    frame_ok = bool(np.array_equal(frame, golden.frame))
    source_ok = bool(np.array_equal(source, golden.source))
    from skimage.metrics import peak_signal_noise_ratio, structural_similarity
    psnr = (float(peak_signal_noise_ratio(reference, frame, data_range=255))
            if (reference != frame).any() else float("inf"))
    ssim = float(structural_similarity(reference, frame, channel_axis=2, data_range=255))

    save_png(out / "frame.png", frame)
    save_png(out / "source_map.png", source)
    save_png(out / "golden.png", golden.frame)
    save_png(out / "golden_source_map.png", golden.source)
    save_png(out / "reference.png", reference)

    pixels = W * H
    traced = int((source < spec.SRC_INTERP_BASE).sum())
    counters_ok = (sum(rtl[f"traced_{k}"] for k in ("initial", "level1", "level2", "level3")) == traced and
                   rtl["traced_initial"] == golden.stats["traced_initial"])
    report = {
        "bit_exact": frame_ok and source_ok,
        "frame_equal": frame_ok,
        "source_map_equal": source_ok,
        "mismatched_pixels": int((frame != golden.frame).any(axis=2).sum()),
        "traced_fraction": traced / pixels,
        "traced": traced,
        "interpolated": pixels - traced,
        "psnr_db": psnr if np.isfinite(psnr) else None,
        "ssim": ssim,
        "cycles": rtl["cycles"],
        "pixels": pixels,
        "cycles_per_pixel": rtl["cycles"] / pixels,
        "sim_cycles_per_second": rtl["sim_cycles_per_second"],
        "sim_seconds": rtl["sim_seconds"],
        "rtl_wall_seconds": round(t_rtl, 3),
        "reference_seconds": round(t_ref, 3),
        "perf_counters": {k: v for k, v in rtl.items() if k.startswith(("traced_", "interpolated_", "render_", "memory_"))},
        "perf_counters_match_source_map": counters_ok,
        "scene": a.scene,
        "camera": a.camera or None,
        "width": W,
        "height": H,
        "params": params.as_dict(),
        "quality": a.quality,
        "render_latency": a.rnd_latency,
        "render_jitter": a.rnd_jitter,
        "num_engines": 4,
    }
    (out / "report.json").write_text(json.dumps(report, indent=2) + "\n")

    p = params
    print(f"make sim: {a.scene} {W}x{H}, tile {p.tile}, levels {p.levels}, thr {','.join(map(str, p.thr))}, "
          f"metric {p.metric}, fov gain {p.fov_gain}")
    print(f"  bit exact vs golden model : {'yes' if report['bit_exact'] else 'NO'}"
          f" (frame {'=' if frame_ok else '!='}, source map {'=' if source_ok else '!='})")
    print(f"  traced                    : {traced} of {pixels} pixels ({traced / pixels:.1%})")
    print(f"  quality vs full render    : PSNR {'inf' if not np.isfinite(psnr) else f'{psnr:.2f}'} dB, SSIM {ssim:.4f}")
    print(f"  RTL cycles                : {rtl['cycles']} ({rtl['cycles'] / pixels:.3f} cycles/pixel)")
    print(f"  simulation speed          : {rtl['sim_cycles_per_second'] / 1e6:.2f} Mcycles/s, "
          f"RTL run {t_rtl:.1f} s, reference render {t_ref:.1f} s")
    if a.waves:
        print(f"  waves                     : {out / 'waves.fst'} (make waves)")
    print(f"  outputs                   : {out}/")
    return 0 if report["bit_exact"] else 1


def main(argv=None) -> int:
    try:
        return run(parse(argv))
    except (UsageError, SpecError) as e:
        msg = str(e.args[0]) if e.args else repr(e)
        print(f"make sim: error: {msg.splitlines()[0]}", file=sys.stderr)
        return EXIT_BAD_INPUT


if __name__ == "__main__":
    sys.exit(main())
