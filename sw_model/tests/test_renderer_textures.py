"""Materials, textures, cameras and lights from model files: the Collada duck is yellow and
textured, a model whose texture files are gone falls back to its material colour with a
warning, glTF 2.0 files written here (.gltf + .bin + .png, and .glb) show their base-colour
texture and factors, and --camera gives the same pixels in render, select and the raw C API."""
import ctypes
import json
import shutil
import struct
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from msr_model import spec
from msr_model.embree import library_path, open_renderer

DUCK = Path("/usr/share/assimp/models/Collada/duck.dae")
needs_duck = pytest.mark.skipif(not DUCK.is_file(), reason="needs the Debian package assimp-testmodels")


def cli(*args):
    return subprocess.run([sys.executable, "-m", "msr_model", *map(str, args)], capture_output=True, text=True)


def masks(img):
    img = img.astype(int)
    r, g, b = img[..., 0], img[..., 1], img[..., 2]
    yellow = (r > 120) & (g > 90) & (b < 0.6 * g) & (r - b > 70)
    orange = (r > 150) & (g < 0.75 * r) & (b < 0.4 * r)
    return yellow, orange


# ---- the Collada duck ----------------------------------------------------------------------------

@needs_duck
def test_duck_is_a_yellow_textured_duck(tmp_path):
    out = tmp_path / "duck.png"
    r = cli("render", "--scene", DUCK, "--width", 320, "--height", 240, "--out", out)
    assert r.returncode == 0, r.stderr
    assert "warning" not in r.stderr
    img = np.asarray(Image.open(out).convert("RGB")).astype(int)
    yellow, orange = masks(img)
    # The body: yellow (duckCM.tga), red above green above blue.
    assert yellow.mean() > 0.01, yellow.mean()
    mean = img[yellow].mean(axis=0)
    assert mean[0] > mean[1] > 2 * mean[2] + 40, mean
    # The texture's detail, not a flat colour: an orange beak and a dark eye inside the duck's
    # box, and a spread of colours over the body.
    ys, xs = np.nonzero(yellow)
    box = img[ys.min():ys.max() + 1, xs.min():xs.max() + 1]
    by, bo = masks(box)
    assert bo.sum() >= 20, bo.sum()
    assert (box.sum(axis=2) < 150).sum() >= 5
    duck = box[by | bo]
    assert (duck[:, 0] - duck[:, 1]).std() > 8      # hue varies: beak vs body
    assert duck.std(axis=0)[:2].min() > 15          # shading and texture


@needs_duck
def test_duck_without_its_texture_falls_back_with_a_warning(tmp_path):
    shutil.copy(DUCK, tmp_path / "duck.dae")  # duckCM.tga not copied
    out = tmp_path / "bare.png"
    r = cli("render", "--scene", tmp_path / "duck.dae", "--width", 160, "--height", 120, "--out", out)
    assert r.returncode == 0, r.stderr
    assert "warning" in r.stderr and "duckCM.tga" in r.stderr and "not found" in r.stderr
    img = np.asarray(Image.open(out).convert("RGB"))
    yellow, orange = masks(img)
    assert yellow.sum() == 0 and orange.sum() == 0
    # The same duck with its texture next to it is yellow again.
    shutil.copy(DUCK.parent / "duckCM.tga", tmp_path / "duckCM.tga")
    with open_renderer(str(tmp_path / "duck.dae"), 160, 120) as rr:
        assert masks(rr.render_full(progress=False))[0].sum() > 50


def write_unit_box(obj) -> None:
    """A unit cube as OBJ, every face mapped to the whole texture, material `paint` from
    box.mtl beside it."""
    v = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    faces = [(1, 3, 4, 2), (5, 6, 8, 7), (1, 2, 6, 5), (3, 7, 8, 4), (1, 5, 7, 3), (2, 4, 8, 6)]
    lines = ["mtllib box.mtl", "usemtl paint"] + [f"v {x} {y} {z}" for x, y, z in v]
    lines += ["vt 0 0", "vt 1 0", "vt 1 1", "vt 0 1"]
    lines += ["f " + " ".join(f"{i}/{k + 1}" for k, i in enumerate(f)) for f in faces]
    obj.write_text("\n".join(lines) + "\n")


def test_missing_map_keeps_the_material_colour(tmp_path, capfd):
    """An OBJ material with a yellow Kd and a map_Kd that is not there renders yellow."""
    obj, mtl = tmp_path / "box.obj", tmp_path / "box.mtl"
    mtl.write_text("newmtl paint\nKd 0.9 0.75 0.05\nmap_Kd textures\\Missing.PNG\n")
    write_unit_box(obj)
    with open_renderer(str(obj), 64, 48) as r:
        img = r.render_full(progress=False)
    assert "Missing.PNG" in capfd.readouterr().err
    yellow, _ = masks(img)
    assert yellow.mean() > 0.05


# ---- glTF 2.0 written here -----------------------------------------------------------------------

def png_bytes(img):
    import io
    buf = io.BytesIO()
    Image.fromarray(img).save(buf, format="PNG")
    return buf.getvalue()


def checker(n=64, cell=16):
    """n x n texels: red and blue squares of cell x cell texels."""
    y, x = np.mgrid[0:n, 0:n] // cell
    img = np.zeros((n, n, 3), np.uint8)
    red = (x + y) % 2 == 0
    img[red] = (230, 20, 20)
    img[~red] = (20, 40, 230)
    return img


def quad_cube():
    """A unit cube with 4 vertices per face and UVs covering each face once."""
    pos, uv, idx = [], [], []
    for axis in range(3):
        for side in (0, 1):
            base = len(pos)
            for (a, b) in ((0, 0), (1, 0), (1, 1), (0, 1)):
                p = [0.0, 0.0, 0.0]
                p[axis] = float(side)
                p[(axis + 1) % 3] = float(a)
                p[(axis + 2) % 3] = float(b)
                pos.append(p)
                uv.append((float(a), float(b)))
            tri = [0, 1, 2, 0, 2, 3] if side else [0, 2, 1, 0, 3, 2]
            idx += [base + t for t in tri]
    return np.array(pos, np.float32), np.array(uv, np.float32), np.array(idx, np.uint16)


def gltf_doc(factor, image):
    pos, uv, idx = quad_cube()
    blob = pos.tobytes() + uv.tobytes() + idx.tobytes()
    doc = {
        "asset": {"version": "2.0"},
        "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 0}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": factor, "baseColorTexture": {"index": 0},
                                                "metallicFactor": 0.0, "roughnessFactor": 1.0}}],
        "textures": [{"source": 0, "sampler": 0}],
        "samplers": [{"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 10497}],
        "images": [image],
        "buffers": [{"byteLength": len(blob)}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": pos.nbytes},
                        {"buffer": 0, "byteOffset": pos.nbytes, "byteLength": uv.nbytes},
                        {"buffer": 0, "byteOffset": pos.nbytes + uv.nbytes, "byteLength": idx.nbytes}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": len(pos), "type": "VEC3",
                       "min": pos.min(0).tolist(), "max": pos.max(0).tolist()},
                      {"bufferView": 1, "componentType": 5126, "count": len(uv), "type": "VEC2"},
                      {"bufferView": 2, "componentType": 5123, "count": len(idx), "type": "SCALAR"}],
    }
    return doc, blob


def write_gltf_files(folder, factor=(1.0, 1.0, 1.0, 1.0)):
    """.gltf + .bin + .png side by side."""
    doc, blob = gltf_doc(list(factor), {"uri": "Checker.png"})
    doc["buffers"][0]["uri"] = "cube.bin"
    (folder / "cube.bin").write_bytes(blob)
    (folder / "Checker.png").write_bytes(png_bytes(checker()))
    (folder / "cube.gltf").write_text(json.dumps(doc))
    return folder / "cube.gltf"


def write_glb(path, factor=(1.0, 1.0, 1.0, 1.0)):
    """Binary glTF: the PNG lives in the binary chunk (an embedded, compressed texture)."""
    png = png_bytes(checker())
    doc, blob = gltf_doc(list(factor), {"bufferView": 3, "mimeType": "image/png"})
    pad = (-len(blob)) % 4
    doc["bufferViews"].append({"buffer": 0, "byteOffset": len(blob) + pad, "byteLength": len(png)})
    body = blob + b"\0" * pad + png
    body += b"\0" * ((-len(body)) % 4)
    doc["buffers"][0]["byteLength"] = len(body)
    js = json.dumps(doc).encode()
    js += b" " * ((-len(js)) % 4)
    chunks = struct.pack("<II", len(js), 0x4E4F534A) + js + struct.pack("<II", len(body), 0x004E4942) + body
    path.write_bytes(struct.pack("<III", 0x46546C67, 2, 12 + len(chunks)) + chunks)
    return path


def shares(img):
    img = img.astype(int)
    red = (img[..., 0] > 2 * img[..., 1] + 30) & (img[..., 0] > 2 * img[..., 2] + 30)
    blue = (img[..., 2] > 2 * img[..., 0] + 30) & (img[..., 2] > img[..., 1] + 30)
    return red.mean(), blue.mean()


def test_gltf_and_glb_show_the_base_colour_texture(tmp_path):
    (tmp_path / "a").mkdir()
    gltf = write_gltf_files(tmp_path / "a")
    glb = write_glb(tmp_path / "cube.glb")
    imgs = []
    for path in (gltf, glb):
        with open_renderer(str(path), 96, 72) as r:
            imgs.append(r.render_full(progress=False))
        red, blue = shares(imgs[-1])
        assert red > 0.03 and blue > 0.03, (path.name, red, blue)
    # External image and embedded image: the same texels, the same pixels.
    assert (imgs[0] == imgs[1]).all()


def test_gltf_base_colour_factor_multiplies_the_texture(tmp_path):
    glb = write_glb(tmp_path / "cyan.glb", factor=(0.0, 1.0, 1.0, 1.0))  # removes the red
    with open_renderer(str(glb), 96, 72) as r:
        red, blue = shares(r.render_full(progress=False))
    assert red == 0 and blue > 0.03


def test_gltf_camera_from_the_file(tmp_path):
    """A glTF camera node replaces the automatic framing (straight down the -z axis here)."""
    doc, blob = gltf_doc([1.0, 1.0, 1.0, 1.0], {"uri": "Checker.png"})
    doc["buffers"][0]["uri"] = "cube.bin"
    (tmp_path / "cube.bin").write_bytes(blob)
    (tmp_path / "Checker.png").write_bytes(png_bytes(checker()))
    doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.5, "aspectRatio": 1.0, "znear": 0.1}}]
    doc["nodes"].append({"camera": 0, "translation": [0.5, 0.5, 4.0]})
    doc["scenes"][0]["nodes"].append(1)
    (tmp_path / "cam.gltf").write_text(json.dumps(doc))
    with open_renderer(str(tmp_path / "cam.gltf"), 64, 64) as r:
        img = r.render_full(progress=False)
    # Head-on: the front face (z = 1) is a square in the middle holding the 4 x 4 checker.
    red, blue = shares(img)
    assert red > 0.05 and blue > 0.05
    mid = img[24:40, 24:40]
    assert sum(shares(mid)) > 0.9
    corner = img[:6, :6]
    assert sum(shares(corner)) == 0


# ---- cameras -------------------------------------------------------------------------------------

CAM = "0.3,1.2,2.5,0,0.4,0,35"


@needs_duck
def test_camera_same_pixels_in_render_select_and_c_api(tmp_path):
    w, h = 64, 48
    ref = tmp_path / "ref.png"
    r = cli("render", "--scene", "duck", "--width", w, "--height", h, "--out", ref, f"--camera={CAM}")
    assert r.returncode == 0, r.stderr
    ref_img = np.asarray(Image.open(ref).convert("RGB"))
    with open_renderer("duck", w, h, camera=CAM) as rr:
        assert (rr.render_full(progress=False) == ref_img).all()
    with open_renderer("duck", w, h) as rr:
        assert (rr.render_full(progress=False) != ref_img).any()  # the view did change
    out, st = tmp_path / "sel.png", tmp_path / "st.json"
    smap = tmp_path / "map.png"
    r = cli("select", "--scene", "duck", "--width", w, "--height", h, "--tile", 8, "--levels", 2, "--thr", "0,0",
            "--out", out, "--source-map", smap, "--stats", st, f"--camera={CAM}")
    assert r.returncode == 0, r.stderr
    sel = np.asarray(Image.open(out).convert("RGB"))
    traced = np.asarray(Image.open(smap)) == 0
    assert traced.any() and (sel[traced] == ref_img[traced]).all()
    # The raw C API, as the DPI bridge calls it, with the same string.
    lib = ctypes.CDLL(str(library_path()))
    lib.msr_render_create_view.restype = ctypes.c_void_p
    lib.msr_render_create_view.argtypes = [ctypes.c_char_p, ctypes.c_char_p, ctypes.c_int, ctypes.c_int,
                                           ctypes.c_int, ctypes.c_char_p, ctypes.c_size_t]
    lib.msr_render_pixel.argtypes = [ctypes.c_void_p, ctypes.c_int, ctypes.c_int, ctypes.POINTER(ctypes.c_uint8)]
    lib.msr_render_destroy.argtypes = [ctypes.c_void_p]
    ctx = lib.msr_render_create_view(b"duck", CAM.encode(), w, h, 0, None, 0)
    assert ctx
    try:
        rgb = (ctypes.c_uint8 * 3)()
        for x, y in [(0, 0), (w // 2, h // 2), (w - 1, h - 1), (17, 29)]:
            lib.msr_render_pixel(ctx, x, y, rgb)
            assert tuple(rgb) == tuple(ref_img[y, x])
    finally:
        lib.msr_render_destroy(ctx)


@pytest.mark.parametrize("bad", ["1,2,3", "1,2,3,4,5,6", "a,b,c,d,e,f,g", "0,0,0,0,0,0,40", "1,2,3,4,5,6,0",
                                 "1,2,3,4,5,6,180", "1,2,3,4,5,6,40,1", "1,2,3,4,5,6,nan"])
@pytest.mark.parametrize("cmd", ["render", "select"])
def test_malformed_camera_is_one_line_exit_2(tmp_path, bad, cmd):
    out = tmp_path / "o.png"
    args = [cmd, "--scene", "cornell", "--width", 16, "--height", 12, "--out", out, f"--camera={bad}"]
    r = cli(*args)
    assert r.returncode == 2
    assert r.stderr.count("\n") == 1 and "camera" in r.stderr, r.stderr
    assert not out.exists()


def test_camera_in_model_units_follows_the_framing(tmp_path):
    """The same view in model units gives the same picture whatever the model's scale."""
    from test_renderer import write_obj
    small = write_obj(tmp_path / "small.obj", scale=1.0)
    big = write_obj(tmp_path / "big.obj", scale=100.0)
    a = open_renderer(str(small), 48, 36, camera="2,1.5,3,0.5,0.5,0.5,40").render_full(progress=False)
    b = open_renderer(str(big), 48, 36, camera="200,150,300,50,50,50,40").render_full(progress=False)
    diff = np.abs(a.astype(int) - b.astype(int)).max(axis=2)
    assert (diff > 8).mean() < 0.01


def test_bad_camera_raises_spec_error():
    with pytest.raises(spec.SpecError, match="camera"):
        open_renderer("cornell", 8, 8, camera="1,2")


@needs_duck
@pytest.mark.parametrize("quality", ["fast", "heavy"])
def test_textured_pixels_do_not_depend_on_order_or_threads(quality):
    w, h = 40, 30
    with open_renderer("duck", w, h, quality=quality, threads=1) as r:
        full = r.render_full(progress=False).reshape(-1, 3)
    rng = np.random.default_rng(5)
    order = rng.permutation(w * h)
    ys, xs = np.divmod(order, w)
    with open_renderer("duck", w, h, quality=quality, threads=2) as r:
        got = r.render(xs, ys)
    assert (got == full[order]).all()


# ---- G-buffer: primitive, material and depth of the primary hit ----------------------------------

def test_gbuffer_ids_and_depth():
    w, h = 64, 48
    with open_renderer("cornell", w, h) as r:
        prim, mat, depth = r.gbuffer_full()
        rgb = r.render_full(progress=False)
        # Deterministic, and the same through any subset of pixels.
        p2, m2, d2 = r.gbuffer(np.array([5, 40]), np.array([7, 30]))
    assert prim.dtype == np.uint32 and mat.dtype == np.uint32 and depth.dtype == np.float32
    assert (p2 == prim[[7, 30], [5, 40]]).all() and (d2 == depth[[7, 30], [5, 40]]).all()
    # Outside the open front of the box (black columns): the sky, id 0, infinite depth.
    sky = rgb.sum(axis=2) == 0
    assert (prim[sky] == 0).all() and (mat[sky] == 0).all() and np.isinf(depth[sky]).all()
    inside = ~sky
    assert (prim[inside] > 0).all() and (mat[inside] > 0).all()
    assert np.isfinite(depth[inside]).all() and (depth[inside] > 800).all()  # the box starts 800 mm away
    # The side walls have their own materials (red, green) and the blocks add primitives.
    assert len(np.unique(mat[inside])) >= 4
    assert len(np.unique(prim[inside])) >= 10


def test_gbuffer_follows_the_camera():
    with open_renderer("cornell", 32, 24, camera="278,273,-800,278,273,0,40") as r:
        _, _, depth = r.gbuffer_full()
    # Looking straight at the back wall's centre through the open front: 800 + 559.2 mm.
    assert abs(float(depth[12, 16]) - 1359.2) < 1e-2


def test_texture_found_by_file_name_with_a_warning(tmp_path):
    """An OBJ whose map_Kd is a Windows path from another machine, with another letter case:
    the picture beside the model is used (by file name, ignoring case), and the warning says
    what was substituted."""
    obj, mtl = tmp_path / "box.obj", tmp_path / "box.mtl"
    mtl.write_text("newmtl paint\nKd 1 1 1\nmap_Kd C:\\Work\\Assets\\TEX\\Checker.PNG\n")
    (tmp_path / "checker.png").write_bytes(png_bytes(checker()))
    write_unit_box(obj)
    out = tmp_path / "box.png"
    r = cli("render", "--scene", obj, "--width", 96, "--height", 72, "--out", out)
    assert r.returncode == 0, r.stderr
    assert "Checker.PNG" in r.stderr and "checker.png" in r.stderr and "not where it says" in r.stderr
    red, blue = shares(np.asarray(Image.open(out).convert("RGB")))
    assert red > 0.03 and blue > 0.03                      # the checker, not the white material


def md2_bytes():
    """A minimal Quake II model (MD2) without skins: one frame, a quad of two triangles. Its
    loader names the diffuse map by the format's placeholder, `$texture_dummy.bmp`."""
    verts = [(0, 0, 0), (255, 0, 0), (255, 255, 0), (0, 255, 0)]
    st = [(0, 0), (63, 0), (63, 63), (0, 63)]
    tris = [((0, 1, 2), (0, 1, 2)), ((0, 2, 3), (0, 2, 3))]
    nv, nst, nt = len(verts), len(st), len(tris)
    framesize = 40 + 4 * nv
    ofs_st = 68
    ofs_tris = ofs_st + 4 * nst
    ofs_frames = ofs_tris + 12 * nt
    ofs_end = ofs_frames + framesize
    head = struct.pack("<4s16i", b"IDP2", 8, 64, 64, framesize, 0, nv, nst, nt, 0, 1,
                       68, ofs_st, ofs_tris, ofs_frames, ofs_end, ofs_end)
    body = b"".join(struct.pack("<2h", *p) for p in st)
    body += b"".join(struct.pack("<3h3h", *v, *t) for v, t in tris)
    body += struct.pack("<3f3f16s", 1 / 255, 1 / 255, 1 / 255, 0, 0, 0, b"frame0")
    body += b"".join(struct.pack("<4B", *v, 0) for v in verts)
    return head + body + bytes(64)     # the loader wants every section to end before the file does


def test_skin_placeholder_resolved_by_the_model_name(tmp_path):
    """A format's placeholder skin name resolves to a picture with the model's name beside it,
    with a warning; without one the material colour stays and the warning says so."""
    md2 = tmp_path / "Ogre.md2"
    md2.write_bytes(md2_bytes())
    r = cli("render", "--scene", md2, "--width", 64, "--height", 64, "--out", tmp_path / "bare.png")
    assert r.returncode == 0, r.stderr
    assert "placeholder" in r.stderr and "no picture named Ogre" in r.stderr
    (tmp_path / "ogre.PNG").write_bytes(png_bytes(checker()))
    r = cli("render", "--scene", md2, "--width", 64, "--height", 64, "--out", tmp_path / "skin.png")
    assert r.returncode == 0, r.stderr
    assert "placeholder" in r.stderr and "ogre.PNG" in r.stderr
    red, blue = shares(np.asarray(Image.open(tmp_path / "skin.png").convert("RGB")))
    assert red > 0.03 and blue > 0.03
