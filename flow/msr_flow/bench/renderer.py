#!/usr/bin/env python3
"""Renderer benchmark: for each built-in scene and quality, the 1920x1080 reference render time
(render_full on every core) and the rays per second it achieved; scene build time separately.

    python scripts/bench_renderer.py [--scenes cornell,bunny] [--quality fast,heavy]
                                     [--width 1920 --height 1080] [--out out/bench/renderer.json]
"""
from __future__ import annotations

import argparse
import json
import os
import platform
import sys
import time
from pathlib import Path

from msr_model.embree import open_renderer, scene_names

from ..filelist import ROOT


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scenes", default=",".join(scene_names()))
    ap.add_argument("--quality", default="fast,heavy")
    ap.add_argument("--width", type=int, default=1920)
    ap.add_argument("--height", type=int, default=1080)
    ap.add_argument("--out", default=str(ROOT / "out" / "bench" / "renderer.json"))
    args = ap.parse_args(argv)

    rows = []
    for scene in args.scenes.split(","):
        for quality in args.quality.split(","):
            t0 = time.perf_counter()
            with open_renderer(scene, args.width, args.height, quality) as r:
                t1 = time.perf_counter()
                c0 = time.process_time()
                r.render_full()
                t2 = time.perf_counter()
                cpu = time.process_time() - c0
                rays = r.rays
                threads = r.threads
            px = args.width * args.height
            row = {"scene": scene, "quality": quality, "width": args.width, "height": args.height,
                   "build_s": round(t1 - t0, 3), "render_s": round(t2 - t1, 3), "cpu_s": round(cpu, 3),
                   "threads": threads, "rays": rays, "rays_per_pixel": round(rays / px, 2),
                   "mrays_per_s": round(rays / (t2 - t1) / 1e6, 2),
                   "mrays_per_cpu_s": round(rays / max(cpu, 1e-9) / 1e6, 2)}
            rows.append(row)
            print(f"{scene:>10} {quality:>5}: build {row['build_s']:6.2f} s  render {row['render_s']:6.2f} s "
                  f"({row['cpu_s']:6.2f} CPU s)  {row['rays_per_pixel']:6.2f} rays/px  "
                  f"{row['mrays_per_s']:6.2f} Mrays/s  ({row['mrays_per_cpu_s']:.2f} per CPU s)", flush=True)

    load = os.getloadavg() if hasattr(os, "getloadavg") else None
    report = {"machine": {"cpu_count": os.cpu_count(), "platform": platform.platform(),
                          "processor": platform.processor(), "load_avg_at_end": load,
                          "embree_isa": os.environ.get("MSR_EMBREE_ISA", "avx2")},
              "results": rows}
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(report, indent=2) + "\n")
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
