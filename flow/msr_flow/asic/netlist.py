"""Figures read from a mapped netlist: the largest fan-out, the logic depth (the longest chain
of gates between flip-flops, macros and ports) and the RTL names of a path's registers."""
from __future__ import annotations

import re
from pathlib import Path

from .config import COMB_CELLS, NOT_FANOUT, OUTPUT_PINS, SEQ_CELLS, AsicError


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
