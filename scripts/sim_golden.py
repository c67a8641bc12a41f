"""Interim `make sim`: the golden model on the built-in test picture, with quality figures."""
import argparse
import json
import sys
from pathlib import Path

import numpy as np
from skimage.metrics import peak_signal_noise_ratio, structural_similarity

from msr_model import ImageRenderer, Params, save_png, select
from msr_model.testimage import test_image


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--height", type=int, default=240)
    ap.add_argument("--tile", type=int, default=16)
    ap.add_argument("--levels", type=int, default=2)
    ap.add_argument("--thr", default="8,16")
    ap.add_argument("--metric", default="max")
    ap.add_argument("--fov-gain", type=int, default=0)
    ap.add_argument("--out", default="out/sim/testimage")
    a = ap.parse_args()
    params = Params(tile=a.tile, levels=a.levels, thr=tuple(int(t) for t in a.thr.split(",")),
                    metric=a.metric, fov_gain=a.fov_gain)
    ref = test_image(a.width, a.height)
    res = select(ImageRenderer(ref), a.width, a.height, params)
    out = Path(a.out)
    save_png(out / "golden.png", res.frame)
    save_png(out / "golden_source_map.png", res.source)
    save_png(out / "reference.png", ref)
    psnr = peak_signal_noise_ratio(ref, res.frame, data_range=255) if (ref != res.frame).any() else float("inf")
    ssim = structural_similarity(ref, res.frame, channel_axis=2, data_range=255)
    report = {**res.stats, "psnr_db": psnr, "ssim": ssim, "flow": "golden model only (no RTL yet)"}
    (out / "report.json").write_text(json.dumps(report, indent=2) + "\n")
    print(f"{a.width}x{a.height}: traced {res.stats['traced_fraction']:.1%}, PSNR {psnr:.2f} dB, "
          f"SSIM {ssim:.4f} -> {out}/")


if __name__ == "__main__":
    sys.exit(main())
