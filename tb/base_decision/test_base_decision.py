"""msr_base_decision (the base decision D = P or Q of the `lindilate` rule, docs/rules.md)
against the golden model: P from spec.color_diff / spec.interpolate_ok, Q from
rules.second_difference_test. Vectors: every gap 2..8 and nominal gap 1..8 with the second
difference just below, at and above the threshold boundary (each outer sample alone and
both), ramps with small noise (the case the rule is for), extreme colours (channels 0/255,
second differences of +-510) and random colours, with random outer-sample flags; the stage
enable toggles at random (the engine's global stall)."""
from __future__ import annotations

from collections import deque
from pathlib import Path

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, ReadOnly, RisingEdge, Timer

from msr_flow.runner import run_cocotb
from msr_tb import pack_rgb, seeded_rng

from msr_model import rules, spec

STAGES = 4   # S1..S4: base_o holds the inputs taken four enabled clocks before


def clamp(v):
    return max(0, min(255, v))


def outer_with_second_diff(rng, near, far, e, metric):
    """An outer sample whose second difference d(outer - 2 near + far) is exactly e, or None."""
    for _ in range(20):
        if metric == "max":
            parts = [rng.randrange(e + 1) for _ in range(3)]
            parts[rng.randrange(3)] = e
        else:
            cuts = sorted(rng.randrange(e + 1) for _ in range(2))
            parts = [cuts[0], cuts[1] - cuts[0], e - cuts[1]]
        out = []
        for c in range(3):
            base = 2 * near[c] - far[c]
            sign = rng.choice((-1, 1))
            v = base + sign * parts[c]
            if not 0 <= v <= 255:
                v = base - sign * parts[c]
            out.append(v)
        if all(0 <= v <= 255 for v in out):
            assert spec.color_diff([o - 2 * n + f for o, n, f in zip(out, near, far)], 0, metric) == e
            return out
    return None


def vectors(rng):
    """(outer_a, ok_a, a, b, outer_b, ok_b, metric, thr, gap, nshift)."""
    vec = []
    rnd = lambda: [rng.randrange(256) for _ in range(3)]  # noqa: E731
    for metric in spec.METRICS:
        for gap in range(2, 9):
            for nshift in range(4):
                nominal = 1 << nshift
                for thr in range(0, 256, 3):
                    edge = (thr * gap + nominal - 1) // nominal    # smallest c2 that fails
                    for e in {edge - 1, edge, edge + 1}:
                        if e < 0:
                            continue
                        a, b = rnd(), rnd()
                        for ok_a, ok_b in ((1, 0), (0, 1), (1, 1)):
                            oa = outer_with_second_diff(rng, a, b, e, metric) if ok_a else rnd()
                            ob = outer_with_second_diff(rng, b, a, e, metric) if ok_b else rnd()
                            if oa is None or ob is None:
                                continue
                            if ok_a and ok_b and rng.random() < 0.5:   # the other one far below
                                ob = [clamp(2 * b[c] - a[c]) for c in range(3)]
                            vec.append((oa, ok_a, a, b, ob, ok_b, metric, thr, gap, nshift))
        for _ in range(3000):   # ramps with noise: A', A, B, B' nearly on a line
            a = rnd()
            step = [rng.randrange(-40, 41) for _ in range(3)]
            b = [clamp(a[c] + step[c]) for c in range(3)]
            oa = [clamp(a[c] - step[c] + rng.randrange(-6, 7)) for c in range(3)]
            ob = [clamp(b[c] + step[c] + rng.randrange(-6, 7)) for c in range(3)]
            vec.append((oa, rng.randrange(2), a, b, ob, rng.randrange(2), metric,
                        rng.randrange(256), rng.randrange(2, 9), rng.randrange(4)))
        ext = [0, 255]
        for i in range(256):
            oa, a, b, ob = ([ext[(i >> (2 * s + c)) & 1] if c < 2 else ext[rng.randrange(2)]
                             for c in range(3)] for s in range(4))
            vec.append((oa, rng.randrange(2), a, b, ob, rng.randrange(2), metric, 255, 8, 0))
        for _ in range(3000):
            vec.append((rnd(), rng.randrange(2), rnd(), rnd(), rnd(), rng.randrange(2), metric,
                        rng.randrange(256), rng.randrange(2, 9), rng.randrange(4)))
    rng.shuffle(vec)
    return vec


def expected(v):
    oa, ok_a, a, b, ob, ok_b, metric, thr, gap, nshift = v
    p = bool(spec.interpolate_ok(spec.color_diff(a, b, metric), thr, gap, 1 << nshift))
    q = bool(rules.second_difference_test(oa, bool(ok_a), a, b, ob, bool(ok_b), thr, gap, 1 << nshift, metric))
    return int(p or q), int(p), int(q)


@cocotb.test()
async def base_decision_vs_golden(dut):
    rng = seeded_rng(dut, 4321)
    vec = vectors(rng)
    want = [expected(v) for v in vec]
    kinds = {(w[1], w[2]) for w in want}
    assert kinds == {(0, 0), (0, 1), (1, 0), (1, 1)}, f"vectors miss a P/Q combination: {kinds}"
    dut.en_i.value = 0
    await Timer(1, unit="ns")
    cocotb.start_soon(Clock(dut.clk_i, 10, unit="ns").start())
    await FallingEdge(dut.clk_i)
    inflight: deque[int] = deque()   # vectors taken by enabled edges, oldest first
    sent = checked = 0
    while checked < len(vec):
        en = rng.random() < 0.8
        dut.en_i.value = int(en)
        i = sent if sent < len(vec) else -1      # past the end: flush with the last inputs
        if en and i >= 0:
            oa, ok_a, a, b, ob, ok_b, metric, thr, gap, nshift = vec[i]
            dut.outer_a_i.value = pack_rgb(oa)
            dut.outer_a_ok_i.value = ok_a
            dut.a_i.value = pack_rgb(a)
            dut.b_i.value = pack_rgb(b)
            dut.outer_b_i.value = pack_rgb(ob)
            dut.outer_b_ok_i.value = ok_b
            dut.metric_i.value = int(metric == "sum")
            dut.thr_i.value = thr
            dut.gap_i.value = gap
            dut.nshift_i.value = nshift
        await RisingEdge(dut.clk_i)
        await ReadOnly()
        if en:
            inflight.append(i)
            sent += 1
            if len(inflight) == STAGES:
                j = inflight.popleft()
                if j >= 0:
                    got = (int(dut.base_o.value), int(dut.patent_o.value), int(dut.second_o.value))
                    assert got == want[j], f"vector {j} {vec[j]}: got (D, P, Q) {got}, want {want[j]}"
                    checked += 1
        await FallingEdge(dut.clk_i)
    dut._log.info("%d base decisions checked", len(vec))


def test_base_decision():
    run_cocotb("msr_base_decision", "test_base_decision", Path(__file__).parent)
