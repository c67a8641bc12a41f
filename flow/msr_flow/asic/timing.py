"""Static timing with OpenSTA: the script (the SDC at the asked period; the whole design, the
paths through the macros and the logic alone), and the parsing of its reports."""
from __future__ import annotations

import re
import shutil
from dataclasses import dataclass
from pathlib import Path

from .config import COMB_CELLS, LIBERTY_SRC, OUT, SDC, AsicError, rel
from .tools import run_tool


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


def fmax_with_macros(period_ns: float, sta: dict, read_clocks: int = 1) -> float:
    """The clock every path meets with the macros' own timing: with one-clock reads that of the
    worst path; with reads of N clocks the paths out of the macros have N periods, so each kind
    gives its own bound (logic alone, out of the macros over N periods, into them over one)."""
    if read_clocks <= 1 or sta.get("from_macro") is None:
        return fmax_mhz(period_ns, float(sta["WORST_ALL"]))
    bounds = [fmax_mhz(period_ns, float(sta["WORST_LOGIC"])),
              round(1000.0 * read_clocks / (read_clocks * period_ns - sta["from_macro"].slack_ns), 1)]
    if sta.get("to_macro") is not None:
        bounds.append(fmax_mhz(period_ns, sta["to_macro"].slack_ns))
    return min(bounds)


def run_sta(top: str, netlists: list[Path], macro_lib: Path | None, period_ns: float, tag: str,
            read_clocks: int = 1) -> dict:
    """OpenSTA on the netlist(s) with the SDC at `period_ns`. Reports (1) every path with the
    cited macro timing, (2) the paths into and out of the macros, (3) the logic alone (macro
    pins cut), each with its worst path. read_clocks > 1 (the RTL's RD_LAT): a macro's read data
    is taken that many clocks after its address, so the paths out of the macros are multi-cycle
    (setup read_clocks, hold read_clocks - 1)."""
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
            + (f"set m {macros}\nset_multicycle_path -setup {read_clocks} -from $m\n"
               f"set_multicycle_path -hold {read_clocks - 1} -from $m\n" if macro_lib and read_clocks > 1 else "")
            + "puts \"@@WORST_ALL [sta::worst_slack -max]\"\npath all\n")
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
