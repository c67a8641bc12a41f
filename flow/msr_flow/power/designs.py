"""The mapped netlists power is computed on: make asic's engine and the top's glue (the engines
black boxes), with the same calls as msr_flow.asic so its cached results (build/asic/*.stamp)
are reused and a run here leaves them for make asic."""
from __future__ import annotations

from dataclasses import dataclass

from ..asic.config import AsicError
from ..asic.mapping import Mapped, map_unit
from ..synth import ENGINE, TOP, default_params, read_filelist


@dataclass
class Designs:
    engine: Mapped
    glue: Mapped
    top_params: dict


def map_designs(with_top: bool = True) -> Designs:
    files = read_filelist()
    top_params = default_params(files, TOP)
    engine_params = {k: top_params[k] for k in default_params(files, ENGINE) if k in top_params}
    eng = map_unit(files, ENGINE, engine_params)
    glue = map_unit(files, TOP, None, blackbox=ENGINE, tag=f"{TOP}_glue", bb_netlist=eng.netlist) if with_top else None
    if with_top and glue is None:
        raise AsicError(f"{TOP}: the glue did not map")
    return Designs(eng, glue, top_params)


if __name__ == "__main__":
    d = map_designs()
    print(f"power: {d.engine.netlist} and {d.glue.netlist} mapped")
