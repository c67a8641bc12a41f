"""The gaze point (docs/spec/contracts.md "Gaze", algorithm.md section 1): foveation around
(X, Y), the default gaze giving the frame-centre thresholds bit for bit."""
import json
import subprocess
import sys

import numpy as np
import pytest
from PIL import Image

from msr_model import ImageRenderer, Params, select, spec
from msr_model.budget import BudgetConfig, select_budget
from msr_model.golden import threshold_maps
from msr_model.tile_model import select_tiled


def centre_thresholds(thr, ntx, nty, gain):
    """algorithm.md's r2 from the frame centre, written out independently of spec.py."""
    ty, tx = np.mgrid[0:nty, 0:ntx]
    r2 = np.maximum(np.abs(2 * tx - (ntx - 1)), np.abs(2 * ty - (nty - 1)))
    return np.minimum(255, thr + ((gain * r2) >> 4))


def gaze_thresholds(thr, ntx, nty, gain, x, y, tile):
    cx, cy = (2 * x + tile // 2) // tile, (2 * y + tile // 2) // tile
    out = np.zeros((nty, ntx), dtype=np.int64)
    for ty in range(nty):
        for tx in range(ntx):
            r2 = max(abs(2 * tx + 1 - cx), abs(2 * ty + 1 - cy))
            out[ty, tx] = min(255, thr + ((gain * r2) >> 4))
    return out


@pytest.mark.parametrize("tile", spec.TILE_SIZES)
def test_default_gaze_is_the_centre_for_every_tile_count_parity(tile):
    """Odd and even tile counts on both axes, full and partial last tiles: the default gaze
    (ntx*T / 2, nty*T / 2) gives algorithm.md's thresholds, given or left out."""
    sizes = sorted({1, 2, 3, tile - 1, tile, tile + 1, 2 * tile, 2 * tile + 3, 3 * tile, 5 * tile - 1,
                    7 * tile + 1, 8 * tile, 4096 - 1, 4096} - {0})
    parities = set()
    for w in sizes:
        for h in sizes[::2] + [sizes[-1]]:
            ntx, nty = spec.tile_counts(w, h, tile)
            parities.add((ntx % 2, nty % 2))
            gx, gy = spec.default_gaze(w, h, tile)
            assert (gx, gy) == (ntx * tile // 2, nty * tile // 2)
            for gain in (0, 1, 37, 255):
                p = Params(tile=tile, levels=1, thr=(9,), fov_gain=gain)
                want = centre_thresholds(9, ntx, nty, gain)
                assert (threshold_maps(p, ntx, nty)[0] == want).all(), (w, h, gain)
                given = Params(tile=tile, levels=1, thr=(9,), fov_gain=gain, gaze=(gx, gy))
                assert spec.gaze_centre(given, ntx, nty) == (ntx, nty)
                assert (threshold_maps(given, ntx, nty)[0] == want).all(), (w, h, gain)
    assert parities == {(0, 0), (0, 1), (1, 0), (1, 1)}


def test_gaze_thresholds_follow_the_contract_formula():
    rng = np.random.default_rng(7)
    for _ in range(300):
        tile = int(rng.choice(spec.TILE_SIZES))
        w, h = int(rng.integers(1, 700)), int(rng.integers(1, 700))
        x, y = int(rng.integers(0, w)), int(rng.integers(0, h))
        gain, thr = int(rng.integers(0, 256)), int(rng.integers(0, 256))
        ntx, nty = spec.tile_counts(w, h, tile)
        p = Params(tile=tile, levels=1, thr=(thr,), fov_gain=gain, gaze=(x, y))
        assert (threshold_maps(p, ntx, nty)[0] == gaze_thresholds(thr, ntx, nty, gain, x, y, tile)).all()
        tx, ty = min(x // tile, ntx - 1), min(y // tile, nty - 1)
        # the tile holding the gaze is at most one half tile from it
        assert spec.tile_thresholds(p, tx, ty, ntx, nty)[0] <= min(255, thr + (gain >> 4))


def test_gaze_outside_the_frame_is_refused():
    img = np.zeros((20, 30, 3), np.uint8)
    for gaze in ((30, 0), (0, 20), (100, 100)):
        with pytest.raises(spec.SpecError, match="outside"):
            select(ImageRenderer(img), 30, 20, Params(tile=8, levels=2, gaze=gaze))
    with pytest.raises(spec.SpecError):
        Params(gaze=(-1, 0))
    select(ImageRenderer(img), 30, 20, Params(tile=8, levels=2, gaze=(29, 19)))


def test_gaze_moves_the_foveation_and_the_step_model_agrees():
    rng = np.random.default_rng(3)
    img = np.cumsum(rng.integers(-9, 10, (61, 83, 3)), axis=1).clip(0, 255).astype(np.uint8)
    base = Params(tile=8, levels=2, thr=(6, 14), fov_gain=120)
    centre = select(ImageRenderer(img), 83, 61, base)
    corner_p = Params(tile=8, levels=2, thr=(6, 14), fov_gain=120, gaze=(2, 3))
    corner = select(ImageRenderer(img), 83, 61, corner_p)
    assert corner.stats["gaze"] == [2, 3] and centre.stats["gaze"] == list(spec.default_gaze(83, 61, 8))
    assert not (corner.source == centre.source).all()
    frame, source = select_tiled(ImageRenderer(img), 83, 61, corner_p)
    assert (frame == corner.frame).all() and (source == corner.source).all()
    # with a budget of 0 the budget path is select() itself, gaze included
    off = select_budget(ImageRenderer(img), 83, 61, corner_p, BudgetConfig())
    assert (off.frame == corner.frame).all()


def cli(*args):
    return subprocess.run([sys.executable, "-m", "msr_model", *map(str, args)], capture_output=True, text=True)


def test_cli_gaze(tmp_path):
    rng = np.random.default_rng(5)
    img = np.cumsum(rng.integers(-5, 6, (37, 53, 3)), axis=1).clip(0, 255).astype(np.uint8)
    path = tmp_path / "in.png"
    Image.fromarray(img).save(path)
    out, stats = tmp_path / "o.png", tmp_path / "s.json"
    common = ("select", path, "--tile", 8, "--levels", 2, "--fov-gain", 60, "--out", out, "--stats", stats)
    for bad in ("53,0", "0,37", "-1,2", "3", "1,2,3", "a,b", ""):
        r = cli(*common, "--gaze", bad)
        assert r.returncode == 2, (bad, r.stderr)
        assert len(r.stderr.strip().splitlines()) == 1 and "gaze" in r.stderr
        assert not out.exists() and not stats.exists()
    r = cli(*common, "--gaze", "52,36")
    assert r.returncode == 0, r.stderr
    s = json.loads(stats.read_text())
    assert s["gaze"] == [52, 36]
    ref = select(ImageRenderer(img), 53, 37, Params(tile=8, levels=2, fov_gain=60, gaze=(52, 36)))
    assert (np.asarray(Image.open(out)) == ref.frame).all()
    r = cli(*common)
    assert r.returncode == 0, r.stderr
    assert json.loads(stats.read_text())["gaze"] == [28, 20]      # ntx*T/2 = 7*8/2, nty*T/2 = 5*8/2
