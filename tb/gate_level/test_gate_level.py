"""The mapped netlist of one tile engine computes the same pixels as the golden model.

`make asic` maps msr_tile_engine to the OSU 0.18 um cells (scripts/asic.py); `make test` builds
that netlist first, with the parameters the default top gives the engine, in its simulation
form (build/asic/msr_tile_engine.sim.v: every cell replaced by the function the library's
liberty gives it, flip-flops with their asynchronous reset, flattened to single-bit nets; the
library's own Verilog cell models simulate the same, but Verilator needs 17 minutes and 323 MB
of C++ for 58 000 cell instances). The tile buffers are the generated macro models (each
wraps the behavioural msr_tile_sram at its real size, as a memory compiler's model would).
The bench drives it with the tile-engine bench's own stimulus and checker
(tb/tile_engine/test_tile_engine.py): random tiles, the two decision rules alternating, random
render latency, response order and back-pressure, every render request and every output
pixel compared bit for bit with msr_model.tile_model.run_tile. The only thing the netlist
cannot offer is the tag pool's internal in-flight count, which the RTL bench reads to inject
duplicate responses: that profile runs here without duplicates; stale responses (answers
with no request in flight) are still sent and must be dropped."""
from __future__ import annotations

import os
import random
from pathlib import Path

import cocotb
import pytest

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
from msr_flow.filelist import rtl_sources
from msr_flow.runner import run_cocotb
from msr_tb import next_cycle, settle, start_clock_and_reset

# The engine's mappings by read latency: the default top's (RD_LAT 1), and the one the cited
# 180 nm macro needs at 200 MHz: reads of four clocks, an address on a port once per five
# (RD_LAT 4, BUF_CYCLE 5; msr_flow.asic.cli.unit_tag names it)
TAGS = {1: "msr_tile_engine", 4: "msr_tile_engine_rl4_cy5"}



def max_outstanding() -> int:
    """The netlist's tag count: the default top's MAX_OUTSTANDING (scripts/asic.py maps the
    engine with the top's parameters)."""
    from msr_flow.synth import TOP, default_params, read_filelist
    return default_params(read_filelist(), TOP)["MAX_OUTSTANDING"]

# tiles per profile (fast, jitter, long); about half of them in each rule
TILE_COUNTS = os.environ.get("GATE_TILE_COUNTS", "40,12,4")


@cocotb.test()
async def gate_level_random_tiles(dut):
    import test_tile_engine as te    # the RTL bench's stimulus, golden model and checks
    seed = int(os.environ.get("SEED", "21"))
    dut._log.info("SEED %d", seed)
    rng = random.Random(seed)
    max_out = int(os.environ["MAX_OUTSTANDING"])
    await start_clock_and_reset(dut, te.IDLE)
    counts = [int(v) for v in TILE_COUNTS.split(",")]
    rules = {"patent": 0, "lindilate": 0}
    for name, n in zip(te.PROFILES, counts):
        tiles = [te.random_tile(rng) for _ in range(n)]
        if name == "long":
            for t in tiles:
                t["w"], t["h"] = min(t["w"], 12), min(t["h"], 12)
                t["img"] = t["img"][:t["h"], :t["w"]]
        cycles = await te.run_tiles(dut, tiles, te.PROFILES[name], rng, max_out, dup_prob=0.0)
        for t in tiles:
            rules[t["rule"]] += 1
        await te.stale_responses(dut, rng, max_out)
        dut._log.info("profile %s: %d tiles in %d cycles, bit exact", name, n, cycles)
        dut.clear_i.value = 1
        await settle()
        await next_cycle()
        dut.clear_i.value = 0
    assert rules["patent"] > 0 and rules["lindilate"] > 0, rules
    dut._log.info("GATE_LEVEL_TILES %s", rules)


@pytest.mark.gate
@pytest.mark.parametrize("rd_lat", sorted(TAGS))
def test_gate_level_tile_engine(rd_lat):
    netlist = ROOT / "build" / "asic" / f"{TAGS[rd_lat]}.sim.v"
    macros = ROOT / "build" / "asic" / f"{TAGS[rd_lat]}.macros.v"
    if not netlist.is_file():
        pytest.fail(f"{netlist} is missing: make {netlist.relative_to(ROOT)} (make test-gate does)")
    sram = [s for s in rtl_sources() if s.name == "msr_tile_sram.sv"]
    # 80 MB of generated C++ (every net of the netlist is public for cocotb): -O0 compiles it
    # several times faster than Verilator's default -Os, and the simulation's time goes to
    # cocotb anyway (make takes variable definitions in MAKEFLAGS as command-line overrides)
    flags = os.environ.get("MAKEFLAGS")
    if "OPT_FAST" not in (flags or ""):
        os.environ["MAKEFLAGS"] = ((flags or "") + " OPT_FAST=-O0 OPT_SLOW=-O0 OPT_GLOBAL=-O0").strip()
    try:
        run_cocotb("msr_tile_engine", "test_gate_level", HERE, tag="gate" + (f"_rl{rd_lat}" if rd_lat > 1 else ""),
                   sources=[*sram, macros, netlist],
                   # the simulator's Python imports the RTL bench's module (tb/tile_engine is on
                   # pytest.ini's pythonpath; the runner hands the simulator pytest's sys.path)
                   extra_env={"GATE_TILE_COUNTS": TILE_COUNTS, "MAX_OUTSTANDING": max_outstanding(),
                              # the second netlist's BUF_CYCLE: its rows of tiles interleave
                              "BUF_CYCLE": "5" if rd_lat > 1 else "1"})
    finally:                # the other benches of the session keep their own flags
        if flags is None:
            os.environ.pop("MAKEFLAGS", None)
        else:
            os.environ["MAKEFLAGS"] = flags
