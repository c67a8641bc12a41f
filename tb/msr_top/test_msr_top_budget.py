"""msr_top: the ray budget through the registers (docs/budget.md)."""
from __future__ import annotations

import cocotb
from cocotb.triggers import ClockCycles

from msr_flow import regs as R
from msr_top_env import MEM, FILL, ERR_BUDGET, ERR_PROFILE, BUDGET_EN, make_image, setup, expect_refused


async def program_budget(env, pixels, scale_init=256, prior_shift=6, seeded=0):
    await env.wr(R.BUDGET, pixels)
    await env.wr(R.BUDGET_CTRL, (scale_init << R.BUDGET_CTRL_SCALE_INIT_LSB)
                 | (prior_shift << R.BUDGET_CTRL_PRIOR_SHIFT_LSB) | (seeded << R.BUDGET_CTRL_SEEDED_LSB))


@cocotb.test()
async def test_budget(dut):
    """The ray budget (docs/budget.md) through the registers: a sequence of frames, the first
    with the first-frame law, each later one seeded as a driver would (SCALE_INIT = SCALE_OUT,
    SEEDED = 1), bit-exact with msr_model.budget.select_budget (pixels, source map, render
    requests) and SCALE_OUT its; a budget below the initial grid refused (14), a seeded frame
    after a frame of another tile-row count refused (15), BUDGET 0 the frame of algorithm.md.
    In a top built without the controller any budget is refused with 14."""
    from msr_model import Params
    from msr_model.budget import BudgetConfig, grid_count
    env, rng = await setup(dut, 31)
    env.set_pauses(0.1)
    if not BUDGET_EN:
        env.ram.write(0, bytes([FILL]) * MEM)
        await env.program(24, 24, 8, 2, 0, [8, 16], 0)
        await program_budget(env, 300)
        await expect_refused(dut, env, ERR_BUDGET, "a budget in a top without the controller")
        return
    # 9 tile rows (dispatched interleaved at S = 2), 5 (row-major), 17 (S = 4, the bottom row,
    # 6 pixels high, fifth in the order)
    for W, H, tile, levels, thr, gain, frac in ((48, 72, 8, 2, [6, 12], 0, 0.35), (40, 40, 8, 3, [8, 16, 32], 60, 0.2),
                                                (24, 134, 8, 2, [6, 12], 30, 0.3)):
        params = Params(tile=tile, levels=levels, thr=tuple(thr), fov_gain=gain)
        G = grid_count(W, H, params)
        budget = G + int((W * H - G) * frac)
        cfg = BudgetConfig(budget=budget)
        for k in range(3):
            env.render.ready_p = rng.choice((1.0, 0.5))
            env.render.max_lat = rng.choice((1, 30))
            await program_budget(env, budget, cfg.scale_init, cfg.prior_shift, int(cfg.profile is not None))
            f = await env.start_frame(W, H, tile, levels, 0, thr, gain)
            st = await env.wait_idle()
            assert st & R.STATUS_DONE_MASK and (st & R.STATUS_ERROR_MASK) == 0, f"budget frame {k}: STATUS {st:#x}"
            gold = env.check_memory(f, budget=cfg)
            bc = gold.stats["budget_control"]
            assert len(env.render.requests) == gold.stats["traced"]
            ctrl = await env.rd(R.BUDGET_CTRL)
            scale_out = (ctrl & R.BUDGET_CTRL_SCALE_OUT_MASK) >> R.BUDGET_CTRL_SCALE_OUT_LSB
            assert ctrl & R.BUDGET_CTRL_SCALE_OUT_VALID_MASK, f"BUDGET_CTRL {ctrl:#x}: SCALE_OUT not valid"
            assert scale_out == bc["scale_out"], f"SCALE_OUT {scale_out}, golden {bc['scale_out']}"
            dut._log.info("budget %d (%dx%d T%d L%d) frame %d: traced %d, scales %s, SCALE_OUT %d: bit-exact",
                          budget, W, H, tile, levels, k, gold.stats["traced"], bc["scale_per_row"], scale_out)
            cfg = BudgetConfig(budget=budget, scale_init=scale_out, profile=tuple(bc["activity_per_row"]),
                               profile_scales=tuple(bc["scale_per_row"]))
            await env.wr(R.STATUS, R.STATUS_DONE_MASK)
    # a soft reset in the middle of a budget frame (msr_budget's clear): idle, nothing pending,
    # and the next budget frame, first-frame law, bit-exact
    params = Params(tile=8, levels=2, thr=(6, 12))
    budget = grid_count(48, 72, params) + 600
    env.render.image = make_image(rng, 48, 72)
    await program_budget(env, budget)
    await env.program(48, 72, 8, 2, 0, [6, 12], 0)
    await env.wr(R.CTRL, R.CTRL_START_MASK)
    await ClockCycles(dut.clk_i, 400)
    assert await env.rd(R.STATUS) & R.STATUS_BUSY_MASK, "budget frame finished before the soft reset"
    await env.wr(R.CTRL, R.CTRL_SOFT_RESET_MASK)
    st = await env.wait_idle()
    assert st == 0, f"STATUS after a soft reset in a budget frame {st:#x}: want idle, not done, no error"
    assert not env.render.pending, "cleared with render responses outstanding"
    env.render.requests = []
    await program_budget(env, budget)
    f = await env.start_frame(48, 72, 8, 2, 0, [6, 12], 0)
    st = await env.wait_idle()
    assert st & R.STATUS_DONE_MASK and (st & R.STATUS_ERROR_MASK) == 0, f"after the reset: STATUS {st:#x}"
    env.check_memory(f, budget=BudgetConfig(budget=budget))
    await env.wr(R.STATUS, R.STATUS_DONE_MASK)
    # refused: below the grid; seeded after a frame with another number of tile rows
    env.ram.write(0, bytes([FILL]) * MEM)
    env.render.requests = []
    await env.program(24, 24, 8, 2, 0, [8, 16], 0)
    G = grid_count(24, 24, Params(tile=8, levels=2, thr=(8, 16)))
    await program_budget(env, G - 1)
    await expect_refused(dut, env, ERR_BUDGET, "a budget one below the initial grid")
    await program_budget(env, G, seeded=1)
    await expect_refused(dut, env, ERR_PROFILE, "seeded after a frame of 5 tile rows, this one has 3")
    # the grid itself is accepted (first-frame law)
    await program_budget(env, G)
    f = await env.start_frame(24, 24, 8, 2, 0, [8, 16], 0)
    st = await env.wait_idle()
    assert st & R.STATUS_DONE_MASK and (st & R.STATUS_ERROR_MASK) == 0, f"budget = grid: STATUS {st:#x}"
    env.check_memory(f, budget=BudgetConfig(budget=G))
    # budget off again: the frame of algorithm.md
    await program_budget(env, 0)
    await env.frame(30, 20, 16, 2, 0, [8, 16], 0)
