"""The golden `sequence` command (docs/spec/contracts.md, fourth round): frames 0 .. N-1 of a
scene along a camera path (or the scene's default orbit, msr_model.camera_path), each the
golden model's selective render of that frame's view.

    python -m msr_model sequence --scene S --width W --height H --frames N [--path FILE]
        [--rule R --tile T --levels L --thr a,b,.. --metric M --fov-gain G --budget B --gaze X,Y]
        [--reuse] --out DIR

writes DIR/frame_KKKK.png, DIR/source_map_KKKK.png and DIR/sequence.json. Frame K is `make
sim`'s frame K with the same parameters: the same camera strings (camera_path.scene_views) and
the same ray-budget driver sequence (`next_budget`: each frame after the first seeded with the
last frame's SCALE_OUT and activity per tile row, as flow/msr_flow/sim_sequence.py programs the
hardware). The pieces `make sim`'s sequence shares live here: `next_budget`, `frame_entry`
(the per-frame quality keys) and `Flicker`.
"""
from __future__ import annotations

import json
import math
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from . import budget as BG
from . import spec
from .clitools import OutputSet, UsageError, gaze_of
from .image_renderer import ImageRenderer, save_png
from .metrics import capped, flicker, format_db, psnr

REUSE_MISSING = "--reuse: reuse across frames: not available yet in the golden model"


def reuse_model():
    """The golden model of reuse across frames (msr_model.reuse, docs/spec/reuse.md), or None
    while the package has none."""
    try:
        from . import reuse
    except ImportError:
        return None
    return reuse if hasattr(reuse, "run_sequence") else None


@dataclass(frozen=True)
class SequenceSetup:
    """What a sequence run takes: the scene and frame size, the selection and its budget."""
    scene: str
    width: int
    height: int
    frames: int
    params: spec.Params
    rule: str = "patent"
    budget: int = 0                 # traced pixels per frame; 0: off
    path: str | None = None         # camera path file; None: the default orbit
    quality: str = "fast"
    reuse: bool = False


def first_budget(width: int, height: int, pixels: int, params: spec.Params) -> BG.BudgetConfig | None:
    """The first frame's budget registers (the driver's seed), None without a budget; a budget
    below the frame's initial grid is refused (UsageError), as START would refuse it."""
    if not pixels:
        return None
    cfg = BG.first_frame_config(width, height, pixels, params)
    try:
        BG.Controller(width, height, params, cfg)
    except spec.SpecError as e:
        raise UsageError(str(e)) from None
    return cfg


def next_budget(cfg: BG.BudgetConfig | None, stats: dict) -> BG.BudgetConfig | None:
    """The driver's registers for the frame after the one `stats` (select_budget's) came from:
    seeded with its SCALE_OUT and activity per tile row (docs/budget.md)."""
    if cfg is None:
        return None
    bc = stats["budget_control"]
    return BG.BudgetConfig(budget=cfg.budget, scale_init=bc["scale_out"], prior_shift=cfg.prior_shift,
                           profile=tuple(bc["activity_per_row"]), profile_scales=tuple(bc["scale_per_row"]))


def frame_entry(k: int, frame: np.ndarray, source: np.ndarray, reference: np.ndarray, camera: str,
                reused: int = 0) -> dict:
    """A frame's keys in sequence.json: traced (rays asked of the renderer), reused, the traced
    fraction, PSNR against the frame's full render (math.inf, JSON Infinity, when identical)."""
    traced = int((source < spec.SRC_INTERP_BASE).sum())
    p = psnr(reference, frame)
    return {"frame": k, "traced": traced, "reused": reused, "traced_fraction": traced / source.size,
            "psnr_db": p, "identical": not math.isfinite(p), "camera": camera}


@dataclass
class Flicker:
    """Temporal flicker of a sequence (msr_model.metrics.flicker): the rms change of the error
    image (frame minus its full render) from each frame to the next."""
    values: list[float] = field(default_factory=list)
    _prev: np.ndarray | None = None

    def add(self, frame: np.ndarray, reference: np.ndarray) -> float | None:
        """Take the next frame; its flicker against the last one (None for the first)."""
        err = frame.astype(np.int16) - reference.astype(np.int16)
        out = None if self._prev is None else flicker(self._prev, err)
        if out is not None:
            self.values.append(out)
        self._prev = err
        return out

    def summary(self) -> dict:
        """`flicker` (mean over the frame pairs, 0 for one frame) and `flicker_worst`."""
        v = self.values
        return {"flicker": float(np.mean(v)) if v else 0.0, "flicker_worst": float(max(v)) if v else 0.0}


def params_per_frame(params: spec.Params, views, frames: int, width: int, height: int) -> list[spec.Params]:
    """Each frame's parameters: `params`, with the gaze point of the path's keys where they carry
    one (camera_path: interpolated, rounded half up). A gaze given for the run as well as in the
    path is refused (UsageError): which one holds would be a guess."""
    try:
        gazes = views.gazes(frames, width, height)
    except spec.SpecError as e:
        raise UsageError(str(e)) from None
    if views.has_gaze and params.gaze is not None:
        raise UsageError(f"a gaze point for the run and gaze points in {views.source}: give one of them")
    return [params if g is None else replace(params, gaze=g) for g in gazes]


def summary(entries: list[dict]) -> dict:
    ps = [e["psnr_db"] for e in entries]
    return {"psnr_db_mean": float(np.mean([capped(p) for p in ps])),    # finite: identical counts as the cap
            "psnr_db_worst": float(min(ps)), "traced_total": sum(e["traced"] for e in entries)}


def run(setup: SequenceSetup, out_dir, log=None) -> dict:
    """Render the sequence, then write its files into out_dir, all or nothing; sequence.json's
    content is returned."""
    from .camera_path import scene_views
    from .embree import open_renderer
    W, H = setup.width, setup.height
    cfg = first_budget(W, H, setup.budget, setup.params)
    views = scene_views(setup.scene, W, H, setup.path, setup.quality)
    cams = views.cameras(setup.frames)
    frame_params = params_per_frame(setup.params, views, setup.frames, W, H)
    reused = None
    if setup.reuse:                         # the previous frame's pixels first (msr_model.reuse)
        model = reuse_model()
        if model is None:
            raise UsageError(REUSE_MISSING)
        reused = model.run_sequence(setup.scene, W, H, cams, frame_params, setup.rule, reuse=True,
                                    quality=setup.quality)
    entries, pictures, fl = [], [], Flicker()
    for k, cam in enumerate(cams):
        params = frame_params[k]
        with open_renderer(setup.scene, W, H, quality=setup.quality, camera=cam) as r:
            reference = r.render_full(progress=False)
        if reused is not None:
            result = reused[k]
        else:
            unit = ImageRenderer(reference)     # the renderer is deterministic: its pixels, from memory
            result = BG.select_budget(unit, W, H, params, cfg or BG.BudgetConfig(), rule=setup.rule)
        e = frame_entry(k, result.frame, result.source, reference, cam,
                        reused=int(result.reused) if reused is not None else 0)
        e["gaze"] = list(params.gaze or spec.default_gaze(W, H, params.tile))
        if reused is not None:
            e["traced"] = int(result.traced)    # rays asked of the renderer
            e["traced_fraction"] = e["traced"] / (W * H)
        e["flicker"] = fl.add(result.frame, reference)
        if cfg is not None:
            bc = result.stats["budget_control"]
            e.update(scale_init=bc["scale_init"], scale_out=bc["scale_out"])
        entries.append(e)
        pictures.append((result.frame, result.source))
        cfg = next_budget(cfg, result.stats)
        if log:
            log(e)
    seq = {"reuse": setup.reuse, "frames": entries, **fl.summary(), **summary(entries),
           "scene": setup.scene, "width": W, "height": H, "num_frames": setup.frames, "rule": setup.rule,
           "params": setup.params.as_dict(), "budget": setup.budget, "quality": setup.quality,
           "camera_path": views.source, "space": views.space}
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    with OutputSet() as out:
        for k, (frame, source) in enumerate(pictures):
            out.write(str(out_dir / f"frame_{k:04d}.png"), lambda t, f=frame: save_png(t, f, format="PNG"))
            out.write(str(out_dir / f"source_map_{k:04d}.png"), lambda t, s=source: save_png(t, s, format="PNG"))
        out.write_text(str(out_dir / "sequence.json"), json.dumps(seq, indent=2) + "\n")
    return seq


# --- command line (python -m msr_model sequence; the parser is msr_model.cli's) ---------------

def add_parser(sub, int_in_arg, thr_arg, budget_arg) -> None:
    """The `sequence` subcommand (the converters are cli's argparse types)."""
    from .rules import DEFAULT_RULE, RULES
    p = sub.add_parser("sequence", help="a sequence of frames along a camera path or the default orbit")
    p.add_argument("--scene", required=True, help="built-in scene name or model file")
    p.add_argument("--width", type=int_in_arg(1, spec.MAX_FRAME, "--width"), required=True)
    p.add_argument("--height", type=int_in_arg(1, spec.MAX_FRAME, "--height"), required=True)
    p.add_argument("--frames", type=int_in_arg(1, 10000, "--frames"), required=True, help="frames 0 .. N-1")
    p.add_argument("--path", default=None, metavar="FILE",
                   help="camera path file (contracts.md); default: the scene's default orbit")
    p.add_argument("--reuse", action="store_true",
                   help="reuse the previous frame's pixels (msr_model.reuse, docs/spec/reuse.md)")
    p.add_argument("--rule", choices=tuple(RULES), default=DEFAULT_RULE)
    p.add_argument("--tile", type=int, choices=spec.TILE_SIZES, default=16)
    p.add_argument("--levels", type=int, choices=spec.LEVEL_RANGE, default=2)
    p.add_argument("--thr", type=thr_arg, default=None, help="per-level thresholds (default 8,16,32 cut to L)")
    p.add_argument("--metric", choices=spec.METRICS, default="max")
    p.add_argument("--fov-gain", type=int_in_arg(0, 255, "--fov-gain"), default=0)
    p.add_argument("--budget", type=budget_arg, default=None, metavar="N|P%",
                   help="ray budget per frame, the driver's seeded sequence across frames (docs/budget.md)")
    p.add_argument("--gaze", default=None, metavar="X,Y", help="gaze point in pixels")
    p.add_argument("--quality", default="fast", help="renderer quality mode (fast|heavy)")
    p.add_argument("--out", required=True, help="output folder")


def setup_of(args) -> SequenceSetup:
    """The flags, checked before anything is rendered or written (UsageError otherwise)."""
    if args.reuse and reuse_model() is None:
        raise UsageError(REUSE_MISSING)
    if args.reuse and args.budget is not None:
        raise UsageError("--reuse with --budget: a ray budget with reuse is not available yet")
    thr = args.thr if args.thr is not None else spec.default_thresholds(args.levels)
    if len(thr) != args.levels:
        raise UsageError(f"--thr has {len(thr)} values but --levels is {args.levels}: give one per level")
    gaze = gaze_of(args.gaze, "--gaze", args.width, args.height)
    try:
        params = spec.Params(tile=args.tile, levels=args.levels, thr=thr, metric=args.metric,
                             fov_gain=args.fov_gain, gaze=gaze)
        pixels = BG.budget_pixels(args.budget if args.budget is not None else ("px", 0), args.width, args.height)
    except (ValueError, spec.SpecError) as e:
        raise UsageError(f"--{e}" if isinstance(e, ValueError) else str(e)) from None
    out = Path(args.out)
    if out.exists() and not out.is_dir():
        raise UsageError(f"--out {out} is not a folder")
    setup = SequenceSetup(scene=args.scene, width=args.width, height=args.height, frames=args.frames,
                          params=params, rule=args.rule, budget=pixels, path=args.path, quality=args.quality,
                          reuse=args.reuse)
    first_budget(setup.width, setup.height, setup.budget, setup.params)     # a budget below the grid: now
    return setup


def cmd_sequence(args) -> int:
    setup = setup_of(args)

    def log(e):
        print(f"  frame {e['frame']:4d}: traced {e['traced_fraction']:.1%}, PSNR {format_db(e['psnr_db'])}",
              flush=True)
    print(f"msr_model sequence: {setup.scene} {setup.width}x{setup.height}, {setup.frames} frames", flush=True)
    seq = run(setup, args.out, log=log)
    print(f"  along {seq['camera_path']}; flicker {seq['flicker']:.3f}; outputs in {args.out}/")
    return 0
