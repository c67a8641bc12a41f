"""From a frame's dump to the per-net activity of one mapped module instance: the signals under
the instance's scope keyed as the mapped netlist names its nets (`unit.reg[3]`), the clock
count, and the tile buffers' accesses (their enables' cycles at 1)."""
from __future__ import annotations

from .model import Source
from .vcd import Activity

TOP_INST = "u_top"           # msr_sim_top's instance of msr_top (sim/msr_sim_top.sv)


def top_scope(act: Activity) -> str:
    for p in act.vars:
        k = p.find(f".{TOP_INST}.")
        if k >= 0:
            return p[:k + len(TOP_INST) + 1]
    raise ValueError(f"no scope {TOP_INST} in the dump")


def cycles(act: Activity, scope: str) -> int:
    tog = act.toggles.get(f"{scope}.clk_i")
    if not tog:
        raise ValueError(f"no {scope}.clk_i in the dump")
    return tog[0] // 2


def sources_at(act: Activity, scope: str, n_cycles: int, skip: tuple[str, ...] = ()) -> dict[str, Source]:
    """Net name (relative to `scope`) -> Source, for every bit traced under `scope` (sub-scopes in
    `skip` left out)."""
    pre = scope + "."
    skips = tuple(pre + s + "." for s in skip)
    out: dict[str, Source] = {}
    for path, v in act.vars.items():
        if not path.startswith(pre) or (skips and path.startswith(skips)):
            continue
        rel = path[len(pre):]
        tog, high = act.toggles[path], act.high[path]
        for j in range(v.width):
            i = v.lsb + j if v.msb >= v.lsb else v.lsb - j
            s = Source(tog[j] / n_cycles, high[j] / act.span if act.span else 0.0)
            out[f"{rel}[{i}]"] = s
            if v.width == 1:
                out[rel] = s
    return out


def duty_cycles(act: Activity, path: str, n_cycles: int) -> float:
    """Clock cycles a 1-bit signal spends at 1 over the dump (0 when not traced)."""
    b = act.bit(path, None)
    return 0.0 if b is None else b[1] * n_cycles
