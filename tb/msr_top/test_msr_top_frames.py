"""msr_top: frames bit-exact with the golden model: random small frames and configurations
(pixels, source map, counters, render requests, the interrupt) and the decision rules a top
carries (CONFIG.RULE)."""
from __future__ import annotations

import cocotb
from cocotb.triggers import RisingEdge

from msr_flow import regs as R
from msr_top_env import MEM, FILL, ERR_RULE, ERR_TILE, LINDILATE, TILE_LIMIT, setup, random_config, expect_refused


@cocotb.test()
async def test_random_frames(dut):
    env, rng = await setup(dut, 11)
    # Fixed corner cases first, then random ones; pauses on every channel vary per frame.
    configs = [dict(W=37, H=21, tile=16, levels=2, metric=0, thr=[8, 16], gain=0),
               dict(W=1, H=1, tile=8, levels=1, metric=0, thr=[8], gain=0),
               dict(W=33, H=9, tile=min(32, TILE_LIMIT), levels=3, metric=1, thr=[4, 8, 16], gain=100)]
    configs += [random_config(rng) for _ in range(5)]
    for i, c in enumerate(configs):
        env.set_pauses(rng.choice((0.0, 0.2, 0.5)))
        env.render.ready_p = rng.choice((1.0, 0.7, 0.3))
        env.render.max_lat = rng.choice((1, 8, 40))
        await env.frame(c["W"], c["H"], c["tile"], c["levels"], c["metric"], c["thr"], c["gain"],
                        src_en=int(i % 4 != 3))


@cocotb.test()
async def test_rule(dut):
    """CONFIG.RULE: sampled at START into every tile descriptor (the descriptor's MSB, seen at
    the tile hand-out; a rule written during the check does not reach the frame), frames in
    lindilate and patent back to back, each bit-exact with the golden model under its rule.
    In a patent-only build (LINDILATE 0): RULE 1 is refused at START (ERR_RULE, nothing
    rendered or written), and patent frames around the refusal are bit-exact. In a build whose
    tile buffers hold smaller tiles (TILE_LIMIT below 32), a larger T is refused the same way
    (ERR_TILE) and the largest T it holds renders bit-exact after the refusal."""
    env, rng = await setup(dut, 23)
    if not LINDILATE:
        await env.frame(20, 10, 8, 2, 0, [8, 16], 0, rule=0)
        env.render.requests = []
        env.ram.write(0, bytes([FILL]) * MEM)
        await env.program(20, 10, 8, 2, 0, [8, 16], 0, rule=1)
        await expect_refused(dut, env, ERR_RULE, "rule 1 in a patent-only top")
        if TILE_LIMIT < 32:
            for t in (t for t in (16, 32) if t > TILE_LIMIT):
                await env.program(40, 40, t, 2, 0, [8, 16], 0, rule=0)
                await expect_refused(dut, env, ERR_TILE, f"T {t} in a top of TILE_LIMIT {TILE_LIMIT}")
            await env.frame(41, 35, TILE_LIMIT, 3, 1, [4, 8, 16], 30, rule=0)
        for _ in range(2):
            c = random_config(rng)
            await env.frame(c["W"], c["H"], c["tile"], c["levels"], c["metric"], c["thr"], c["gain"], rule=0)
        return
    seen = []

    async def monitor():
        while True:
            await RisingEdge(dut.clk_i)
            if int(dut.dbg_desc_fire_o.value):
                v = dut.desc.value
                seen.append((int(v) >> (len(v) - 1)) & 1)
    cocotb.start_soon(monitor())
    f = await env.start_frame(40, 24, 8, 2, 0, [8, 16], 0, rule=1)
    await env.wr(R.CONFIG, (8 << R.CONFIG_TILE_LSB) | (2 << R.CONFIG_LEVELS_LSB))   # rule 0, during the check
    st = await env.wait_idle()
    assert st & R.STATUS_DONE_MASK and not st & R.STATUS_ERROR_MASK, f"STATUS {st:#x}"
    assert len(seen) == 15 and set(seen) == {1}, f"rule 1: {len(seen)} descriptors carried {sorted(set(seen))}"
    env.check_memory(f)
    for rule in (0, 1, 1, 0):
        c = random_config(rng)
        env.set_pauses(rng.choice((0.0, 0.2)))
        seen.clear()
        await env.frame(c["W"], c["H"], c["tile"], c["levels"], c["metric"], c["thr"], c["gain"], rule=rule)
        assert seen and set(seen) == {rule}, f"rule {rule}: descriptors carried {sorted(set(seen))}"
