"""The `python -m msr_model select IMAGE.png` contract (../shared/spec/contracts.md)."""
import json
import subprocess
import sys

import numpy as np
import pytest
from PIL import Image

from msr_model import ImageRenderer, Params, select


def cli(*args, cwd=None):
    return subprocess.run([sys.executable, "-m", "msr_model", *map(str, args)],
                          capture_output=True, text=True, cwd=cwd)


@pytest.fixture
def picture(tmp_path):
    rng = np.random.default_rng(2)
    img = np.cumsum(rng.integers(-5, 6, (37, 53, 3)), axis=1).clip(0, 255).astype(np.uint8)
    path = tmp_path / "in.png"
    Image.fromarray(img).save(path)
    return path, img


def outputs(tmp_path):
    return tmp_path / "o.png", tmp_path / "m.png", tmp_path / "s.json"


def test_select_writes_the_contract_files(tmp_path, picture):
    path, img = picture
    out, smap, stats = outputs(tmp_path)
    r = cli("select", path, "--tile", 8, "--levels", 3, "--thr", "6,12,24", "--metric", "sum",
            "--fov-gain", 40, "--out", out, "--source-map", smap, "--stats", stats)
    assert r.returncode == 0, r.stderr
    ref = select(ImageRenderer(img), 53, 37, Params(tile=8, levels=3, thr=(6, 12, 24), metric="sum", fov_gain=40))
    got = Image.open(out)
    assert got.mode == "RGB" and (np.asarray(got) == ref.frame).all()
    m = Image.open(smap)
    assert m.mode == "L" and (np.asarray(m) == ref.source).all()
    st = json.loads(stats.read_text())
    for key in ("width", "height", "traced", "interpolated", "traced_fraction"):
        assert st[key] == ref.stats[key]


def test_rgba_alpha_dropped(tmp_path, picture):
    path, img = picture
    rgba = np.dstack([img, np.full(img.shape[:2], 7, np.uint8)])
    Image.fromarray(rgba, "RGBA").save(tmp_path / "a.png")
    out, smap, stats = outputs(tmp_path)
    r = cli("select", tmp_path / "a.png", "--tile", 16, "--levels", 2, "--thr", "8,16", "--out", out,
            "--source-map", smap, "--stats", stats)
    assert r.returncode == 0, r.stderr
    ref = select(ImageRenderer(img), 53, 37, Params())
    assert (np.asarray(Image.open(out)) == ref.frame).all()


BAD = [
    (["--tile", "12"], "tile"),
    (["--tile", "x"], "tile"),
    (["--levels", "0", "--thr", "8"], "levels"),
    (["--levels", "4", "--thr", "1,2,3,4"], "levels"),
    (["--thr", "8,x"], "thr"),
    (["--thr", "8,"], "thr"),
    (["--thr", ""], "thr"),
    (["--thr", "8,256"], "256"),
    (["--thr=-1,8"], "-1"),
    (["--levels", "3", "--thr", "8,16"], "thr"),
    (["--metric", "mean"], "metric"),
    (["--fov-gain", "300"], "fov-gain"),
]


@pytest.mark.parametrize("flags, word", BAD)
def test_bad_flags_exit_2_one_line_no_output(tmp_path, picture, flags, word):
    path, _ = picture
    out, smap, stats = outputs(tmp_path)
    args = ["select", path, "--tile", "16", "--levels", "2", "--thr", "8,16"]
    args += flags + ["--out", out, "--source-map", smap, "--stats", stats]
    r = cli(*args)
    assert r.returncode == 2
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and word in lines[0], r.stderr
    assert not out.exists() and not smap.exists() and not stats.exists()


@pytest.mark.parametrize("content", [None, b"this is not a png", b"\x89PNG\r\n\x1a\n broken"])
def test_unreadable_image(tmp_path, content):
    src = tmp_path / "bad.png"
    if content is not None:
        src.write_bytes(content)
    out, smap, stats = outputs(tmp_path)
    r = cli("select", src, "--out", out, "--source-map", smap, "--stats", stats)
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1, r.stderr
    assert not out.exists() and not smap.exists() and not stats.exists()


def test_too_large_and_16bit_images(tmp_path):
    Image.fromarray(np.zeros((1, 4097, 3), np.uint8)).save(tmp_path / "wide.png")
    Image.new("I;16", (4, 4)).save(tmp_path / "deep.png")
    for name in ("wide.png", "deep.png"):
        out = tmp_path / "o.png"
        r = cli("select", tmp_path / name, "--out", out)
        assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1, r.stderr
        assert not out.exists()


def test_missing_required_and_both_sources(tmp_path, picture):
    path, _ = picture
    assert cli("select", path).returncode == 2                           # no --out
    r = cli("select", "--out", tmp_path / "o.png")                       # neither image nor scene
    assert r.returncode == 2 and not (tmp_path / "o.png").exists()
    r = cli("select", path, "--scene", "cornell", "--width", 8, "--height", 8, "--out", tmp_path / "o.png")
    assert r.returncode == 2 and not (tmp_path / "o.png").exists()
    assert cli("bogus").returncode == 2
