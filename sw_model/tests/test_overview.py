"""The summary picture (msr_model.overview): `make sim`'s summary.png and `select --overview`.

Checked on the written PNG: its size and every panel's size from `layout`, the frame and
reference panels, the source map in the palette where the codes are, the legend swatches in
the palette colours, the error and traced-per-tile heat maps against their colour maps; and
the one palette shared with the eval's example strips."""
import subprocess
import sys

import matplotlib
import numpy as np
import pytest
from PIL import Image

from msr_model import ImageRenderer, Params, select, spec
from msr_model.overview import RunInfo, abs_error, error_scale, layout, traced_per_tile, write_summary
from msr_model.palette import SOURCE_COLOURS, legend_entries, legend_image, source_rgb
from msr_model.testimage import test_image as make_image


def _lut(name):
    return (matplotlib.colormaps[name](np.linspace(0, 1, 256))[:, :3] * 255 + 0.5).astype(np.uint8)


def _crop(png, box):
    x0, y0, x1, y1 = box
    return png[y0:y1, x0:x1]


def _run(w, h, params):
    img = make_image(w, h)
    res = select(ImageRenderer(img), w, h, params)
    return img, res


CASES = [  # (W, H): enlarged 3:1, as is, reduced 1:2 (wider than 640), 1080p reduced 1:3
    (160, 120), (640, 480), (1000, 300), (1920, 1080)]


@pytest.mark.parametrize("w,h", CASES)
def test_summary_panels(tmp_path, w, h):
    params = Params(tile=16, levels=2, thr=(8, 16), metric="max", fov_gain=0)
    ref, res = _run(w, h, params)
    path = tmp_path / "summary.png"
    lay = write_summary(path, res.frame, ref, res.source,
                        RunInfo("testimage", params, psnr_db=30.0, ssim=0.9, cycles=1234, bit_exact=True))
    png = np.asarray(Image.open(path).convert("RGB"))
    assert png.shape[:2] == (lay.size[1], lay.size[0]) == (layout(w, h).size[1], layout(w, h).size[0])
    pw, ph = lay.panel
    assert pw <= 640 and pw >= min(480, w) and abs(pw / ph - w / h) < 0.05
    for name in ("frame", "reference", "error", "source", "traced"):
        x0, y0, x1, y1 = lay.boxes[name]
        assert (x1 - x0, y1 - y0) == (pw, ph) and x1 <= lay.size[0] and y1 <= lay.size[1]

    # Sample panel pixels and the frame pixels they show (nearest).
    rng = np.random.default_rng(0)
    pxs, pys = rng.integers(0, pw, 400), rng.integers(0, ph, 400)
    fxy = [lay.frame_xy(int(px), int(py)) for px, py in zip(pxs, pys)]
    src = _crop(png, lay.boxes["source"])
    for (px, py), (fx, fy) in zip(zip(pxs, pys), fxy):
        assert tuple(src[py, px]) == SOURCE_COLOURS[int(res.source[fy, fx])]
    if lay.down == 1:      # frames shown pixel for pixel (enlarged by repetition)
        for (px, py), (fx, fy) in zip(zip(pxs, pys), fxy):
            assert (_crop(png, lay.boxes["frame"])[py, px] == res.frame[fy, fx]).all()
            assert (_crop(png, lay.boxes["reference"])[py, px] == ref[fy, fx]).all()
    else:                  # reduced: the block mean
        d = lay.down
        for (px, py), (fx, fy) in zip(zip(pxs, pys), fxy):
            if fx + d <= w and fy + d <= h:
                mean = res.frame[fy:fy + d, fx:fx + d].reshape(-1, 3).mean(axis=0)
                assert np.abs(_crop(png, lay.boxes["frame"])[py, px] - mean).max() <= 1

    # Error map: the colour of the largest error in the block; traced per tile: its tile's fraction.
    err, vmax = abs_error(res.frame, ref), None
    vmax = error_scale(err)
    per_tile = traced_per_tile(res.source, params.tile)
    inferno, viridis = _lut("inferno"), _lut("viridis")
    d = lay.down
    for (px, py), (fx, fy) in zip(zip(pxs, pys), fxy):
        e = err[fy:fy + d, fx:fx + d].max()
        want = inferno[int(np.clip(e / vmax * 255 + 0.5, 0, 255))]
        assert (_crop(png, lay.boxes["error"])[py, px] == want).all()
        f = per_tile[min(fy // params.tile, per_tile.shape[0] - 1), min(fx // params.tile, per_tile.shape[1] - 1)]
        assert (_crop(png, lay.boxes["traced"])[py, px] == viridis[int(f * 255 + 0.5)]).all()

    # Colour bars and the legend: one swatch per code of an L-level run, in the palette colour.
    for bar in ("error_bar", "traced_bar"):
        x0, y0, x1, y1 = lay.boxes[bar]
        col = png[y0:y1, (x0 + x1) // 2]
        assert (col[-1] == (inferno if bar == "error_bar" else viridis)[0]).all()
        assert len({tuple(c) for c in col}) > 50
    codes = [e.code for e in legend_entries(params.levels, res.source)]
    assert codes[:5] == [0, 1, 2, 17, 18]
    for c in codes:
        x0, y0, x1, y1 = lay.boxes[f"legend_{c}"]
        sw = png[y0 + 2:y1 - 2, x0 + 2:x1 - 2].reshape(-1, 3)
        assert (sw == SOURCE_COLOURS[c]).all(), c
        assert not (png[y0:y1, x1 + 10:x1 + 200] == 255).all(), f"no label next to swatch {c}"


def test_palette_is_categorical_and_shared_with_the_eval_strips():
    colours = [SOURCE_COLOURS[c] for c in (0, 1, 2, 3, 16, 17, 18, 19)]
    assert len(set(colours)) == 8
    # every pair differs clearly (sum of channel differences)
    for i, a in enumerate(colours):
        for b in colours[i + 1:]:
            assert sum(abs(x - y) for x, y in zip(a, b)) > 60
    from msr_eval import methods, report
    params = Params(tile=16, levels=3, thr=(8, 16, 32), metric="max", fov_gain=0)
    ref = make_image(96, 64)
    for res in (methods.multi_level(ImageRenderer(ref), 96, 64, params),
                methods.checkerboard(ImageRenderer(ref), 96, 64)):     # codes 0 and 16 only
        strip = np.asarray(report.example_strip(ref, res, panel_w=96))
        panel = strip[:64, 100:196]            # the source-map panel, 1:1 at this size
        assert (panel == source_rgb(res.source)).all()
        legend = np.asarray(legend_image(None, res.source))
        assert (strip[64:64 + legend.shape[0], :legend.shape[1]] == legend).all()
        present = {tuple(c) for c in legend.reshape(-1, 3)}
        codes = [int(c) for c in np.unique(res.source)]
        assert all(SOURCE_COLOURS[c] in present for c in codes), codes
    assert codes == [0, 16]


def test_select_overview_flag(tmp_path):
    img = make_image(64, 48)
    src = tmp_path / "in.png"
    Image.fromarray(img).save(src)
    out, ov = tmp_path / "o.png", tmp_path / "ov.png"

    def cli(*args):
        return subprocess.run([sys.executable, "-m", "msr_model", "select", str(src), *map(str, args)],
                              capture_output=True, text=True)

    r = cli("--out", out, "--overview", ov)
    assert r.returncode == 0, r.stderr
    lay = layout(64, 48)
    assert Image.open(ov).size == lay.size
    res = select(ImageRenderer(img), 64, 48, Params(tile=16, levels=2, thr=(8, 16), metric="max", fov_gain=0))
    src_panel = _crop(np.asarray(Image.open(ov).convert("RGB")), lay.boxes["source"])
    assert (src_panel[:: lay.up, :: lay.up] == source_rgb(res.source)).all()
    # the output-path checks cover --overview: bad suffix, the same file as another output or
    # the input, a folder; one line, exit status 2, nothing written
    out2 = tmp_path / "o2.png"
    for bad in (tmp_path / "ov.jpg", out2, src, tmp_path):
        r = cli("--out", out2, "--overview", bad)
        assert r.returncode == 2 and r.stderr.count("\n") == 1, (bad, r.stderr)
        assert not out2.exists()
