"""Runs the renderer's C++ unit tests (GoogleTest, built by `make renderer-tests`), one pytest
item per C++ test so that a failure shows up by name in pytest's summary."""
import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
BIN = ROOT / "build" / "renderer" / "renderer_tests"


def _cases():
    if not BIN.is_file():
        return ["<binary missing>"]
    out = subprocess.run([str(BIN), "--gtest_list_tests"], capture_output=True, text=True, check=True).stdout
    names, suite = [], ""
    for line in out.splitlines():
        if not line.strip() or line.startswith("Running main"):
            continue
        if not line.startswith(" "):
            suite = line.split()[0]
        else:
            names.append(suite + line.split()[0])
    return names


@pytest.mark.parametrize("name", _cases())
def test_cpp(name):
    assert BIN.is_file(), f"{BIN} not built: run `make renderer-tests` (part of `make test`)"
    env = dict(os.environ)
    env.pop("MSR_EMBREE_ISA", None)
    r = subprocess.run([str(BIN), f"--gtest_filter={name}"], capture_output=True, text=True, cwd=ROOT,
                       env=env, timeout=300)
    assert r.returncode == 0, r.stdout[-4000:] + r.stderr[-2000:]
    assert "[  PASSED  ] 1 test" in r.stdout, r.stdout[-2000:]
