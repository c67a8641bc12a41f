"""Tests of the evaluation's decision rules (msr_eval.rules) through golden.select's rule hook."""
import numpy as np
import pytest

from msr_eval.rules import rule_function
from msr_model import ImageRenderer, Params, SpecError, select
from msr_model.testimage import test_image as make_test_image


def select_rule(renderer, w, h, params, rule):
    return select(renderer, w, h, params, rule=rule_function(rule))


@pytest.mark.parametrize("w,h", [(70, 50), (33, 17), (16, 16), (1, 5)])
@pytest.mark.parametrize("params", [
    Params(16, 2, (8, 16)), Params(8, 3, (4, 8, 16), fov_gain=30), Params(32, 1, (10,)),
    Params(16, 3, (2, 4, 8), metric="sum")])
def test_patent_rule_is_golden(w, h, params):
    img = make_test_image(w, h)
    g = select(ImageRenderer(img), w, h, params)
    r = select_rule(ImageRenderer(img), w, h, params, rule="patent")
    assert (g.frame == r.frame).all() and (g.source == r.source).all()


def _ramp(w, h, sx, sy):
    yy, xx = np.mgrid[0:h, 0:w]
    v = sx * xx + sy * yy
    return np.stack([v, 2 * xx + yy, 255 - v], -1).astype(np.uint8)


def test_linear_rule_interpolates_steep_ramp():
    """A ramp steeper than the threshold: the patent traces it, the linear rule interpolates it exactly."""
    img = _ramp(32, 32, 4, 3)          # 4 per pixel in x: d = 16 over a gap of 4 > thr 8
    p = Params(16, 2, (8, 8))
    pat = select_rule(ImageRenderer(img), 32, 32, p, rule="patent")
    lin_r = ImageRenderer(img)
    lin = select_rule(lin_r, 32, 32, p, rule="linear")
    assert (lin.frame == img).all()
    assert lin.stats["traced"] < pat.stats["traced"]
    assert lin_r.pixels_traced == lin.stats["traced"]
    # gaps with no second sample on the line inside the tile fall back to the patent test:
    # tile row y = 0, gap (12, 15) has a - g = 9 (not a sample) and b + g outside the tile
    assert lin.source[0, 13] == 1 and lin.source[0, 14] in (2, 18)


def test_linear_rule_still_traces_edges():
    """A step edge between A and B gives a second difference of |B - A|: still traced."""
    img = np.zeros((16, 16, 3), np.uint8)
    img[:, 6:] = 200
    p = Params(16, 2, (8, 16))
    lin = select_rule(ImageRenderer(img), 16, 16, p, rule="linear")
    assert (lin.frame == img).all()
    # row 0: gap (4, 8) traced at level 1 (x = 6), then gap (4, 6) traced at level 2 (x = 5)
    assert lin.source[0, 6] == 1 and lin.source[0, 5] == 2


def test_diag_rule_catches_crossing_edges():
    """L = 1 on a 3 x 3 tile: corners 0/200/200/0, H results 100 and 100 at the top and bottom.
    The patent interpolates the centre from (1, 0) and (1, 2); the diag rule sees the corner
    range 200 and traces it."""
    img = np.array([[[0] * 3, [100] * 3, [200] * 3],
                    [[90] * 3, [7] * 3, [90] * 3],
                    [[200] * 3, [100] * 3, [0] * 3]], np.uint8)
    p = Params(8, 1, (20,))
    pat = select_rule(ImageRenderer(img), 3, 3, p, rule="patent")
    dia = select_rule(ImageRenderer(img), 3, 3, p, rule="diag")
    assert pat.source[1, 1] == 17 and tuple(pat.frame[1, 1]) == (100, 100, 100)
    assert dia.source[1, 1] == 1 and tuple(dia.frame[1, 1]) == (7, 7, 7)
    # non-centre pixels are decided as in the patent
    mask = np.ones((3, 3), bool)
    mask[1, 1] = False
    assert (pat.source[mask] == dia.source[mask]).all()


def test_dilate_rule_traces_next_to_a_detection():
    """L = 1, 5 x 5: a bright sample at (2, 0) makes both gaps of row 0 fail; row 2 hides a
    feature at (1, 2) that its samples cannot see. The patent interpolates it away, the
    dilate rule traces row 2's gaps because row 0 (the neighbouring sampled row) failed."""
    img = np.zeros((5, 5, 3), np.uint8)
    img[0, 2] = 200
    img[2, 1] = 100
    p = Params(8, 1, (20,))
    pat = select_rule(ImageRenderer(img), 5, 5, p, rule="patent")
    dil = select_rule(ImageRenderer(img), 5, 5, p, rule="dilate")
    assert pat.source[2, 1] == 17 and pat.frame[2, 1, 0] == 0
    assert dil.source[2, 1] == 1 and dil.frame[2, 1, 0] == 100 and dil.source[2, 3] == 1
    assert dil.source[4, 1] == 17          # row 4's neighbour (row 2) passed the test
    # every trace of the patent is also a trace of the dilate rule at level 1's H pass
    assert ((pat.source[::2] == 1) <= (dil.source[::2] == 1)).all()


def test_rules_tile_independent():
    img = make_test_image(64, 48)
    p = Params(16, 3, (4, 8, 16))
    for rule in ("linear", "diag", "dilate", "lindilate"):
        whole = select_rule(ImageRenderer(img), 64, 48, p, rule=rule)
        crop = np.ascontiguousarray(img[16:32, 32:48])
        part = select_rule(ImageRenderer(crop), 16, 16, p, rule=rule)
        assert (part.frame == whole.frame[16:32, 32:48]).all()


def test_bad_rule():
    with pytest.raises(SpecError):
        select_rule(ImageRenderer(make_test_image(8, 8)), 8, 8, Params(), rule="magic")


def test_levels_4_only_as_the_evaluation_extension():
    """L = 4 (stride 16) is outside algorithm.md and the registers: refused unless the Params is
    marked as the evaluation extension, and then a complete frame whose initial grid is the
    stride-16 grid of every tile (docs/rules.md "L = 4")."""
    with pytest.raises(SpecError, match="1, 2 or 3"):
        Params(32, 4, (1, 2, 4, 8))
    with pytest.raises(SpecError, match="1 to 4"):
        Params(32, 5, (1, 2, 4, 8, 16), extension=True)
    p = Params(32, 4, (1, 2, 4, 8), extension=True)
    assert p.stride == 16 and p.as_dict()["extension"] is True
    assert "extension" not in Params(32, 3, (1, 2, 4)).as_dict()     # the RTL's settings unchanged
    w, h = 70, 50
    flat = np.full((h, w, 3), 90, np.uint8)
    r = select(ImageRenderer(flat), w, h, p)
    # a flat frame: only the initial grid is traced; per axis, every tile's 0, 16, ... and its last pixel
    from msr_model import spec
    per_axis = [sum(len(spec.initial_grid(n, 16)) for _, n in spec.axis_spans(m, 32)) for m in (w, h)]
    assert r.stats["traced"] == per_axis[0] * per_axis[1] and (r.frame == flat).all()
    img = make_test_image(w, h)
    for rule in ("patent", "lindilate2d"):
        full = select_rule(ImageRenderer(img), w, h, Params(32, 4, (0, 0, 0, 0), extension=True), rule)
        assert (full.frame == img).all() and full.stats["traced"] == w * h
        some = select_rule(ImageRenderer(img), w, h, p, rule)
        assert (some.source != 255).all() and 0 < some.stats["traced"] < w * h
