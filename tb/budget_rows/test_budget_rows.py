"""budget_rows: per tile row, the traced pixels at the writer's inputs, handed to the budget
controller in dispatch order (docs/budget.md sections 2 and 3: rows interleaved,
msr_model.budget.row_order) once each of the row's tiles has sent its last pixel, flagged when it
is the frame's bottom row. The bench plays the tile generator's rule (a row starts only when the
row two before it in that order was handed on), spreads the tiles over the inputs, interleaves
their pixels at random and checks every row's count against its own tally."""
from __future__ import annotations

from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent

import cocotb  # noqa: E402
from cocotb.triggers import ClockCycles, ReadOnly, RisingEdge  # noqa: E402
from msr_tb import clear_pulse, seeded_rng, start_clock_and_reset  # noqa: E402

TILE_LOG2 = {8: 3, 16: 4, 32: 5}


def tiles_of(W, H, T):
    """(position, pixels) of every tile in dispatch order."""
    from msr_model.budget import row_order
    for k, ty in enumerate(row_order((H + T - 1) // T)):
        for tx in range((W + T - 1) // T):
            yield k, [(x, y) for y in range(ty * T, min(H, ty * T + T)) for x in range(tx * T, min(W, tx * T + T))]


async def start_frame(dut, W, H, T):
    """A start pulse, then the tile generator's grid and order registers as it sets them: the
    counts the clock after the start, the stride S the clock after that (until then S = 1)."""
    from msr_model.budget import row_stride_log2
    ntx, nty = (W + T - 1) // T, (H + T - 1) // T
    s = 1 << row_stride_log2(nty)
    dut.tile_log2_i.value = TILE_LOG2[T]
    dut.start_i.value = 1
    await RisingEdge(dut.clk_i)
    dut.start_i.value = 0
    dut.ntx_i.value, dut.nty_i.value, dut.smask_i.value, dut.nty_s_i.value = ntx, nty, 0, nty - 1
    await RisingEdge(dut.clk_i)
    dut.smask_i.value, dut.nty_s_i.value = s - 1, nty - s
    await RisingEdge(dut.clk_i)                  # (the unit sets its open rows; a_rows_set)


async def run_frame(dut, rng, W, H, T, p_traced, p_ready):
    n_in = int(dut.NUM_IN.value)
    nty = (H + T - 1) // T
    from msr_model.budget import row_order
    order = row_order(nty)
    await start_frame(dut, W, H, T)
    todo = list(tiles_of(W, H, T))
    streams = [[] for _ in range(n_in)]          # per input: (y, traced, last) still to send
    want = [0] * nty
    handed = []
    for _ in range(200000):
        # hand the next tiles to idle inputs, rows no further than two below the oldest open one
        for i in range(n_in):
            if not streams[i] and todo and todo[0][0] < len(handed) + 3 and rng.random() < 0.5:
                ty, pix = todo.pop(0)
                rng.shuffle(pix)
                for k, (x, y) in enumerate(pix):
                    tr = rng.random() < p_traced
                    want[ty] += tr
                    streams[i].append((y, tr, k == len(pix) - 1))
        fire = [bool(s) and rng.random() < 0.7 for s in streams]
        dut.pix_fire_i.value = sum(1 << i for i in range(n_in) if fire[i])
        dut.pix_y_i.value = sum(streams[i][0][0] << (12 * i) for i in range(n_in) if fire[i])
        dut.pix_traced_i.value = sum(int(streams[i][0][1]) << i for i in range(n_in) if fire[i])
        dut.pix_last_i.value = sum(int(streams[i][0][2]) << i for i in range(n_in) if fire[i])
        dut.row_ready_i.value = int(rng.random() < p_ready)
        await ReadOnly()
        if int(dut.row_valid_o.value) and int(dut.row_ready_i.value):
            r = int(dut.row_idx_o.value)
            assert r == len(handed), f"position {r} handed on, expected {len(handed)}"
            assert int(dut.row_bottom_o.value) == (order[r] == nty - 1), f"position {r}: bottom flag"
            handed.append(int(dut.row_traced_o.value))
        busy = int(dut.busy_o.value)
        await RisingEdge(dut.clk_i)
        for i in range(n_in):
            if fire[i]:
                streams[i].pop(0)
        if not busy and not todo and not any(streams):
            break
    else:
        raise AssertionError("rows never all handed on")
    dut.pix_fire_i.value = 0
    assert handed == want, f"{W}x{H} T{T}: rows {handed}, want {want}"


@cocotb.test()
async def test_rows(dut):
    rng = seeded_rng(dut, 4242)
    await start_clock_and_reset(dut, {"clear_i": 0, "start_i": 0, "pix_fire_i": 0, "row_ready_i": 0})
    await RisingEdge(dut.clk_i)
    # 13 rows (S = 2), 38 (S = 8), 65 (S = 16: four phases of five rows, the rest of four)
    cases = [(1, 1, 8, 1.0, 1.0), (70, 50, 16, 0.3, 0.5), (33, 100, 8, 0.0, 0.2),
             (64, 64, 32, 1.0, 0.9), (130, 9, 16, 0.5, 0.05), (20, 300, 8, 0.4, 0.6), (9, 520, 8, 0.6, 0.3)]
    for _ in range(3):
        cases.append((rng.randint(1, 90), rng.randint(1, 90), rng.choice((8, 16, 32)), rng.random(), rng.random() * 0.9 + 0.1))
    for c in cases:
        await run_frame(dut, rng, *c)
    # a clear mid-frame forgets it: the next frame counts from zero
    await start_frame(dut, 40, 40, 8)
    dut.pix_fire_i.value = 1
    dut.pix_y_i.value = 0
    dut.pix_traced_i.value = 1
    dut.pix_last_i.value = 0
    await ClockCycles(dut.clk_i, 5)
    dut.pix_fire_i.value = 0
    await clear_pulse(dut)
    assert int(dut.busy_o.value) == 0 and int(dut.row_valid_o.value) == 0
    await RisingEdge(dut.clk_i)
    await run_frame(dut, rng, 40, 40, 8, 0.5, 0.5)


@pytest.mark.parametrize("n_in", [1, 4])
def test_budget_rows(n_in):
    from msr_flow.filelist import RTL
    from msr_flow.runner import run_cocotb
    run_cocotb("msr_budget_rows", "test_budget_rows", HERE, {"NUM_IN": n_in}, f"n{n_in}",
               sources=[RTL / "pkg/msr_pkg.sv", RTL / "budget/msr_budget_pkg.sv",
                        RTL / "budget/msr_budget_rows.sv"])
