"""The contract's decision rules (msr_model.rules, docs/rules.md): the worked example, the
edge and tie cases by hand, and the three forms (vectorised, per tile, tile by tile in any
order) agreeing on every rule."""
import itertools
import random

import numpy as np
import pytest

from msr_model import RULES, ImageRenderer, Params, SpecError, run_tile, select, select_tiled, spec
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
