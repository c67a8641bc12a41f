"""msr_top: the whole accelerator against the golden model (the pytest entry points).

Each build runs the cocotb tests of every module in COCOTB_MODULES in one simulation:
test_msr_top_frames (random frames and configurations bit-exact with msr_model.golden.select,
the decision rules), test_msr_top_regs (bad register values, addresses, writes while busy),
test_msr_top_resets (soft and hard resets anywhere in a frame), test_msr_top_errors (watchdog,
memory errors, rendering-unit faults), test_msr_top_budget (the ray budget), test_msr_top_gaze
(the gaze point: refused outside the frame, frames around random gaze points), and this module's
test_soak (make soak only). What they share is msr_top_env (the bench: Env, RenderModel, setup).
"""
from __future__ import annotations

import os
from pathlib import Path

import cocotb
import pytest
from cocotb.triggers import ClockCycles

from msr_flow import regs as R
from msr_top_env import make_image, random_config, setup

HERE = Path(__file__).resolve().parent
# cocotb imports these from HERE (the runner's test_dir); make soak runs test_soak from this one
COCOTB_MODULES = ("test_msr_top_frames", "test_msr_top_regs", "test_msr_top_resets", "test_msr_top_errors",
                  "test_msr_top_budget", "test_msr_top_gaze", "test_msr_top")


@cocotb.test(skip=not os.environ.get("SOAK_SECONDS"))
async def test_soak(dut):
    """make soak (scripts/soak.py): random configurations, back-pressure and frames until
    SOAK_SECONDS of wall time, now and then a soft reset in the middle of a frame; every frame
    checked as in test_random_frames. Each checked frame is a JSON line in MSR_SOAK_LOG."""
    import json
    import time

    env, rng = await setup(dut, 14)
    deadline = time.monotonic() + float(os.environ["SOAK_SECONDS"])
    log = os.environ.get("MSR_SOAK_LOG")
    frames = resets = 0
    while time.monotonic() < deadline:
        c = random_config(rng)
        env.set_pauses(rng.choice((0.0, 0.1, 0.3, 0.6)))
        env.render.ready_p = rng.choice((1.0, 0.8, 0.5, 0.2))
        env.render.max_lat = rng.choice((1, 4, 16, 64))
        if rng.random() < 0.15:
            # a soft reset at a random point of a frame (it may be over already)
            env.render.image = make_image(rng, c["W"], c["H"])
            await env.program(c["W"], c["H"], c["tile"], c["levels"], c["metric"], c["thr"], c["gain"])
            await env.wr(R.CTRL, R.CTRL_START_MASK)
            await ClockCycles(dut.clk_i, rng.randint(1, 400))
            await env.wr(R.CTRL, R.CTRL_SOFT_RESET_MASK)
            st = await env.wait_idle()
            assert st == 0, f"STATUS after soft reset {st:#x}: want idle, not done, no error"
            resets += 1
            c = random_config(rng)
        src_en = int(rng.random() < 0.8)
        await env.frame(c["W"], c["H"], c["tile"], c["levels"], c["metric"], c["thr"], c["gain"], src_en=src_en)
        frames += 1
        if log:
            with open(log, "a") as fh:
                fh.write(json.dumps({"seed": os.environ.get("SEED"), "frame": frames, "src_en": src_en, **c}) + "\n")
    dut._log.info("SOAK_FRAMES %d SOFT_RESETS %d", frames, resets)



@pytest.mark.parametrize("engines,outstanding,ctx,width", [(4, 16, 8, 256), (3, 4, 3, 64)])
def test_msr_top(engines, outstanding, ctx, width):
    from msr_flow.runner import checked_sources, run_cocotb
    # The AXI protocol checkers bound to the writer and the register block (rtl/checkers), in
    # the build folder (_chk) that scripts/soak.py uses too: make test's short soak reuses it.
    run_cocotb("msr_top", ",".join(COCOTB_MODULES), HERE,
               {"NUM_ENGINES": engines, "MAX_OUTSTANDING": outstanding, "NUM_CTX": ctx, "AXI_DATA_W": width},
               f"e{engines}_o{outstanding}_c{ctx}_w{width}_chk", extra_env={"NUM_ENGINES": str(engines)},
               sources=checked_sources())


def test_msr_top_patent_only():
    """msr_top built with LINDILATE 0 (the rules a top carries) and tile buffers of 16 x 16
    (TILE_LIMIT 16): test_rule's patent-only branch (RULE 1 and T 32 refused, patent frames
    bit-exact)."""
    from msr_flow.filelist import rtl_sources
    from msr_flow.runner import run_cocotb
    run_cocotb("msr_top", ",".join(COCOTB_MODULES), HERE,
               {"NUM_ENGINES": 2, "MAX_OUTSTANDING": 16, "NUM_CTX": 3, "AXI_DATA_W": 256, "LINDILATE": 0,
                "TILE_LIMIT": 16},
               "patent_only_t16", extra_env={"NUM_ENGINES": "2", "LINDILATE": "0", "TILE_LIMIT": "16"},
               sources=rtl_sources(),
               testcase="test_rule")


def test_msr_top_macro_cycle():
    """msr_top built as a slow SRAM macro needs it: reads of 4 clocks (RD_LAT), a port's address
    once per 5 (BUF_CYCLE: 3 streamers per engine, rows of tiles interleaved), 16 x 16 buffers
    (TILE_LIMIT): random frames bit-exact under memory pauses and render back-pressure, and soft
    resets in every state (the streamers and the row merge cleared mid-row)."""
    from msr_flow.filelist import rtl_sources
    from msr_flow.runner import run_cocotb
    run_cocotb("msr_top", ",".join(COCOTB_MODULES), HERE,
               {"NUM_ENGINES": 2, "MAX_OUTSTANDING": 16, "NUM_CTX": 5, "AXI_DATA_W": 256, "RD_LAT": 4,
                "BUF_CYCLE": 5, "TILE_LIMIT": 16},
               "macro_cycle", extra_env={"NUM_ENGINES": "2", "TILE_LIMIT": "16"}, sources=rtl_sources(),
               testcase="test_random_frames,test_soft_reset,test_soft_reset_states")


def test_msr_top_budget():
    """msr_top built with the ray-budget controller (BUDGET_EN 1): test_budget's sequences and
    refusals, and random frames with the budget off bit-exact as without it."""
    from msr_flow.filelist import rtl_sources
    from msr_flow.runner import run_cocotb
    run_cocotb("msr_top", ",".join(COCOTB_MODULES), HERE,
               {"NUM_ENGINES": 3, "MAX_OUTSTANDING": 16, "NUM_CTX": 3, "AXI_DATA_W": 64, "BUDGET_EN": 1},
               "budget", extra_env={"NUM_ENGINES": "3", "BUDGET_EN": "1"}, sources=rtl_sources(),
               testcase="test_budget,test_random_frames")
