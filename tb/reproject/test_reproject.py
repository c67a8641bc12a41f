"""msr_reproject against msr_model.reuse.reproject, bit for bit (docs/spec/reuse.md section 4).

1. Pure Python: the seed table the RTL computes (its formula is read from the source) is
   msr_model.reuse.RECIP_T, and the Newton step's r stays in the RTL's bounds for every d.
2. The RTL, camera map by camera map (the map is static while pixels are in flight, so the
   bench drains the pipeline before it writes the next one), random valid/ready per map:
   - driver maps: camera_map of random eye/target pairs and a nearby second camera (moved and
     turned a little), random frame sizes up to 4096 x 4096 and INVZ_EXP; still cameras;
     pixels anywhere in the frame and at its corners, inverse depths of plausible depths,
     uniform, and 0 (sky), 1, 2, 2^15, 65534, 65535;
   - register-limit maps: every register from {-2^31, -2^31 + 1, -1, 0, 1, 2^31 - 1} or
     uniform 32-bit, coordinates 0 / 4095 or random;
   - solved maps: a map built for one pixel so that P0, P1, P2 take chosen values: P2 at both
     ends of every seed interval (d = 2^23 + k 2^15 and + 2^15 - 1) at random n, every bit
     length n from 1 to 59 (P2 = 2^(n-1), 2^n - 1), P2 = 2^22 - 1, 2^22, 0, -1 (the validity
     edge), and P0 or P1 around +-2^59 (|p0s| = 2^37 - 1, 2^37: the range edge).
   ok_o is compared always; U, V (saturated to 18 bits) and Wp (17 bits) where ok_o is set."""
from __future__ import annotations

import math
import re
from pathlib import Path

import cocotb
import numpy as np

from msr_flow.filelist import ROOT
from msr_flow.runner import run_cocotb
from msr_tb import seeded_rng, start_clock_and_reset, stream
from msr_tb_reuse import rand_camera

from msr_model import reuse
from msr_model.reuse import CameraMap

RTL = ROOT / "rtl"
SRC = RTL / "reuse" / "msr_reproject.sv"
XY_W, UV_W, WP_W = 12, 18, 17
I32 = (-(1 << 31), (1 << 31) - 1)


def rtl_seed_table() -> np.ndarray:
    """The RTL's seed formula, evaluated here as the elaboration does (integer division)."""
    m = re.search(r"SEED = \(\(1 << (\d+)\) \+ (\d+) \+ (\d+) \* i\) / \((\d+) \+ (\d+) \* i\)", SRC.read_text())
    e, a, b, c, k = (int(g) for g in m.groups())
    return np.array([((1 << e) + a + b * i) // (c + k * i) for i in range(256)], np.int64)


def test_seed_table_and_newton_bounds():
    assert np.array_equal(rtl_seed_table(), reuse.RECIP_T)
    d = np.arange(1 << 23, 1 << 24, dtype=np.int64)
    t = reuse.RECIP_T[(d >> 15) & 255]
    assert (d * t).max() < 1 << 40                      # 2^40 - d t is a 40-bit value
    r = (t * ((np.int64(1) << 40) - d * t)) >> 31
    assert r.min() >= (1 << 23) - 8 and r.max() <= 1 << 24  # a_recip_range; r fits 25 bits


# --- stimulus -----------------------------------------------------------------------------

def frame_size(rng) -> tuple[int, int]:
    return rng.choice([(160, 120), (480, 270), (960, 540), (1920, 1080), (4096, 4096), (33, 17),
                       (rng.randint(1, 4096), rng.randint(1, 4096))])


W_EDGES = (0, 1, 2, 1 << 15, 65534, 65535)


def driver_pixels(rng, wd, ht, invz_exp, n):
    xs, ys, ws = [], [], []
    for i in range(n):
        if i < 4:
            x, y = ((0, 0), (wd - 1, 0), (0, ht - 1), (wd - 1, ht - 1))[i]
        else:
            x, y = rng.randrange(wd), rng.randrange(ht)
        kind = rng.random()
        if kind < 0.6:      # a surface at a plausible depth
            z = math.exp(rng.uniform(math.log(0.3), math.log(100)))
            w = min(65535, max(1, int(2.0 ** invz_exp / z + 0.5)))
        elif kind < 0.8:
            w = rng.randrange(1 << 16)
        else:
            w = rng.choice(W_EDGES)
        xs.append(x), ys.append(y), ws.append(w)
    return xs, ys, ws


def driver_maps(rng, n_maps, n_pix):
    """(map, pixels) from the driver's camera_map; None maps (registers overflow) are skipped."""
    out, skipped = [], 0
    while len(out) < n_maps:
        wd, ht = frame_size(rng)
        invz_exp = rng.randint(8, 24)
        prev, cur = rand_camera(rng)
        if rng.random() < 0.1:
            cur = prev                                   # still camera
        cmap = reuse.camera_map(prev, cur, wd, ht, invz_exp)
        if cmap is None:
            skipped += 1
            continue
        out.append((cmap, driver_pixels(rng, wd, ht, invz_exp, n_pix)))
    return out, skipped


REG_EDGES = (-(1 << 31), -(1 << 31) + 1, -1, 0, 1, (1 << 31) - 1)


def limit_maps(rng, n_maps, n_pix):
    out = []
    for _ in range(n_maps):
        reg = lambda: rng.choice(REG_EDGES) if rng.random() < 0.5 else rng.randint(*I32)   # noqa: E731
        cmap = CameraMap(tuple(tuple(reg() for _ in range(3)) for _ in range(3)), tuple(reg() for _ in range(3)))
        edge = lambda: rng.choice((0, (1 << XY_W) - 1)) if rng.random() < 0.5 else rng.randrange(1 << XY_W)  # noqa: E731
        xs = [edge() for _ in range(n_pix)]
        ys = [edge() for _ in range(n_pix)]
        ws = [rng.choice(W_EDGES) if rng.random() < 0.5 else rng.randrange(1 << 16) for _ in range(n_pix)]
        out.append((cmap, (xs, ys, ws)))
    return out


def solve_row(rng, x, y, w, target):
    """(m_r0, m_r1, m_r2, b_r) with ((m_r0 x + m_r1 y + m_r2) << 16) + b_r w == target, or None."""
    low = target & 0xFFFF
    if w == 0:
        if low:
            return None
        b = rng.randint(*I32)
    else:
        b = (low * pow(w, -1, 1 << 16)) % (1 << 16)     # w odd: b w == target mod 2^16
        b -= rng.randrange(2) << 16
    a = (target - b * w) >> 16
    assert (a << 16) + b * w == target
    m0 = max(I32[0], min(I32[1], a // (2 * x))) if x else 0
    m1 = max(I32[0], min(I32[1], (a - m0 * x) // y)) if y else 0
    m2 = a - m0 * x - m1 * y
    if not I32[0] <= m2 <= I32[1]:
        return None
    return (m0, m1, m2), b


def solved_map(rng, targets, w=None):
    for _ in range(100):
        x, y = rng.randrange(2048, 1 << XY_W), rng.randrange(2048, 1 << XY_W)
        ww = w if w is not None else rng.randrange(1 << 16) | 1
        rows = [solve_row(rng, x, y, ww, t) for t in targets]
        if all(rows):
            return CameraMap(tuple(r[0] for r in rows), tuple(r[1] for r in rows)), ([x], [y], [ww])
    raise AssertionError(f"no map for {targets}")


def seam_maps(rng):
    out = []

    def with_p2(p2):
        # P0, P1: a previous position somewhere around the frame, or far outside it
        pos = [rng.randint(-(1 << 16), 1 << 16) if rng.random() < 0.8 else rng.randint(-(1 << 30), 1 << 30)
               for _ in range(2)]
        return [max(-(1 << 59), min(1 << 59, (p * max(p2, 1)) >> 15)) for p in pos] + [p2]

    for k in range(256):                       # both ends of every seed interval
        for d in ((1 << 23) + (k << 15), (1 << 23) + (k << 15) + (1 << 15) - 1):
            for _ in range(2):
                n = rng.randint(24, 59)
                p2 = (d << (n - 24)) + rng.randrange(1 << (n - 24))
                out.append(solved_map(rng, with_p2(p2)))
    for n in range(1, 60):                     # every bit length
        for p2 in ((1 << (n - 1)), (1 << n) - 1):
            out.append(solved_map(rng, with_p2(p2)))
    for p2 in ((1 << 22) - 1, 1 << 22, (1 << 22) + 1, 0, -1, -(1 << 40)):   # the validity edge
        out.append(solved_map(rng, with_p2(p2)))
    for row in (0, 1):                         # |p0s| and |p1s| around 2^37
        for p in ((1 << 59) - 1, 1 << 59, (1 << 59) + (1 << 22), -(1 << 59), -(1 << 59) + (1 << 22) - 1,
                  -(1 << 59) + (1 << 22), -(1 << 59) - 1):
            t = with_p2(1 << rng.randint(40, 50))
            t[row] = p
            out.append(solved_map(rng, t))
    for _ in range(20):                         # sky pixels (w = 0) with chosen P
        p2 = rng.randint(1 << 22, 1 << 50) & ~0xFFFF
        t = [v & ~0xFFFF for v in with_p2(p2)]
        out.append(solved_map(rng, t, w=0))
    return out


def golden(cmap, xs, ys, ws):
    rp = reuse.reproject(cmap, np.array(xs, np.int64), np.array(ys, np.int64), np.array(ws, np.int64))
    lo, hi = -(1 << (UV_W - 1)), (1 << (UV_W - 1)) - 1
    return (rp.ok, np.clip(rp.u, lo, hi), np.clip(rp.v, lo, hi), np.minimum(rp.wp, (1 << WP_W) - 1),
            (rp.u < lo) | (rp.u > hi) | (rp.v < lo) | (rp.v > hi) | (rp.wp >= 1 << WP_W))


def signed(v, bits):
    v = int(v)
    return v - (1 << bits) if v >> (bits - 1) else v


@cocotb.test()
async def reproject_vs_golden(dut):
    rng = seeded_rng(dut, 2027)
    mask = (1 << 32) - 1
    await start_clock_and_reset(dut, {"clear_i": 0, "valid_i": 0, "ready_i": 0, "x_i": 0, "y_i": 0,
                                      "w_i": 0, "user_i": 0, "m_i": 0, "b_i": 0})
    drv, skipped = driver_maps(rng, 400, 60)
    lim = limit_maps(rng, 100, 40)
    seam = seam_maps(rng)
    counts = {"vectors": 0, "ok": 0, "saturated": 0, "sky": 0}
    for group, maps in (("driver", drv), ("limits", lim), ("solved", seam)):
        for cmap, (xs, ys, ws) in maps:
            ok, u, v, wp, sat = golden(cmap, xs, ys, ws)
            m_word = 0
            for r in range(3):
                for c in range(3):
                    m_word |= (cmap.m[r][c] & mask) << (32 * (3 * r + c))
            dut.m_i.value = m_word
            dut.b_i.value = sum((cmap.b[r] & mask) << (32 * r) for r in range(3))

            def drive(i, xs=xs, ys=ys, ws=ws):
                dut.x_i.value, dut.y_i.value, dut.w_i.value = xs[i], ys[i], ws[i]
                dut.user_i.value = i & 0xFF

            def check(i, cmap=cmap, xs=xs, ys=ys, ws=ws, ok=ok, u=u, v=v, wp=wp):
                what = f"{group} map {cmap} pixel ({xs[i]}, {ys[i]}) w {ws[i]}"
                assert int(dut.user_o.value) == i & 0xFF, "results out of order"
                assert int(dut.ok_o.value) == int(ok[i]), f"{what}: ok {int(dut.ok_o.value)}, want {int(ok[i])}"
                if ok[i]:
                    got = (signed(dut.u_o.value, UV_W), signed(dut.v_o.value, UV_W), int(dut.wp_o.value))
                    want = (int(u[i]), int(v[i]), int(wp[i]))
                    assert got == want, f"{what}: (U, V, Wp) {got}, want {want}"

            p_valid, p_ready = rng.choice(((1.0, 1.0), (1.0, 0.5), (0.8, 0.9), (0.3, 1.0), (1.0, 0.15)))
            await stream(dut, rng, len(xs), drive, check, p_valid, p_ready)
            counts["vectors"] += len(xs)
            counts["ok"] += int(ok.sum())
            counts["saturated"] += int((ok & sat).sum())
            counts["sky"] += int((ok & (np.array(ws) == 0)).sum())
        dut._log.info("%s maps done: %s", group, counts)
    dut._log.info("%d driver maps (%d camera pairs skipped: registers overflow), %d limit maps, %d solved maps",
                  len(drv), skipped, len(lim), len(seam))
    assert counts["ok"] > counts["vectors"] // 2 and counts["saturated"] > 0 and counts["sky"] > 0, counts


def test_reproject():
    run_cocotb("msr_reproject", "test_reproject", Path(__file__).parent, {"USER_W": 8},
               sources=[*(RTL / "prim" / f for f in ("msr_lzc.sv", "msr_clr_reg.sv", "msr_stall_ctrl.sv",
                                                   "msr_en_pipe.sv", "msr_pipe_mul.sv")), SRC])
