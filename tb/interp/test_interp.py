"""msr_interp against spec.interpolate.

1. A pure-Python proof that the reciprocal constants of rtl/engine/msr_interp.sv divide exactly:
   for every g in 2..8 and every numerator 0..2047 (the 11-bit range; the largest reachable
   numerator is 8*255+4 = 2044), (n * ceil(2^14/g)) >> 14 == n // g. The constants are read
   from the RTL source, not copied.
2. The RTL, exhaustively for every reachable (g, o = floor(g/2)) pair and every (A, B) channel
   pair 0..255 x 0..255 (three channel pairs per vector), plus every other (g, o) with
   1 <= o < g on the channel extremes and random values; random valid/ready."""
from __future__ import annotations

from pathlib import Path

import cocotb
import numpy as np

from msr_flow.filelist import ROOT
from msr_flow.runner import run_cocotb
from msr_tb import rtl_reciprocals, pack_rgb, seeded_rng, start_clock_and_reset, stream, unpack_rgb

from msr_model import spec

SRC = ROOT / "rtl" / "engine" / "msr_interp.sv"


def test_reciprocals_exact():
    shift, table = rtl_reciprocals(SRC, 16)
    assert sorted(table) == list(range(2, 9)), table
    n = np.arange(2048, dtype=np.int64)
    for g, r in table.items():
        assert np.array_equal((n * r) >> shift, n // g), f"g={g}: reciprocal {r} not exact"
    # and the numerator bound the RTL sizes for (11 bits) really covers the reachable range
    assert max(g * 255 + g // 2 for g in range(2, 9)) < 2048


def all_vectors(rng):
    vec = []
    chans = [(a, b) for a in range(256) for b in range(256)]
    for g in range(2, 9):           # reachable pairs: o = floor(g/2), exhaustive in (A, B)
        o = g // 2
        pairs = chans[:]
        rng.shuffle(pairs)
        pairs += pairs[:(-len(pairs)) % 3]
        for i in range(0, len(pairs), 3):
            p = pairs[i:i + 3]
            vec.append(([x[0] for x in p], [x[1] for x in p], g, o))
    for g in range(2, 9):           # every other offset: extremes and random
        for o in range(1, g):
            for ia in range(8):
                for ib in range(8):
                    vec.append(([255 * ((ia >> c) & 1) for c in range(3)],
                                [255 * ((ib >> c) & 1) for c in range(3)], g, o))
            for _ in range(200):
                vec.append(([rng.randrange(256) for _ in range(3)],
                            [rng.randrange(256) for _ in range(3)], g, o))
    return vec


@cocotb.test()
async def interp_vs_golden(dut):
    rng = seeded_rng(dut, 99)
    await start_clock_and_reset(dut, {"clear_i": 0, "valid_i": 0, "ready_i": 0, "a_i": 0, "b_i": 0,
                                      "gap_i": 2, "off_i": 1, "user_i": 0, "metric_i": 0,
                                      "thr_i": 0, "nshift_i": 0})
    vec = all_vectors(rng)
    a_all = np.array([v[0] for v in vec]); b_all = np.array([v[1] for v in vec])
    g_all = np.array([v[2] for v in vec]); o_all = np.array([v[3] for v in vec])
    want = spec.interpolate(a_all, b_all, np.zeros_like(g_all), g_all, o_all)

    def drive(i):
        a, b, g, o = vec[i]
        dut.a_i.value = pack_rgb(a)
        dut.b_i.value = pack_rgb(b)
        dut.gap_i.value = g
        dut.off_i.value = o
        dut.user_i.value = i & 0xFFFF

    def check(i):
        res = unpack_rgb(dut.rgb_o.value)
        exp = tuple(int(c) for c in want[i])
        assert int(dut.user_o.value) == i & 0xFFFF, "results out of order"
        assert res == exp, f"vector {i} {vec[i]}: got {res}, want {exp}"

    await stream(dut, rng, len(vec), drive, check, p_valid=0.97, p_ready=0.95)
    dut._log.info("%d interpolations (x3 channels) checked", len(vec))


def test_interp():
    run_cocotb("msr_decision_pipe", "test_interp", Path(__file__).parent, {"USER_W": 16})
