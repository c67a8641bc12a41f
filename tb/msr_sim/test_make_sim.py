"""`make sim` flow: the Verilator harness with Embree over DPI, against the golden model.

Small frames (the harness is fast, the build is not): the default scene, a model file with
every parameter changed, and the contract's error path (unreadable model file: exit 2)."""
from __future__ import annotations

import json
import subprocess
from pathlib import Path

import pytest

from msr_sim_run import build_harness, run_sim

MODEL = Path("/usr/share/assimp/models/3DS/fels.3ds")   # Debian assimp-testmodels


@pytest.fixture(scope="module")
def harness():
    return build_harness("sim-build")


def check_outputs(out):
    report = json.loads((out / "report.json").read_text())
    for f in ("frame.png", "source_map.png", "golden.png", "golden_source_map.png", "reference.png"):
        assert (out / f).is_file(), f
    for k in ("bit_exact", "traced_fraction", "psnr_db", "ssim", "cycles", "pixels"):
        assert k in report, k
    return report


def test_default_scene(harness, tmp_path):
    r = run_sim(harness, tmp_path, "--width", "72", "--height", "40")
    assert r.returncode == 0, r.stderr
    rep = check_outputs(tmp_path)
    assert rep["bit_exact"] and rep["perf_counters_match_source_map"]
    assert rep["rule"] == "patent" and r.stdout.strip().splitlines()[-1].startswith("make sim: passed")
    assert rep["pixels"] == 72 * 40 and rep["cycles"] >= rep["pixels"]


@pytest.mark.skipif(not MODEL.is_file(), reason="assimp-testmodels not installed")
def test_model_file_all_parameters(harness, tmp_path):
    r = run_sim(harness, tmp_path, "--scene", str(MODEL), "--width", "61", "--height", "35", "--tile", "8",
                "--levels", "3", "--thr", "4,12,30", "--metric", "sum", "--fov-gain", "60",
                "--rnd-latency", "1", "--rnd-jitter", "30")
    assert r.returncode == 0, r.stderr
    rep = check_outputs(tmp_path)
    assert rep["bit_exact"]
    assert rep["params"] == {"tile": 8, "levels": 3, "thr": [4, 12, 30], "metric": "sum", "fov_gain": 60}


def test_unreadable_model_file(harness, tmp_path):
    bad = tmp_path / "broken.obj"
    bad.write_text("this is not a model\n")
    r = run_sim(harness, tmp_path / "out", "--scene", str(bad), "--width", "16", "--height", "16")
    assert r.returncode == 2
    assert len(r.stderr.strip().splitlines()) == 1 and "error" in r.stderr
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("fb_base,code", [(0x1002, 5), (0x40000000, 8)])
def test_harness_error_paths(harness, fb_base, code):
    """An unaligned FB_BASE is refused (code 5, nothing runs); a frame buffer outside the
    memory is answered with SLVERR, which STATUS reports (code 8). Both: exit status 1."""
    r = subprocess.run([str(harness), "--width", "24", "--height", "16", "--quiet", "--fb-base", hex(fb_base),
                        "+scene=cornell", "+width=24", "+height=16"], capture_output=True, text=True)
    assert r.returncode == 1, r.stderr
    assert f"STATUS.ERROR = {code}" in r.stderr


def test_harness_rule(harness):
    """--rule: a bad name is refused before anything runs (exit 2); CONFIG.RULE 2 and 3, written
    as is, are refused by the hardware (STATUS.ERROR 13, exit 1); the stats record the rule."""
    base = [str(harness), "--width", "16", "--height", "8", "--quiet", "+scene=cornell", "+width=16", "+height=8"]
    r = subprocess.run(base + ["--rule", "magic"], capture_output=True, text=True)
    assert r.returncode == 2 and "--rule must be" in r.stderr, r.stderr
    for value in ("2", "3"):
        r = subprocess.run(base + ["--rule", value], capture_output=True, text=True)
        assert r.returncode == 1 and "STATUS.ERROR = 13" in r.stderr, r.stderr


def test_lindilate(harness, tmp_path):
    """RULE=lindilate through the RTL: CONFIG.RULE = 1 in the harness's stats, report.json says
    lindilate, bit exact with the golden model's lindilate frame."""
    r = run_sim(harness, tmp_path, "--width", "72", "--height", "40", "--rule", "lindilate")
    rep = check_outputs(tmp_path)
    assert rep["rule"] == "lindilate"
    assert r.returncode == 0 and rep["bit_exact"], r.stdout + r.stderr


@pytest.fixture(scope="module")
def budget_harness():
    return build_harness("sim-budget-build")


def test_budget(budget_harness, harness, tmp_path):
    """make sim BUDGET= (contracts.md, third round): the frame through a top with the budget
    controller, bit exact with select_budget, report.json's budget fields, SCALE_OUT read from
    the RTL equal to the golden model's; a percentage budget; a budget below the initial grid
    refused before anything runs (exit 2); a budget given to a harness without the controller
    is a failure, not a silent frame without it."""
    r = run_sim(budget_harness, tmp_path / "a", "--width", "96", "--height", "64", "--levels", "3",
                "--thr", "8,16,32", "--budget", "1200")
    assert r.returncode == 0, r.stdout + r.stderr
    rep = check_outputs(tmp_path / "a")
    bc = rep["budget_control"]
    assert rep["bit_exact"] and rep["budget"] == 1200 and bc["scale_out_equal"]
    assert len(bc["scale_per_row"]) == 4 and sum(bc["traced_per_row"]) == rep["traced"]
    assert bc["budget_error"] == pytest.approx((rep["traced"] - 1200) / 1200)
    r = run_sim(budget_harness, tmp_path / "b", "--width", "96", "--height", "64", "--levels", "3",
                "--budget", "25%")
    assert r.returncode == 0, r.stdout + r.stderr
    assert json.loads((tmp_path / "b" / "report.json").read_text())["budget"] == 96 * 64 // 4
    r = run_sim(budget_harness, tmp_path / "c", "--width", "96", "--height", "64", "--levels", "3",
                "--budget", "10")
    assert r.returncode == 2 and "initial grid" in r.stderr, r.stderr
    r = run_sim(harness, tmp_path / "d", "--width", "96", "--height", "64", "--levels", "3", "--budget", "1200")
    assert r.returncode == 1 and "STATUS.ERROR = 14" in (r.stdout + r.stderr)


def test_sequence(harness, budget_harness, tmp_path):
    """make sim FRAMES=N (contracts.md, third round): N frames in one harness run along the
    default orbit, each bit exact with the golden model on its own view; sequence.json's
    frames, the frames and source maps, a playable animation and the strip; with a budget the
    harness seeds each frame with the last SCALE_OUT as a driver would, and the golden model's
    seeded frames agree; a bad path file is refused (exit 2) before anything runs."""
    from PIL import Image
    out = tmp_path / "seq"
    r = run_sim(harness, out, "--width", "48", "--height", "32", "--frames", "3")
    assert r.returncode == 0, r.stdout + r.stderr
    seq = json.loads((out / "sequence.json").read_text())
    assert seq["bit_exact"] and seq["num_frames"] == 3 and [e["frame"] for e in seq["frames"]] == [0, 1, 2]
    for e in seq["frames"]:
        assert e["bit_exact"] and 0 < e["traced_fraction"] <= 1 and "psnr_db" in e
        assert (out / f"frame_{e['frame']:04d}.png").is_file() and (out / f"source_map_{e['frame']:04d}.png").is_file()
    assert len({e["camera"] for e in seq["frames"]}) == 3                     # the camera moved
    for pic in ("sequence.webp", "sequence.gif"):
        with Image.open(out / pic) as im:
            assert getattr(im, "n_frames", 1) == 3, pic
    assert (out / "summary_strip.png").is_file()
    r = run_sim(budget_harness, tmp_path / "b", "--width", "64", "--height", "48", "--levels", "3",
                "--frames", "2", "--budget", "20%")
    assert r.returncode == 0, r.stdout + r.stderr
    fr = json.loads((tmp_path / "b" / "sequence.json").read_text())["frames"]
    assert all(e["bit_exact"] and e["scale_out_equal"] for e in fr)
    assert fr[1]["scale_init"] == fr[0]["scale_out"]                          # seeded from frame 0
    bad = tmp_path / "bad.json"
    bad.write_text('{"keys": [{"frame": 0, "eye": [0, 0, 1], "target": [0, 0, 1], "fov": 40}]}')
    r = run_sim(harness, tmp_path / "c", "--width", "48", "--height", "32", "--frames", "2", "--camera-path", str(bad))
    assert r.returncode == 2 and "same point" in r.stderr and not (tmp_path / "c").exists()


@pytest.mark.parametrize("w,h", [(1, 1), (6, 40), (5, 3)])
def test_smallest_frames(harness, tmp_path, w, h):
    """Every size the bounds accept finishes: below SSIM's 7x7 window report.json's ssim is null
    (not defined there), and the run passes bit exact."""
    r = run_sim(harness, tmp_path, "--width", str(w), "--height", str(h))
    assert r.returncode == 0, r.stdout + r.stderr
    rep = check_outputs(tmp_path)
    assert rep["bit_exact"] and rep["ssim"] is None and (tmp_path / "summary.png").is_file()
