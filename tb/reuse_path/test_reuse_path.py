"""msr_reuse_path (msr_reproject -> msr_reuse_gather -> msr_reuse_check) against the golden
model's own decision, msr_model.reuse._reuse_decision, bit for bit (docs/spec/reuse.md
sections 4 to 6).

Per previous frame (the frame's registers are static while positions are in flight: the bench
drains the path in between): a previous frame of random size with smooth patches, sky, surfaces
and ages (msr_tb_reuse.prev_frame); a camera pair near each other (msr_tb_reuse.rand_camera) and
the driver's camera map for it; positions anywhere in the frame with the inverse depth of the
previous frame there (the same surface) or random; A and B near the previous colour there or
random, their depths sky or surface; random thresholds, gaps, n_k, metric, tile size and frame
number. The golden verdict is _reuse_decision's on a pass view built of the same fields; ok, R
and the new age are compared on every position, under random valid/ready and the window memory
of the gather bench."""
from __future__ import annotations

from pathlib import Path
from types import SimpleNamespace

import cocotb
import numpy as np

from msr_flow.filelist import ROOT
from msr_flow.runner import run_cocotb
from msr_tb import pack_rgb, seeded_rng, start_clock_and_reset, stream, unpack_rgb
from msr_tb_reuse import prev_frame, rand_camera, window_memory

from msr_model import reuse, spec

RTL = ROOT / "rtl"
SIZES = ((64, 48), (160, 90), (37, 23), (256, 16))


def view_of(fields: dict, tile: int):
    """A pass view with the fields _reuse_decision reads, one entry per position."""
    thr, gap, nom = fields["thr"], fields["gap"], 1 << fields["nshift"]
    metric = fields["metric"]
    return SimpleNamespace(
        A=fields["a"], B=fields["b"], metric=metric, tile=tile,
        diff=lambda c1, c2: spec.color_diff(c1, c2, metric),
        below_threshold=lambda d: spec.interpolate_ok(d, thr, gap, nom))


def positions(rng, state, invz_exp, n):
    ht, wd = state.invz.shape
    nrng = np.random.default_rng(rng.randrange(1 << 30))
    x, y = nrng.integers(0, wd, n), nrng.integers(0, ht, n)
    base = state.frame[y, x].astype(np.int64)
    wm = state.invz[y, x].astype(np.int64)
    rand_w = nrng.random(n) < 0.2
    wm[rand_w] = nrng.integers(0, 65536, int(rand_w.sum()))
    a = np.clip(base + nrng.integers(-4, 5, (n, 3)), 0, 255)
    b = np.clip(base + nrng.integers(-4, 5, (n, 3)), 0, 255)
    far = nrng.random(n) < 0.2
    a[far] = nrng.integers(0, 256, (int(far.sum()), 3))
    wa = np.where(nrng.random(n) < 0.1, 0, np.maximum(wm, 1))
    wb = np.where(nrng.random(n) < 0.1, 0, np.maximum(wm, 1))
    metric = rng.choice(("max", "sum"))
    return {"x": x, "y": y, "wm": wm, "a": a, "b": b, "wa": wa, "wb": wb, "metric": metric,
            "thr": nrng.choice((0, 4, 8, 16, 40, 255), n), "gap": nrng.integers(1, 9, n),
            "nshift": nrng.integers(0, 4, n)}


@cocotb.test()
async def path_vs_golden(dut):
    rng = seeded_rng(dut, 4099)
    mask = (1 << 32) - 1
    await start_clock_and_reset(dut, {
        "clear_i": 0, "valid_i": 0, "ready_i": 0, "cam_m_i": 0, "cam_b_i": 0, "width_i": 1, "height_i": 1,
        "tile_lg_i": 4, "frame_i": 0, "x_i": 0, "y_i": 0, "wm_i": 0, "a_i": 0, "b_i": 0, "wa_i": 0,
        "wb_i": 0, "metric_i": 0, "thr_i": 0, "gap_i": 1, "nshift_i": 0, "user_i": 0,
        "tap_rgb_i": 0, "tap_w_i": 0, "tap_age_i": 0})
    holder = [None]
    cocotb.start_soon(window_memory(dut, holder))
    counts = {"positions": 0, "ok": 0, "maps": 0}
    while counts["maps"] < 24:
        wd, ht = SIZES[counts["maps"] % len(SIZES)]
        invz_exp = rng.randint(10, 20)
        prev_cam, cur_cam = rand_camera(rng)
        cmap = reuse.camera_map(prev_cam, cur_cam, wd, ht, invz_exp)
        if cmap is None:
            continue
        counts["maps"] += 1
        state = prev_frame(rng, wd, ht)
        holder[0] = state
        tile, index = rng.choice((8, 16, 32)), rng.randrange(100)
        f = positions(rng, state, invz_exp, 400)
        take = reuse._reuse_decision(view_of(f, tile), np.ones(len(f["x"]), bool), state, cmap, f["x"], f["y"],
                                     f["wa"], f["wb"], f["wm"], index)
        dut.cam_m_i.value = sum((cmap.m[r][c] & mask) << (32 * (3 * r + c)) for r in range(3) for c in range(3))
        dut.cam_b_i.value = sum((cmap.b[r] & mask) << (32 * r) for r in range(3))
        dut.width_i.value, dut.height_i.value = wd, ht
        dut.tile_lg_i.value, dut.frame_i.value = tile.bit_length() - 1, index & 7
        dut.metric_i.value = int(f["metric"] == "sum")

        def drive(i, f=f):
            dut.x_i.value, dut.y_i.value, dut.wm_i.value = int(f["x"][i]), int(f["y"][i]), int(f["wm"][i])
            dut.a_i.value, dut.b_i.value = pack_rgb(f["a"][i]), pack_rgb(f["b"][i])
            dut.wa_i.value, dut.wb_i.value = int(f["wa"][i]), int(f["wb"][i])
            dut.thr_i.value, dut.gap_i.value, dut.nshift_i.value = int(f["thr"][i]), int(f["gap"][i]), int(f["nshift"][i])
            dut.user_i.value = i & 0xFF

        def check(i, f=f, take=take):
            what = (f"map {counts['maps']} ({wd}x{ht}, T {tile}, frame {index}) position ({f['x'][i]}, {f['y'][i]}) "
                    f"w_m {f['wm'][i]}")
            assert int(dut.user_o.value) == i & 0xFF, "results out of order"
            assert int(dut.ok_o.value) == int(take.ok[i]), f"{what}: ok {int(dut.ok_o.value)}, want {int(take.ok[i])}"
            if take.ok[i]:
                got = (unpack_rgb(dut.rgb_o.value), int(dut.age_o.value))
                want = (tuple(int(c) for c in take.colour[i]), int(take.age[i]))
                assert got == want, f"{what}: (R, age) {got}, want {want}"

        p_valid, p_ready = rng.choice(((1.0, 1.0), (1.0, 0.5), (0.7, 0.9), (1.0, 0.2)))
        await stream(dut, rng, len(f["x"]), drive, check, p_valid, p_ready)
        counts["positions"] += len(f["x"])
        counts["ok"] += int(take.ok.sum())
    dut._log.info("reuse_path: %s", counts)
    assert counts["ok"] > 200 and counts["positions"] - counts["ok"] > 200, counts


def test_reuse_path():
    run_cocotb("msr_reuse_path", "test_reuse_path", Path(__file__).parent, {"USER_W": 8},
               sources=[RTL / "pkg" / "msr_pkg.sv",
                        *(RTL / "prim" / f for f in ("msr_lzc.sv", "msr_clr_reg.sv", "msr_stall_ctrl.sv",
                                                   "msr_en_pipe.sv", "msr_pipe_mul.sv")),
                        *(RTL / "reuse" / f for f in ("msr_reproject.sv", "msr_reuse_gather.sv",
                                                      "msr_reuse_check.sv", "msr_reuse_path.sv"))])
