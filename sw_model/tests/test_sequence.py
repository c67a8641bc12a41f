"""The golden `sequence` command, the default orbit and framed camera paths (contracts.md,
fourth round): the orbit moves on any model, a framed path frames two models alike, the
command's files and keys, its frame K equal to `select` on the same view, bad flags refused."""
from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from msr_model import load_rgb
from msr_model.camera_path import ORBIT_FRAMES, CameraPath, Framing, Orbit, scene_views
from msr_model.embree import open_renderer

HORSE = Path("/usr/share/glmark2/models/horse.3ds")        # Debian glmark2-data
CAT = Path("/usr/share/glmark2/models/cat.3ds")
needs_models = pytest.mark.skipif(not (HORSE.is_file() and CAT.is_file()), reason="glmark2-data not installed")
FRAMED = {"space": "framed", "keys": [{"frame": 0, "eye": [0, 0.6, 3.2], "target": [0, 0.45, 0], "fov": 45},
                                      {"frame": 4, "eye": [1.2, 0.8, 3.0], "target": [0, 0.45, 0], "fov": 45}]}


def msr(*args) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "msr_model", *map(str, args)], capture_output=True, text=True)


def test_framing_round_trip_and_framed_path():
    f = Framing(pivot=(1.0, -2.0, 3.0), scale=0.25, cos_yaw=0.6, sin_yaw=0.8, offset=(0.5, 0.0, -0.5))
    p = (4.0, 5.0, -6.0)
    assert np.allclose(f.to_model(f.to_framed(p)), p)
    cp = CameraPath.from_dict(FRAMED)
    eye = [float(v) for v in cp.camera(0, f).split(",")[:3]]
    assert np.allclose(f.to_framed(eye), (0, 0.6, 3.2))
    with pytest.raises(Exception, match="framing"):
        cp.camera(0)                                        # a framed path needs the scene's framing
    with pytest.raises(Exception, match="space"):
        CameraPath.from_dict({**FRAMED, "space": "world"})


def test_orbit_turns_about_the_framed_centre():
    f = Framing(pivot=(10.0, 0.0, 20.0), scale=0.5)
    o = Orbit(((10.0, 1.0, 30.0), (10.0, 1.0, 20.0), 40.0), f)
    assert o.at(0) == ((10.0, 1.0, 30.0), (10.0, 1.0, 20.0), 40.0)
    assert o.at(ORBIT_FRAMES) == o.at(0)                                     # one full turn
    half = o.at(ORBIT_FRAMES // 2)
    assert np.allclose(half[0], (10.0, 1.0, 10.0)) and np.allclose(half[1], (10.0, 1.0, 20.0))
    for k in range(0, ORBIT_FRAMES, 7):                                      # the distance to the axis holds
        e = o.at(k)[0]
        assert math.hypot(e[0] - 10.0, e[2] - 20.0) == pytest.approx(10.0)


@needs_models
def test_default_orbit_moves_on_a_model_file():
    views = scene_views(str(HORSE), 48, 32)
    cams = views.cameras(4)
    assert len(set(cams)) == 4 and views.space == "model"
    frames = []
    for cam in cams[:2]:
        with open_renderer(str(HORSE), 48, 32, camera=cam) as r:
            frames.append(r.render_full(progress=False))
    assert not np.array_equal(frames[0], frames[1])


def _subject_box(scene, cam, w=96, h=64):
    """The pixel box of the model (not the sky, not the ground: the ground's material comes last)."""
    with open_renderer(scene, w, h, camera=cam) as r:
        _, mat, _ = r.gbuffer_full()
    ys, xs = np.nonzero((mat > 0) & (mat != mat.max()))
    return xs.min() / w, xs.max() / w, ys.min() / h, ys.max() / h


@needs_models
def test_framed_path_frames_two_models_alike(tmp_path):
    path = tmp_path / "framed.json"
    path.write_text(json.dumps(FRAMED))
    boxes = [_subject_box(str(m), scene_views(str(m), 96, 64, path).camera(0)) for m in (HORSE, CAT)]
    for x0, x1, y0, y1 in boxes:
        assert abs((x0 + x1) / 2 - 0.5) < 0.12 and abs((y0 + y1) / 2 - 0.5) < 0.2    # centred
        assert 0.3 < x1 - x0 < 1.0                                                       # in frame
    assert scene_views(str(HORSE), 96, 64, path).camera(0) != scene_views(str(CAT), 96, 64, path).camera(0)


@needs_models
def test_sequence_command(tmp_path):
    out = tmp_path / "seq"
    r = msr("sequence", "--scene", HORSE, "--width", 48, "--height", 32, "--frames", 3, "--levels", 3,
            "--budget", "30%", "--out", out)
    assert r.returncode == 0, r.stderr
    seq = json.loads((out / "sequence.json").read_text())
    assert seq["reuse"] is False and seq["budget"] == 48 * 32 * 30 // 100 and "flicker" in seq
    assert [e["frame"] for e in seq["frames"]] == [0, 1, 2]
    for e in seq["frames"]:
        for k in ("traced", "reused", "traced_fraction", "psnr_db", "identical", "camera"):
            assert k in e, k
        assert e["reused"] == 0 and e["traced_fraction"] == e["traced"] / (48 * 32)
        assert (out / f"frame_{e['frame']:04d}.png").is_file() and (out / f"source_map_{e['frame']:04d}.png").is_file()
    assert seq["frames"][1]["scale_init"] == seq["frames"][0]["scale_out"]    # the driver's seeded sequence
    assert seq["flicker"] > 0 and seq["frames"][0]["flicker"] is None


@needs_models
def test_sequence_frame_equals_select(tmp_path):
    """Frame K of a framed path equals select --path FILE --frame K (the same camera string)."""
    path = tmp_path / "framed.json"
    path.write_text(json.dumps(FRAMED))
    common = ["--width", 40, "--height", 24, "--tile", 8, "--thr", "6,12"]
    r = msr("sequence", "--scene", HORSE, "--frames", 3, "--path", path, "--out", tmp_path / "s", *common)
    assert r.returncode == 0, r.stderr
    r = msr("select", "--scene", HORSE, "--path", path, "--frame", 2, "--out", tmp_path / "f.png",
            "--source-map", tmp_path / "m.png", "--stats", tmp_path / "st.json", *common)
    assert r.returncode == 0, r.stderr
    assert np.array_equal(load_rgb(tmp_path / "s" / "frame_0002.png"), load_rgb(tmp_path / "f.png"))
    seq = json.loads((tmp_path / "s" / "sequence.json").read_text())
    st = json.loads((tmp_path / "st.json").read_text())
    assert seq["space"] == "framed" and st["camera_path"]["camera"] == seq["frames"][2]["camera"]
    assert st["traced"] == seq["frames"][2]["traced"]


@pytest.mark.parametrize("extra,msg", [
    (["--reuse", "--budget", "50%"], "reuse"),
    (["--frames", "0"], "--frames"),
    (["--thr", "1,2,3"], "--thr"),
    (["--budget", "3"], "initial grid"),
    (["--gaze", "99,1"], "gaze"),
    (["--path", "/nonexistent.json"], "camera path"),
])
def test_sequence_bad_flags(tmp_path, extra, msg):
    out = tmp_path / "o"
    args = ["sequence", "--scene", "cornell", "--width", 32, "--height", 32, "--frames", 2, "--out", out, *extra]
    r = msr(*args)
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1 and msg in r.stderr, r.stderr
    assert not out.exists()


@needs_models
def test_sequence_reuse(tmp_path):
    """--reuse: the golden model of reuse across frames where the package has it (frame 0 as
    without reuse, later frames reuse pixels); without it, one line and exit status 2."""
    from msr_model.sequence import reuse_model
    args = ["sequence", "--scene", HORSE, "--width", 48, "--height", 32, "--frames", 2, "--reuse"]
    r = msr(*args, "--out", tmp_path / "r")
    if reuse_model() is None:
        assert r.returncode == 2 and "reuse" in r.stderr and not (tmp_path / "r").exists()
        return
    assert r.returncode == 0, r.stderr
    assert msr(*args[:-1], "--out", tmp_path / "n").returncode == 0
    seq = json.loads((tmp_path / "r" / "sequence.json").read_text())
    assert seq["reuse"] is True and seq["frames"][0]["reused"] == 0 and seq["frames"][1]["reused"] > 0
    assert np.array_equal(load_rgb(tmp_path / "r" / "frame_0000.png"), load_rgb(tmp_path / "n" / "frame_0000.png"))


def test_identical_frame_reported(tmp_path):
    """Thresholds 0 trace every pixel: each frame equals its full render, PSNR inf (JSON
    Infinity) and identical true; the flicker of identical frames is 0."""
    out = tmp_path / "i"
    r = msr("sequence", "--scene", "cornell", "--width", 24, "--height", 16, "--frames", 2, "--thr", "0,0",
            "--out", out)
    assert r.returncode == 0, r.stderr
    text = (out / "sequence.json").read_text()
    assert "Infinity" in text
    seq = json.loads(text)
    assert all(e["identical"] and math.isinf(e["psnr_db"]) for e in seq["frames"]) and seq["flicker"] == 0


def test_sequence_gaze_from_the_path(tmp_path):
    """A path's gaze keys move the foveation centre frame by frame (the camera held still):
    frame K equals select --gaze with the interpolated point, sequence.json records it; a run
    gaze beside path gaze points, or a path point outside the frame, is refused (exit 2)."""
    with open_renderer("cornell", 72, 40) as r:         # the scene's own view, held still
        eye, target, fov = r.view()
    still = {"eye": list(eye), "target": list(target), "fov": fov}
    gaze_path = {"keys": [{"frame": 0, **still, "gaze": [2, 2]}, {"frame": 2, **still, "gaze": [69, 37]}]}
    path = tmp_path / "gaze.json"
    path.write_text(json.dumps(gaze_path))
    common = ["--scene", "cornell", "--width", 72, "--height", 40, "--tile", 8, "--thr", "10,20", "--fov-gain", 200]
    r = msr("sequence", *common, "--frames", 3, "--path", path, "--out", tmp_path / "s")
    assert r.returncode == 0, r.stderr
    seq = json.loads((tmp_path / "s" / "sequence.json").read_text())
    assert [e["gaze"] for e in seq["frames"]] == [[2, 2], [36, 20], [69, 37]]     # 35.5, 19.5 rounded up
    maps = [load_rgb(tmp_path / "s" / f"source_map_{k:04d}.png") for k in range(3)]
    assert not np.array_equal(maps[0], maps[2]), "the gaze moved nothing"
    for k, g in ((1, "36,20"), (2, "69,37")):
        cam = seq["frames"][k]["camera"]
        r = msr("select", *common, "--camera", cam, "--gaze", g, "--out", tmp_path / "f.png",
                "--source-map", tmp_path / "m.png", "--stats", tmp_path / "st.json")
        assert r.returncode == 0, r.stderr
        assert np.array_equal(load_rgb(tmp_path / "m.png"), maps[k]), k
    r = msr("sequence", *common, "--frames", 2, "--path", path, "--gaze", "1,1", "--out", tmp_path / "b")
    assert r.returncode == 2 and "gaze" in r.stderr and not (tmp_path / "b").exists(), r.stderr
    far = {"keys": [dict(gaze_path["keys"][0], gaze=[72, 0])]}
    path.write_text(json.dumps(far))
    r = msr("sequence", *common, "--frames", 2, "--path", path, "--out", tmp_path / "c")
    assert r.returncode == 2 and "outside" in r.stderr and len(r.stderr.strip().splitlines()) == 1, r.stderr
    assert not (tmp_path / "c").exists()
