"""Textures that really apply, per model format in the Debian model packages: a model whose
texture file is found renders with it (its pixels differ from the same model's render with
the picture taken away, which falls back to the material colour with a warning); a texture
that is found but cannot be applied is a warning naming the file and the reason."""
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

M = Path("/usr/share/assimp/models")
needs_models = pytest.mark.skipif(not M.is_dir(), reason="needs the Debian package assimp-testmodels")
W, H = 96, 72


def render(path, tmp_path, name="out.png"):
    out = tmp_path / name
    r = subprocess.run([sys.executable, "-m", "msr_model", "render", "--scene", str(path), "--width", str(W),
                        "--height", str(H), "--out", str(out)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return np.asarray(Image.open(out).convert("RGB")).astype(int), r.stderr


# (model, files beside it the model needs besides its textures, texture file name)
FORMATS = [
    ("Collada/duck.dae", [], "duckCM.tga"),
    ("OBJ/spider.obj", ["spider.mtl"], "SpiderTex.jpg"),
    ("glTF2/BoxTextured-glTF/BoxTextured.gltf", ["BoxTextured0.bin"], "CesiumLogoFlat.png"),
    ("glTF/BoxTextured-glTF/BoxTextured.gltf", ["BoxTextured.bin"], "CesiumLogoFlat.png"),
    ("MS3D/jeep1.ms3d", [], "jeep1.jpg"),                          # '.\jeep1.jpg', emissive 0.35
    ("3DS/cube_with_diffuse_texture.3DS", [], "TEST.PNG"),
    ("LWO/LWO2/MappingModes/earth_spherical_y.lwo", [], "earthSpherical.jpg"),   # no UVs: generated
]


@needs_models
@pytest.mark.parametrize("model,extra,texture", FORMATS, ids=[Path(f[0]).suffix + ":" + Path(f[0]).stem for f in FORMATS])
def test_found_texture_is_applied(tmp_path, model, extra, texture):
    src = M / model
    if not src.is_file():
        pytest.skip(f"{src} not installed")
    with_tex, err = render(src, tmp_path, "tex.png")
    assert "not found" not in err and "not applied" not in err and "cannot be decoded" not in err, err
    # The model alone (its texture left behind): the material colour, and a warning naming the file.
    bare = tmp_path / "bare"
    bare.mkdir()
    for f in [src.name, *extra]:
        shutil.copy(src.parent / f, bare / f)
    plain, err = render(bare / src.name, tmp_path, "plain.png")
    assert "not found" in err and texture.lower() in err.lower(), err
    # Same framing, so the background agrees; over the object the texture changes the colours.
    diff = np.abs(with_tex - plain).max(axis=2)
    changed = diff > 24
    assert changed.mean() > 0.03, changed.mean()
    assert diff[changed].mean() > 40, diff[changed].mean()


@needs_models
def test_embedded_gltf_textures_apply():
    """The binary (.glb) and the data-URI glTF 2.0 box hold their picture inside the file: the
    logo's blue and green show, and both give the same pixels (the external box differs only
    in its sampler's wrap modes)."""
    from msr_model.embree import open_renderer
    imgs = []
    for variant in ("BoxTextured-glTF-Binary/BoxTextured.glb", "BoxTextured-glTF-Embedded/BoxTextured.gltf"):
        with open_renderer(str(M / "glTF2" / variant), W, H) as r:
            imgs.append(r.render_full(progress=False).astype(int))
    assert (imgs[0] == imgs[1]).all()
    r, g, b = imgs[0][..., 0], imgs[0][..., 1], imgs[0][..., 2]
    assert ((b > r + 40) & (b > g)).mean() > 0.03           # the logo's blue
    assert ((g > r + 30) & (g > b)).mean() > 0.03           # and green, on a material without colour


def write_box(folder, mtl_lines, uvs=True):
    """A unit cube as OBJ with material `paint` (box.mtl), with or without texture coordinates."""
    v = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    faces = [(1, 3, 4, 2), (5, 6, 8, 7), (1, 2, 6, 5), (3, 7, 8, 4), (1, 5, 7, 3), (2, 4, 8, 6)]
    lines = ["mtllib box.mtl", "usemtl paint"] + [f"v {x} {y} {z}" for x, y, z in v]
    if uvs:
        lines += ["vt 0 0", "vt 1 0", "vt 1 1", "vt 0 1"]
        lines += ["f " + " ".join(f"{i}/{k + 1}" for k, i in enumerate(f)) for f in faces]
    else:
        lines += ["f " + " ".join(map(str, f)) for f in faces]
    (folder / "box.obj").write_text("\n".join(lines) + "\n")
    (folder / "box.mtl").write_text("\n".join(["newmtl paint", *mtl_lines]) + "\n")
    Image.fromarray(np.tile(np.array([[[230, 20, 20], [20, 40, 230]]], np.uint8), (8, 4, 1))).save(folder / "check.png")
    return folder / "box.obj"


def test_texture_without_uvs_is_a_warning(tmp_path):
    obj = write_box(tmp_path, ["Kd 1 1 1", "map_Kd check.png"], uvs=False)
    _, err = render(obj, tmp_path)
    assert "check.png" in err and "no texture coordinates" in err, err


def test_texture_on_a_lamp_is_a_warning(tmp_path):
    """Emission brighter than the surface reflects makes a lamp, which takes no map: said so."""
    obj = write_box(tmp_path, ["Kd 0.5 0.5 0.5", "Ke 4 4 4", "map_Kd check.png"])
    _, err = render(obj, tmp_path)
    assert "check.png" in err and "not applied" in err and "emissive" in err, err


def test_faint_emission_keeps_the_map(tmp_path):
    """A self-illumination term below the diffuse colour (as Milkshape writes) keeps the map."""
    obj = write_box(tmp_path, ["Kd 0.8 0.8 0.8", "Ke 0.35 0.35 0.35", "map_Kd check.png"])
    img, err = render(obj, tmp_path)
    assert "not applied" not in err, err
    red = (img[..., 0] > 2 * img[..., 1] + 30) & (img[..., 0] > 2 * img[..., 2] + 30)
    blue = (img[..., 2] > 2 * img[..., 0] + 30)
    assert red.mean() > 0.02 and blue.mean() > 0.02


def test_unreadable_texture_is_a_warning(tmp_path):
    obj = write_box(tmp_path, ["Kd 1 1 1", "map_Kd check.png"])
    (tmp_path / "check.png").write_bytes(b"not a picture")
    _, err = render(obj, tmp_path)
    assert "check.png" in err and "cannot be decoded" in err, err
