"""The parts of a liberty file that power needs: per cell its leakage, its pins' capacitances and
logic functions, the internal energy tables, and whether it is a flip-flop."""
from __future__ import annotations

import bisect
import re
from dataclasses import dataclass, field
from pathlib import Path


@dataclass
class Table:
    """An energy table: index_1 and (for 2-D) index_2, values in rows of index_1."""
    index_1: list[float]
    index_2: list[float]
    values: list[list[float]]
    var_1: str = ""

    def at(self, x1: float, x2: float = 0.0) -> float:
        """Bilinear interpolation, clamped to the table's edges."""
        def frac(idx, x):
            if len(idx) < 2:
                return 0, 0, 0.0
            x = min(max(x, idx[0]), idx[-1])
            j = min(max(bisect.bisect_right(idx, x) - 1, 0), len(idx) - 2)
            return j, j + 1, (x - idx[j]) / (idx[j + 1] - idx[j])
        if not self.index_2:
            row = self.values[0]
            a, b, t = frac(self.index_1, x1)
            return row[a] + t * (row[b] - row[a]) if len(row) > 1 else row[0]
        a, b, t = frac(self.index_1, x1)
        c, d, u = frac(self.index_2, x2)
        v = self.values
        lo = v[a][c] + u * (v[a][d] - v[a][c])
        hi = v[b][c] + u * (v[b][d] - v[b][c])
        return lo + t * (hi - lo)


@dataclass
class Power:
    related: str
    rise: Table | None
    fall: Table | None

    def energy(self, load_pf: float, slew_ns: float) -> float:
        """Mean of rise and fall energy (pJ) per transition at the load and input slew."""
        vals = []
        for t in (self.rise, self.fall):
            if t is None:
                continue
            if t.index_2:        # the templates here: variable_1 load, variable_2 slew
                vals.append(t.at(load_pf, slew_ns) if "capacitance" in t.var_1 else t.at(slew_ns, load_pf))
            else:
                vals.append(t.at(slew_ns))
        return sum(vals) / len(vals) if vals else 0.0


@dataclass
class Pin:
    name: str
    direction: str
    cap_pf: float = 0.0
    function: str = ""
    power: list[Power] = field(default_factory=list)


@dataclass
class Cell:
    name: str
    leakage_nw: float
    pins: dict[str, Pin]
    seq: bool
    seq_out: dict[str, str] = field(default_factory=dict)    # output pin -> "Q" or "QN"


def _groups(text: str):
    """Tokens of a liberty file: ('open', head, args), ('close',), ('attr', name, value)."""
    tok = re.compile(r'\s*(?:(/\*.*?\*/)|(\\\n)|(\})|([\w\[\]\.]+)\s*\(([^)]*)\)\s*(\{|;)?|([\w\.]+)\s*:\s*("[^"]*"|[^;]*);)', re.S)
    pos = 0
    while pos < len(text):
        m = tok.match(text, pos)
        if not m:
            pos += 1
            continue
        pos = m.end()
        if m.group(1) or m.group(2):
            continue
        if m.group(3):
            yield ("close",)
        elif m.group(4):
            if m.group(6) == "{":
                yield ("open", m.group(4), m.group(5).strip().strip('"'))
            else:
                yield ("attr", m.group(4), m.group(5))
        elif m.group(7):
            yield ("attr", m.group(7), m.group(8).strip().strip('"'))


def _floats(s: str) -> list[float]:
    return [float(x) for x in re.findall(r"[-+]?\d*\.?\d+(?:[eE][-+]?\d+)?", s)]


def read_liberty(path: Path) -> dict[str, Cell]:
    """Cell name -> Cell of the liberty at `path` (tables' indexes from their templates when absent)."""
    text = path.read_text()
    templates: dict[str, dict] = {}
    cells: dict[str, Cell] = {}
    stack: list[tuple[str, str, dict]] = []
    for t in _groups(text):
        if t[0] == "open":
            stack.append((t[1], t[2], {"attrs": {}, "kids": []}))
        elif t[0] == "attr":
            if stack:
                stack[-1][2]["attrs"].setdefault(t[1], t[2])
        else:
            if not stack:
                continue
            head, arg, body = stack.pop()
            node = (head, arg, body)
            if head in ("lu_table_template", "power_lut_template"):
                templates[arg] = body["attrs"]
            elif head == "cell":
                cells[arg] = _cell(arg, body, templates)
            elif stack:
                stack[-1][2]["kids"].append(node)
    return cells


def _table(node, templates) -> Table:
    _, arg, body = node
    a, tpl = body["attrs"], templates.get(node[1], {})
    idx1 = _floats(a.get("index_1", tpl.get("index_1", "")))
    idx2 = _floats(a.get("index_2", "")) if "index_2" in a or "index_2" in tpl else []
    if not idx2 and "index_2" in tpl:
        idx2 = _floats(tpl["index_2"])
    flat = _floats(a.get("values", ""))
    n2 = len(idx2) or len(flat)
    rows = [flat[i:i + n2] for i in range(0, len(flat), n2)] if n2 else [flat]
    return Table(idx1, idx2 if len(rows) > 1 else [], rows, tpl.get("variable_1", ""))


def _cell(name: str, body: dict, templates) -> Cell:
    pins: dict[str, Pin] = {}
    seq, seq_out, ff_vars = False, {}, ()
    for head, arg, kid in body["kids"]:
        if head in ("ff", "latch"):
            seq = True
            ff_vars = tuple(v.strip() for v in arg.split(","))
        if head != "pin":
            continue
        a = kid["attrs"]
        p = Pin(arg, a.get("direction", ""), float(a.get("capacitance", "0") or 0), a.get("function", ""))
        for h2, _, k2 in kid["kids"]:
            if h2 == "internal_power":
                tabs = {h3: (h3, a3, k3) for h3, a3, k3 in k2["kids"]}
                p.power.append(Power(k2["attrs"].get("related_pin", ""),
                                     _table(tabs["rise_power"], templates) if "rise_power" in tabs else None,
                                     _table(tabs["fall_power"], templates) if "fall_power" in tabs else None))
        pins[arg] = p
    if seq:
        for p in pins.values():
            if p.direction == "output" and p.function in ff_vars:
                seq_out[p.name] = "Q" if p.function == ff_vars[0] else "QN"
    return Cell(name, float(body["attrs"].get("cell_leakage_power", "0") or 0), pins, seq, seq_out)


def truth_table(function: str, inputs: list[str]):
    """The function as a callable over a dict of 0/1 inputs (liberty syntax: ! & * + | ^, and
    juxtaposition for AND)."""
    toks = re.findall(r"[A-Za-z_]\w*|[()!^+|&*]", function)
    out, prev = [], None
    for t in toks:
        operand_start = t[0].isalpha() or t[0] == "_" or t in ("(", "!")
        if prev is not None and (prev[0].isalpha() or prev[0] == "_" or prev == ")") and operand_start:
            out.append("&")
        out.append({"!": "~", "+": "|", "*": "&"}.get(t, t if not (t[0].isalpha() or t[0] == "_") else f"v['{t}']"))
        prev = t
    code = compile("(" + " ".join(out) + ") & 1", "<liberty function>", "eval")
    return lambda v: eval(code, {}, {"v": v})  # noqa: S307 (a liberty function, not user input)
