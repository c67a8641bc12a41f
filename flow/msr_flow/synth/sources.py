"""The RTL as the synthesis flows see it: the sources of rtl/msr.f, the modules they define,
a module's parameter defaults and names, and the Yosys (slang) front-end command that reads
them. The standard-cell flow reads the RTL through the same helpers."""
from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

from msr_flow.filelist import rtl_incdirs, rtl_sources

from .config import ENGINE, FILELIST, ROOT, SRAM_HINT, TOP


def read_filelist(path: Path = FILELIST) -> list[str]:
    """Source files of rtl/msr.f, relative to the repo root (the YoWASP sandbox sees only cwd)."""
    return [str(p.resolve().relative_to(ROOT)) for p in rtl_sources(path)]


def incdirs(path: Path = FILELIST) -> list[str]:
    """Include folders of rtl/msr.f, relative to the repo root."""
    return [str(p.resolve().relative_to(ROOT)) for p in rtl_incdirs(path)]


def modules_in(files: list[str]) -> list[str]:
    """Every module the files define, in file-list order."""
    mods = []
    for f in files:
        for m in re.finditer(r"^\s*module\s+(\w+)", (ROOT / f).read_text(), re.M):
            mods.append(m.group(1))
    return mods


def default_params(files: list[str], module: str) -> dict[str, int]:
    """Integer parameter defaults of `module`'s header (`parameter int unsigned NAME = 4,`)."""
    for f in files:
        text = (ROOT / f).read_text()
        m = re.search(rf"^\s*module\s+{module}\b(.*?)\)\s*\(", text, re.M | re.S)
        if m:
            return {n: int(v) for n, v in re.findall(r"parameter\s+int\s+unsigned\s+(\w+)\s*=\s*(\d+)\b", m.group(1))}
    raise ValueError(f"module {module} not in the file list")


def bb_param_names(files: list[str], module: str) -> list[str]:
    """Every parameter, localparam and genvar name of `module`: the front end leaves them on
    a black-boxed instance, and a mapped netlist of the module takes none."""
    for f in files:
        text = (ROOT / f).read_text()
        m = re.search(rf"^\s*module\s+{module}\b(.*?)^\s*endmodule", text, re.M | re.S)
        if m:
            body = m.group(1)
            # (an unpacked dimension may follow the name: localparam t NAME [8] = ...)
            names = re.findall(r"\b(?:parameter|localparam)\s+(?:\w+\s+)*?(\w+)\s*(?:\[[^\]]*\]\s*)*=", body)
            names += re.findall(r"\bgenvar\s+(\w+)", body)
            return sorted(set(names))
    raise ValueError(f"module {module} not in the file list")


def read_cmd(files: list[str], top: str, blackbox: str | None = None, params: dict | None = None) -> str:
    """The Yosys lines that read `files` with slang, `top` as the top (its parameters
    overridden by `params`), `blackbox` (a module) kept as an empty box."""
    # the level controller's grid loops unroll past slang's default limit of 4000
    overrides = "".join(f" -G {k}={v}" for k, v in (params or {}).items())
    includes = " ".join(f"-I {d}" for d in incdirs())
    return ("slang_defaults -add --threads 1\n"
            + f"read_slang --unroll-limit=100000 {includes} {' '.join(files)} --top {top}"
            + overrides + (f" --blackboxed-module {blackbox}" if blackbox else "") + "\n")


@dataclass(frozen=True)
class Design:
    """What a run synthesises: the sources, the units they define (packages left out), the
    tile SRAM module, and the parameters of the default top and of the engine inside it."""

    files: list[str]
    units: list[str]
    sram: str
    top_params: dict[str, int]
    engine_params: dict[str, int]

    @classmethod
    def read(cls, path: Path = FILELIST) -> "Design":
        files = read_filelist(path)
        units = [m for m in modules_in(files) if not m.endswith("_pkg")]
        top_params = default_params(files, TOP)
        return cls(files=files, units=units, sram=[m for m in units if SRAM_HINT in m][0], top_params=top_params,
                   engine_params={k: top_params[k] for k in default_params(files, ENGINE) if k in top_params})

    @property
    def n_engines(self) -> int:
        return self.top_params["NUM_ENGINES"]
