"""Shared helpers of the tests of the Verilator full-frame harness (tb/msr_sim): build a
harness through make, run scripts/run_sim.py on it."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
# Each harness: the make command line that builds it and what it builds (mk/sim.mk).
HARNESSES = {
    "sim-build": (["sim-build"], ROOT / "build" / "sim" / "fast" / "Vmsr_sim_top"),           # make sim
    "sim-assert-build": (["sim-assert-build"], ROOT / "build" / "sim" / "assert" / "Vmsr_sim_top"),
    # make sim BUDGET=...: msr_top with the ray-budget controller (BUDGET_EN 1)
    "sim-budget-build": (["sim-build", "BUDGET=1"], ROOT / "build" / "sim" / "fast_budget" / "Vmsr_sim_top"),
    # make sim DEPTH=1: msr_top with the engines' depth channel (DEPTH_EN 1)
    "sim-depth-build": (["sim-build", "DEPTH=1"], ROOT / "build" / "sim" / "fast_depth" / "Vmsr_sim_top"),
}


def build_harness(name: str) -> Path:
    """Build a harness of HARNESSES through make and return its path. make test builds the
    harnesses before pytest starts (TEST_DEPS), so there this only checks they are up to date."""
    args, path = HARNESSES[name]
    subprocess.run(["make", "-s", *args], cwd=ROOT, check=True)
    return path


def run_sim(harness: Path, out: Path, *args: str, **kwargs) -> subprocess.CompletedProcess:
    """scripts/run_sim.py on `harness`, writing into `out`, with `args`; stdout and stderr
    captured as text (kwargs go to subprocess.run, e.g. timeout)."""
    return subprocess.run([sys.executable, str(ROOT / "scripts" / "run_sim.py"), "--harness", str(harness),
                           "--out", str(out), *args], cwd=ROOT, capture_output=True, text=True, **kwargs)
