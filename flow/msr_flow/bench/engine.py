"""Tile engine throughput: cycles per 16x16 tile against render latency, and decisions per
clock inside a pass. Runs the RTL (cocotb on Verilator) and writes out/bench/engine.json
plus a Markdown table on stdout.

    .venv/bin/python scripts/bench_engine.py

Set-up per point: 32 tiles of 16x16 back to back, L = 2, metric max; the renderer answers a
request exactly `latency` cycles after the cycle that accepted it (latency 0 = the next
cycle), in order; req_ready and pix_ready always 1; NUM_CTX 7 (msr_top's) unless MSR_BENCH_NUM_CTX says
otherwise, the tile buffers' read latency RD_LAT 1 unless MSR_BENCH_RD_LAT says otherwise. Scenes: a smooth image with thr 8,16 (31 % traced), 26,52 (17 %, like the
default cornell frame) and 0,0 (every pixel traced: the worst case). Reported: steady-state
cycles per tile (between the last pixels of tile 8 and tile 32, so the ramp while the
contexts fill is left out), the same with the ramp, cycles of a lone tile (descriptor to last
pixel, the engine otherwise empty), traced fraction, and the decision rate inside the lone
tile's H / V passes (issued positions / cycles from a pass's first to its last issue).
The decision rule of every tile is MSR_BENCH_RULE (patent or lindilate; default patent),
as for scripts/bench_hw.py.
"""
from __future__ import annotations

import json
import os
import sys
from pathlib import Path

from ..filelist import ROOT

# MSR_BENCH_LATENCIES / MSR_BENCH_OUTSTANDING / MSR_BENCH_NUM_CTX / MSR_BENCH_RD_LAT narrow or change
# the sweep.
LATENCIES = tuple(int(v) for v in os.environ.get("MSR_BENCH_LATENCIES", "0,16,64,256").split(","))
OUTSTANDING = tuple(int(v) for v in os.environ.get("MSR_BENCH_OUTSTANDING", "16,64").split(","))
NUM_CTX = int(os.environ.get("MSR_BENCH_NUM_CTX", "7"))  # msr_top's default
RD_LAT = int(os.environ.get("MSR_BENCH_RD_LAT", "1"))    # msr_top's default
THRS = tuple(tuple(int(v) for v in s.split(",")) for s in os.environ.get("MSR_BENCH_THR", "8,16 26,52 0,0").split())
TILES = 32
RULE = os.environ.get("MSR_BENCH_RULE", "patent")
RULES = ("patent", "lindilate")                 # rule_e encodings
OUT = ROOT / "out" / "bench" / "engine.json"


def scene_image(w=16 * TILES, h=16):
    import numpy as np
    yy, xx = np.mgrid[0:h, 0:w]
    img = np.stack([128 + 100 * np.sin(0.07 * xx + 0.05 * yy),
                    128 + 90 * np.cos(0.05 * xx - 0.08 * yy),
                    100 + 0.8 * xx % 60 + 20 * (xx > w // 2)], axis=-1)
    return np.clip(img, 0, 255).astype(np.uint8)


try:
    import cocotb
    from cocotb.triggers import FallingEdge, ReadOnly
except ImportError:  # pragma: no cover
    cocotb = None

def pack_desc(x0, y0, w, h, levels, metric, thr, rule="patent"):
    thr = list(thr) + [0] * (3 - len(thr))
    v = (RULES.index(rule) << 12) | x0
    for val, width in ((y0, 12), (w, 6), (h, 6), (levels, 2), (int(metric == "sum"), 1),
                       (thr[2], 8), (thr[1], 8), (thr[0], 8)):
        v = (v << width) | val
    return v


PROBE = {} if os.environ.get("MSR_BENCH_PROBE") == "1" else None

if cocotb is not None and os.environ.get("MSR_BENCH_SIM") == "1":
    from msr_tb import pack_rgb, start_clock_and_reset

    async def run_point(dut, latency, thr, img, n_tiles=TILES):
        """Returns (cycle of each tile's last pixel from the first descriptor, traced, pass
        stats of the issued positions)."""
        descs = [pack_desc(16 * i, 0, 16, 16, 2, "max", thr, RULE) for i in range(n_tiles)]
        pending = []                       # (due cycle, tag, rgb) in request order
        cycle = 0
        start = None
        done = []
        di = pixels = traced = 0
        rsp = None
        issue_cycles, pass_log = [], []
        while pixels < 256 * n_tiles:
            dut.desc_valid_i.value = int(di < n_tiles)
            if di < n_tiles:
                dut.desc_i.value = descs[di]
            if rsp is None and pending and pending[0][0] <= cycle:
                rsp = pending.pop(0)
            dut.rsp_valid_i.value = int(rsp is not None)
            if rsp is not None:
                dut.rsp_tag_i.value = rsp[1]
                dut.rsp_rgb_i.value = rsp[2]
            await ReadOnly()
            if di < n_tiles and dut.desc_ready_o.value:
                di += 1
                if start is None:
                    start = cycle
            if dut.req_valid_o.value:
                x, y = int(dut.req_x_o.value), int(dut.req_y_o.value)
                pending.append((cycle + 1 + latency, int(dut.req_tag_o.value), pack_rgb(img[y, x])))
                traced += 1
            if rsp is not None and dut.rsp_ready_o.value:
                rsp = None
            if dut.gr_valid.value:
                # the position issued this cycle (granted the cycle before, still its
                # context's head): its pass-start flag and direction
                gi = int(dut.gr_ctx.value)
                g_first = (int(dut.ctx_first.value) >> gi) & 1
                g_hv = not (int(dut.iss_pos.value) & 1)          # pos_t.init is its last bit
                if g_first and g_hv:
                    pass_log.append([cycle, cycle, 0])
                if g_hv and pass_log:
                    pass_log[-1][1] = cycle
                    pass_log[-1][2] += 1
            if PROBE is not None:
                free = bin(int(dut.ctx_free.value)).count("1")
                full = bin(int(dut.ctx_full.value)).count("1")
                key = ("issue" if int(dut.issue.value) else
                       "no_credit" if not int(dut.can_issue.value) else
                       "no_ctx" if free == NUM_CTX else
                       "barrier_or_idle")
                PROBE[key] = PROBE.get(key, 0) + 1
                PROBE[f"full{full}"] = PROBE.get(f"full{full}", 0) + 1
                PROBE["stream"] = PROBE.get("stream", 0) + int(int(dut.ctx_str_own.value) != 0)
            if dut.pix_valid_o.value:
                pixels += 1
                if dut.pix_last_o.value:
                    done.append(cycle - start + 1)
            cycle += 1
            await FallingEdge(dut.clk_i)
        return done, traced, pass_log

    async def clear(dut):
        dut.clear_i.value = 1
        await ReadOnly()
        await FallingEdge(dut.clk_i)
        dut.clear_i.value = 0

    @cocotb.test()
    async def bench(dut):
        img = scene_image()
        await start_clock_and_reset(dut, {"clear_i": 0, "desc_valid_i": 0, "desc_i": 0,
                                          "req_ready_i": 1, "rsp_valid_i": 0, "rsp_tag_i": 0,
                                          "rsp_rgb_i": 0, "pix_ready_i": 1})
        results = []
        for thr in THRS:
            for lat in LATENCIES:
                # A lone tile: its latency, and the decision rate inside its passes.
                lone, _, passes = await run_point(dut, lat, thr, img, 1)
                dec = sum(p[2] for p in passes)
                span = sum(p[1] - p[0] + 1 for p in passes)
                await clear(dut)
                # A stream of tiles: steady state after the first quarter (the ramp while the
                # contexts fill is left out), and the whole run.
                done, traced, _ = await run_point(dut, lat, thr, img)
                s = TILES // 4
                results.append({"latency": lat, "thr": list(thr), "tiles": TILES, "rule": RULE,
                                "cycles_per_tile": (done[-1] - done[s - 1]) / (TILES - s),
                                "cycles_per_tile_with_ramp": done[-1] / TILES,
                                "lone_tile_cycles": lone[0],
                                "traced_fraction": traced / (256 * TILES),
                                "decisions_per_clock_in_pass": dec / span if span else None,
                                "passes": len(passes)})
                await clear(dut)
        Path(os.environ["MSR_BENCH_OUT"]).write_text(json.dumps(results))
        if PROBE is not None:
            print("PROBE", sorted(PROBE.items()))


def main() -> int:
    from ..runner import run_cocotb
    if RULE not in RULES:
        print(f"bench_engine: MSR_BENCH_RULE={RULE!r} is not one of {', '.join(RULES)}", file=sys.stderr)
        return 2
    if not 1 <= RD_LAT <= 4:
        print(f"bench_engine: MSR_BENCH_RD_LAT={RD_LAT} is not in 1..4", file=sys.stderr)
        return 2
    table = []
    for max_out in OUTSTANDING:
        part = ROOT / "build" / "bench" / f"engine_{max_out}_rl{RD_LAT}.json"
        part.parent.mkdir(parents=True, exist_ok=True)
        # this module is the cocotb test module too (MSR_BENCH_SIM=1 inside the simulator)
        run_cocotb("msr_tile_engine", "msr_flow.bench.engine", part.parent,
                   {"MAX_OUTSTANDING": max_out, "NUM_CTX": NUM_CTX, "RD_LAT": RD_LAT}, tag="bench",
                   extra_env={"MSR_BENCH_SIM": "1", "MSR_BENCH_OUT": part})
        for r in json.loads(part.read_text()):
            r["max_outstanding"] = max_out
            table.append(r)
    OUT.parent.mkdir(parents=True, exist_ok=True)
    OUT.write_text(json.dumps({"setup": __doc__.split("Set-up per point:")[1].strip(), "rule": RULE,
                               "num_ctx": NUM_CTX, "rd_lat": RD_LAT, "results": table}, indent=1))
    print("| MAX_OUTSTANDING | thr | latency | cycles / 16x16 tile (steady) | with ramp | lone tile | pixels / clock "
          "| traced | decisions / clock in a pass |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in table:
        print(f"| {r['max_outstanding']} | {','.join(map(str, r['thr']))} | {r['latency']} "
              f"| {r['cycles_per_tile']:.0f} | {r['cycles_per_tile_with_ramp']:.0f} | {r['lone_tile_cycles']} "
              f"| {256 / r['cycles_per_tile']:.3f} | {r['traced_fraction']:.2f} "
              f"| {r['decisions_per_clock_in_pass']:.3f} |")
    print(f"written {OUT.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
