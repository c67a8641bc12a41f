"""The rows of the report: one per unit from its mapping and timing, and the default top built
from its parts (the glue mapped with the engines black-boxed, NUM_ENGINES x the engine, timed
whole); the rates per mm^2 of logic and the labelled estimates at other nodes."""
from __future__ import annotations

import json
import re

from ..filelist import ROOT
from ..synth import ENGINE, TOP, pixels_per_clock
from .config import COMB_CELLS, MACRO_JSON, OUT, SCALING, SEQ_CELLS, SRAM_MODULE, AsicError
from .macros import MacroModel
from .mapping import Mapped, map_unit
from .netlist import name_registers, netlist_figures
from .timing import fmax_mhz, fmax_with_macros, run_sta


def unit_row(m: Mapped, sta: dict, period_ns: float, nand2_um2: float, figures: dict,
             read_clocks: int = 1) -> dict:
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
            "fmax_with_cited_sram_mhz": fmax_with_macros(period_ns, sta, read_clocks),
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
        "fmax_with_cited_sram_mhz": fmax_with_macros(period_ns, sta, engine.get("sram_read_clocks", 1)),
        "sram_read_clocks": engine.get("sram_read_clocks", 1),
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


def top_row(files, mapped: dict, n: int, period_ns: float, nand2: float, params: dict | None = None) -> dict:
    """Map the glue (engines black-boxed), time the whole top with the engine's netlist in every
    engine instance, and compose the area. params: the top's parameters other than its defaults
    that its glue sees (TILE_LIMIT: the configuration check's)."""
    if ENGINE not in mapped:
        raise AsicError(f"{TOP} needs {ENGINE}'s netlist, and its run failed")
    eng = mapped[ENGINE]
    suffix = "".join(f"_{k.lower()}{v}" for k, v in sorted((params or {}).items()))
    glue = map_unit(files, TOP, params, blackbox=ENGINE, tag=f"{TOP}_glue{suffix}", bb_netlist=eng["mapped"].netlist)
    resized = [ln for ln in (OUT / f"{TOP}_glue{suffix}.synth.yosys.log").read_text().splitlines()
               if "Resizing cell port" in ln and SRAM_MODULE not in ln]
    if resized:
        raise AsicError(f"{TOP} glue: an engine port was resized ({resized[0].strip()})")
    text = glue.netlist.read_text()
    n_inst = len(re.findall(rf"^\s*{ENGINE}\s+\S+\s*\(", text, re.M))
    if n_inst != n:
        raise AsicError(f"{TOP} glue holds {n_inst} engine instances, expected {n}")
    figs = netlist_figures(text, TOP)
    rd_lat = eng["row"].get("sram_read_clocks", 1)
    sta = run_sta(TOP, [glue.netlist, eng["mapped"].netlist], OUT / f"{eng['mapped'].tag}.macros.lib",
                  period_ns, f"{TOP}_whole" + (f"_rl{rd_lat}" if rd_lat > 1 else "") + suffix, read_clocks=rd_lat)
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
