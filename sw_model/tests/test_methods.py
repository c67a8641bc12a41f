"""Tests of the comparison methods (msr_eval.methods) against hand computation and the golden model."""
import numpy as np
import pytest

from msr_model import ImageRenderer, Params, SpecError, select
from msr_eval import methods as M
from msr_model.testimage import test_image as make_test_image
from recorder import Recorder


def _rand(h, w, seed=1):
    return np.random.default_rng(seed).integers(0, 256, (h, w, 3), dtype=np.uint8)


def _check_honest(res, rec, image=None):
    """Traced count = pixels asked for, no pixel asked twice, and exactly the source-map traced pixels."""
    assert res.traced == len(rec.asked)
    assert len(set(rec.asked)) == len(rec.asked)
    traced = {(x, y) for y, x in zip(*np.nonzero(res.source < 16))}
    assert traced == set(rec.asked)
    if image is not None:
        m = res.source < 16
        assert (res.frame[m] == image[m]).all()   # traced pixels exactly as rendered


def test_full_render():
    img = _rand(37, 53)
    rec = Recorder(img)
    r = M.full_render(rec, 53, 37, rows_per_call=8)
    assert (r.frame == img).all() and r.traced == 53 * 37 and r.traced_fraction == 1.0
    _check_honest(r, rec, img)


@pytest.mark.parametrize("w,h,step", [(17, 9, 2), (17, 9, 4), (20, 13, 4), (1, 1, 2), (5, 1, 4)])
def test_coarse_grid_counts_and_exact_on_bilinear(w, h, step):
    yy, xx = np.mgrid[0:h, 0:w]
    img = np.stack([3 * xx + 2 * yy, 5 * xx, 7 * yy], -1).astype(np.uint8)  # bilinear (linear) picture
    rec = Recorder(img)
    r = M.coarse_grid(rec, w, h, step)
    nx = len(range(0, w, step)) + (0 if (w - 1) % step == 0 else 1)
    ny = len(range(0, h, step)) + (0 if (h - 1) % step == 0 else 1)
    assert r.traced == nx * ny
    assert (r.frame == img).all()      # a linear picture is reconstructed exactly
    _check_honest(r, rec, img)


def test_coarse_grid_hand_example():
    # 3 x 1 frame, step 2: pixels 0 and 2 traced, pixel 1 = round((10 + 21) / 2) = 16 (half up)
    img = np.array([[[10, 0, 255], [99, 99, 99], [21, 1, 0]]], np.uint8)
    r = M.coarse_grid(Recorder(img), 3, 1, 2)
    assert r.frame[0, 1].tolist() == [16, 1, 128]
    # 5 x 1, step 4: pixel 1 = 0.75 * 0 + 0.25 * 100 = 25, pixel 3 = 75
    img = np.zeros((1, 5, 3), np.uint8)
    img[0, 4] = 100
    r = M.coarse_grid(Recorder(img), 5, 1, 4)
    assert r.frame[0, :, 0].tolist() == [0, 25, 50, 75, 100]


def test_checkerboard():
    img = _rand(11, 14)
    rec = Recorder(img)
    r = M.checkerboard(rec, 14, 11)
    assert r.traced == (14 * 11 + 1) // 2
    _check_honest(r, rec, img)
    f = img.astype(int)
    # interior odd pixel: mean of 4, rounded half up
    y, x = 5, 6
    assert (x + y) % 2 == 1
    exp = (f[y, x - 1] + f[y, x + 1] + f[y - 1, x] + f[y + 1, x] + 2) // 4
    assert (r.frame[y, x] == exp).all()
    # corner (13, 0) is odd: 2 neighbours
    exp = (f[0, 12] + f[1, 13] + 1) // 2
    assert (r.frame[0, 13] == exp).all()
    # edge pixel (0, 1): 3 neighbours
    exp = (f[0, 0] + f[2, 0] + f[1, 1] + 1) // 3
    assert (r.frame[1, 0] == exp).all()


def test_single_level_borrowed_equals_golden_one_level():
    """On a frame inside one tile, single level with stride 2 and L = 1 of the patent are the same rule."""
    img = make_test_image(15, 13)
    for thr in (0, 5, 20, 255):
        a = M.single_level(ImageRenderer(img), 15, 13, thr, stride=2, border="borrowed")
        g = select(ImageRenderer(img), 15, 13, Params(tile=16, levels=1, thr=(thr,)))
        assert (a.frame == g.frame).all()
        assert ((a.source < 16) == (g.source < 16)).all()


def test_single_level_hand_example():
    # one row, 9 pixels, stride 4: samples 0, 4, 8. Gap 0-4 flat (interpolated), 4-8 an edge (traced).
    img = np.zeros((1, 9, 3), np.uint8)
    img[0, 0:4] = 10
    img[0, 4] = 14
    img[0, 5:] = 200
    img[0, 1] = 77        # a spike the samples cannot see: it is interpolated away
    rec = Recorder(img)
    r = M.single_level(rec, 9, 1, thr=8, stride=4, border="borrowed")
    assert r.frame[0, :, 0].tolist() == [10, 11, 12, 13, 14, 200, 200, 200, 200]
    assert sorted(rec.asked) == [(0, 0), (4, 0), (5, 0), (6, 0), (7, 0), (8, 0)]
    _check_honest(r, rec, img)


@pytest.mark.parametrize("border", ["traced", "borrowed"])
def test_single_level_limits(border):
    img = make_test_image(40, 35)
    rec = Recorder(img)
    r = M.single_level(rec, 40, 35, thr=0, stride=4, border=border, tile=16)
    assert (r.frame == img).all() and r.traced == 40 * 35      # thr 0 traces everything
    _check_honest(r, rec, img)
    rec = Recorder(img)
    r = M.single_level(rec, 40, 35, thr=256, stride=4, border=border, tile=16)
    _check_honest(r, rec, img)
    if border == "borrowed":     # only the grid 0, 4, .., 36, 39 x 0, 4, .., 32, 34
        assert r.traced == 11 * 10
    else:
        # per axis and tile (16, 16, 8 wide): grid 0,4,8,12 + border 13..15 / grid 0,4 + border 5..7
        tx = (4, 3), (4, 3), (2, 3)            # (grid, border) per tile along x (40 = 16+16+8)
        ty = (4, 3), (4, 3)                    # 35 = 16 + 16 + 3: last tile grid 0 + border 1, 2
        ty = ty + ((1, 2),)
        gx, bx = sum(t[0] for t in tx), sum(t[1] for t in tx)
        gy, by = sum(t[0] for t in ty), sum(t[1] for t in ty)
        expected = gx * gy + bx * 35 + by * 40 - bx * by
        assert r.traced == expected


def test_single_level_tiles_independent():
    """Fig. 5b: each tile only reads its own pixels, so a tile run alone gives the same pixels."""
    img = make_test_image(48, 32)
    whole = M.single_level(ImageRenderer(img), 48, 32, thr=12, border="traced", tile=16)
    for ty in range(2):
        for tx in range(3):
            crop = np.ascontiguousarray(img[ty * 16:(ty + 1) * 16, tx * 16:(tx + 1) * 16])
            part = M.single_level(ImageRenderer(crop), 16, 16, thr=12, border="traced", tile=16)
            assert (part.frame == whole.frame[ty * 16:(ty + 1) * 16, tx * 16:(tx + 1) * 16]).all()


def test_multi_level_is_golden():
    img = make_test_image(70, 50)
    p = Params(tile=16, levels=3, thr=(4, 8, 16), fov_gain=20)
    rec = Recorder(img)
    r = M.multi_level(rec, 70, 50, p)
    g = select(ImageRenderer(img), 70, 50, p)
    assert (r.frame == g.frame).all() and (r.source == g.source).all()
    assert r.traced == g.stats["traced"]
    _check_honest(r, rec, img)


def test_counting_renderer_counts_duplicates():
    img = _rand(4, 4)
    c = M.CountingRenderer(ImageRenderer(img), 4, 4)
    c.render([1, 1, 2], [0, 0, 3])
    assert c.requests == 3 and c.mask.sum() == 2
    with pytest.raises(ValueError):
        c.render([4], [0])


def test_bad_arguments():
    img = _rand(8, 8)
    with pytest.raises(SpecError):
        M.single_level(ImageRenderer(img), 8, 8, thr=8, border="sideways")
    with pytest.raises(SpecError):
        M.coarse_grid(ImageRenderer(img), 8, 8, 0)
    with pytest.raises(SpecError):
        M.full_render(ImageRenderer(img), 0, 8)


def test_multi_level_other_rule_counts_through_renderer():
    img = make_test_image(48, 40)
    p = Params(16, 3, (4, 8, 16))
    rec = Recorder(img)
    r = M.multi_level(rec, 48, 40, p, rule="lindilate")
    ref = select(ImageRenderer(img), 48, 40, p, rule="lindilate")
    assert (r.frame == ref.frame).all() and r.traced == ref.stats["traced"]
    _check_honest(r, rec, img)
