"""tile_gen: every tile of random frames, in row-major order, with the golden model's extent
and foveated thresholds (spec section 1, around the frame centre or a gaze point) and the
frame's decision rule, dispatched only to ready engines."""
from __future__ import annotations

from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent

import cocotb  # noqa: E402
from cocotb.triggers import ClockCycles, FallingEdge, RisingEdge, ReadOnly  # noqa: E402
from msr_funcov import partial, record  # noqa: E402
from msr_tb import clear_pulse, seeded_rng, start_clock_and_reset  # noqa: E402

TILE_ENC = {8: 0, 16: 1, 32: 2}


def unpack_desc(v: int) -> dict:
    """tile_desc_t (rtl/pkg/msr_pkg.sv), packed MSB first: rule x0 y0 w h levels metric thr[2] thr[1]
    thr[0] (64 bits)."""
    assert v >> 64 == 0, f"descriptor wider than 64 bits: {v:#x}"
    return {"thr": tuple((v >> (8 * k)) & 0xFF for k in range(3)), "metric": (v >> 24) & 1,
            "levels": (v >> 25) & 3, "h": (v >> 27) & 0x3F, "w": (v >> 33) & 0x3F,
            "y0": (v >> 39) & 0xFFF, "x0": (v >> 51) & 0xFFF, "rule": (v >> 63) & 1}


def expected_tiles(W, H, T, L, metric, thr, gain, rule, gaze=None):
    """The golden model's descriptors; gaze: (X, Y) in pixels, or None (the default gaze)."""
    from msr_model import spec
    from msr_model.tile_model import frame_tiles

    ntx, nty = spec.tile_counts(W, H, T)
    cx, cy = spec.gaze_centre(spec.Params(tile=T, levels=L, thr=tuple(thr[:L]), gaze=gaze), ntx, nty)
    out = []
    for tx, ty, x0, y0, w, h in frame_tiles(W, H, T):
        out.append({"x0": x0, "y0": y0, "w": w, "h": h, "levels": L, "metric": metric, "rule": rule,
                    "thr": tuple(spec.foveated_threshold(t, tx, ty, cx, cy, gain) for t in thr)})
    return out


def drive_gaze(dut, T, gaze):
    """gaze_en_i and (cx, cy) as the controller forms them: (2X + T/2) div T, (2Y + T/2) div T."""
    dut.gaze_en_i.value = int(gaze is not None)
    x, y = gaze if gaze is not None else (0, 0)
    dut.gaze_cx_i.value = (2 * x + T // 2) // T
    dut.gaze_cy_i.value = (2 * y + T // 2) // T


async def run_frame(dut, n_eng, rng, W, H, T, L, metric, thr, gain, ready_prob, rule, gaze=None):
    dut.width_i.value = W
    dut.height_i.value = H
    dut.tile_i.value = TILE_ENC[T]
    dut.levels_i.value = L
    dut.metric_i.value = metric
    dut.thr_i.value = thr[0] | (thr[1] << 8) | (thr[2] << 16)
    dut.fov_gain_i.value = gain
    dut.rule_i.value = rule   # 0 patent, 1 lindilate (rule_e)
    drive_gaze(dut, T, gaze)
    dut.start_i.value = 1
    await RisingEdge(dut.clk_i)
    dut.start_i.value = 0
    got, engines = [], []
    for _ in range(200000):
        dut.desc_ready_i.value = sum(1 << i for i in range(n_eng) if rng.random() < ready_prob)
        await ReadOnly()
        valid, ready = int(dut.desc_valid_o.value), int(dut.desc_ready_i.value)
        assert valid & ~ready == 0, "offered to an engine that is not ready"
        assert valid & (valid - 1) == 0, "offered to more than one engine"
        if valid:
            got.append(unpack_desc(int(dut.desc_o.value)))
            engines.append(valid.bit_length() - 1)
            assert valid == (ready & -ready), "not the lowest-numbered ready engine"
        if int(dut.done_o.value):
            break
        await RisingEdge(dut.clk_i)
    else:
        raise AssertionError("frame never done")
    want = expected_tiles(W, H, T, L, metric, thr, gain, rule, gaze)
    assert len(got) == len(want), f"{len(got)} tiles, want {len(want)}"
    for i, (g, w) in enumerate(zip(got, want)):
        assert g == w, f"tile {i} ({W}x{H} T{T} gain {gain} rule {rule} gaze {gaze}): got {g}, want {w}"
    record("msr_tile_gen", engines=n_eng, tile=T, fov="on" if gain else "off", partial=partial(W, H, T))
    await RisingEdge(dut.clk_i)
    dut.desc_ready_i.value = 0


@cocotb.test()
async def test_frames(dut):
    n_eng = int(dut.NUM_ENGINES.value)
    rng = seeded_rng(dut, 1234 + n_eng)
    # Reset (and every input) before the first clock edge: with a random initial state
    # (MSR_RAND_RESET=1, +verilator+rand+reset+2) an edge before it would see random state.
    await reset(dut)
    # The last field is the rule: the descriptors carry it (their MSB), patent then lindilate
    # back to back so a stale rule would show.
    cases = [(1, 1, 8, 1, 0, (0, 0, 0), 0, 1.0, 1),            # a single pixel
             (4096, 9, 8, 3, 1, (250, 3, 100), 255, 0.7, 0),   # 512 x 2 tiles: widest r2, saturation
             (33, 4096, 32, 2, 0, (8, 16, 32), 200, 0.5, 1),   # tall, last tile 1 pixel wide
             (100, 60, 16, 2, 0, (8, 16, 32), 17, 0.3, 0)]
    for _ in range(6):
        cases.append((rng.randint(1, 200), rng.randint(1, 120), rng.choice((8, 16, 32)), rng.randint(1, 3),
                      rng.randint(0, 1), tuple(rng.randint(0, 255) for _ in range(3)), rng.randint(0, 255),
                      rng.choice((0.2, 0.6, 1.0)), rng.randint(0, 1)))
    for c in cases:
        await run_frame(dut, n_eng, rng, *c)
    # A clear in the middle of a frame forgets it; the next frame is complete.
    dut.width_i.value = 64
    dut.height_i.value = 64
    dut.tile_i.value = 0
    dut.start_i.value = 1
    await RisingEdge(dut.clk_i)
    dut.start_i.value = 0
    dut.desc_ready_i.value = 1
    await ClockCycles(dut.clk_i, 9)
    await clear_pulse(dut)
    assert int(dut.busy_o.value) == 0 and int(dut.done_o.value) == 0
    await RisingEdge(dut.clk_i)
    await run_frame(dut, n_eng, rng, 40, 24, 8, 2, 0, (8, 16, 32), 40, 0.5, 1)


async def reset(dut):
    await start_clock_and_reset(dut, {"clear_i": 0, "start_i": 0, "desc_ready_i": 0, "bud_en_i": 0,
                                      "row_ok_i": 0, "row_m_i": 256, "gaze_en_i": 0, "gaze_cx_i": 0,
                                      "gaze_cy_i": 0})
    await RisingEdge(dut.clk_i)


@cocotb.test()
async def test_gaze(dut):
    """Random gaze points (corners, edges, inside) against the golden model's thresholds; the
    default gaze given explicitly equals gaze_en_i low; frames with and without a gaze back to
    back, so a stale gaze would show."""
    n_eng = int(dut.NUM_ENGINES.value)
    rng = seeded_rng(dut, 4321 + n_eng)
    await reset(dut)
    from msr_model import spec
    cases = [(4096, 17, 8, 2, (4095, 0), 255), (64, 4096, 32, 1, (63, 4095), 200),
             (4096, 40, 8, 3, (0, 39), 255), (1, 1, 16, 1, (0, 0), 255)]
    for _ in range(14):
        W, H, T = rng.randint(1, 300), rng.randint(1, 200), rng.choice((8, 16, 32))
        g = rng.choice(((0, 0), (W - 1, H - 1), (W - 1, 0), (rng.randrange(W), rng.randrange(H)),
                        (rng.randrange(W), rng.randrange(H))))
        cases.append((W, H, T, rng.randint(1, 3), g, rng.choice((16, 50, 255, rng.randint(1, 255)))))
    for W, H, T, L, gaze, gain in cases:
        thr = tuple(rng.randint(0, 255) for _ in range(3))
        await run_frame(dut, n_eng, rng, W, H, T, L, rng.randint(0, 1), thr, gain, rng.choice((0.3, 1.0)),
                        rng.randint(0, 1), gaze)
        gx, gy = spec.default_gaze(W, H, T)
        if gx < W and gy < H:       # the default gaze written out equals the default
            await run_frame(dut, n_eng, rng, W, H, T, L, 0, thr, gain, 1.0, 0, (gx, gy))
        await run_frame(dut, n_eng, rng, W, H, T, L, 0, thr, gain, 1.0, 0, None)


@cocotb.test()
async def test_budget_rows(dut):
    """BUDGET_EN: a budget frame's walker takes the tile rows in the interleaved order of
    docs/budget.md section 2 (msr_model.budget.row_order), starts a row only once its scale is
    known (row_ok_i for row_idx_o, the row's position in that order), and every tile's
    thresholds are its row's, scaled and dithered as section 1 (scale_threshold with
    thr_dither) on top of the foveation."""
    if not int(dut.BUDGET_EN.value):
        return                                  # a top without the stage: test_frames covers it
    from msr_model.budget import row_order, scale_threshold, thr_dither
    n_eng = int(dut.NUM_ENGINES.value)
    rng = seeded_rng(dut, 777 + n_eng)
    await reset(dut)
    # 5 rows (row-major), 12 rows (S = 2), 2 rows, 38 rows (S = 8, the last phase shorter)
    for W, H, T, L, gain, gap in ((100, 70, 16, 3, 40, 150), (37, 90, 8, 2, 0, 60), (300, 64, 32, 3, 255, 0),
                                  (70, 300, 8, 3, 90, 40)):
        thr = tuple(rng.randint(0, 255) for _ in range(3))
        nty = (H + T - 1) // T
        m = [rng.choice((8, 255, 256, 257, 8190, rng.randint(8, 8190))) for _ in range(nty)]   # by position
        order = row_order(nty)
        pos_of = {r: k for k, r in enumerate(order)}
        released = [2]
        now = [0]

        async def controller():
            # the controller's answer for the row the walker is in, settled before the next edge
            while True:
                await FallingEdge(dut.clk_i)
                now[0] += 1
                if gap and now[0] % gap == 0:
                    released[0] += 1
                elif not gap:
                    released[0] = nty
                idx = int(dut.row_idx_o.value)
                dut.row_ok_i.value = int(idx < released[0])
                dut.row_m_i.value = m[idx] if idx < nty else 256
        task = cocotb.start_soon(controller())
        dut.width_i.value, dut.height_i.value, dut.tile_i.value = W, H, TILE_ENC[T]
        dut.levels_i.value, dut.metric_i.value, dut.rule_i.value = L, 0, 0
        dut.thr_i.value = thr[0] | (thr[1] << 8) | (thr[2] << 16)
        dut.fov_gain_i.value = gain
        dut.bud_en_i.value = 1
        dut.start_i.value = 1
        await RisingEdge(dut.clk_i)
        dut.start_i.value = 0
        got = []
        for _ in range(100000):
            dut.desc_ready_i.value = (1 << n_eng) - 1 if rng.random() < 0.5 else 0
            await ReadOnly()
            if int(dut.desc_valid_o.value):
                d = unpack_desc(int(dut.desc_o.value))
                assert pos_of[d["y0"] // T] < released[0], f"row {d['y0'] // T} handed out before its scale"
                got.append(d)
            if int(dut.done_o.value):
                break
            await RisingEdge(dut.clk_i)
        else:
            raise AssertionError("budget frame never done")
        task.cancel()
        want = sorted(expected_tiles(W, H, T, L, 0, thr, gain, 0), key=lambda w: (pos_of[w["y0"] // T], w["x0"]))
        for w in want:
            k, tx, ty = pos_of[w["y0"] // T], w["x0"] // T, w["y0"] // T
            w["thr"] = tuple(scale_threshold(t, m[k], thr_dither(tx, ty)) for t in w["thr"])
        assert len(got) == len(want)
        for i, (g, w) in enumerate(zip(got, want)):
            assert g == w, f"tile {i} ({W}x{H} T{T}): got {g}, want {w}"
        if gap:
            assert now[0] >= gap * (nty - 2), "the walker did not wait for the rows' scales"
        await RisingEdge(dut.clk_i)
        dut.desc_ready_i.value = 0
        dut.bud_en_i.value = 0


@pytest.mark.parametrize("engines,budget", [(1, 0), (3, 0), (4, 0), (4, 1)])
def test_tile_gen(engines, budget):
    from msr_flow.filelist import RTL
    from msr_flow.runner import run_cocotb
    # the generator as the top uses it: with the budget's stage when BUDGET_EN (msr_tile_gen_tb.sv)
    run_cocotb("msr_tile_gen_tb", "test_tile_gen", HERE, {"NUM_ENGINES": engines, "BUDGET_EN": budget},
               f"e{engines}" + ("_budget" if budget else ""),
               sources=[RTL / "pkg/msr_pkg.sv", RTL / "prim/msr_clr_reg.sv",
                        RTL / "budget/msr_budget_pkg.sv", RTL / "tilegen/msr_tile_gen.sv",
                        RTL / "budget/msr_budget_stage.sv", HERE / "msr_tile_gen_tb.sv"])
