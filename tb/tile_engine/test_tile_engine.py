"""tile_engine against the per-tile golden model tile_model.run_tile.

Random tiles (smooth, noisy and blocky images, every L, both metrics, both decision rules,
random thresholds, w and h 1..32) are pushed through the engine back to back; a Python rendering model answers
each render request from the tile's image after a random latency, in random order, with
random req_ready back-pressure, while the output stream stalls at random. Checked, bit for
bit: the render requests (coordinates, and their order within each tile: tiles in flight at
the same time interleave; with the lindilate rule the set of requests, each exactly once: a
dilation that traces a pixel of the line before asks for it after the line it was decided
on, docs/architecture.md) and every output pixel (tiles leave whole, in any tile order; within
a tile: order, coordinates, colour, source code, last flag). The spec's worked example and
docs/rules.md's (lindilate) are separate tests with values computed by hand. The RTL's own SVA (handshakes, tags, write-once) run all the time.
In the DEPTH_EN=1 build (test_tile_engine_depth) every tile also has an inverse-depth plane
(ramps, noise, flat, sky zeros beside surfaces, saturated 65535) that the rendering model
answers rsp_invz_i from, and every pixel's pix_invz_o is checked against run_tile's invz."""
from __future__ import annotations

import os
import itertools
import random
from pathlib import Path

import cocotb
import numpy as np
import pytest

from msr_flow.filelist import rtl_incdirs
from msr_flow.runner import run_cocotb
from msr_tb import next_cycle, pack_rgb, settle, start_clock_and_reset, unpack_rgb
from msr_funcov import record, size_class

from msr_model.spec import Params
from msr_model.tile_model import run_tile

COORD_W, LDIM_W = 12, 6


RULES = ("patent", "lindilate")     # rule_e encodings
DEPTH = os.environ.get("DEPTH_EN") == "1"   # the build has the inverse-depth channel
# the build's BUF_CYCLE: above 1 the engine drains several tiles at once, their rows interleaved
ROWS_INTERLEAVE = int(os.environ.get("BUF_CYCLE", "1")) > 1


def pack_desc(x0, y0, w, h, levels, metric, thr, rule="patent") -> int:
    thr = list(thr) + [0] * (3 - len(thr))
    v = (RULES.index(rule) << COORD_W) | x0
    for val, width in ((y0, COORD_W), (w, LDIM_W), (h, LDIM_W), (levels, 2),
                       (int(metric == "sum"), 1), (thr[2], 8), (thr[1], 8), (thr[0], 8)):
        v = (v << width) | val
    return v


def make_image(rng: random.Random, w: int, h: int) -> np.ndarray:
    kind = rng.choice(["smooth", "smooth", "noisy", "blocky", "flat"])
    nrng = np.random.default_rng(rng.randrange(1 << 30))
    yy, xx = np.mgrid[0:h, 0:w]
    if kind == "noisy":
        return nrng.integers(0, 256, (h, w, 3), dtype=np.uint8)
    if kind == "flat":
        return np.broadcast_to(nrng.integers(0, 256, 3, dtype=np.uint8), (h, w, 3)).copy()
    if kind == "blocky":
        bs = rng.choice([2, 3, 5, 8])
        base = nrng.integers(0, 256, ((h + bs - 1) // bs, (w + bs - 1) // bs, 3))
        img = base[yy // bs, xx // bs]
        return np.clip(img + nrng.integers(-3, 4, img.shape), 0, 255).astype(np.uint8)
    out = np.empty((h, w, 3))
    for c in range(3):
        fx, fy = rng.uniform(0, 0.6), rng.uniform(0, 0.6)
        out[..., c] = (128 + rng.uniform(30, 127) * np.sin(fx * xx + fy * yy + rng.uniform(0, 6))
                       + rng.uniform(-3, 3) * nrng.standard_normal((h, w)))
    return np.clip(out, 0, 255).astype(np.uint8)


def make_invz(rng: random.Random, w: int, h: int) -> np.ndarray:
    """A tile's inverse-depth plane (uint16): a smooth ramp, noise or a flat value, often with
    sky (0) beside the surface (a silhouette or patches) and some saturated (65535) pixels."""
    kind = rng.choice(["ramp", "ramp", "noise", "flat"])
    nrng = np.random.default_rng(rng.randrange(1 << 30))
    yy, xx = np.mgrid[0:h, 0:w]
    if kind == "noise":
        p = nrng.integers(0, 65536, (h, w))
    elif kind == "flat":
        p = np.full((h, w), rng.choice([1, 65535, rng.randrange(65536)]))
    else:
        p = rng.randrange(65536) + rng.randint(-3000, 3000) * xx + rng.randint(-3000, 3000) * yy
    if rng.random() < 0.4:                               # sky on one side of a straight edge
        p = np.where(rng.uniform(-1, 1) * (xx - rng.uniform(0, w)) + rng.uniform(-1, 1) * (yy - rng.uniform(0, h)) > 0,
                     0, p)
    for val in (0, 65535):                               # a few rectangles of sky and of saturation
        for _ in range(rng.choice([0, 0, 1, 2, 3])):
            y, x = rng.randrange(h), rng.randrange(w)
            p[y:y + rng.randint(1, 6), x:x + rng.randint(1, 6)] = val
    return np.clip(p, 0, 65535).astype(np.uint16)


_SLOTS = itertools.count()


def random_tile(rng: random.Random):
    # the build's TILE_LIMIT: the largest tile its buffers hold
    T = rng.choice([t for t in (8, 16, 32) if t <= int(os.environ.get("TILE_LIMIT", "32"))])
    full = rng.random() < 0.5
    w = T if full else rng.randint(1, T)
    h = T if full or rng.random() < 0.3 else rng.randint(1, T)
    levels = rng.choice([1, 2, 3])
    metric = rng.choice(["max", "sum"])
    style = rng.random()
    if style < 0.15:
        thr = [0] * levels                                # trace everything
    elif style < 0.3:
        thr = [255] * levels                              # interpolate everything possible
    else:
        thr = sorted(rng.randrange(0, 256 if metric == "sum" else 64) for _ in range(levels))
    # Every tile of a run gets its own 40x40 slot of the 4096x4096 frame: tiles in flight at
    # the same time never share a pixel, so a render request names its tile by position.
    slot = next(_SLOTS)
    x0 = (slot % 100) * 40 + rng.randrange(0, 40 - w + 1)
    y0 = (slot // 100 % 100) * 40 + rng.randrange(0, 40 - h + 1)
    return dict(x0=x0, y0=y0, w=w, h=h, levels=levels, metric=metric, thr=thr,
                rule=RULES[slot % 2], img=make_image(rng, w, h))   # the rules alternate


def golden(tile):
    img, x0, y0 = tile["img"], tile["x0"], tile["y0"]
    params = Params(tile=32, levels=tile["levels"], thr=tuple(tile["thr"]), metric=tile["metric"])
    invz = tile.get("invz")
    return run_tile(lambda x, y: img[y - y0, x - x0], x0, y0, tile["w"], tile["h"], params,
                    tuple(tile["thr"]), rule=tile.get("rule", "patent"),
                    render_invz=None if invz is None else (lambda x, y: invz[y - y0, x - x0]))


def describe(t) -> str:
    """A tile's descriptor, for failure messages."""
    return ", ".join(f"{k}={t[k]}" for k in ("x0", "y0", "w", "h", "levels", "metric", "rule", "thr") if k in t)


class Profile:
    def __init__(self, lat_max, req_ready, rsp_prob, pix_ready, desc_gap):
        self.lat_max, self.req_ready, self.rsp_prob = lat_max, req_ready, rsp_prob
        self.pix_ready, self.desc_gap = pix_ready, desc_gap


PROFILES = {
    "fast": Profile(0, 1.0, 1.0, 1.0, 0.0),            # zero-latency, no back-pressure
    "jitter": Profile(12, 0.7, 0.8, 0.6, 0.05),
    "long": Profile(300, 0.8, 0.7, 0.7, 0.1),            # latency 0..300, random order
}


class Driver:
    """Writes a DUT input only when its value changes (each write costs a VPI call)."""

    def __init__(self, dut):
        self.dut, self.last = dut, {}

    def __setitem__(self, name, value):
        if self.last.get(name) != value:
            getattr(self.dut, name).value = value
            self.last[name] = value


async def run_tiles(dut, tiles, prof: Profile, rng: random.Random, max_out: int,
                    dup_prob: float = 0.0):
    """Drive all tiles through the engine; check requests and pixels as they appear. With
    dup_prob, a response just taken is sent again at once now and then (a duplicate): the
    engine must drop it (rsp_drop_o), write nothing and free no tag twice. In the DEPTH_EN=1
    build a tile without an inverse-depth plane is given one (make_invz), and each pixel's
    pix_invz_o is checked as a sixth field."""
    drv = Driver(dut)
    exp_req, exp_pix = [], []                           # per tile: its requests in order
    for t in tiles:
        if DEPTH and "invz" not in t:
            t["invz"] = make_invz(rng, t["w"], t["h"])
        r = golden(t)
        exp_req.append(list(r.requests))
        stream = r.output_stream()
        exp_pix.append([(x, y, rgb, code, i == len(stream) - 1) for i, (x, y, rgb, code) in enumerate(stream)])
        if DEPTH:
            exp_pix[-1] = [e + (int(r.invz[e[1] - t["y0"], e[0] - t["x0"]]),) for e in exp_pix[-1]]
    n_pix = sum(len(s) for s in exp_pix)
    pix_next = [0] * len(tiles)                         # per tile: pixels seen so far
    cur = None                                          # tile being streamed out
    pending = {}                                        # tag -> (due cycle, rgb[, invz])
    rsp_cur = None
    dup_sent = dup_seen = 0
    desc_hold = False
    di = ri = pi = 0
    cycle = 0
    limit = 200 + sum(t["w"] * t["h"] * (8 + prof.lat_max // 2) for t in tiles)

    req_next = [0] * len(tiles)                         # per tile: requests seen so far
    n_req = sum(len(r) for r in exp_req)

    def tile_of(x, y):
        for i, t in enumerate(tiles):
            if t["x0"] <= x < t["x0"] + t["w"] and t["y0"] <= y < t["y0"] + t["h"]:
                return i
        raise AssertionError(f"render request ({x},{y}) outside every tile")

    def render(x, y):
        """A render request: in its tile's golden order, answered from the tile's image (and,
        DEPTH_EN=1, its inverse-depth plane: (rgb, invz))."""
        i = tile_of(x, y)
        assert i < di, f"request ({x},{y}) for tile {i}, not accepted yet"
        k = req_next[i]
        assert k < len(exp_req[i]), f"tile {i}: extra render request ({x},{y})"
        if tiles[i].get("rule") == "lindilate":
            # every expected request exactly once, in any order: move it to position k
            assert (x, y) in exp_req[i][k:], f"tile {i} (lindilate): request ({x},{y}) not expected or repeated"
            j = exp_req[i].index((x, y), k)
            exp_req[i][k], exp_req[i][j] = exp_req[i][j], exp_req[i][k]
        assert (x, y) == exp_req[i][k], f"tile {i} request {k}: got ({x},{y}), want {exp_req[i][k]}"
        req_next[i] += 1
        t = tiles[i]
        rgb = tuple(int(c) for c in t["img"][y - t["y0"], x - t["x0"]])
        return (rgb, int(t["invz"][y - t["y0"], x - t["x0"]])) if DEPTH else rgb

    while pi < n_pix:
        # ---- drive (after the falling edge) ----
        # a descriptor, once offered, stays offered until taken
        if di < len(tiles) and (desc_hold or rng.random() >= prof.desc_gap):
            t = tiles[di]
            desc_hold = True
            drv['desc_valid_i'] = 1
            drv['desc_i'] = pack_desc(t["x0"], t["y0"], t["w"], t["h"], t["levels"], t["metric"], t["thr"],
                                      t.get("rule", "patent"))
        else:
            drv['desc_valid_i'] = 0
        req_ready = int(rng.random() < prof.req_ready)
        drv['req_ready_i'] = req_ready
        if rsp_cur is None and pending and rng.random() < prof.rsp_prob:
            due = [tg for tg, (d, _) in pending.items() if d <= cycle]
            if due:
                tag = rng.choice(due)
                rsp_cur = (tag, pending.pop(tag)[1])
        if rsp_cur is not None:
            drv['rsp_valid_i'] = 1
            drv['rsp_tag_i'] = rsp_cur[0]
            if DEPTH:
                drv['rsp_rgb_i'] = pack_rgb(rsp_cur[1][0])
                drv['rsp_invz_i'] = rsp_cur[1][1]
            else:
                drv['rsp_rgb_i'] = pack_rgb(rsp_cur[1])
        else:
            drv['rsp_valid_i'] = 0
        pix_ready = int(rng.random() < prof.pix_ready)
        drv['pix_ready_i'] = pix_ready
        # ---- sample (ReadOnly): what the rising edge will do ----
        await settle()
        if drv.last.get('desc_valid_i') and dut.desc_ready_o.value:
            di += 1
            desc_hold = False
        if req_ready and dut.req_valid_o.value:
            x, y, tag = int(dut.req_x_o.value), int(dut.req_y_o.value), int(dut.req_tag_o.value)
            assert tag not in pending and (rsp_cur is None or rsp_cur[0] != tag), f"tag {tag} reused"
            pending[tag] = (cycle + 1 + rng.randint(0, prof.lat_max), render(x, y))
            ri += 1
        if rsp_cur is not None and dut.rsp_ready_o.value:
            taken = rsp_cur
            rsp_cur = None
            # a duplicate only while at least 4 tags are free: the engine reuses a tag only
            # after every other free one, so the copy cannot meet a new request of that tag
            if (len(taken) == 2 and rng.random() < dup_prob
                    and int(dut.inflight_o.value) <= max_out - 4):
                rsp_cur = (taken[0], taken[1], "duplicate")
                dup_sent += 1
        if dut.rsp_drop_o.value:
            dup_seen += 1
        if pix_ready and dut.pix_valid_o.value:
            got = (int(dut.pix_x_o.value), int(dut.pix_y_o.value), unpack_rgb(dut.pix_rgb_o.value),
                   int(dut.pix_src_o.value), bool(dut.pix_last_o.value))
            if DEPTH:
                got += (int(dut.pix_invz_o.value),)
            else:
                assert int(dut.pix_invz_o.value) == 0, "pix_invz_o is not 0 in a build without depth"
            # Tiles leave whole and row-major, in any order (a tile that waits long for its
            # renders does not hold up the others); a build whose buffers need several clocks
            # between addresses (BUF_CYCLE > 1) drains tiles at once and keeps only each row
            # whole: rows of different tiles interleave, each tile's in order.
            i = tile_of(got[0], got[1]) if cur is None else cur
            assert i < di, f"pixel {got[:2]} of tile {i}, not accepted yet"
            k = pix_next[i]
            assert k < len(exp_pix[i]) and got == exp_pix[i][k], \
                f"tile {i} pixel {k}: got {got}, want {exp_pix[i][k] if k < len(exp_pix[i]) else None} " \
                f"({describe(tiles[i])})"
            pix_next[i] += 1
            row_end = got[0] == tiles[i]["x0"] + tiles[i]["w"] - 1
            cur = None if got[4] or (ROWS_INTERLEAVE and row_end) else i
            pi += 1
        assert int(dut.inflight_o.value) <= max_out
        cycle += 1
        assert cycle < limit, f"timeout: {ri}/{n_req} requests, {pi}/{n_pix} pixels"
        await next_cycle()
    assert ri == n_req and req_next == [len(r) for r in exp_req]
    for _ in range(8):                                  # drops still in the response stages
        await settle()
        dup_seen += int(dut.rsp_drop_o.value)
        await next_cycle()
    assert dup_seen == dup_sent, f"{dup_sent} duplicate responses sent, {dup_seen} dropped"
    # after the last pixel the engine is idle and holds no tags
    drv['pix_ready_i'] = 1
    drv['desc_valid_i'] = 0
    drv['rsp_valid_i'] = 0
    await settle()
    assert not dut.busy_o.value and int(dut.inflight_o.value) == 0
    await next_cycle()
    return cycle


async def stale_responses(dut, rng: random.Random, max_out: int, n: int = 6):
    """With nothing in flight, answers for any tag are stale: each is dropped (rsp_drop_o),
    nothing is written, no tag is freed (the in-flight count stays 0)."""
    sent = seen = 0
    while sent < n:
        dut.rsp_valid_i.value = 1
        dut.rsp_tag_i.value = rng.randrange(max_out)
        dut.rsp_rgb_i.value = rng.randrange(1 << 24)
        if DEPTH:
            dut.rsp_invz_i.value = rng.randrange(1 << 16)
        await settle()
        sent += int(dut.rsp_ready_o.value)
        seen += int(dut.rsp_drop_o.value)
        await next_cycle()
    dut.rsp_valid_i.value = 0
    for _ in range(8):
        await settle()
        seen += int(dut.rsp_drop_o.value)
        await next_cycle()
    assert seen == n, f"{n} stale responses, {seen} dropped"
    await settle()
    assert int(dut.inflight_o.value) == 0 and not dut.busy_o.value
    await next_cycle()


IDLE = {"clear_i": 0, "desc_valid_i": 0, "desc_i": 0, "req_ready_i": 0, "rsp_valid_i": 0,
        "rsp_tag_i": 0, "rsp_rgb_i": 0, "rsp_invz_i": 0, "pix_ready_i": 0}


@cocotb.test()
async def random_tiles(dut):
    seed = int(os.environ.get("SEED", "1"))
    dut._log.info("SEED %d", seed)
    counts = [int(v) for v in os.environ["TILE_COUNTS"].split(",")]
    max_out = int(os.environ["MAX_OUTSTANDING"])
    rng = random.Random(seed)
    await start_clock_and_reset(dut, IDLE)
    total = 0
    for name, n in zip(PROFILES, counts):
        tiles = [random_tile(rng) for _ in range(n)]
        if name == "long":                   # keep the slow profile's tiles small
            for t in tiles:
                t["w"], t["h"] = min(t["w"], 12), min(t["h"], 12)
                t["img"] = t["img"][:t["h"], :t["w"]]
        cycles = await run_tiles(dut, tiles, PROFILES[name], rng, max_out,
                                 dup_prob=0.05 if name == "jitter" else 0.0)
        for t in tiles:                      # every tile above was checked bit for bit
            record("msr_tile_engine", levels=t["levels"], metric=t["metric"], w=size_class(t["w"]),
                   h=size_class(t["h"]), profile=name, max_out=max_out, rule=t["rule"])
        total += n
        await stale_responses(dut, rng, max_out)
        dut._log.info("profile %s: %d tiles (%d pixels) in %d cycles", name, n, sum(t["w"] * t["h"] for t in tiles),
                      cycles)
        # soft reset between profiles (nothing in flight): the engine must come back clean
        dut.clear_i.value = 1
        await settle()
        await next_cycle()
        dut.clear_i.value = 0
    dut._log.info("TILES_CHECKED %d", total)


@cocotb.test()
async def worked_example(dut):
    """Spec worked example: T=16, L=2, max, thr 8,16. Row 0 (all rows equal) is chosen so
    that level 1 interpolates x=2 (gap 4: d=7 < 8), traces x=6 (d=8) and interpolates x=13
    from 12 and 15 (gap 3: 4*5 < 3*8) to (2A+B+1)/3; level 2 decides x=14 from 13 and 15."""
    await start_clock_and_reset(dut, IDLE)
    row = np.zeros((16, 3), dtype=np.uint8)
    row[0] = (0, 0, 0)
    row[4] = (7, 7, 7)
    row[8] = (18, 10, 10)
    row[6] = (100, 101, 102)                 # what the renderer returns for x=6
    row[12] = (30, 60, 90)
    row[15] = (35, 60, 93)
    img = np.broadcast_to(row, (16, 16, 3)).copy()
    tile = dict(x0=32, y0=48, w=16, h=16, levels=2, metric="max", thr=[8, 16], img=img)
    ref = golden(tile)
    # hand-computed values (independent of the golden model's code)
    hand = {2: ((4, 4, 4), 17),                         # (2*0 + 2*7 + 2) // 4
            6: ((100, 101, 102), 1),                    # traced at level 1
            13: ((32, 60, 91), 17)}                     # (2A + B + 1) // 3
    for x, (rgb, code) in hand.items():
        assert tuple(ref.pixels[0, x]) == rgb and ref.codes[0, x] == code, "golden model disagrees"
    # run_tiles checks every pixel of the engine against this golden stream, so the engine
    # matches the hand values too
    rng = random.Random(5)
    await run_tiles(dut, [tile], PROFILES["jitter"], rng, int(os.environ["MAX_OUTSTANDING"]))


@cocotb.test()
async def worked_example_lindilate(dut):
    """docs/rules.md's worked example (T=16, L=2, max, thr 8,16, rule lindilate): a red ramp
    with a green edge in row 4 from x = 10 on. After the level-1 H pass the codes at x = 2, 6,
    10, 13 of rows 0, 4, 8, 12, 15 are as written there (hand-derived); the whole tile is
    checked against the golden model by run_tiles."""
    await start_clock_and_reset(dut, IDLE)
    yy, xx = np.mgrid[0:16, 0:16]
    img = np.stack([10 * xx, np.full_like(xx, 50), np.full_like(xx, 50)], axis=-1)
    img[4, 10:, 1] = 200
    img = img.astype(np.uint8)
    tile = dict(x0=64, y0=16, w=16, h=16, levels=2, metric="max", thr=[8, 16], rule="lindilate", img=img)
    ref = golden(tile)
    hand = {0: (17, 1, 1, 1), 4: (17, 1, 1, 1), 8: (17, 1, 1, 1), 12: (17, 17, 17, 1), 15: (17, 17, 17, 1)}
    for y, codes in hand.items():
        assert tuple(int(ref.codes[y, x]) for x in (2, 6, 10, 13)) == codes, f"golden model disagrees, row {y}"
    assert tuple(ref.pixels[0, 2]) == (20, 50, 50)
    assert int((ref.codes < 16).sum()) == 78, "docs/rules.md: lindilate traces 78 pixels of the tile"
    rng = random.Random(6)
    await run_tiles(dut, [tile], PROFILES["jitter"], rng, int(os.environ["MAX_OUTSTANDING"]))


BUILDS = [
    # (MAX_OUTSTANDING, NUM_CTX, RD_LAT, BUF_CYCLE, tiles per profile fast,jitter,long, seed)
    # half the tiles of each profile patent, half lindilate: some 1 450 tiles of each rule.
    # 16 tags and 8 contexts are msr_top's 4-engine build too (tb/msr_top), whose frames put
    # this engine through whole frames as well. RD_LAT: the tile buffers' read latency (the
    # standard-cell build's macros take several clocks; 1 is the FPGA's block RAM); BUF_CYCLE:
    # the clocks a macro's port needs between two addresses (the cited macro's 5 at 200 MHz).
    (16, 8, 1, 1, "1100,225,30", 11),
    (2, 2, 2, 3, "600,150,20", 12),
    (64, 5, 4, 5, "600,150,30", 13),     # a ring that is not a power of two
]


QUICK = os.environ.get("MSR_TB_QUICK")


@pytest.mark.parametrize("max_out,ctx,rd_lat,cycle,counts,seed", BUILDS)
def test_tile_engine(max_out, ctx, rd_lat, cycle, counts, seed):
    run_cocotb("msr_tile_engine", "test_tile_engine", Path(__file__).parent,
               {"MAX_OUTSTANDING": max_out, "NUM_CTX": ctx, "RD_LAT": rd_lat, "BUF_CYCLE": cycle},
               extra_env={"TILE_COUNTS": QUICK or counts, "SEED": seed, "MAX_OUTSTANDING": max_out,
                          "BUF_CYCLE": cycle})


def test_tile_engine_depth():
    """The DEPTH_EN=1 build: every pixel's inverse depth checked as well (16 tags, 4 contexts,
    reads of 3 clocks, buffers of 16 x 16 pixels: tiles of 8 and 16)."""
    run_cocotb("msr_tile_engine", "test_tile_engine", Path(__file__).parent,
               {"MAX_OUTSTANDING": 16, "NUM_CTX": 4, "DEPTH_EN": 1, "RD_LAT": 3, "TILE_LIMIT": 16},
               extra_env={"TILE_COUNTS": QUICK or "300,80,10", "SEED": 14, "MAX_OUTSTANDING": 16, "DEPTH_EN": "1",
                          "TILE_LIMIT": "16"})


@pytest.mark.parametrize("params", [{"MAX_OUTSTANDING": 12}, {"MAX_OUTSTANDING": 1},
                                    {"MAX_OUTSTANDING": 128}, {"MAX_OUTSTANDING": 16, "TAG_W": 3},
                                    {"NUM_CTX": 1}, {"NUM_CTX": 17}, {"RD_LAT": 0}, {"RD_LAT": 5},
                                    {"TILE_LIMIT": 12}, {"TILE_LIMIT": 64}, {"BUF_CYCLE": 0}, {"BUF_CYCLE": 9}])
def test_bad_parameters_rejected(params):
    """The elaboration-time checks stop an illegal MAX_OUTSTANDING / TAG_W / NUM_CTX / RD_LAT /
    TILE_LIMIT / BUF_CYCLE with a message."""
    import subprocess

    from msr_flow.filelist import ROOT, rtl_sources
    # the package, the primitives and the engine's units: everything below the system level
    srcs = [str(s) for s in rtl_sources() if s.name == "msr_pkg.sv" or s.parent.name in ("prim", "engine")]
    cmd = ["verilator", "--lint-only", *[f"-I{d}" for d in rtl_incdirs()], "--top-module", "msr_tile_engine"]
    cmd += [f"-G{k}={v}" for k, v in params.items()]
    p = subprocess.run(cmd + srcs, cwd=ROOT, capture_output=True, text=True)
    assert p.returncode != 0, "illegal parameters were accepted"
    assert "msr_tile_engine: " in p.stdout + p.stderr and "must be" in p.stdout + p.stderr, p.stderr
