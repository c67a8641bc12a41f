"""msr_eval.reuse: reprojection by depth and two cameras, and the rule + reuse bookkeeping.

The synthetic scenes are ray-cast here in a few lines through reuse.Camera's own rays: a
background plane z = 10 with vertical stripes and (where asked) a red square at z = 5, seen
by cameras looking along +z. One test checks Camera against the renderer itself.
"""
from __future__ import annotations

import numpy as np
import pytest

from msr_model import ImageRenderer, Params, select
from msr_model.embree import library_path
from msr_eval.reuse import Camera, PrevFrame, gather, placement_unit, select_reuse

W, H = 48, 32
PARAMS = Params(tile=16, levels=3, thr=(8, 16, 32))


def cam(eye=(0.0, 0.0, 0.0), unit=1.0, w=W, h=H):
    return Camera(tuple(eye), (eye[0], eye[1], eye[2] + 1.0), 60.0, w, h, unit)


def cast(c: Camera, square=True):
    """(colour (H, W, 3) uint8, depth (H, W) renderer units, hit_square (H, W))."""
    ys, xs = np.mgrid[0:c.height, 0:c.width]
    r = c.rays(xs, ys)                       # fwd is +z with unit z component
    e = np.asarray(c.eye)
    bg = e + r * (10.0 - e[2])
    fg = e + r * (5.0 - e[2])
    hit = square & (np.abs(fg[..., 0]) < 1.0) & (np.abs(fg[..., 1]) < 1.0)
    stripe = (np.floor(bg[..., 0] * 2) % 2).astype(bool)
    col = np.where(stripe[..., None], [200, 200, 60], [30, 60, 200])
    col = np.where(hit[..., None], [220, 20, 20], col).astype(np.uint8)
    depth = np.where(hit, 5.0 - e[2], 10.0 - e[2]) * c.unit
    return col, depth, hit


def test_static_camera_reprojects_identity():
    c = cam(unit=3.0)
    col, depth, _ = cast(c)
    ys, xs = np.mgrid[0:H, 0:W]
    R, valid, fx, fy = gather(PrevFrame(col, depth, c), c, xs, ys, depth)
    assert valid.all()
    np.testing.assert_allclose(fx, xs + 0.5, atol=1e-9)
    np.testing.assert_allclose(fy, ys + 0.5, atol=1e-9)
    assert (R == col).all()


@pytest.mark.parametrize("unit", [1.0, 0.25])
def test_translation_moves_by_known_pixels(unit):
    """Eye moved by d along the camera's right axis: a point at depth D lands d / (D s)
    pixels away in the other frame (s = tan(fov/2) / (H/2)); here 3 pixels."""
    c0 = cam(unit=unit)
    _, fwd, right, _, s = c0.basis()
    D = 10.0
    shift = 3
    c1 = cam(eye=tuple(right * shift * D * s), unit=unit)
    col0, depth0, _ = cast(c0, square=False)
    ys, xs = np.mgrid[0:H, 0:W]
    depth1 = np.full((H, W), D * unit)
    R, valid, fx, fy = gather(PrevFrame(col0, depth0, c0), c1, xs, ys, depth1)
    np.testing.assert_allclose(fx, xs + 0.5 + shift, atol=1e-6)
    np.testing.assert_allclose(fy, ys + 0.5, atol=1e-6)
    inside = xs + shift < W
    assert valid[inside].all() and not valid[~inside].any()
    assert (R[inside] == col0[ys[inside], xs[inside] + shift]).all()


def test_disoccluded_pixel_is_not_reused():
    """The square moves against the background: background it hid in the previous frame is
    not taken from the square's pixels, neither by gather nor by select_reuse."""
    c0, c1 = cam(), cam(eye=(0.6, 0.0, 0.0))
    col0, depth0, hit0 = cast(c0)
    col1, depth1, hit1 = cast(c1)
    prev = PrevFrame(col0, depth0, c0)
    ys, xs = np.mgrid[0:H, 0:W]
    _, valid, fx, fy = gather(prev, c1, xs, ys, depth1)
    x0, y0 = np.floor(fx - 0.5).astype(int), np.floor(fy - 0.5).astype(int)
    hidden = ~hit1 & (x0 >= 0) & (x0 + 1 < W) & (y0 >= 0) & (y0 + 1 < H)
    for dx in (0, 1):
        for dy in (0, 1):
            hidden &= hit0[np.clip(y0 + dy, 0, H - 1), np.clip(x0 + dx, 0, W - 1)]
    assert hidden.sum() >= 10, "the set-up must disocclude background"
    assert not valid[hidden].any()
    # through the passes: the previous frame's colours there are the square's (red), which
    # would even pass the colour test against a red neighbour; still never reused
    res = select_reuse(ImageRenderer(col1), W, H, PARAMS, "patent", depth1, prev, c1)
    assert not (res.source[hidden] >= 32).any()
    assert (res.frame[hidden & (res.source < 16)] == col1[hidden & (res.source < 16)]).all()


def _edge_image():
    img = np.zeros((H, W, 3), np.uint8)
    img[:, 21:] = 255
    img[10:, 37:] = (255, 0, 0)
    return img


def test_reuse_failing_colour_test_is_traced():
    img = _edge_image()
    depth = np.full((H, W), 7.0)
    c = cam()
    alone = select(ImageRenderer(img), W, H, PARAMS)
    rule_traced = (alone.source >= 1) & (alone.source < 16)      # traced at a level, not G0
    assert rule_traced.sum() > 20
    stale = img.copy()
    stale[rule_traced] = (255, 0, 255)                           # matches neither side
    res = select_reuse(ImageRenderer(img), W, H, PARAMS, "patent", depth, PrevFrame(stale, depth, c), c)
    assert (res.source[rule_traced] < 16).all()
    assert (res.frame[rule_traced] == img[rule_traced]).all()
    assert res.saved == 0


def test_ray_bookkeeping():
    """Static camera, exact previous frame: every ray the rule spends past G0 is saved, the
    renderer is asked exactly for the traced pixels, and the counts add up."""
    img = _edge_image()
    depth = np.full((H, W), 7.0)
    c = cam()

    class Counting(ImageRenderer):
        asked = 0

        def render(self, xs, ys):
            Counting.asked += np.asarray(xs).size
            return super().render(xs, ys)

    alone = select_reuse(ImageRenderer(img), W, H, PARAMS, "patent", depth, None)
    ref = select(ImageRenderer(img), W, H, PARAMS)
    assert (alone.frame == ref.frame).all() and alone.traced == ref.stats["traced"]
    res = select_reuse(Counting(img), W, H, PARAMS, "patent", depth, PrevFrame(img, depth, c), c)
    g0 = res.per_level["initial"]
    assert Counting.asked == res.traced == int((res.source < 16).sum())
    assert res.traced == g0 + sum(res.per_level.get(f"t{k}", 0) for k in (1, 2, 3))
    assert res.saved == ref.stats["traced"] - g0 > 0
    assert res.traced == g0
    assert (res.frame == img).all()
    assert res.reused == int((res.source >= 32).sum()) >= res.saved


needs_lib = pytest.mark.skipif(not library_path().is_file(), reason="needs the rendering library (make renderer)")


@needs_lib
@pytest.mark.parametrize("scene", ["cornell", "duck"])
def test_camera_matches_renderer(scene):
    """Frame 1's true depth, gathered into frame 0 of an orbit, lands on frame 0's own depth:
    the pinhole and the placement scale are the renderer's."""
    from msr_model.embree import open_renderer
    from msr_eval.temporal import orbit_path
    w, h = 96, 54
    with open_renderer(scene, w, h) as r:      # make setup installs both scenes: a missing one fails
        view = r.view()
    unit = placement_unit(scene, view)
    path = orbit_path(view, 16)
    frames = []
    for k in (0, 1):
        with open_renderer(scene, w, h, camera=path.camera(k)) as r:
            frames.append((r.render_full(progress=False), r.gbuffer_full()[2]))
    c0, c1 = (Camera.from_string(path.camera(k), w, h, unit) for k in (0, 1))
    ys, xs = np.mgrid[0:h, 0:w]
    R, valid, _, _ = gather(PrevFrame(frames[0][0], frames[0][1], c0), c1, xs, ys, frames[1][1])
    assert valid.mean() > 0.8
    err = np.abs(R.astype(int) - frames[1][0].astype(int)).max(axis=-1)[valid]
    assert np.median(err) <= 2 and np.mean(err) < 6


def test_tap_spread_marks_an_edge_under_the_read():
    """Half a pixel of motion: the bilinear read of a pixel next to an edge of the previous
    frame spans both sides, and its tap range (what no_edge tests) says so; elsewhere 0."""
    c0 = cam()
    _, _, right, _, s = c0.basis()
    D = 10.0
    c1 = cam(eye=tuple(right * 0.5 * D * s))
    prev = np.zeros((H, W, 3), np.uint8)
    prev[:, 20:] = 200
    ys, xs = np.mgrid[0:H, 0:W]
    R, valid, fx, _, rng = gather(PrevFrame(prev, np.full((H, W), D), c0), c1, xs, ys, np.full((H, W), D),
                                  spread=True)
    np.testing.assert_allclose(fx, xs + 1.0, atol=1e-6)
    assert (rng[:, 19] == 200).all() and (R[:, 19] == 100).all()
    others = np.ones(W, bool)
    others[19] = False
    others[W - 1] = False                      # its second tap is outside the frame: not valid
    assert (rng[:, others] == 0).all() and valid[:, others].all() and not valid[:, W - 1].any()


def test_age_bound_stops_a_chain():
    """Taps already reused max_age frames in a row are not reused again; one frame younger
    they are, and the reused pixels carry the age one higher."""
    img = _edge_image()
    depth = np.full((H, W), 7.0)
    c = cam()
    ref = select(ImageRenderer(img), W, H, PARAMS)
    old = select_reuse(ImageRenderer(img), W, H, PARAMS, "patent", depth,
                       PrevFrame(img, depth, c, np.full((H, W), 4, np.int32)), c, max_age=4)
    assert old.saved == 0 and old.reused == 0 and old.traced == ref.stats["traced"]
    young = select_reuse(ImageRenderer(img), W, H, PARAMS, "patent", depth,
                         PrevFrame(img, depth, c, np.full((H, W), 3, np.int32)), c, max_age=4)
    assert young.saved > 0
    assert (young.age[young.source >= 32] == 4).all() and (young.age[young.source < 32] == 0).all()


def test_plot_writes_both_figures(tmp_path):
    """plot() draws every scene's sweep and reuse points and the per-frame traces into two
    PNG files (a result shaped as run_sequences writes it, numbers made up)."""
    from PIL import Image
    from msr_eval import reuse as R
    rng = np.random.default_rng(3)
    runs = {}
    for rule in R.RULE_NAMES:
        for mode, scales in (("alone", (0.5, 1.0, 2.0)), ("reuse", R.REUSE_SCALES)):
            for s in scales:
                runs[f"{rule}|{mode}|{s}"] = {"psnr": list(40 + rng.random(5)), "traced": list(rng.random(5) * 0.3),
                                              "flicker": list(rng.random(4))}
    result = {"scenes": {"cornell": {"runs": runs}, "bunny": {"runs": runs}}}
    paths = R.plot(result, tmp_path / "figs")
    assert [p.name for p in paths] == ["reuse_curves.png", "reuse_frames.png"]
    for p in paths:
        w, h = Image.open(p).size
        assert w > 400 and h > 200
