"""Image-quality metrics of 8-bit RGB frames, the one place each is computed: PSNR, SSIM, FLIP
and the temporal flicker of an error sequence.

PSNR of identical frames is `math.inf` (a float, everywhere): JSON carries it as `Infinity`,
text shows it as "identical" (`format_db`). Code that averages PSNRs or interpolates along a
curve of them takes `capped` values (an identical frame counts as PSNR_CAP dB there).
"""
from __future__ import annotations

import math

import numpy as np

PEAK = 255.0
PSNR_CAP = 100.0            # what an identical frame counts as in means and interpolation
SSIM_WIN = 7                # skimage's default window: SSIM is not defined on a frame smaller than it


def psnr_of_mse(mse):
    """PSNR in dB of a mean squared error on 0..255 values (a number or an array); inf where
    the error is zero."""
    m = np.asarray(mse, dtype=np.float64)
    with np.errstate(divide="ignore"):
        p = np.where(m > 0, 10 * np.log10(PEAK ** 2 / np.where(m > 0, m, 1)), np.inf)
    return float(p) if p.ndim == 0 else p


def mse(ref, img) -> float:
    d = ref.astype(np.float64) - img.astype(np.float64)
    return float(np.mean(d * d))


def psnr(ref, img) -> float:
    """PSNR in dB of img against ref; math.inf for identical frames."""
    return psnr_of_mse(mse(ref, img))


def capped(p) -> float:
    """A PSNR for means, sorting and interpolation: at most PSNR_CAP (identical frames count as
    PSNR_CAP). None is taken as identical too: records written before inf was the answer carry
    null there."""
    return PSNR_CAP if p is None else min(float(p), PSNR_CAP)


def format_db(p) -> str:
    """A PSNR for text: "identical" for identical frames, else two decimals and the unit."""
    return "identical" if p is None or not math.isfinite(p) else f"{p:.2f} dB"


def ssim(ref, img) -> float | None:
    """SSIM of img against ref (skimage, 7x7 window); None for a frame narrower or lower than
    the window, where SSIM is not defined (reports carry null, not a made-up value)."""
    from skimage.metrics import structural_similarity
    if min(ref.shape[:2]) < SSIM_WIN:
        return None
    return float(structural_similarity(ref, img, channel_axis=2, data_range=255))


def flip(ref, img, want_map=False):
    """Mean LDR FLIP of img against ref (and the error map with `want_map`)."""
    import flip_evaluator
    emap, mean, _ = flip_evaluator.evaluate(ref.astype(np.float32) / 255, img.astype(np.float32) / 255,
                                            "LDR", applyMagma=False)
    return (float(mean), np.asarray(emap)[..., 0]) if want_map else float(mean)


def flicker(err_prev, err) -> float:
    """Temporal flicker: RMS of the change of the error image between two frames."""
    d = err.astype(np.float64) - err_prev.astype(np.float64)
    return float(np.sqrt(np.mean(d * d)))
