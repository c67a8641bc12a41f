"""fbw_rowbuf: the frame-buffer writer's row buffers alone. Random frames dealt to NUM_IN
inputs (each whole tiles row-major, random gaps), odd bases and strides so rows start on any
lane of a wide beat; the bench is the address and W side: it takes complete rows at random
times, reads each row's beats back and frees the buffer. Checks the ring's order (pick),
every row's metadata (y, x0, length) against the frame, every pixel and code in its lane and
beat (the placement rule of the module header: word ow + l, lane mod WPB), backpressure
exactly when three rows are held, the tile-done pulses and idle at the end."""
from __future__ import annotations

from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent

import cocotb  # noqa: E402
from cocotb.triggers import FallingEdge, ReadOnly  # noqa: E402
from msr_tb import seeded_rng, start_clock_and_reset  # noqa: E402

TILE_ENC = {8: 0, 16: 1, 32: 2}
CODES = (0, 1, 2, 3, 16, 17, 18, 19)
NBUF = 3
CODE_W = 5


def pack(values, width):
    v = 0
    for i, x in enumerate(values):
        v |= x << (width * i)
    return v


def field(v, i, width):
    return (v >> (width * i)) & ((1 << width) - 1)


def pix_word(x, y, rgb, src, last):
    """pix_word_t (rtl/pkg/msr_pkg.sv), MSB first: x[12] y[12] rgb[24] src[8] last[1]."""
    return (x << 45) | (y << 33) | (rgb << 9) | (src << 1) | int(last)


def fb_cfg(fb_base, fb_stride, src_en, src_base, src_stride):
    """fb_cfg_t (rtl/fbw/msr_fbw_pkg.sv), MSB first: fb_base fb_stride src_en src_base src_stride."""
    return (fb_base << 97) | (fb_stride << 65) | (src_en << 64) | (src_base << 32) | src_stride


def frame_rows(W, H, T, n_in, rng):
    """Per input its rows in order; a row is (y, x0, [(x, rgb, code, last), ...])."""
    rows = [[] for _ in range(n_in)]
    k = 0
    for y0 in range(0, H, T):
        for x0 in range(0, W, T):
            w, h = min(T, W - x0), min(T, H - y0)
            for y in range(h):
                rows[k % n_in].append((y0 + y, x0, [(x0 + x, rng.randrange(1 << 24), rng.choice(CODES),
                                                     y == h - 1 and x == w - 1) for x in range(w)]))
            k += 1
    return rows


@cocotb.test()
async def test_rows(dut):
    rng = seeded_rng(dut, 35)
    n_in = len(dut.pix_valid_i)
    wpb = len(dut.rd_pix_o) // 24
    pb, sb = (32 + 2 * wpb - 2) // wpb, (8 + 2 * wpb - 2) // wpb
    await start_clock_and_reset(dut, {"clear_i": 0, "pix_valid_i": 0, "take_i": 0, "free_valid_i": 0,
                                      "pix_row_end_i": 0, "tile_i": 0, "fb_i": 0, "pix_i": 0, "raddr_i": 0,
                                      "rd_in_i": 0, "meta_in_i": 0, "meta_buf_i": 0, "free_in_i": 0,
                                      "free_buf_i": 0})
    frames = [(40, 17, 8, 0x0FE4, 4 * 40 + 12, 0x80FFC, 44, 0.0, 0.0), (1, 1, 8, 0x4, 4, 0x3FFC, 4, 0.0, 0.0)]
    for _ in range(4):
        W, H, T = rng.randint(1, 80), rng.randint(1, 40), rng.choice((8, 16, 32))
        frames.append((W, H, T, 4 * rng.randrange(0x4000), 4 * W + 4 * rng.randrange(8), 4 * rng.randrange(0x4000),
                       (W + 3) // 4 * 4 + 4 * rng.randrange(4), rng.random() * 0.6, rng.random() * 0.8))
    nxt_pick = [0] * n_in                 # the buffer the ring offers next (kept across frames)
    col = [0] * n_in                      # the buffer that collects
    for W, H, T, fb_base, fb_stride, src_base, src_stride, gap_p, slow_p in frames:
        await FallingEdge(dut.clk_i)
        dut.tile_i.value = TILE_ENC[T]
        dut.fb_i.value = fb_cfg(fb_base, fb_stride, 1, src_base, src_stride)
        await FallingEdge(dut.clk_i)
        rows = frame_rows(W, H, T, n_in, rng)
        ntiles = len(range(0, W, T)) * len(range(0, H, T))
        pos = [(0, 0)] * n_in             # per input: (row, pixel) offered next
        held = [[] for _ in range(n_in)]  # per input: complete rows not yet freed, oldest first
        job = None                        # the row being read: (input, buffer, row, beats, wait)
        free = None
        tiles = 0
        idle = 0
        while any(pos[i][0] < len(rows[i]) for i in range(n_in)) or any(held) or job:
            # registered outputs, settled since the rising edge
            ready = int(dut.pix_ready_o.value)
            row_ready = int(dut.row_ready_o.value)
            pick = int(dut.pick_o.value)
            for i in range(n_in):
                want = len(held[i]) < NBUF
                assert (ready >> i) & 1 == want, f"input {i}: pix_ready {(ready >> i) & 1} with {len(held[i])} rows held"
                assert field(pick, i, 2) == nxt_pick[i], f"input {i}: pick {field(pick, i, 2)} want {nxt_pick[i]}"
                assert not (row_ready >> i) & 1 or any(e[0] == "full" for e in held[i]), \
                    f"input {i}: a row offered with none complete and untaken"
            # pixels offered
            valid, ends, words, offer = 0, 0, [0] * n_in, [None] * n_in
            for i in range(n_in):
                r, p = pos[i]
                if r < len(rows[i]) and rng.random() >= gap_p:
                    y, x0, pix = rows[i][r]
                    x, rgb, code, last = pix[p]
                    valid |= 1 << i
                    # the writer's input slice tests the row end (x mod T == T-1 or x == W-1)
                    ends |= int(x % T == T - 1 or x == W - 1) << i
                    words[i] = pix_word(x, y, rgb, code, last)
                    offer[i] = (r, p)
            dut.pix_valid_i.value = valid
            dut.pix_row_end_i.value = ends
            dut.pix_i.value = pack(words, 57)
            # take one offered row (the oldest complete, untaken one of a random input)
            take = 0
            cand = [i for i in range(n_in) if (row_ready >> i) & 1]
            meta_want = None
            if cand and rng.random() >= slow_p:
                i = rng.choice(cand)
                ent = next(e for e in held[i] if e[0] == "full")
                assert ent[1] == nxt_pick[i], f"input {i}: offered buffer {nxt_pick[i]}, oldest row in {ent[1]}"
                ent[0] = "taken"
                take = 1 << i
                dut.meta_in_i.value = i
                dut.meta_buf_i.value = nxt_pick[i]
                y, x0, pix = rows[i][ent[2]]
                meta_want = (i, y, x0, len(pix) - 1)
                nxt_pick[i] = (nxt_pick[i] + 1) % NBUF
            dut.take_i.value = take
            # the W side: one beat per clock of the oldest taken row, after a short wait
            if job is None:
                for i in rng.sample(range(n_in), n_in):
                    ent = next((e for e in held[i] if e[0] == "taken"), None)
                    if ent is not None:
                        ent[0] = "reading"
                        job = [i, ent, 0, rng.randint(2, 6)]
                        break
            read = None
            if job is not None:
                i, ent, k, wait = job
                y, x0, pix = rows[i][ent[2]]
                npb = (((fb_base // 4 + y * fb_stride // 4) % wpb) + len(pix) - 1) // wpb + 1
                nsb = (((src_base // 4 + y * src_stride // 4 + x0 // 4) % wpb) + (len(pix) - 1) // 4) // wpb + 1
                if wait > 0:
                    job[3] -= 1
                elif k < npb + nsb:
                    src = k >= npb
                    beat = k - npb if src else k
                    addr = ent[1] * (sb if src else pb) + beat
                    dut.raddr_i.value = addr << (len(dut.raddr_i) // n_in * i)
                    dut.rd_in_i.value = i
                    read = (i, y, x0, pix, src, beat)
                    job[2] += 1
            fr = 0
            if free is not None:
                dut.free_in_i.value, dut.free_buf_i.value = free
                fr = 1
            dut.free_valid_i.value = fr
            await ReadOnly()
            tiles += bin(int(dut.tile_done_o.value)).count("1")
            if meta_want is not None:
                i, y, x0, l = meta_want
                m = int(dut.meta_o.value)
                got = (m >> 17, (m >> 5) & 0xFFF, m & 0x1F)
                assert got == (y, x0, l), f"input {i}: metadata {got} want {(y, x0, l)}"
            if read is not None:
                i, y, x0, pix, src, beat = read
                if not src:
                    ow = (fb_base // 4 + y * fb_stride // 4) % wpb
                    data = int(dut.rd_pix_o.value)
                    for l, (x, rgb, _, _) in enumerate(pix):
                        if (ow + l) // wpb == beat:
                            got = field(data, (ow + l) % wpb, 24)
                            assert got == rgb, f"pixel ({x},{y}) input {i}: {got:#08x} want {rgb:#08x}"
                else:
                    sow = (src_base // 4 + y * src_stride // 4 + x0 // 4) % wpb
                    data = int(dut.rd_code_o.value)
                    for l, (x, _, code, _) in enumerate(pix):
                        if (sow + l // 4) // wpb == beat:
                            got = field(field(data, (sow + l // 4) % wpb, 4 * CODE_W), l % 4, CODE_W)
                            assert got == code, f"code ({x},{y}) input {i}: {got} want {code}"
            # the handshakes this clock edge acts on
            if free is not None:
                i, b = free
                held[i] = [e for e in held[i] if e[1] != b]
                free = None
            if job is not None and job[3] == 0:
                i, ent, k, _ = job
                y, x0, pix = rows[i][ent[2]]
                npb = (((fb_base // 4 + y * fb_stride // 4) % wpb) + len(pix) - 1) // wpb + 1
                nsb = (((src_base // 4 + y * src_stride // 4 + x0 // 4) % wpb) + (len(pix) - 1) // 4) // wpb + 1
                if k >= npb + nsb:
                    free = (i, ent[1])
                    job = None
            moved = False
            for i in range(n_in):
                if offer[i] is not None and (ready >> i) & 1:
                    r, p = offer[i]
                    moved = True
                    if p == len(rows[i][r][2]) - 1:
                        held[i].append(["full", col[i], r])
                        col[i] = (col[i] + 1) % NBUF
                        pos[i] = (r + 1, 0)
                    else:
                        pos[i] = (r, p + 1)
            idle = 0 if moved or take or read else idle + 1
            assert idle < 200, "nothing moves for 200 cycles"
            await FallingEdge(dut.clk_i)
        dut.pix_valid_i.value = 0
        dut.take_i.value = 0
        dut.free_valid_i.value = 0
        for _ in range(4):
            await FallingEdge(dut.clk_i)
        await ReadOnly()
        assert int(dut.idle_o.value) == 1, "not idle after the frame"
        assert tiles == ntiles, f"tile_done pulses {tiles}, want {ntiles}"
        dut._log.info("frame %dx%d T%d: %d rows", W, H, T, sum(len(r) for r in rows))


@pytest.mark.parametrize("n_in,width", [(2, 256), (1, 32), (3, 64)])
def test_fbw_rowbuf(n_in, width):
    from msr_flow.filelist import RTL
    from msr_flow.runner import run_cocotb
    run_cocotb("msr_fbw_rowbuf", "test_fbw_rowbuf", HERE, {"NUM_IN": n_in, "AXI_DATA_W": width}, "",
               sources=[RTL / "pkg/msr_pkg.sv", RTL / "prim/msr_clr_reg.sv", RTL / "fbw/msr_fbw_pkg.sv",
                        RTL / "fbw/msr_fbw_rowbuf.sv"])
