"""docs/asic.md, rendered from the report (docs/asic.json) with the Jinja2 template
templates/asic.md.j2: the template holds the prose, this module the number formats."""
from __future__ import annotations

import math

import xml.etree.ElementTree as ET
from pathlib import Path

import jinja2

from ..filelist import ROOT
from ..synth import ENGINE, TOP, params_text
from .config import CELL_MODELS, DOC, GATE_RESULTS, GATE_RESULTS_RL4, SCALING, rel

TEMPLATES = Path(__file__).resolve().parents[1] / "templates"


def fmt_int(n) -> str:
    """1 234 567: thousands apart by a space (the page's style)."""
    return f"{n:,}".replace(",", " ") if isinstance(n, (int, float)) else str(n)


def pct(share: float) -> str:
    return f"{100 * share:.0f}"


def path_text(p: dict | None, cells: int = 40) -> str:
    """A critical path in a sentence: its ends (with their registers' names), arrival, slack,
    gate count and the cells along it."""
    if not p:
        return "(none)"
    seq = " -> ".join(p["cells"][:cells]) + (" ..." if len(p["cells"]) > cells else "")
    start = p["start"].split(" (")[0] + (f" (register `{p['start_register']}`)" if p.get("start_register") else "")
    end = p["end"].split(" (")[0] + (f" (register `{p['end_register']}`)" if p.get("end_register") else "")
    return (f"from {start} to {end}, arrival {p['arrival_ns']} ns, slack {p['slack_ns']} ns, "
            f"{p['depth']} gates: {seq}")


def path_end(p: dict, key: str) -> str:
    """A path end for the table: the register's name, else the port or pin."""
    return f"`{p[key + '_register']}`" if p.get(key + "_register") else f"`{p.get(key, '').split(' ')[0]}`"


def gate_level_result(results: Path = GATE_RESULTS, results_rl4: Path | None = GATE_RESULTS_RL4) -> dict | None:
    """The gate-level bench's last result (cocotb's results.xml), None when it has not run here;
    with the result on the RD_LAT 4 netlist under "rd_lat_4" when that has run too."""
    rl4 = gate_level_result(results_rl4, None) if results_rl4 is not None else None
    if not results.is_file():
        return {"result": "not run here", "from": None, "rd_lat_4": rl4} if rl4 else None
    failed = any(t.tag in ("failure", "error") for t in ET.parse(results).iter())
    where = rel(results) if results.is_relative_to(ROOT) else str(results)
    out = {"result": "FAILED" if failed else "passed", "from": where}
    if rl4:
        out["rd_lat_4"] = rl4
    return out


def gate_level_text(gl: dict | None) -> str:
    if not gl:
        return "not run yet (`make test-gate` runs it)"
    text = f"{gl['result']} (`make test-gate`" + (f", {gl['from']})" if gl.get("from") else ")")
    rl4 = gl.get("rd_lat_4")
    return text + (f"; as the cited macro needs it (RD_LAT 4, BUF_CYCLE 5): {rl4['result']} ({rl4['from']})"
                   if rl4 else "")


def macro_cycle(sram: dict, period_ns: float, depth: int = 1024) -> dict:
    """What the cited macro asks of a DEPTH-word tile buffer at the clock: its clock-to-data and
    minimum clock period, each the 512-word point plus the per-doubling step between the two
    published points (sram_macro.json's access rule, applied to the period alike), in ns and in
    whole clocks."""
    a, b = sram["source"]["points"]
    doublings = math.log2(depth / 512)
    dbl = math.log2((b["bits"] // 8) / (a["bits"] // 8))

    def at(key: str) -> float:
        return b[key] + (b[key] - a[key]) / dbl * doublings
    access, cycle = at("clk_to_q_ns"), at("min_period_ns")
    return {"depth": depth, "access_ns": round(access, 3), "cycle_ns": round(cycle, 3),
            "access_clocks": math.ceil(access / period_ns), "cycle_clocks": math.ceil(cycle / period_ns)}


def build_checks(report: dict) -> dict:
    """Per recorded memory build: its macro's access and cycle at the top's Fmax with the macro,
    against the RD_LAT and BUF_CYCLE clocks the RTL gives them (the cycle is not a timing arc of
    the macro's Liberty cell, so this is where it is checked)."""
    out = {}
    for tag, b in report.get("builds", {}).items():
        p = b["params"]
        fmax = b["modules"][TOP]["fmax_with_cited_sram_mhz"]
        mc = macro_cycle(report["sram_model"], 1000 / fmax, p.get("TILE_LIMIT", 32) ** 2)
        period = 1000 / fmax
        out[tag] = {"depth": mc["depth"], "period_ns": round(period, 3), "access_ns": mc["access_ns"],
                    "cycle_ns": mc["cycle_ns"], "read_ns": round(p.get("RD_LAT", 1) * period, 3),
                    "spacing_ns": round(p.get("BUF_CYCLE", 1) * period, 3),
                    "cycle_met": p.get("BUF_CYCLE", 1) * period >= mc["cycle_ns"]}
    return out


def environment() -> jinja2.Environment:
    env = jinja2.Environment(loader=jinja2.FileSystemLoader(TEMPLATES), trim_blocks=True, lstrip_blocks=True,
                             keep_trailing_newline=True, undefined=jinja2.Undefined, autoescape=False)
    env.filters.update(num=fmt_int, pct=pct, iround=round, params=params_text, path_text=path_text,
                       path_end=path_end)
    return env


def render(report: dict) -> str:
    """The page's text from a report (build/asic/report.json's schema)."""
    mods = report["modules"]
    eng, top = mods.get(ENGINE, {}), mods.get(TOP, {})
    top_ok = bool(top) and "error" not in top
    types = top.get("cells_by_type", {}) if top_ok else {}
    return environment().get_template("asic.md.j2").render(
        report=report, clk=report["clock"], mods=mods, eng=eng, top=top, ENGINE=ENGINE, TOP=TOP,
        ecp5=report.get("ecp5"), sram=report["sram_model"], src=report["sram_model"]["source"],
        scaling=SCALING, cell_models=str(CELL_MODELS), gate_level=gate_level_text(report.get("gate_level")),
        top_share=top.get("sequential_share", 0) if top_ok else 0,
        dffsr=types.get("DFFSR", 0), dff=types.get("DFFPOSX1", 0),
        top_area=max(1.0, top.get("area_um2", 1.0) if top_ok else 1.0),
        mc=macro_cycle(report["sram_model"], report["clock"]["period_ns"]),
        mc16=macro_cycle(report["sram_model"], report["clock"]["period_ns"], 256), checks=build_checks(report))


def write_doc(report: dict, doc: Path = DOC) -> None:
    doc.write_text(render(report))
