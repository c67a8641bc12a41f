"""msr_depth_interp against msr_model.reuse.lerp_invz (the spec's interpolation on the 16-bit
inverse-depth channel, the nearer surface where exactly one neighbour is sky).

1. A pure-Python proof that the reciprocal constants of rtl/reuse/msr_depth_interp.sv divide
   exactly: for every g in 2..8 and every numerator below 2^19 (the largest reachable one is
   8 * 65535 + 4), (n * RECIP[g]) >> SHIFT == n // g. The constants are read from the RTL.
2. The RTL for every (g, o), 2 <= g <= 8, 0 <= o < g: the extremes (0, 1, 65534, 65535 on
   either side: sky against surface, both sky, both far and near) and random depths, driven
   with random valid and a random consumer that stalls the pipeline (advance_i low)."""
from __future__ import annotations

from pathlib import Path

import cocotb
import numpy as np

from msr_flow.filelist import ROOT
from msr_flow.runner import run_cocotb
from msr_tb import rtl_reciprocals, next_cycle, seeded_rng, settle, start_clock_and_reset

from msr_model.reuse import lerp_invz

SRC = ROOT / "rtl" / "reuse" / "msr_depth_interp.sv"


def test_reciprocals_exact():
    shift, table = rtl_reciprocals(SRC, 24)
    assert sorted(table) == list(range(2, 9)), table
    n = np.arange(1 << 19, dtype=np.int64)
    for g, r in table.items():
        assert np.array_equal((n * r) >> shift, n // g), f"g={g}: reciprocal {r} not exact"
    assert 8 * 65535 + 4 < 1 << 19      # the numerator's 19 bits cover every reachable value


def vectors(rng):
    ends = (0, 1, 2, 65534, 65535)
    vec = []
    for g in range(2, 9):
        for o in range(g):
            vec += [(wa, wb, g, o) for wa in ends for wb in ends]
            vec += [(rng.randrange(65536), rng.randrange(65536), g, o) for _ in range(120)]
            vec += [(rng.choice((0, rng.randrange(1, 65536))), rng.choice((0, rng.randrange(1, 65536))), g, o)
                    for _ in range(30)]
    rng.shuffle(vec)
    return vec


@cocotb.test()
async def depth_interp_vs_golden(dut):
    rng = seeded_rng(dut, 7)
    await start_clock_and_reset(dut, {"clear_i": 0, "advance_i": 0, "valid_i": 0, "wa_i": 0, "wb_i": 0,
                                      "gap_i": 2, "off_i": 1})
    vec = vectors(rng)
    v = np.array(vec, dtype=np.int64)
    want = lerp_invz(v[:, 0], v[:, 1], 0, v[:, 2], v[:, 3])
    sent = got = stalls = 0
    await next_cycle()
    while got < len(vec):
        ready = rng.random() < 0.8
        advance = (not int(dut.valid_o.value)) or ready
        stalls += not advance
        dut.advance_i.value = int(advance)
        offer = sent < len(vec) and rng.random() < 0.9
        dut.valid_i.value = int(offer)
        if offer:
            wa, wb, g, o = vec[sent]
            dut.wa_i.value, dut.wb_i.value, dut.gap_i.value, dut.off_i.value = wa, wb, g, o
        await settle()
        if int(dut.valid_o.value) and advance:
            res = int(dut.invz_o.value)
            assert res == int(want[got]), f"vector {got} {vec[got]}: got {res}, want {int(want[got])}"
            got += 1
        if offer and advance:
            sent += 1
        await next_cycle()
    dut._log.info("%d interpolations checked, %d stalled cycles", len(vec), stalls)


def test_depth_interp():
    run_cocotb("msr_depth_interp", "test_depth_interp", Path(__file__).parent)
