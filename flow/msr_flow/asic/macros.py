"""The tile-buffer SRAM macros: the area and access-time model from the published 180 nm
figures (syn/asic/sram_macro.json), the instances Yosys leaves as black boxes, and the Liberty
and simulation models generated for each macro variant."""
from __future__ import annotations

import json
import math
import re
from dataclasses import dataclass
from pathlib import Path

from .config import MACRO_JSON, SRAM_MODULE, AsicError


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
    return ("/* Generated by msr_flow.asic from syn/asic/sram_macro.json: tile-buffer SRAM macros. */\n"
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
    out = ["// Generated by msr_flow.asic: simulation models of the tile-SRAM macro variants.",
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


def blackbox_port_widths(dump: str) -> dict[str, int]:
    """Port name -> width of the black-box module in a Yosys `dump` of it, in port order."""
    ports = []
    for m in re.finditer(r"^\s*wire\s+(?:width\s+(\d+)\s+)?(input|output)\s+(\d+)\s+\\(\w+)", dump, re.M):
        ports.append((int(m.group(3)), m.group(4), int(m.group(1) or 1)))
    if not ports:
        raise AsicError("the tile SRAM black box has no ports in the dump")
    return {name: w for _, name, w in sorted(ports)}
