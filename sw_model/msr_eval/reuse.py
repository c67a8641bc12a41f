"""Reuse across frames: the previous frame, reprojected, stands in for pixels the rule would trace.

A study that decides a hardware feature (docs/reuse.md). The camera moves, the scene does not
(the sequence set of msr_eval.temporal): a surface point seen in frame k-1 is, where it is
still visible, the same colour in frame k up to view-dependent shading. So every pixel of
frame k-1 is carried forward with its depth to where it lands in frame k, and a pixel the
selective renderer would trace may take that colour instead, if it passes checks:

1. Reprojection (backward, a gather: what a decision unit fetching from the previous frame
   would do). A new pixel m of a pass lies between the samples A and B; its depth is
   predicted from theirs (inverse depth interpolated linearly: exact on a plane under
   perspective). The point the current camera sees at m at that depth is projected through
   the previous camera (both exactly the renderer's pinhole, `Camera`); the previous frame
   is read there bilinearly (2 x 2 taps of colour and depth). The source is *valid* when the
   point is in front of the previous camera, every tap of non-zero weight is inside the
   previous frame, and the taps' depth at the point (inverse depth, bilinear: exact on a
   plane however oblique) is the point's within DEPTH_TOL (relative): a nearer surface
   there means the point was hidden in the previous frame (disoccluded now), a farther one
   that m is not on the pair's surface; either way nothing is reused. Sky (depth inf) is a
   direction, moved by the rotation only; a pair of one sky and one surface sample (a
   silhouette) never reuses. A bilinear read across an edge in the previous frame blends
   the two sides, which the colour test below then refuses: a nearest-pixel read instead
   picks a side by position alone and puts the wrong side on edge pixels (measured: on the
   Cornell box a forward splat, nearest pixel, made about 170 pixels per frame wrong by more
   than 32 on wall corners, where depth is continuous and only colour changes).

2. The rule's colour test (`reuse_ok`). Only new pixels of a pass (levels 1..L) may be reused;
   the initial grid G0 x G0 is always traced, so every frame keeps fresh anchors and a stale
   colour cannot survive a frame in which its neighbours changed. At a decision of the pass
   (new pixel m between the samples A at a and B at b, gap g, level k, the tile's thr_k'), the
   reprojected colour R, from a valid source, is accepted when it passes the rule's own
   interpolation test against A or against B: d(R, A) n_k < thr_k' g or d(R, B) n_k < thr_k' g
   (the spec's colour metric and gap weighting), and the bilinear taps it was read from agree
   among themselves within the same test (their colour range, largest channel: no edge of
   the previous frame under the read, whose blend or misplaced side could pass the one-sided
   test; measured, this lifts the smooth scenes by 1 to 6 dB for at most one point more
   rays, docs/reuse.md).

   Why this test: the rule traces a gap because A and B differ by more than the threshold,
   i.e. an edge lies between them, and the true colour of m is then close to one of the two
   sides. A reprojected colour that matches one side within the very tolerance the rule
   grants an interpolation, on the surface the pair spans, is a colour the current frame
   already contains next to m: its error is bounded the way an interpolated pixel's is. A
   colour that matches neither side (a moved highlight, a blend across an edge, a wrong
   surface) is refused and the rule decides: traced where the rule traces, interpolated
   where it interpolates. The threshold is the rule's at that pixel and level (thr_k' of the
   tile, n_k, g), so a denser setting of the rule is also a stricter reuse.

   Where R is accepted the pixel takes R whether the rule would trace or interpolate it
   (a reused colour is a sample of the surface, an interpolated one a guess); a ray is saved
   only where the rule would have traced. The depth the accelerator keeps for the next frame
   is the renderer's at traced pixels and the predicted one elsewhere.

3. Bookkeeping: the renderer is asked only for traced pixels (CountingRenderer), so the
   traced count is the rays spent; `saved` counts decisions the rule traced and reuse took.
   Later levels read reused pixels as final samples, so rule + reuse traced can differ from
   rule alone traced minus saved; the study reports both runs' actual ray counts.

CLI: python -m msr_eval.reuse --scenes cornell bunny duck --frames 24 --width 480 --height 270
--out build/reuse [--img docs/img]; scenes run in parallel processes are joined with
--merge A/reuse.json B/reuse.json --out DIR.
"""
from __future__ import annotations

import argparse
import json
import math
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from msr_model import Params, spec
from msr_model.golden import decided_passes, frame_axis, threshold_maps
from msr_model.reuse import pass_neighbours
from msr_model.renderer import render_checked

from .rules import rule_function

DEPTH_TOL = 0.02           # relative depth tolerance of a tap against the gathered point
SRC_REUSED_BASE = 32       # reused at level k -> 32 + k (>= 16: not traced)
RULE_NAMES = ("patent", "lindilate")
BASE_THR = (8, 16, 32)     # L = 3, T = 16, as in msr_eval.temporal
SWEEP_SCALES = (0.5, 0.75, 1.0, 1.5, 2.0)   # the rule alone, thresholds scaled
REUSE_SCALES = (0.5, 1.0)  # rule + reuse at these scales of BASE_THR


# --- cameras and reprojection --------------------------------------------------------------

@dataclass(frozen=True)
class Camera:
    """One frame's pinhole camera, exactly the renderer's (render.cpp Renderer::Renderer and
    primary_ray; scenes.cpp set_view): fwd = normalize(target - eye), right = normalize(fwd x
    +y), up = right x fwd; pixel (x, y) looks along fwd + right px + up py with px = (x + 0.5 -
    W/2) s, py = (H/2 - y - 0.5) s, s = tan(fov/2) / (H/2). Eye and target in model units;
    `unit`: renderer depth units per model unit (the scene's placement scale; 1 for the
    built-in scenes)."""
    eye: tuple
    target: tuple
    fov: float
    width: int
    height: int
    unit: float = 1.0

    @classmethod
    def from_string(cls, text: str, width: int, height: int, unit: float = 1.0) -> "Camera":
        v = [float(t) for t in text.split(",")]
        return cls(tuple(v[0:3]), tuple(v[3:6]), v[6], width, height, unit)

    def basis(self):
        e, t = np.asarray(self.eye, np.float64), np.asarray(self.target, np.float64)
        fwd = (t - e) / np.linalg.norm(t - e)
        right = np.cross(fwd, [0.0, 1.0, 0.0])
        if np.dot(right, right) <= 0.25:  # looking along up (render.cpp's fallback axis)
            right = np.cross(fwd, [0.0, 0.0, 1.0] if abs(fwd[2]) < 0.9 else [1.0, 0.0, 0.0])
        right /= np.linalg.norm(right)
        up = np.cross(right, fwd)
        s = math.tan(math.radians(self.fov) / 2) / (0.5 * self.height)
        return e, fwd, right, up, s

    def rays(self, xs, ys):
        """Unnormalised rays fwd + right px + up py through the centres of pixels (xs, ys)."""
        e, fwd, right, up, s = self.basis()
        px = (np.asarray(xs, np.float64) + 0.5 - 0.5 * self.width) * s
        py = (0.5 * self.height - np.asarray(ys, np.float64) - 0.5) * s
        return fwd + right * px[..., None] + up * py[..., None]

    def unproject(self, xs, ys, depth):
        """Points (model units) seen at pixels (xs, ys) at `depth` (renderer units); where the
        depth is inf (sky) the ray directions instead. Returns (points, finite)."""
        depth = np.asarray(depth, np.float64)
        finite = np.isfinite(depth)
        r = self.rays(xs, ys)
        e = np.asarray(self.eye, np.float64)
        return np.where(finite[..., None], e + r * np.where(finite, depth / self.unit, 0.0)[..., None], r), finite

    def project(self, v, finite):
        """Continuous pixel coordinates (fx, fy: pixel x's centre at x + 0.5), depth (renderer
        units; inf for directions) and in-front flag of points v (model units; where not
        `finite`, v are directions)."""
        e, fwd, right, up, s = self.basis()
        rel = np.where(finite[..., None], v - e, v)
        z = rel @ fwd
        with np.errstate(divide="ignore", invalid="ignore"):
            fx = (rel @ right) / z / s + 0.5 * self.width
            fy = 0.5 * self.height - (rel @ up) / z / s
        depth = np.where(finite, z * self.unit, np.inf)
        return fx, fy, depth, z > 0


@dataclass
class PrevFrame:
    colour: np.ndarray     # (H, W, 3) uint8: the previous frame as output
    depth: np.ndarray      # (H, W) its depth as the accelerator held it (inf: sky)
    camera: Camera
    age: np.ndarray | None = None   # (H, W) frames since a pixel's colour was made fresh (None: all 0)


def gather(prev: PrevFrame, cur: Camera, xs, ys, depth, depth_tol: float = DEPTH_TOL, spread: bool = False):
    """The previous frame at the point current pixels (xs, ys) see at `depth` (module
    docstring, 1): (colour uint8 (..., 3), valid bool (...), fx, fy in the previous frame).
    Valid: in front of the previous camera, every bilinear tap of non-zero weight in the
    frame and sky exactly where the point is, and the taps' inverse depth interpolated
    bilinearly (exact on a plane) at the point's within depth_tol: otherwise the point was
    hidden or out of view in the previous frame (disoccluded). spread: also return the
    colour range of the taps of non-zero weight (largest channel, max - min)."""
    pts, finite = cur.unproject(xs, ys, depth)
    fx, fy, z, front = prev.camera.project(pts, finite)
    h, w = prev.depth.shape
    with np.errstate(invalid="ignore"):
        u, v = np.nan_to_num(fx - 0.5, nan=-9.0), np.nan_to_num(fy - 0.5, nan=-9.0)
        u, v = np.clip(u, -9.0, w + 9.0), np.clip(v, -9.0, h + 9.0)
    x0, y0 = np.floor(u).astype(np.int64), np.floor(v).astype(np.int64)
    wx, wy = u - x0, v - y0
    valid = np.asarray(front, bool).copy()
    acc = np.zeros(np.shape(u) + (3,))
    inv = np.zeros(np.shape(u))                 # inverse depth of the taps, bilinear
    hi = np.zeros(np.shape(u) + (3,))
    lo = np.full(np.shape(u) + (3,), 255.0)
    age = np.zeros(np.shape(u), np.int32)
    for dx, dy, wt in ((0, 0, (1 - wx) * (1 - wy)), (1, 0, wx * (1 - wy)), (0, 1, (1 - wx) * wy), (1, 1, wx * wy)):
        xi, yi = x0 + dx, y0 + dy
        used = wt > 1e-9
        inside = (xi >= 0) & (xi < w) & (yi >= 0) & (yi < h)
        xc, yc = np.clip(xi, 0, w - 1), np.clip(yi, 0, h - 1)
        zp = prev.depth[yc, xc]
        valid &= ~used | (inside & (np.isinf(zp) == ~finite))
        inv += np.where(used, wt, 0.0) / zp
        acc += np.where(used, wt, 0.0)[..., None] * prev.colour[yc, xc]
        if prev.age is not None:
            age = np.where(used, np.maximum(age, prev.age[yc, xc]), age)
        if spread:
            hi = np.where(used[..., None], np.maximum(hi, prev.colour[yc, xc]), hi)
            lo = np.where(used[..., None], np.minimum(lo, prev.colour[yc, xc]), lo)
    with np.errstate(invalid="ignore", divide="ignore"):
        valid &= ~finite | (np.abs(inv * z - 1.0) <= depth_tol)
    out = np.clip(np.floor(acc + 0.5), 0, 255).astype(np.uint8), valid, fx, fy
    gather.last_age = age          # the oldest tap of each read (select_reuse's age bound)
    return (*out, np.maximum(hi - lo, 0).max(axis=-1).astype(np.int32)) if spread else out


def placement_unit(scene: str, view) -> float:
    """Renderer depth units per model unit of a scene (its placement scale, not in the
    library's API): the axis ray of a 1x1 frame, seen from the view and from the eye moved
    along that axis half-way to the surface it hits, meets the same point, so the depth
    difference is the move (a first move of a tenth of eye-target estimates the distance)."""
    from msr_model.embree import open_renderer
    eye, target, fov = view
    e, t = np.asarray(eye, np.float64), np.asarray(target, np.float64)

    def axis_depth(ee):
        cam = ",".join(format(v, ".17g") for v in (*ee, *(ee + (t - e)), fov))   # same axis
        with open_renderer(scene, 1, 1, camera=cam, threads=1) as r:
            return float(r.gbuffer([0], [0])[2][0])

    fwd = (t - e) / np.linalg.norm(t - e)
    d0 = axis_depth(e)
    if np.isfinite(d0):
        step = 0.1 * float(np.linalg.norm(t - e))       # a first estimate, then a move of half the depth
        u = (d0 - axis_depth(e + step * fwd)) / step
        if np.isfinite(u) and u > 0:
            step = 0.5 * d0 / u
            d1 = axis_depth(e + step * fwd)
            if np.isfinite(d1):
                return (d0 - d1) / step
    raise spec.SpecError(f"{scene}: the view's axis meets the sky; cannot measure the placement scale")


# --- selection with reuse ------------------------------------------------------------------

@dataclass
class ReuseResult:
    frame: np.ndarray            # (H, W, 3) uint8
    source: np.ndarray           # (H, W) uint8: < 16 traced, 16 + k interpolated, 32 + k reused
    depth: np.ndarray            # (H, W) the frame's depth as the accelerator would hold it
    traced: int                  # pixels the renderer was asked for (rays)
    saved: int                   # decisions the rule traced and reuse took
    reused: int                  # pixels reused (saved ones and ones the rule interpolated)
    per_level: dict = field(default_factory=dict)
    age: np.ndarray | None = None  # (H, W) reuses in a row behind each pixel (0: traced or interpolated)

    @property
    def traced_fraction(self) -> float:
        return self.traced / self.source.size


def reuse_ok(view, R, valid) -> np.ndarray:
    """Where a decision of the pass takes the previous frame's colour R (module docstring, 2):
    a valid source and R passes the rule's own test against A or against B."""
    colour_ok = view.below_threshold(view.diff(R, view.A)) | view.below_threshold(view.diff(R, view.B))
    return np.asarray(valid & colour_ok, bool)


def _lerp_depth(zA, zB, a, b, m):
    """Depth at m between A (at a) and B (at b): inverse depth interpolated linearly (exact on
    a plane under perspective); inf when both are sky, the nearer where one is."""
    both = np.isfinite(zA) & np.isfinite(zB)
    t = (m - a) / (b - a)
    with np.errstate(invalid="ignore", divide="ignore"):
        inv = (1.0 / zA) * (1 - t) + (1.0 / zB) * t
        return np.where(both, 1.0 / inv, np.minimum(zA, zB))


def select_reuse(renderer, width: int, height: int, params: Params, rule: str = "patent",
                 depth=None, prev: PrevFrame | None = None, camera: Camera | None = None,
                 depth_tol: float = DEPTH_TOL, only_traced: bool = False, no_edge: bool = True,
                 max_age: int | None = None) -> ReuseResult:
    """golden.select_region's passes with reuse: `renderer` gives colours of traced pixels,
    `depth` (H, W) the current frame's true depth (what the renderer returns with a traced
    colour; read only at traced pixels), `prev` the previous frame and `camera` the current
    one (prev None: the rule alone, as on a sequence's first frame). only_traced: reuse only
    where the rule traces (False: also in place of the rule's interpolations). no_edge: the
    taps must also agree among themselves within the rule's test (no edge under the bilinear
    read: module docstring, 2); False is the first design of docs/reuse.md. max_age: a
    pixel reused from taps already reused max_age times in a row is not reused again (None:
    no bound); the result's `age` carries the count to the next frame."""
    from .methods import CountingRenderer
    spec.check_frame_size(width, height)
    decide = rule_function(rule)
    c = CountingRenderer(renderer, width, height)
    T, L = params.tile, params.levels
    ax, ay = frame_axis(width, T, L), frame_axis(height, T, L)
    thr_maps = threshold_maps(params, *spec.tile_counts(width, height, T))
    true_z = np.full((height, width), np.inf) if depth is None else np.asarray(depth, np.float64)
    frame = np.zeros((height, width, 3), np.uint8)
    source = np.full((height, width), spec.SRC_UNSET, np.uint8)
    zbuf = np.full((height, width), np.nan)
    age = np.zeros((height, width), np.int32)
    yy, xx = np.meshgrid(ay.known[0], ax.known[0], indexing="ij")
    frame[yy, xx] = c.render(xx.ravel(), yy.ravel()).reshape(yy.shape + (3,))
    source[yy, xx] = spec.SRC_INITIAL
    zbuf[yy, xx] = true_z[yy, xx]
    stats = {"initial": int(yy.size)}
    saved = reused = 0
    for k in range(1, L + 1):
        for horizontal, v, interp, values in decided_passes(frame, source, params, k, ax, ay, thr_maps[k - 1],
                                                            decide):
            ty, tx = v.ys, v.xs
            zA, zB = pass_neighbours(zbuf, v, horizontal)
            zv = _lerp_depth(zA, zB, v.a, v.b, v.m)
            if prev is not None:
                one_sky = np.isinf(zA) != np.isinf(zB)            # a silhouette against the sky
                R, valid, _, _, rng = gather(prev, camera, tx, ty, zv, depth_tol, spread=True)
                tap_age = gather.last_age
                if no_edge:
                    valid = valid & v.below_threshold(rng)
                if max_age is not None:
                    valid = valid & (tap_age < max_age)
                take = reuse_ok(v, R, valid & ~one_sky)
                if only_traced:
                    take &= ~interp
            else:
                take = np.zeros(v.shape, bool)
            trace = ~interp & ~take
            if trace.any():
                values[trace] = c.render(tx[trace], ty[trace])
                zv[trace] = true_z[ty[trace], tx[trace]]
            if take.any():
                values[take] = R[take]
                age[ty[take], tx[take]] = tap_age[take] + 1
            frame[ty, tx] = values
            zbuf[ty, tx] = zv
            source[ty, tx] = np.where(take, SRC_REUSED_BASE + k,
                                      np.where(interp, spec.source_code_interp(k), spec.source_code_traced(k)))
            n_saved = int((take & ~interp).sum())
            saved += n_saved
            reused += int(take.sum())
            stats[f"t{k}"] = stats.get(f"t{k}", 0) + int(trace.sum())
            stats[f"s{k}"] = stats.get(f"s{k}", 0) + n_saved
    assert not (source == spec.SRC_UNSET).any(), "every pixel is final after level L"
    return ReuseResult(frame, source, zbuf, c.requests, saved, reused, stats, age)


# --- the study -----------------------------------------------------------------------------

def _scaled(scale: float) -> tuple[int, ...]:
    return tuple(max(0, min(255, int(round(t * scale)))) for t in BASE_THR)


def task_scene(scene: str, width: int, height: int, frames: int, log=print,
               sweep=SWEEP_SCALES, reuse_scales=REUSE_SCALES, no_edge: bool = True,
               max_age: int | None = None) -> dict:
    """One scene's sequence (temporal.orbit_path): per frame the full render, every rule alone
    over the threshold sweep, and rule + reuse at `reuse_scales`."""
    from msr_model import ImageRenderer
    from msr_model.embree import open_renderer
    from msr_model.metrics import capped, flicker, psnr
    from .temporal import orbit_path
    with open_renderer(scene, width, height) as r:
        view = r.view()
    path = orbit_path(view, frames)
    unit = placement_unit(scene, view)
    cams = [path.camera(k) for k in range(frames)]
    runs = {}
    for rule in RULE_NAMES:
        for s in sweep:
            runs[(rule, "alone", s)] = None
        for s in reuse_scales:
            runs[(rule, "reuse", s)] = None
    per = {key: {"psnr": [], "traced": [], "flicker": [], "saved": [], "reused": []} for key in runs}
    state = {key: None for key in runs}      # PrevFrame of each run
    err_prev = {}
    for k, cam_text in enumerate(cams):
        t0 = time.perf_counter()
        with open_renderer(scene, width, height, quality="fast", camera=cam_text) as r:
            full = r.render_full(progress=False)
            _, _, true_z = r.gbuffer_full()
        cam = Camera.from_string(cam_text, width, height, unit)
        for key in runs:
            rule, mode, s = key
            params = Params(tile=16, levels=3, thr=_scaled(s))
            prev = state[key] if mode == "reuse" else None
            res = select_reuse(ImageRenderer(full), width, height, params, rule, true_z, prev, cam,
                               no_edge=no_edge and mode == "reuse", max_age=max_age)
            state[key] = PrevFrame(res.frame, res.depth, cam, res.age)
            err = res.frame.astype(np.int16) - full.astype(np.int16)
            m = per[key]
            m["psnr"].append(capped(psnr(full, res.frame)))      # finite: averaged and interpolated below
            m["traced"].append(res.traced / (width * height))
            m["saved"].append(res.saved / (width * height))
            m["reused"].append(res.reused / (width * height))
            if key in err_prev:
                m["flicker"].append(flicker(err_prev[key], err))
            err_prev[key] = err
        log(f"reuse: {scene} frame {k + 1}/{frames} ({time.perf_counter() - t0:.1f} s)")
    return {"cameras": cams, "unit": unit,
            "runs": {f"{r}|{m}|{s}": v for (r, m, s), v in per.items()}}


def _sweep(sc: dict, rule: str) -> list[float]:
    return sorted({float(k.split("|")[2]) for k in sc["runs"] if k.startswith(f"{rule}|alone|")})


def equal_quality(sc: dict, rule: str, scale: float, skip: int = 1) -> dict:
    """Rule + reuse at `scale` against the rule alone swept over thresholds, frames from `skip`
    on (frame 0 has no previous frame): the rule alone's traced fraction interpolated at the
    mean PSNR rule + reuse reaches (piecewise linear in PSNR over the sweep)."""
    ru = sc["runs"][f"{rule}|reuse|{scale}"]
    p_reuse = float(np.mean(ru["psnr"][skip:]))
    t_reuse = float(np.mean(ru["traced"][skip:]))
    pts = sorted((float(np.mean(sc["runs"][f"{rule}|alone|{s}"]["psnr"][skip:])),
                  float(np.mean(sc["runs"][f"{rule}|alone|{s}"]["traced"][skip:]))) for s in _sweep(sc, rule))
    ps, ts = [p for p, _ in pts], [t for _, t in pts]
    inside = ps[0] <= p_reuse <= ps[-1]
    t_alone = float(np.interp(p_reuse, ps, ts)) if inside else float("nan")
    same = sc["runs"][f"{rule}|alone|{scale}"]
    return {"rule": rule, "scale": scale, "thr": list(_scaled(scale)),
            "psnr_reuse": p_reuse, "traced_reuse": t_reuse, "traced_alone_equal_q": t_alone,
            "saved_equal_q": t_alone - t_reuse if inside else float("nan"),
            "saved_rel": (t_alone - t_reuse) / t_alone if inside and t_alone > 0 else float("nan"),
            "psnr_alone_same_thr": float(np.mean(same["psnr"][skip:])),
            "traced_alone_same_thr": float(np.mean(same["traced"][skip:])),
            "saved_decisions": float(np.mean(ru["saved"][skip:])),
            "reused": float(np.mean(ru["reused"][skip:])),
            "flicker_reuse": float(np.mean(ru["flicker"][skip:])) if ru["flicker"][skip:] else 0.0,
            "flicker_alone_same_thr": float(np.mean(same["flicker"][skip:])) if same["flicker"][skip:] else 0.0,
            "flicker_alone_equal_q": _interp_flicker(sc, rule, p_reuse, skip)}


def _interp_flicker(sc, rule, p, skip):
    pts = sorted((float(np.mean(sc["runs"][f"{rule}|alone|{s}"]["psnr"][skip:])),
                  float(np.mean(sc["runs"][f"{rule}|alone|{s}"]["flicker"][skip:]))) for s in _sweep(sc, rule))
    ps = [a for a, _ in pts]
    if not ps[0] <= p <= ps[-1]:
        return float("nan")
    return float(np.interp(p, ps, [b for _, b in pts]))


def run(scenes, frames: int, width: int, height: int, log=print, no_edge: bool = True, alone_from=None,
        max_age: int | None = None) -> dict:
    """The study; alone_from: a finished result of the same sequences whose rule-alone runs
    are taken instead of rerunning them (they do not depend on reuse)."""
    t0 = time.perf_counter()
    out = {"width": width, "height": height, "frames": frames, "depth_tol": DEPTH_TOL, "no_edge": no_edge, "max_age": max_age,
           "base_thr": list(BASE_THR), "sweep_scales": list(SWEEP_SCALES), "reuse_scales": list(REUSE_SCALES),
           "scenes": {}}
    for scene in scenes:
        if alone_from is not None:
            sc = task_scene(scene, width, height, frames, log, sweep=(), no_edge=no_edge, max_age=max_age)
            sc["runs"].update({k: v for k, v in alone_from["scenes"][scene]["runs"].items() if "|alone|" in k})
        else:
            sc = task_scene(scene, width, height, frames, log, no_edge=no_edge, max_age=max_age)
        sc["equal_quality"] = [equal_quality(sc, r, s) for r in RULE_NAMES for s in REUSE_SCALES]
        out["scenes"][scene] = sc
    out["seconds"] = round(time.perf_counter() - t0, 1)
    return out


def _save(plt, fig, axes, path: Path) -> Path:
    """The legend on the first row's last panel, then the figure written and closed."""
    axes[0][-1].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return path


def plot(result: dict, out_dir: Path) -> list[Path]:
    """reuse_curves.png: per scene, traced % against PSNR (the rule alone's sweep as a line,
    rule + reuse as points); reuse_frames.png: per scene, traced % and flicker over the frames."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from msr_model.scenes import scene_id
    scenes = list(result["scenes"])
    colours = {"patent": "tab:blue", "lindilate": "tab:orange"}
    out_dir.mkdir(parents=True, exist_ok=True)
    fig, axes = plt.subplots(1, len(scenes), figsize=(3.8 * len(scenes), 3.4), squeeze=False)
    for j, scene in enumerate(scenes):
        ax = axes[0][j]
        runs = result["scenes"][scene]["runs"]
        for rule in RULE_NAMES:
            sw = _sweep(result["scenes"][scene], rule)
            p = [np.mean(runs[f"{rule}|alone|{s}"]["psnr"][1:]) for s in sw]
            t = [100 * np.mean(runs[f"{rule}|alone|{s}"]["traced"][1:]) for s in sw]
            ax.plot(p, t, "-o", ms=3, color=colours[rule], label=f"{rule} alone")
            p = [np.mean(runs[f"{rule}|reuse|{s}"]["psnr"][1:]) for s in REUSE_SCALES]
            t = [100 * np.mean(runs[f"{rule}|reuse|{s}"]["traced"][1:]) for s in REUSE_SCALES]
            ax.plot(p, t, "*", ms=10, color=colours[rule], label=f"{rule} + reuse")
        ax.set_title(scene_id(scene), fontsize=10)
        ax.set_xlabel("mean PSNR vs full render (dB)")
    axes[0][0].set_ylabel("traced % (rays per pixel)")
    p1 = _save(plt, fig, axes, out_dir / "reuse_curves.png")
    fig, axes = plt.subplots(2, len(scenes), figsize=(3.8 * len(scenes), 5.6), squeeze=False)
    for j, scene in enumerate(scenes):
        runs = result["scenes"][scene]["runs"]
        for rule in RULE_NAMES:
            for mode, ls in (("alone", "--"), ("reuse", "-")):
                m = runs[f"{rule}|{mode}|1.0"]
                axes[0][j].plot([100 * t for t in m["traced"]], ls, color=colours[rule], lw=1, label=f"{rule} {mode}")
                axes[1][j].plot(range(1, 1 + len(m["flicker"])), m["flicker"], ls, color=colours[rule], lw=1)
        axes[0][j].set_title(scene_id(scene), fontsize=10)
        axes[1][j].set_xlabel("frame")
    axes[0][0].set_ylabel("traced % (thr 8,16,32)")
    axes[1][0].set_ylabel("flicker (rms change of error)")
    p2 = _save(plt, fig, axes, out_dir / "reuse_frames.png")
    return [p1, p2]


def markdown_table(result: dict) -> str:
    """The measured table of docs/reuse.md."""
    from msr_model.scenes import scene_id
    px = result["width"] * result["height"]
    lines = ["| scene | rule | thr | PSNR +reuse | traced % +reuse | traced % alone at equal PSNR | rays saved / frame "
             "(% of alone) | traced % alone same thr (PSNR) | reused % | flicker +reuse / alone same thr / alone equal "
             "PSNR |", "|---|---|---|---|---|---|---|---|---|---|"]
    for scene, sc in result["scenes"].items():
        for e in sc["equal_quality"]:
            saved = (f"{e['saved_equal_q'] * px:,.0f} ({100 * e['saved_rel']:.1f} %)"
                     if math.isfinite(e["saved_equal_q"]) else "outside the sweep")
            t_eq = f"{100 * e['traced_alone_equal_q']:.2f}" if math.isfinite(e["traced_alone_equal_q"]) else "-"
            lines.append(f"| {scene_id(scene)} | {e['rule']} | {','.join(map(str, e['thr']))} | "
                         f"{e['psnr_reuse']:.2f} | {100 * e['traced_reuse']:.2f} | {t_eq} | {saved} | "
                         f"{100 * e['traced_alone_same_thr']:.2f} ({e['psnr_alone_same_thr']:.2f}) | "
                         f"{100 * e['reused']:.1f} | {e['flicker_reuse']:.2f} / {e['flicker_alone_same_thr']:.2f} / "
                         f"{e['flicker_alone_equal_q']:.2f} |")
    return "\n".join(lines)


def _report(res: dict, out: Path, img: Path | None) -> str:
    out.mkdir(parents=True, exist_ok=True)
    (out / "reuse.json").write_text(json.dumps(res, indent=1) + "\n")
    plot(res, img or out)
    table = markdown_table(res)
    (out / "reuse_table.md").write_text(table + "\n")
    return table


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m msr_eval.reuse", description=__doc__.split("\n")[0])
    ap.add_argument("--scenes", nargs="+", default=["cornell", "bunny", "duck"])
    ap.add_argument("--frames", type=int, default=24)
    ap.add_argument("--width", type=int, default=480)
    ap.add_argument("--height", type=int, default=270)
    ap.add_argument("--out", type=Path, default=Path("build/reuse"))
    ap.add_argument("--img", type=Path, default=None, help="where the plots go (default: --out)")
    ap.add_argument("--merge", nargs="+", type=Path, default=None,
                    help="no run: merge these reuse.json files (one scene each, run in parallel) into --out")
    ap.add_argument("--edge-ok", action="store_true",
                    help="the first design: the bilinear taps need not agree among themselves")
    ap.add_argument("--max-age", type=int, default=None,
                    help="no reuse from taps already reused this many frames in a row (default: no bound)")
    ap.add_argument("--alone-from", type=Path, default=None,
                    help="take the rules-alone runs from this finished reuse.json (same scenes, frames, size)")
    ap.add_argument("--add-scales", nargs="+", type=float, default=None,
                    help="with --merge: run the rules alone at these further threshold scales and add them")
    a = ap.parse_args(argv)
    if a.merge:
        parts = [json.loads(p.read_text()) for p in a.merge]
        res = {**parts[0], "scenes": {k: v for p in parts for k, v in p["scenes"].items()},
               "seconds": max(p["seconds"] for p in parts)}
        for scene, sc in res["scenes"].items() if a.add_scales else ():
            more = task_scene(scene, res["width"], res["height"], res["frames"], sweep=tuple(a.add_scales),
                              reuse_scales=())
            sc["runs"].update(more["runs"])
            sc["equal_quality"] = [equal_quality(sc, r, s) for r in RULE_NAMES for s in res["reuse_scales"]]
            res["sweep_scales"] = sorted(set(res["sweep_scales"]) | set(a.add_scales))
    else:
        res = run(a.scenes, a.frames, a.width, a.height, no_edge=not a.edge_ok, max_age=a.max_age,
                  alone_from=json.loads(a.alone_from.read_text()) if a.alone_from else None)
    print(_report(res, a.out, a.img))
    print(f"{res['seconds']:.0f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
