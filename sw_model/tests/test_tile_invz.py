"""tile_model.run_tile's inverse-depth plane (render_invz) against reuse.select_with_reuse.

Over random frames, the per-tile planes assembled over the frame's tiles equal the
frame-level model's (reuse off): traced pixels carry the renderer's invz, interpolated ones
reuse.lerp_invz of their pass neighbours', sky (0) and saturated (65535) values included.
The colours and source codes agree too, and every interpolated pixel's invz is checked
against the formula written out here (docs: A, B the colour's neighbours; the planes are
write-once, so the final plane holds the neighbours' values), independently of lerp_invz."""
from __future__ import annotations

import random

import numpy as np
import pytest

from msr_model import reuse as RU
from msr_model import spec
from msr_model.spec import Params
from msr_model.tile_model import frame_tiles, run_tile

SIZES = [(37, 29), (64, 48), (50, 33)]


def image(rng: np.random.Generator, w: int, h: int) -> np.ndarray:
    """Smooth colour ramps with flat blocks, an edge and noisy patches: the rules both
    interpolate and trace."""
    yy, xx = np.mgrid[0:h, 0:w]
    img = np.stack([(xx * rng.integers(1, 6) + yy * rng.integers(0, 4)) % 256,
                    np.full((h, w), rng.integers(0, 256)), (yy * rng.integers(1, 5)) % 256], -1)
    img = img + rng.integers(0, 3, img.shape)
    for _ in range(3):
        y, x = rng.integers(0, h), rng.integers(0, w)
        img[y:y + rng.integers(2, 12), x:x + rng.integers(2, 12)] = rng.integers(0, 256, 3)
    y, x = rng.integers(0, h), rng.integers(0, w)
    img[y:y + 6, x:x + 6] = rng.integers(0, 256, (min(6, h - y), min(6, w - x), 3))
    return np.clip(img, 0, 255).astype(np.uint8)


def invz_plane(rng: np.random.Generator, w: int, h: int) -> np.ndarray:
    """A ramp with sky (0) patches, saturated (65535) patches and a noisy patch."""
    yy, xx = np.mgrid[0:h, 0:w]
    p = rng.integers(0, 30000) + xx * rng.integers(-300, 300) + yy * rng.integers(-300, 300)
    for val in (0, 0, 0, 65535, 65535, None):
        y, x = rng.integers(0, h), rng.integers(0, w)
        dy, dx = rng.integers(1, 14), rng.integers(1, 14)
        sub = p[y:y + dy, x:x + dx]
        sub[...] = rng.integers(0, 65536, sub.shape) if val is None else val
    return np.clip(p, 0, 65535).astype(np.uint16)


def lerp_ref(wa: int, wb: int, a: int, b: int, m: int) -> int:
    """The inverse-depth interpolation, one pixel, plain integers."""
    if (wa == 0) != (wb == 0):          # exactly one neighbour is sky: the surface's value
        return max(wa, wb)
    g = b - a
    return ((b - m) * wa + (m - a) * wb + g // 2) // g


def check_interpolated(r) -> tuple[int, int]:
    """Every interpolated decision of tile result r against lerp_ref: (pixels, of them with
    exactly one sky neighbour)."""
    n = n_sky = 0
    for d in r.decisions:
        if not d.interpolate:
            continue
        s = d.step
        wa, wb = int(r.invz[s.ay, s.ax]), int(r.invz[s.by, s.bx])
        a, b, m = (s.ax, s.bx, s.x) if s.direction == "H" else (s.ay, s.by, s.y)
        assert int(r.invz[s.y, s.x]) == lerp_ref(wa, wb, a, b, m), (r.x0, r.y0, s, wa, wb)
        n += 1
        n_sky += (wa == 0) != (wb == 0)
    return n, n_sky


def tiled(img, plane, W, H, params, rule):
    """The frame through run_tile tile by tile: (frame, source, invz, interpolated pixels
    checked against lerp_ref, of them next to the sky)."""
    frame = np.zeros((H, W, 3), np.uint8)
    source = np.zeros((H, W), np.uint8)
    invz = np.zeros((H, W), np.uint16)
    ntx, nty = spec.tile_counts(W, H, params.tile)
    n = n_sky = 0
    for tx, ty, x0, y0, w, h in frame_tiles(W, H, params.tile):
        r = run_tile(lambda x, y: img[y, x], x0, y0, w, h, params, spec.tile_thresholds(params, tx, ty, ntx, nty),
                     rule=rule, render_invz=lambda x, y: plane[y, x])
        frame[y0:y0 + h, x0:x0 + w] = r.pixels
        source[y0:y0 + h, x0:x0 + w] = r.codes
        invz[y0:y0 + h, x0:x0 + w] = r.invz
        dn, ds = check_interpolated(r)
        n, n_sky = n + dn, n_sky + ds
    return frame, source, invz, n, n_sky


@pytest.mark.parametrize("seed", range(10))
def test_tile_invz_matches_frame_model(seed):
    rnd = random.Random(seed)
    rng = np.random.default_rng(seed)
    n_interp = n_mixed = n_sky = 0
    for _ in range(4):
        W, H = rnd.choice(SIZES)
        L = rnd.randint(1, 3)
        metric = rnd.choice(["max", "sum"])
        params = Params(tile=rnd.choice([8, 16, 32]), levels=L, metric=metric,
                        thr=sorted(rnd.randrange(0, 64 if metric == "max" else 200) for _ in range(L)))
        rule = rnd.choice(["patent", "lindilate"])
        img, plane = image(rng, W, H), invz_plane(rng, W, H)
        want, _ = RU.select_with_reuse(RU.PlaneRenderer(img, plane), W, H, params, rule, reuse=False)
        frame, source, invz, n_ref, n_ref_sky = tiled(img, plane, W, H, params, rule)
        ctx = f"{W}x{H} {params} {rule}"
        assert (frame == want.frame).all() and (source == want.source).all(), ctx
        bad = np.argwhere(invz != want.invz)
        assert not bad.size, f"{ctx}: invz differs at {len(bad)} pixels, first (y, x) {tuple(bad[0])}: " \
                             f"{invz[tuple(bad[0])]} != {want.invz[tuple(bad[0])]}"
        interp = (source >= spec.SRC_INTERP_BASE) & (source < spec.SRC_REUSED_BASE)
        assert ((invz == plane) | interp).all(), "a traced pixel carries the renderer's invz"
        assert n_ref == int(interp.sum())
        n_interp += n_ref
        n_sky += n_ref_sky
        n_mixed += int((interp & (invz != plane)).sum())
    assert n_interp > 0 and n_mixed > 0 and n_sky > 0     # the lerp and its sky case were exercised


def test_no_render_invz_gives_none():
    img = np.zeros((8, 8, 3), np.uint8)
    r = run_tile(lambda x, y: img[y, x], 0, 0, 8, 8, Params(tile=8, levels=1, thr=(8,)), (8,))
    assert r.invz is None
