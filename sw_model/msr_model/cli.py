"""Command line of the golden model (docs/spec/contracts.md).

    python -m msr_model select IMAGE.png --tile 16 --levels 2 --thr 8,16 [--metric max|sum]
        [--fov-gain 0] [--gaze X,Y] [--rule patent|lindilate|lindilate2d] --out OUT.png --source-map MAP.png --stats STATS.json
        [--overview SUMMARY.png] [--budget N|P%] [--scale-init U] [--prior-shift S] [--budget-prev STATS.json]
    python -m msr_model select --scene SCENE --width W --height H [--camera ... | --path FILE --frame K] [the same flags]
    python -m msr_model render --scene SCENE --width W --height H [--camera ... | --path FILE --frame K] --out REF.png
    python -m msr_model sequence --scene SCENE --width W --height H --frames N [--path FILE] [the select
        flags, --budget, --gaze] --out DIR            (msr_model.sequence)

Any bad argument, unreadable or unsuitable input (over 4096 x 4096, 16-bit channels) or
output path that cannot be written (unknown suffix, the same file twice, a folder that cannot
be written): one line on stderr, exit status 2, no file written. Everything is checked
before anything is decoded or computed; the outputs are written to temporary files in their
folders and renamed into place at the end.
"""
from __future__ import annotations

import argparse
import json
import time

import numpy as np

from . import spec
from . import budget as BG
from .clitools import OutputSet, Parser, UsageError, check_outputs, int_in, int_list, run_main
from .image_renderer import ImageRenderer, check_image, load_rgb, save_png
from .rules import DEFAULT_RULE, RULES


def _int_in(lo, hi, what):
    def conv(text):
        try:
            return int_in(text, what, lo, hi)
        except UsageError as e:
            raise argparse.ArgumentTypeError(str(e)) from None
    return conv


def _thr_list(text):
    try:
        return int_list(text, "--thr", 0, 255)
    except UsageError as e:
        raise argparse.ArgumentTypeError(str(e)) from None


def _gaze_arg(text):
    """--gaze X,Y: two integers >= 0 (the frame bound is checked once the size is known)."""
    try:
        vals = int_list(text, "--gaze", 0, None)
    except UsageError as e:
        raise argparse.ArgumentTypeError(str(e)) from None
    if len(vals) != 2:
        raise argparse.ArgumentTypeError(f"--gaze must be X,Y (two integers), got {text!r}")
    return vals


def _add_select_flags(p):
    p.add_argument("--tile", type=int, choices=spec.TILE_SIZES, default=16, help="tile size T")
    p.add_argument("--levels", type=int, choices=spec.LEVEL_RANGE, default=2, help="levels L")
    p.add_argument("--thr", type=_thr_list, default=None,
                   help="per-level thresholds, comma-separated, one per level (default 8,16,32 cut to L)")
    p.add_argument("--metric", choices=spec.METRICS, default="max")
    p.add_argument("--fov-gain", type=_int_in(0, 255, "--fov-gain"), default=0)
    p.add_argument("--gaze", type=_gaze_arg, default=None, metavar="X,Y",
                   help="gaze point in pixels, 0 <= X < W, 0 <= Y < H: the foveation centre "
                        "(default: the centre of the tile grid)")
    p.add_argument("--rule", choices=tuple(RULES), default=DEFAULT_RULE,
                   help="decision rule: patent (algorithm.md, default), lindilate or lindilate2d (docs/rules.md)")
    p.add_argument("--out", required=True, help="output frame PNG")
    p.add_argument("--source-map", help="output source-code map PNG (8-bit grey)")
    p.add_argument("--stats", help="output statistics JSON")
    p.add_argument("--overview", help="output summary PNG for people: frame, full reference, error, "
                   "source map in colour with a legend, traced fraction per tile (msr_model.overview)")
    p.add_argument("--budget", type=_budget_arg, default=None, metavar="N|P%",
                   help="ray budget (docs/budget.md): traced pixels per frame, or P%% of the frame's "
                        "pixels; 0 = off (the default: exactly as without the flag)")
    p.add_argument("--scale-init", type=_scale_init_arg, default=None, metavar="U|auto",
                   help=f"budget: the seed scale of the first two tile rows (register SCALE_INIT, 1.0 = "
                        f"{BG.SCALE_ONE}, 0 = 1.0), or auto: the driver's seed from the frame size, budget "
                        f"and thresholds (budget.first_frame_config). Default: from --budget-prev, else auto")
    p.add_argument("--prior-shift", type=_int_in(0, BG.PRIOR_SHIFT_MAX, "--prior-shift"),
                   default=None, metavar="S",
                   help=f"budget: weight of the seed's guess, a frame >> S (default {BG.AUTO_PRIOR_SHIFT} "
                        f"with the auto seed, else {BG.PRIOR_SHIFT}, the register's reset value)")
    p.add_argument("--budget-prev", default=None, metavar="STATS.json",
                   help="budget: seed from the previous frame's STATS.json (its final scale and its "
                        "activity per tile row), as the hardware seeds the next frame")


def _scale_init_arg(text):
    """--scale-init: `auto` or an integer 0..U_MAX."""
    if str(text).strip().lower() == "auto":
        return "auto"
    return _int_in(0, BG.U_MAX, "--scale-init")(text)


def _budget_arg(text):
    """`N` (pixels) or `P%` (of the frame): budget.parse_budget, as an argparse type."""
    try:
        return BG.parse_budget(text)
    except ValueError as e:
        raise argparse.ArgumentTypeError(f"--{e}") from None


def _budget_config(args, width: int, height: int) -> BG.BudgetConfig:
    """The budget registers for a W x H frame from the flags (pixels; a percentage rounds down)."""
    try:
        pixels = BG.budget_pixels(args.budget if args.budget is not None else ("px", 0), width, height)
    except ValueError as e:
        raise UsageError(f"--{e}") from None
    scale_init, profile, profile_scales = args.scale_init, None, None
    if args.budget_prev is not None:
        prev = _read_prev(args.budget_prev)
        profile = tuple(prev["activity_per_row"])
        profile_scales = tuple(prev["scale_per_row"])
        if scale_init is None:
            scale_init = prev["scale_out"]
    elif args.budget is None and args.scale_init is not None:
        raise UsageError("--scale-init needs --budget")
    prior_shift = args.prior_shift
    if scale_init in (None, "auto"):              # a first frame: the driver's seed
        auto = BG.first_frame_config(width, height, pixels, _params(args)) if pixels else BG.BudgetConfig()
        scale_init = auto.scale_init
        prior_shift = auto.prior_shift if prior_shift is None else prior_shift
    cfg = BG.BudgetConfig(budget=pixels, scale_init=scale_init,
                          prior_shift=BG.PRIOR_SHIFT if prior_shift is None else prior_shift,
                          profile=profile, profile_scales=profile_scales)
    if pixels:
        BG.Controller(width, height, _params(args), cfg)      # refuses a budget below the grid now
    return cfg


def _read_prev(path) -> dict:
    try:
        data = json.loads(open(path).read())
        ctl = data["budget_control"]
        out = {"scale_out": int(ctl["scale_out"]), "activity_per_row": [int(a) for a in ctl["activity_per_row"]],
               "scale_per_row": [int(u) for u in ctl["scale_per_row"]]}
    except OSError as e:
        raise UsageError(f"cannot read --budget-prev {path}: {e.strerror or e}") from None
    except (ValueError, KeyError, TypeError):
        raise UsageError(f"--budget-prev {path}: not the STATS.json of a select run with a budget") from None
    if not 0 <= out["scale_out"] <= BG.U_MAX:
        raise UsageError(f"--budget-prev {path}: scale_out {out['scale_out']} outside 0..{BG.U_MAX}")
    return out


def _add_scene_flags(p, required):
    p.add_argument("--scene", required=required, help="built-in scene name or model file")
    p.add_argument("--width", type=_int_in(1, spec.MAX_FRAME, "--width"))
    p.add_argument("--height", type=_int_in(1, spec.MAX_FRAME, "--height"))
    p.add_argument("--quality", default="fast", help="renderer quality mode (fast|heavy)")
    p.add_argument("--camera", default=None, metavar="EX,EY,EZ,TX,TY,TZ,FOV",
                   help="view: eye, target (model units), vertical field of view in degrees; up is +Y")
    p.add_argument("--path", default=None, metavar="FILE",
                   help="camera path (JSON keys, contracts.md): the view of frame --frame")
    p.add_argument("--frame", type=_int_in(0, 1 << 30, "--frame"), default=None, metavar="K",
                   help="frame number on --path (default 0)")


def build_parser():
    ap = Parser(prog="msr_model", description="Golden model of multi-level selective rendering")
    sub = ap.add_subparsers(dest="cmd", required=True, parser_class=Parser)
    sel = sub.add_parser("select", help="selective render of an image or a scene")
    sel.add_argument("image", nargs="?", help="PNG used as the rendering unit")
    _add_select_flags(sel)
    _add_scene_flags(sel, required=False)
    ren = sub.add_parser("render", help="full reference render of a scene")
    _add_scene_flags(ren, required=True)
    ren.add_argument("--out", required=True, help="output PNG")
    from .sequence import add_parser
    add_parser(sub, _int_in, _thr_list, _budget_arg)
    return ap


def _params(args) -> spec.Params:
    thr = args.thr if args.thr is not None else spec.default_thresholds(args.levels)
    if len(thr) != args.levels:
        raise UsageError(f"--thr has {len(thr)} values but --levels is {args.levels}: give one per level")
    return spec.Params(tile=args.tile, levels=args.levels, thr=thr, metric=args.metric,
                       fov_gain=args.fov_gain, gaze=getattr(args, "gaze", None))


def _check_gaze(params: spec.Params, width: int, height: int) -> None:
    try:
        spec.check_gaze(params.gaze, width, height)
    except spec.SpecError as e:
        raise UsageError(f"--{e}") from None


def _camera(args) -> str | None:
    """The view: --camera, or frame --frame of the camera path --path (msr_model.camera_path)."""
    path, frame, camera = getattr(args, "path", None), getattr(args, "frame", None), getattr(args, "camera", None)
    if frame is not None and path is None:
        raise UsageError("--frame needs --path")
    if path is None:
        return camera
    if camera is not None:
        raise UsageError("give either --camera or --path, not both")
    from .camera_path import load_path, scene_views
    cp = load_path(path)
    if cp.space != "framed":
        return cp.camera(frame or 0)
    if args.scene is None or args.width is None or args.height is None:
        raise UsageError("a framed --path needs --scene, --width and --height")
    if getattr(args, "_framed_camera", None) is None:     # the scene opens once for its framing
        args._framed_camera = scene_views(args.scene, args.width, args.height, path, args.quality).camera(frame or 0)
    return args._framed_camera


def _open_scene(args):
    if args.width is None or args.height is None:
        raise UsageError("--scene needs --width and --height")
    camera = _camera(args)
    from .embree import open_renderer  # the Embree rendering unit (C++ library through ctypes)
    return open_renderer(args.scene, args.width, args.height, quality=args.quality, camera=camera)


def _close(renderer):
    close = getattr(renderer, "close", None)
    if close:
        close()


def cmd_select(args) -> int:
    params = _params(args)
    if (args.image is None) == (args.scene is None):
        raise UsageError("give either IMAGE.png or --scene SCENE")
    if args.image is not None and (args.path is not None or args.camera is not None):
        raise UsageError("--camera and --path are views of a --scene, not of IMAGE.png")
    check_outputs({"--out": (args.out, (".png",)), "--source-map": (args.source_map, (".png",)),
                   "--stats": (args.stats, (".json",)), "--overview": (args.overview, (".png",))},
                  inputs=[args.image])
    t0 = time.perf_counter()
    if args.image is not None:
        check_image(args.image)          # size and bit depth from the header, before decoding
        reference = load_rgb(args.image)
        _check_gaze(params, reference.shape[1], reference.shape[0])
        renderer = ImageRenderer(reference)
        budget = _budget_config(args, renderer.width, renderer.height)
        result = BG.select_budget(renderer, renderer.width, renderer.height, params, budget, rule=args.rule)
    else:
        if args.width is not None and args.height is not None:
            _check_gaze(params, args.width, args.height)
            budget = _budget_config(args, args.width, args.height)
        renderer = _open_scene(args)
        try:
            result = BG.select_budget(renderer, args.width, args.height, params, budget, rule=args.rule)
            # the full reference only for the overview (it traces every pixel)
            reference = renderer.render_full() if args.overview else None
        finally:
            _close(renderer)
    stats = dict(result.stats)
    stats.setdefault("budget", 0)
    stats["seconds"] = round(time.perf_counter() - t0, 4)
    stats["source"] = args.image if args.image is not None else args.scene
    if args.path is not None:
        stats["camera_path"] = {"file": args.path, "frame": args.frame or 0, "camera": _camera(args)}
    # All computed: only now write, all or nothing.
    with OutputSet() as out:
        out.write(args.out, lambda t: save_png(t, result.frame, format="PNG"))
        if args.source_map:
            out.write(args.source_map, lambda t: save_png(t, result.source, format="PNG"))
        if args.stats:
            out.write_text(args.stats, json.dumps(stats, indent=2) + "\n")
        if args.overview:
            out.write(args.overview, lambda t: _write_overview(t, args, params, result, reference))
    return 0


def _write_overview(path, args, params, result, reference):
    from .overview import RunInfo, psnr_ssim, write_summary
    psnr, ssim = psnr_ssim(reference, result.frame)
    info = RunInfo(scene=args.image if args.image is not None else args.scene, params=params, rule=args.rule,
                   psnr_db=psnr, ssim=ssim, frame_label="golden model frame")
    write_summary(path, result.frame, reference, result.source, info)


def cmd_render(args) -> int:
    check_outputs({"--out": (args.out, (".png",))})
    renderer = _open_scene(args)
    try:
        img = renderer.render_full()
    finally:
        _close(renderer)
    with OutputSet() as out:
        out.write(args.out, lambda t: save_png(t, np.asarray(img, dtype=np.uint8), format="PNG"))
    return 0


def main(argv=None) -> int:
    def go():
        args = build_parser().parse_args(argv)
        from .sequence import cmd_sequence
        return {"select": cmd_select, "render": cmd_render, "sequence": cmd_sequence}[args.cmd](args)
    return run_main("msr_model", go)
