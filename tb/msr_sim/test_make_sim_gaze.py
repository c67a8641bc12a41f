"""`make sim GAZE=X,Y` (docs/spec/contracts.md "Gaze"): the harness writes GAZE, the frame is
bit-exact with the golden model run with the same gaze and differs from the default frame when
FOV_GAIN > 0; without GAZE the frame is the default one (the golden model's frame-centre
foveation); a gaze outside the frame is refused by the script (exit 2, one line, nothing run)
and, written as is by the harness, by the hardware (STATUS.ERROR 16). A camera path's gaze keys
set GAZE frame by frame, bit-exact with the golden `sequence` command on the same path."""
from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest
from PIL import Image

from msr_flow import regs as R
from msr_model import load_rgb
from msr_model.embree import open_renderer
from msr_sim_run import ROOT, build_harness, run_sim

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


def test_gaze_keys_of_a_path(harness, tmp_path):
    """The camera held still, the gaze moving from corner to corner along the path's keys: each
    frame bit exact, the harness's GAZE the interpolated point, the same frames as the golden
    sequence command's, and the source maps of the first and last frame differ."""
    with open_renderer("cornell", 72, 40) as r:
        eye, target, fov = r.view()
    still = {"eye": list(eye), "target": list(target), "fov": fov}
    path = tmp_path / "gaze.json"
    path.write_text(json.dumps({"keys": [{"frame": 0, **still, "gaze": [2, 2]},
                                         {"frame": 2, **still, "gaze": [69, 37]}]}))
    r = run_sim(harness, tmp_path / "sim", *FRAME, "--frames", "3", "--camera-path", str(path))
    assert r.returncode == 0, r.stdout + r.stderr
    seq = json.loads((tmp_path / "sim" / "sequence.json").read_text())
    assert seq["bit_exact"] and [e["gaze"] for e in seq["frames"]] == [[2, 2], [36, 20], [69, 37]]
    g = subprocess.run([sys.executable, "-m", "msr_model", "sequence", "--scene", "cornell", *FRAME,
                        "--frames", "3", "--path", str(path), "--out", str(tmp_path / "gold")],
                       capture_output=True, text=True, cwd=ROOT)
    assert g.returncode == 0, g.stderr
    for k in range(3):
        for name in (f"frame_{k:04d}.png", f"source_map_{k:04d}.png"):
            assert np.array_equal(load_rgb(tmp_path / "sim" / name), load_rgb(tmp_path / "gold" / name)), name
    assert not np.array_equal(load_rgb(tmp_path / "sim" / "source_map_0000.png"),
                              load_rgb(tmp_path / "sim" / "source_map_0002.png")), "the gaze moved nothing"
    # a gaze for the run beside the path's: refused before the harness runs
    r = run_sim(harness, tmp_path / "both", *FRAME, "--frames", "2", "--camera-path", str(path), "--gaze", "1,1")
    assert r.returncode == 2 and "gaze" in r.stderr and not (tmp_path / "both").exists(), r.stderr
