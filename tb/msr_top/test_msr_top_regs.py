"""msr_top: the register block: every bad register value refused (error code, nothing started,
nothing written), addresses outside the map, writes while a frame runs."""
from __future__ import annotations

import cocotb
from cocotb.triggers import ClockCycles, RisingEdge

from msr_flow import regs as R
from msr_top_env import (
    MEM, FILL, FB_BASE, SRC_BASE, ERR_FRAME_SIZE, ERR_TILE, ERR_LEVELS, ERR_FB_STRIDE, ERR_FB_BASE,
    ERR_SRC_STRIDE, ERR_SRC_BASE, ERR_FB_WRAP, ERR_SRC_WRAP, ERR_OVERLAP, ERR_RULE, SLVERR,
    REG_ADDRS, make_image, setup, expect_refused, snapshot)


@cocotb.test()
async def test_bad_registers(dut):
    env, rng = await setup(dut, 12)
    env.set_pauses(0.2)
    good = dict(W=20, H=10, tile=16, levels=2, metric=0, thr=[8, 16], gain=0)
    cases = [  # (what, register overrides, expected code)
        ("width 0", dict(W=0), ERR_FRAME_SIZE), ("width 4097", dict(W=4097), ERR_FRAME_SIZE),
        ("width 8191", dict(W=8191), ERR_FRAME_SIZE), ("height 0", dict(H=0), ERR_FRAME_SIZE),
        ("height 4097", dict(H=4097), ERR_FRAME_SIZE),
        ("tile 0", dict(tile=0), ERR_TILE), ("tile 12", dict(tile=12), ERR_TILE), ("tile 4", dict(tile=4), ERR_TILE),
        ("tile 63", dict(tile=63), ERR_TILE), ("tile 24", dict(tile=24), ERR_TILE),
        ("levels 0", dict(levels=0), ERR_LEVELS),
        ("fb stride short", dict(fb_stride=4 * 20 - 4), ERR_FB_STRIDE),
        ("fb stride 0", dict(fb_stride=0), ERR_FB_STRIDE),
        ("fb stride unaligned", dict(fb_stride=4 * 20 + 2), ERR_FB_STRIDE),
        ("fb base +1", dict(fb_base=FB_BASE + 1), ERR_FB_BASE), ("fb base +2", dict(fb_base=FB_BASE + 2), ERR_FB_BASE),
        ("src stride short", dict(src_stride=16), ERR_SRC_STRIDE),
        ("src stride unaligned", dict(src_stride=22), ERR_SRC_STRIDE),
        ("src base +3", dict(src_base=SRC_BASE + 3), ERR_SRC_BASE),
        ("fb plane wraps past 4 GiB", dict(fb_base=0xFFFFFF00), ERR_FB_WRAP),
        ("fb plane wraps by its stride", dict(fb_stride=0x20000000), ERR_FB_WRAP),
        ("src plane wraps past 4 GiB", dict(src_base=0xFFFFFFF0), ERR_SRC_WRAP),
        ("planes overlap", dict(src_base=FB_BASE + 64), ERR_OVERLAP),
        ("src plane around the fb plane", dict(src_base=FB_BASE - 4, src_stride=1 << 16), ERR_OVERLAP),
        ("rule 2", dict(rule=2), ERR_RULE), ("rule 3", dict(rule=3), ERR_RULE),
        # the first failing check in the order of the codes: the rule's comes last
        ("rule 3 and levels 0", dict(rule=3, levels=0), ERR_LEVELS),
        ("rule 2 and planes overlap", dict(rule=2, src_base=FB_BASE + 64), ERR_OVERLAP),
    ]
    env.ram.write(0, bytes([FILL]) * MEM)
    for what, over, code in cases:
        cfg = dict(good)
        regs = {k: over.pop(k) for k in list(over) if k in ("fb_base", "fb_stride", "src_base", "src_stride", "rule")}
        cfg.update(over)
        env.render.requests = []
        await env.program(cfg["W"], cfg["H"], cfg["tile"], cfg["levels"], cfg["metric"], cfg["thr"], cfg["gain"],
                          **regs)
        await expect_refused(dut, env, code, what)
    # A refused START raises the interrupt while IRQ_EN; CFG_ERR is write-1-to-clear.
    await env.wr(R.CTRL, R.CTRL_IRQ_EN_MASK)
    await RisingEdge(dut.clk_i)
    assert int(dut.irq_o.value) == 1, "no interrupt on a configuration error"
    await env.wr(R.STATUS, R.STATUS_CFG_ERR_MASK)
    await RisingEdge(dut.clk_i)
    assert int(dut.irq_o.value) == 0 and not (await env.rd(R.STATUS)) & R.STATUS_CFG_ERR_MASK
    await env.wr(R.CTRL, 0)
    # The source-map checks apply only when the plane is enabled.
    env.render.image = make_image(rng, 4, 2)
    await env.program(4, 2, 8, 1, 0, [8], 0, src_en=0, src_stride=1, src_base=3)
    await env.wr(R.CTRL, R.CTRL_START_MASK)
    st = await env.wait_idle()
    assert st & R.STATUS_DONE_MASK and not st & R.STATUS_ERROR_MASK, f"STATUS {st:#x}"
    # A good START after errors clears the code and renders correctly.
    await env.frame(**{**good, "W": 19})


@cocotb.test()
async def test_bad_register_address(dut):
    """Reads and writes of words off the register map: SLVERR, nothing changed (every register
    read back the same), nothing started or written; idle and while a frame runs."""
    env, rng = await setup(dut, 18)
    env.set_pauses(0.2)
    regs = set(REG_ADDRS)
    bad = [a for a in range(0, 0x80, 4) if a not in regs]
    assert bad, "no free word in the map"
    await env.program(30, 20, 16, 2, 0, [8, 16], 0)
    env.ram.write(0, bytes([FILL]) * MEM)
    before = await snapshot(env)
    for a in bad:
        w = await env.lite.write(a, (0xFFFFFFFF).to_bytes(4, "little"))
        r = await env.lite.read(a, 4)
        assert int(w.resp) == SLVERR and int(r.resp) == SLVERR, f"{a:#x}: write {w.resp}, read {r.resp}"
    after = await snapshot(env)
    assert after == before, {hex(a): (before[a], after[a]) for a in before if before[a] != after[a]}
    assert not env.render.requests and set(env.ram.read(0, MEM)) == {FILL}
    # While busy: SLVERR again, the frame is not disturbed.
    f = await env.start_frame(30, 20, 16, 2, 0, [8, 16], 0)
    for a in rng.sample(bad, min(4, len(bad))):
        w = await env.lite.write(a, rng.randrange(1 << 32).to_bytes(4, "little"))
        r = await env.lite.read(a, 4)
        assert int(w.resp) == SLVERR and int(r.resp) == SLVERR
    st = await env.wait_idle()
    assert st & R.STATUS_DONE_MASK and not st & R.STATUS_ERROR_MASK, f"STATUS {st:#x}"
    env.check_memory(f)
    await env.frame(19, 11, 8, 1, 1, [12], 0)


@cocotb.test()
async def test_writes_while_busy(dut):
    """START and every configuration register written while a frame runs: the running frame
    keeps the configuration sampled at its START (bit-exact, nothing outside its planes), the
    second START is ignored (nothing starts after DONE); the values written while busy are
    kept and the next START renders them bit-exact."""
    env, rng = await setup(dut, 19)
    for _ in range(2):
        env.set_pauses(rng.choice((0.0, 0.3)))
        f = await env.start_frame(48, 40, rng.choice((8, 16)), 2, 0, [8, 16], 0)
        await ClockCycles(dut.clk_i, rng.randint(60, 300))
        assert (await env.rd(R.STATUS)) & R.STATUS_BUSY_MASK, "frame over before the writes"
        await env.wr(R.CTRL, R.CTRL_START_MASK | R.CTRL_IRQ_EN_MASK)
        c2 = dict(W=rng.randint(9, 30), H=rng.randint(5, 20), tile=rng.choice((8, 32)), levels=3, metric=1,
                  thr=[rng.randrange(40) for _ in range(3)], gain=rng.choice((0, 90)))
        src_en2 = rng.randint(0, 1)
        fb2, src2 = await env.program(c2["W"], c2["H"], c2["tile"], c2["levels"], c2["metric"], c2["thr"],
                                      c2["gain"], src_en=src_en2)
        await env.wr(R.CTRL, R.CTRL_START_MASK | R.CTRL_IRQ_EN_MASK)
        assert (await env.rd(R.STATUS)) & R.STATUS_BUSY_MASK, "frame over before the writes ended"
        st = await env.wait_idle()
        assert st & R.STATUS_DONE_MASK and not st & R.STATUS_ERROR_MASK, f"STATUS {st:#x}"
        gold = env.check_memory(f)
        assert len(env.render.requests) == gold.stats["traced"]
        n = len(env.render.requests)
        await ClockCycles(dut.clk_i, 300)
        assert not (await env.rd(R.STATUS)) & R.STATUS_BUSY_MASK and len(env.render.requests) == n, \
            "a START written while busy started a frame later"
        # The next START renders what was written while busy.
        img = make_image(rng, c2["W"], c2["H"])
        env.render.image, env.render.requests = img, []
        env.ram.write(0, bytes([FILL]) * MEM)
        await env.wr(R.CTRL, R.CTRL_START_MASK | R.CTRL_IRQ_EN_MASK)
        st = await env.wait_idle()
        assert st & R.STATUS_DONE_MASK and not st & R.STATUS_ERROR_MASK, f"STATUS {st:#x}"
        gold = env.check_memory(dict(img=img, src_en=src_en2, fb_stride=fb2, src_stride=src2, **c2))
        assert len(env.render.requests) == gold.stats["traced"]
        await env.wr(R.STATUS, R.STATUS_DONE_MASK)
