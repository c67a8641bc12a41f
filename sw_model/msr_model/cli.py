"""Command line of the golden model (../shared/spec/contracts.md).

    python -m msr_model select IMAGE.png --tile 16 --levels 2 --thr 8,16 [--metric max|sum]
        [--fov-gain 0] --out OUT.png --source-map MAP.png --stats STATS.json
    python -m msr_model select --scene SCENE --width W --height H [the same flags]
    python -m msr_model render --scene SCENE --width W --height H --out REF.png

Any bad argument or unreadable input: one line on stderr, exit status 2, no file written.
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

from . import spec
from .golden import select
from .image_renderer import ImageRenderer, load_rgb, save_png

EXIT_BAD_INPUT = 2


class UsageError(Exception):
    pass


class _Parser(argparse.ArgumentParser):
    """argparse, but every error is one line and exit status 2."""

    def error(self, message):  # noqa: D401
        raise UsageError(message)


def _int_in(lo, hi, what):
    def conv(text):
        try:
            v = int(text, 0)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{what} must be an integer, got {text!r}") from None
        if not lo <= v <= hi:
            raise argparse.ArgumentTypeError(f"{what} {v} outside {lo}..{hi}")
        return v
    return conv


def _thr_list(text):
    parts = text.split(",")
    try:
        vals = tuple(int(p.strip(), 0) for p in parts)
    except ValueError:
        raise argparse.ArgumentTypeError(f"--thr must be a comma-separated list of integers, got {text!r}") from None
    for v in vals:
        if not 0 <= v <= 255:
            raise argparse.ArgumentTypeError(f"threshold {v} outside 0..255")
    return vals


def _add_select_flags(p):
    p.add_argument("--tile", type=int, choices=spec.TILE_SIZES, default=16, help="tile size T")
    p.add_argument("--levels", type=int, choices=spec.LEVEL_RANGE, default=2, help="levels L")
    p.add_argument("--thr", type=_thr_list, default=None,
                   help="per-level thresholds, comma-separated, one per level (default 8,16,32 cut to L)")
    p.add_argument("--metric", choices=spec.METRICS, default="max")
    p.add_argument("--fov-gain", type=_int_in(0, 255, "--fov-gain"), default=0)
    p.add_argument("--out", required=True, help="output frame PNG")
    p.add_argument("--source-map", help="output source-code map PNG (8-bit grey)")
    p.add_argument("--stats", help="output statistics JSON")


def _add_scene_flags(p, required):
    p.add_argument("--scene", required=required, help="built-in scene name or model file")
    p.add_argument("--width", type=_int_in(1, spec.MAX_FRAME, "--width"))
    p.add_argument("--height", type=_int_in(1, spec.MAX_FRAME, "--height"))
    p.add_argument("--quality", default="fast", help="renderer quality mode (fast|heavy)")
    p.add_argument("--camera", default=None, metavar="EX,EY,EZ,TX,TY,TZ,FOV",
                   help="view: eye, target (model units), vertical field of view in degrees; up is +Y")


def build_parser():
    ap = _Parser(prog="msr_model", description="Golden model of multi-level selective rendering")
    sub = ap.add_subparsers(dest="cmd", required=True, parser_class=_Parser)
    sel = sub.add_parser("select", help="selective render of an image or a scene")
    sel.add_argument("image", nargs="?", help="PNG used as the rendering unit")
    _add_select_flags(sel)
    _add_scene_flags(sel, required=False)
    ren = sub.add_parser("render", help="full reference render of a scene")
    _add_scene_flags(ren, required=True)
    ren.add_argument("--out", required=True, help="output PNG")
    return ap


def _params(args) -> spec.Params:
    thr = args.thr if args.thr is not None else (8, 16, 32)[: args.levels]
    if len(thr) != args.levels:
        raise UsageError(f"--thr has {len(thr)} values but --levels is {args.levels}: give one per level")
    return spec.Params(tile=args.tile, levels=args.levels, thr=thr, metric=args.metric,
                       fov_gain=args.fov_gain)


def _check_outputs(*paths):
    for p in paths:
        if p is None:
            continue
        parent = Path(p).resolve().parent
        if parent.exists() and not parent.is_dir():
            raise UsageError(f"cannot write {p}: {parent} is not a folder")
        if Path(p).is_dir():
            raise UsageError(f"cannot write {p}: it is a folder")


def _open_scene(args):
    if args.width is None or args.height is None:
        raise UsageError("--scene needs --width and --height")
    from .embree import open_renderer  # the Embree rendering unit (C++ library through ctypes)
    return open_renderer(args.scene, args.width, args.height, quality=args.quality,
                         camera=getattr(args, "camera", None))


def cmd_select(args) -> int:
    params = _params(args)
    _check_outputs(args.out, args.source_map, args.stats)
    if (args.image is None) == (args.scene is None):
        raise UsageError("give either IMAGE.png or --scene SCENE")
    t0 = time.perf_counter()
    if args.image is not None:
        renderer = ImageRenderer(load_rgb(args.image))
        result = select(renderer, renderer.width, renderer.height, params)
    else:
        renderer = _open_scene(args)
        try:
            result = select(renderer, args.width, args.height, params)
        finally:
            close = getattr(renderer, "close", None)
            if close:
                close()
    stats = dict(result.stats)
    stats["seconds"] = round(time.perf_counter() - t0, 4)
    stats["source"] = args.image if args.image is not None else args.scene
    # All computed: only now write, so a failure above leaves no partial output.
    save_png(args.out, result.frame)
    if args.source_map:
        save_png(args.source_map, result.source)
    if args.stats:
        Path(args.stats).parent.mkdir(parents=True, exist_ok=True)
        Path(args.stats).write_text(json.dumps(stats, indent=2) + "\n")
    return 0


def cmd_render(args) -> int:
    _check_outputs(args.out)
    renderer = _open_scene(args)
    try:
        img = renderer.render_full()
    finally:
        close = getattr(renderer, "close", None)
        if close:
            close()
    save_png(args.out, np.asarray(img, dtype=np.uint8))
    return 0


def main(argv=None) -> int:
    try:
        args = build_parser().parse_args(argv)
        return {"select": cmd_select, "render": cmd_render}[args.cmd](args)
    except (UsageError, spec.SpecError) as e:
        msg = str(e).replace("\n", " ")
        print(f"msr_model: error: {msg}", file=sys.stderr)
        return EXIT_BAD_INPUT
