"""msr_decision_pipe (the decision half) against spec.color_diff / spec.interpolate_ok: every gap 1..8 and nominal gap
1..8, every threshold with the difference just below, at and above the decision boundary,
all 64 extreme colour pairs (channels 0/255), and random colours; random valid/ready."""
from __future__ import annotations

from pathlib import Path

import cocotb

from msr_flow.runner import run_cocotb
from msr_tb import pack_rgb, seeded_rng, start_clock_and_reset, stream

from msr_model import spec


def colour_with_diff(rng, d, metric):
    """Two colours whose difference under `metric` is exactly d (d <= 255 or <= 765)."""
    a = [rng.randrange(256) for _ in range(3)]
    if metric == "max":
        parts = [rng.randrange(d + 1) for _ in range(3)]
        parts[rng.randrange(3)] = d
    else:
        parts = [0, 0, 0]
        left = d
        for c in rng.sample(range(3), 3):
            parts[c] = min(255, left)
            left -= parts[c]
        rng.shuffle(parts)
    b = []
    for c in range(3):
        up = a[c] + parts[c] <= 255
        down = a[c] - parts[c] >= 0
        if up and (not down or rng.random() < 0.5):
            b.append(a[c] + parts[c])
        elif down:
            b.append(a[c] - parts[c])
        else:  # neither fits from this a: move a to an end
            a[c] = 0
            b.append(parts[c])
    return a, b


def vectors(rng):
    vec = []
    for metric in spec.METRICS:
        dmax = 255 if metric == "max" else 765
        for gap in range(1, 9):
            for nshift in range(4):
                nominal = 1 << nshift
                for thr in range(256):
                    # boundary: d * n < thr * g  <=>  d < thr * g / n
                    edge = (thr * gap + nominal - 1) // nominal
                    for d in {edge - 1, edge, edge + 1}:
                        if 0 <= d <= dmax:
                            a, b = colour_with_diff(rng, d, metric)
                            vec.append((a, b, metric, thr, gap, nshift))
        ext = [0, 255]
        for ia in range(8):
            for ib in range(8):
                a = [ext[(ia >> c) & 1] for c in range(3)]
                b = [ext[(ib >> c) & 1] for c in range(3)]
                vec.append((a, b, metric, rng.randrange(256), rng.randrange(1, 9), rng.randrange(4)))
        for _ in range(3000):
            a = [rng.randrange(256) for _ in range(3)]
            b = [rng.randrange(256) for _ in range(3)]
            vec.append((a, b, metric, rng.randrange(256), rng.randrange(1, 9), rng.randrange(4)))
    rng.shuffle(vec)
    return vec


@cocotb.test()
async def decide_vs_golden(dut):
    rng = seeded_rng(dut, 1234)
    await start_clock_and_reset(dut, {"clear_i": 0, "valid_i": 0, "ready_i": 0, "a_i": 0, "b_i": 0,
                                      "metric_i": 0, "thr_i": 0, "gap_i": 1, "off_i": 0, "nshift_i": 0,
                                      "user_i": 0})
    vec = vectors(rng)
    expect = []
    for i, (a, b, metric, thr, gap, nshift) in enumerate(vec):
        d = spec.color_diff(a, b, metric)
        expect.append((int(spec.interpolate_ok(d, thr, gap, 1 << nshift)), d, i & 0xFFFF))

    def drive(i):
        a, b, metric, thr, gap, nshift = vec[i]
        dut.a_i.value = pack_rgb(a)
        dut.b_i.value = pack_rgb(b)
        dut.metric_i.value = int(metric == "sum")
        dut.thr_i.value = thr
        dut.gap_i.value = gap
        dut.off_i.value = gap // 2
        dut.nshift_i.value = nshift
        dut.user_i.value = i & 0xFFFF

    def check(i):
        res = (int(dut.interp_o.value), int(dut.diff_o.value), int(dut.user_o.value))
        assert res == expect[i], f"vector {i} {vec[i]}: got {res}, want {expect[i]}"

    await stream(dut, rng, len(vec), drive, check, p_valid=0.9, p_ready=0.8)
    dut._log.info("%d decisions checked", len(vec))


def test_decide():
    run_cocotb("msr_decision_pipe", "test_decide", Path(__file__).parent, {"USER_W": 16})
