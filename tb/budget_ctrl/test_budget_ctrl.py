"""budget_ctrl: the ray-budget controller's arithmetic (rtl/budget/msr_budget_ctrl.sv) against
the golden model msr_model.budget.Controller (docs/budget.md sections 1-4 and 6), clock by clock.

Every clock the bench asks the controller about one row position (row_idx_i: the tile rows
in dispatch order, docs/budget.md section 2) and checks the registered answer exactly:
row_ok_o is 1 iff a budget frame is on and the position is the next one to be consumed or the
one after it (so a position j >= 2 is never ok before the update of j - 2 has ended), and
row_m_o is then (u * u + 128) >> 8 of the model's scale of that position. Row results c_j go
in as soon as (or some clocks after) row_ready_o, flagged when the position holds the frame's
bottom tile row (its own height); SCALE_OUT after the last row,
the check's two flags and its latency (<= 20 clocks) are checked against the model and the
rules of docs/budget.md (refusal 0 < min(B, W*H) < G; SEEDED needs a memory written by a
finished budget frame with as many tile rows)."""
from __future__ import annotations

from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent

import cocotb  # noqa: E402
from cocotb.clock import Clock  # noqa: E402
from cocotb.triggers import ClockCycles, FallingEdge, ReadOnly, Timer  # noqa: E402
from msr_tb import seeded_rng  # noqa: E402

CHECK_CLOCKS_MAX = 21          # the configuration check waits this long (docs, msr_cfg_ctrl)
UPDATE_CLOCKS_MAX = 100        # docs/budget.md section 6: "an update takes under 100 clocks"
LOG2 = {8: 3, 16: 4, 32: 5}


def model():
    from msr_model import budget as BG
    from msr_model import spec
    return BG, spec


def make_params(T, L):
    BG, spec = model()
    return spec.Params(tile=T, levels=L, thr=spec.default_thresholds(L))


class Bench:
    """Drives the controller and checks every clock's read-back. State of the observations:
    `act` (a budget frame is on: row_ready_o has been seen since the start, frame_done_o not
    yet), `upd` (updates the controller has finished this frame), `pending` (a row result was
    given and its update has not ended)."""

    def __init__(self, dut, rng):
        self.dut, self.rng = dut, rng
        self.act = False
        self.upd = 0
        self.pending = False
        self.nty = 0
        self.ctl = None
        self.prev = None          # (act, upd, probe, pulse) of the last clock
        self.mem = None           # the activity memory as the bench expects it: list or None
        self.mem_u = None         # ... and the scale of each of its rows
        self.frames = self.rows = self.probes_ok = 0
        self.max_update = self.max_check = self.max_start = self.max_pass = 0
        self.starting = False
        self.seen_window = set()
        self.law = {}             # which branch of the law each new scale took (model side)

    async def reset(self):
        dut = self.dut
        dut.rst_ni.value = 0
        for name in ("clear_i", "check_i", "start_i", "row_done_i", "row_traced_i", "row_bottom_i", "row_idx_i",
                     "width_i", "height_i", "tile_log2_i", "levels_i", "budget_i", "scale_init_i",
                     "prior_shift_i", "seeded_i"):
            getattr(dut, name).value = 0
        await Timer(1, unit="ns")
        cocotb.start_soon(Clock(dut.clk_i, 10, unit="ns").start())
        await ClockCycles(dut.clk_i, 2)
        await FallingEdge(dut.clk_i)
        dut.rst_ni.value = 1
        self.mem = None
        self.act, self.upd, self.pending, self.prev = False, 0, False, None

    def config(self, W, H, T, L, B, u0, ps, seeded):
        d = self.dut
        d.width_i.value, d.height_i.value = W, H
        d.tile_log2_i.value, d.levels_i.value = LOG2[T], L
        d.budget_i.value, d.scale_init_i.value = B, u0
        d.prior_shift_i.value, d.seeded_i.value = ps, int(seeded)

    def pick_probe(self):
        r = self.rng.random()
        if r < 0.3:
            v = self.upd
        elif r < 0.55:
            v = self.upd + 1
        elif r < 0.8:
            v = self.upd + 2
        elif r < 0.9:
            v = max(self.upd - 1, 0)
        else:
            v = self.rng.randrange(0, 1 << 10)
        return v & 0x3FF

    async def clock(self, check=0, start=0, clear=0, row=None, probe=None, cfg=None, bottom=False):
        """One clock: inputs written after the falling edge, outputs read in ReadOnly (they are
        the state after the last rising edge; the inputs act at the next one)."""
        d = self.dut
        await FallingEdge(d.clk_i)
        if cfg is not None:
            self.config(*cfg)
        d.check_i.value, d.start_i.value, d.clear_i.value = check, start, clear
        d.row_done_i.value = 0 if row is None else 1
        if row is not None:
            assert int(d.row_ready_o.value) == 1, "row result given while row_ready_o is low"
            d.row_traced_i.value = row
            d.row_bottom_i.value = int(bottom)
        probe = self.pick_probe() if probe is None else probe
        d.row_idx_i.value = probe
        await ReadOnly()
        ok, m = int(d.row_ok_o.value), int(d.row_m_o.value)
        # 1. The registered answer to the last clock's question.
        if self.prev is not None:
            act, upd, asked, pulse = self.prev
            # Rows 0 and 1 become known at the start sequence's end, before a seeded frame's
            # seed pass (row_ready_o rises after it): the first answer for one of them marks it.
            if (ok and self.starting and not act and not pulse and upd == 0 and asked <= 1
                    and asked < self.nty):
                act = self.act = True
                self.starting = False
            want = act and not pulse and upd <= asked <= upd + 1 and asked < self.nty
            assert ok == int(want), (f"row_ok_o {ok} for row {asked}: frame on {act}, updates done "
                                     f"{upd}, rows {self.nty}")
            if ok:
                BG, _ = model()
                assert asked < len(self.ctl.scales), f"row {asked} ok before the model knows it"
                want_m = BG.thr_multiplier(self.ctl.scales[asked])
                assert m == want_m, f"row {asked}: m {m}, want {want_m} (u {self.ctl.scales[asked]})"
                self.probes_ok += 1
                self.seen_window.add(asked - upd)
        # 2. This clock's state.
        fd, rr = int(d.frame_done_o.value), int(d.row_ready_o.value)
        if fd:
            assert self.act and self.pending, "frame_done_o outside a frame's last update"
            self.act, self.pending = False, False
            self.upd += 1
        elif rr and self.ctl is not None and self.upd < self.nty:
            self.act = True
            self.starting = False
            if self.pending:
                self.pending = False
                self.upd += 1
        if row is not None:
            self.pending = True
        self.prev = (self.act, self.upd, probe, bool(check or start or clear))
        return d

    # ---- The check ------------------------------------------------------------------------
    def expected_errors(self, W, H, T, L, B, seeded):
        BG, spec = model()
        params = make_params(T, L)
        G = BG.grid_count(W, H, params)
        err_budget = 0 < min(B, W * H) < G
        nty = spec.tile_counts(W, H, T)[1]
        err_profile = bool(seeded) and (self.mem is None or len(self.mem) != nty)
        return err_budget, err_profile, G

    async def check(self, W, H, T, L, B, u0, ps, seeded):
        await self.clock(check=1, cfg=(W, H, T, L, B, u0, ps, seeded))
        self.act = False                   # a check ends any frame (none runs in the bench)
        for n in range(1, 64):
            d = await self.clock()
            if int(d.check_done_o.value):
                break
        else:
            raise AssertionError("check_done_o never rose")
        assert n <= CHECK_CLOCKS_MAX, f"check took {n} clocks"
        self.max_check = max(self.max_check, n)
        eb, ep, G = self.expected_errors(W, H, T, L, B, seeded)
        got = (int(d.err_budget_o.value), int(d.err_profile_o.value))
        assert got == (int(eb), int(ep)), (f"check {W}x{H} T{T} L{L} B {B} (G {G}) seeded {seeded}: "
                                           f"err_budget/profile {got}, want {(int(eb), int(ep))}")
        # The flags hold.
        for _ in range(self.rng.randint(0, 3)):
            d = await self.clock()
            assert int(d.check_done_o.value) == 1
            assert (int(d.err_budget_o.value), int(d.err_profile_o.value)) == got
        return not eb and not ep

    # ---- A frame ----------------------------------------------------------------------------
    async def readback(self, r):
        """Ask row r for one clock; the answer of the next clock (also checked by clock())."""
        await self.clock(probe=r)
        d = await self.clock()
        return int(d.row_ok_o.value), int(d.row_m_o.value)

    async def frame(self, W, H, T, L, B, u0, ps, seeded, traced, gap=(0, 3), abort_after=None,
                    hook=None):
        """Check and (if accepted and B != 0) run one frame. traced(j, g, p, u) gives c_j.
        Returns the model controller (None if refused)."""
        BG, spec = model()
        accepted = await self.check(W, H, T, L, B, u0, ps, seeded)
        if not accepted or B == 0:
            return None
        params = make_params(T, L)
        self.nty = spec.tile_counts(W, H, T)[1]
        cfg = BG.BudgetConfig(budget=B, scale_init=min(u0, BG.U_MAX), prior_shift=ps,
                              profile=tuple(self.mem) if seeded else None,
                              profile_scales=tuple(self.mem_u) if seeded else None)
        self.ctl = BG.Controller(W, H, params, cfg)
        if seeded:
            # which branch of the seed pass's weight w(u'_k, u0) = min(u'_k, u0) every word took
            u0s = cfg.seed
            for u in self.mem_u:
                k = "w_below" if u <= u0s else "w_seed"
                self.law[k] = self.law.get(k, 0) + 1
        self.upd, self.pending, self.act = 0, False, False
        await self.clock(start=1)
        self.starting = True
        self.mem = None                    # the memory is being rewritten
        n = 0
        while not self.act:
            await self.clock(probe=n % 2)      # ask for rows 0 and 1 until one is known
            n += 1
            assert n < 200, "rows 0 and 1 never became known"
        # a seeded start's seed pass: at most 40 clocks a row before the first row result
        n_pass = 0
        while not int(self.dut.row_ready_o.value):
            await self.clock()
            n_pass += 1
            assert n_pass <= 40 * self.nty + 4, "the seed pass never ended"
        self.max_pass = max(self.max_pass, n_pass)
        self.max_start = max(self.max_start, n)
        for j in range(self.nty):
            for _ in range(self.rng.randint(*gap)):
                await self.clock()
            if hook is not None:
                await hook(j)
            while not int(self.dut.row_ready_o.value):
                await self.clock()
            h = self.ctl.row_height(j)
            g, p = BG.row_grid(W, h, params), W * h
            c = max(g, min(p, int(traced(j, g, p, self.ctl.scales[j]))))
            if abort_after is not None and j == abort_after:
                await self.clock(clear=1)
                self.act, self.pending, self.ctl = False, False, None
                return None
            await self.clock(row=c, bottom=self.ctl.order[j] == self.nty - 1)
            self.ctl.finish_row(c)
            self.rows += 1
            self.classify(j)
            t0 = 0
            while self.pending:
                await self.clock()
                t0 += 1
                assert t0 <= UPDATE_CLOCKS_MAX, f"row {j}: update longer than {UPDATE_CLOCKS_MAX} clocks"
            self.max_update = max(self.max_update, t0)
        d = self.dut
        assert self.ctl.scale_out is not None
        assert int(d.scale_out_valid_o.value) == 1
        assert int(d.scale_out_o.value) == self.ctl.scale_out, (
            f"SCALE_OUT {int(d.scale_out_o.value)}, want {self.ctl.scale_out} ({W}x{H} T{T} L{L} B {B})")
        self.mem = list(self.ctl.activity)
        self.mem_u = self.ctl.scale_of_rows()
        self.frames += 1
        for _ in range(self.rng.randint(1, 4)):
            await self.clock()
            assert int(d.row_ok_o.value) == 0 and int(d.scale_out_valid_o.value) == 1
        return self.ctl

    def classify(self, j):
        """The branch of the law row j's update took, from the model's state after it."""
        BG, _ = model()
        ctl = self.ctl
        if j == self.nty - 1:
            k = "out_max" if ctl.scale_out == BG.U_MAX else "out_min" if ctl.scale_out == BG.U_MIN else "out_mid"
        elif j + 2 >= self.nty:
            k = "none"
        else:
            x = ctl.budget - ctl.traced - (ctl.grid - ctl.grid_done)
            q, slew, rise = ctl.quotient(), ctl.scale_fall(ctl.scales[j + 1]), ctl.scales[j + 1] << 1
            law = "seeded" if ctl.profile is not None else "first"
            deep = ctl.scales[j + 2] < BG.U_MIN         # a first frame's row below 45
            k = ("x<=0" if x <= 0 else f"{law}_rise" if q > rise and rise <= BG.U_MAX else
                 f"{law}_sat" if q > BG.U_MAX else f"{law}_slew" if q < slew
                 else "first_deep" if deep else f"{law}_min" if q < BG.U_MIN else f"{law}_mid")
        self.law[k] = self.law.get(k, 0) + 1

    def summary(self):
        self.dut._log.info("%d frames, %d rows, %d ok read-backs checked (windows %s); longest check "
                           "%d clocks, start %d clocks, seed pass %d clocks, update %d clocks",
                           self.frames, self.rows, self.probes_ok, sorted(self.seen_window),
                           self.max_check, self.max_start, self.max_pass, self.max_update)
        self.dut._log.info("law branches: %s", dict(sorted(self.law.items())))


def scene(rng, nty, kind=None):
    """A per-row activity shape: the traced excess of row j at scale u is about
    (p - g) * f_j * 256 / u (excess ~ 1 / u, the model of docs/budget.md), with noise."""
    kind = kind or rng.choice(("flat", "busy", "band", "random", "ramp"))
    if kind == "flat":
        f = [0.0] * nty
    elif kind == "busy":
        f = [rng.uniform(0.3, 1.5) for _ in range(nty)]
    elif kind == "band":
        a, b = sorted(rng.randrange(nty + 1) for _ in range(2))
        f = [rng.uniform(0.2, 0.8) if a <= j < b else rng.uniform(0, 0.02) for j in range(nty)]
    elif kind == "ramp":
        f = [0.5 * j / max(1, nty - 1) for j in range(nty)]
    else:
        f = [rng.random() ** 3 for _ in range(nty)]
    return f


def traced_fn(rng, f, mode):
    def fn(j, g, p, u):
        if mode == "min":
            return g
        if mode == "max":
            return p
        if mode == "extremes":
            return rng.choice((g, p, rng.randint(g, p)))
        if mode == "uniform":
            return rng.randint(g, p)
        noise = rng.uniform(0.8, 1.25)
        return g + min(p - g, int((p - g) * f[j] * 256 / u * noise))
    return fn


def random_budget(rng, W, H, G):
    WH = W * H
    k = rng.random()
    if k < 0.1:
        return G
    if k < 0.2:
        return G + 1
    if k < 0.3:
        return WH
    if k < 0.35:
        return rng.randint(WH, (1 << 24) - 1)
    if k < 0.8:
        return min(WH, G + int((WH - G) * rng.choice((0.01, 0.05, 0.1, 0.2, 0.4))) + rng.randint(0, 7))
    return rng.randint(G, WH)


async def random_sequence(bench, rng, W, H, T, L, n_frames, gap=(0, 3)):
    BG, spec = model()
    G = BG.grid_count(W, H, make_params(T, L))
    B = random_budget(rng, W, H, G)
    ps = rng.randint(0, 7)
    u0 = rng.choice((0, 256, rng.randint(0, 2047), rng.randint(45, 1448), 1, 2047))
    nty = spec.tile_counts(W, H, T)[1]
    f = scene(rng, nty)
    mode = rng.choice(("scene", "scene", "scene", "uniform", "extremes", "min", "max"))
    for i in range(n_frames):
        ctl = await bench.frame(W, H, T, L, B, u0, ps, i > 0, traced_fn(rng, f, mode), gap=gap)
        assert ctl is not None, "an accepted frame expected"
        u0 = ctl.scale_out if rng.random() < 0.85 else rng.randint(0, 2047)
        if rng.random() < 0.3:
            f = [x * rng.uniform(0.7, 1.3) for x in f]


@cocotb.test()
async def test_worked_example(dut):
    """docs/budget.md section 5: 64 x 40, T 16, L 2, B 640, the first frame's rows 300, 200,
    130 (u_2 = 422, m = 696, SCALE_OUT = 279), then the seeded frame (row 0 traces 290:
    u_2 = 279 from the seed pass's words, row 2's weighted min(422, 279) = 279)."""
    rng = seeded_rng(dut, 505)
    b = Bench(dut, rng)
    await b.reset()
    c1 = iter((300, 200, 130))
    seen = {}

    async def row2(j):
        # before row j is given: rows j and j + 1 are known, j + 2 is not
        for r in range(3):
            seen[(j, r)] = await b.readback(r)

    ctl = await b.frame(64, 40, 16, 2, 640, 256, 6, False, lambda j, g, p, u: next(c1), hook=row2)
    assert seen[(0, 0)] == (1, 256) and seen[(0, 1)] == (1, 256) and seen[(0, 2)][0] == 0
    assert seen[(1, 1)] == (1, 256) and seen[(1, 2)] == (1, 696) and seen[(1, 0)][0] == 0
    assert seen[(2, 2)] == (1, 696)
    assert (ctl.prior_n, ctl.prior_p, ctl.grid) == (1520, 40, 260)
    assert ctl.scales == [256, 256, 422] and ctl.activity == [51200, 25600, 29540]
    assert int(dut.scale_out_o.value) == 279
    c2 = iter((290, 200, 100))
    seen.clear()
    ctl = await b.frame(64, 40, 16, 2, 640, 279, 6, True, lambda j, g, p, u: next(c2), hook=row2)
    assert ctl.scales[:3] == [279, 279, 279]
    assert seen[(0, 0)] == (1, 304) and seen[(1, 2)] == (1, (279 * 279 + 128) >> 8)
    b.summary()


@cocotb.test()
async def test_check(dut):
    """The check: budgets G - 1, G, 0, 1 and above W * H; SEEDED with an empty memory after
    reset, after a frame of another tile-row count, after a cleared frame; its latency."""
    BG, spec = model()
    rng = seeded_rng(dut, 606)
    b = Bench(dut, rng)
    await b.reset()
    cases = [(64, 40, 16, 2), (1, 1, 8, 1), (4096, 4096, 8, 1), (4096, 4096, 32, 3), (1920, 1080, 16, 3),
             (33, 17, 32, 3), (100, 7, 8, 2)]
    for _ in range(12):
        cases.append((rng.randint(1, 4096), rng.randint(1, 4096), rng.choice((8, 16, 32)), rng.randint(1, 3)))
    for W, H, T, L in cases:
        G = BG.grid_count(W, H, make_params(T, L))
        for B in {G - 1, G, 0, 1, max(G - 2, 0), min(W * H, (1 << 24) - 1), (1 << 24) - 1, G + 1}:
            if 0 <= B < (1 << 24):
                await b.check(W, H, T, L, B, 256, 6, rng.random() < 0.5)   # memory empty: seeded refused
    # A frame of 3 tile rows, then seeded checks with 3 rows (accepted) and other counts (refused).
    fn = traced_fn(rng, None, "uniform")
    assert await b.frame(64, 40, 16, 2, 640, 256, 6, False, fn) is not None
    assert await b.check(64, 48, 16, 2, 640, 256, 6, True)                  # 3 rows: ok
    assert not await b.check(64, 49, 16, 2, 640, 256, 6, True)              # 4 rows
    assert not await b.check(64, 40, 8, 2, 640, 256, 6, True)               # 5 rows
    assert await b.check(64, 40, 8, 2, 640, 256, 6, False)                  # not seeded: ok
    assert await b.check(200, 33, 16, 3, 0, 256, 6, True)                   # 3 rows, budget off
    assert not await b.check(64, 40, 16, 2, 259, 256, 6, True)              # G - 1
    # A seeded frame from that memory, then a frame cleared half way: the memory is gone.
    assert await b.frame(64, 33, 16, 1, 2000, 300, 3, True, fn) is not None
    assert await b.frame(64, 40, 16, 2, 700, 256, 6, True, fn, abort_after=1) is None
    await b.clock()
    assert int(dut.check_done_o.value) == 0
    assert not await b.check(64, 40, 16, 2, 700, 256, 6, True)
    assert await b.frame(64, 40, 16, 2, 700, 256, 6, False, fn) is not None
    assert await b.frame(64, 40, 16, 2, 700, 256, 6, True, fn) is not None
    # A reset forgets the memory.
    await FallingEdge(dut.clk_i)
    dut.rst_ni.value = 0
    await FallingEdge(dut.clk_i)
    dut.rst_ni.value = 1
    b.mem, b.act, b.prev = None, False, None
    assert not await b.check(64, 40, 16, 2, 700, 256, 6, True)
    b.summary()


@cocotb.test()
async def test_random_frames(dut):
    """Sequences of 2-3 frames (first frame, then seeded ones carrying the memory over) of
    random small and odd sizes, every T and L, budgets from G to above W * H, every prior
    shift, seeds including 0 and above U_MAX, traced counts from a scene model and the
    extremes g_j and p_j."""
    rng = seeded_rng(dut, 707)
    b = Bench(dut, rng)
    await b.reset()
    for i in range(150):
        W, H = ((rng.randint(1, 40), rng.randint(1, 70)) if i % 3 == 0 else
                (rng.randint(1, 300), rng.randint(1, 300)) if i % 3 == 1 else
                (rng.randint(100, 1920), rng.randint(100, 1080)))
        await random_sequence(b, rng, W, H, rng.choice((8, 16, 32)), rng.randint(1, 3), rng.randint(2, 3),
                              gap=rng.choice(((0, 0), (0, 3), (0, 20))))
    b.summary()
    for k in ("first_mid", "first_slew", "first_sat", "first_rise", "first_min", "first_deep", "seeded_mid",
              "seeded_slew", "seeded_sat", "seeded_rise", "x<=0", "none", "out_mid", "out_max", "out_min",
              "w_below", "w_seed"):
        assert b.law.get(k, 0) > 0, f"law branch {k} never taken: {b.law}"


@cocotb.test()
async def test_large_frames(dut):
    """1920 x 1080 (L = 3, budgets of 5, 10, 20 %: the evaluation's settings), 4096 x 4096 at
    T = 8 (512 tile rows: the whole memory, the widest sums) and other large sizes."""
    BG, spec = model()
    rng = seeded_rng(dut, 808)
    b = Bench(dut, rng)
    await b.reset()
    W, H, T, L = 1920, 1080, 16, 3
    nty = spec.tile_counts(W, H, T)[1]
    for share in (0.05, 0.10, 0.20):
        f = scene(rng, nty, "band")
        u0 = 256
        for i in range(2):
            ctl = await b.frame(W, H, T, L, int(W * H * share), u0, 6, i > 0, traced_fn(rng, f, "scene"), gap=(0, 0))
            u0 = ctl.scale_out
    f = scene(rng, 512, "busy")
    await b.frame(4096, 4096, 8, 1, (1 << 24) - 1, 1448, 0, False, traced_fn(rng, f, "max"), gap=(0, 0))
    await b.frame(4096, 4096, 8, 1, (1 << 24) - 1, 1448, 0, True, traced_fn(rng, f, "min"), gap=(0, 0))
    G = BG.grid_count(4096, 4096, make_params(8, 3))
    await b.frame(4096, 4096, 8, 3, G + 1, 45, 7, False, traced_fn(rng, f, "extremes"), gap=(0, 0))
    for _ in range(3):
        await random_sequence(b, rng, rng.randint(1000, 4096), rng.randint(300, 1080), rng.choice((16, 32)),
                              rng.randint(1, 3), 2, gap=(0, 1))
    b.summary()


def test_budget_ctrl():
    from msr_flow.filelist import RTL
    from msr_flow.runner import run_cocotb
    run_cocotb("msr_budget_ctrl", "test_budget_ctrl", HERE, {}, "",
               sources=[RTL / "pkg/msr_pkg.sv", RTL / "budget/msr_budget_pkg.sv", RTL / "prim/msr_shift_add_mul.sv", RTL / "prim/msr_seq_div.sv",
                        RTL / "budget/msr_budget_grid.sv", RTL / "budget/msr_budget_mem.sv",
                        RTL / "budget/msr_budget_pass.sv",
                        RTL / "budget/msr_budget_law.sv",
                        RTL / "budget/msr_budget_mul_ops.sv",
                        RTL / "budget/msr_budget_ctrl.sv"])
