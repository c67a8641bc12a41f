"""Power of one mapped module from switching activity: the flip-flops' outputs, the inputs and
the macros' outputs take their toggle rate and duty from the simulation; the combinational
nets get theirs by propagation through the cells' logic functions (Najm's transition density,
D(y) = sum_i P(dy/dx_i) D(x_i), and the signal probability, inputs taken as independent); each
cell then costs its liberty internal energy per output and input transition, each net
C V^2 / 2 per toggle (pin capacitances plus a wire estimate), and its leakage."""
from __future__ import annotations

import math
from collections import defaultdict
from dataclasses import dataclass, field
from itertools import product

from .liberty import Cell, truth_table
from .netlist import Module

VDD = 1.8                     # the liberty's typical corner (osu018_stdcells.lib: 1.8 V, 25 C)
SLEW_NS = 0.2                 # input slew at which internal energy is read (pre-layout)
# Wire capacitance: metal2 of the library's LEF (osu018_stdcells.lef: width 0.3 um, 1.9e-5 pF/um^2
# over the area, 6e-5 pF/um per edge, two edges), a net's length estimated as one cell pitch per
# pin it joins (driver and loads), the pitch that of the mean cell at 70 % utilisation.
WIRE_PF_PER_UM = 0.3 * 1.9e-5 + 2 * 6e-5
UTILISATION = 0.7
CLOCKS = ("clk_i",)


@dataclass
class Source:
    """A net whose activity the simulation gives: toggles per clock and probability of 1."""
    d: float
    p: float


@dataclass
class ModulePower:
    """Energy per clock (pJ) by kind and by unit, leakage (nW) and the activity's coverage."""
    internal_pj: float = 0.0
    switching_pj: float = 0.0
    clock_pj: float = 0.0                    # the clock net and the flip-flops' clock pins
    leakage_nw: float = 0.0
    by_unit: dict[str, float] = field(default_factory=lambda: defaultdict(float))
    flops: int = 0
    flops_traced: int = 0
    inputs: int = 0
    inputs_traced: int = 0
    macro_outputs: int = 0
    macro_outputs_traced: int = 0
    mean_flop_toggle: float = 0.0

    @property
    def dynamic_pj(self) -> float:
        return self.internal_pj + self.switching_pj + self.clock_pj


_FUNCS: dict[tuple[str, str], tuple[list[str], list[int]]] = {}


def _function(cell: Cell, pin: str) -> tuple[list[str], list[int]]:
    """Inputs and truth table (index: input bits, first input most significant) of an output."""
    key = (cell.name, pin)
    if key not in _FUNCS:
        ins = [p.name for p in cell.pins.values() if p.direction == "input"]
        f = truth_table(cell.pins[pin].function, ins)
        _FUNCS[key] = (ins, [f(dict(zip(ins, bits))) for bits in product((0, 1), repeat=len(ins))])
    return _FUNCS[key]


def _propagate(ins: list[str], table: list[int], acts: list[Source]) -> Source:
    n = len(ins)
    p1, d = 0.0, 0.0
    probs = []
    for idx, val in enumerate(table):
        pr = 1.0
        for k in range(n):
            b = (idx >> (n - 1 - k)) & 1
            pr *= acts[k].p if b else 1.0 - acts[k].p
        probs.append(pr)
        p1 += pr * val
    for k in range(n):
        if acts[k].d == 0:
            continue
        bitk = 1 << (n - 1 - k)
        # P(dy/dx_k): probability over the other inputs that flipping x_k flips y
        sens = 0.0
        for idx in range(len(table)):
            if idx & bitk or table[idx] == table[idx | bitk]:
                continue
            pk = acts[k].p
            pr = probs[idx] / (1.0 - pk) if pk < 1.0 else 0.0
            sens += pr
        d += sens * acts[k].d
    return Source(d, min(max(p1, 0.0), 1.0))


def pitch_um(mod: Module, lib: dict[str, Cell], areas: dict[str, float]) -> float:
    cells = [areas[i.type] for i in mod.insts if i.type in areas]
    return math.sqrt((sum(cells) / len(cells)) / UTILISATION) if cells else 10.0


def module_power(mod: Module, lib: dict[str, Cell], areas: dict[str, float], sources: dict[str, Source],
                 fallback: Source, unit_of=None) -> ModulePower:
    """Energy per clock of `mod`. `sources` maps net names (any alias) to the simulated activity of
    flip-flop outputs, inputs and macro outputs; one not found takes `fallback`. `unit_of(net)`
    names the unit a named net belongs to (default: its first hierarchy level)."""
    unit_of = unit_of or (lambda n: n.split(".")[0] if "." in n else "(top level)")
    res = ModulePower()
    names = mod.names_of()
    rep = mod.rep

    def simulated(net: str) -> Source | None:
        for n in names.get(rep(net), [net]) + [net]:
            if n in sources:
                return sources[n]
        return None

    act: dict[str, Source] = {"0": Source(0.0, 0.0), "1": Source(0.0, 1.0)}
    loads: dict[str, list[tuple[object, str]]] = defaultdict(list)
    drivers: dict[str, tuple[object, str]] = {}
    for inst in mod.insts:
        cell = lib.get(inst.type)
        for pin, nets in inst.pins.items():
            lp = cell.pins.get(pin) if cell else None
            out = (lp.direction == "output") if lp else pin.endswith("_o") or pin in ("Q", "Y")
            for n in nets:
                (drivers.__setitem__(rep(n), (inst, pin)) if out else loads[rep(n)].append((inst, pin)))
    # sources: inputs, flip-flop outputs, outputs of cells not in the library (macros, black boxes)
    traced_toggles = []
    for n in mod.inputs:
        r = rep(n)
        if n in CLOCKS:
            act[r] = Source(2.0, 0.5)
            continue
        s = simulated(n)
        res.inputs += 1
        res.inputs_traced += s is not None
        act[r] = s or fallback
    for inst in mod.insts:
        cell = lib.get(inst.type)
        if cell is not None and not cell.seq:
            continue
        for pin, nets in inst.pins.items():
            if cell is not None and pin not in cell.seq_out:
                continue
            if cell is None and not (pin.endswith("_o") or "rdata" in pin):
                continue
            for n in nets:
                if n in ("0", "1"):
                    continue
                s = simulated(n)
                if cell is not None:
                    res.flops += 1
                    res.flops_traced += s is not None
                    if s is not None:
                        traced_toggles.append(s.d)
                else:
                    res.macro_outputs += 1
                    res.macro_outputs_traced += s is not None
                act[rep(n)] = s or fallback
    res.mean_flop_toggle = sum(traced_toggles) / len(traced_toggles) if traced_toggles else 0.0
    # combinational cells in topological order
    comb = [i for i in mod.insts if i.type in lib and not lib[i.type].seq]
    waiting: dict[int, int] = {}
    users: dict[str, list[int]] = defaultdict(list)
    for k, inst in enumerate(comb):
        cell = lib[inst.type]
        need = {r for r in (rep(inst.pins[p.name][0]) for p in cell.pins.values()
                            if p.direction == "input" and p.name in inst.pins) if r not in act}
        waiting[k] = len(need)
        for r in need:
            users[r].append(k)
    ready = [k for k, w in waiting.items() if w == 0]
    order = []
    while ready:
        k = ready.pop()
        order.append(k)
        inst, cell = comb[k], lib[comb[k].type]
        for p in cell.pins.values():
            if p.direction != "output" or p.name not in inst.pins:
                continue
            ins, table = _function(cell, p.name)
            a = _propagate(ins, table, [act.get(rep(inst.pins[i][0]), fallback) if i in inst.pins else fallback
                                        for i in ins])
            r = rep(inst.pins[p.name][0])
            if r in act:
                continue
            act[r] = a
            for u in users.get(r, ()):
                waiting[u] -= 1
                if waiting[u] == 0:
                    ready.append(u)
    for k, inst in enumerate(comb):          # cells on a loop (none expected): the fallback
        if waiting[k] > 0:
            for p in lib[inst.type].pins.values():
                if p.direction == "output" and p.name in inst.pins:
                    act.setdefault(rep(inst.pins[p.name][0]), fallback)
    # units: a named net's own; an anonymous cell takes the unit of the first of its loads that has one
    pitch = pitch_um(mod, lib, areas)
    inst_unit: dict[int, str] = {}

    def named_unit(net: str) -> str | None:
        for n in names.get(rep(net), [net]) + [net]:
            if not n.startswith("_") and n not in ("0", "1"):
                return unit_of(n)
        return None

    for inst in mod.insts:
        outs = [n for pin, nets in inst.pins.items() for n in nets if drivers.get(rep(n), (None,))[0] is inst]
        u = next((named_unit(n) for n in outs if named_unit(n)), None)
        if u:
            inst_unit[id(inst)] = u
    for k in reversed(order):
        inst = comb[k]
        if id(inst) in inst_unit:
            continue
        outs = [n for pin, nets in inst.pins.items() for n in nets if drivers.get(rep(n), (None,))[0] is inst]
        for n in outs:
            for li, _ in loads.get(rep(n), ()):
                if id(li) in inst_unit:
                    inst_unit[id(inst)] = inst_unit[id(li)]
                    break
            if id(inst) in inst_unit:
                break
    # energy per clock
    clock_reps = {rep(c) for c in CLOCKS}
    for r, ls in loads.items():
        cap = sum(lib[i.type].pins[p].cap_pf if i.type in lib and p in lib[i.type].pins else 0.02
                  for i, p in ls) + WIRE_PF_PER_UM * pitch * (len(ls) + 1)
        a = act.get(r, fallback)
        e = 0.5 * cap * VDD * VDD * a.d
        drv = drivers.get(r)
        if r in clock_reps:
            res.clock_pj += e
            continue
        res.switching_pj += e
        unit = inst_unit.get(id(drv[0])) if drv else None
        res.by_unit[unit or named_unit(r) or "(other)"] += e
        if drv and drv[0].type in lib:
            inst, pin = drv
            cell = lib[inst.type]
            entries = cell.pins[pin].power
            if cell.seq:
                entries = [w for w in entries if w.related == "CLK"] or entries
            if entries:
                ei = a.d * sum(w.energy(cap, SLEW_NS) for w in entries) / len(entries)
                res.internal_pj += ei
                res.by_unit[unit or "(other)"] += ei
    for inst in mod.insts:
        cell = lib.get(inst.type)
        if cell is None:
            continue
        res.leakage_nw += cell.leakage_nw
        for pin, nets in inst.pins.items():
            lp = cell.pins.get(pin)
            if lp is None or lp.direction != "input" or not lp.power or not nets:
                continue
            a = act.get(rep(nets[0]), fallback)
            e = a.d * sum(w.energy(0.0, SLEW_NS) for w in lp.power) / len(lp.power)
            if rep(nets[0]) in clock_reps:
                res.clock_pj += e
            else:
                res.internal_pj += e
            res.by_unit[inst_unit.get(id(inst), "(other)")] += e if rep(nets[0]) not in clock_reps else 0.0
        if cell.seq:
            res.by_unit[inst_unit.get(id(inst), "(other)")] += 0.0
    return res
