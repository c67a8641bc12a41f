"""Golden model against the spec: worked example, hand-computed cases, properties, and
agreement of the vectorised, per-tile and literal-oracle forms."""
import itertools
import random

import numpy as np
import pytest

from msr_model import ImageRenderer, Params, SpecError, select, select_tiled, spec, tile_schedule
from msr_model.tile_model import frame_tiles, run_tile

from spec_oracle import oracle_select


def run(img, **kw):
    img = np.asarray(img, dtype=np.uint8)
    r = ImageRenderer(img)
    res = select(r, img.shape[1], img.shape[0], Params(**kw))
    return res, r


def row_image(values, height=1):
    """A (height, len(values), 3) image whose every row is `values` (rgb tuples)."""
    return np.array([values] * height, dtype=np.uint8)


# ---- spec section 2/3: positions ------------------------------------------------------

def test_initial_grid_examples():
    assert spec.initial_grid(16, 4) == [0, 4, 8, 12, 15]        # the spec's example
    assert spec.initial_grid(16, 8) == [0, 8, 15]
    assert spec.initial_grid(1, 4) == [0]
    assert spec.initial_grid(2, 4) == [0, 1]
    assert spec.initial_grid(5, 4) == [0, 4]
    assert spec.initial_grid(9, 8) == [0, 8]
    assert spec.initial_grid(32, 2) == list(range(0, 32, 2)) + [31]


def test_worked_example_positions():
    """T=16, L=2, row y=0: level 1 decides 2, 6, 10, 13; level 2 decides 1,3,5,7,9,11,14."""
    passes = tile_schedule(16, 16, 2)
    h1 = [s for s in passes[1].steps if s.y == 0]
    assert [(s.x, s.ax, s.bx, s.gap, s.nominal) for s in h1] == [
        (2, 0, 4, 4, 4), (6, 4, 8, 4, 4), (10, 8, 12, 4, 4), (13, 12, 15, 3, 4)]
    h2 = [s for s in passes[3].steps if s.y == 0]
    assert [s.x for s in h2] == [1, 3, 5, 7, 9, 11, 14]
    assert [(s.ax, s.bx, s.gap, s.nominal) for s in h2 if s.x == 14] == [(13, 15, 2, 2)]


def test_schedule_covers_every_pixel_once():
    for L, w, h in itertools.product((1, 2, 3), range(1, 33), (1, 2, 3, 5, 16, 17, 31, 32)):
        seen = [(s.x, s.y) for p in tile_schedule(w, h, L) for s in p.steps]
        assert len(seen) == len(set(seen)) == w * h, (L, w, h)


# ---- section 3: the decision, border weighting and interpolation, by hand ---------------

def test_worked_example_border_gap3():
    """x=13 from 12 and 15 (gap 3, level 1 of L=2): interpolate iff 4*d < 3*thr = 24."""
    A, B_ok, B_no = (10, 20, 30), (15, 25, 35), (16, 25, 35)
    for B, expect_interp in ((B_ok, True), (B_no, False)):
        row = [(0, 0, 0)] * 16
        row[12], row[13], row[14], row[15] = A, (99, 99, 99), (77, 77, 77), B
        img = row_image(row)
        res, _ = run(img, tile=16, levels=2, thr=(8, 16))
        if expect_interp:   # d = 5: 20 < 24
            assert res.source[0, 13] == 17
            assert tuple(res.frame[0, 13]) == ((2 * 10 + 15 + 1) // 3, (2 * 20 + 25 + 1) // 3, (2 * 30 + 35 + 1) // 3)
            assert tuple(res.frame[0, 13]) == (12, 22, 32)
        else:               # d = 6: 24 is not < 24
            assert res.source[0, 13] == 1
            assert tuple(res.frame[0, 13]) == (99, 99, 99)


def test_gap2_rounding_half_up():
    # 5 wide, L=1: G0 = {0, 2, 4}; x=1 from (0, 2), x=3 from (2, 4), gap 2 = n_1.
    img = row_image([(10, 0, 255), (1, 1, 1), (13, 1, 254), (9, 9, 9), (13, 1, 254)])
    res, _ = run(img, tile=8, levels=1, thr=(255,))
    assert tuple(res.frame[0, 1]) == ((10 + 13 + 1) >> 1, (0 + 1 + 1) >> 1, (255 + 254 + 1) >> 1) == (12, 1, 255)
    assert tuple(res.frame[0, 3]) == (13, 1, 254)
    assert list(res.source[0]) == [0, 17, 0, 17, 0]


def test_threshold_strictness_gap2():
    # d == thr traces, d == thr - 1 interpolates
    for d, code in ((7, 1), (6, 17)):
        img = row_image([(100, 100, 100), (0, 0, 0), (100 + d, 100, 100)])
        res, _ = run(img, tile=8, levels=1, thr=(7,))
        assert res.source[0, 1] == code


def test_sum_metric():
    # max diff 3, sum diff 9: thr 5 interpolates with max and traces with sum
    img = row_image([(10, 10, 10), (0, 0, 0), (13, 13, 13)])
    assert run(img, tile=8, levels=1, thr=(5,), metric="max")[0].source[0, 1] == 17
    assert run(img, tile=8, levels=1, thr=(5,), metric="sum")[0].source[0, 1] == 1
    assert run(img, tile=8, levels=1, thr=(10,), metric="sum")[0].source[0, 1] == 17


def test_five_wide_levels2_by_hand():
    # G0 = {0, 4}; level 1: x=2 from (0,4) gap 4 = n_1; level 2: x=1, 3 gap 2 = n_2.
    img = row_image([(0, 0, 0), (7, 7, 7), (7, 7, 7), (7, 7, 7), (100, 50, 3)])
    res, _ = run(img, tile=8, levels=2, thr=(255, 255))
    assert tuple(res.frame[0, 2]) == ((2 * 0 + 2 * 100 + 2) // 4, (2 * 50 + 2) // 4, (2 * 3 + 2) // 4) == (50, 25, 2)
    assert tuple(res.frame[0, 1]) == ((0 + 50 + 1) >> 1, (0 + 25 + 1) >> 1, (0 + 2 + 1) >> 1)
    assert tuple(res.frame[0, 3]) == ((50 + 100 + 1) >> 1, (25 + 50 + 1) >> 1, (2 + 3 + 1) >> 1)
    assert list(res.source[0]) == [0, 18, 17, 18, 0]


def test_border_gap3_level1_of_L3_weighting():
    # L=3, 4-wide tile: G0 = {0, 3}, level 1: x=1 from (0,3), gap 3, n_1 = 8: 8*d < 3*thr.
    for d, code in ((2, 17), (3, 1)):         # thr 8: 16 < 24 yes; 24 < 24 no
        img = row_image([(50, 50, 50), (0, 0, 0), (0, 0, 0), (50 + d, 50, 50)])
        res, _ = run(img, tile=8, levels=3, thr=(8, 8, 8))
        assert res.source[0, 1] == code


@pytest.mark.parametrize("width, tile, levels, traced_x", [
    (1, 8, 2, [0]), (2, 8, 2, [0, 1]), (5, 8, 2, [0, 4]),
    (17, 16, 2, [0, 4, 8, 12, 15, 16]), (17, 16, 3, [0, 8, 15, 16]), (9, 8, 1, [0, 2, 4, 6, 7, 8])])
def test_partial_tiles_flat_image_traces_only_grid(width, tile, levels, traced_x):
    img = np.full((1, width, 3), 123, dtype=np.uint8)
    res, r = run(img, tile=tile, levels=levels, thr=(255,) * levels)
    assert sorted(np.flatnonzero(res.source[0] == 0).tolist()) == traced_x
    assert r.pixels_traced == len(traced_x)
    assert (res.frame == img).all()


def test_one_by_one_and_column_frames():
    for w, h in ((1, 1), (1, 37), (37, 1), (2, 2)):
        img = np.random.default_rng(w * 100 + h).integers(0, 256, (h, w, 3), dtype=np.uint8)
        res, _ = run(img, tile=8, levels=3, thr=(0, 0, 0))
        assert (res.frame == img).all()


# ---- section 1: thresholds --------------------------------------------------------------

def test_foveation_by_hand():
    # 3x3 tiles: centre r2 = 0, edge middles r2 = 2, corners r2 = 2; 4x1 tiles: r2 = 3, 1, 1, 3
    assert spec.foveated_threshold(10, 1, 1, 3, 3, 200) == 10
    assert spec.foveated_threshold(10, 0, 1, 3, 3, 24) == 10 + (24 * 2 >> 4)
    assert spec.foveated_threshold(10, 0, 0, 4, 1, 16) == 13
    assert spec.foveated_threshold(10, 1, 0, 4, 1, 16) == 11
    assert spec.foveated_threshold(250, 0, 0, 4, 1, 255) == 255       # clamp
    p = Params(tile=8, levels=2, thr=(4, 240), fov_gain=100)
    assert spec.tile_thresholds(p, 0, 0, 5, 5) == (4 + (100 * 4 >> 4), 255)


def test_foveation_changes_decisions_at_the_edge_only():
    # flat-ish image where d = 10 everywhere; thr 8 traces, foveation lifts edge tiles above 10
    rng = np.random.default_rng(7)
    base = rng.integers(0, 2, (48, 48, 1)) * 10
    img = np.repeat(base, 3, axis=2).astype(np.uint8)
    res0, _ = run(img, tile=16, levels=1, thr=(8,), fov_gain=0)
    res1, _ = run(img, tile=16, levels=1, thr=(8,), fov_gain=48)   # r2 = 2 at the edge: +6
    centre = (slice(16, 32), slice(16, 32))
    assert (res0.source[centre] == res1.source[centre]).all()
    assert (res1.source != 1).sum() > (res0.source != 1).sum()


# ---- properties ----------------------------------------------------------------------------

PARAM_SETS = [(T, L, m) for T in spec.TILE_SIZES for L in spec.LEVEL_RANGE for m in spec.METRICS]


@pytest.mark.parametrize("T, L, metric", PARAM_SETS)
def test_threshold_zero_traces_everything(T, L, metric):
    img = np.random.default_rng(T + L).integers(0, 256, (45, 70, 3), dtype=np.uint8)
    res, r = run(img, tile=T, levels=L, thr=(0,) * L, metric=metric)
    assert (res.frame == img).all() and (res.source < 16).all()
    assert r.pixels_traced == img.shape[0] * img.shape[1]


@pytest.mark.parametrize("T, L, metric", PARAM_SETS)
def test_flat_image_max_threshold_traces_only_grid(T, L, metric):
    W, H = 77, 41
    img = np.full((H, W, 3), (30, 60, 90), dtype=np.uint8)
    res, r = run(img, tile=T, levels=L, thr=(255,) * L, metric=metric)
    grid = sum(len(spec.initial_grid(w, 1 << L)) * len(spec.initial_grid(h, 1 << L))
               for _, _, _, _, w, h in frame_tiles(W, H, T))
    assert r.pixels_traced == grid == int((res.source == 0).sum())
    assert (res.frame == img).all()


@pytest.mark.parametrize("T, L, metric", PARAM_SETS)
def test_constant_image_reproduced(T, L, metric):
    rng = random.Random(T * 10 + L)
    img = np.full((33, 50, 3), (rng.randrange(256), rng.randrange(256), rng.randrange(256)), dtype=np.uint8)
    for _ in range(3):
        thr = tuple(rng.randrange(256) for _ in range(L))
        res, _ = run(img, tile=T, levels=L, thr=thr, metric=metric, fov_gain=rng.randrange(256))
        assert (res.frame == img).all()


def test_tile_order_does_not_matter():
    rng = np.random.default_rng(3)
    img = np.cumsum(rng.integers(-6, 7, (40, 57, 3)), axis=1).clip(0, 255).astype(np.uint8)
    p = Params(tile=8, levels=2, thr=(12, 20), fov_gain=30)
    ref = select(ImageRenderer(img), 57, 40, p)
    n = len(frame_tiles(57, 40, 8))
    for seed in range(3):
        order = list(range(n))
        random.Random(seed).shuffle(order)
        f, s = select_tiled(ImageRenderer(img), 57, 40, p, order=order)
        assert (f == ref.frame).all() and (s == ref.source).all()


def _random_case(rng):
    W, H = int(rng.integers(1, 70)), int(rng.integers(1, 70))
    kind = rng.integers(3)
    if kind == 0:
        img = rng.integers(0, 256, (H, W, 3))
    elif kind == 1:   # smooth: random walk along both axes
        img = np.cumsum(np.cumsum(rng.integers(-2, 3, (H, W, 3)), axis=0), axis=1) + 128
    else:             # blocks with edges
        img = np.kron(rng.integers(0, 256, (H // 5 + 1, W // 5 + 1, 3)), np.ones((5, 5, 1)))[:H, :W]
    return np.clip(img, 0, 255).astype(np.uint8)


@pytest.mark.parametrize("T, L, metric", PARAM_SETS)
def test_vectorised_per_tile_and_oracle_agree(T, L, metric):
    rng = np.random.default_rng(1000 + T * 7 + L * 3 + (metric == "sum"))
    for _ in range(4):
        img = _random_case(rng)
        H, W = img.shape[:2]
        thr = tuple(int(v) for v in rng.integers(0, 256, L))
        p = Params(tile=T, levels=L, thr=thr, metric=metric, fov_gain=int(rng.integers(0, 256)))
        vec = select(ImageRenderer(img), W, H, p)
        f, s = select_tiled(ImageRenderer(img), W, H, p)
        assert (f == vec.frame).all() and (s == vec.source).all()
        out, code, traced = oracle_select(img.tolist(), T, L, thr, metric, p.fov_gain)
        assert len(traced) == len(set(traced)) == vec.stats["traced"]
        for (x, y), v in out.items():
            assert tuple(vec.frame[y, x]) == v and vec.source[y, x] == code[(x, y)], (x, y)


def test_renderer_asked_only_for_traced_pixels():
    class Recorder(ImageRenderer):
        def __init__(self, img):
            super().__init__(img)
            self.asked = []

        def render(self, xs, ys):
            self.asked += list(zip(np.asarray(xs).tolist(), np.asarray(ys).tolist()))
            return super().render(xs, ys)

    img = _random_case(np.random.default_rng(5))
    r = Recorder(img)
    res = select(r, img.shape[1], img.shape[0], Params(tile=8, levels=3, thr=(10, 20, 30)))
    assert len(r.asked) == len(set(r.asked)) == res.stats["traced"]
    assert all(res.source[y, x] < 16 for x, y in r.asked)


def test_run_tile_request_order_matches_schedule():
    img = _random_case(np.random.default_rng(9))
    H, W = img.shape[:2]
    p = Params(tile=16, levels=2, thr=(10, 20))
    w, h = min(16, W), min(16, H)
    res = run_tile(lambda x, y: img[y, x], 0, 0, w, h, p, p.thr)
    order = [(s.x, s.y) for ps in tile_schedule(w, h, 2) for s in ps.steps]
    traced_in_order = [xy for xy in order if res.codes[xy[1], xy[0]] < 16]
    assert res.requests == traced_in_order


def test_stats_and_limits():
    img = _random_case(np.random.default_rng(11))
    res, _ = run(img, tile=8, levels=2, thr=(10, 20))
    st = res.stats
    assert st["traced"] + st["interpolated"] == st["width"] * st["height"]
    assert st["traced"] == st["traced_initial"] + st["traced_level1"] + st["traced_level2"]
    assert st["traced_fraction"] == pytest.approx(st["traced"] / (st["width"] * st["height"]))
    with pytest.raises(SpecError):
        spec.check_frame_size(4097, 1)
    with pytest.raises(SpecError):
        Params(tile=12)
    with pytest.raises(SpecError):
        Params(levels=2, thr=(1,))
    with pytest.raises(SpecError):
        Params(levels=1, thr=(256,))
    with pytest.raises(SpecError):
        Params(metric="mean")
