"""rsp_check (the tile engine's tags and response check) against a Python model of the tags in
flight.

Random allocations (each with a random context, tile-buffer address and level) whenever a tag
is free, answered after a random delay in random order; now and then an answer is sent twice
in a row (a duplicate) or an answer arrives for a tag that is not in flight (stale). The
pipeline's own write (pipe_we_i on a random context) takes the context's port at random, and
the port of the answer's context is busy at random (port_ok_i low: a macro's cycle).
Checked every cycle: each accepted answer has exactly one outcome, in order: a write of the
entry its tag was allocated with and the answer's colour (the tag is then free), or a drop
(duplicates and stale answers); a write never meets the pipeline's write to the same context;
inflight_o is the model's count; a tag is never handed out while in flight; after a soft reset
every tag is free again within MAX_OUTSTANDING cycles."""
from __future__ import annotations

import os
import random
from pathlib import Path

import cocotb
import pytest

from msr_flow.runner import run_cocotb
from msr_tb import next_cycle, seeded_rng, settle, start_clock_and_reset

CTX_W, TADDR_W = 3, 10
IDLE = {"clear_i": 0, "rsp_valid_i": 0, "rsp_tag_i": 0, "rsp_rgb_i": 0, "alloc_i": 0, "alloc_ctx_i": 0,
        "alloc_addr_i": 0, "alloc_level_i": 0, "pipe_we_i": 0, "pipe_ctx_i": 0, "port_ok_i": 1}


async def wait_init(dut, n: int) -> None:
    """The tag walk after reset or clear: at most n + 1 cycles, nothing in flight, no tag offered."""
    for _ in range(n + 2):
        await settle()
        if not dut.init_o.value:
            await next_cycle()
            return
        assert not dut.tag_avail_o.value and int(dut.inflight_o.value) == 0
        await next_cycle()
    raise AssertionError("the tag walk did not end within MAX_OUTSTANDING cycles")


async def run(dut, rng: random.Random, n_tags: int, n_answers: int, p_pipe: float, p_odd: float):
    inflight = {}        # tag -> entry (ctx, addr, level): allocated, not yet written
    answered = set()     # tags whose answer is inside the unit
    due = []             # [cycle, tag, rgb]: answers to send
    outcomes = []        # expected outcomes of the accepted answers, in order
    rsp = None           # (tag, rgb, kind) on offer
    quiet = 0            # cycles without allocation (a duplicate or stale answer is inside)
    cycle = allocs = writes = drops = odd = 0
    while allocs < n_answers or inflight or rsp is not None:
        # ---- drive (write window) ----
        entry = (rng.randrange(1 << CTX_W), rng.randrange(1 << TADDR_W), rng.randrange(4))
        pipe_we, pipe_ctx = int(rng.random() < p_pipe), rng.randrange(1 << CTX_W)
        dut.alloc_ctx_i.value, dut.alloc_addr_i.value, dut.alloc_level_i.value = entry
        dut.pipe_we_i.value, dut.pipe_ctx_i.value = pipe_we, pipe_ctx
        port_ok = int(rng.random() < 0.8)
        dut.port_ok_i.value = port_ok
        if rsp is None:
            ready = [d for d in due if d[0] <= cycle]
            if ready and rng.random() < 0.7:
                d = rng.choice(ready)
                due.remove(d)
                rsp = (d[1], d[2], "ok")
            elif quiet == 0 and rng.random() < p_odd:
                idle = [t for t in range(n_tags) if t not in inflight]
                if idle:
                    rsp, quiet = (rng.choice(idle), rng.randrange(1 << 24), "stale"), 8
        dut.rsp_valid_i.value = int(rsp is not None)
        if rsp is not None:
            dut.rsp_tag_i.value, dut.rsp_rgb_i.value = rsp[0], rsp[1]
        # no allocation while a stale answer waits (it must name a tag that stays free)
        want = allocs < n_answers and quiet == 0 and rng.random() < 0.6
        alloc = want and bool(dut.tag_avail_o.value)      # a register: settled since the edge
        dut.alloc_i.value = int(alloc)
        # ---- sample (what the coming edge does) ----
        await settle()
        assert int(dut.inflight_o.value) == len(inflight), \
            f"cycle {cycle}: inflight_o {int(dut.inflight_o.value)}, model {len(inflight)}"
        freed = None
        if dut.drop_o.value:
            assert outcomes and outcomes[0][0] == "drop", f"cycle {cycle}: drop, want {outcomes[:1]}"
            outcomes.pop(0)
            drops += 1
        if dut.we_o.value:
            got = ((int(dut.wctx_o.value), int(dut.waddr_o.value), int(dut.wlevel_o.value)),
                   int(dut.wrgb_o.value))
            assert outcomes and outcomes[0][0] == "write" and outcomes[0][1:3] == got, \
                f"cycle {cycle}: write {got}, want {outcomes[:1]}"
            assert not (pipe_we and pipe_ctx == got[0][0]), f"cycle {cycle}: write meets the pipeline's"
            assert port_ok, f"cycle {cycle}: write while the context's port rests"
            freed = outcomes.pop(0)[3]
            writes += 1
        if alloc:
            tag = int(dut.free_tag_o.value)
            assert tag not in inflight, f"cycle {cycle}: tag {tag} handed out while in flight"
        if rsp is not None and dut.rsp_ready_o.value:
            t, rgb, kind = rsp
            rsp = None
            if kind == "ok":
                outcomes.append(("write", inflight[t], rgb, t))
                answered.add(t)
                if quiet == 0 and rng.random() < p_odd:     # the same answer again, right behind
                    rsp, quiet = (t, rgb, "dup"), 8
            else:
                outcomes.append(("drop",))
                odd += 1
        await next_cycle()
        # ---- the edge happened ----
        if freed is not None:
            del inflight[freed]
            answered.discard(freed)
        if alloc:
            inflight[tag] = entry
            due.append([cycle + 1 + rng.randint(0, 40), tag, rng.randrange(1 << 24)])
            allocs += 1
        dut.alloc_i.value = 0
        cycle += 1
        # an odd answer on offer keeps the pool quiet, and so does a clock with a resting port
        # (the answers ahead of it wait, so it reaches the tag lookup later)
        if (rsp is None or rsp[2] == "ok") and port_ok:
            quiet = max(0, quiet - 1)
        assert cycle < 100 * n_answers + 1000, f"timeout: {writes} writes, {drops} drops"
    for _ in range(6):          # the last odd answers leave
        await settle()
        if dut.drop_o.value:
            outcomes.pop(0)
            drops += 1
        await next_cycle()
    assert not outcomes and drops == odd, f"{odd} odd answers, {drops} dropped, left {outcomes}"
    return writes, drops


@cocotb.test()
async def random_answers(dut):
    rng = seeded_rng(dut, 21)
    n = int(os.environ["MAX_OUTSTANDING"])
    dut.pipe_we_i.value = 0
    dut.port_ok_i.value = 1
    await start_clock_and_reset(dut, IDLE)
    await wait_init(dut, n)
    for p_pipe, p_odd in ((0.0, 0.0), (0.3, 0.1), (0.8, 0.3)):
        writes, drops = await run(dut, rng, n, 400, p_pipe, p_odd)
        dut._log.info("pipe %.1f odd %.1f: %d writes, %d drops", p_pipe, p_odd, writes, drops)
        assert writes == 400
    # a soft reset with tags in flight: every tag free again within N cycles
    for _ in range(min(3, n)):
        dut.alloc_i.value = int(bool(dut.tag_avail_o.value))
        await next_cycle()
    dut.alloc_i.value = 0
    await settle()
    assert int(dut.inflight_o.value) > 0
    await next_cycle()
    dut.clear_i.value = 1
    await next_cycle()
    dut.clear_i.value = 0
    await wait_init(dut, n)
    await settle()
    assert int(dut.inflight_o.value) == 0 and not dut.tags_out_o.value


@pytest.mark.parametrize("max_out", [2, 16])
def test_rsp_check(max_out):
    run_cocotb("msr_rsp_check", "test_rsp_check", Path(__file__).parent,
               {"MAX_OUTSTANDING": max_out, "CTX_W": CTX_W}, extra_env={"MAX_OUTSTANDING": max_out})
