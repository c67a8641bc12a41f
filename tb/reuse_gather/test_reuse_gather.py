"""msr_reuse_gather against msr_model.reuse.gather and the depth and sky tests of
_reuse_decision (docs/spec/reuse.md sections 5 and 6, tests 1 and 2), bit for bit.

The bench is the window memory: a tap whose tap_rd_o is set at a clock edge has its word
(colour, W, age at tap_x_o, tap_y_o of the previous frame) on tap_*_i from the next clock on;
every other tap keeps its word (so an unused tap shows a stale word, which must not count).
Per previous frame (the extent is static while pixels are in flight: the bench drains the
pipeline in between), random valid/ready:
- frames of 1 x 1, 2 x 3, 37 x 23, 64 x 48 and strips 4096 x 6, 5 x 4096 (the extent's limit);
  planes of random colours over smooth patches, W with sky (0), saturated (65535) and smooth
  surfaces, a band of sky, ages 0..7;
- positions U, V anywhere from three pixels outside to three outside the far edge, on pixel
  centres (fx = 0, fy = 0: unused taps), and U, V saturated (+-2^17);
- w_m 0 (sky), 65535, random; Wp random or around the tolerance edge |Wb - Wp| = (Wp >> 6) + 1;
  the reprojection's ok random.
geo_ok_o and inside_o are compared always; R, Wb, lo, hi and age where inside_o is set."""
from __future__ import annotations

from pathlib import Path

import cocotb
import numpy as np

from msr_flow.filelist import ROOT
from msr_flow.runner import run_cocotb
from msr_tb import seeded_rng, start_clock_and_reset, stream, unpack_rgb
from msr_tb_reuse import prev_frame, window_memory

from msr_model import reuse

RTL = ROOT / "rtl"
UV_W, WP_W = 18, 17
SIZES = ((1, 1), (2, 3), (37, 23), (64, 48), (4096, 6), (5, 4096))


def pixels(rng, state, n):
    ht, wd = state.invz.shape
    u, v = [], []
    for _ in range(n):
        k = rng.random()
        if k < 0.05:
            u.append(rng.choice((-(1 << 17), (1 << 17) - 1))), v.append(rng.randint(-48, ht * 16 + 48))
        elif k < 0.1:
            u.append(rng.randint(-48, wd * 16 + 48)), v.append(rng.choice((-(1 << 17), (1 << 17) - 1)))
        else:
            uu, vv = rng.randint(-48, wd * 16 + 48), rng.randint(-48, ht * 16 + 48)
            if rng.random() < 0.2:
                uu &= ~15
            if rng.random() < 0.2:
                vv &= ~15
            u.append(uu), v.append(vv)
    wb = reuse.gather(state, np.array(u), np.array(v)).wb
    wm, wp, ok = [], [], []
    for i in range(n):
        k = rng.random()
        wm.append(0 if k < 0.15 else 65535 if k < 0.2 else rng.randrange(1, 65535))
        if rng.random() < 0.6:          # around the tolerance's edge
            b = int(wb[i])
            tol = (b >> 6) + 1
            wp.append(max(0, min((1 << WP_W) - 1, b + rng.choice((-1, 1)) * (tol + rng.randint(-2, 2)))))
        else:
            wp.append(rng.randrange(1 << WP_W))
        ok.append(int(rng.random() < 0.9))
    return u, v, wm, wp, ok


def golden(state, u, v, wm, wp, ok):
    g = reuse.gather(state, np.array(u, np.int64), np.array(v, np.int64))
    wm, wp, ok = (np.array(a, np.int64) for a in (wm, wp, ok))
    depth_ok = np.abs(g.wb - wp) <= (wp >> reuse.DEPTH_TOL_SHIFT) + 1
    geo = (ok == 1) & g.inside & np.where(wm == 0, g.sky_all, g.sky_none & (wm < reuse.INVZ_MAX) & depth_ok)
    return g, geo


@cocotb.test()
async def gather_vs_golden(dut):
    rng = seeded_rng(dut, 515)
    await start_clock_and_reset(dut, {"clear_i": 0, "valid_i": 0, "ready_i": 0, "width_i": 1, "height_i": 1,
                                      "ok_i": 0, "u_i": 0, "v_i": 0, "wp_i": 0, "wm_i": 0, "user_i": 0,
                                      "tap_rgb_i": 0, "tap_w_i": 0, "tap_age_i": 0})
    holder = [None]
    cocotb.start_soon(window_memory(dut, holder))
    counts = {"vectors": 0, "inside": 0, "geo_ok": 0, "sky_ok": 0}
    for rep in range(40):
        wd, ht = SIZES[rep % len(SIZES)]
        state = prev_frame(rng, wd, ht)
        holder[0] = state
        dut.width_i.value, dut.height_i.value = wd, ht
        u, v, wm, wp, ok = pixels(rng, state, 500)
        g, geo = golden(state, u, v, wm, wp, ok)
        um = (1 << UV_W) - 1

        def drive(i):
            dut.u_i.value, dut.v_i.value = u[i] & um, v[i] & um
            dut.wm_i.value, dut.wp_i.value, dut.ok_i.value = wm[i], wp[i], ok[i]
            dut.user_i.value = i & 0xFF

        def check(i):
            what = f"{wd}x{ht} pixel {i}: U {u[i]} V {v[i]} w_m {wm[i]} Wp {wp[i]} ok {ok[i]}"
            assert int(dut.user_o.value) == i & 0xFF, "results out of order"
            assert int(dut.inside_o.value) == int(g.inside[i]), f"{what}: inside {int(dut.inside_o.value)}"
            assert int(dut.geo_ok_o.value) == int(geo[i]), f"{what}: geo_ok {int(dut.geo_ok_o.value)}"
            if g.inside[i]:
                got = (unpack_rgb(dut.rgb_o.value), int(dut.wb_o.value), unpack_rgb(dut.lo_o.value),
                       unpack_rgb(dut.hi_o.value), int(dut.age_o.value))
                want = (tuple(int(c) for c in g.colour[i]), int(g.wb[i]), tuple(int(c) for c in g.lo[i]),
                        tuple(int(c) for c in g.hi[i]), int(g.age[i]))
                assert got == want, f"{what}: (R, Wb, lo, hi, age) {got}, want {want}"

        p_valid, p_ready = rng.choice(((1.0, 1.0), (1.0, 0.5), (0.7, 0.9), (1.0, 0.2)))
        await stream(dut, rng, len(u), drive, check, p_valid, p_ready)
        counts["vectors"] += len(u)
        counts["inside"] += int(g.inside.sum())
        counts["geo_ok"] += int(geo.sum())
        counts["sky_ok"] += int((geo & (np.array(wm) == 0)).sum())
    dut._log.info("gather: %s", counts)
    assert min(counts.values()) > 100, counts


def test_reuse_gather():
    run_cocotb("msr_reuse_gather", "test_reuse_gather", Path(__file__).parent, {"USER_W": 8},
               sources=[*(RTL / "prim" / f for f in ("msr_clr_reg.sv", "msr_stall_ctrl.sv", "msr_en_pipe.sv")),
                        RTL / "reuse/msr_reuse_gather.sv"])
