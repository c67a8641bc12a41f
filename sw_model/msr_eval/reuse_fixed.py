"""The reuse study with the fixed-point golden model (msr_model.reuse, docs/spec/reuse.md).

Per scene of the sequence set: the orbit of msr_eval.temporal, per frame the full render and
its inverse-depth plane (the renderer's 16-bit format), the rules alone over a threshold sweep
(golden.select) and rule + reuse (msr_model.reuse.select_with_reuse, the hardware's integer
steps) at two threshold scales. Rays are counted as the renderer was asked. The result has the
float study's layout (msr_eval.reuse: equal_quality, markdown_table apply) plus per run the
worst frame's traced count against the sequence mean (frames 1..N-1).

    python -m msr_eval.reuse_fixed --scenes cornell duck --frames 60 --width 480 --height 270 \
        --out build/reuse_fixed [--merge A/reuse.json B/reuse.json]
"""
from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np

from msr_model import ImageRenderer, Params
from msr_model import reuse as RU
from msr_model.golden import select

from . import reuse as FL
from .reuse import RULE_NAMES, _scaled, equal_quality, markdown_table

SWEEP = (0.25, 0.35, 0.5, 0.75, 1.0, 1.5, 2.0)
REUSE_SCALES = (0.5, 1.0)
FLOAT_MODES = ("float", "floatt")    # the float study as published; the same reusing traces only


def task_scene(scene: str, width: int, height: int, frames: int, log=print, sweep=SWEEP,
               reuse_scales=REUSE_SCALES, with_float: bool = True, refresh: int = RU.REFRESH,
               age_max: int = RU.AGE_MAX) -> dict:
    from msr_model.embree import open_renderer
    from msr_model.metrics import capped, flicker, psnr
    from .temporal import orbit_path
    with open_renderer(scene, width, height) as r:
        view = r.view()
        invz_exp = RU.choose_invz_exp(r)
    unit = FL.placement_unit(scene, view) if with_float else 1.0
    cams = [orbit_path(view, frames).camera(k) for k in range(frames)]
    keys = [(rule, "alone", s) for rule in RULE_NAMES for s in sweep]
    keys += [(rule, "reuse", s) for rule in RULE_NAMES for s in reuse_scales]
    # the float study's method beside it (chains bounded at 4): as published, and reusing only
    # where the rule traces (the fixed-point contract's choice)
    keys += [("lindilate", mode, s) for mode in FLOAT_MODES for s in reuse_scales] if with_float else []
    per = {k: {"psnr": [], "traced": [], "flicker": [], "saved": [], "reused": [], "rays": []} for k in keys}
    state = {k: None for k in keys}
    err_prev = {}
    ys, xs = np.divmod(np.arange(width * height, dtype=np.int32), np.int32(width))
    for f, cam in enumerate(cams):
        t0 = time.perf_counter()
        with open_renderer(scene, width, height, quality="fast", camera=cam) as r:
            full = r.render_full(progress=False)
            _, invz = r.render_invz(xs, ys, invz_exp)
            true_z = r.gbuffer_full()[2] if with_float else None
        plane = RU.PlaneRenderer(full, invz.reshape(height, width))
        for key in keys:
            rule, mode, s = key
            params = Params(tile=16, levels=3, thr=_scaled(s))
            if mode == "alone":
                res = select(plane, width, height, params, rule)
                out, traced, reused = res.frame, int((res.source < 16).sum()), 0
            elif mode in FLOAT_MODES:
                fcam = FL.Camera.from_string(cam, width, height, unit)
                res = FL.select_reuse(ImageRenderer(full), width, height, params, rule, true_z, state[key], fcam,
                                      only_traced=mode == "floatt", max_age=4)
                state[key] = FL.PrevFrame(res.frame, res.depth, fcam, res.age)
                out, traced, reused = res.frame, res.traced, res.reused
            else:
                res, state[key] = RU.select_with_reuse(plane, width, height, params, rule, cam, state[key], invz_exp,
                                                       refresh=refresh, age_max=age_max)
                out, traced, reused = res.frame, res.traced, res.reused
            err = out.astype(np.int16) - full.astype(np.int16)
            m = per[key]
            m["psnr"].append(capped(psnr(full, out)))
            m["traced"].append(traced / (width * height))
            m["rays"].append(traced)
            m["saved"].append(reused / (width * height))     # reuse replaces traces only
            m["reused"].append(reused / (width * height))
            if key in err_prev:
                m["flicker"].append(flicker(err_prev[key], err))
            err_prev[key] = err
        log(f"reuse_fixed: {scene} frame {f + 1}/{frames} ({time.perf_counter() - t0:.1f} s)")
    return {"cameras": cams, "invz_exp": invz_exp, "runs": {f"{r}|{m}|{s}": v for (r, m, s), v in per.items()}}


def worst_ratio(run: dict, skip: int = 1) -> float:
    """The largest traced count of frames skip.. over their mean."""
    rays = np.asarray(run["rays"][skip:], float)
    return float(rays.max() / rays.mean()) if rays.size and rays.mean() > 0 else float("nan")


def finish(result: dict) -> dict:
    for sc in result["scenes"].values():
        sc["equal_quality"] = [equal_quality(sc, r, s) for r in RULE_NAMES for s in result["reuse_scales"]]
        for e in sc["equal_quality"]:
            e["worst_ratio"] = worst_ratio(sc["runs"][f"{e['rule']}|reuse|{e['scale']}"])
            e["worst_ratio_alone"] = worst_ratio(sc["runs"][f"{e['rule']}|alone|{e['scale']}"])
        sc["equal_quality_float"] = {}
        for mode in FLOAT_MODES:
            if f"lindilate|{mode}|1.0" not in sc["runs"]:
                continue
            runs = {k: v for k, v in sc["runs"].items() if "|alone|" in k}
            runs.update({k.replace(f"|{mode}|", "|reuse|"): v for k, v in sc["runs"].items() if f"|{mode}|" in k})
            eq = [equal_quality({"runs": runs}, "lindilate", s) for s in result["reuse_scales"]]
            for e in eq:
                e["worst_ratio"] = worst_ratio(runs[f"lindilate|reuse|{e['scale']}"])
            sc["equal_quality_float"][mode] = eq
    return result


def compare_table(result: dict) -> str:
    """Lindilate: rays saved at equal PSNR, fixed point against the float method's two forms."""
    from msr_model.scenes import scene_id
    lines = ["| scene | thr | saved: fixed point | float, traces only | float as published | "
             "worst/mean: fixed | float traces only | float published |", "|---|---|---|---|---|---|---|---|"]
    pct = lambda e: f"{100 * e['saved_rel']:.1f} %" if np.isfinite(e["saved_rel"]) else "-"  # noqa: E731
    for scene, sc in result["scenes"].items():
        fx = [e for e in sc["equal_quality"] if e["rule"] == "lindilate"]
        fl = sc.get("equal_quality_float", {})
        for i, e in enumerate(fx):
            t, p = fl.get("floatt", [None] * 2)[i], fl.get("float", [None] * 2)[i]
            lines.append(f"| {scene_id(scene)} | {','.join(map(str, e['thr']))} | {pct(e)} | "
                         f"{pct(t) if t else '-'} | {pct(p) if p else '-'} | {e['worst_ratio']:.3f} | "
                         f"{t['worst_ratio'] if t else float('nan'):.3f} | {p['worst_ratio'] if p else float('nan'):.3f} |")
    return "\n".join(lines)


def worst_table(result: dict) -> str:
    from msr_model.scenes import scene_id
    lines = ["| scene | rule | thr | worst frame / mean traced, + reuse | the same, rule alone |", "|---|---|---|---|---|"]
    for scene, sc in result["scenes"].items():
        for e in sc["equal_quality"]:
            lines.append(f"| {scene_id(scene)} | {e['rule']} | {','.join(map(str, e['thr']))} | "
                         f"{e['worst_ratio']:.3f} | {e['worst_ratio_alone']:.3f} |")
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m msr_eval.reuse_fixed", description=__doc__.split("\n")[0])
    ap.add_argument("--scenes", nargs="+", default=["cornell", "duck"])
    ap.add_argument("--frames", type=int, default=60)
    ap.add_argument("--width", type=int, default=480)
    ap.add_argument("--height", type=int, default=270)
    ap.add_argument("--out", type=Path, default=Path("build/reuse_fixed"))
    ap.add_argument("--merge", nargs="+", type=Path, default=None, help="no run: merge these reuse.json files")
    ap.add_argument("--alone-from", type=Path, default=None,
                    help="take the rules-alone and float runs from this reuse.json (same scenes and size)")
    ap.add_argument("--refresh", type=int, default=RU.REFRESH, help="the refresh period (study only)")
    ap.add_argument("--age-max", type=int, default=RU.AGE_MAX, help="the age bound (study only)")
    a = ap.parse_args(argv)
    if a.merge:
        parts = [json.loads(p.read_text()) for p in a.merge]
        res = {**parts[0], "scenes": {k: v for p in parts for k, v in p["scenes"].items()}}
    else:
        t0 = time.perf_counter()
        res = {"width": a.width, "height": a.height, "frames": a.frames, "sweep_scales": list(SWEEP),
               "reuse_scales": list(REUSE_SCALES), "scenes": {}}
        old = json.loads(a.alone_from.read_text()) if a.alone_from else None
        res.update(refresh=a.refresh, age_max=a.age_max)
        for scene in a.scenes:
            if old is None:
                res["scenes"][scene] = task_scene(scene, a.width, a.height, a.frames, refresh=a.refresh,
                                                  age_max=a.age_max)
                continue
            sc = task_scene(scene, a.width, a.height, a.frames, sweep=(), with_float=False, refresh=a.refresh,
                            age_max=a.age_max)
            sc["runs"].update({k: v for k, v in old["scenes"][scene]["runs"].items() if "|reuse|" not in k})
            res["scenes"][scene] = sc
        res["seconds"] = round(time.perf_counter() - t0, 1)
    res = finish(res)
    a.out.mkdir(parents=True, exist_ok=True)
    (a.out / "reuse.json").write_text(json.dumps(res, indent=1) + "\n")
    text = markdown_table(res) + "\n\n" + worst_table(res) + "\n\n" + compare_table(res)
    (a.out / "reuse_table.md").write_text(text + "\n")
    print(text)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
