"""The converged-reference helpers (msr_eval.reference, msr_eval.conv_report) on hand cases."""
import math

import numpy as np
import pytest

from msr_eval import conv_report as CR
from msr_eval import reference as REF


def test_tile_psnrs_by_hand():
    ref = np.zeros((40, 64, 3), np.uint8)
    img = ref.copy()
    img[5, 40, 1] = 255                       # tile (row 0, col 1): one channel of one pixel
    img[35, 3, 0] = 255                       # the partial bottom row of tiles: 8 rows of 32
    p = REF.tile_psnrs(ref, img, 32)
    assert p.shape == (2, 2)
    assert p[0, 1] == pytest.approx(10 * math.log10(32 * 32 * 3))     # 255^2 / (255^2 / 3072)
    assert p[1, 0] == pytest.approx(10 * math.log10(8 * 32 * 3))
    assert p[0, 0] == math.inf and p[1, 1] == math.inf                  # identical tiles
    assert REF.tile_min_psnr(ref, img) == pytest.approx(10 * math.log10(768))


def test_psnr_at_front():
    pts = [(0.10, 30.0), (0.20, 36.0), (0.15, 29.0), (0.40, 44.0)]    # (0.15, 29) is dominated
    assert CR.psnr_at(pts, 0.05) is None                              # cheaper than every setting
    assert CR.psnr_at(pts, 0.10) == 30.0
    assert CR.psnr_at(pts, 0.15) == pytest.approx(33.0)               # on the front, not 29
    assert CR.psnr_at(pts, 0.30) == pytest.approx(40.0)
    assert CR.psnr_at(pts, 0.90) == 44.0                              # more than the family spends


def _rec(scene, fam, f, p, pc, label="x"):
    return {"scene": scene, "mode": "heavy", "family": fam, "label": label, "traced_fraction": f,
            "psnr": p, "psnr_conv": pc, "tile32_min_psnr_conv": pc - 5}


def test_conv_views_and_head_to_head():
    recs = [_rec("a", "multi_L3_T16", 0.1, 41, 33, "t1"), _rec("a", "multi_L3_T16", 0.3, 45, 41, "t2"),
            _rec("a", "dacs", 0.2, 44, 40, "d1"), _rec("a", "dacs", 0.05, 30, 28, "d2"),
            _rec("a", "vrs_T8", 0.5, 39, 36, "v1"), _rec("a", "full", 1.0, None, 37, "full")]
    conv = REF.as_conv(recs)
    assert [r["psnr"] for r in conv] == [33, 41, 40, 28, 36, 37]
    assert REF.pick_near_conv(recs, "a", "heavy", "multi_L3_T16", 40)["label"] == "t2"
    assert REF.pick_near_conv(recs, "a", "heavy", "vrs_T8", 40)["label"] == "v1"      # best if none reaches
    need = CR.needed_conv(recs)
    # patent: 33 @ 0.1 -> 41 @ 0.3: 40 dB at 0.1 + 7/8 * 0.2 = 0.275; DACS reaches 40 at its 0.2 setting
    assert need["a"]["heavy"]["multi_L3_T16"]["40"]["fraction"] == pytest.approx(0.275)
    h = CR.head_to_head(need, ["a"], "heavy", "40")[0]
    assert h["patent"][0] == "multi_L3_T16" and h["patent"][1] == pytest.approx(0.275)
    assert h["dacs"][1] == pytest.approx(0.2) and h["vrs"] is None and h["ours"] is None
    # the full render alone does not reach 40 dB against the converged reference
    assert need["a"]["heavy"]["full"]["40"]["fraction"] is None


def test_conv_grids():
    assert REF.conv_grids_for("heavy") == REF.CONV_GRIDS["heavy"]
    assert REF.conv_grids_for("heavy", 8) == (8,)
    assert min(g * g for g in REF.CONV_GRIDS["heavy"]) >= 256
    assert REF.conv_key("heavy", None, True) != REF.conv_key("heavy", None, False)
    frame, info = REF.task_converged("image", "testimage", "image", 40, 30, (16,), True)
    assert frame.shape == (30, 40, 3) and info["spp"] == 1
