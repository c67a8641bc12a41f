"""The Embree rendering unit from Python (msr_model.embree) and the `render` / `select --scene`
commands: determinism, Python vs C API, importer errors, built-in and never-named model files."""
import base64
import ctypes
import json
import os
import struct
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from msr_model import Params, select, spec
from msr_model.embree import library_path, open_renderer, scene_names

W, H = 64, 48


def cli(*args, env=None):
    return subprocess.run([sys.executable, "-m", "msr_model", *map(str, args)], capture_output=True, text=True,
                          env=env)


@pytest.fixture(scope="module")
def frames():
    """Fast 64x48 render_full of every built-in scene (rendered once per module)."""
    out = {}
    for name in scene_names():
        with open_renderer(name, W, H) as r:
            out[name] = r.render_full()
    return out


def grid(w, h):
    ys, xs = np.divmod(np.arange(w * h), w)
    return xs, ys


# ---- built-in scenes ----------------------------------------------------------------------------

def test_scene_names():
    names = scene_names()
    assert names[0] == "cornell"  # the default `make sim` scene
    assert {"cornell", "showcase", "bunny"} <= set(names)
    assert len(names) >= 4


BUILTINS = ["cornell", "showcase", "bunny", "duck", "teapots", "engine"]


def test_every_builtin_is_checked():
    assert sorted(scene_names()) == sorted(BUILTINS)


@pytest.mark.parametrize("name", BUILTINS)
def test_builtin_scene_is_a_picture(frames, name):
    img = frames[name]
    assert img.shape == (H, W, 3) and img.dtype == np.uint8
    colours, counts = np.unique(img.reshape(-1, 3), axis=0, return_counts=True)
    assert len(colours) >= 200, f"only {len(colours)} distinct colours"
    assert counts.max() / counts.sum() < 0.5, "one colour covers half the frame"
    lum = img.astype(float) @ [0.2126, 0.7152, 0.0722]
    assert 25 < lum.mean() < 230 and lum.std() > 15


def test_cornell_layout(frames):
    """Published camera: the box fills the square in the middle of a 4:3 frame, red wall left,
    green wall right, black outside the open front."""
    img = frames["cornell"].astype(int)
    black = (img.sum(axis=2) == 0)
    assert 0.15 < black.mean() < 0.35
    assert black[:, :4].all() and black[:, -4:].all()                      # beside the box
    left, right = img[H // 2, 10], img[H // 2, W - 11]                     # the side walls
    assert left[0] > 2 * left[1] and left[0] > 2 * left[2], left            # red
    assert right[1] > 1.4 * right[0] and right[1] > 1.4 * right[2], right   # green
    ceiling_light = img[2:8, 24:40].sum(axis=2).max()
    assert ceiling_light >= 3 * 250                                        # the lamp is white


def test_bunny_covers_a_sane_share(frames):
    """The bunny replaces the two blocks: the pixels that differ from an empty box are the
    bunny and its shadow, a fair part of the box but far from all of it."""
    with open_renderer("cornell", W, H) as r:
        box = r.render_full().astype(int)
    bunny = frames["bunny"].astype(int)
    differs = np.abs(bunny - box).sum(axis=2) > 12
    assert 0.08 < differs.mean() < 0.6


# ---- determinism, Python vs C -------------------------------------------------------------------

@pytest.mark.parametrize("quality", ["fast", "heavy"])
def test_same_pixels_in_any_order_batch_and_thread_count(quality):
    w, h = 48, 36
    with open_renderer("showcase", w, h, quality) as r:
        full = r.render_full()
        xs, ys = grid(w, h)
        perm = np.random.default_rng(5).permutation(xs.size)
        shuffled = r.render(xs[perm], ys[perm])
        assert (shuffled == full[ys[perm], xs[perm]]).all()
        # uneven batches, singles, reversed
        parts = np.split(np.arange(xs.size), [1, 2, 333, 1000])
        for p in parts:
            assert (r.render(xs[p][::-1], ys[p][::-1]) == full[ys[p][::-1], xs[p][::-1]]).all()
        assert (r.render(xs, ys) == full[ys, xs]).all()
    with open_renderer("showcase", w, h, quality, threads=1) as r1:
        assert (r1.render_full() == full).all()
    with open_renderer("showcase", w, h, quality, threads=3) as r3:
        assert (r3.render_full(progress=False) == full).all()


def test_python_binding_equals_raw_c_api():
    """Pixels through the binding equal pixels from the C functions called directly (a separate
    ctypes handle, as the DPI bridge would call them)."""
    lib = ctypes.CDLL(str(library_path()))
    lib.msr_render_create.restype = ctypes.c_void_p
    lib.msr_render_create.argtypes = [ctypes.c_char_p, ctypes.c_int, ctypes.c_int, ctypes.c_int,
                                      ctypes.c_char_p, ctypes.c_size_t]
    lib.msr_render_pixel.argtypes = [ctypes.c_void_p, ctypes.c_int, ctypes.c_int, ctypes.POINTER(ctypes.c_uint8)]
    lib.msr_render_pixels.argtypes = [ctypes.c_void_p, ctypes.c_int, ctypes.c_void_p, ctypes.c_void_p,
                                      ctypes.c_void_p]
    lib.msr_render_destroy.argtypes = [ctypes.c_void_p]
    err = ctypes.create_string_buffer(256)
    ctx = lib.msr_render_create(b"cornell", W, H, 0, err, len(err))
    assert ctx, err.value
    try:
        xs, ys = grid(W, H)
        xs, ys = xs.astype(np.int32), ys.astype(np.int32)
        raw = np.empty((xs.size, 3), np.uint8)
        lib.msr_render_pixels(ctx, xs.size, xs.ctypes.data, ys.ctypes.data, raw.ctypes.data)
        with open_renderer("cornell", W, H) as r:
            full = r.render_full()
            assert (raw.reshape(H, W, 3) == full).all()
            for x, y in [(0, 0), (W - 1, H - 1), (31, 20), (17, 40)]:
                rgb = (ctypes.c_uint8 * 3)()
                lib.msr_render_pixel(ctx, x, y, rgb)
                assert tuple(rgb) == tuple(full[y, x]) == r.render_pixel(x, y)
    finally:
        lib.msr_render_destroy(ctx)


def test_heavy_differs_but_resembles_fast(frames):
    with open_renderer("cornell", W, H, "heavy") as r:
        heavy = r.render_full().astype(int)
    fast = frames["cornell"].astype(int)
    d = np.abs(heavy - fast).mean()
    assert 0.5 < d < 20


# ---- bad input -----------------------------------------------------------------------------------

def _one_line(msg):
    assert msg and "\n" not in msg.strip()
    return msg


@pytest.mark.parametrize("kwargs, needle", [
    (dict(scene="no_such_scene_42"), "unknown scene"),
    (dict(width=0), "width"),
    (dict(height=4097), "height"),
    (dict(quality="ultra"), "quality"),
    (dict(quality=3), "quality"),
    (dict(scene=""), "scene"),
])
def test_bad_arguments_raise_spec_error(kwargs, needle):
    args = dict(scene="cornell", width=W, height=H, quality="fast") | kwargs
    with pytest.raises(spec.SpecError, match=needle) as e:
        open_renderer(args["scene"], args["width"], args["height"], args["quality"])
    _one_line(str(e.value))


def test_render_rejects_pixels_outside_the_frame_and_after_close():
    r = open_renderer("cornell", 8, 6)
    with pytest.raises(spec.SpecError):
        r.render([8], [0])
    with pytest.raises(spec.SpecError):
        r.render([0, 1], [0])
    with pytest.raises(spec.SpecError):
        r.render(np.array([2**32 + 1]), np.array([0]))  # would wrap to 1 as int32
    with pytest.raises(spec.SpecError, match="integers"):
        r.render(np.array([1.5]), np.array([0.0]))
    assert r.render([], []).shape == (0, 3)
    assert (r.render(np.array([3], np.uint16), np.array([2], np.int64)) == r.render([3], [2])).all()
    r.close()
    r.close()  # twice is fine
    with pytest.raises(spec.SpecError, match="closed"):
        r.render([0], [0])


@pytest.fixture
def bad_models(tmp_path):
    files = {}
    files["missing"] = tmp_path / "nope.obj"
    (tmp_path / "garbage.obj").write_bytes(b"this is not a model\n" * 3)
    files["garbage"] = tmp_path / "garbage.obj"
    (tmp_path / "random.ply").write_bytes(np.random.default_rng(0).integers(0, 256, 400, np.uint8).tobytes())
    files["random"] = tmp_path / "random.ply"
    (tmp_path / "lines.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\n")
    files["lines"] = tmp_path / "lines.obj"
    (tmp_path / "points.ply").write_text("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                                         "property float y\nproperty float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n")
    files["points"] = tmp_path / "points.ply"
    (tmp_path / "dir.obj").mkdir()
    files["folder"] = tmp_path / "dir.obj"
    return files


@pytest.mark.parametrize("kind, needle", [("missing", "no such file"), ("garbage", "cannot read|no triangles"),  # OBJ parsing is lenient
                                          ("random", "cannot read"), ("lines", "no triangles"),
                                          ("points", "no triangles"), ("folder", "not a regular file")])
def test_unreadable_models(bad_models, kind, needle):
    with pytest.raises(spec.SpecError, match=needle) as e:
        open_renderer(str(bad_models[kind]), W, H)
    _one_line(str(e.value))


@pytest.mark.parametrize("kind", ["missing", "garbage", "lines"])
@pytest.mark.parametrize("cmd", ["render", "select"])
def test_cli_bad_model_exit_2_and_no_output(tmp_path, bad_models, kind, cmd):
    out = tmp_path / "o.png"
    extra = ["--source-map", tmp_path / "m.png", "--stats", tmp_path / "s.json"] if cmd == "select" else []
    r = cli(cmd, "--scene", bad_models[kind], "--width", W, "--height", H, "--out", out, *extra)
    assert r.returncode == 2, r.stderr
    assert len(r.stderr.strip().splitlines()) == 1, r.stderr
    assert not out.exists() and not (tmp_path / "m.png").exists() and not (tmp_path / "s.json").exists()


def test_cli_missing_library_is_one_line(tmp_path):
    env = dict(os.environ, MSR_RENDER_LIB=str(tmp_path / "libnothing.so"))
    out = tmp_path / "o.png"
    r = cli("render", "--scene", "cornell", "--width", 8, "--height", 8, "--out", out, env=env)
    assert r.returncode == 2 and "make renderer" in r.stderr and len(r.stderr.strip().splitlines()) == 1
    assert not out.exists()


def _limited():
    """Child process guard: if the header check regressed, assimp would allocate gigabytes."""
    import resource
    resource.setrlimit(resource.RLIMIT_AS, (4 << 30, 4 << 30))


@pytest.mark.parametrize("kind", ["ply_ascii", "ply_binary", "off", "assimp_oom_off"])
def test_header_with_absurd_counts_is_rejected_fast(tmp_path, kind):
    """OFF and PLY headers declaring 10^9 elements in a few hundred bytes: a one-line error at
    once (assimp itself would allocate and loop for minutes)."""
    if kind == "assimp_oom_off":
        path = Path("/usr/share/assimp/models/invalid/OutOfMemory.off")
        if not path.is_file():
            pytest.skip("assimp-testmodels not installed")
    else:
        fmt = {"ply_ascii": "ascii", "ply_binary": "binary_little_endian"}.get(kind)
        if fmt:
            text = (f"ply\nformat {fmt} 1.0\nelement vertex 1500000000\nproperty float x\nproperty float y\n"
                    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                    "0 0 0\n1 0 0\n")
            path = tmp_path / "huge.ply"
        else:
            text = "OFF\n# a comment\n4000000000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"
            path = tmp_path / "huge.off"
        path.write_text(text)
    out = tmp_path / "o.png"
    r = subprocess.run([sys.executable, "-m", "msr_model", "render", "--scene", str(path), "--width", "8",
                        "--height", "8", "--out", str(out)], capture_output=True, text=True, timeout=120,
                       preexec_fn=_limited)
    assert r.returncode == 2 and "malformed" in r.stderr and len(r.stderr.strip().splitlines()) == 1, r.stderr
    assert not out.exists()


# ---- model files the project never names ---------------------------------------------------------

CUBE_V = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
CUBE_F = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]


def write_obj(path, offset=(0, 0, 0), scale=1.0, colour=(0.8, 0.05, 0.05)):
    """A cube with an mtl material of the given colour (OBJ faces counter-clockwise)."""
    mtl = path.with_suffix(".mtl")
    mtl.write_text(f"newmtl paint\nKd {colour[0]} {colour[1]} {colour[2]}\n")
    lines = [f"mtllib {mtl.name}", "usemtl paint"]
    lines += [f"v {offset[0] + scale * x} {offset[1] + scale * y} {offset[2] + scale * z}" for x, y, z in CUBE_V]
    lines += ["f " + " ".join(str(i + 1) for i in reversed(f)) for f in CUBE_F]
    path.write_text("\n".join(lines) + "\n")
    return path


def write_ply(path):
    """A red tetrahedron with per-vertex colours (binary little-endian PLY)."""
    verts = [(0, 0, 0), (1, 0, 0), (0.5, 0, 0.9), (0.5, 0.8, 0.3)]
    faces = [(0, 2, 1), (0, 1, 3), (1, 2, 3), (2, 0, 3)]
    head = ("ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
            "property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
            "element face 4\nproperty list uchar int vertex_indices\nend_header\n").encode()
    body = b"".join(struct.pack("<fffBBB", *v, 220, 20, 20) for v in verts)
    body += b"".join(struct.pack("<Biii", 3, *f) for f in faces)
    path.write_bytes(head + body)
    return path


def write_gltf(path):
    """A red octahedron as glTF 2.0 with an embedded buffer and a PBR base colour."""
    pos = np.array([(1, 1, 0), (-1, 1, 0), (0, 2, 0), (0, 0, 0), (0, 1, 1), (0, 1, -1)], np.float32)
    pos[:, 1] -= 1
    idx = np.array([2, 4, 0, 2, 1, 4, 2, 5, 1, 2, 0, 5, 3, 0, 4, 3, 4, 1, 3, 1, 5, 3, 5, 0], np.uint16)
    blob = pos.tobytes() + idx.tobytes()
    doc = {
        "asset": {"version": "2.0"},
        "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.85, 0.05, 0.05, 1.0],
                                                "metallicFactor": 0.0, "roughnessFactor": 1.0}}],
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": pos.nbytes},
                        {"buffer": 0, "byteOffset": pos.nbytes, "byteLength": idx.nbytes}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 6, "type": "VEC3",
                       "min": pos.min(0).tolist(), "max": pos.max(0).tolist()},
                      {"bufferView": 1, "componentType": 5123, "count": 24, "type": "SCALAR"}],
    }
    path.write_text(json.dumps(doc))
    return path


def red_share(img):
    img = img.astype(int)
    red = (img[..., 0] > 2 * img[..., 1] + 20) & (img[..., 0] > 2 * img[..., 2] + 20)
    return red.mean()


@pytest.mark.parametrize("writer, name", [(write_obj, "thing.obj"), (write_ply, "thing.ply"),
                                          (write_gltf, "thing.gltf")])
def test_unnamed_model_file_renders_framed(tmp_path, writer, name):
    path = writer(tmp_path / name)
    with open_renderer(str(path), W, H) as r:
        img = r.render_full()
    share = red_share(img)
    # Auto framing: the red model takes a fair part of the middle of the frame, with ground
    # and sky around it.
    assert 0.04 < share < 0.6, share
    assert red_share(img[H // 4: 3 * H // 4, W // 4: 3 * W // 4]) > share
    assert len(np.unique(img.reshape(-1, 3), axis=0)) >= 100


def test_valid_off_and_ascii_stl_pass_the_header_check(tmp_path):
    off = tmp_path / "cube.off"
    off.write_text("OFF\n8 6 0\n" + "".join(f"{x} {y} {z}\n" for x, y, z in CUBE_V)
                   + "".join(f"4 {' '.join(str(i) for i in reversed(f))}\n" for f in CUBE_F))
    stl = tmp_path / "tet.stl"
    tris = [((0, 0, 0), (0, 1, 0), (1, 0, 0)), ((0, 0, 0), (1, 0, 0), (0, 0, 1)),
            ((0, 0, 0), (0, 0, 1), (0, 1, 0)), ((1, 0, 0), (0, 1, 0), (0, 0, 1))]
    stl.write_text("solid t\n" + "".join(
        "facet normal 0 0 0\nouter loop\n" + "".join(f"vertex {a} {b} {c}\n" for a, b, c in t)
        + "endloop\nendfacet\n" for t in tris) + "endsolid t\n")
    for path in (off, stl):
        with open_renderer(str(path), W, H) as r:
            img = r.render_full()
        assert len(np.unique(img.reshape(-1, 3), axis=0)) >= 100, path


def test_framing_ignores_model_position_and_scale(tmp_path):
    with open_renderer(str(write_obj(tmp_path / "a.obj")), W, H) as r:
        a = r.render_full().astype(int)
    with open_renderer(str(write_obj(tmp_path / "b.obj", offset=(5000, -300, 20), scale=250)), W, H) as r:
        b = r.render_full().astype(int)
    close = (np.abs(a - b).max(axis=2) <= 2).mean()
    assert close > 0.97, close


# ---- the contract commands -----------------------------------------------------------------------

def test_cli_render_writes_the_reference(tmp_path):
    out = tmp_path / "ref.png"
    r = cli("render", "--scene", "cornell", "--width", W, "--height", H, "--out", out)
    assert r.returncode == 0, r.stderr
    got = np.asarray(Image.open(out))
    with open_renderer("cornell", W, H) as rr:
        assert got.shape == (H, W, 3) and (got == rr.render_full()).all()


def test_cli_render_model_file(tmp_path):
    out = tmp_path / "ref.png"
    r = cli("render", "--scene", write_ply(tmp_path / "t.ply"), "--width", 40, "--height", 30, "--out", out)
    assert r.returncode == 0, r.stderr
    assert np.asarray(Image.open(out)).shape == (30, 40, 3)


def test_cli_select_scene_traces_true_pixels(tmp_path):
    out, smap, stats = tmp_path / "o.png", tmp_path / "m.png", tmp_path / "s.json"
    r = cli("select", "--scene", "bunny", "--width", W, "--height", H, "--tile", 8, "--levels", 2,
            "--thr", "8,16", "--out", out, "--source-map", smap, "--stats", stats)
    assert r.returncode == 0, r.stderr
    frame, source = np.asarray(Image.open(out)), np.asarray(Image.open(smap))
    st = json.loads(stats.read_text())
    with open_renderer("bunny", W, H) as rr:
        ref = rr.render_full()
        golden = select(rr, W, H, Params(tile=8, levels=2, thr=(8, 16)))
    traced = source < spec.SRC_INTERP_BASE
    assert (frame[traced] == ref[traced]).all()          # traced pixels are the renderer's
    assert (frame == golden.frame).all() and (source == golden.source).all()
    assert st["traced"] == int(traced.sum()) and 0 < st["traced_fraction"] < 1
    assert st["source"] == "bunny"


def test_srgb_table_is_generated_from_the_exact_curve():
    """The committed threshold table equals its generator's output (60-digit decimals)."""
    root = Path(__file__).resolve().parents[2]
    gen = root / "sw_model" / "renderer" / "tools" / "gen_srgb_table.py"
    r = subprocess.run([sys.executable, str(gen)], capture_output=True, text=True, check=True)
    assert r.stdout == (root / "sw_model" / "renderer" / "src" / "srgb_table.h").read_text()


def test_cli_render_heavy_and_bad_quality(tmp_path):
    out = tmp_path / "h.png"
    r = cli("render", "--scene", "showcase", "--width", 24, "--height", 18, "--quality", "heavy", "--out", out)
    assert r.returncode == 0, r.stderr
    with open_renderer("showcase", 24, 18, "heavy") as rr:
        assert (np.asarray(Image.open(out)) == rr.render_full()).all()
    bad = tmp_path / "b.png"
    r = cli("render", "--scene", "showcase", "--width", 24, "--height", 18, "--quality", "best", "--out", bad)
    assert r.returncode == 2 and "quality" in r.stderr and not bad.exists()


def test_isa_override(tmp_path):
    """MSR_EMBREE_ISA picks Embree's instruction set; an unknown name is an error, not a silent
    fallback to whatever Embree likes best."""
    base = dict(os.environ)
    out = tmp_path / "o.png"
    r = cli("render", "--scene", "cornell", "--width", 8, "--height", 6, "--out", out,
            env=base | {"MSR_EMBREE_ISA": "avx3000"})
    assert r.returncode == 2 and "MSR_EMBREE_ISA" in r.stderr and not out.exists()
    r = cli("render", "--scene", "cornell", "--width", 32, "--height", 24, "--out", out,
            env=base | {"MSR_EMBREE_ISA": "sse4.2"})
    assert r.returncode == 0, r.stderr
    with open_renderer("cornell", 32, 24) as rr:
        ref = rr.render_full()
    got = np.asarray(Image.open(out))
    # Another ISA may flip a pixel exactly on a triangle edge, nothing more.
    assert (got != ref).any(axis=2).mean() < 0.01


def test_tall_frame_fits_the_shorter_side():
    """The field of view spans the shorter side: in a tall frame the box fills the width and
    the void shows above and below (the transpose of the wide frame's layout)."""
    with open_renderer("cornell", 36, 48) as r:
        img = r.render_full().astype(int)
    black = img.sum(axis=2) == 0
    assert black[:3].all() and black[-3:].all()
    assert not black[24, 2:-2].any()           # the middle row is box (the view is 8 mm wider)
    left = img[24, 1]
    assert left[0] > 2 * left[1], left          # red wall at the left edge
