"""msr_top bench: what its cocotb test modules share (tb/msr_top/test_msr_top_*.py).

Registers through cocotbext-axi AxiLiteMaster, the frame buffer in an AxiRamWrite with random
pauses on AW, W and B, and a Python rendering unit (an image: random latency, random order,
random back-pressure); `Env.frame` runs one frame and checks it bit-exact with
msr_model.golden.select (pixels and source map), the counters and the render requests."""
from __future__ import annotations

import os
import random

import numpy as np

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, RisingEdge, Timer
from cocotbext.axi import AxiLiteBus, AxiLiteMaster, AxiRamWrite, AxiWriteBus

from msr_flow import regs as R  # generated from rtl/regs/msr_regs.rdl
from msr_funcov import backpressure, partial, record

MEM = 1 << 18
FILL = 0xEE
FB_BASE, SRC_BASE = 0x1000, 0x30000
# STATUS.ERROR codes, generated from rtl/regs/msr_regs.rdl (enum status_error_e).
ERR_NONE, ERR_FRAME_SIZE, ERR_TILE, ERR_LEVELS = (R.STATUS_ERROR_NONE, R.STATUS_ERROR_FRAME_SIZE,
                                                  R.STATUS_ERROR_TILE, R.STATUS_ERROR_LEVELS)
ERR_FB_STRIDE, ERR_FB_BASE, ERR_SRC_STRIDE, ERR_SRC_BASE = (R.STATUS_ERROR_FB_STRIDE, R.STATUS_ERROR_FB_BASE,
                                                            R.STATUS_ERROR_SRC_STRIDE, R.STATUS_ERROR_SRC_BASE)
ERR_FB_WRAP, ERR_SRC_WRAP, ERR_OVERLAP = R.STATUS_ERROR_FB_WRAP, R.STATUS_ERROR_SRC_WRAP, R.STATUS_ERROR_OVERLAP
ERR_WATCHDOG = R.STATUS_ERROR_WATCHDOG
ERR_RULE = R.STATUS_ERROR_RULE
ERR_BUDGET, ERR_PROFILE = R.STATUS_ERROR_BUDGET, R.STATUS_ERROR_PROFILE
ERR_GAZE = R.STATUS_ERROR_GAZE
RULES = ("patent", "lindilate")   # CONFIG.RULE 0, 1 (2, 3 are refused with ERR_RULE)
# msr_top's LINDILATE of this build (the rules it carries): 0 = patent only, RULE 1 refused too
LINDILATE = int(os.environ.get("LINDILATE", "1"))
# msr_top's TILE_LIMIT of this build: the largest CONFIG.TILE it takes (a larger one: ERR_TILE)
TILE_LIMIT = int(os.environ.get("TILE_LIMIT", "32"))
# msr_top's BUDGET_EN of this build: 0 = no ray-budget controller, a non-zero BUDGET refused
BUDGET_EN = int(os.environ.get("BUDGET_EN", "0"))
DRAIN_TIMEOUT = 16384      # msr_cfg_ctrl: a soft reset's wait without progress, WATCHDOG 0


def pause(rng, p):
    while True:
        yield int(rng.random() < p)


def make_image(rng, w, h):
    """Smooth areas (interpolated), edges and noise (traced): every decision outcome occurs."""
    yy, xx = np.mgrid[0:h, 0:w]
    img = np.stack([(xx * 255 // max(1, w - 1)), (yy * 255 // max(1, h - 1)), ((xx + yy) * 3) % 256], axis=2)
    for _ in range(3):
        x0, y0 = rng.randrange(w), rng.randrange(h)
        img[y0:y0 + rng.randint(1, 12), x0:x0 + rng.randint(1, 12)] = [rng.randrange(256) for _ in range(3)]
    noise = np.array([[rng.randrange(-6, 7) for _ in range(w)] for _ in range(h)])
    return np.clip(img + noise[..., None], 0, 255).astype(np.uint8)


class RenderModel:
    """The render port: takes requests (random ready), answers after a random latency, any order."""

    def __init__(self, dut, rng):
        self.dut, self.rng = dut, rng
        self.image = None
        self.pending = []          # [due_cycle, tag, rgb]
        self.requests = []
        self.ready_p, self.max_lat = 0.8, 20
        self.lose = set()          # indices (into requests) whose response is never sent
        self.flush = False         # set by a hard reset: forget every request taken
        self.inject = []           # (tag, rgb) responses to send for no request (stale, bad engine id)
        dut.rnd_req_ready_i.value = 0
        dut.rnd_rsp_valid_i.value = 0
        cocotb.start_soon(self.run())

    async def run(self):
        dut, rng = self.dut, self.rng
        cycle, current = 0, None
        while True:
            await RisingEdge(dut.clk_i)
            cycle += 1
            if self.flush:
                self.pending.clear()
                current = None
                self.flush = False
            # Handshakes of this edge (values before the edge are still visible here).
            if int(dut.rnd_req_valid_o.value) and int(dut.rnd_req_ready_i.value):
                x, y, tag = int(dut.rnd_req_x_o.value), int(dut.rnd_req_y_o.value), int(dut.rnd_req_tag_o.value)
                assert self.image is not None and y < self.image.shape[0] and x < self.image.shape[1], \
                    f"request ({x},{y}) outside the frame"
                self.requests.append((x, y))
                rgb = self.image[y, x]
                if len(self.requests) - 1 not in self.lose:
                    self.pending.append([cycle + rng.randint(1, self.max_lat), tag,
                                         (int(rgb[0]) << 16) | (int(rgb[1]) << 8) | int(rgb[2])])
            if current is not None and int(dut.rnd_rsp_ready_o.value):
                current = None
            if current is None and self.inject:
                current = [cycle, *self.inject.pop(0)]
            if current is None:
                due = [p for p in self.pending if p[0] <= cycle]
                if due:
                    current = rng.choice(due)
                    self.pending.remove(current)
            dut.rnd_rsp_valid_i.value = int(current is not None)
            if current is not None:
                dut.rnd_rsp_tag_i.value = current[1]
                dut.rnd_rsp_rgb_i.value = current[2]
            dut.rnd_req_ready_i.value = int(rng.random() < self.ready_p)


class Env:
    def __init__(self, dut, rng):
        self.dut, self.rng = dut, rng
        self.lite = AxiLiteMaster(AxiLiteBus.from_prefix(dut, "s_axil"), dut.clk_i, dut.rst_ni,
                                  reset_active_level=False)
        self.ram = AxiRamWrite(AxiWriteBus.from_prefix(dut, "m_axi"), dut.clk_i, dut.rst_ni,
                               reset_active_level=False, size=MEM)
        self.render = RenderModel(dut, rng)
        self.mem_pause = 0.0
        self.hold_b = False        # withhold every write response while set
        # Write-response faults: each B the memory model sends is SLVERR or DECERR with
        # probability b_err_p (b_err_codes to choose from), or only while b_err_when() is true.
        self.b_err_p, self.b_err_codes, self.b_err_when = 0.0, (2, 3), None
        self.b_log = []            # bresp of every B the model queued, in burst order
        self.aw_log = []           # AWADDR of every burst accepted, in order
        self._b_send = self.ram.b_channel.send
        self.ram.b_channel.send = self._b_send_faulty
        cocotb.start_soon(self._aw_monitor())

    async def _b_send_faulty(self, b):
        if self.b_err_p and self.rng.random() < self.b_err_p and (self.b_err_when is None or self.b_err_when()):
            b.bresp = self.rng.choice(self.b_err_codes)
        self.b_log.append(int(b.bresp))
        await self._b_send(b)

    async def _aw_monitor(self):
        dut = self.dut
        while True:
            await RisingEdge(dut.clk_i)
            if int(dut.rst_ni.value) and int(dut.m_axi_awvalid.value) and int(dut.m_axi_awready.value):
                self.aw_log.append(int(dut.m_axi_awaddr.value))

    def b_pause(self, p):
        while True:
            yield int(self.hold_b or self.rng.random() < p)

    async def wr(self, addr, value):
        await self.lite.write_dword(addr, value)

    async def rd(self, addr):
        return await self.lite.read_dword(addr)

    def set_pauses(self, p):
        rng = self.rng
        self.mem_pause = p
        self.ram.aw_channel.set_pause_generator(pause(rng, p))
        self.ram.w_channel.set_pause_generator(pause(rng, p))
        self.ram.b_channel.set_pause_generator(self.b_pause(p))
        for ch in (self.lite.write_if.aw_channel, self.lite.write_if.w_channel, self.lite.write_if.b_channel,
                   self.lite.read_if.ar_channel, self.lite.read_if.r_channel):
            ch.set_pause_generator(pause(rng, p))

    async def program(self, W, H, tile, levels, metric, thr, gain, fb_base=FB_BASE, fb_stride=None,
                      src_en=1, src_base=SRC_BASE, src_stride=None, rule=0, gaze=None):
        """gaze: (X, Y) written with GAZE.EN, or None: GAZE 0 (the default gaze, the centre)."""
        fb_stride = 4 * W if fb_stride is None else fb_stride
        src_stride = (W + 3) // 4 * 4 if src_stride is None else src_stride
        thr = list(thr) + [0] * (3 - len(thr))
        await self.wr(R.FRAME_SIZE, (W << R.FRAME_SIZE_WIDTH_LSB) | (H << R.FRAME_SIZE_HEIGHT_LSB))
        await self.wr(R.CONFIG, (tile << R.CONFIG_TILE_LSB) | (levels << R.CONFIG_LEVELS_LSB)
                      | (metric << R.CONFIG_METRIC_LSB) | (rule << R.CONFIG_RULE_LSB))
        await self.wr(R.THRESH, (thr[0] << R.THRESH_THR1_LSB) | (thr[1] << R.THRESH_THR2_LSB)
                      | (thr[2] << R.THRESH_THR3_LSB))
        await self.wr(R.FOV_GAIN, gain)
        await self.wr(R.GAZE, 0 if gaze is None else (R.GAZE_EN_MASK | (gaze[0] << R.GAZE_X_LSB)
                                                      | (gaze[1] << R.GAZE_Y_LSB)))
        await self.wr(R.FB_BASE, fb_base)
        await self.wr(R.FB_STRIDE, fb_stride)
        await self.wr(R.SRC_BASE, src_base)
        await self.wr(R.SRC_STRIDE, src_stride)
        await self.wr(R.SRC_CTRL, src_en)
        return fb_stride, src_stride

    async def wait_idle(self, limit=400000):
        for _ in range(limit // 64):
            await ClockCycles(self.dut.clk_i, 64)
            st = await self.rd(R.STATUS)
            if not st & R.STATUS_BUSY_MASK:
                return st
        raise AssertionError("accelerator still busy")

    async def start_frame(self, W, H, tile, levels, metric, thr, gain, src_en=1, fill=True, rule=0, gaze=None):
        """Program a frame of a new random image and START it (IRQ_EN); the memory is filled
        with FILL first unless fill=False. Returns what check_frame needs."""
        img = make_image(self.rng, W, H)
        self.render.image = img
        self.render.requests = []
        self.b_log, self.aw_log = [], []
        if fill:
            self.ram.write(0, bytes([FILL]) * MEM)
        fb_stride, src_stride = await self.program(W, H, tile, levels, metric, thr, gain, src_en=src_en,
                                                   rule=rule, gaze=gaze)
        await self.wr(R.CTRL, R.CTRL_START_MASK | R.CTRL_IRQ_EN_MASK)
        return dict(img=img, W=W, H=H, tile=tile, levels=levels, metric=metric, thr=list(thr), gain=gain,
                    src_en=src_en, fb_stride=fb_stride, src_stride=src_stride, rule=rule, gaze=gaze)

    def check_memory(self, f, exact=True, budget=None):
        """The frame's pixels and source codes bit-exact with the golden model (exact=False: a
        frame cut short, not checked), and not one byte written outside them (padding of the
        strides included). `budget`: the frame's msr_model.budget.BudgetConfig (the golden
        model's select_budget). Returns the golden result."""
        from msr_model import ImageRenderer, Params, select
        from msr_model.budget import select_budget

        W, H, thr = f["W"], f["H"], f["thr"]
        params = Params(tile=f["tile"], levels=f["levels"], thr=tuple(thr), metric=("max", "sum")[f["metric"]],
                        fov_gain=f["gain"], gaze=f.get("gaze"))
        if budget is None:
            gold = select(ImageRenderer(f["img"]), W, H, params, rule=RULES[f.get("rule", 0)])
        else:
            gold = select_budget(ImageRenderer(f["img"]), W, H, params, budget, rule=RULES[f.get("rule", 0)])
        fb_stride, src_stride = f["fb_stride"], f["src_stride"]
        mem = self.ram.read(0, MEM)
        fb = np.frombuffer(mem[FB_BASE:FB_BASE + fb_stride * H], dtype="<u4").reshape(H, fb_stride // 4)[:, :W]
        rgb = np.stack([(fb >> 16) & 0xFF, (fb >> 8) & 0xFF, fb & 0xFF], axis=2).astype(np.uint8)
        bad = np.argwhere((rgb != gold.frame).any(axis=2)) if exact else []
        assert not len(bad), f"{len(bad)} pixels differ from the golden model, first (y,x) {tuple(bad[0])}"
        assert not exact or not (fb >> 24).any(), "frame-buffer pixel with a non-zero top byte"
        written = np.zeros(MEM, dtype=bool)
        for y in range(H):
            written[FB_BASE + y * fb_stride:FB_BASE + y * fb_stride + 4 * W] = True
        if f["src_en"]:
            src = np.frombuffer(mem[SRC_BASE:SRC_BASE + src_stride * H], dtype=np.uint8).reshape(H, src_stride)[:, :W]
            bad = np.argwhere(src != gold.source) if exact else []
            assert not len(bad), f"{len(bad)} source codes differ, first (y,x) {tuple(bad[0])}"
            for y in range(H):
                written[SRC_BASE + y * src_stride:SRC_BASE + y * src_stride + W] = True
        outside = np.argwhere((np.frombuffer(mem, dtype=np.uint8) != FILL) & ~written)
        assert not len(outside), f"{len(outside)} bytes written outside the frame planes, first {int(outside[0][0]):#x}"
        return gold

    async def frame(self, W, H, tile, levels, metric, thr, gain, src_en=1, rule=0, gaze=None):
        f = await self.start_frame(W, H, tile, levels, metric, thr, gain, src_en=src_en, rule=rule, gaze=gaze)
        st = await self.wait_idle()
        assert st & R.STATUS_DONE_MASK and (st & R.STATUS_ERROR_MASK) == 0, f"STATUS {st:#x}"
        assert int(self.dut.irq_o.value) == 1, "interrupt not raised at DONE"
        gold = self.check_memory(f)
        # Requests: exactly the golden model's traced pixels, each once.
        assert len(self.render.requests) == gold.stats["traced"]
        assert len(set(self.render.requests)) == len(self.render.requests), "a pixel traced twice"
        # Performance counters against the golden model's statistics.
        assert await self.rd(R.PERF_TRACED_0) == gold.stats["traced_initial"]
        for k in range(1, 4):
            assert await self.rd(getattr(R, f"PERF_TRACED_{k}")) == gold.stats.get(f"traced_level{k}", 0)
            assert await self.rd(getattr(R, f"PERF_INTERP_{k - 1}")) == gold.stats.get(f"interpolated_level{k}", 0)
        cycles = await self.rd(R.PERF_CYCLES)
        # Each engine streams at most one pixel per clock into the writer.
        engines = int(os.environ["NUM_ENGINES"])
        assert cycles * engines >= W * H, f"{cycles} cycles for {W * H} pixels with {engines} engines"
        # DONE is write-1-to-clear and takes the interrupt with it.
        await self.wr(R.STATUS, R.STATUS_DONE_MASK)
        assert (await self.rd(R.STATUS)) & R.STATUS_DONE_MASK == 0
        await RisingEdge(self.dut.clk_i)
        assert int(self.dut.irq_o.value) == 0
        self.dut._log.info("frame %dx%d T%d L%d thr %s gain %d rule %s gaze %s: bit-exact, %d traced, %d cycles",
                           W, H, tile, levels, thr, gain, RULES[rule], gaze, gold.stats["traced"], cycles)
        record("msr_top", tile=tile, levels=levels, metric=("max", "sum")[metric], fov="on" if gain else "off",
               partial=partial(W, H, tile), engines=engines, src="on" if src_en else "off",
               backpressure=backpressure(max(self.mem_pause, 1.0 - self.render.ready_p)))


async def setup(dut, seed):
    """seed: the test's own default; SEED in the environment replaces it (each test derives
    its own stream from SEED, so the tests stay independent)."""
    if os.environ.get("SEED"):
        seed = int(os.environ["SEED"]) * 1000 + seed
    dut._log.info("SEED %s (stream %d)", os.environ.get("SEED", "unset"), seed)
    rng = random.Random(seed)
    # Reset before the first clock edge: with a random initial state (+verilator+rand+reset+2)
    # rst_ni itself starts random, and an edge before the reset would check random state.
    dut.rst_ni.value = 0
    await Timer(1, unit="ns")
    cocotb.start_soon(Clock(dut.clk_i, 10, unit="ns").start())
    env = Env(dut, rng)
    await ClockCycles(dut.clk_i, 4)
    dut.rst_ni.value = 1
    await ClockCycles(dut.clk_i, 2)
    return env, rng


def tiles_built():
    """The tile sizes this build takes (CONFIG.TILE up to its TILE_LIMIT)."""
    return tuple(t for t in (8, 16, 32) if t <= TILE_LIMIT)


def random_config(rng):
    tile = rng.choice(tiles_built())
    levels = rng.randint(1, 3)
    return dict(W=rng.randint(1, 48), H=rng.randint(1, 40), tile=tile, levels=levels, metric=rng.randint(0, 1),
                thr=[rng.choice((0, 4, 8, 16, 40, 255)) for _ in range(levels)], gain=rng.choice((0, 0, 30, 255)))


async def expect_refused(dut, env, code, what):
    """START with the registers as programmed is refused with `code`: the error and CFG_ERR in
    STATUS, nothing started, no render request, the memory untouched (still FILL)."""
    await env.wr(R.CTRL, R.CTRL_START_MASK)
    await ClockCycles(dut.clk_i, 50)
    st = await env.rd(R.STATUS)
    err = (st & R.STATUS_ERROR_MASK) >> R.STATUS_ERROR_LSB
    assert err == code, f"{what}: error code {err}, want {code}"
    assert not st & (R.STATUS_BUSY_MASK | R.STATUS_DONE_MASK), f"{what}: STATUS {st:#x}: something started"
    assert st & R.STATUS_CFG_ERR_MASK, f"{what}: STATUS {st:#x}: CFG_ERR not set"
    assert not env.render.requests, f"{what}: render requests issued"
    assert set(env.ram.read(0, MEM)) == {FILL}, f"{what}: memory written"


async def wait_idle_within(env, limit):
    """Cycles until STATUS.BUSY falls, polled every 16 cycles; fails after `limit`."""
    for n in range(0, limit, 16):
        await ClockCycles(env.dut.clk_i, 16)
        if not int(env.dut.u_ctrl.busy_o.value):
            return n + 16
    raise AssertionError(f"still busy after {limit} cycles")


SLVERR, DECERR = 2, 3
REG_ADDRS = [v for k, v in vars(R).items() if k.isupper() and isinstance(v, int)
             and not k.endswith(("_MASK", "_LSB", "_WIDTH"))]     # every register of the map


async def snapshot(env):
    """Every register of the map, read back (CTRL's fields are pulses or a plain bit)."""
    return {a: await env.rd(a) for a in sorted(set(REG_ADDRS))}


async def wait_state(dut, states, limit=100000):
    """Wait until msr_cfg_ctrl's state is one of `states` (cycles waited)."""
    for n in range(limit):
        await RisingEdge(dut.clk_i)
        if int(dut.u_ctrl.state_q.value) in states:
            return n
    raise AssertionError(f"state never in {states}")


ST_IDLE, ST_SAMPLE, ST_CHECK, ST_RUN, ST_DRAIN, ST_CLEAR = range(6)   # msr_cfg_ctrl's state_e
