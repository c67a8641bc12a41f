"""Reuse across frames in fixed point (msr_model.reuse, docs/spec/reuse.md)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from msr_model import reuse as RU
from msr_model import spec
from msr_model.golden import select
from msr_model.image_renderer import ImageRenderer
from msr_model.spec import Params

W, H = 96, 64
CAM = "0,0,0,0,0,1,40"
PARAMS = Params(tile=16, levels=3, thr=(8, 16, 32))


def picture(seed: int = 1) -> np.ndarray:
    """Flat regions, edges and a little noise: the rule traces edges, interpolates the rest."""
    rng = np.random.default_rng(seed)
    img = np.zeros((H, W, 3), np.int32)
    img[:, :40] = (200, 50, 50)
    img[:, 40:] = (30, 180, 60)
    img[20:30, 10:70] = (250, 250, 250)
    img[40:, 60:] = (20, 20, 200)
    return np.clip(img + rng.integers(0, 3, img.shape), 0, 255).astype(np.uint8)


def plane(value: int = 20000) -> np.ndarray:
    return np.full((H, W), value, np.uint16)


@pytest.mark.parametrize("rule", ["patent", "lindilate"])
def test_reuse_off_is_select(rule):
    img = picture()
    r = RU.PlaneRenderer(img, plane())
    want = select(ImageRenderer(img), W, H, PARAMS, rule)
    state = None
    for _ in range(3):     # reuse=False: every frame is golden.select's, state or not
        res, state = RU.select_with_reuse(r, W, H, PARAMS, rule, CAM, state, 16, reuse=False)
        assert (res.frame == want.frame).all() and (res.source == want.source).all()
        assert res.reused == 0 and res.traced == int((want.source < 16).sum())


def test_first_frame_is_select():
    img = picture()
    res, _ = RU.select_with_reuse(RU.PlaneRenderer(img, plane()), W, H, PARAMS, "lindilate", CAM, None, 16)
    want = select(ImageRenderer(img), W, H, PARAMS, "lindilate")
    assert (res.frame == want.frame).all() and (res.source == want.source).all()


def test_identity_camera_mapping():
    cm = RU.camera_map(CAM, CAM, W, H, 16)
    assert cm.m == ((1 << 18, 0, 0), (0, 1 << 18, 0), (0, 0, 1 << 29)) and cm.b == (0, 0, 0)
    x, y = np.meshgrid(np.arange(W), np.arange(H))
    rp = RU.reproject(cm, x, y, np.full(x.shape, 12345))
    assert rp.ok.all() and (rp.u == 16 * x).all() and (rp.v == 16 * y).all() and (rp.wp == 12345).all()


def test_static_camera_reuses_its_own_colours():
    """Frame 1 of a still camera over a still picture: the same pixels; every trace of the rule
    past the initial grid is reused except the eighth whose staggered refresh falls on it."""
    img = picture()
    r = RU.PlaneRenderer(img, plane())
    f0, st = RU.select_with_reuse(r, W, H, PARAMS, "lindilate", CAM, None, 16)
    grid = f0.stats["traced_initial"]
    level_traces = f0.traced - grid
    counts = []
    for k in range(1, 10):
        res, st = RU.select_with_reuse(r, W, H, PARAMS, "lindilate", CAM, st, 16)
        assert (res.frame == f0.frame).all()
        assert res.traced + res.reused == f0.traced
        ys, xs = np.nonzero(res.source >= spec.SRC_REUSED_BASE)
        assert ((k + RU.refresh_phase(xs, ys, 16)) % RU.REFRESH != 0).all()
        counts.append(res.traced)
        assert res.reused >= 0.6 * level_traces
    assert max(counts) <= 1.15 * np.mean(counts)


def test_reused_source_code():
    img = picture()
    r = RU.PlaneRenderer(img, plane())
    f0, st = RU.select_with_reuse(r, W, H, PARAMS, "patent", CAM, None, 16)
    res, _ = RU.select_with_reuse(r, W, H, PARAMS, "patent", CAM, st, 16)
    codes = set(np.unique(res.source).tolist())
    assert codes & {33, 34, 35} and not codes & {32}      # the initial grid is never reused
    reused = res.source >= 32
    assert reused.sum() == res.reused
    assert (f0.source[reused] < 16).all() and (f0.source[reused] > 0).all()   # where the rule traced
    assert RU.source_code_reused(2) == 34 == spec.SRC_REUSED_BASE + 2


def test_pure_translation():
    """The eye moves sideways by d in front of a plane at depth D: points move d / (D s) pixels
    (looking along +z, the camera's right is -x: an eye moved to +x sees the plane move right)."""
    D, d = 10.0, 0.05
    prev = "0,0,0,0,0,1,40"
    cur = f"{d},0,0,{d},0,1,40"
    s = math.tan(math.radians(40) / 2) / (H / 2)
    shift = d / (D * s)
    invz_exp = 16
    w = int(round(2 ** invz_exp / D))
    cm = RU.camera_map(prev, cur, W, H, invz_exp)
    x, y = np.meshgrid(np.arange(W), np.arange(H))
    rp = RU.reproject(cm, x, y, np.full(x.shape, w))
    assert rp.ok.all()
    want = (x - shift) * 16
    assert np.abs(rp.u - want).max() <= 1.0      # within a sixteenth of a pixel
    assert (rp.v == 16 * y).all() and (np.abs(rp.wp - w) <= 1).all()
    # a sky pixel (w = 0) moves by the rotation only: not at all
    sky = RU.reproject(cm, x, y, np.zeros(x.shape, np.int64))
    assert (sky.u == 16 * x).all() and (sky.v == 16 * y).all()


def test_translation_reuses_shifted_frame():
    """A shift of a whole number of pixels: every reused colour is the current frame's own."""
    D, n = 8.0, 3
    s = math.tan(math.radians(40) / 2) / (H / 2)
    d = n * D * s
    big = np.concatenate([picture(), picture(2)], axis=1)
    w = int(round(2 ** 16 / D))
    r_prev = RU.PlaneRenderer(np.ascontiguousarray(big[:, :W]), plane(w))
    r_cur = RU.PlaneRenderer(np.ascontiguousarray(big[:, n:W + n]), plane(w))
    f0, st = RU.select_with_reuse(r_prev, W, H, PARAMS, "patent", "0,0,0,0,0,1,40", None, 16)
    res, _ = RU.select_with_reuse(r_cur, W, H, PARAMS, "patent", f"{-d!r},0,0,{-d!r},0,1,40", st, 16)
    assert res.reused > 0
    ys, xs = np.nonzero(res.source >= 32)
    assert (xs < W - n).all()                  # the columns new in this frame have no source
    assert (res.frame[ys, xs] == f0.frame[ys, xs + n]).all()    # the previous output, moved


def test_reciprocal_error_bound():
    """Every normalised input 2^23 .. 2^24 - 1: r within 2^-17.9 of 2^47 / d."""
    d = np.arange(1 << 23, 1 << 24, dtype=np.int64)
    r, n = RU.recip(d)
    assert (n == 24).all()
    rel = np.abs(r / (2.0 ** 47 / d.astype(float)) - 1)
    assert rel.max() < 4.0e-6
    assert (r <= 1 << 24).all() and (r > (1 << 23) - 16).all()     # 25 bits
    assert RU.RECIP_T.max() < 1 << 16
    # other exponents: the same mantissa path
    big = np.array([3, 1 << 30, (1 << 45) + 12345, (1 << 61) - 1], np.int64)
    r, n = RU.recip(big)
    approx = r.astype(float) * 2.0 ** -(n.astype(float) + 23)
    assert np.all(np.abs(approx * big - 1) < 4.0e-6)


def test_bad_state_means_no_reuse():
    img = picture()
    r = RU.PlaneRenderer(img, plane())
    _, st = RU.select_with_reuse(r, W, H, PARAMS, "patent", CAM, None, 16)
    small = RU.PlaneRenderer(np.ascontiguousarray(img[:48, :80]), np.ascontiguousarray(plane()[:48, :80]))
    res, _ = RU.select_with_reuse(small, 80, 48, PARAMS, "patent", CAM, st, 16)   # another frame size
    want = select(ImageRenderer(small.image), 80, 48, PARAMS, "patent")
    assert res.reused == 0 and (res.frame == want.frame).all() and (res.source == want.source).all()
    res, _ = RU.select_with_reuse(r, W, H, PARAMS, "patent", CAM, st, 17)   # another inverse-depth exponent
    assert res.reused == 0
    res, _ = RU.select_with_reuse(r, W, H, PARAMS, "patent", None, st, 16)   # no camera
    assert res.reused == 0


def test_disocclusion_depth_test():
    """A previous frame whose depth is nearer than the reprojected point (an occluder there) is
    never read."""
    img = picture()
    _, st = RU.select_with_reuse(RU.PlaneRenderer(img, plane(30000)), W, H, PARAMS, "patent", CAM, None, 16)
    res, _ = RU.select_with_reuse(RU.PlaneRenderer(img, plane(20000)), W, H, PARAMS, "patent", CAM, st, 16)
    assert res.reused == 0


def test_refresh_phase_balanced():
    from msr_model.golden import frame_axis
    for T, L in ((8, 2), (16, 3), (32, 3), (16, 2)):
        ax, ay = frame_axis(480, T, L), frame_axis(272, T, L)
        for k in range(1, L + 1):
            for xs, ys in (np.meshgrid(ax.new_m[k - 1], ay.known[k - 1]), np.meshgrid(ax.known[k], ay.new_m[k - 1])):
                h = np.bincount(RU.refresh_phase(xs, ys, T).ravel(), minlength=RU.REFRESH) / xs.size * RU.REFRESH
                assert h.max() < 1.05, (T, L, k, h)


def test_embree_inverse_depth():
    emb = pytest.importorskip("msr_model.embree")
    try:
        r = emb.open_renderer("cornell", 32, 18)
        r.render_invz([0], [0], 16)
    except emb.RendererUnavailable:
        pytest.skip("rendering library without inverse depth")
    with r:
        ys, xs = np.divmod(np.arange(32 * 18), 32)
        rgb, invz = r.render_invz(xs, ys, 24)
        _, _, z = r.gbuffer(xs, ys)
        assert (rgb == r.render(xs, ys)).all() and invz.dtype == np.uint16
        sky = ~np.isfinite(z)
        assert (invz[sky] == 0).all()
        want = np.minimum(65535, np.floor(2.0 ** 24 * r.model_scale() / z[~sky].astype(float) + 0.5))
        assert (invz[~sky] == want).all()
