"""Small cocotb helpers shared by the RTL unit tests.

Timing convention (simulator independent): the testbench writes every input right after a
falling clock edge, then waits for ReadOnly and samples the DUT's outputs; what it samples
there is what the next rising edge will act on, so a handshake "valid && ready" seen in
ReadOnly is a transfer at that rising edge."""
from __future__ import annotations

import os
import random
import re
from pathlib import Path

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, ReadOnly, RisingEdge, Timer


def pack_rgb(c) -> int:
    r, g, b = (int(v) for v in c)
    return (r << 16) | (g << 8) | b


def unpack_rgb(v: int) -> tuple[int, int, int]:
    v = int(v)
    return ((v >> 16) & 0xFF, (v >> 8) & 0xFF, v & 0xFF)


def seeded_rng(dut, default: int) -> random.Random:
    """The bench's random stream: SEED from the environment replaces the default seed; logged
    so a failure can be replayed (msr_runner prints the rerun command)."""
    dut._log.info("SEED %s", os.environ.get("SEED", "unset"))
    return random.Random(int(os.environ["SEED"]) if os.environ.get("SEED") else default)


async def start_clock_and_reset(dut, idle_inputs: dict, cycles: int = 3) -> None:
    """10 ns clock on clk_i, inputs to their idle values, rst_ni low for a few cycles. The reset
    is low before the first clock edge: with a random initial state (MSR_RAND_RESET=1) rst_ni
    starts random, and an edge before the reset would check random state."""
    dut.rst_ni.value = 0
    for name, val in idle_inputs.items():
        getattr(dut, name).value = val
    await Timer(1, unit="ns")
    cocotb.start_soon(Clock(dut.clk_i, 10, unit="ns").start())
    for _ in range(cycles):
        await RisingEdge(dut.clk_i)
    await FallingEdge(dut.clk_i)
    dut.rst_ni.value = 1


async def next_cycle() -> None:
    """From ReadOnly of one cycle to the write window (falling edge) of the next."""
    await FallingEdge(cocotb.top.clk_i)


async def settle() -> None:
    await ReadOnly()


async def clear_pulse(dut) -> None:
    """clear_i high across one rising edge, low again after it; returns in that cycle's
    ReadOnly, where the cleared state can be sampled."""
    dut.clear_i.value = 1
    await RisingEdge(dut.clk_i)
    dut.clear_i.value = 0
    await ReadOnly()


async def stream(dut, rng: random.Random, n: int, drive, check, p_valid: float, p_ready: float) -> None:
    """n items through a valid/ready pipeline (valid_i/ready_o in, valid_o/ready_i out), from
    the write window of a cycle: each cycle item `sent` is offered with probability p_valid
    (drive(sent) writes its inputs; an item not taken is offered again) and the output is
    taken with probability p_ready (check(got) reads the got-th result). Returns once n
    results were checked."""
    sent = got = 0
    while got < n:
        if sent < n and rng.random() < p_valid:
            dut.valid_i.value = 1
            drive(sent)
        else:
            dut.valid_i.value = 0
        dut.ready_i.value = int(rng.random() < p_ready)
        await settle()
        if dut.valid_i.value and dut.ready_o.value:
            sent += 1
        if dut.valid_o.value and dut.ready_i.value:
            check(got)
            got += 1
        await next_cycle()


def rtl_reciprocals(src: Path, bits: int) -> tuple[int, dict[int, int]]:
    """An interpolation unit's division by g as the RTL source has it: its SHIFT and the
    case table of RECIP[g] (`4'dG: return <bits>'dR;`), read from the file, not copied."""
    text = Path(src).read_text()
    shift = int(re.search(r"localparam int unsigned SHIFT\s*=\s*(\d+)", text).group(1))
    table = {int(g): int(v) for g, v in re.findall(rf"4'd(\d):\s*return {bits}'d(\d+);", text)}
    return shift, table

