"""msr_reuse_check against the tests 3 to 7 of msr_model.reuse._reuse_decision
(docs/spec/reuse.md section 6), bit for bit.

Per vector, as the golden model computes them: the silhouette test on w_A, w_B; R against A
or B and the taps' range hi - lo with spec.color_diff and spec.interpolate_ok (the pass's
metric, threshold, gap and n_k); the oldest tap's age against AGE_MAX; the refresh slot from
reuse.refresh_phase and the frame's number (the unit takes it mod 8). Stimulus, under random
valid/ready: R near A or B or far from both, taps spread from 0 to wide, thresholds 0..255,
gaps 1..8, n_k 1..8, both metrics, tiles 8, 16, 32 anywhere in a 4096-pixel frame, sky and
surface depths, ages 0..7, frames 0..1000, and tests 1-2's result (geo_ok) mostly set.
ok, R and the new age are compared on every vector, and every test is seen to fail alone."""
from __future__ import annotations

from pathlib import Path

import cocotb
import numpy as np

from msr_flow.filelist import ROOT
from msr_flow.runner import run_cocotb
from msr_tb import pack_rgb, seeded_rng, start_clock_and_reset, stream, unpack_rgb

from msr_model import reuse, spec

RTL = ROOT / "rtl"
N_VEC = 6000


def near(rng, c, spread):
    return tuple(max(0, min(255, v + rng.randint(-spread, spread))) for v in c)


def vector(rng):
    a = tuple(rng.randrange(256) for _ in range(3))
    b = near(rng, a, rng.choice((0, 4, 40)))
    k = rng.random()
    r = near(rng, a, 3) if k < 0.35 else near(rng, b, 3) if k < 0.7 else tuple(rng.randrange(256) for _ in range(3))
    lo = near(rng, r, rng.choice((0, 2, 10)))
    hi = tuple(min(255, l + rng.choice((0, 1, 3, 8, 60))) for l in lo)
    sky = (0, rng.randrange(1, 65536))
    wa = sky[rng.random() < 0.85]
    wb = sky[rng.random() < 0.85] if rng.random() < 0.3 else (wa if wa == 0 else rng.randrange(1, 65536))
    tile = rng.choice((8, 16, 32))
    return {"geo_ok": int(rng.random() < 0.9), "r": r, "lo": lo, "hi": hi, "age": rng.randrange(8),
            "a": a, "b": b, "wa": wa, "wb": wb, "metric": rng.choice(("max", "sum")),
            "thr": rng.choice((0, 1, rng.randrange(256), rng.randrange(64))), "gap": rng.randint(1, 8),
            "nshift": rng.randrange(4), "x": rng.randrange(4096), "y": rng.randrange(4096),
            "tile": tile, "frame": rng.randrange(1000)}


def golden(v):
    """(ok, the tests that failed) as msr_model.reuse._reuse_decision decides them."""
    n_k = 1 << v["nshift"]

    def below(d):
        return bool(spec.interpolate_ok(d, v["thr"], v["gap"], n_k))

    tests = {
        "geo": bool(v["geo_ok"]),
        "silhouette": (v["wa"] == 0) == (v["wb"] == 0),
        "colour": below(spec.color_diff(v["r"], v["a"], v["metric"])) or below(spec.color_diff(v["r"], v["b"], v["metric"])),
        "taps": below(spec.color_diff(v["hi"], v["lo"], v["metric"])),
        "age": v["age"] < reuse.AGE_MAX,
        "refresh": (v["frame"] + int(reuse.refresh_phase(v["x"], v["y"], v["tile"]))) % reuse.REFRESH != 0,
    }
    return all(tests.values()), [t for t, ok in tests.items() if not ok]


@cocotb.test()
async def check_vs_golden(dut):
    rng = seeded_rng(dut, 733)
    await start_clock_and_reset(dut, {"clear_i": 0, "valid_i": 0, "ready_i": 0, "geo_ok_i": 0, "r_i": 0,
                                      "lo_i": 0, "hi_i": 0, "age_i": 0, "a_i": 0, "b_i": 0, "wa_i": 0, "wb_i": 0,
                                      "metric_i": 0, "thr_i": 0, "gap_i": 1, "nshift_i": 0, "x_i": 0, "y_i": 0,
                                      "tile_lg_i": 4, "frame_i": 0, "user_i": 0})
    vecs = [vector(rng) for _ in range(N_VEC)]
    want = [golden(v) for v in vecs]
    seen = {"ok": 0, **{t: 0 for t in ("geo", "silhouette", "colour", "taps", "age", "refresh")}}
    for ok, failed in want:
        seen["ok"] += ok
        if len(failed) == 1:            # a test that fails alone decides the vector by itself
            seen[failed[0]] += 1

    def drive(i):
        v = vecs[i]
        dut.geo_ok_i.value = v["geo_ok"]
        dut.r_i.value, dut.lo_i.value, dut.hi_i.value = pack_rgb(v["r"]), pack_rgb(v["lo"]), pack_rgb(v["hi"])
        dut.a_i.value, dut.b_i.value = pack_rgb(v["a"]), pack_rgb(v["b"])
        dut.age_i.value, dut.wa_i.value, dut.wb_i.value = v["age"], v["wa"], v["wb"]
        dut.metric_i.value = int(v["metric"] == "sum")
        dut.thr_i.value, dut.gap_i.value, dut.nshift_i.value = v["thr"], v["gap"], v["nshift"]
        dut.x_i.value, dut.y_i.value = v["x"], v["y"]
        dut.tile_lg_i.value = v["tile"].bit_length() - 1
        dut.frame_i.value = v["frame"] & 7
        dut.user_i.value = i & 0xFF

    def check(i):
        v, (ok, failed) = vecs[i], want[i]
        what = f"vector {i} {v}: failed {failed}"
        assert int(dut.user_o.value) == i & 0xFF, "results out of order"
        assert int(dut.ok_o.value) == int(ok), f"{what}: ok_o {int(dut.ok_o.value)}"
        assert unpack_rgb(dut.rgb_o.value) == tuple(v["r"]), f"{what}: R {unpack_rgb(dut.rgb_o.value)}"
        assert int(dut.age_o.value) == (v["age"] + 1) & 7, f"{what}: age {int(dut.age_o.value)}"

    for part in range(4):
        lo, hi = part * N_VEC // 4, (part + 1) * N_VEC // 4
        p_valid, p_ready = ((1.0, 1.0), (1.0, 0.5), (0.7, 0.9), (1.0, 0.2))[part]
        await stream(dut, rng, hi - lo, lambda i: drive(lo + i), lambda i: check(lo + i), p_valid, p_ready)
    dut._log.info("reuse_check: %s", seen)
    assert min(seen.values()) > 30, f"some test never decided a vector alone: {seen}"


def test_reuse_check():
    run_cocotb("msr_reuse_check", "test_reuse_check", Path(__file__).parent, {"USER_W": 8},
               sources=[RTL / "pkg" / "msr_pkg.sv",
                        *(RTL / "prim" / f for f in ("msr_clr_reg.sv", "msr_stall_ctrl.sv", "msr_en_pipe.sv")),
                        RTL / "reuse/msr_reuse_check.sv"])
