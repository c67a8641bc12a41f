"""msr_top: soft and hard resets: in the middle of a frame, in the clock a frame completes, in
every state of msr_cfg_ctrl, in the middle of a burst; each followed by a clean frame."""
from __future__ import annotations

import cocotb
from cocotb.triggers import ClockCycles, RisingEdge, ReadOnly

from msr_flow import regs as R
from msr_top_env import (
    MEM, FILL, ST_IDLE, ST_SAMPLE, ST_CHECK, ST_RUN, ST_DRAIN, make_image, setup, snapshot,
    tiles_built, wait_state)


@cocotb.test()
async def test_soft_reset(dut):
    env, rng = await setup(dut, 13)
    env.set_pauses(0.3)
    env.render.max_lat = 30
    env.render.ready_p = 0.6
    for delay in (40, 300, 900):
        img = make_image(rng, 40, 32)
        env.render.image = img
        await env.program(40, 32, 8, 2, 0, [8, 16], 0)
        await env.wr(R.CTRL, R.CTRL_START_MASK)
        await ClockCycles(dut.clk_i, delay)
        st = await env.rd(R.STATUS)
        assert st & R.STATUS_BUSY_MASK, "frame finished before the soft reset: make it bigger"
        await env.wr(R.CTRL, R.CTRL_SOFT_RESET_MASK)
        st = await env.wait_idle()
        assert st == 0, f"STATUS after soft reset {st:#x}: want idle, not done, no error"
        assert not env.render.pending, "cleared with render responses outstanding"
        assert await env.rd(R.PERF_CYCLES) == 0, "counters not cleared"
        # The next frame is clean and bit-exact.
        await env.frame(27, 19, rng.choice((8, 16)), 2, 0, [8, 16], 20)


@cocotb.test()
async def test_soft_reset_at_done(dut):
    """A soft reset written in the very clock a frame completes: the frame is aborted and STATUS
    reads 0 (DONE too: CTRL.SOFT_RESET clears it, and the register block's hardware set outranks
    its clear, so msr_cfg_ctrl must not set it then). The bench times the write around the frame's measured end until the two coincide."""
    env, rng = await setup(dut, 17)
    env.set_pauses(0.0)
    env.render.max_lat = 1
    env.render.ready_p = 1.0
    u = dut.u_ctrl
    hit = [False]

    async def watch():
        while True:
            await RisingEdge(dut.clk_i)
            await ReadOnly()
            if int(u.soft_reset_i.value) and int(u.frame_done_q.value) and int(u.state_q.value) == 3:
                hit[0] = True
    task = cocotb.start_soon(watch())
    img = make_image(rng, 16, 8)
    # the frame's length from START's write to its completion (deterministic here)
    env.render.image = img
    await env.program(16, 8, 8, 1, 0, [8], 0)
    await env.wr(R.CTRL, R.CTRL_START_MASK)
    n = 0
    while not int(u.frame_done_q.value):
        await RisingEdge(dut.clk_i)
        n += 1
        assert n < 20000, "the frame never completed"
    await env.wait_idle()
    await env.wr(R.STATUS, R.STATUS_DONE_MASK)
    for k in range(max(0, n - 24), n + 8):
        env.render.image = img
        await env.program(16, 8, 8, 1, 0, [8], 0)
        await env.wr(R.CTRL, R.CTRL_START_MASK)
        await ClockCycles(dut.clk_i, k)
        await env.wr(R.CTRL, R.CTRL_SOFT_RESET_MASK)
        st = await env.wait_idle()
        assert st & ~R.STATUS_DONE_MASK == 0, f"delay {k}: STATUS {st:#x} after soft reset"
        if hit[0]:
            assert st == 0, f"delay {k}: soft reset in the completing clock left STATUS {st:#x}"
            break
        await env.wr(R.STATUS, R.STATUS_DONE_MASK)
    task.cancel()
    assert hit[0], f"no delay in {max(0, n - 24)}..{n + 7} put the soft reset in the completing clock"
    await env.frame(16, 8, 8, 1, 0, [8], 0)


@cocotb.test()
async def test_soft_reset_states(dut):
    """CTRL.SOFT_RESET written in every state of msr_cfg_ctrl a register write can reach: idle,
    just after a START (sample / check), with START in the same write, running, during the
    drain of an earlier soft reset, after DONE, after a refused START. Each time: idle after it,
    DONE 0, ERROR 0, nothing written outside the planes, and the next frame bit-exact."""
    env, rng = await setup(dut, 20)
    env.set_pauses(0.2)
    seen = set()

    async def monitor():
        while True:
            await RisingEdge(dut.clk_i)
            if int(dut.u_ctrl.soft_reset_i.value):
                seen.add(int(dut.u_ctrl.state_q.value))
    cocotb.start_soon(monitor())
    for case in ("idle", "check", "start+soft", "run", "drain", "done", "refused"):
        env.render.max_lat = 200 if case == "drain" else 20
        f = None
        if case == "idle":
            await env.wr(R.CTRL, R.CTRL_SOFT_RESET_MASK)
        elif case in ("check", "run", "drain"):
            env.set_pauses(0.0 if case == "check" else 0.2)
            f = await env.start_frame(40, 32, 8, 2, 0, [8, 16], 0)
            if case != "check":
                await ClockCycles(dut.clk_i, rng.randint(100, 400))
            await env.wr(R.CTRL, R.CTRL_SOFT_RESET_MASK)
            if case == "drain":
                await wait_state(dut, (ST_DRAIN,))
                await env.wr(R.CTRL, R.CTRL_SOFT_RESET_MASK)
        elif case == "start+soft":
            img = make_image(rng, 40, 32)
            env.render.image = img
            env.ram.write(0, bytes([FILL]) * MEM)
            fbs, srcs = await env.program(40, 32, 8, 2, 0, [8, 16], 0)
            await env.wr(R.CTRL, R.CTRL_START_MASK | R.CTRL_SOFT_RESET_MASK)     # both in one write
            f = dict(img=img, W=40, H=32, tile=8, levels=2, metric=0, thr=[8, 16], gain=0, src_en=1,
                     fb_stride=fbs, src_stride=srcs)
        elif case == "done":
            f = await env.start_frame(20, 12, 8, 2, 0, [8, 16], 0)
            st = await env.wait_idle()
            assert st & R.STATUS_DONE_MASK
            await env.wr(R.CTRL, R.CTRL_SOFT_RESET_MASK)
        elif case == "refused":
            env.ram.write(0, bytes([FILL]) * MEM)
            await env.program(20, 12, 12, 2, 0, [8, 16], 0)
            await env.wr(R.CTRL, R.CTRL_START_MASK)
            await ClockCycles(dut.clk_i, 40)
            assert (await env.rd(R.STATUS)) & R.STATUS_CFG_ERR_MASK
            await env.wr(R.STATUS, R.STATUS_CFG_ERR_MASK)
            await env.wr(R.CTRL, R.CTRL_SOFT_RESET_MASK)
        st = await env.wait_idle()
        assert not st & (R.STATUS_BUSY_MASK | R.STATUS_DONE_MASK | R.STATUS_ERROR_MASK), f"{case}: STATUS {st:#x}"
        while env.render.pending:
            await ClockCycles(dut.clk_i, 16)
        if f is not None:
            env.check_memory(f, exact=(case == "done"))
        dut._log.info("soft reset %s: STATUS %#x, states seen so far %s", case, st, sorted(seen))
        await env.frame(rng.randint(9, 33), rng.randint(3, 21), rng.choice(tiles_built()), 2, 0, [8, 16], 0)
    assert {ST_IDLE, ST_RUN, ST_DRAIN} <= seen and seen & {ST_SAMPLE, ST_CHECK}, f"states seen {sorted(seen)}"


@cocotb.test()
async def test_hard_reset_mid_burst(dut):
    """rst_ni low at a random cycle in the middle of a write burst (a W beat offered, not the
    last of its burst), for 1..5 cycles; the memory and register models are reset with it, the
    rendering model forgets its requests. Afterwards every register reads its reset value,
    nothing was written outside the planes, and the next frame is bit-exact."""
    env, rng = await setup(dut, 21)
    reset_values = await snapshot(env)
    for k in range(3):
        env.set_pauses(rng.choice((0.0, 0.2, 0.5)))
        # tiles of 16 or 32: rows of 64 or 128 bytes, bursts of two or more beats on every bus
        f = await env.start_frame(48, 32, rng.choice([t for t in tiles_built() if t >= 16]), 2, 0, [8, 16], 0)
        await ClockCycles(dut.clk_i, rng.randint(0, 150))
        for _ in range(100000):
            await RisingEdge(dut.clk_i)
            if int(dut.m_axi_wvalid.value) and not int(dut.m_axi_wlast.value):
                break
        else:
            raise AssertionError("no burst of two or more beats")
        for _ in range(rng.randint(0, 2)):
            await ClockCycles(dut.clk_i, 1, rising=False)
        dut.rst_ni.value = 0
        env.render.flush = True
        await ClockCycles(dut.clk_i, rng.randint(1, 5))
        dut.rst_ni.value = 1
        await ClockCycles(dut.clk_i, 4)
        env.render.flush = True
        await ClockCycles(dut.clk_i, 2)
        assert int(dut.irq_o.value) == 0
        regs = await snapshot(env)
        assert regs == reset_values, {hex(a): (reset_values[a], regs[a]) for a in regs if regs[a] != reset_values[a]}
        env.check_memory(f, exact=False)
        dut._log.info("hard reset %d mid burst: registers at reset values, nothing outside the planes", k)
        await env.frame(rng.randint(9, 40), rng.randint(3, 30), rng.choice((8, 16, 32)), 2, 0, [8, 16], 0)
