"""The ray-budget controller (msr_model.budget, docs/budget.md): the worked example by hand,
budget 0 unchanged, monotonic, bounded, refusals, the CLI."""
import json
import subprocess
import sys

import numpy as np
import pytest

from msr_model import ImageRenderer, Params, save_png, select
from msr_model import budget as BG
from msr_model.testimage import test_image as make_picture

L2 = Params(tile=16, levels=2, thr=(8, 16))
L3 = Params(tile=16, levels=3, thr=(8, 16, 32))


def _noise_picture(w, h, seed):
    """Smooth ramps plus blocks of noise: rows of very different activity."""
    rng = np.random.default_rng(seed)
    img = make_picture(w, h).astype(np.int32)
    y0 = rng.integers(0, h // 2)
    img[y0:y0 + h // 4, : w // 2] += rng.integers(-40, 41, size=(min(h // 4, h - y0), w // 2, 3))
    return np.clip(img, 0, 255).astype(np.uint8)


# --- the worked example of docs/budget.md, by hand --------------------------------------------

def test_worked_example_by_hand():
    """64 x 40, T 16, L 2: rows of height 16, 16, 8; grid 100, 100, 60 (G = 260); B = 640."""
    assert BG.grid_axis(16, 4) == 5 and BG.grid_axis(8, 4) == 3
    assert BG.grid_count(64, 40, L2) == 260
    ctl = BG.Controller(64, 40, L2, BG.BudgetConfig(budget=640, scale_init=256, prior_shift=6))
    assert (ctl.prior_n, ctl.prior_p) == (1520, 40)       # (380 * 256) >> 6, 2560 >> 6
    assert ctl.scales == [256, 256]
    ctl.finish_row(300)               # a = 200 * 256; X = 640 - 300 - 160 = 180; Q = 1536
    assert ctl.activity == [51200]
    assert ctl.scales == [256, 256, 422]                  # 52720 * 1536 // (1064 * 180)
    assert BG.thr_multiplier(422) == 696
    assert [BG.scale_threshold(t, 696) for t in (8, 16)] == [22, 44]
    ctl.finish_row(200)
    assert ctl.scales == [256, 256, 422] and ctl.scale_out is None
    ctl.finish_row(130)               # a = 70 * 422 = 29540; N = 106340
    assert ctl.activity == [51200, 25600, 29540]
    assert ctl.scale_out == 279                           # 106340 // 380
    # the next frame, seeded with SCALE_OUT and the activity memory
    nxt = BG.Controller(64, 40, L2, BG.BudgetConfig(640, ctl.scale_out, 6, tuple(ctl.activity),
                                                    tuple(ctl.scales)))
    assert nxt.scales == [279, 279]
    # the seed pass: b = a * min(u, 279) = 51200 * 256, 25600 * 256 (rows below the seed: their
    # own u) and 29540 * 279 (row 2 ran above it, at 422: the seed)
    assert nxt.prof_words == [13107200, 6553600, 8241660] and nxt.prof_total == 27902460
    nxt.finish_row(290)               # X = 190; (27902460 - 13107200) // (279 * 190) = 279
    assert nxt.scales == [279, 279, 279]


def test_seed_weight_is_the_lower_scale():
    """The seed pass's weight (docs/budget.md section 4): a row at or below the seed keeps its own
    scale (excess ~ 1 / u^2 up to the seed), one above it the seed's (v5, as v3)."""
    assert BG.seed_weight(200, 279) == 200 and BG.seed_weight(279, 279) == 279
    assert BG.seed_weight(422, 279) == 279 and BG.seed_weight(1448, 45) == 45
    cfg = BG.BudgetConfig(640, 279, 6, (51200, 25600, 4 * 422), (256, 256, 422))
    assert BG.Controller(64, 40, L2, cfg).prof_words == [51200 * 256, 25600 * 256, 4 * 422 * 279]


def test_activity_floor_by_hand():
    """A row that traces only its grid (or a little more) still counts p >> 7 pixels of activity
    at its scale: 64 x 40, rows of 1024, 1024 and 512 pixels, floors 8, 8 and 4."""
    ctl = BG.Controller(64, 40, L2, BG.BudgetConfig(budget=640, scale_init=256, prior_shift=6))
    ctl.finish_row(100)               # the grid only: max(0, 1024 >> 7) * 256
    assert ctl.activity == [8 * 256]
    ctl.finish_row(103)               # 3 above the grid, under the floor
    assert ctl.activity == [2048, 8 * 256]
    u2 = ctl.scales[2]
    ctl.finish_row(65)                # 5 above the grid of the last row, over its floor of 4
    assert ctl.activity == [2048, 2048, 5 * u2]
    assert ctl.n_act == sum(ctl.activity)


def test_threshold_scale_identity_and_saturation():
    assert BG.thr_multiplier(256) == 256
    assert all(BG.scale_threshold(t, 256) == t for t in range(256))
    assert BG.scale_threshold(255, BG.thr_multiplier(BG.U_MAX)) == 255
    assert BG.scale_threshold(8, BG.thr_multiplier(BG.U_MIN)) == 0      # (8 * 8 + 128) >> 8
    assert BG.thr_multiplier(BG.U_MIN) == 8 and BG.thr_multiplier(BG.U_MAX) == 8190


# --- the dispatch order and the dither (v5, docs/budget.md sections 1 and 2) -------------------

@pytest.mark.parametrize("nty", [1, 2, 3, 7, 8, 9, 15, 16, 30, 34, 68, 135, 512])
def test_row_order_interleaves_the_rows(nty):
    order = BG.row_order(nty)
    assert sorted(order) == list(range(nty))
    s = 1 << BG.row_stride_log2(nty)
    assert (nty < 8 and s == 1) or 4 * s <= nty < 8 * s        # the largest S with 4 S <= nty
    assert order == [r for phase in range(s) for r in range(phase, nty, s)]
    # next_row as the hardware walks it (nty_s = nty - S a register of the frame)
    r, walk = 0, [0]
    for _ in range(nty - 1):
        r = BG.next_row(r, BG.row_stride_log2(nty), nty)
        walk.append(r)
    assert walk == order


def test_budget_frame_renders_its_rows_in_dispatch_order():
    w, h = 40, 16 * 9                                            # 9 tile rows: S = 2
    img = _noise_picture(w, h, 8)
    seen = []

    class Recorder(ImageRenderer):
        def render(self, xs, ys):
            ys = np.asarray(ys)
            if ys.size and (not seen or seen[-1] != int(ys.min()) // 16):
                seen.append(int(ys.min()) // 16)
            return super().render(xs, ys)
    BG.select_budget(Recorder(img), w, h, L2, BG.BudgetConfig(w * h // 4))
    assert seen == [0, 2, 4, 6, 8, 1, 3, 5, 7] == BG.row_order(9)


def test_dither_is_neutral_at_unit_scale_and_fractional_elsewhere():
    row = [BG.thr_dither(tx, 3) for tx in range(256)]
    assert sorted(row) == list(range(256))                      # every d once in 256 tiles
    assert row[:4] == [BG.thr_dither(0, 3), 0b00100000, 0b10100000, 0b01100000]
    assert all(BG.scale_threshold(t, 256, d) == t for t in range(256) for d in (0, 127, 255))
    # the mean threshold of 256 tiles follows thr * m / 256 (the rounding would give one integer)
    for t, m in ((16, 24 * 16), (16, 23 * 16), (8, 700), (32, 100)):
        mean = np.mean([BG.scale_threshold(t, m, d) for d in row])
        assert abs(mean - t * m / 256) <= 0.5 / 256 + 1e-9
        assert BG.scale_threshold(t, m) == (t * m + 128) >> 8


def test_grid_count_is_the_initial_samples():
    for (w, h), p in (((64, 40), L2), ((100, 37), L3), ((33, 17), Params(tile=8, levels=1, thr=(9,))),
                      ((96, 70), Params(tile=32, levels=3, thr=(4, 8, 16)))):
        r = select(ImageRenderer(make_picture(w, h)), w, h, p)
        assert BG.grid_count(w, h, p) == r.stats["traced_initial"]


# --- budget 0 is today's select, bit for bit; the row-by-row run is too -----------------------

@pytest.mark.parametrize("rule", ["patent", "lindilate"])
@pytest.mark.parametrize("seed,size,params", [(0, (96, 64), L2), (1, (120, 75), L3),
                                              (2, (70, 53), Params(tile=8, levels=2, thr=(5, 30), fov_gain=40))])
def test_budget_zero_and_unit_scale_are_select(rule, seed, size, params):
    w, h = size
    img = _noise_picture(w, h, seed)
    ref = select(ImageRenderer(img), w, h, params, rule=rule)
    off = BG.select_budget(ImageRenderer(img), w, h, params, BG.BudgetConfig(0), rule=rule)
    one = BG.select_budget(ImageRenderer(img), w, h, params, BG.BudgetConfig(0), rule=rule, fixed_scale=256)
    for r in (off, one):
        assert np.array_equal(r.frame, ref.frame) and np.array_equal(r.source, ref.source)
        assert r.stats["traced"] == ref.stats["traced"]
    assert "budget" not in off.stats or off.stats["budget"] == 0


def test_rows_use_their_own_scale():
    """A budgeted frame equals, row for row, a fixed-scale frame at that row's scale."""
    w, h = 96, 64
    img = _noise_picture(w, h, 3)
    r = BG.select_budget(ImageRenderer(img), w, h, L3, BG.BudgetConfig(w * h // 5))
    scales = r.stats["budget_control"]["scale_per_row"]
    assert len(set(scales)) > 1
    for row, u in enumerate(scales):
        f = BG.select_budget(ImageRenderer(img), w, h, L3, BG.BudgetConfig(0), fixed_scale=u, fixed_dither=True)
        band = slice(row * 16, row * 16 + 16)
        assert np.array_equal(r.source[band], f.source[band]) and np.array_equal(r.frame[band], f.frame[band])


# --- monotonic, bounded ------------------------------------------------------------------------

def test_traced_rises_with_the_budget_and_falls_with_the_scale():
    w, h = 160, 96
    img = _noise_picture(w, h, 4)
    fixed = [BG.select_budget(ImageRenderer(img), w, h, L3, BG.BudgetConfig(0), fixed_scale=u).stats["traced"]
             for u in (BG.U_MIN, 128, 256, 512, BG.U_MAX)]
    assert fixed == sorted(fixed, reverse=True) and fixed[0] > fixed[-1]
    traced = [BG.select_budget(ImageRenderer(img), w, h, L3, BG.BudgetConfig(w * h * p // 100)).stats["traced"]
              for p in (6, 10, 20, 40)]
    assert traced == sorted(traced) and traced[0] < traced[-1]


def test_scales_stay_in_bounds_on_random_rows():
    rng = np.random.default_rng(5)
    for _ in range(200):
        w, h = int(rng.integers(16, 400)), int(rng.integers(16, 300))
        p = [L2, L3][int(rng.integers(0, 2))]
        g, total = BG.grid_count(w, h, p), w * h
        budget = int(rng.integers(g, total + 1))
        ctl = BG.Controller(w, h, p, BG.BudgetConfig(budget, int(rng.integers(0, BG.U_MAX + 1)),
                                                     int(rng.integers(0, 8))))
        for r in range(ctl.nty):
            hr = ctl.row_height(r)
            lo = BG.row_grid(w, hr, p)
            ctl.finish_row(int(rng.integers(lo, w * hr + 1)))
            assert all(BG.U_MIN_FIRST <= u <= BG.U_MAX for u in ctl.scales)
            assert all(b >= a >> 1 or b == BG.U_MIN for a, b in zip(ctl.scales[1:], ctl.scales[2:]))
            assert all(b >= BG.U_MIN or a <= BG.U_MIN for a, b in zip(ctl.scales[1:], ctl.scales[2:]))
        assert BG.U_MIN <= ctl.scale_out <= BG.U_MAX and len(ctl.scales) == ctl.nty


def test_a_first_frame_reaches_below_u_min_a_seeded_frame_does_not():
    # Rows that trace only their grid against a budget of most of the frame: the scale falls
    # by half a row to 45, and on a first frame one row later to 32; seeded frames and
    # SCALE_OUT stay at 45.
    w, h = 256, 160
    g = BG.grid_count(w, h, L2)
    cfg = BG.BudgetConfig(w * h * 9 // 10)
    first = BG.Controller(w, h, L2, cfg)
    for r in range(first.nty):
        first.finish_row(BG.row_grid(w, first.row_height(r), L2))
    assert first.scales[2:] == [128, 64, 45, 32, 32, 32, 32, 32] and first.scale_out == BG.U_MIN
    assert g < cfg.budget
    seeded = BG.Controller(w, h, L2, BG.BudgetConfig(cfg.budget, first.scale_out, profile=first.activity,
                                                     profile_scales=first.scale_of_rows()))
    assert BG.BudgetConfig(1, scale_init=BG.U_MIN_FIRST).seed == BG.U_MIN     # u0 is never below 45
    for r in range(seeded.nty):
        seeded.finish_row(BG.row_grid(w, seeded.row_height(r), L2))
    assert min(seeded.scales) == BG.U_MIN and seeded.scale_out == BG.U_MIN


def test_a_seeded_frame_falls_by_at_most_a_quarter_per_row():
    # Rows that trace only their grid against most of the frame: q is far below every scale, so
    # the fall limit sets each next scale. A first frame halves per row; a seeded frame
    # (the same budget, seed 256) takes u - (u >> 2) per row down to U_MIN.
    w, h = 256, 160
    cfg = BG.BudgetConfig(w * h * 9 // 10)
    first = BG.Controller(w, h, L2, cfg)
    for r in range(first.nty):
        first.finish_row(BG.row_grid(w, first.row_height(r), L2))
    seeded = BG.Controller(w, h, L2, BG.BudgetConfig(cfg.budget, 256, profile=first.activity,
                                                     profile_scales=first.scale_of_rows()))
    for r in range(seeded.nty):
        seeded.finish_row(BG.row_grid(w, seeded.row_height(r), L2))
    assert seeded.scales == [256, 256, 192, 144, 108, 81, 61, 46, 45, 45]
    assert first.scales[:5] == [256, 256, 128, 64, 45]


def test_spent_budget_raises_the_scale_twofold_per_row():
    # Nothing left above the grid (q = U_MAX + 1): the scale rises, but by at most 2x a row (v5).
    ctl = BG.Controller(64, 64, L2, BG.BudgetConfig(budget=BG.grid_count(64, 64, L2) + 10))
    ctl.finish_row(64 * 16)           # a whole row traced: nothing left above the grid
    ctl.finish_row(BG.row_grid(64, 16, L2))
    assert ctl.scales == [256, 256, 512, 1024]
    ctl = BG.Controller(64, 64, L2, BG.BudgetConfig(budget=BG.grid_count(64, 64, L2) + 10, scale_init=1000))
    ctl.finish_row(64 * 16)
    assert ctl.scales[2] == BG.U_MAX  # 2 u > U_MAX: the clamp


# --- refusals ----------------------------------------------------------------------------------

def test_budget_below_the_grid_is_refused():
    g = BG.grid_count(64, 40, L2)
    with pytest.raises(BG.BudgetRefused, match=str(BG.ERR_BUDGET)):
        BG.Controller(64, 40, L2, BG.BudgetConfig(g - 1))
    BG.Controller(64, 40, L2, BG.BudgetConfig(g))              # exactly the grid: accepted
    with pytest.raises(BG.BudgetRefused, match=str(BG.ERR_PROFILE)):
        BG.Controller(64, 40, L2, BG.BudgetConfig(g, 256, 6, (256, 512), (256, 256)))


def test_budget_config_ranges():
    for bad in ({"budget": -1}, {"budget": 1 << 24}, {"scale_init": BG.U_MAX + 1}, {"prior_shift": 8},
                {"profile": (256,)}, {"profile": (256,), "profile_scales": (256, 256)},
                {"profile": (256,), "profile_scales": (BG.U_MIN_FIRST - 1,)},
                {"profile": (257,), "profile_scales": (256,)},
                {"profile": (256 << 18,), "profile_scales": (256,)}):
        with pytest.raises(BG.spec.SpecError):
            BG.BudgetConfig(**bad)
    assert BG.BudgetConfig(1, scale_init=0).seed == 256 and BG.BudgetConfig(1, scale_init=1).seed == BG.U_MIN


# --- the command line ---------------------------------------------------------------------------

def _cli(*args):
    return subprocess.run([sys.executable, "-m", "msr_model", *map(str, args)], capture_output=True, text=True)


@pytest.fixture
def picture(tmp_path):
    p = tmp_path / "in.png"
    save_png(p, _noise_picture(96, 64, 6))
    return p


def test_cli_budget_percent_pixels_and_seed(tmp_path, picture):
    s1, s2, s0 = tmp_path / "s1.json", tmp_path / "s2.json", tmp_path / "s0.json"
    base = [picture, "--levels", "3", "--thr", "8,16,32"]
    assert _cli("select", *base, "--budget", "20%", "--out", tmp_path / "a.png", "--stats", s1).returncode == 0
    d1 = json.loads(s1.read_text())
    assert d1["budget"] == 96 * 64 * 20 // 100 and "traced" in d1
    ctl = d1["budget_control"]
    assert len(ctl["scale_per_row"]) == 4 and ctl["scale_out"] is not None
    r = _cli("select", *base, "--budget", str(d1["budget"]), "--budget-prev", s1, "--out", tmp_path / "b.png",
             "--stats", s2)
    assert r.returncode == 0, r.stderr
    d2 = json.loads(s2.read_text())
    assert d2["budget_control"]["seeded"] and d2["budget_control"]["scale_per_row"][0] == ctl["scale_out"]
    assert _cli("select", *base, "--out", tmp_path / "c.png", "--stats", s0).returncode == 0
    assert json.loads(s0.read_text())["budget"] == 0


@pytest.mark.parametrize("value,word", [("abc", "percentage"), ("-5", "outside"), ("101%", "0..100"),
                                        ("10", "initial grid"), ("99999", "more than"), ("x%", "percentage")])
def test_cli_bad_budget_exit_2(tmp_path, picture, value, word):
    out = tmp_path / "o.png"
    r = _cli("select", picture, "--levels", "3", "--thr", "8,16,32", "--budget", value, "--out", out)
    assert r.returncode == 2 and word in r.stderr and len(r.stderr.strip().splitlines()) == 1
    assert not out.exists()


def test_cli_bad_budget_prev(tmp_path, picture):
    bad = tmp_path / "bad.json"
    bad.write_text("{}")
    r = _cli("select", picture, "--budget", "30%", "--budget-prev", bad, "--out", tmp_path / "o.png")
    assert r.returncode == 2 and "budget-prev" in r.stderr


def test_budget_seed_from_the_budget_alone():
    p = Params(tile=16, levels=3, thr=(8, 16, 32))
    # c * sqrt(W * H / (B - G)) * (1920 * 1080 / (W * H)) ** (1/4) * sqrt(16 / thr_g), by hand:
    # 1080p at 10 %: B - G = 207 360 - 73 080 = 134 280, 33.4 * sqrt(15.443) = 131.25 -> 131
    assert [BG.budget_seed(1920, 1080, 1920 * 1080 * k // 100, p) for k in (5, 10, 20)] == [275, 131, 82]
    # a quarter of the pixels (960x540, G = 18 270): 33.4 * sqrt(518 400 / 33 570) * sqrt(2) = 185.6
    assert BG.budget_seed(960, 540, 960 * 540 // 10, p) == 186
    # thresholds twice as large: a scale sqrt(2) smaller (131.25 / 1.414 = 92.8)
    assert BG.budget_seed(1920, 1080, 1920 * 1080 // 10, Params(tile=16, levels=3, thr=(16, 32, 64))) == 93
    g = BG.grid_count(64, 64, p)
    assert BG.budget_seed(64, 64, g, p) == BG.U_MAX                   # nothing above the grid
    assert BG.budget_seed(64, 64, g + 1, p) == BG.U_MAX               # clamped
    assert BG.budget_seed(1920, 1080, 1 << 24, p) == BG.U_MIN         # the whole frame: 34, clamped
    cfg = BG.first_frame_config(1920, 1080, 207360, p)                  # the driver's first frame
    assert (cfg.budget, cfg.scale_init, cfg.prior_shift, cfg.profile) == (207360, 131, BG.AUTO_PRIOR_SHIFT, None)


def test_cli_first_frame_seed(tmp_path, picture):
    """select --budget without --scale-init writes the driver's seed (first_frame_config); an
    explicit --scale-init and --prior-shift are written as given."""
    base = [picture, "--levels", "3", "--thr", "8,16,32", "--budget", "20%"]
    want = BG.first_frame_config(96, 64, 96 * 64 // 5, Params(tile=16, levels=3, thr=(8, 16, 32)))
    runs = {"auto": [], "u": ["--scale-init", "300", "--prior-shift", "5"], "a5": ["--scale-init", "auto", "--prior-shift", "5"]}
    got = {}
    for k, extra in runs.items():
        s = tmp_path / f"{k}.json"
        r = _cli("select", *base, *extra, "--out", tmp_path / f"{k}.png", "--stats", s)
        assert r.returncode == 0, r.stderr
        bc = json.loads(s.read_text())["budget_control"]
        got[k] = (bc["scale_init"], bc["prior_shift"])
    assert got == {"auto": (want.scale_init, 3), "u": (300, 5), "a5": (want.scale_init, 5)}
    r = _cli("select", *base, "--scale-init", "autox", "--out", tmp_path / "x.png")
    assert r.returncode == 2 and "--scale-init" in r.stderr
