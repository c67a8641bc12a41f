"""`make sim DEPTH=1`: msr_top with the engines' depth channel (DEPTH_EN 1). The DPI rendering
unit answers each trace with the primary hit's inverse depth at the driver's exponent
(msr_model.reuse.choose_invz_exp), the render mux and the engines carry it, and every pixel's
inverse depth as it leaves its engine (the harness's --depth plane) equals the golden model's
(msr_model.reuse.select_with_reuse without reuse: traced pixels the renderer's, the others
interpolated from their pass neighbours), with the frame and source map bit-exact as ever.
Refused: DEPTH with a ray budget or a sequence (exit 2, nothing run), and --depth on a harness
built without the channel."""
from __future__ import annotations

import json

import numpy as np
import pytest
from PIL import Image

from msr_sim_run import build_harness, run_sim

MODEL = "/usr/share/assimp/models/PLY/Wuson.ply"


@pytest.fixture(scope="module")
def harness():
    return build_harness("sim-depth-build")


@pytest.mark.parametrize("scene,args", [
    ("cornell", ("--width", "96", "--height", "64", "--tile", "16", "--levels", "2", "--thr", "8,16")),
    (MODEL, ("--width", "120", "--height", "90", "--tile", "32", "--levels", "3", "--thr", "4,8,16",
             "--rule", "lindilate")),
])
def test_depth_plane_bit_exact(harness, tmp_path, scene, args):
    r = run_sim(harness, tmp_path, "--scene", scene, "--depth", *args)
    assert r.returncode == 0, r.stdout + r.stderr
    rep = json.loads((tmp_path / "report.json").read_text())
    assert rep["bit_exact"] and rep["depth_equal"] and rep["mismatched_depths"] == 0, rep
    depth = np.asarray(Image.open(tmp_path / "depth.png"))
    src = np.asarray(Image.open(tmp_path / "source_map.png"))
    # a plane worth comparing: surfaces at several depths, and interpolated pixels among them
    assert depth.shape == src.shape and len(np.unique(depth[depth > 0])) > 20
    assert (src >= 16).any() and (src < 16).any()


def test_depth_refusals(harness, tmp_path):
    r = run_sim(harness, tmp_path / "b", "--width", "32", "--height", "32", "--depth", "--budget", "200")
    assert r.returncode == 2 and "DEPTH=1" in r.stderr, r.stderr
    plain = build_harness("sim-build")
    r = run_sim(plain, tmp_path / "p", "--width", "32", "--height", "32", "--depth")
    assert r.returncode == 1 and "no depth channel" in r.stdout + r.stderr, r.stdout + r.stderr
