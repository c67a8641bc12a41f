"""The contract's decision rules (msr_model.rules, docs/rules.md): the worked example, the
edge and tie cases by hand, and the three forms (vectorised, per tile, tile by tile in any
order) agreeing on every rule."""
import itertools
import random

import numpy as np
import pytest

from msr_model import RULES, ImageRenderer, Params, SpecError, run_tile, select, select_tiled, spec
from msr_model.golden import frame_axis
from msr_model.testimage import test_image as make_test_image


def example_tile():
    img = np.zeros((16, 16, 3), np.uint8)
    img[:, :, 0] = (10 * np.arange(16))[None, :]
    img[:, :, 1:] = 50
    img[4, 10:, 1] = 200
    return img


def test_worked_example_of_docs_rules_md():
    img = example_tile()
    p = Params(tile=16, levels=2, thr=(8, 16))
    pat = select(ImageRenderer(img), 16, 16, p)
    lin = select(ImageRenderer(img), 16, 16, p, rule="lindilate")
    assert pat.stats["traced"] == 128 and lin.stats["traced"] == 78
    assert lin.stats["rule"] == "lindilate" and pat.stats["rule"] == "patent"
    codes = {y: [int(lin.source[y, x]) for x in (2, 6, 10, 13)] for y in (0, 4, 8, 12, 15)}
    assert codes == {0: [17, 1, 1, 1], 4: [17, 1, 1, 1], 8: [17, 1, 1, 1], 12: [17, 17, 17, 1],
                     15: [17, 17, 17, 1]}
    assert tuple(lin.frame[0, 2]) == (20, 50, 50)
    assert (pat.source[[0, 4, 8, 12, 15]][:, [2, 6, 10, 13]] == 1).all()
    # wherever either rule interpolates, the ramp's exact colour (away from the edge row)
    for r in (pat, lin):
        interp = r.source >= 16
        interp[4] = False
        assert (r.frame[interp] == img[interp]).all()


def one_row(values):
    return np.array([values], dtype=np.uint8)


def test_second_difference_missing_and_one_sided_samples():
    """T=8, L=1, one row: G0 = {0, 2, 4, 6, 7}; gaps (0,2): only B' at 4; (4,6): only A' at 2
    (B' at 8 is outside); (2,4): both; gap (6,7) has no new pixel."""
    ramp = [(20 * x, 0, 0) for x in range(8)]
    p = Params(tile=8, levels=1, thr=(10,))
    r = select(ImageRenderer(one_row(ramp)), 8, 1, p, rule="lindilate")
    assert [int(c) for c in r.source[0]] == [0, 17, 0, 17, 0, 17, 0, 0]
    # Bend the ramp at x = 6 (120 -> 200). (0,2) reads only B' at 4: still a ramp. (2,4) reads
    # B' at 6: |40 - 160 + 200| = 80, not below 10: traced. (4,6) reads only A' at 2:
    # |40 - 160 + 200| = 80: traced.
    bent = list(ramp)
    bent[6] = (200, 0, 0)
    r = select(ImageRenderer(one_row(bent)), 8, 1, p, rule="lindilate")
    assert [int(c) for c in r.source[0]] == [0, 17, 0, 1, 0, 1, 0, 0]


def test_ties_are_strict():
    """c2 * n_k == thr * g fails, as d * n_k == thr * g does."""
    # T=8, L=1, row 0..4 (w=5: G0 = {0, 2, 4}): x=1 from (0,2) reads B' at 4 only.
    for c2, expect in ((9, 17), (10, 1)):
        row = [(0, 0, 0), (7, 7, 7), (50, 0, 0), (0, 0, 0), (100 + c2, 0, 0)]
        r = select(ImageRenderer(one_row(row)), 5, 1, Params(tile=8, levels=1, thr=(10,)), rule="lindilate")
        assert r.source[0, 1] == expect, c2
    r = select(ImageRenderer(one_row([(0, 0, 0)] * 5)), 5, 1, Params(tile=8, levels=1, thr=(0,)), rule="lindilate")
    assert (r.source[0] < 16).all()          # threshold 0 traces everything


@pytest.mark.parametrize("rule", list(RULES))
def test_vectorised_equals_per_tile_in_any_order(rule):
    rng = random.Random(5)
    cases = list(itertools.product([(57, 40), (16, 9), (1, 33), (40, 1)], (8, 16, 32), (1, 2, 3), ("max", "sum"),
                                   (0, 90)))
    for (w, h), T, L, metric, gain in rng.sample(cases, 16):   # the per-tile form is slow Python
        img = make_test_image(w, h)
        p = Params(tile=T, levels=L, thr=tuple(rng.randrange(1, 40) for _ in range(L)), metric=metric,
                   fov_gain=gain)
        whole = select(ImageRenderer(img), w, h, p, rule=rule)
        order = list(range(len(spec.frame_tiles(w, h, T))))
        rng.shuffle(order)
        frame, source = select_tiled(ImageRenderer(img), w, h, p, order=order, rule=rule)
        assert (frame == whole.frame).all() and (source == whole.source).all(), (w, h, T, L, metric, gain)


def test_lindilate_reads_only_its_own_tile():
    """Changing every pixel outside one tile changes nothing inside it."""
    img = make_test_image(64, 48)
    noisy = np.random.default_rng(3).integers(0, 256, img.shape).astype(np.uint8)
    noisy[16:32, 32:48] = img[16:32, 32:48]
    p = Params(16, 3, (4, 8, 16))
    a = select(ImageRenderer(img), 64, 48, p, rule="lindilate")
    b = select(ImageRenderer(noisy), 64, 48, p, rule="lindilate")
    assert (a.frame[16:32, 32:48] == b.frame[16:32, 32:48]).all()
    assert (a.source[16:32, 32:48] == b.source[16:32, 32:48]).all()


def test_run_tile_decisions_and_requests_follow_the_rule():
    img = example_tile()
    p = Params(tile=16, levels=2, thr=(8, 16))
    res = run_tile(lambda x, y: img[y, x], 0, 0, 16, 16, p, (8, 16), rule="lindilate")
    whole = select(ImageRenderer(img), 16, 16, p, rule="lindilate")
    assert (res.pixels == whole.frame).all() and (res.codes == whole.source).all()
    assert len(res.requests) == 78
    assert sum(not d.interpolate for d in res.decisions) == 78 - 25     # 25 initial samples
    d = [d for d in res.decisions if (d.step.x, d.step.y, d.step.direction) == (2, 0, "H")][0]
    assert d.diff == 40 and d.interpolate and d.value == (20, 50, 50)


def test_unknown_rule_and_bad_rule_function():
    img = make_test_image(8, 8)
    with pytest.raises(SpecError):
        select(ImageRenderer(img), 8, 8, Params(), rule="magic")
    with pytest.raises(RuntimeError):
        select(ImageRenderer(img), 8, 8, Params(), rule=lambda v: np.ones(3, bool))


def test_lindilate2d_decides_as_lindilate_and_smooths_the_last_v_pass():
    """lindilate2d: the same sources as lindilate everywhere; the same colours
    except at the last level's V-pass interpolations, which are (2 (A + B) + the four
    diagonal corners + 4) >> 3 where the corners lie in the tile and the six agree within
    the level's threshold, checked here against a formula written out independently."""
    rng = np.random.default_rng(7)
    h, w = 40, 56
    yy, xx = np.mgrid[0:h, 0:w]
    img = np.clip(np.stack([2 * xx + yy, 100 + xx - yy, 60 + 0 * xx], -1) + rng.integers(-3, 4, (h, w, 3)),
                  0, 255).astype(np.uint8)
    img[20:, 30:] = 220                                   # an edge: the range test must keep it sharp
    for T, L, thr in ((16, 2, (8, 12)), (8, 1, (10,)), (32, 3, (4, 8, 16))):
        p = Params(tile=T, levels=L, thr=thr)
        lin = select(ImageRenderer(img), w, h, p, rule="lindilate")
        new = select(ImageRenderer(img), w, h, p, rule="lindilate2d")
        assert (new.source == lin.source).all() and new.stats["traced"] == lin.stats["traced"]
        F, changed = new.frame.astype(np.int32), 0
        known = set(int(v) for v in frame_axis(h, T, L).known[L - 1])      # Gy(L-1), frame rows
        for y, x in zip(*np.nonzero(new.source == 16 + L)):
            if y in known or y - 1 not in known or y + 1 not in known:     # not the V pass, gap 2
                assert (new.frame[y, x] == lin.frame[y, x]).all()
                continue
            ty, tx = y // T, x // T
            inside = (x - 1) // T == tx and (x + 1) // T == tx and x + 1 < w and (y + 1) // T == ty and y + 1 < h
            if not inside:
                assert (new.frame[y, x] == lin.frame[y, x]).all()
                continue
            six = np.stack([F[y - 1, x], F[y + 1, x], F[y - 1, x - 1], F[y - 1, x + 1], F[y + 1, x - 1],
                            F[y + 1, x + 1]])
            rng6 = int((six.max(0) - six.min(0)).max())
            if rng6 * 2 < thr[L - 1] * 2:                     # n_L = 2 = the gap: d < thr
                want = (2 * (six[0] + six[1]) + six[2:].sum(0) + 4) >> 3
                changed += int((want != lin.frame[y, x]).any())
            else:
                want = lin.frame[y, x]
            assert (new.frame[y, x] == want).all(), (T, L, y, x)
        assert changed > 10, (T, L)
        assert (new.frame[20:, 31:] == 220).all()          # the flat side of the edge stays flat
    # by hand: T=8, L=1, w=4: G0 = {0, 2, 3} across, {0, 2} down. The V pass's (2, 1) lies
    # between A = (2, 0) = 100 and B = (2, 2) = 110 (traced); its corners: (1, 0) = 90 (the H
    # pass's mean of 80 and 100), (3, 0) = 150, (1, 2) = 100 (of 90 and 110), (3, 2) = 100.
    # Range 60 < 200: (2 * 210 + 90 + 150 + 100 + 100 + 4) >> 3 = 108 (lindilate: 105).
    img = np.zeros((3, 4, 3), np.uint8)
    img[0, :, 0] = [80, 0, 100, 150]
    img[2, :, 0] = [90, 0, 110, 100]
    p = Params(tile=8, levels=1, thr=(200,))
    a = select(ImageRenderer(img), 4, 3, p, rule="lindilate")
    b = select(ImageRenderer(img), 4, 3, p, rule="lindilate2d")
    assert a.frame[0, 1, 0] == 90 and a.frame[2, 1, 0] == 100 and a.frame[1, 2, 0] == 105
    assert b.frame[1, 2, 0] == 108 and b.source[1, 2] == a.source[1, 2] == 17
    assert b.frame[1, 3, 0] == a.frame[1, 3, 0]          # (3, 1): its right corners lie off the frame
    # one notch of threshold below the range (60): the spec's interpolation again
    p = Params(tile=8, levels=1, thr=(60,))
    assert select(ImageRenderer(img), 4, 3, p, rule="lindilate2d").frame[1, 2, 0] == 105


def test_lindilate2d_reads_only_its_own_tile():
    img = make_test_image(64, 48)
    noisy = np.random.default_rng(4).integers(0, 256, img.shape).astype(np.uint8)
    noisy[16:32, 32:48] = img[16:32, 32:48]
    p = Params(16, 2, (40, 80))
    a = select(ImageRenderer(img), 64, 48, p, rule="lindilate2d")
    b = select(ImageRenderer(noisy), 64, 48, p, rule="lindilate2d")
    assert (a.frame[16:32, 32:48] == b.frame[16:32, 32:48]).all()
    assert (a.source[16:32, 32:48] == b.source[16:32, 32:48]).all()


def test_rule_reconstruction_is_checked():
    img = make_test_image(8, 8)

    def bad(v):
        return np.ones(v.shape, bool)
    bad.interpolate = lambda v, lin: lin[..., :2]
    with pytest.raises(RuntimeError):
        select(ImageRenderer(img), 8, 8, Params(), rule=bad)
