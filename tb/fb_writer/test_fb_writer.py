"""fb_writer: random frames written as tile rows (rows of different tiles interleaved as the
engines would), random pauses on AW, W and B, odd strides and bases so rows cross 4 KiB.
Checks every frame-buffer word and source byte, that nothing outside the frame is touched,
one burst per row part, no burst across 4 KiB, and the tile-done count."""
from __future__ import annotations

import itertools
import random
import sys
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))

import cocotb  # noqa: E402
from cocotb.clock import Clock  # noqa: E402
from cocotb.triggers import ClockCycles, RisingEdge, ReadOnly  # noqa: E402
from cocotbext.axi import AxiRamWrite, AxiWriteBus  # noqa: E402

TILE_ENC = {8: 0, 16: 1, 32: 2}
CODES = (0, 1, 2, 3, 17, 18, 19)
MEM = 1 << 20
FILL = 0xA5


def pause(rng, p):
    while True:
        yield int(rng.random() < p)


def row_stream(rng, W, H, T):
    """Tile rows of the frame, tiles interleaved at row granularity, each tile's rows in order."""
    tiles = []
    for y0 in range(0, H, T):
        for x0 in range(0, W, T):
            w, h = min(T, W - x0), min(T, H - y0)
            tiles.append([[(x0 + x, y0 + y, y == h - 1 and x == w - 1) for x in range(w)] for y in range(h)])
    active = []
    out = []
    while tiles or active:
        while tiles and len(active) < 4:
            active.append(tiles.pop(0))
        t = rng.choice(active)
        out.append(t.pop(0))
        if not t:
            active.remove(t)
    return out


async def run_frame(dut, ram, rng, W, H, T, fb_base, fb_stride, src_en, src_base, src_stride, gap_p):
    dut.width_i.value = W
    dut.tile_i.value = TILE_ENC[T]
    dut.fb_base_i.value = fb_base
    dut.fb_stride_i.value = fb_stride
    dut.src_en_i.value = src_en
    dut.src_base_i.value = src_base
    dut.src_stride_i.value = src_stride
    await RisingEdge(dut.clk_i)
    pixels = {}
    tiles_done = 0
    for row in row_stream(rng, W, H, T):
        for x, y, last in row:
            while rng.random() < gap_p:
                dut.pix_valid_i.value = 0
                await RisingEdge(dut.clk_i)
            rgb = (rng.randrange(256), rng.randrange(256), rng.randrange(256))
            code = rng.choice(CODES)
            pixels[(x, y)] = (rgb, code)
            dut.pix_valid_i.value = 1
            dut.pix_x_i.value = x
            dut.pix_y_i.value = y
            dut.pix_rgb_i.value = (rgb[0] << 16) | (rgb[1] << 8) | rgb[2]
            dut.pix_src_i.value = code
            dut.pix_last_i.value = int(last)
            for _ in range(5000):
                await ReadOnly()
                assert int(dut.pix_row_end_o.value) == int(x == row[-1][0]), f"row end at x={x}"
                hs = int(dut.pix_ready_o.value)
                tiles_done += int(dut.tile_done_o.value)
                await RisingEdge(dut.clk_i)
                if hs:
                    break
            else:
                raise AssertionError(f"pixel ({x},{y}) never taken")
    dut.pix_valid_i.value = 0
    for _ in range(20000):
        await RisingEdge(dut.clk_i)
        await ReadOnly()
        if int(dut.idle_o.value):
            break
    else:
        raise AssertionError("writer never idle")
    await RisingEdge(dut.clk_i)
    ntiles = len(range(0, W, T)) * len(range(0, H, T))
    assert tiles_done == ntiles, f"tile_done pulses {tiles_done}, want {ntiles}"
    mem = ram.read(0, MEM)
    touched = bytearray([0]) * MEM
    for (x, y), (rgb, code) in pixels.items():
        a = fb_base + y * fb_stride + 4 * x
        word = int.from_bytes(mem[a:a + 4], "little")
        assert word == (rgb[0] << 16) | (rgb[1] << 8) | rgb[2], f"pixel ({x},{y}) at {a:#x}: {word:#010x}"
        touched[a:a + 4] = b"\1\1\1\1"
        if src_en:
            s = src_base + y * src_stride + x
            assert mem[s] == code, f"source ({x},{y}) at {s:#x}: {mem[s]} want {code}"
            touched[s] = 1
    stray = [i for i in range(MEM) if not touched[i] and mem[i] != FILL]
    assert not stray, f"{len(stray)} bytes written outside the frame, first at {stray[0]:#x}"


async def aw_monitor(dut, log):
    """Every burst: INCR, 4-byte beats, never across a 4 KiB boundary."""
    while True:
        await RisingEdge(dut.clk_i)
        if int(dut.m_axi_awvalid.value) and int(dut.m_axi_awready.value):
            a, n = int(dut.m_axi_awaddr.value), int(dut.m_axi_awlen.value) + 1
            assert int(dut.m_axi_awsize.value) == 2 and int(dut.m_axi_awburst.value) == 1
            assert a % 4 == 0 and a >> 12 == (a + 4 * n - 1) >> 12, f"burst {a:#x}+{n} crosses 4 KiB"
            log.append((a, n))


@cocotb.test()
async def test_random_frames(dut):
    rng = random.Random(77)
    cocotb.start_soon(Clock(dut.clk_i, 10, unit="ns").start())
    dut.rst_ni.value = 0
    dut.clear_i.value = 0
    dut.pix_valid_i.value = 0
    ram = AxiRamWrite(AxiWriteBus.from_prefix(dut, "m_axi"), dut.clk_i, dut.rst_ni,
                      reset_active_level=False, size=MEM)
    await ClockCycles(dut.clk_i, 3)
    dut.rst_ni.value = 1
    bursts = []
    cocotb.start_soon(aw_monitor(dut, bursts))
    cases = [(40, 20, 8, 0x0FE0, 4 * 40 + 20, 1, 0x80FFC, 48, 0.0, 0.0),   # bursts across 4 KiB
             (33, 17, 16, 0x100, 4 * 33, 1, 0x90000, 36, 0.3, 0.5),
             (70, 9, 32, 0xFF0, 4 * 72, 0, 0, 0, 0.5, 0.2),
             (1, 1, 8, 0x4, 4, 1, 0x3FFC, 4, 0.0, 0.0)]
    for _ in range(3):
        W, H, T = rng.randint(1, 80), rng.randint(1, 40), rng.choice((8, 16, 32))
        cases.append((W, H, T, 4 * rng.randrange(0x10000 // 4), 4 * W + 4 * rng.randrange(8), rng.randint(0, 1),
                      0x80000 + 4 * rng.randrange(0x1000), (W + 3) // 4 * 4 + 4 * rng.randrange(4),
                      rng.random() * 0.6, rng.random() * 0.5))
    for W, H, T, fb_base, fb_stride, src_en, src_base, src_stride, chan_p, gap_p in cases:
        ram.write(0, bytes([FILL]) * MEM)
        ram.aw_channel.set_pause_generator(pause(rng, chan_p))
        ram.w_channel.set_pause_generator(pause(rng, chan_p))
        ram.b_channel.set_pause_generator(pause(rng, chan_p))
        bursts.clear()
        await run_frame(dut, ram, rng, W, H, T, fb_base, fb_stride, src_en, src_base, src_stride, gap_p)
        rows = sum(min(T, H - y0) for y0 in range(0, H, T)) * len(range(0, W, T))
        assert len(bursts) >= rows * (1 + src_en)
        dut._log.info("frame %dx%d T%d: %d bursts for %d rows", W, H, T, len(bursts), rows)


@pytest.mark.parametrize("max_out", [1, 8])
def test_fb_writer(max_out):
    from sys_tb import RTL, run_cocotb
    run_cocotb("fb_writer", "test_fb_writer", HERE, {"MAX_OUT": max_out}, f"o{max_out}",
               sources=[RTL / "msr_pkg.sv", RTL / "sys_fifo.sv", RTL / "fb_writer.sv"])
