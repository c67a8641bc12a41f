"""`make sim FRAMES=N` on a model file (contracts.md, fourth round): the default orbit of any
scene, bit exact frame for frame with the golden `sequence` command; sequence.json's reuse,
traced, reused, identical and flicker keys; REUSE=1 refused until the hardware has it."""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from msr_model import load_rgb
from msr_sim_run import ROOT, build_harness, run_sim

HORSE = Path("/usr/share/glmark2/models/horse.3ds")        # Debian glmark2-data


@pytest.fixture(scope="module")
def harness():
    return build_harness("sim-build")


@pytest.mark.skipif(not HORSE.is_file(), reason="glmark2-data not installed")
def test_model_sequence_equals_golden_sequence(harness, tmp_path):
    size = ["--width", "96", "--height", "64", "--frames", "3"]
    r = run_sim(harness, tmp_path / "sim", "--scene", str(HORSE), *size, timeout=300)
    assert r.returncode == 0, r.stdout + r.stderr
    g = subprocess.run([sys.executable, "-m", "msr_model", "sequence", "--scene", str(HORSE), *size,
                        "--out", str(tmp_path / "gold")], capture_output=True, text=True, cwd=ROOT, timeout=300)
    assert g.returncode == 0, g.stderr
    sim = json.loads((tmp_path / "sim" / "sequence.json").read_text())
    gold = json.loads((tmp_path / "gold" / "sequence.json").read_text())
    assert sim["bit_exact"] and sim["reuse"] is False and gold["reuse"] is False
    assert sim["camera_path"] == gold["camera_path"] and "orbit" in sim["camera_path"]
    assert sim["flicker"] == pytest.approx(gold["flicker"]) and sim["flicker"] > 0
    assert sim["strip_error_max"] > 0 and (tmp_path / "sim" / "summary_strip.png").is_file()   # one error scale
    for s, o in zip(sim["frames"], gold["frames"]):
        assert s["camera"] == o["camera"] and s["traced"] == o["traced"] and s["reused"] == 0
        assert s["identical"] is False and s["psnr_db"] == pytest.approx(o["psnr_db"])
    for k in range(3):
        for name in (f"frame_{k:04d}.png", f"source_map_{k:04d}.png"):
            assert np.array_equal(load_rgb(tmp_path / "sim" / name), load_rgb(tmp_path / "gold" / name)), name
    assert not np.array_equal(load_rgb(tmp_path / "sim" / "frame_0000.png"),
                              load_rgb(tmp_path / "sim" / "frame_0002.png"))          # the orbit moves


def test_identical_frames(harness, tmp_path):
    """THR=0,0 traces every pixel: each frame equals its full render; sequence.json says so
    (psnr_db Infinity, identical true) and the flicker is 0."""
    r = run_sim(harness, tmp_path, "--width", "24", "--height", "16", "--frames", "2", "--thr", "0,0")
    assert r.returncode == 0, r.stdout + r.stderr
    text = (tmp_path / "sequence.json").read_text()
    seq = json.loads(text)
    assert "Infinity" in text and all(e["identical"] and e["bit_exact"] for e in seq["frames"])
    assert seq["flicker"] == 0 and seq["reuse"] is False


def test_reuse_refused(tmp_path):
    """REUSE=1: one line of error, exit status 2, nothing written nor built (run_sim.py, make sim)."""
    r = run_sim(tmp_path / "no_harness", tmp_path / "o", "--width", "32", "--height", "32", "--frames", "2", "--reuse", "1")
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1 and "REUSE" in r.stderr, r.stderr
    assert not (tmp_path / "o").exists()
    r = subprocess.run(["make", "-s", "sim", "REUSE=1", "FRAMES=2", f"OUT={tmp_path / 'm'}"], cwd=ROOT,
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 2 and "REUSE" in r.stderr and not (tmp_path / "m").exists()
