"""Camera paths (contracts.md, third round): the file format, interpolation between keys, the
hold before the first and after the last key, every malformed file refused with a reason, and
`render` / `select --scene` with `--path FILE --frame K`: the same pixels on every run and the
same as the interpolated view given as --camera."""
from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest
from PIL import Image

from msr_model import spec
from msr_model.camera_path import CameraPath, load_path

KEYS = {"keys": [{"frame": 0, "eye": [0, 1, 4], "target": [0, 0.5, 0], "fov": 40},
                 {"frame": 10, "eye": [4, 1, 0], "target": [0, 0.5, 0], "fov": 50, "note": "ignored"},
                 {"frame": 12, "eye": [4, 3, 0], "target": [0, 0.5, 1], "fov": 50}]}


def cli(*args):
    return subprocess.run([sys.executable, "-m", "msr_model", *map(str, args)], capture_output=True, text=True)


def test_interpolation_and_holds():
    p = CameraPath.from_dict(KEYS)
    eye, target, fov = p.at(5)
    assert eye == (2.0, 1.0, 2.0) and target == (0.0, 0.5, 0.0) and fov == 45.0
    assert p.at(11) == ((4.0, 2.0, 0.0), (0.0, 0.5, 0.5), 50.0)
    assert p.at(0) == p.at(0) and p.at(12) == p.at(500)              # held after the last key
    later = CameraPath.from_dict({"keys": KEYS["keys"][1:]})
    assert later.at(0) == later.at(10)                                 # held before the first key
    # the camera string carries the exact doubles
    cam = p.camera(3)
    assert [float(v) for v in cam.split(",")] == [*p.at(3)[0], *p.at(3)[1], p.at(3)[2]]


@pytest.mark.parametrize("data,why", [
    ({}, "keys"), ({"keys": []}, "no keys"), ({"keys": [1]}, "object"),
    ({"keys": [{"frame": 0, "eye": [0, 0, 1], "target": [0, 0, 0]}]}, "missing fov"),
    ({"keys": [{"frame": -1, "eye": [0, 0, 1], "target": [0, 0, 0], "fov": 40}]}, "frame must"),
    ({"keys": [{"frame": 1.5, "eye": [0, 0, 1], "target": [0, 0, 0], "fov": 40}]}, "frame must"),
    ({"keys": [{"frame": 2, "eye": [0, 0, 1], "target": [0, 0, 0], "fov": 40},
               {"frame": 2, "eye": [0, 0, 2], "target": [0, 0, 0], "fov": 40}]}, "not after"),
    ({"keys": [{"frame": 0, "eye": [0, 0], "target": [0, 0, 0], "fov": 40}]}, "3 numbers"),
    ({"keys": [{"frame": 0, "eye": [0, 0, "x"], "target": [0, 0, 0], "fov": 40}]}, "3 numbers"),
    ({"keys": [{"frame": 0, "eye": [0, 0, float("nan")], "target": [0, 0, 0], "fov": 40}]}, "finite"),
    ({"keys": [{"frame": 0, "eye": [0, 0, 1], "target": [0, 0, 0], "fov": 180}]}, "fov"),
    ({"keys": [{"frame": 0, "eye": [0, 0, 1], "target": [0, 0, 1], "fov": 40}]}, "same point"),
])
def test_malformed_paths_refused(data, why):
    with pytest.raises(spec.SpecError, match=why):
        CameraPath.from_dict(data)


def test_gaze_keys_interpolated_and_rounded_half_up():
    """A key's "gaze" is interpolated between the keys that carry one (a key without one is
    skipped), held before the first and after the last, rounded half up; none: None."""
    k = [dict(KEYS["keys"][0], gaze=[0, 10]), KEYS["keys"][1], dict(KEYS["keys"][2], gaze=[3, 13])]
    p = CameraPath.from_dict({"keys": k})
    assert p.has_gaze and p.gaze(0) == (0, 10) and p.gaze(12) == (3, 13) and p.gaze(99) == (3, 13)
    assert p.gaze(2) == (1, 11)          # 0.5, 10.5 rounded half up
    assert p.gaze(4) == (1, 11)          # 1.0, 11.0
    assert p.gaze(6) == (2, 12)          # 1.5, 11.5
    assert [p.gaze(f) for f in range(13)] == [(int(3 * f / 12 + 0.5), int(10 + 3 * f / 12 + 0.5)) for f in range(13)]
    assert CameraPath.from_dict(KEYS).gaze(5) is None and not CameraPath.from_dict(KEYS).has_gaze


@pytest.mark.parametrize("gaze", [[1], [1, 2, 3], [-1, 0], ["a", 0], [True, 1], [float("inf"), 0], 7])
def test_bad_gaze_keys_refused(gaze):
    with pytest.raises(spec.SpecError, match="gaze"):
        CameraPath.from_dict({"keys": [dict(KEYS["keys"][0], gaze=gaze)]})


def test_interpolated_eye_on_target_refused():
    p = CameraPath.from_dict({"keys": [{"frame": 0, "eye": [0, 0, 1], "target": [0, 0, 0], "fov": 40},
                                       {"frame": 2, "eye": [0, 0, -1], "target": [0, 0, 0], "fov": 40}]})
    with pytest.raises(spec.SpecError, match="same point"):
        p.camera(1)


def test_unreadable_files(tmp_path):
    with pytest.raises(spec.SpecError, match="cannot read"):
        load_path(tmp_path / "missing.json")
    bad = tmp_path / "bad.json"
    bad.write_text("{keys: ")
    with pytest.raises(spec.SpecError, match="not JSON"):
        load_path(bad)


def test_render_and_select_on_a_path(tmp_path):
    path = tmp_path / "path.json"
    path.write_text(json.dumps(KEYS))
    w, h = 48, 32
    outs = []
    for i in range(2):
        out = tmp_path / f"r{i}.png"
        r = cli("render", "--scene", "bunny", "--width", w, "--height", h, "--path", path, "--frame", 5, "--out", out)
        assert r.returncode == 0, r.stderr
        outs.append(np.asarray(Image.open(out).convert("RGB")))
    assert (outs[0] == outs[1]).all()                                   # the same pixels every run
    cam = tmp_path / "cam.png"
    r = cli("render", "--scene", "bunny", "--width", w, "--height", h, f"--camera={CameraPath.from_dict(KEYS).camera(5)}",
            "--out", cam)
    assert r.returncode == 0 and (np.asarray(Image.open(cam).convert("RGB")) == outs[0]).all()
    r = cli("render", "--scene", "bunny", "--width", w, "--height", h, "--path", path, "--frame", 0, "--out",
            tmp_path / "f0.png")
    assert r.returncode == 0 and (np.asarray(Image.open(tmp_path / "f0.png").convert("RGB")) != outs[0]).any()
    st = tmp_path / "st.json"
    r = cli("select", "--scene", "bunny", "--width", w, "--height", h, "--path", path, "--frame", 5,
            "--thr", "0,0", "--out", tmp_path / "s.png", "--stats", st)
    assert r.returncode == 0, r.stderr
    assert (np.asarray(Image.open(tmp_path / "s.png").convert("RGB")) == outs[0]).all()   # thr 0: every pixel exact
    assert json.loads(st.read_text())["camera_path"]["frame"] == 5
    # bad use: a clear error, exit 2, nothing written
    for args, why in ((("--frame", 3), "--frame needs --path"),
                      (("--path", path, "--camera=0,0,1,0,0,0,40"), "either --camera or --path"),
                      (("--path", tmp_path / "none.json"), "cannot read camera path")):
        bad = tmp_path / "bad.png"
        r = cli("render", "--scene", "bunny", "--width", w, "--height", h, *args, "--out", bad)
        assert r.returncode == 2 and why in r.stderr and not bad.exists(), r.stderr
