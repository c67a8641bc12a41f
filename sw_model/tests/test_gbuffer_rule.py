"""The G-buffer edge rule of msr_eval.gbuffer_rule on small hand cases (docs/rules.md,
"Rule gbuf"): which pixels it traces, what it keeps of ids and depths for interpolated
pixels, the combination with lindilate, and the same frame on the live renderer."""
import numpy as np
import pytest

from msr_model import Params, SpecError
from msr_model.testimage import test_image as make_test_image
from msr_eval import methods as M
from msr_eval.gbuffer_rule import (GBufferImage, TileGBuffer, edges, flat_gbuffer, gbuffer_rule,
                                   multi_level_gbuffer)
from msr_model import select

W = H = 16
P2 = Params(tile=16, levels=2, thr=(8, 16), fov_gain=0)
FLAT = np.full((H, W, 3), 100, np.uint8)            # one colour: every colour test interpolates


def _traced(res):
    ys, xs = np.nonzero(res.source < 16)
    return set(zip(xs.tolist(), ys.tolist()))


def test_edge_test_by_hand():
    idA = np.array([1, 1, 1, 1, 0, 1])
    idB = np.array([1, 2, 1, 1, 0, 1])
    zA = np.array([10, 10, 10, 10, np.inf, np.inf], np.float32)
    zB = np.array([10, 10, 10.9, 11.5, np.inf, 10], np.float32)
    # same | other id | 0.9 <= 0.1*10 | 1.5 > 1.0 | sky = sky | sky depth vs surface
    assert edges(idA, zA, idB, zB, 0.1).tolist() == [False, True, False, True, False, True]
    # ids only: no depth edge, even against the sky's infinite depth
    assert edges(idA, zA, idB, zB, np.inf).tolist() == [False, True, False, False, False, False]
    # a tie is not beyond: |9 - 8| = 0.125 * 8 (exact in binary); either order
    one = np.array([1])
    assert not edges(one, np.float32([8]), one, np.float32([9]), 0.125).any()
    assert not edges(one, np.float32([9]), one, np.float32([8]), 0.125).any()
    assert edges(one, np.float32([8]), one, np.float32([9]), 0.124).all()


def test_material_border_forces_exactly_the_gaps_across_it():
    """ids 1 for x <= 6, 2 from x = 7 on; flat colour. T=16, L=2: G0 = {0, 4, 8, 12, 15};
    level 1 H pass: x = 6 (between 4 and 8) on the 5 rows of G0; level 2 H pass: x = 7
    (between 6 and 8) on the 9 rows of G_y(1) = {0, 2, 4, 6, 8, 10, 12, 13, 15}; no V-pass
    decision crosses the border. 14 traces more than the patent's rule, nothing else."""
    ids = np.where(np.arange(W) >= 7, 2, 1).astype(np.uint32)[None, :].repeat(H, 0)
    z = (100 + np.arange(W, dtype=np.float32))[None, :].repeat(H, 0)     # a ramp: 4 % per gap of 4, no edge
    unit = GBufferImage(FLAT, (ids, ids, z))
    base = M.multi_level(GBufferImage(FLAT, (ids, ids, z)), W, H, P2, "patent")
    c = M.CountingRenderer(unit, W, H)
    gb = TileGBuffer(c, unit.gbuffer, W, H)
    r = select(gb, W, H, P2, rule=gbuffer_rule(gb, "patent", 0.1))
    res = M.MethodResult(r.frame, r.source, c.requests, "x")
    extra = _traced(res) - _traced(base)
    assert _traced(base) <= _traced(res)
    assert extra == {(6, y) for y in (0, 4, 8, 12, 15)} | {(7, y) for y in (0, 2, 4, 6, 8, 10, 12, 13, 15)}
    assert res.traced == base.traced + 14 == unit.pixels_traced
    assert (res.frame == FLAT).all()
    # every pixel, traced or interpolated, ends with its true id, and the ramp's depth
    assert (gb.ids == ids).all()
    assert np.array_equal(gb.depth, z.astype(np.float16))


def test_depth_step_forces_traces_only_beyond_the_tolerance():
    ids = np.ones((H, W), np.uint32)
    z = np.where(np.arange(W) >= 7, 20.0, 10.0).astype(np.float32)[None, :].repeat(H, 0)
    base = _traced(M.multi_level(GBufferImage(FLAT, (ids, ids, z)), W, H, P2, "patent"))
    near = _traced(multi_level_gbuffer(GBufferImage(FLAT, (ids, ids, z)), W, H, P2, "patent", depth_tol=0.1))
    assert near - base == {(6, y) for y in (0, 4, 8, 12, 15)} | {(7, y) for y in (0, 2, 4, 6, 8, 10, 12, 13, 15)}
    # a step of 10 at depth 10 is not beyond a tolerance of 1.0 (100 %)
    assert _traced(multi_level_gbuffer(GBufferImage(FLAT, (ids, ids, z)), W, H, P2, "patent",
                                       depth_tol=1.0)) == base


def test_combined_rule_dilates_an_edge_to_the_neighbouring_lines():
    """One pixel of another material at (8, 4). Level 1 H pass, row 4: x = 6 (4..8) and
    x = 10 (8..12) cross it. gbuf traces them on row 4 only; gbuflindilate also on rows 0
    and 8, the lines before and after row 4 in G0 (docs/rules.md, dilation)."""
    ids = np.ones((H, W), np.uint32)
    ids[4, 8] = 2
    z = np.full((H, W), 5.0, np.float32)
    g = (ids, ids, z)
    base = _traced(M.multi_level(GBufferImage(FLAT, g), W, H, P2, "lindilate"))
    alone = _traced(multi_level_gbuffer(GBufferImage(FLAT, g), W, H, P2, "patent"))
    both = _traced(multi_level_gbuffer(GBufferImage(FLAT, g), W, H, P2, "lindilate"))
    assert {(6, 4), (10, 4)} <= alone and not ({(6, 0), (10, 0), (6, 8), (10, 8)} & alone)
    assert {(x, y) for x in (6, 10) for y in (0, 4, 8)} <= both - base


@pytest.mark.parametrize("combine, base_rule", [("patent", "patent"), ("lindilate", "lindilate")])
def test_without_edges_the_rule_is_its_base_rule(combine, base_rule):
    img = make_test_image(64, 48)
    p = Params(tile=16, levels=3, thr=(4, 8, 16), fov_gain=0)
    a = M.multi_level(GBufferImage(img, flat_gbuffer(48, 64)), 64, 48, p, base_rule)
    b = multi_level_gbuffer(GBufferImage(img, flat_gbuffer(48, 64)), 64, 48, p, combine)
    assert (a.frame == b.frame).all() and (a.source == b.source).all() and a.traced == b.traced
    assert b.method == ("multi_gbuf" if combine == "patent" else "multi_gbuflindilate")


def test_bad_arguments():
    with pytest.raises(SpecError, match="gbuffer"):
        multi_level_gbuffer(M.CountingRenderer(None, 4, 4), 4, 4, P2)
    unit = GBufferImage(FLAT, flat_gbuffer(H, W))
    with pytest.raises(SpecError, match="combine"):
        multi_level_gbuffer(unit, W, H, P2, combine="dilate")
    with pytest.raises(SpecError, match="id_kind"):
        multi_level_gbuffer(unit, W, H, P2, id_kind="object")
    with pytest.raises(SpecError, match="depth_tol"):
        multi_level_gbuffer(unit, W, H, P2, depth_tol=0)
    with pytest.raises(ValueError, match="G-buffer shapes"):
        GBufferImage(FLAT, flat_gbuffer(H, W + 1))


def test_live_renderer_equals_the_cached_reference_and_gbuffer():
    """What the sweep does (picture + G-buffer rendered once) gives the live renderer's frame."""
    # No skip on a missing renderer: make test builds it first, and a skip would hide a failure.
    from msr_model import embree
    r = embree.open_renderer("duck", 64, 48, quality="fast")
    p = Params(tile=16, levels=3, thr=(4, 8, 16), fov_gain=0)
    with r:
        ref, gb = r.render_full(), r.gbuffer_full()
        live = multi_level_gbuffer(r, 64, 48, p, "lindilate")
    cached = multi_level_gbuffer(GBufferImage(ref, gb), 64, 48, p, "lindilate")
    assert (live.frame == cached.frame).all() and (live.source == cached.source).all()
    # the duck's silhouette against the floor is an edge: the rule traces more than lindilate
    plain = M.multi_level(GBufferImage(ref, gb), 64, 48, p, "lindilate")
    assert cached.traced > plain.traced
