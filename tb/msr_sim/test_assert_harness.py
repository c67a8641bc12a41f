"""The full-frame harness with assertions on: build/sim/assert/Vmsr_sim_top (mk/sim.mk,
`make sim-assert-build`), built with Verilator --assert and the AXI protocol checkers of
rtl/checkers bound to msr_fb_writer and msr_regs. One small frame of the default scene with
random render latency: bit-exact against the golden model, and no assertion fired (an SVA
failure prints %Error and stops the harness with a non-zero exit status)."""
from __future__ import annotations

import json
import subprocess

import pytest

from msr_sim_run import build_harness, run_sim


@pytest.fixture(scope="module")
def harness():
    return build_harness("sim-assert-build")


def test_assertions_compiled_in(harness):
    """The build really has the checkers and the RTL's own assertions: their messages are in
    the generated model (a --noassert build or a missing bind has none of them)."""
    text = "".join(p.read_text(errors="replace") for p in harness.parent.glob("Vmsr_sim_top*.cpp"))
    for msg in ("AXI4 AW: AWVALID dropped", "AXI4 W: WLAST=", "AXI4 B: BVALID with no completed write",
                "AXI4-Lite B: BVALID dropped", "AXI4-Lite R: RVALID with no read",
                "assertion a_count_range failed"):
        assert msg in text, f"{msg!r} not in the assertion build"


def test_frame_with_assertions(harness, tmp_path):
    r = run_sim(harness, tmp_path, "--width", "160", "--height", "120", "--tile", "8", "--levels", "2",
                "--thr", "8,16", "--rnd-latency", "2", "--rnd-jitter", "40", timeout=900)
    log = r.stdout + r.stderr
    assert "%Error" not in log, log[-3000:]
    assert r.returncode == 0, log[-3000:]
    rep = json.loads((tmp_path / "report.json").read_text())
    assert rep["bit_exact"] and rep["perf_counters_match_source_map"], rep
    assert rep["pixels"] == 160 * 120


def test_slverr_with_assertions(harness):
    """A frame buffer outside the harness's memory: every burst answered with SLVERR, which
    STATUS reports (code 8, exit status 1), and still no protocol rule broken on either port."""
    r = subprocess.run([str(harness), "--width", "24", "--height", "16", "--quiet", "--fb-base", "0x40000000",
                        "+scene=cornell", "+width=24", "+height=16"], capture_output=True, text=True, timeout=600)
    assert r.returncode == 1, r.stderr
    assert "STATUS.ERROR = 8" in r.stderr and "%Error" not in r.stdout + r.stderr, r.stderr
