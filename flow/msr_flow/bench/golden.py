"""Golden-model speed: wall time of the vectorised model on frames up to 1920x1080.

Writes out/bench/golden.json. Compare ratios inside one run: the machine is shared."""
import json
import time
from pathlib import Path

from tqdm import tqdm

from msr_model import ImageRenderer, Params, default_thresholds, select
from msr_model.testimage import test_image

CASES = [(640, 480, 16, 2), (1920, 1080, 8, 1), (1920, 1080, 16, 2), (1920, 1080, 32, 3),
         (4096, 4096, 16, 2)]


def main():
    rows = []
    for w, h, t, lv in tqdm(CASES, desc="golden bench", disable=None):
        img = test_image(w, h)
        params = Params(tile=t, levels=lv, thr=default_thresholds(lv))
        best = float("inf")
        for _ in range(3):
            t0 = time.perf_counter()
            res = select(ImageRenderer(img), w, h, params)
            best = min(best, time.perf_counter() - t0)
        rows.append({"width": w, "height": h, "tile": t, "levels": lv, "seconds": round(best, 4),
                     "mpixels_per_s": round(w * h / best / 1e6, 2),
                     "traced_fraction": round(res.stats["traced_fraction"], 4)})
    out = Path("out/bench/golden.json")
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(rows, indent=2) + "\n")
    for r in rows:
        print(f"golden {r['width']}x{r['height']} T={r['tile']} L={r['levels']}: {r['seconds']:.3f} s "
              f"({r['mpixels_per_s']} Mpixel/s, traced {r['traced_fraction']:.1%})")


if __name__ == "__main__":
    main()
