"""The report: its header (library, clock, tools, the macro model, the parameters), the ECP5
figure it is compared with, and where it is kept (build/asic/ for every run, docs/asic.json
for the page)."""
from __future__ import annotations

import json
from pathlib import Path

from ..filelist import ROOT
from .config import (ABC_SCRIPT, AIM_MHZ, CORNER, DATA, LIB_NAME, LIBERTY_SRC, MACRO_JSON, OUT, SDC,
                     TARGET_MHZ, TOOLS, AsicError, rel)


def new_report(period_ns: float, nand2_um2: float, engine_params: dict, top_params: dict) -> dict:
    """Everything of a run but its rows (`modules`), its failures and its duration."""
    return {"library": LIB_NAME, "liberty": str(LIBERTY_SRC), "corner": CORNER,
            "clock": {"port": "clk_i", "period_ns": period_ns, "target_mhz": round(1000 / period_ns, 1),
                      "goal_mhz": TARGET_MHZ, "aim_mhz": AIM_MHZ, "sdc": rel(SDC)},
            "nand2_um2": nand2_um2, "abc_script": ABC_SCRIPT, "abc_delay_target_ps": round(1e6 / AIM_MHZ),
            "sram_model": json.loads(MACRO_JSON.read_text()), "tools": dict(TOOLS),
            "engine_params": engine_params, "top_params": top_params, "modules": {}, "failures": [],
            "ecp5": ecp5_figure()}


def ecp5_figure() -> dict | None:
    """The default top's ECP5 row of make synth (build/synth/report.json, else the committed
    docs/synthesis.json): LUT4, Fmax, pixels per second per LUT4. Kept in the report so that
    the page compares with the figure of the day of the run."""
    for p in (ROOT / "build" / "synth" / "report.json", ROOT / "docs" / "synthesis.json"):
        try:
            r = json.loads(p.read_text())["top_ecp5"]
            if r.get("pixels_per_second_per_lut4"):
                return {"luts": r["luts"], "fmax_mhz": r["fmax_mhz"],
                        "pixels_per_second_per_lut4": r["pixels_per_second_per_lut4"], "from": rel(p)}
        except (OSError, ValueError, KeyError, TypeError):
            continue
    return None


def write_report(report: dict, full: bool) -> Path:
    """build/asic/report.json (a full run; also the page's docs/asic.json) or, for a subset of
    the units, build/asic/report_partial.json: a subset never replaces the whole."""
    text = json.dumps(report, indent=2) + "\n"
    out = OUT / ("report.json" if full else "report_partial.json")
    out.write_text(text)
    if full:
        DATA.write_text(text)
    return out


def read_data(path: Path = DATA) -> dict:
    try:
        return json.loads(path.read_text())
    except (OSError, ValueError) as e:
        raise AsicError(f"no readable {rel(path)} ({e}): run make asic first") from None
