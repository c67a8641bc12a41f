"""`make sim GAZE=X,Y` (docs/spec/contracts.md "Gaze"): the harness writes GAZE, the frame is
bit-exact with the golden model run with the same gaze and differs from the default frame when
FOV_GAIN > 0; without GAZE the frame is the default one (the golden model's frame-centre
foveation); a gaze outside the frame is refused by the script (exit 2, one line, nothing run)
and, written as is by the harness, by the hardware (STATUS.ERROR 16)."""
from __future__ import annotations

import json
import subprocess

import numpy as np
import pytest
from PIL import Image

from msr_flow import regs as R
from msr_sim_run import build_harness, run_sim

FRAME = ("--width", "72", "--height", "40", "--tile", "8", "--levels", "2", "--thr", "10,20", "--fov-gain", "200")


@pytest.fixture(scope="module")
def harness():
    return build_harness("sim-build")


def test_gaze_frames(harness, tmp_path):
    r = run_sim(harness, tmp_path / "centre", *FRAME)
    assert r.returncode == 0, r.stderr
    centre = json.loads((tmp_path / "centre" / "report.json").read_text())
    assert centre["bit_exact"] and centre["gaze"] == [36, 20]       # ntx*T/2 = 9*8/2, nty*T/2 = 5*8/2
    assert "gaze" not in centre["params"]
    r = run_sim(harness, tmp_path / "corner", *FRAME, "--gaze", "3,38")
    assert r.returncode == 0, r.stderr
    corner = json.loads((tmp_path / "corner" / "report.json").read_text())
    assert corner["bit_exact"] and corner["gaze"] == [3, 38]
    codes = [np.asarray(Image.open(tmp_path / d / "source_map.png")) for d in ("centre", "corner")]
    assert (codes[0] != codes[1]).any(), "the gaze moved nothing"
    # the default gaze written out gives the default frame
    r = run_sim(harness, tmp_path / "given", *FRAME, "--gaze", "36,20")
    assert r.returncode == 0, r.stderr
    given = np.asarray(Image.open(tmp_path / "given" / "source_map.png"))
    assert (given == codes[0]).all()
    assert (np.asarray(Image.open(tmp_path / "given" / "frame.png"))
            == np.asarray(Image.open(tmp_path / "centre" / "frame.png"))).all()


@pytest.mark.parametrize("gaze", ["72,0", "0,40", "-1,3", "5", "1,2,3", "x,y"])
def test_bad_gaze_is_refused_before_the_harness(harness, tmp_path, gaze):
    r = run_sim(harness, tmp_path / "out", *FRAME, f"--gaze={gaze}")      # as mk/sim.mk passes GAZE
    assert r.returncode == 2, r.stderr
    assert len(r.stderr.strip().splitlines()) == 1 and "GAZE" in r.stderr, r.stderr
    assert not (tmp_path / "out").exists()


def test_harness_gaze_refused_by_the_hardware(harness):
    base = [str(harness), "--width", "16", "--height", "8", "--quiet", "+scene=cornell", "+width=16", "+height=8"]
    r = subprocess.run(base + ["--gaze", "16,0"], capture_output=True, text=True)
    assert r.returncode == 1 and f"STATUS.ERROR = {R.STATUS_ERROR_GAZE}" in r.stderr, r.stderr
    r = subprocess.run(base + ["--gaze", "bad"], capture_output=True, text=True)
    assert r.returncode == 2 and "--gaze" in r.stderr, r.stderr
