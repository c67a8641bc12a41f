"""Helpers of the reuse benches (tb/reproject, tb/reuse_gather, tb/reuse_path): a previous
frame's planes, the window memory the gather reads, and camera pairs as the driver sees them."""
from __future__ import annotations

import numpy as np
from cocotb.triggers import FallingEdge, ReadOnly

from msr_model import reuse
from msr_tb import pack_rgb


def prev_frame(rng, wd, ht):
    nrng = np.random.default_rng(rng.randrange(1 << 30))
    frame = nrng.integers(0, 256, (ht, wd, 3))
    base = nrng.integers(0, 256, 3)
    smooth = nrng.random((ht, wd)) < 0.6
    frame[smooth] = np.clip(base + nrng.integers(-3, 4, (int(smooth.sum()), 3)), 0, 255)
    invz = nrng.integers(1, 65535, (ht, wd))
    surf = nrng.random((ht, wd)) < 0.6
    invz[surf] = nrng.integers(20000, 20100, int(surf.sum()))
    invz[nrng.random((ht, wd)) < 0.1] = 0
    invz[nrng.random((ht, wd)) < 0.03] = 65535
    invz[: ht // 3] = 0                  # a band of sky
    age = nrng.integers(0, 8, (ht, wd))
    return reuse.ReuseState(frame.astype(np.uint8), invz.astype(np.uint16), age.astype(np.uint8), None)


async def window_memory(dut, holder):
    """Each clock: the taps read at the coming edge (seen in ReadOnly) are on tap_*_i after it."""
    rgb, w, age = [0] * 4, [0] * 4, [0] * 4
    while True:
        await ReadOnly()
        rd = int(dut.tap_rd_o.value)
        state = holder[0]
        if rd and state is not None:
            xs, ys = int(dut.tap_x_o.value), int(dut.tap_y_o.value)
            for k in range(4):
                if rd >> k & 1:
                    x, y = xs >> (12 * k) & 0xFFF, ys >> (12 * k) & 0xFFF
                    assert y < state.invz.shape[0] and x < state.invz.shape[1], f"tap {k} read outside ({x}, {y})"
                    rgb[k], w[k], age[k] = pack_rgb(state.frame[y, x]), int(state.invz[y, x]), int(state.age[y, x])
        await FallingEdge(dut.clk_i)
        dut.tap_rgb_i.value = sum(c << (24 * k) for k, c in enumerate(rgb))
        dut.tap_w_i.value = sum(c << (16 * k) for k, c in enumerate(w))
        dut.tap_age_i.value = sum(c << (3 * k) for k, c in enumerate(age))


def rand_camera(rng) -> tuple[str, str]:
    """A previous camera and the current one: moved by up to ~0.3 model units, its target by up
    to ~0.5, the same field of view (now and then another)."""
    eye = np.array([rng.uniform(-5, 5) for _ in range(3)])
    if rng.random() < 0.05:
        direc = np.array([rng.uniform(-0.05, 0.05), rng.choice([-1.0, 1.0]), rng.uniform(-0.05, 0.05)])
    else:
        direc = np.array([rng.gauss(0, 1) for _ in range(3)])
    tgt = eye + direc / np.linalg.norm(direc) * rng.uniform(0.5, 10)
    fov = rng.uniform(20, 100)
    step = rng.choice([0.0, 0.01, 0.05, 0.3])
    eye2 = eye + np.array([rng.gauss(0, step) for _ in range(3)])
    tgt2 = tgt + np.array([rng.gauss(0, step * 1.5) for _ in range(3)])
    fov2 = fov if rng.random() < 0.9 else fov * rng.uniform(0.95, 1.05)
    fmt = lambda e, t, f: ",".join(f"{v:.6f}" for v in (*e, *t, f))   # noqa: E731
    return fmt(eye, tgt, fov), fmt(eye2, tgt2, fov2)
