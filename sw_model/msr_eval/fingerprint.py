"""Behavioural fingerprints of the sweep's families: what a kept record's validity rests on.

A record (msr_eval.sweep.task_record) is a pure function of its setting, the reference
frames and the code that decides, reconstructs and scores. The sweep used to stand for that
code by hashing its source files, and a refactor that changed no output (golden.select's loop
split into a function of its own) then invalidated every committed 1080p record: hours of
computing again for nothing. Here each setting instead runs on a small probe frame, and what
comes out (the traced count, the frame, its scores) is hashed: a change that alters any
output on the probe changes the family's signature; a refactor does not.

The probe is built to reach every branch the sweep's methods have: a size that is not a
multiple of 8, 16 or 32 (partial tiles on both axes, border gaps of every length), smooth
gradients, a silhouette, a checkerboard, a high-frequency band, per-pixel noise as in a
path-traced render, and a G-buffer whose materials and depths change at the silhouette and
the floor. A change whose effect the probe cannot show must bump sweep.RECORD_VERSION by hand.
"""
from __future__ import annotations

import hashlib

import numpy as np

from msr_model.testimage import test_image

from . import gbuffer_rule as G
from . import reference as REF
from .metrics import flip, psnr, ssim

PROBE_W, PROBE_H = 172, 108          # 172 = 5*32 + 12, 108 = 3*32 + 12: partial tiles everywhere
PROBE_SEED = 0x5EED0FF


def probe():
    """(reference, converged, G-buffer) of the probe: the reference is the test picture with
    per-pixel noise (a 16-spp render's), the converged one the clean picture."""
    conv = test_image(PROBE_W, PROBE_H)
    rng = np.random.default_rng(PROBE_SEED)
    ref = np.clip(conv.astype(np.int16) + rng.integers(-10, 11, conv.shape), 0, 255).astype(np.uint8)
    y, x = np.mgrid[0:PROBE_H, 0:PROBE_W].astype(np.float64)
    u, v = x / (PROBE_W - 1), y / (PROBE_H - 1)
    # the same silhouette and floor as test_image
    disc = np.hypot(x - 0.35 * PROBE_W, y - 0.55 * PROBE_H) < 0.25 * min(PROBE_W, PROBE_H)
    floor = (u > 0.6) & (v > 0.55)
    mat = (1 + disc + 2 * floor).astype(np.uint32)
    prim = (mat * 1000 + (x // 9).astype(np.uint32)).astype(np.uint32)
    depth = (10.0 + 4.0 * v - 3.0 * disc + 0.5 * floor * u).astype(np.float32)
    return ref, conv, (prim, mat, depth)


def _floats(values) -> str:
    return repr([float(f"{float(v):.9g}") for v in values])


def scoring_fingerprint() -> bytes:
    """The scoring code's outputs on the probe: PSNR, SSIM, FLIP, the worst tile and the
    converged scores of the noisy reference and of a coarse copy of it."""
    ref, conv, _ = probe()
    coarse = np.repeat(np.repeat(ref[::4, ::4], 4, 0), 4, 1)[:PROBE_H, :PROBE_W]
    out = []
    for a, b in ((conv, ref), (ref, coarse), (conv, coarse)):
        out += [psnr(a, b), ssim(a, b), flip(a, b)]
        out += [v for _, v in sorted(REF.score(a, b, True).items())]
    return _floats(out).encode()


def family_fingerprints(sweep) -> dict:
    """Per family: a hash of every setting's label, traced count and frame on the probe."""
    ref, _, gbuf = probe()
    out: dict[str, hashlib._Hash] = {}
    for st in sweep:
        rr = G.rendering_unit(ref, gbuf if G.needs_gbuffer(st) else None)
        res = st.run(rr, PROBE_W, PROBE_H)
        h = out.setdefault(st.family, hashlib.sha1())
        h.update(f"{st.label}|{res.method}|{res.traced}|{rr.pixels_traced}|".encode())
        h.update(np.ascontiguousarray(res.frame, dtype=np.uint8).tobytes())
    return {f: h.digest() for f, h in out.items()}
