"""The `python -m msr_model select IMAGE.png` contract (docs/spec/contracts.md)."""
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


# ---- inputs and outputs refused before any work: exit 2, one line, nothing left behind -------

def png_chunk(kind: bytes, data: bytes) -> bytes:
    import zlib
    return len(data).to_bytes(4, "big") + kind + data + zlib.crc32(kind + data).to_bytes(4, "big")


def huge_png(path, w=100000, h=100000):
    """A valid PNG header claiming w x h (8-bit RGB) with one tiny data chunk: decoding it
    would need 30 GB, so it must be refused from the header alone."""
    import zlib
    ihdr = w.to_bytes(4, "big") + h.to_bytes(4, "big") + bytes([8, 2, 0, 0, 0])
    path.write_bytes(b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", ihdr)
                     + png_chunk(b"IDAT", zlib.compress(b"\0" * 16)) + png_chunk(b"IEND", b""))


def rgb16_png(path, w=6, h=5):
    """A 16-bit RGB PNG (colour type 2, bit depth 16)."""
    import zlib
    rows = b"".join(b"\0" + bytes(range(6 * w)) for _ in range(h))
    ihdr = w.to_bytes(4, "big") + h.to_bytes(4, "big") + bytes([16, 2, 0, 0, 0])
    path.write_bytes(b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", ihdr)
                     + png_chunk(b"IDAT", zlib.compress(rows)) + png_chunk(b"IEND", b""))


def assert_refused(r, tmp_path, *words, before=()):
    assert r.returncode == 2, (r.returncode, r.stderr)
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("msr_model: error:"), r.stderr
    for w in words:
        assert w in lines[0], (w, lines[0])
    left = sorted(p.name for p in tmp_path.rglob("*") if p.is_file() and p.name not in before)
    assert left == [], left


def test_huge_png_header_refused_before_decoding(tmp_path):
    huge_png(tmp_path / "huge.png")
    out, smap, stats = outputs(tmp_path)
    r = cli("select", tmp_path / "huge.png", "--out", out, "--source-map", smap, "--stats", stats)
    assert_refused(r, tmp_path, "100000x100000", "4096", before={"huge.png"})


def test_16bit_rgb_png_refused(tmp_path):
    rgb16_png(tmp_path / "deep.png")
    assert Image.open(tmp_path / "deep.png").mode == "RGB"   # what a plain reader would take as 8-bit
    out, smap, stats = outputs(tmp_path)
    r = cli("select", tmp_path / "deep.png", "--out", out, "--source-map", smap, "--stats", stats)
    assert_refused(r, tmp_path, "16-bit", before={"deep.png"})


@pytest.mark.parametrize("which", ["--out", "--source-map", "--stats"])
def test_unwritable_output_path(tmp_path, picture, which):
    path, _ = picture
    blocker = tmp_path / "file"
    blocker.write_text("a file, not a folder\n")
    paths = dict(zip(("--out", "--source-map", "--stats"), outputs(tmp_path)))
    paths[which] = blocker / ("x.json" if which == "--stats" else "x.png")
    flags = [a for k, v in paths.items() for a in (k, v)]
    r = cli("select", path, *flags)
    assert_refused(r, tmp_path, "cannot write", before={"in.png", "file"})


def test_unwritable_folder(tmp_path, picture):
    """A folder nobody may create files in (/proc is refused even to root)."""
    path, _ = picture
    r = cli("select", path, "--out", "/proc/msr_out.png")
    assert_refused(r, tmp_path, "cannot write", before={"in.png"})


@pytest.mark.parametrize("same", [("--out", "--source-map"), ("--out", "--stats"), ("--source-map", "input")])
def test_same_path_for_two_outputs(tmp_path, picture, same):
    path, _ = picture
    paths = dict(zip(("--out", "--source-map", "--stats"), outputs(tmp_path)))
    a, b = same
    if b == "input":
        paths[a] = path
    else:
        paths[b] = paths[a]
        if b == "--stats":
            paths[a] = paths[b] = tmp_path / "both.json"
    flags = [x for k, v in paths.items() for x in (k, v)]
    r = cli("select", path, *flags)
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1, r.stderr
    assert {p.name for p in tmp_path.iterdir()} == {"in.png"}
    assert (np.asarray(Image.open(path)) == picture[1]).all()        # the input untouched


@pytest.mark.parametrize("flag, name", [("--out", "o.jpg"), ("--out", "o"), ("--source-map", "m.txt"),
                                        ("--stats", "s.png")])
def test_unknown_output_extension(tmp_path, picture, flag, name):
    path, _ = picture
    paths = dict(zip(("--out", "--source-map", "--stats"), outputs(tmp_path)))
    paths[flag] = tmp_path / name
    flags = [x for k, v in paths.items() for x in (k, v)]
    r = cli("select", path, *flags)
    assert_refused(r, tmp_path, flag, before={"in.png"})


def test_outputs_into_new_folder_and_no_temporary_files_left(tmp_path, picture):
    path, _ = picture
    out = tmp_path / "new" / "deeper" / "o.png"
    r = cli("select", path, "--out", out, "--stats", tmp_path / "new" / "s.json")
    assert r.returncode == 0, r.stderr
    assert sorted(p.name for p in (tmp_path / "new").rglob("*") if p.is_file()) == ["o.png", "s.json"]


# ---- --rule ----------------------------------------------------------------------------------

def test_rule_flag(tmp_path, picture):
    path, img = picture
    H, W = img.shape[:2]
    for rule in ("patent", "lindilate"):
        out, smap, stats = outputs(tmp_path)
        r = cli("select", path, "--tile", 8, "--levels", 3, "--thr", "4,8,16", "--rule", rule,
                "--out", out, "--source-map", smap, "--stats", stats)
        assert r.returncode == 0, r.stderr
        ref = select(ImageRenderer(img), W, H, Params(tile=8, levels=3, thr=(4, 8, 16)), rule=rule)
        assert (np.asarray(Image.open(out)) == ref.frame).all()
        assert (np.asarray(Image.open(smap)) == ref.source).all()
        assert json.loads(stats.read_text())["rule"] == rule
    # the default is the patent's rule
    r = cli("select", path, "--tile", 8, "--levels", 3, "--thr", "4,8,16", "--out", out, "--stats", stats)
    assert r.returncode == 0 and json.loads(stats.read_text())["rule"] == "patent"


def test_unknown_rule(tmp_path, picture):
    path, _ = picture
    out, smap, stats = outputs(tmp_path)
    r = cli("select", path, "--rule", "magic", "--out", out, "--source-map", smap, "--stats", stats)
    assert_refused(r, tmp_path, "rule", before={"in.png"})
