#!/usr/bin/env python3
"""Image quality against traced pixels, on real scenes, against the alternatives: `make eval`.

    python scripts/eval.py                 # quick run: small frames (make eval)
    python scripts/eval.py --full          # 1920x1080, every scene, fast and heavy (make eval FULL=1)
    python scripts/eval.py --scheduler tcp://host:8786   # the sweep on an existing Dask cluster
    python scripts/eval.py --workers 0     # the sweep serially in this process

The sweep (scenes x modes x methods x settings) runs as tasks on Dask distributed: a
LocalCluster with one worker per CPU unless --scheduler or $MSR_DASK_SCHEDULER names an
existing scheduler; the records are the same as a serial run's (msr_eval.sweep). The wall-time
speed-up is measured afterwards, here, on the live Embree renderer (heavy mode), where the
selective frame is also checked to be bit-equal to the cached run.

Output: out/eval/results.json, out/eval/*.png plots and example images; with --docs also
docs/results.md and small figures in docs/img/. The code: msr_eval.metrics, .sweep, .executors, .report.
"""
from __future__ import annotations

import argparse
import json
import subprocess
import time
from pathlib import Path

from msr_eval import conv_report as CR
from msr_eval import conv_store as CS
from msr_eval import headline as HL
from msr_eval import reference as REF
from msr_eval import report as R
from msr_eval import sweep as S
from msr_eval.executors import make_executor
from msr_eval.metrics import PSNR_CAP, pick_near, rule_comparison, summarise
from msr_eval.scenes import MODEL_FILES, scene_id

REPO = Path(__file__).resolve().parents[2]


def run_temporal(a, executor, full: bool, W: int, H: int, out: Path) -> dict:
    """The sequences of the temporal section (msr_eval.temporal): the set's five scenes, 60
    frames at 960x540 in the full run; two scenes, 6 frames at the quick size otherwise."""
    from msr_eval import temporal as T
    scenes = [s for s in (T.SEQ_SCENES if full else T.QUICK_SCENES) if "/" not in s or Path(s).is_file()]
    frames = a.temporal_frames or (60 if full else 6)
    tw, th = (960, 540) if full else (W, H)
    res = T.run(scenes, frames, tw, th, executor, log=lambda m: print(m, flush=True))
    T.plot(res, out / "temporal.png")
    return res


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
    ap.add_argument("--scheduler", default=None,
                    help="Dask scheduler address (tcp://host:port); default $MSR_DASK_SCHEDULER, "
                         "else a LocalCluster; 'serial' runs every task in this process")
    ap.add_argument("--workers", type=int, default=None,
                    help="LocalCluster workers (default: one per CPU); 0 = serial")
    ap.add_argument("--no-progress", action="store_true", help="no progress bars")
    ap.add_argument("--no-conv", action="store_true",
                    help="no converged reference (score against the full render only)")
    ap.add_argument("--conv-grid", type=int, default=None,
                    help="converged reference: GRID x GRID samples per pixel (default: msr_eval.reference."
                         "CONV_GRIDS: heavy 256 spp, 1024 where two seeds differ by more than "
                         "CONV_TARGET_DB; fast 256 spp)")
    ap.add_argument("--conv-page", default=None, metavar="NAME",
                    help="also write the converged comparison alone as DOCS_DIR/NAME (e.g. results_converged.md)")
    ap.add_argument("--no-conv-check", action="store_true",
                    help="skip the second-seed render of each converged reference (no two-seed PSNR)")
    ap.add_argument("--conv-check", action="store_true",
                    help="the second-seed render at full size too (the quick run always has it)")
    ap.add_argument("--conv-modes", default=None,
                    help="modes with a converged reference (default: every mode quick, heavy at full size)")
    ap.add_argument("--store", default=None, metavar="DIR",
                    help="committed references and records to resume from and write to (default: "
                         "data/converged with --full, none in the quick run; 'none' for none)")
    ap.add_argument("--refs-only", action="store_true",
                    help="stop after the full renders and converged references")
    ap.add_argument("--temporal-frames", type=int, default=None, metavar="N",
                    help="frames of each sequence of the temporal section (default 60 with --full at 960x540, "
                         "6 in the quick run at its size; msr_eval.temporal)")
    ap.add_argument("--no-temporal", action="store_true", help="no sequences (temporal section)")
    ap.add_argument("--temporal-only", action="store_true",
                    help="only the sequences: added to an existing OUT/results.json, then the docs rewritten")
    ap.add_argument("--heldout", action="store_true",
                    help="held-out scenes (with --scenes): write the head-to-head to "
                         "data/converged/heldout_WxH.json for the results page, not the page itself")
    a = ap.parse_args(argv)

    if a.temporal_only:
        result = json.loads((Path(a.out) / "results.json").read_text())
        ex = make_executor(a.scheduler, a.workers)
        try:
            result["temporal"] = run_temporal(a, ex, result["config"]["full"], result["config"]["width"],
                                              result["config"]["height"], Path(a.out))
        finally:
            ex.close()
        (Path(a.out) / "results.json").write_text(json.dumps(result, indent=1))
        if a.docs:
            R.write_docs(result, Path(a.out), Path(a.docs_dir))
        return result
    if a.report_only:
        result = json.loads((Path(a.out) / "results.json").read_text())
        if any("psnr_conv" in r and r["mode"] == "heavy" for r in result["records"]):
            result["head_to_head"] = HL.analyse(result["records"], "heavy")    # the page's code of now
        if a.docs or not a.conv_page:
            R.write_docs(result, Path(a.out), Path(a.docs_dir))
        if a.conv_page and result.get("converged"):
            CR.write_page(result, Path(a.out), Path(a.docs_dir), a.conv_page)
        return result
    full = a.full
    W = a.width or (1920 if full else 192)
    H = a.height or (1080 if full else 108)
    quick = not full
    scales = S.FULL_SCALES if full else S.QUICK_SCALES
    backend = S.Backend(a.backend)
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
    # Full size: the fast renderer is scored against its own full render only (its
    # error against a converged image is aliasing, which no selective method removes); the heavy
    # renderer's reference takes the sample count the quick-size ladder chose per scene, one seed
    # unless --conv-check; finished references and records are committed under data/converged/.
    conv_check = (a.conv_check or quick) and not a.no_conv_check
    conv_modes = tuple(a.conv_modes.split(",")) if a.conv_modes else (None if quick else ("heavy",))
    store = a.store if a.store is not None else (str(CS.STORE) if full else "none")
    cfg = S.SweepConfig(W, H, tuple(scales), quick, a.all_metrics, out / "cache", conv=not a.no_conv,
                        conv_grid=a.conv_grid, conv_check=conv_check, conv_modes=conv_modes,
                        conv_ladder=full, store=None if store == "none" else Path(store),
                        refs_only=a.refs_only)
    sweep = cfg.sweep
    log = lambda s: print(s, flush=True)  # noqa: E731
    log(f"eval: {W}x{H}, backend {backend.name}, scenes {[scene_id(s) for s in scenes]}, modes {modes}")

    t_start = time.perf_counter()
    executor = make_executor(a.scheduler, a.workers)
    try:
        log(f"eval: tasks on {executor.name}")
        records, refs, infos = S.run_sweep(backend, scenes, modes, cfg, executor, log=log,
                                           show_progress=not a.no_progress)
        temporal = (run_temporal(a, executor, full, W, H, out)
                    if backend.embree and not a.no_temporal and not a.refs_only else None)
    finally:
        executor.close()
    if a.refs_only:
        log(f"eval: references done in {time.perf_counter() - t_start:.0f} s")
        return None

    needed, set_curves, headline = summarise(records, modes)
    conv_records = REF.as_conv(records)
    needed_c, set_curves_c, headline_c = summarise(conv_records, modes) if conv_records else ({}, {}, {})
    rules_cmp = rule_comparison(records)

    speed = []
    if backend.embree and not a.no_speedup:
        smode = "heavy" if "heavy" in modes else modes[0]
        for scene in scenes:
            for fam in ("multi_L3_T16", "multi_L3_T16_lindilate"):
                r = pick_near(records, scene_id(scene), smode, fam, 40.0)
                if r is not None:
                    s = S.speedup(backend, scene, smode, r, refs[(scene, smode)], infos[(scene, smode)], sweep)
                    speed.append(s)
                    log(f"  speedup {s['scene']}/{smode} {fam} {s['label']}: {s['speedup']:.2f}x "
                        f"at {100 * s['traced_fraction']:.1f} % traced, bit-equal {s['bit_equal_to_cached_run']}")

    # plots and examples
    for mode in modes:
        R.plot_curves(records, mode, out / f"curves_{mode}.png", f"PSNR against traced pixels, {mode} renderer, {W}x{H}")
        R.plot_set(set_curves, mode, out / f"pareto_{mode}.png", f"Mean over the scene set, {mode} renderer, {W}x{H}")
        if conv_records:
            CR.plot_scene_fronts(records, mode, out / f"fronts_conv_{mode}.png",
                                  f"Pareto fronts against the converged reference, {mode} renderer, {W}x{H}")
    # The converged head-to-head that leads the page (msr_eval.headline): heavy renderer.
    head_to_head = HL.analyse(records, "heavy") if conv_records else {}
    if head_to_head:
        HL.plot_fronts(records, out / "fronts_headline.png",
                       f"Traced pixels against PSNR to the converged image, heavy renderer, {W}x{H}")
    conv_info = {}
    lad = CS.ladder()
    for s in scenes:
        ci = infos.get((s, "heavy"), {}).get("converged")
        if ci:
            conv_info[scene_id(s)] = {"spp": ci.get("spp"), "render_s": ci.get("render_s"),
                                        "from": ci.get("from", "rendered"),
                                        "ladder": lad.get(scene_id(s), {}).get("two_seeds_db", {})}
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
        res = S.rerun(refs[(scene, ex_mode)], r, sweep, gbuf=S.gbuffer_of(backend, scene, cfg))
        strip = R.example_strip(refs[(scene, ex_mode)], res, panel_w=min(320, W))
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
                   "threshold_scales": list(scales), "psnr_cap_db": PSNR_CAP, "executor": executor.name, "git": commit,
                   "date_utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
                   "runtime_s": time.perf_counter() - t_start,
                   "metrics_note": ("PSNR for every setting; SSIM and FLIP for every setting with --all-metrics, "
                                    "else for the key settings: the cheapest setting of each of KEY_FAMILIES "
                                    "that reaches 40 dB (and 35 dB in the quick run) on the scene; in the full "
                                    "run FLIP only for FLIP_FAMILIES_FULL"),
                   "key_families": list(S.KEY_FAMILIES), "flip_families_full": list(S.FLIP_FAMILIES_FULL)},
        "full_render": [{"scene": scene_id(s), "mode": m, **infos[(s, m)]} for s in scenes for m in modes],
        "records": records,
        "needed_fraction": needed,
        "set_curves": set_curves,
        "headline": headline,
        "rule_vs_patent": rules_cmp,
        "converged": {"needed_fraction": needed_c, "set_curves": set_curves_c, "headline": headline_c,
                      "conv_grids": {m: list(REF.conv_grids_for(m, a.conv_grid)) for m in modes},
                      "conv_modes": list(conv_modes) if conv_modes else list(modes),
                      "per_scene": {f"{scene_id(s)}/{m}": infos[(s, m)]["converged"] for s in scenes
                                    for m in modes if "converged" in infos[(s, m)]},
                      "target_two_seeds_db": REF.CONV_TARGET_DB,
                      "seeds": list(REF.CONV_SEEDS)} if conv_records else None,
        "head_to_head": head_to_head,
        "head_to_head_references": conv_info,
        "speedup": speed,
        "examples": examples,
        "temporal": temporal,
    }
    (out / "results.json").write_text(json.dumps(result, indent=1))
    if a.heldout and head_to_head:
        ho = {"config": {**result["config"], "conv_spp": (a.conv_grid or 16) ** 2},
              "head_to_head": head_to_head, "head_to_head_references": conv_info}
        hf = (CS.STORE if store == "none" else Path(store)) / f"heldout_{W}x{H}.json"
        hf.write_text(json.dumps(ho, indent=1))
        log(f"eval: held-out head-to-head in {hf}")
    log(f"eval: wrote {out / 'results.json'} ({len(records)} records) in {time.perf_counter() - t_start:.0f} s")
    for mode, h in headline.items():
        b, c = h["best_psnr_at_most_15pct"], h["cheapest_40db_mean"]
        if b:
            log(f"  {mode}: best mean PSNR at <= 15 % traced: {b['psnr_mean']:.2f} dB at "
                f"{100 * b['traced_fraction']:.1f} % ({b['family']} {b['label']})")
        if c:
            log(f"  {mode}: cheapest >= 40 dB mean: {100 * c['traced_fraction']:.1f} % ({c['family']} {c['label']})")
    if a.docs:
        R.write_docs(result, out, Path(a.docs_dir))
    if a.conv_page and result.get("converged"):
        CR.write_page(result, out, Path(a.docs_dir), a.conv_page)
    return result


if __name__ == "__main__":
    main()
