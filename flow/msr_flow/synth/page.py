"""docs/synthesis.md: the report's figures as table rows (`page_model`), rendered through the
Jinja2 template msr_flow/templates/synthesis.md.j2."""
from __future__ import annotations

import json
import re
from dataclasses import dataclass
from pathlib import Path

import jinja2

from .config import (DOC, ECP5_DEVICE, ECP5_DP16KD, ECP5_LUTS, ECP5_PLACER_ARGS, ECP5_ROUTER, ECP5_SPEED,
                     ECP5_TARGET_MHZ, ENGINE, TOP)
from .report import pixels_per_clock

TEMPLATE = "synthesis.md.j2"
# a merged row's kind names the run and its commit; the page keeps only that it is a unit run
UNIT_RUN = re.compile(r"\s*\(unit run at [^)]*\)")


def fmt(n) -> str:
    """An integer with thin groups of three (12 345); anything else as it is."""
    return f"{n:,}".replace(",", " ") if isinstance(n, int) else str(n)


def params_text(p: dict) -> str:
    return ", ".join(f"{k} {v}" for k, v in p.items()) or "defaults"


def doc_pixels_per_clock(report: dict) -> tuple[float, str]:
    """The pixels per clock the page names: the one the top's row was computed with (a --merge of
    unit rows keeps the top's row, so its figure must not be re-read from a bench report this
    machine may not have), else the current figure."""
    row = report.get("ecp5", {}).get(TOP, {})
    if "pixels_per_clock" in row:
        return row["pixels_per_clock"], row.get("pixels_per_clock_source", "top row")
    return pixels_per_clock()


@dataclass(frozen=True)
class GenericRow:
    module: str
    kind: str
    unit_run: bool          # measured by a unit run merged into the whole design's report
    run: dict


@dataclass(frozen=True)
class Ecp5Row:
    name: str
    unit_run: bool
    run: dict


def generic_table(report: dict) -> list[GenericRow]:
    return [GenericRow(mod, UNIT_RUN.sub("", kind), bool(UNIT_RUN.search(kind)), r)
            for mod, runs in report["generic"].items() for kind, r in runs.items()]


def ecp5_table(report: dict) -> list[Ecp5Row]:
    return [Ecp5Row(f"`{TOP}` glue ({ENGINE} black-boxed)" if mod == f"{TOP}_glue" else f"`{mod}`",
                    "merged_from" in r, r)
            for mod, r in report["ecp5"].items()]


def page_model(report: dict) -> dict:
    """Everything the template shows, from a report (report.json or docs/synthesis.json)."""
    ppc, ppc_source = doc_pixels_per_clock(report)
    top = report["ecp5"].get(TOP, {})
    return {"report": report, "TOP": TOP, "ENGINE": ENGINE, "generic": generic_table(report),
            "ecp5": ecp5_table(report), "device": ECP5_DEVICE, "speed": ECP5_SPEED, "device_luts": ECP5_LUTS,
            "device_dp16kd": ECP5_DP16KD, "placer_args": " ".join(ECP5_PLACER_ARGS),
            "placer_weight": ECP5_PLACER_ARGS[-1], "router": ECP5_ROUTER,
            "target_mhz": top.get("target_mhz", ECP5_TARGET_MHZ),
            "ppc": ppc, "ppc_source": ppc_source, "top": top if "fmax_seeds" in top else None,
            "picture": (str(Path(top["floorplan_picture"]).relative_to("docs")) if top.get("floorplan_picture")
                        else None)}


def environment() -> jinja2.Environment:
    env = jinja2.Environment(loader=jinja2.PackageLoader("msr_flow", "templates"), trim_blocks=True,
                             lstrip_blocks=True, keep_trailing_newline=True, undefined=jinja2.StrictUndefined,
                             autoescape=False)      # Markdown, not HTML
    env.filters["fmt"] = fmt
    env.filters["params"] = params_text
    env.filters["json"] = json.dumps
    return env


def render(report: dict) -> str:
    """docs/synthesis.md's text for a report."""
    return environment().get_template(TEMPLATE).render(page_model(report))


def write_doc(report: dict, path: Path = DOC) -> None:
    path.write_text(render(report))
