"""DACS (msr_eval.dacs) and the VRS-like baseline (msr_eval.vrs) on small hand cases."""
import numpy as np
import pytest

from msr_model import SpecError
from msr_model.testimage import test_image as make_test_image
from msr_eval import dacs as D
from msr_eval import vrs as V
from recorder import Recorder


def _honest(res, rec, image):
    assert res.traced == len(rec.asked) == len(set(rec.asked))          # no pixel twice
    assert {(x, y) for y, x in zip(*np.nonzero(res.source < 16))} == set(rec.asked)
    m = res.source < 16
    assert (res.frame[m] == image[m]).all()


def _ramp(w, h):
    """Grey ramp 10 * x (all channels)."""
    img = np.zeros((h, w, 3), np.uint8)
    img[:] = (10 * np.arange(w, dtype=np.uint8))[None, :, None]
    return img


# --- DACS ------------------------------------------------------------------------------------

def test_dacs_pass_order_covers_each_pixel_once():
    p = D.pass_of(8, 8)
    assert (np.bincount(p.ravel()) == [4, 4, 8, 16, 32]).all()
    assert p[0, 0] == 0 and p[2, 2] == 1 and p[0, 2] == 2 and p[2, 0] == 2 and p[1, 1] == 3 and p[3, 3] == 3
    assert p[0, 1] == 4 and p[1, 0] == 4


def test_dacs_ramp_by_hand():
    """5x5 ramp 10*x, variance threshold 300. Pass 0 traces the corners (0, 40 in x).
    (2,2): neighbours 0,40,0,40: variance 400 > 300 -> traced (20).
    (2,0): (0,0)=0, (4,0)=40, (2,2)=20 (the fourth is off the frame): variance 266.7 -> mean 20.
    (0,2): (2,2)=20, (0,0)=0, (0,4)=0: variance 88.9 -> (20 + 1) // 3 = 7 (the truth is 0).
    (4,2): (2,2)=20, (4,0)=40, (4,4)=40: variance 88.9 -> (100 + 1) // 3 = 33."""
    img = _ramp(5, 5)
    rec = Recorder(img)
    res = D.dacs(rec, 5, 5, thr=300)
    _honest(res, rec, img)
    f = res.frame[..., 0]
    assert res.source[2, 2] == D.SRC_TRACED and f[2, 2] == 20
    assert res.source[0, 2] == D.SRC_INTERP and f[0, 2] == 20 and f[4, 2] == 20
    assert res.source[2, 0] == D.SRC_INTERP and f[2, 0] == 7
    assert res.source[2, 4] == D.SRC_INTERP and f[2, 4] == 33
    # one notch lower than (2,2)'s 400 traces it, exactly at 400 interpolates it
    assert D.dacs(Recorder(img), 5, 5, thr=399.9375).source[2, 2] == D.SRC_TRACED
    r400 = D.dacs(Recorder(img), 5, 5, thr=400)
    assert r400.source[2, 2] == D.SRC_INTERP and r400.frame[2, 2, 0] == 20


def test_dacs_metrics_by_hand():
    img = _ramp(5, 5)
    # range of (2,2)'s neighbours is 40
    assert D.dacs(Recorder(img), 5, 5, thr=40, metric="range").source[2, 2] == D.SRC_INTERP
    assert D.dacs(Recorder(img), 5, 5, thr=39, metric="range").source[2, 2] == D.SRC_TRACED
    # luma of a grey is the grey (weights sum to 1): the same 400 as per channel
    assert D.dacs(Recorder(img), 5, 5, thr=401, metric="lumvar").source[2, 2] == D.SRC_INTERP
    assert D.dacs(Recorder(img), 5, 5, thr=399, metric="lumvar").source[2, 2] == D.SRC_TRACED
    # a pure chroma edge: red 200 | green 200 (luma differs, but per channel variance is larger)
    nb = np.array([[[200, 0, 0], [200, 0, 0], [0, 200, 0], [0, 200, 0]]], np.uint8)
    valid = np.ones((1, 4), bool)
    assert D.statistic(nb, valid, "var")[0] == pytest.approx(100 ** 2)
    assert D.statistic(nb, valid, "lumvar")[0] == pytest.approx(((0.7152 - 0.2126) * 200 / 2) ** 2)
    assert D.statistic(nb, valid, "range")[0] == 200
    # invalid neighbours do not count
    valid = np.array([[True, True, False, False]])
    assert D.statistic(nb, valid, "var")[0] == 0 and D.statistic(nb, valid, "range")[0] == 0


def test_dacs_extremes_and_counts():
    img = np.full((12, 16, 3), 77, np.uint8)
    rec = Recorder(img)
    res = D.dacs(rec, 16, 12, thr=0)              # flat: pass 0 traced, and the pixels beyond
    _honest(res, rec, img)                        # the last grid row (8) and column (12) that
    assert (res.frame == 77).all()                # no opposite pair of neighbours surrounds
    extra = {(x, y) for x, y in rec.asked if x % 4 or y % 4}
    assert res.traced == 4 * 3 + len(extra) and len(extra) == 23
    assert all(x > 12 or y > 8 for x, y in extra)
    # (2,10): corners (0,8), (4,8) only, one side: traced. (4,10): (2,10) and (6,10) left and
    # right: interpolated. (0,10): right and up only: traced. (2,11): left and right: interpolated.
    assert (2, 10) in extra and (4, 10) not in extra and (0, 10) in extra and (2, 11) not in extra
    img = make_test_image(37, 29)
    rec = Recorder(img)
    res = D.dacs(rec, 37, 29, thr=-1)             # negative threshold: everything traced
    _honest(res, rec, img)
    assert res.traced == 37 * 29 and (res.frame == img).all()
    fr = []
    for t in (0, 4, 64, 1024, 1e9):
        rec = Recorder(img)
        r = D.dacs(rec, 37, 29, thr=t)
        _honest(r, rec, img)
        fr.append(r.traced)
    assert fr == sorted(fr, reverse=True) and fr[-1] < fr[0]
    # a huge threshold interpolates every pixel but pass 0's (37 x 29: the last row and column
    # lie on the grid, so every pixel lies between two of its neighbours)
    assert fr[-1] == len(range(0, 37, 4)) * len(range(0, 29, 4))
    with pytest.raises(SpecError):
        D.dacs(Recorder(img), 37, 29, thr=1, metric="median")


# --- VRS-like ---------------------------------------------------------------------------------

def test_vrs_rates_and_replication_by_hand():
    """16x16, tiles of 8, s = 2. Pre-pass samples at multiples of 4; the tile (0,0) brackets
    samples x, y in {0, 4, 8}, so the marks at (12,4), (4,12), (12,12) reach only their own
    tile: contrasts 0, 3, 7, 50 -> rates 4x4, 2x2, 2x1, 1x1."""
    img = np.full((16, 16, 3), 100, np.uint8)
    img[4, 12] = 103
    img[12, 4] = 107
    img[12, 12] = 150
    img[13, 13] = 10                                   # not a pre-pass pixel
    rec = Recorder(img)
    res = V.vrs_tier2(rec, 16, 16, thr=2, tile=8)
    _honest(res, rec, img)
    assert res.rates.tolist() == [[0, 1], [2, 3]]
    # 16 pre-pass + 12 (2x2 anchors not pre-pass) + 28 (2x1) + 60 (1x1)
    assert res.traced == 16 + 12 + 28 + 60
    assert (res.frame[8:, 8:] == img[8:, 8:]).all()    # the 1x1 tile is exact
    assert tuple(res.frame[4, 13]) == (103,) * 3 and tuple(res.frame[5, 13]) == (103,) * 3   # 2x2 copies
    assert tuple(res.frame[12, 5]) == (107,) * 3 and tuple(res.frame[13, 4]) == (100,) * 3   # 2x1: rows apart
    assert (res.frame[:8, :8] == 100).all()
    # a larger s coarsens every tile but the 1x1 one; s = 50 makes everything 4x4
    assert V.vrs_tier2(Recorder(img), 16, 16, thr=4, tile=8).rates.tolist() == [[0, 0], [1, 3]]
    r = V.vrs_tier2(Recorder(img), 16, 16, thr=50, tile=8)
    assert r.rates.tolist() == [[0, 0], [0, 0]] and r.traced == 16
    assert tuple(r.frame[15, 15]) == (150,) * 3     # replicated from (12, 12)


def test_vrs_tile16_and_odd_frame():
    img = make_test_image(45, 27)
    for tile in (8, 16):
        prev = None
        for s in (0, 2, 8, 32, 255):
            rec = Recorder(img)
            res = V.vrs_tier2(rec, 45, 27, thr=s, tile=tile)
            _honest(res, rec, img)
            assert res.rates.shape == (-(-27 // tile), -(-45 // tile))
            assert prev is None or res.traced <= prev
            prev = res.traced
        assert prev == 12 * 7                          # all 4x4: just the pre-pass
    rec = Recorder(img)
    r = V.vrs_tier2(rec, 45, 27, thr=-1, tile=16)      # all 1x1: the frame exactly
    assert r.traced == 45 * 27 and (r.frame == img).all()
    with pytest.raises(SpecError):
        V.vrs_tier2(Recorder(img), 45, 27, thr=1, tile=12)


def _dacs_oracle(img, thr, metric):
    """DACS pixel by pixel, written from the module docstring (no numpy tricks)."""
    h, w = img.shape[:2]
    frame = np.zeros_like(img)
    done = np.zeros((h, w), bool)
    traced = set()
    for y in range(0, h, 4):
        for x in range(0, w, 4):
            frame[y, x] = img[y, x]
            done[y, x] = True
            traced.add((x, y))
    for pos, offs in D.PASSES:
        for dy in range(4):
            for dx in range(4):
                if (dx, dy) not in pos:
                    continue
                for y in range(dy, h, 4):
                    for x in range(dx, w, 4):
                        nb = [frame[y + oy, x + ox].astype(int) for ox, oy in offs
                              if 0 <= x + ox < w and 0 <= y + oy < h]
                        assert all(done[y + oy, x + ox] for ox, oy in offs if 0 <= x + ox < w and 0 <= y + oy < h)
                        inside = [0 <= x + ox < w and 0 <= y + oy < h for ox, oy in offs]
                        pairs = ((0, 3), (1, 2)) if offs[0][0] and offs[0][1] else ((0, 1), (2, 3))
                        ok = False
                        if any(inside[i] and inside[j] for i, j in pairs):
                            a = np.array(nb, float)
                            if metric == "var":
                                stat = max(a[:, k].var() for k in range(3))
                            elif metric == "lumvar":
                                stat = (a @ D.LUMA).var()
                            else:
                                stat = max(a[:, k].max() - a[:, k].min() for k in range(3))
                            ok = stat <= thr + 1e-9 * max(1.0, abs(thr))
                        if ok:
                            n = len(nb)
                            frame[y, x] = [(sum(v[k] for v in nb) + n // 2) // n for k in range(3)]
                        else:
                            frame[y, x] = img[y, x]
                            traced.add((x, y))
                        done[y, x] = True
    return frame, traced


@pytest.mark.parametrize("metric", D.METRICS)
def test_dacs_against_a_pixel_by_pixel_oracle(metric):
    rng = np.random.default_rng(5)
    for w, h in ((13, 9), (17, 11), (8, 8)):
        for img in (make_test_image(w, h), (rng.integers(0, 4, (h, w, 3)) * 60).astype(np.uint8)):
            for thr in (0, 10, 300, 3000):
                rec = Recorder(img)
                res = D.dacs(rec, w, h, thr=thr, metric=metric)
                _honest(res, rec, img)
                frame, traced = _dacs_oracle(img, thr, metric)
                assert set(rec.asked) == traced, (w, h, thr)
                assert (res.frame == frame).all(), (w, h, thr)


# --- DACS on 8x8 blocks, VRS with every tier-2 rate and centred samples -------------

def test_dacs_block8_passes_and_counts():
    """8x8 blocks: six passes after the first, each pixel decided once; the last four are the
    4x4 passes; a flat frame traces one pixel in 64 (plus the unbracketed edge pixels)."""
    p = D.pass_of(16, 16, block=8)
    assert p[0, 0] == 0 and p[4, 4] == 1 and p[0, 4] == 2 and p[4, 0] == 2 and p[2, 2] == 3
    assert p[2, 0] == 4 and p[1, 1] == 5 and p[0, 1] == 6
    assert (np.bincount(p.ravel()) == [4, 4, 8, 16, 32, 64, 128]).all()
    assert D.passes_for(8)[2:] == D.passes_for(4)[:0] + tuple(
        (tuple(pos), offs) for pos, offs in D.passes_for(8)[2:])       # shape only
    img = np.full((17, 25, 3), 9, np.uint8)
    rec = Recorder(img)
    res = D.dacs(rec, 25, 17, thr=0, block=8)
    _honest(res, rec, img)
    assert res.traced == len(range(0, 25, 8)) * len(range(0, 17, 8)) and (res.frame == 9).all()
    img = make_test_image(45, 27)
    counts = []
    for t in (-1, 0, 16, 256, 1e9):
        rec = Recorder(img)
        r = D.dacs(rec, 45, 27, thr=t, block=8)
        _honest(r, rec, img)
        counts.append(r.traced)
    assert counts[0] == 45 * 27 and counts == sorted(counts, reverse=True)
    with pytest.raises(SpecError):
        D.dacs(Recorder(img), 45, 27, thr=1, block=16)


def test_vrs_tier2_rates_by_hand():
    """The ladder (s = 2): contrast 0 -> 4x4; 3 -> 4x2 when the colour changes less along x
    (gx <= gy), else 2x4; 7 -> 2x2; 12 -> 2x1 or 1x2 by direction; 50 -> 1x1."""
    c = np.array([[0, 3, 3, 7, 12, 12, 50]])
    gx = np.array([[0, 1, 5, 0, 1, 5, 0]])
    gy = np.array([[0, 5, 1, 0, 5, 1, 0]])
    got = [V.RATES_TIER2[i] for i in V.rate_index_tier2(c, gx, gy, 2)[0]]
    assert got == [(4, 4), (4, 2), (2, 4), (2, 2), (2, 1), (1, 2), (1, 1)]
    # directions: pre-pass samples of one 8x8 tile's window (3x3 samples) with a step along y
    pre = np.zeros((3, 3, 3), np.uint8)
    pre[2, :] = 40
    gx, gy = V.tile_directions(pre, 8, 8, 8)
    assert gx.tolist() == [[0]] and gy.tolist() == [[40]]
    # a frame: 16x16, tile 8; tile (1, 1) holds a step along x in its own samples only
    img = np.full((16, 16, 3), 100, np.uint8)
    img[8:, 12:] = 160
    rec = Recorder(img)
    res = V.vrs_tier2(rec, 16, 16, thr=2, tile=8, rates="tier2", anchor="centre")
    _honest(res, rec, img)
    assert V.RATES_TIER2[res.rates[0, 0]] == (4, 4)
    assert V.RATES_TIER2[res.rates[1, 1]] == (1, 1)         # contrast 60 > 8s
    assert (res.frame[0:4, 0:4] == img[2, 2]).all()         # a 4x4 coarse pixel: its centred sample
    r = V.vrs_tier2(Recorder(img), 16, 16, thr=10, tile=8, rates="tier2", anchor="centre")
    assert V.RATES_TIER2[r.rates[1, 1]] == (1, 2)           # 60 <= 8s, the change is along x


def test_vrs_tier2_extremes():
    img = make_test_image(45, 27)
    for tile in (8, 16):
        prev = None
        for s in (-1, 0, 2, 8, 32, 255, 1e9):
            rec = Recorder(img)
            res = V.vrs_tier2(rec, 45, 27, thr=s, tile=tile, rates="tier2", anchor="centre")
            _honest(res, rec, img)
            assert prev is None or res.traced <= prev
            prev = res.traced
            if s == -1:
                assert res.traced == 45 * 27 and (res.frame == img).all()
        assert prev == 12 * 7                          # all 4x4: the centred pre-pass only
    with pytest.raises(SpecError):
        V.vrs_tier2(Recorder(img), 45, 27, thr=1, rates="tier3")
    with pytest.raises(SpecError):
        V.vrs_tier2(Recorder(img), 45, 27, thr=1, anchor="corner")


# --- exact statistics: integers, thresholds in sixteenths -------------------------------------

def _float_stat(nb, valid, metric):
    """The statistic as floats (what DACS computed before it went to integers)."""
    x = nb.astype(np.int64)
    n = np.maximum(valid.sum(axis=-1), 1).astype(np.float64)
    if metric == "lumvar":
        y = (x @ D.LUMA) * valid
        s1, s2 = y.sum(axis=-1), (y * y).sum(axis=-1)
        return (n * s2 - s1 * s1) / (n * n)
    xv = x * valid[..., None]
    s1, s2 = xv.sum(axis=-2), (xv * x).sum(axis=-2)
    return ((n[..., None] * s2 - s1 * s1) / (n * n)[..., None]).max(axis=-1)


@pytest.mark.parametrize("metric", ["var", "lumvar"])
def test_integer_statistic_equals_the_float_one_away_from_ties(metric):
    rng = np.random.default_rng(7)
    base = rng.integers(0, 256, (4000, 1, 3))
    nb = np.clip(base + rng.integers(-3, 4, (4000, 4, 3)) * rng.integers(0, 30, (4000, 1, 1)), 0, 255)
    valid = rng.random((4000, 4)) < 0.85
    valid[:, 0] = True
    x = nb * valid[..., None]
    num, den = D.stat_parts([x[:, k] for k in range(4)], [valid[:, k] for k in range(4)], metric)
    ref = _float_stat(nb, valid, metric)
    assert np.allclose(num / den, ref, rtol=1e-12, atol=1e-9)
    for thr in (0, 0.1875, 0.5, 1, 3, 40.0625, 300, 3000):
        t16 = D.thr_sixteenths(thr)
        clear = np.abs(ref - thr) > 1e-6
        assert (D.within(num, den, t16) == (ref <= thr))[clear].all()


def test_exact_ties_interpolate():
    """A tie (stat == thr) interpolates, decided in integers. (2,2)'s diagonal neighbours in a
    5x5 frame: one of four 1 level off is a variance of 3/16 exactly."""
    img = np.full((5, 5, 3), 100, np.uint8)
    img[4, 4] = 101
    assert D.dacs(Recorder(img), 5, 5, thr=0.1875).source[2, 2] == D.SRC_INTERP
    assert D.dacs(Recorder(img), 5, 5, thr=0.125).source[2, 2] == D.SRC_TRACED
    # Luma: greys 2 apart in pairs are a luma variance of exactly 1, which the float luma put
    # 7e-12 above (so a threshold of 1 traced it); in integers the tie interpolates.
    nb = np.array([[[25, 245, 47], [25, 245, 47], [27, 247, 49], [27, 247, 49]]])
    assert _float_stat(nb, np.ones((1, 4), bool), "lumvar")[0] > 1
    assert D.statistic(nb, np.ones((1, 4), bool), "lumvar")[0] == 1
    img = np.zeros((5, 5, 3), np.uint8)
    for (x, y), c in zip(((0, 0), (4, 0), (0, 4), (4, 4)), nb[0]):
        img[y, x] = c
    assert D.dacs(Recorder(img), 5, 5, thr=1, metric="lumvar").source[2, 2] == D.SRC_INTERP
    assert D.dacs(Recorder(img), 5, 5, thr=0.9375, metric="lumvar").source[2, 2] == D.SRC_TRACED


def test_thresholds_come_in_sixteenths():
    assert D.thr_sixteenths(0) == 0 and D.thr_sixteenths(0.0625) == 1 and D.thr_sixteenths(3) == 48
    assert D.thr_sixteenths(-1) == -1 and D.thr_sixteenths(-0.3) == -1
    assert D.thr_sixteenths(1e30) == D.thr_sixteenths(16384 * 64)       # capped: all pass alike
    for bad in (0.1, 399.9, float("nan"), "1"):
        with pytest.raises(SpecError):
            D.thr_sixteenths(bad)
