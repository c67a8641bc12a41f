"""Mapping a unit to the library: Yosys synthesis with the tile SRAM (and, for the top's
glue, the engine) as black boxes, then dfflibmap and ABC against the liberty; the gate-level
netlist's simulation form for the gate-level bench."""
from __future__ import annotations

import json
import re
import time
from dataclasses import dataclass, field
from pathlib import Path

from ..filelist import ROOT, with_macros
from ..synth import bb_param_names, modules_in, read_cmd
from .config import ABC_CONSTR, ABC_SCRIPT, AIM_MHZ, IDEAL_MACRO_NS, OUT, SRAM_MODULE, rel
from .macros import MacroInstance, MacroModel, blackbox_port_widths, macro_liberty, macro_sim_models, parse_macro_dump
from .tools import liberty, yosys


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
