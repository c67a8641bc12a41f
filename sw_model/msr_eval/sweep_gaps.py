"""Holes in the sweep's curves: per family, the largest step in traced fraction between two
neighbouring settings, over every scene and mode (`python -m msr_eval.sweep_gaps`).

A family's settings are ordered by the traced fraction they reach (for a family monotone in
its threshold that is the threshold order); a step of more than GAP_LIMIT points leaves a
stretch of its curve unmeasured, where a front comparison reads only an interpolation.
Families of one setting (full, grid2, grid4, checkerboard) have no step.
"""
from __future__ import annotations

import argparse
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

from . import gbuffer_rule as G
from .scenes import MODEL_FILES, scene_id
from .sweep import Backend, open_unit
from .sweep_space import FULL_SCALES, QUICK_SCALES, Setting, settings
from . import methods as M

GAP_LIMIT = 10.0          # points of traced fraction


@dataclass(frozen=True)
class Point:
    """One setting's traced fraction on one scene and mode."""

    scene: str
    mode: str
    family: str
    label: str
    fraction: float


@dataclass(frozen=True)
class Gap:
    """A family's largest step: where, between which settings, how many points."""

    family: str
    points: float
    scene: str = ""
    mode: str = ""
    below: str = ""            # the label with the smaller traced fraction
    above: str = ""


def family_gaps(points: list[Point]) -> dict[str, Gap]:
    """Per family, its largest step over every scene and mode (0 points for a single setting)."""
    curves: dict[tuple, list[Point]] = {}
    for p in points:
        curves.setdefault((p.family, p.scene, p.mode), []).append(p)
    out: dict[str, Gap] = {}
    for (fam, scene, mode), pts in curves.items():
        pts = sorted(pts, key=lambda p: (p.fraction, p.label))
        best = out.setdefault(fam, Gap(fam, 0.0))
        for a, b in zip(pts, pts[1:]):
            step = 100.0 * (b.fraction - a.fraction)
            if step > best.points:
                best = out[fam] = Gap(fam, step, scene, mode, a.label, b.label)
    return out


def scene_points(ref, sid: str, mode: str, sweep: list[Setting], gbuf=None) -> list[Point]:
    """Every setting of `sweep` on one reference frame: its traced fraction."""
    H, W = ref.shape[:2]
    out = []
    for st in sweep:
        res = st.run(G.rendering_unit(ref, gbuf if G.needs_gbuffer(st) else None), W, H)
        out.append(Point(sid, mode, st.family, st.label, res.traced / (W * H)))
    return out


def measure(scenes: list[str], modes: list[str], width: int, height: int, sweep: list[Setting],
            backend: Backend, log=print) -> list[Point]:
    """Renders each scene once per mode and runs the sweep on it."""
    points = []
    with tempfile.TemporaryDirectory() as cache:
        for scene in scenes:
            gbuf = None
            if any(G.needs_gbuffer(st) for st in sweep):
                gbuf = G.scene_gbuffer(backend.name, scene, width, height, Path(cache), f"{scene_id(scene)}_gaps")
            for mode in modes:
                t0 = time.perf_counter()
                unit = open_unit(backend.name, scene, width, height, mode)
                try:
                    ref = M.full_render(unit, width, height).frame
                finally:
                    getattr(unit, "close", lambda: None)()
                points += scene_points(ref, scene_id(scene), mode, sweep, gbuf)
                log(f"  {scene_id(scene)}/{mode}: {time.perf_counter() - t0:.1f} s")
    return points


def record_points(path: Path, families: tuple[str, ...] | None = None) -> list[Point]:
    """The points of an evaluation's records (results.json of `make eval`, e.g. the committed
    1920x1080 data/results.json): no rendering."""
    import json
    recs = json.loads(Path(path).read_text())["records"]
    return [Point(r["scene"], r["mode"], r["family"], r["label"], float(r["traced_fraction"])) for r in recs
            if families is None or r["family"].startswith(families)]


def report(gaps: dict[str, Gap], limit: float = GAP_LIMIT) -> str:
    """One line per family, largest step first."""
    lines = [f"{'family':32s} {'gap':>6s}  where"]
    for g in sorted(gaps.values(), key=lambda g: (-g.points, g.family)):
        flag = "  > limit" if g.points > limit else ""
        where = f"{g.scene}/{g.mode}: {g.below} .. {g.above}" if g.scene else "-"
        lines.append(f"{g.family:32s} {g.points:6.2f}  {where}{flag}")
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--width", type=int, default=240)
    ap.add_argument("--height", type=int, default=135)
    ap.add_argument("--modes", default="heavy,fast")
    ap.add_argument("--scenes", help="comma-separated scene names / model paths (default: the evaluation's set)")
    ap.add_argument("--families", help="comma-separated family name prefixes (default: every family)")
    ap.add_argument("--quick", action="store_true", help="the quick run's sweep instead of the full run's")
    ap.add_argument("--limit", type=float, default=GAP_LIMIT)
    ap.add_argument("--backend", default="auto", choices=("auto", "embree", "image"))
    ap.add_argument("--records", metavar="RESULTS_JSON",
                    help="read the traced fractions from an evaluation's results.json instead of rendering "
                         "(data/results.json: the full run at 1920x1080)")
    a = ap.parse_args(argv)
    prefixes = tuple(f.strip() for f in a.families.split(",")) if a.families else None
    if a.records:
        try:
            points = record_points(Path(a.records), prefixes)
        except (OSError, ValueError, KeyError) as e:
            print(f"sweep_gaps: cannot read records from {a.records}: {e}", file=sys.stderr)
            return 2
        print(f"sweep_gaps: {a.records}, {len(points)} records")
    else:
        backend = Backend(a.backend)
        if a.scenes:
            scenes = [s.strip() for s in a.scenes.split(",") if s.strip()]
        else:
            scenes = backend.builtin_scenes() + ([m for m in MODEL_FILES if Path(m).is_file()] if backend.embree else [])
        sweep = settings(a.width, a.height, QUICK_SCALES if a.quick else FULL_SCALES, a.quick)
        if prefixes:
            sweep = [st for st in sweep if st.family.startswith(prefixes)]
        modes = [m.strip() for m in a.modes.split(",")] if backend.embree else ["fast"]
        print(f"sweep_gaps: {a.width}x{a.height}, {len(scenes)} scenes, modes {modes}, {len(sweep)} settings",
              flush=True)
        points = measure(scenes, modes, a.width, a.height, sweep, backend, log=lambda m: print(m, flush=True))
    gaps = family_gaps(points)
    print(report(gaps, a.limit))
    worst = max((g.points for g in gaps.values()), default=0.0)
    print(f"largest gap: {worst:.2f} points (limit {a.limit:g})")
    return 1 if worst > a.limit else 0

if __name__ == "__main__":
    sys.exit(main())
