"""One rule's frame through the traced harness, and the power of the engine and the top from
its activity: the gate-level model (model.py) on every engine instance and on the top's glue,
the tile buffers from their enables and the cited macro energies (memory.py)."""
from __future__ import annotations

import json
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

from ..asic.tools import liberty_areas
from ..filelist import ROOT
from . import memory
from .activity import cycles, duty_cycles, sources_at, top_scope
from .liberty import Cell
from .model import ModulePower, Source, module_power
from .netlist import Module
from .vcd import read_activity, vcd_lines

ENGINE_TYPE = "msr_tile_engine"
SRAM_PREFIX = "msr_tile_sram_"


@dataclass
class RuleResult:
    rule: str
    width: int
    height: int
    cycles: int
    pixels: int
    decisions: int
    clock_mhz: float
    engines: dict[str, ModulePower] = field(default_factory=dict)
    sram_pj: dict[str, float] = field(default_factory=dict)        # engine instance -> pJ over the frame
    sram_accesses: dict[str, dict] = field(default_factory=dict)
    glue: ModulePower | None = None
    seconds: float = 0.0


def run_frame(harness: Path, rule: str, width: int, height: int, out: Path, scene: str = "cornell") -> dict:
    """The frame through the harness (make sim's script) with the whole frame in the FST; reused
    when its report is newer than the harness."""
    rep, fst = out / "report.json", out / "waves.fst"
    if rep.is_file() and fst.is_file() and rep.stat().st_mtime > harness.stat().st_mtime:
        r = json.loads(rep.read_text())
        if (r.get("width"), r.get("height"), r.get("rule")) == (width, height, rule):
            return r
    cmd = [sys.executable, str(ROOT / "scripts" / "run_sim.py"), "--harness", str(harness), "--scene", scene,
           "--width", str(width), "--height", str(height), "--rule", rule, "--waves",
           "--wave-cycles", "0,1000000000000", "--out", str(out)]
    print(f"power: {rule}: {scene} {width}x{height} frame through {harness}", file=sys.stderr, flush=True)
    subprocess.run(cmd, cwd=ROOT, check=True)
    return json.loads(rep.read_text())


def engine_instances(glue: Module) -> list[str]:
    return [i.name for i in glue.insts if i.type == ENGINE_TYPE]


def sram_energy(engine: Module, act, scope: str, n: int) -> tuple[float, dict]:
    """pJ of the tile buffers over the frame: reads per read port in use, writes into every macro."""
    total, acc = 0.0, {"reads": 0.0, "writes": 0.0}
    for inst in engine.insts:
        if not inst.type.startswith(SRAM_PREFIX):
            continue
        depth, width = (int(x) for x in inst.type[len(SRAM_PREFIX):].split("x"))
        e = memory.per_access(depth, width)
        ports = [p for p in ("re0_i", "re1_i") if inst.pins.get(p) not in (["0"], None)]
        reads = sum(duty_cycles(act, f"{scope}.{inst.name}.{p}", n) for p in ports)
        writes = duty_cycles(act, f"{scope}.{inst.name}.we_i", n) * len(ports)
        total += reads * e.read_pj + writes * e.write_pj
        acc["reads"] += reads
        acc["writes"] += writes
    return total, acc


def power_of_rule(harness: Path, rule: str, width: int, height: int, engine: Module, glue: Module,
                  lib: dict[str, Cell], lib_path: Path, clock_mhz: float) -> RuleResult:
    t0 = time.time()
    out = ROOT / "build" / "power" / f"sim_{rule}"
    rep = run_frame(harness, rule, width, height, out)
    print(f"power: {rule}: reading the activity of {out / 'waves.fst'}", file=sys.stderr, flush=True)
    act = read_activity(vcd_lines(out / "waves.fst"), want=lambda p: ".u_top." in p)
    scope = top_scope(act)
    n = cycles(act, scope)
    pixels = width * height
    res = RuleResult(rule, width, height, n, pixels, pixels - rep["perf_counters"]["traced_initial"], clock_mhz)
    areas = liberty_areas(lib_path)
    insts = engine_instances(glue)
    for name in insts:
        src = sources_at(act, f"{scope}.{name}", n)
        mean = [s.d for s in src.values()]
        fb = Source(sum(mean) / len(mean) if mean else 0.0, 0.5)
        res.engines[name] = module_power(engine, lib, areas, src, fb)
        res.sram_pj[name], res.sram_accesses[name] = sram_energy(engine, act, f"{scope}.{name}", n)
        print(f"power: {rule}: {name}: {res.engines[name].flops_traced} of {res.engines[name].flops} flip-flops "
              f"traced", file=sys.stderr, flush=True)
    src = sources_at(act, scope, n, skip=tuple(insts))
    # the glue's nets driven by an engine: the engine ports' activity, named as the glue names them
    for name in insts:
        for k, s in sources_at(act, f"{scope}.{name}", n).items():
            if "." not in k:
                src.setdefault(f"{name}.{k}", s)
    mean = [s.d for s in src.values()]
    res.glue = module_power(glue, lib, areas, src, Source(sum(mean) / len(mean) if mean else 0.0, 0.5))
    res.seconds = round(time.time() - t0, 1)
    return res
