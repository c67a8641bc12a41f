"""A Yosys gate-level netlist (write_verilog -noattr -noexpr -simple-lhs) read into bit-level
nets: every module's cell instances with their pins' nets, its ports, and the nets an
`assign` joins (one electrical net under several names)."""
from __future__ import annotations

import re
from dataclasses import dataclass, field


@dataclass
class Inst:
    name: str
    type: str
    pins: dict[str, list[str]]          # pin -> nets, most significant bit first


@dataclass
class Module:
    name: str
    inputs: list[str] = field(default_factory=list)        # bit nets
    outputs: list[str] = field(default_factory=list)
    widths: dict[str, tuple[int, int]] = field(default_factory=dict)
    insts: list[Inst] = field(default_factory=list)
    alias: dict[str, str] = field(default_factory=dict)    # net -> its representative

    def rep(self, net: str) -> str:
        seen = net
        while seen in self.alias and self.alias[seen] != seen:
            seen = self.alias[seen]
        return seen

    def names_of(self) -> dict[str, list[str]]:
        """Representative -> every name of that net."""
        out: dict[str, list[str]] = {}
        for n in set(self.alias) | {r for r in self.alias.values()}:
            out.setdefault(self.rep(n), []).append(n)
        return out


IDENT = r"(?:\\\S+|[A-Za-z_][\w$]*)"


def bit(name: str, i: int | None) -> str:
    """The canonical name of one bit: `base[i]` (escapes dropped), or `base` for a scalar."""
    base = name[1:] if name.startswith("\\") else name
    return base if i is None else f"{base}[{i}]"


def expand(expr: str, widths: dict[str, tuple[int, int]]) -> list[str]:
    """The bits of a connection expression, most significant first; a constant bit is '0'/'1'."""
    expr = expr.strip()
    if not expr:
        return []
    if expr.startswith("{"):
        parts, depth, cur = [], 0, ""
        for ch in expr[1:-1]:
            if ch == "," and depth == 0:
                parts.append(cur)
                cur = ""
                continue
            depth += ch in "{"
            depth -= ch in "}"
            cur += ch
        parts.append(cur)
        return [b for p in parts for b in expand(p, widths)]
    m = re.fullmatch(r"(\d+)'([bhdo])([0-9a-fA-FxXzZ_]+)", expr)
    if m:
        n, base, digits = int(m.group(1)), m.group(2), m.group(3).replace("_", "").lower()
        if any(c in "xz" for c in digits):
            return ["0"] * n
        v = int(digits, {"b": 2, "h": 16, "d": 10, "o": 8}[base])
        return [str((v >> i) & 1) for i in range(n - 1, -1, -1)]
    m = re.fullmatch(rf"({IDENT})\s*(?:\[(\d+)(?::(\d+))?\])?", expr)
    if not m:
        raise ValueError(f"netlist: cannot read the connection {expr!r}")
    name, hi, lo = m.group(1), m.group(2), m.group(3)
    key = name[1:] if name.startswith("\\") else name
    if hi is not None and lo is None:
        return [bit(name, int(hi))]
    if key in widths:
        msb, lsb = widths[key]
        if hi is not None:
            msb, lsb = int(hi), int(lo)
        step = -1 if msb >= lsb else 1
        return [bit(name, i) for i in range(msb, lsb + step, step)]
    return [bit(name, None)]


def read_netlist(text: str) -> dict[str, Module]:
    mods: dict[str, Module] = {}
    for mm in re.finditer(r"^module\s+(\S+?)\s*\((.*?)^endmodule", text, re.M | re.S):
        mod = Module(mm.group(1))
        body = mm.group(2)
        stmts = [s.strip() for s in re.split(r";\s*\n", body)]
        for s in stmts:
            m = re.match(rf"(input|output|inout|wire)\s+(?:\[(\d+):(\d+)\]\s+)?({IDENT})\s*$", s)
            if m:
                key = m.group(4)[1:] if m.group(4).startswith("\\") else m.group(4)
                if m.group(2) is not None:
                    mod.widths[key] = (int(m.group(2)), int(m.group(3)))
                if m.group(1) in ("input", "output"):
                    (mod.inputs if m.group(1) == "input" else mod.outputs).append(m.group(4))
        mod.inputs = [b for p in mod.inputs for b in expand(p, mod.widths)]
        mod.outputs = [b for p in mod.outputs for b in expand(p, mod.widths)]
        for s in stmts:
            m = re.match(r"assign\s+(.*?)\s*=\s*(.*)$", s, re.S)
            if m:
                lhs, rhs = expand(m.group(1), mod.widths), expand(m.group(2), mod.widths)
                for a, b in zip(lhs, rhs[-len(lhs):] if lhs else []):
                    ra, rb = mod.rep(a), mod.rep(b)
                    if ra != rb:
                        # a constant or a driven net is the representative
                        if ra in ("0", "1"):
                            mod.alias[rb] = ra
                        else:
                            mod.alias[ra] = rb
                continue
            m = re.match(rf"({IDENT})\s+({IDENT})\s*\((.*)\)\s*$", s, re.S)
            if m and m.group(1) not in ("input", "output", "wire", "inout", "assign"):
                pins = {p: expand(e, mod.widths) for p, e in re.findall(r"\.(\w+)\s*\(\s*(.*?)\s*\)\s*(?=,\s*\.|$)",
                                                                         m.group(3), re.S)}
                name = m.group(2)[1:] if m.group(2).startswith("\\") else m.group(2)
                mod.insts.append(Inst(name, m.group(1), pins))
        mods[mod.name] = mod
    return mods
