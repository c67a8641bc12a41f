"""Reuse across frames in fixed point: the golden model the hardware is built to, bit for bit.

The contract is docs/spec/reuse.md; this module is its executable form. Every step after the
driver's camera mapping is integer arithmetic, written as the RTL computes it.

API
---
    cmap = camera_map(prev_camera, cur_camera, W, H, invz_exp)   # the driver: M, b rounded (CameraMap)
    res, state = select_with_reuse(renderer, W, H, params, rule, camera, prev_state, invz_exp)
        # renderer: .render_invz(xs, ys) -> ((N, 3) uint8 colours, (N,) uint16 inverse depths)
        #   (InvzRenderer over the Embree binding, PlaneRenderer over a picture and a plane)
        # prev_state: the ReuseState select_with_reuse returned for the previous frame, or None
        # res: ReuseFrame (frame, source, invz, traced, reused, stats); state: this frame's ReuseState
    frames = run_sequence(scene, W, H, cameras, params, rule, reuse=True)
        # per frame a ReuseFrame; reuse=False gives golden.select's frames, pixel for pixel

A ReuseState from another frame size, another invz_exp or no camera means no reuse this frame
(never an error): the frame is the rule alone's.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from . import spec
from .golden import decided_passes, frame_axis, frame_stats, threshold_maps
from .rules import get_rule
from .spec import Params

# --- the contract's constants (docs/spec/reuse.md) ------------------------------------------
INVZ_MAX = 65535           # 16-bit inverse depth; 0 is the sky, INVZ_MAX saturated (too near)
ROW_FRAC = 18              # M rows 0, 1 and b0, b1: signed 32-bit Q13.18
Z_FRAC = 29                # M row 2 and b2: signed 32-bit Q2.29
W_FRAC = 16                # the product terms b_r * w: w read as w / 2^16
UV_FRAC = 4                # previous-frame position: 4 fraction bits (bilinear weights in 1/16)
RECIP_INDEX_BITS = 8       # reciprocal seed table: 256 entries of 16 bits
DEPTH_TOL_SHIFT = 6        # |Wb - Wp| <= (Wp >> 6) + 1: about 1.6 %
AGE_BITS = 3
AGE_MAX = 7                # reuse only from taps of age < AGE_MAX (chains of at most 7 reuses)
REFRESH = 8                # every pixel refuses reuse one frame in REFRESH, staggered by position
SRC_REUSED_BASE = spec.SRC_REUSED_BASE   # reused at level k -> 32 + k (algorithm.md section 4)


def source_code_reused(level: int) -> int:
    return SRC_REUSED_BASE + level


# --- the driver: the camera mapping, float then rounded ---------------------------------------

def _pinhole(camera: str, width: int, height: int):
    """The renderer's pinhole (render.cpp primary_ray): eye, rows right/up/fwd, s = tan(fov/2)/(H/2)."""
    v = [float(t) for t in camera.split(",")]
    e, t = np.array(v[0:3]), np.array(v[3:6])
    fwd = (t - e) / np.linalg.norm(t - e)
    right = np.cross(fwd, [0.0, 1.0, 0.0])
    if np.dot(right, right) <= 0.25:       # looking along up: render.cpp's fallback axis
        right = np.cross(fwd, [0.0, 0.0, 1.0] if abs(fwd[2]) < 0.9 else [1.0, 0.0, 0.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, fwd)
    s = math.tan(math.radians(v[6]) / 2) / (0.5 * height)
    return e, np.stack([right, up, fwd]), s


@dataclass(frozen=True)
class CameraMap:
    """The 12 registers: M (3 x 3) and b (3), rows 0, 1 in Q13.18, row 2 in Q2.29 (int32 each)."""
    m: tuple            # ((m00, m01, m02), (m10, m11, m12), (m20, m21, m22)) ints
    b: tuple            # (b0, b1, b2) ints

    def arrays(self):
        return np.array(self.m, np.int64), np.array(self.b, np.int64)


def camera_map_float(prev_camera: str, cur_camera: str, width: int, height: int):
    """p = M [x, y, 1] + b w (w: model-unit inverse depth): (u, v) = (p0 / p2, p1 / p2) is the
    previous frame's pixel position (integers at pixel centres), p2 = Z_prev * w."""
    ec, Rc, s = _pinhole(cur_camera, width, height)
    ep, Rp, sp = _pinhole(prev_camera, width, height)
    kinv = np.array([[s, 0, s * (0.5 - width / 2)], [0, -s, s * (height / 2 - 0.5)], [0, 0, 1]])
    kp = np.array([[1 / sp, 0, width / 2 - 0.5], [0, -1 / sp, height / 2 - 0.5], [0, 0, 1]])
    return kp @ Rp @ Rc.T @ kinv, kp @ Rp @ (ec - ep)


def camera_map(prev_camera: str, cur_camera: str, width: int, height: int, invz_exp: int) -> CameraMap | None:
    """The driver's registers for one frame: camera_map_float with b scaled by 2^(16 - invz_exp)
    (the renderer's w is w_model * 2^invz_exp, the hardware reads it as w / 2^16), rounded to
    nearest; None (reuse off this frame) when a value does not fit its format."""
    M, b = camera_map_float(prev_camera, cur_camera, width, height)
    b = b * 2.0 ** (W_FRAC - invz_exp)
    fr = np.array([ROW_FRAC, ROW_FRAC, Z_FRAC], float)[:, None]
    mi = np.floor(M * 2.0 ** fr + 0.5)
    bi = np.floor(b * 2.0 ** fr[:, 0] + 0.5)
    if not (np.all(np.isfinite(mi)) and np.all(np.isfinite(bi))):
        return None
    if np.abs(mi).max() >= 2 ** 31 or np.abs(bi).max() >= 2 ** 31:
        return None
    return CameraMap(tuple(tuple(int(v) for v in row) for row in mi), tuple(int(v) for v in bi))


# --- the hardware: reciprocal, reprojection, bilinear read ----------------------------------

def recip_table() -> np.ndarray:
    """T[i] = round(2^24 / (256.5 + i)): 1 / d at the middle of the seed interval, 16 bits."""
    i = np.arange(1 << RECIP_INDEX_BITS)
    return np.floor(2.0 ** 24 / (256.5 + i) + 0.5).astype(np.int64)


RECIP_T = recip_table()


def bit_length(v: np.ndarray) -> np.ndarray:
    """Bits of positive int64 values (a leading-zero count in hardware); 0 for v <= 0."""
    v = np.asarray(v, np.int64)
    n = np.zeros(v.shape, np.int64)
    x = np.where(v > 0, v, 0)
    for sh in (32, 16, 8, 4, 2, 1):
        big = x >= (np.int64(1) << sh)
        n += np.where(big, sh, 0)
        x = np.where(big, x >> sh, x)
    return n + (x > 0)


def recip(p2: np.ndarray):
    """1 / p2 for positive integers: (r, n), 1 / p2 ~= r * 2^-(n + 23), r in [2^23 - 8, 2^24 - 64]
    (over every 24-bit d: the one Newton step lands up to 8 below 2^23 where d is just under 2^24).
    p2 normalised to 24 bits d (truncated), seed T[8 bits after the leading one], one Newton
    step r = (T (2^40 - d T)) >> 31."""
    p2 = np.asarray(p2, np.int64)
    n = bit_length(p2)
    d = np.where(n >= 24, p2 >> np.maximum(n - 24, 0), p2 << np.maximum(24 - n, 0))
    t = RECIP_T[(d >> 15) & 255]
    r = (t * ((np.int64(1) << 40) - d * t)) >> 31
    return r, n


@dataclass
class Reprojection:
    u: np.ndarray       # previous-frame x in 1/16 pixel (pixel centres at multiples of 16)
    v: np.ndarray
    wp: np.ndarray      # the point's inverse depth as the previous camera saw it (w units)
    ok: np.ndarray      # in front of the previous camera and inside the arithmetic's range


def reproject(cmap: CameraMap, x, y, w) -> Reprojection:
    """Current pixel (x, y) with inverse depth w (uint16; 0: sky, a direction) -> previous
    frame: P_r = ((m_r0 x + m_r1 y + m_r2) << 16) + b_r w (int64; units 2^-34 for rows 0, 1 and
    2^-45 for row 2), u = P0 / P2 and v = P1 / P2 in 1/16 pixel, rounded half up, Wp = w / p2."""
    M, b = cmap.arrays()
    x, y, w = (np.asarray(a, np.int64) for a in (x, y, w))
    P = [((M[r, 0] * x + M[r, 1] * y + M[r, 2]) << W_FRAC) + b[r] * w for r in range(3)]
    r, n = recip(P[2])
    lim = np.int64(1) << 37                 # |u p2| below 2^25 pixels: P0s * r stays in int64
    p0s, p1s = P[0] >> 22, P[1] >> 22       # units 2^-12
    ok = (P[2] > 0) & (n >= 23) & (np.abs(p0s) < lim) & (np.abs(p1s) < lim)
    sh = np.maximum(n - 14, 1)              # u = p0s * r * 2^(14 - n) in 1/16 pixel
    u = (p0s * r + (np.int64(1) << (sh - 1))) >> sh
    v = (p1s * r + (np.int64(1) << (sh - 1))) >> sh
    shw = np.maximum(n - 22, 1)
    wp = (w * r + (np.int64(1) << (shw - 1))) >> shw
    return Reprojection(u, v, wp, ok)


@dataclass
class Gather:
    colour: np.ndarray   # (..., 3) int32: the bilinear colour R
    wb: np.ndarray       # the taps' inverse depth, bilinear
    spread: np.ndarray   # (..., 3) max - min of the used taps per channel (lo, hi kept for the metric)
    lo: np.ndarray
    hi: np.ndarray
    age: np.ndarray      # the oldest used tap's age
    inside: np.ndarray   # every used tap inside the previous frame
    sky_all: np.ndarray  # every used tap is sky (0)
    sky_none: np.ndarray  # no used tap is sky or saturated


def gather(state: "ReuseState", u, v) -> Gather:
    """The previous frame at (u, v) (1/16 pixel): taps (u >> 4, v >> 4) and their right and lower
    neighbours, weights (16 - fx)(16 - fy), fx (16 - fy), (16 - fx) fy, fx fy (sum 256); a tap
    of weight 0 is not used (not read, need not be inside). R = (sum w C + 128) >> 8 per
    channel, Wb = (sum w W + 128) >> 8."""
    h, wd = state.invz.shape
    u, v = np.asarray(u, np.int64), np.asarray(v, np.int64)
    x0, y0, fx, fy = u >> UV_FRAC, v >> UV_FRAC, u & 15, v & 15
    shape = u.shape
    acc = np.zeros(shape + (3,), np.int64)
    accw = np.zeros(shape, np.int64)
    lo = np.full(shape + (3,), 255, np.int64)
    hi = np.zeros(shape + (3,), np.int64)
    age = np.zeros(shape, np.int64)
    inside = np.ones(shape, bool)
    sky_all = np.ones(shape, bool)
    sky_none = np.ones(shape, bool)
    for dx, dy, wt in ((0, 0, (16 - fx) * (16 - fy)), (1, 0, fx * (16 - fy)),
                       (0, 1, (16 - fx) * fy), (1, 1, fx * fy)):
        xi, yi = x0 + dx, y0 + dy
        used = wt > 0
        ins = (xi >= 0) & (xi < wd) & (yi >= 0) & (yi < h)
        inside &= ~used | ins
        xc, yc = np.clip(xi, 0, wd - 1), np.clip(yi, 0, h - 1)
        c = state.frame[yc, xc].astype(np.int64)
        z = state.invz[yc, xc].astype(np.int64)
        acc += wt[..., None] * c
        accw += wt * z
        lo = np.where(used[..., None], np.minimum(lo, c), lo)
        hi = np.where(used[..., None], np.maximum(hi, c), hi)
        age = np.where(used, np.maximum(age, state.age[yc, xc]), age)
        sky_all &= ~used | (z == 0)
        sky_none &= ~used | ((z > 0) & (z < INVZ_MAX))
    return Gather((acc + 128) >> 8, (accw + 128) >> 8, hi - lo, lo, hi, age, inside, sky_all, sky_none)


def refresh_phase(x, y, tile: int, period: int = REFRESH) -> np.ndarray:
    """The staggered expiry's phase of pixel (x, y), 0..period-1: a hash of the position inside
    the tile plus tx + 2 ty, so that every in-tile position takes every phase over a block of
    tiles (each level's positions split evenly over the phases)."""
    x, y = np.asarray(x, np.int64), np.asarray(y, np.int64)
    sh = int(tile).bit_length() - 1
    xl, yl = x & (tile - 1), y & (tile - 1)
    h = (xl ^ (xl >> 2) ^ (xl >> 4)) + 2 * (yl ^ (yl >> 2) ^ (yl >> 4)) + (yl >> 1) + 3 * (xl >> 1)
    return (h + (x >> sh) + 2 * (y >> sh)) % period


def pass_neighbours(plane: np.ndarray, view, horizontal: bool) -> tuple[np.ndarray, np.ndarray]:
    """A pass's neighbours A and B in a per-pixel plane (colour, depth): along the row in a
    horizontal pass, along the column in a vertical one (view: the pass's positions)."""
    a, b = np.broadcast_to(view.a, view.shape), np.broadcast_to(view.b, view.shape)
    if horizontal:
        return plane[view.ys, a], plane[view.ys, b]
    return plane[a, view.xs], plane[b, view.xs]


def lerp_invz(wa, wb, a, b, m):
    """A new pixel's inverse depth from its neighbours': the spec's interpolation on a 16-bit
    channel; where exactly one is sky (0), the other (the nearer surface)."""
    wa, wb = np.asarray(wa, np.int64), np.asarray(wb, np.int64)
    a, b, m = (np.asarray(t, np.int64) for t in (a, b, m))
    g = b - a
    lin = ((b - m) * wa + (m - a) * wb + g // 2) // g
    return np.where((wa == 0) != (wb == 0), np.maximum(wa, wb), lin)


# --- the frame: selection with reuse ---------------------------------------------------------

@dataclass
class ReuseState:
    """What the accelerator keeps of a frame for the next: colour, inverse depth, age planes,
    the frame's camera string, its number in the sequence and the inverse depth's exponent."""
    frame: np.ndarray          # (H, W, 3) uint8
    invz: np.ndarray           # (H, W) uint16
    age: np.ndarray            # (H, W) uint8, 0..AGE_MAX (3 bits)
    camera: str | None
    index: int = 0
    invz_exp: int = 0


@dataclass
class ReuseFrame:
    frame: np.ndarray          # (H, W, 3) uint8
    source: np.ndarray         # (H, W) uint8: < 16 traced, 16 + k interpolated, 32 + k reused
    invz: np.ndarray           # (H, W) uint16 inverse-depth plane
    traced: int                # rays asked of the renderer
    reused: int                # pixels whose colour came from the previous frame
    stats: dict = field(default_factory=dict)
    camera: str | None = None


def usable(prev: ReuseState | None, width: int, height: int, invz_exp: int, camera: str | None) -> bool:
    """A previous frame reuse may read: same size and exponent, both cameras known."""
    return (prev is not None and camera is not None and prev.camera is not None
            and prev.invz.shape == (height, width) and prev.frame.shape == (height, width, 3)
            and prev.invz_exp == invz_exp)


def select_with_reuse(renderer, width: int, height: int, params: Params, rule="patent",
                      camera: str | None = None, prev: ReuseState | None = None,
                      invz_exp: int = 0, reuse: bool = True, refresh: int = REFRESH,
                      age_max: int = AGE_MAX) -> tuple[ReuseFrame, ReuseState]:
    """golden.select_region's passes; where the rule traces a new pixel (levels 1..L), the
    previous frame is asked first (docs/spec/reuse.md). `renderer.render_invz(xs, ys)` gives
    traced pixels' colours and inverse depths. Without a usable `prev` (or reuse=False) the
    frame and source map are golden.select's. refresh, age_max: the contract's REFRESH and
    AGE_MAX (other values for the study only)."""
    spec.check_frame_size(width, height)
    rule_name, decide = get_rule(rule)
    T, L = params.tile, params.levels
    ax, ay = frame_axis(width, T, L), frame_axis(height, T, L)
    thr_maps = threshold_maps(params, *spec.tile_counts(width, height, T))
    cmap = None
    if reuse and usable(prev, width, height, invz_exp, camera):
        cmap = camera_map(prev.camera, camera, width, height, invz_exp)
    index = prev.index + 1 if prev is not None else 0
    frame = np.zeros((height, width, 3), np.uint8)
    source = np.full((height, width), spec.SRC_UNSET, np.uint8)
    invz = np.zeros((height, width), np.int64)
    age = np.zeros((height, width), np.uint8)
    traced = 0

    def trace(xs, ys):
        nonlocal traced
        xs, ys = np.asarray(xs, np.int32).ravel(), np.asarray(ys, np.int32).ravel()
        if xs.size == 0:
            return np.zeros((0, 3), np.uint8), np.zeros(0, np.int64)
        rgb, w = renderer.render_invz(xs, ys)
        traced += xs.size
        return np.asarray(rgb, np.uint8).reshape(-1, 3), np.asarray(w, np.int64).ravel()

    yy, xx = np.meshgrid(ay.known[0], ax.known[0], indexing="ij")
    rgb, w = trace(xx, yy)          # the initial grid: always traced (fresh anchors every frame)
    frame[yy, xx] = rgb.reshape(yy.shape + (3,))
    invz[yy, xx] = w.reshape(yy.shape)
    source[yy, xx] = spec.SRC_INITIAL
    per_level = {"initial": int(yy.size)}
    reused = 0
    for k in range(1, L + 1):
        for horizontal, view, interp, values in decided_passes(frame, source, params, k, ax, ay,
                                                                thr_maps[k - 1], decide):
            ty, tx = view.ys, view.xs
            wa, wb = pass_neighbours(invz, view, horizontal)
            wm = lerp_invz(wa, wb, view.a, view.b, view.m)
            take = np.zeros(view.shape, bool)
            if cmap is not None:
                take = _reuse_decision(view, ~interp, prev, cmap, tx, ty, wa, wb, wm, index, refresh, age_max)
                values = np.where(take.ok[..., None], take.colour, values).astype(np.uint8)
                age[ty[take.ok], tx[take.ok]] = take.age[take.ok]
                take = take.ok
            tr = ~interp & ~take
            if tr.any():
                rgb, w = trace(tx[tr], ty[tr])
                values[tr] = rgb
                wm[tr] = w
            frame[ty, tx] = values
            invz[ty, tx] = wm
            source[ty, tx] = np.where(take, source_code_reused(k),
                                      np.where(interp, spec.source_code_interp(k), spec.source_code_traced(k)))
            per_level[f"t{k}"] = per_level.get(f"t{k}", 0) + int(tr.sum())
            per_level[f"i{k}"] = per_level.get(f"i{k}", 0) + int(interp.sum())
            per_level[f"r{k}"] = per_level.get(f"r{k}", 0) + int(take.sum())
            reused += int(take.sum())
    assert not (source == spec.SRC_UNSET).any(), "every pixel is final after level L"
    invz16 = invz.astype(np.uint16)
    stats = frame_stats(source, params, per_level, rule_name)
    stats.update({"rays": traced, "reused": reused, "reuse_active": cmap is not None, "frame_index": index})
    res = ReuseFrame(frame, source, invz16, traced, reused, stats, camera)
    return res, ReuseState(frame, invz16, age, camera, index, invz_exp)


@dataclass
class _Take:
    ok: np.ndarray
    colour: np.ndarray
    age: np.ndarray


def _reuse_decision(view, traces, prev: ReuseState, cmap: CameraMap, tx, ty, wa, wb, wm, index: int,
                    refresh: int = REFRESH, age_max: int = AGE_MAX) -> _Take:
    """Where a decision the rule traces takes the previous frame's colour (docs/spec/reuse.md,
    steps 3 to 8), and that colour and the pixel's new age."""
    rp = reproject(cmap, tx, ty, wm)
    g = gather(prev, rp.u, rp.v)
    sky = wm == 0
    depth_ok = np.abs(g.wb - rp.wp) <= (rp.wp >> DEPTH_TOL_SHIFT) + 1
    valid = rp.ok & g.inside & np.where(sky, g.sky_all, g.sky_none & (wm < INVZ_MAX) & depth_ok)
    valid &= (wa == 0) == (wb == 0)                       # a silhouette against the sky: never
    R = g.colour.astype(np.int32)
    colour_ok = view.below_threshold(view.diff(R, view.A)) | view.below_threshold(view.diff(R, view.B))
    taps_ok = view.below_threshold(spec.color_diff(g.hi, g.lo, view.metric))
    fresh = (index + refresh_phase(tx, ty, view.tile, refresh)) % refresh != 0
    ok = traces & valid & colour_ok & taps_ok & (g.age < age_max) & fresh
    return _Take(np.asarray(ok, bool), R.astype(np.uint8), (g.age + 1).astype(np.uint8))


# --- renderers that return inverse depth -------------------------------------------------------

class PlaneRenderer:
    """A picture and an inverse-depth plane as the rendering unit (tests)."""

    def __init__(self, image: np.ndarray, invz: np.ndarray):
        self.image, self.invz = np.asarray(image, np.uint8), np.asarray(invz, np.uint16)
        self.height, self.width = self.image.shape[:2]
        self.pixels_traced = 0

    def render(self, xs, ys):
        return self.render_invz(xs, ys)[0]

    def render_invz(self, xs, ys):
        xs, ys = np.asarray(xs), np.asarray(ys)
        self.pixels_traced += xs.size
        return self.image[ys, xs], self.invz[ys, xs]


class InvzRenderer:
    """The Embree binding's colours and inverse depths at a fixed exponent."""

    def __init__(self, embree, invz_exp: int):
        self.r, self.invz_exp = embree, int(invz_exp)
        self.width, self.height = embree.width, embree.height

    def render(self, xs, ys):
        return self.r.render(xs, ys)

    def render_invz(self, xs, ys):
        return self.r.render_invz(xs, ys, self.invz_exp)


def choose_invz_exp(embree, probe: int = 16) -> int:
    """The driver's exponent for a sequence: the nearest depth z of a probe x probe G-buffer of
    its first view, in model units, maps to about 2^15 (one octave below saturation)."""
    xs = (np.arange(probe) * embree.width) // probe
    ys = (np.arange(probe) * embree.height) // probe
    gx, gy = np.meshgrid(xs, ys)
    _, _, z = embree.gbuffer(gx.ravel(), gy.ravel())
    z = z[np.isfinite(z)] / embree.model_scale()
    if z.size == 0:
        return 16
    return int(np.clip(math.floor(math.log2(float(z.min()))) + 15, 0, 40))


def run_sequence(scene: str, width: int, height: int, cameras, params, rule="patent",
                 reuse: bool = True, quality: str = "fast", invz_exp: int | None = None, log=None):
    """Frames 0 .. len(cameras)-1 of `scene` seen from `cameras` (camera strings): a list of
    ReuseFrame. reuse=False: each frame is golden.select's (the same pixels and source codes).
    `params` is one Params for every frame or a list of one per frame (a path's gaze points)."""
    from .embree import open_renderer
    out, state = [], None
    per_frame = params if isinstance(params, (list, tuple)) else [params] * len(cameras)
    for k, cam in enumerate(cameras):
        params = per_frame[k]
        with open_renderer(scene, width, height, quality=quality, camera=cam) as r:
            if invz_exp is None:
                invz_exp = choose_invz_exp(r)
            res, state = select_with_reuse(InvzRenderer(r, invz_exp), width, height, params, rule, cam, state,
                                           invz_exp, reuse)
        out.append(res)
        if log:
            log(f"frame {k}: traced {res.traced} reused {res.reused}")
    return out
