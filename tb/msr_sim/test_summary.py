"""`make sim` writes summary.png (msr_model.overview): checked on a real run of the harness,
against the run's own contract files (frame.png, reference.png, source_map.png); the terminal
summary names it and the output carries no progress bars (stderr is not a terminal here)."""
from __future__ import annotations


import numpy as np
import pytest
from PIL import Image

from msr_model.overview import layout, legend_swatches
from msr_model.palette import SOURCE_COLOURS, source_rgb

from msr_sim_run import build_harness, run_sim


@pytest.fixture(scope="module")
def harness():
    return build_harness("sim-build")


def test_make_sim_writes_summary(harness, tmp_path):
    W, H = 96, 56
    r = run_sim(harness, tmp_path, "--width", str(W), "--height", str(H), "--levels", "3")
    assert r.returncode == 0, r.stderr
    summary = tmp_path / "summary.png"
    assert f"summary picture           : {summary}" in r.stdout
    assert "\r" not in r.stderr and "%|" not in r.stderr, "a progress bar in a redirected log"

    png = np.asarray(Image.open(summary).convert("RGB"))
    lay = layout(W, H)
    assert png.shape[:2] == lay.size[::-1]
    u = lay.up
    crop = lambda name: png[lay.boxes[name][1]:lay.boxes[name][3], lay.boxes[name][0]:lay.boxes[name][2]]  # noqa: E731
    source = np.asarray(Image.open(tmp_path / "source_map.png"))
    assert source.ndim == 2 and source.max() <= 19            # the contract's map is unchanged: grey codes
    assert (crop("source")[::u, ::u] == source_rgb(source)).all()
    assert (crop("frame")[::u, ::u] == np.asarray(Image.open(tmp_path / "frame.png"))).all()
    assert (crop("reference")[::u, ::u] == np.asarray(Image.open(tmp_path / "reference.png"))).all()
    swatches = legend_swatches(lay, 3, source)
    for code in (0, 1, 2, 3, 17, 18, 19):                      # the legend of a 3-level run
        x0, y0, x1, y1 = swatches[code]
        assert (png[y0 + 2:y1 - 2, x0 + 2:x1 - 2] == SOURCE_COLOURS[code]).all()
