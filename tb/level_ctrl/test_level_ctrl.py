"""msr_level_ctrl against tile_model.tile_schedule: the whole stream of positions (pass by
pass, with neighbours, gap, offset, level, direction, n_k and the pass-start flag) for every
L in 1..3 and every tile w, h in 1..32, with random ready back-pressure. Also the third read
port's address for the `lindilate` rule (docs/rules.md): B' = b + g, or A' = a - g where B'
is outside the tile; and the property that makes one port enough, derived here from
spec.axis_plan: wherever A' exists (inside the tile, in G(k-1)) and is not the A of the line's
previous position (what the context keeps), B' is outside the tile."""
from __future__ import annotations

import random
from pathlib import Path

import cocotb

from msr_flow.filelist import rtl_sources
from msr_flow.runner import run_cocotb
from msr_tb import next_cycle, settle, start_clock_and_reset

from msr_model import spec
from msr_model.tile_model import tile_schedule

DIRS = {"init": 0, "H": 1, "V": 2}


def outer(s, w, h, levels, prev):
    """(o2a, o2x, o2y) of one H/V step: prev is the step before it on its line (None at a
    line start). Checks that one read serves: A' that is not prev's A only where B' is out."""
    horiz = s.direction == "H"
    n = w if horiz else h
    grid = set(spec.axis_plan(n, levels).grids[s.level - 1])       # G(k-1) of the position axis
    a, b = (s.ax, s.bx) if horiz else (s.ay, s.by)
    pa, pb = a - s.gap, b + s.gap
    oka = pa >= 0 and pa in grid
    prev_a = None if prev is None else (prev.ax if horiz else prev.ay)
    o2a = pb > n - 1
    assert not (oka and prev_a != pa and not o2a), \
        f"{w}x{h} L={levels}: A' at {pa} is not the previous A and B' at {pb} is inside"
    o2 = (pa if o2a else pb) % 32
    line = s.y if horiz else s.x
    o2x, o2y = (o2, line) if horiz else (line, o2)
    return o2a, o2x, o2y


def expected(w, h, levels):
    out = []
    for p in tile_schedule(w, h, levels):
        prev, line_of_prev = None, None
        for i, s in enumerate(p.steps):
            if s.direction == "init":
                row = (s.x, s.y, None, None, None, None, 0, 0, 0, 0, i == 0)
                extra = None
            else:
                nshift = s.nominal.bit_length() - 1
                row = (s.x, s.y, s.ax, s.ay, s.bx, s.by, s.gap, s.m_offset, s.level, DIRS[s.direction],
                       i == 0)
                line = s.y if s.direction == "H" else s.x
                if line != line_of_prev:
                    prev = None
                o2a, o2x, o2y = outer(s, w, h, levels, prev)
                # the address is only used where the sample is inside the tile
                inside = 0 <= (o2y if s.direction == "V" else o2x) < (h if s.direction == "V" else w)
                extra = (o2a, (o2x, o2y) if inside else None)
                prev, line_of_prev = s, line
            out.append((row, None if s.direction == "init" else nshift, extra))
    return out


@cocotb.test()
async def schedule_matches_golden(dut):
    rng = random.Random(7)
    await start_clock_and_reset(dut, {"clear_i": 0, "start_valid_i": 0, "w_i": 1, "h_i": 1,
                                      "levels_i": 1, "step_ready_i": 0})
    tiles = [(w, h, lv) for lv in (1, 2, 3) for w in range(1, 33) for h in range(1, 33)]
    rng.shuffle(tiles)
    total = 0
    for n, (w, h, lv) in enumerate(tiles):
        want = expected(w, h, lv)
        stall = n % 8 == 0                      # every 8th tile with random back-pressure
        dut.start_valid_i.value = 1
        dut.w_i.value, dut.h_i.value, dut.levels_i.value = w, h, lv
        dut.step_ready_i.value = 1
        await settle()
        assert dut.start_ready_o.value == 1, "controller not idle at tile start"
        await next_cycle()
        dut.start_valid_i.value = 0
        got = 0
        cycles = 0
        while got < len(want):
            ready = int(rng.random() < 0.7) if stall else 1
            dut.step_ready_i.value = ready
            await settle()
            if dut.step_valid_o.value and ready:
                d = dut.step_dir_o.value.to_unsigned()
                row = (int(dut.step_x_o.value), int(dut.step_y_o.value))
                if d == 0:
                    row += (None, None, None, None, 0, 0, int(dut.step_level_o.value), 0)
                else:
                    row += (int(dut.step_ax_o.value), int(dut.step_ay_o.value),
                            int(dut.step_bx_o.value), int(dut.step_by_o.value),
                            int(dut.step_gap_o.value), int(dut.step_off_o.value),
                            int(dut.step_level_o.value), d)
                row += (bool(dut.step_first_o.value),)
                nshift = None if d == 0 else int(dut.step_nshift_o.value)
                extra = None
                if d != 0:
                    o2 = int(dut.step_o2_o.value)          # on the line: x (H pass) or y (V)
                    o2x, o2y = (row[0], o2) if d == 2 else (o2, row[1])
                    extra = (bool(dut.step_o2a_o.value), (o2x, o2y) if o2 < (h if d == 2 else w) else None)
                res = (row, nshift, extra)
                assert res == want[got], f"tile {w}x{h} L={lv} step {got}: got {res}, want {want[got]}"
                got += 1
            cycles += 1
            assert cycles < 2 * w * h + 32, f"tile {w}x{h} L={lv}: stuck after {got} steps"
            await next_cycle()
        dut.step_ready_i.value = 1
        await settle()
        idle_wait = 0
        while dut.busy_o.value:               # trailing empty passes / holes
            assert not dut.step_valid_o.value, f"tile {w}x{h} L={lv}: extra step"
            idle_wait += 1
            assert idle_wait < 40, f"tile {w}x{h} L={lv}: controller does not finish"
            await next_cycle()
            await settle()
        await next_cycle()
        total += got
    dut._log.info("%d tiles, %d positions checked", len(tiles), total)


def test_level_ctrl():
    here = Path(__file__).parent
    run_cocotb("msr_level_ctrl_tb", "test_level_ctrl", here,
               sources=[*rtl_sources(), here / "msr_level_ctrl_tb.sv"])
