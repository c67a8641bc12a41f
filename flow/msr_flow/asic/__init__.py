"""Standard-cell figures: every RTL unit, one tile engine and the default top mapped to the OSU
0.18 um library (Debian qflow-tech-osu018) with Yosys, timed with OpenSTA at the library's
typical corner. Writes build/asic/report.json, docs/asic.json (the page's data) and
docs/asic.md.

Flow per unit (the same file list and front end as msr_flow.synth, whose helpers it imports):
  yosys  read_slang (rtl/msr.f) -> synth -flatten          (tile SRAM black-boxed as a macro)
         dfflibmap -liberty; abc -liberty -constr -D <target> with a script that maps for
         delay and then buffers, upsizes and downsizes (ABC's buffer/upsize/dnsize)
         stat -liberty (area, sequential area); write_verilog (the gate-level netlist)
  sta    read_liberty (cells + the SRAM macro model) read_verilog link_design, SDC
         syn/asic/msr_asic.sdc at CLK_PERIOD_NS: worst slack, the critical path, Fmax
The tile buffers (msr_tile_sram) are memories: their instances stay black boxes, each gets an
area and a clock-to-output time from the published 180 nm SRAM figures in
syn/asic/sram_macro.json (a Liberty model is generated from it), and their area is kept apart
from the logic area.

The top is built from its parts as a synthesis team builds a design with replicated blocks:
the engine is mapped once with the parameters the top gives it, the top is mapped with the
engines as black boxes (the "glue"), and OpenSTA times the whole top with the engine's
netlist filling every engine instance (a hierarchical netlist: every path of the chip, only
optimisation across an engine's ports is given up). Area = glue + NUM_ENGINES x engine.

    python -m msr_flow.asic [--modules a,b] [--period-ns 5.0] [--netlist-only] [--doc-only]

--modules m: only those units (msr_top needs msr_tile_engine and runs it), into
build/asic/report_partial.json. --netlist-only: map msr_tile_engine and write its gate-level
netlist and macro models for the gate-level bench (tb/gate_level), no timing, no report.
--doc-only: render docs/asic.md from docs/asic.json (and the gate-level bench's last result).

Modules: config (paths, library, constants), macros (the SRAM macro model), tools (running
Yosys and OpenSTA), mapping (Yosys to the cells), netlist (fan-out, depth), timing (OpenSTA and
its reports), rows (per-unit rows, the top from its parts), report (header, data file), page
(docs/asic.md from templates/asic.md.j2), cli.
"""
from .cli import main, run, select_units, units_of
from .config import (COMB_CELLS, DATA, DOC, LIBERTY_SRC, MACRO_JSON, OUT, SCALING, SEQ_CELLS, SRAM_MODULE,
                     AsicError)
from .macros import (MacroInstance, MacroModel, blackbox_port_widths, macro_liberty, macro_sim_models,
                     parse_macro_dump)
from .mapping import Mapped, map_unit, modules_below, sim_netlist, yosys_name
from .netlist import name_registers, netlist_figures, netlist_graph
from .page import render, write_doc
from .report import ecp5_figure, new_report, read_data
from .rows import add_rates, compose_top, scaled, top_row, unit_row
from .timing import TimingPath, fmax_mhz, parse_path, parse_sta, run_sta
from .tools import liberty, liberty_areas, run_tool, yosys

__all__ = [n for n in dir() if not n.startswith("_")]
