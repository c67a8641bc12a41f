"""A cross-check with OpenSTA: its report_power on the same netlist, with every input at a given
activity (the one kind of activity this OpenSTA takes), beside the model's figures."""
from __future__ import annotations

import re
import subprocess
from dataclasses import dataclass
from pathlib import Path


@dataclass
class StaPower:
    internal_w: float
    switching_w: float
    leakage_w: float
    total_w: float


def sta_script(liberty: Path, netlists: list[Path], top: str, period_ns: float, activity: float,
               extra_libs: tuple[Path, ...] = ()) -> str:
    """The OpenSTA commands: the design, the clock, the inputs' activity, report_power."""
    tcl = "".join(f"read_liberty {p}\n" for p in (liberty, *extra_libs))
    tcl += "".join(f"read_verilog {p}\n" for p in netlists)
    tcl += (f"link_design {top}\n"
            f"create_clock -name clk -period {period_ns} [get_ports clk_i]\n"
            f"set_power_activity -input -activity {activity} -duty 0.5\n"
            "report_power\n")
    return tcl


def parse_report_power(text: str) -> StaPower:
    m = re.search(r"^Total\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)", text, re.M)
    if not m:
        raise ValueError("no Total line in the OpenSTA power report")
    return StaPower(*(float(x) for x in m.groups()))


def run_sta_power(script: str, workdir: Path, timeout_s: float = 900) -> StaPower:
    tcl = workdir / "power_check.tcl"
    tcl.write_text(script + "exit\n")
    out = subprocess.run(["nice", "-n", "19", "sta", "-no_splash", "-exit", str(tcl)], cwd=workdir,
                         capture_output=True, text=True, timeout=timeout_s)
    return parse_report_power(out.stdout)
