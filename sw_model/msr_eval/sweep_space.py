"""What the evaluation sweep runs: the families, their threshold scales and every setting
(`Setting`: a method of msr_eval.methods with its arguments, plain data so a task can travel to
another machine). msr_eval.sweep runs them."""
from __future__ import annotations

from dataclasses import dataclass, field

from msr_model import Params, spec

from . import gbuffer_rule as G
from . import methods as M

# Threshold scales s: the patent's families use thr = (s, 2s, 4s)[:L] (at least 1 each).
# Main families get the dense list, the others the sparse one (1080p costs ~0.6 s a setting).
FULL_SCALES = (0.25, 0.5, 1, 1.5, 2, 3, 4, 6, 8, 12, 16, 24, 32, 64)
SPARSE_SCALES = (0.5, 2, 8, 32)
QUICK_SCALES = (0.25, 1, 2, 4, 8, 16, 64)
MAIN_FAMILIES = ("multi_L3_T16", "multi_L3_T32", "multi_L3_T16_dilate", "multi_L3_T16_lindilate",
                 "multi_L3_T32_lindilate", "multi_L3_T16_lindilate2d", "multi_L3_T32_lindilate2d",
                 "multi_L2_T16", "multi_L2_T32", "multi_L2_T16_lindilate", "multi_L2_T32_lindilate",
                 "multi_L2_T16_lindilate2d", "multi_L2_T32_lindilate2d", "multi_L3_T32_r4",
                 "multi_L3_T32_lindilate_r4", "multi_L3_T32_lindilate2d_r4", "multi_L3_T32_r8",
                 "multi_L3_T32_lindilate_r8", "multi_L3_T32_lindilate2d_r8", "multi_L2_T32_lindilate2d_r4",
                 "multi_L4_T32", "multi_L4_T32_lindilate2d", *G.SWEEP_FAMILIES)
# SSIM and FLIP (FLIP ~6 s per 1080p frame) are computed for these families' key settings.
KEY_FAMILIES = ("grid2", "grid4", "checkerboard", "single_traced", "single_borrowed", "multi_L1_T16",
                "multi_L2_T16", "multi_L3_T16", "multi_L3_T32", "multi_L3_T16_fov", "multi_L3_T16_dilate",
                "multi_L3_T16_lindilate", "multi_L3_T32_lindilate", "multi_L3_T16_lindilate2d",
                "multi_L3_T32_lindilate2d", *G.SWEEP_FAMILIES,
                "dacs", "dacs_lumvar", "dacs_B8", "dacs_B8_lumvar", "vrs_T8", "vrs_T16")
# The families of the converged head-to-head (msr_eval.headline): at full size their SSIM and
# FLIP against the converged reference are computed at the equal-quality point.
CONV_FAMILIES = ("full", "checkerboard", "multi_L3_T16", "multi_L3_T32", "multi_L3_T16_dilate",
                 "multi_L3_T16_lindilate", "multi_L3_T32_lindilate", "multi_L3_T16_lindilate2d",
                 "multi_L3_T32_lindilate2d", "multi_L2_T16", "multi_L2_T32", "multi_L2_T16_lindilate",
                 "multi_L2_T32_lindilate", "multi_L2_T16_lindilate2d", "multi_L2_T32_lindilate2d",
                 "multi_L3_T32_r4", "multi_L3_T32_lindilate_r4", "multi_L3_T32_lindilate2d_r4",
                 "multi_L3_T32_r8", "multi_L3_T32_lindilate_r8", "multi_L3_T32_lindilate2d_r8",
                 "multi_L2_T32_lindilate2d_r4", "multi_L4_T32", "multi_L4_T32_lindilate2d", "dacs",
                 "dacs_lumvar", "dacs_B8", "dacs_B8_lumvar", "vrs_T8", "vrs_T16")
# FLIP in the full run only for these (the quick run: all key families)
FLIP_FAMILIES_FULL = ("grid2", "checkerboard", "single_borrowed", "multi_L3_T16", "multi_L3_T16_dilate",
                      "multi_L3_T16_lindilate", "dacs", "vrs_T8", "vrs_T16")
# The peers: DACS (msr_eval.dacs) over its variance threshold, the VRS-like baseline
# (msr_eval.vrs) over its contrast scale, per 8x8 and 16x16 tile.
# (a variance of 16256 = 127.5^2 is the largest 8-bit neighbours can have: everything interpolated)
# Below 1 in steps of 1/16, the variance's own step for four 8-bit neighbours (from 0 to 1 the
# traced fraction falls by some 40 points: neighbours 1 or 2 levels apart, the renderer's
# noise); above 1 half-octave steps (1, 1.5, 2, 3, 4, 6, ..). At 240x135 no two neighbouring
# settings of any scene are then more than 9.2 points apart, except where one value of the
# statistic holds many pixels (docs/dacs.md "Thresholds").
SIXTEENTHS = tuple(k / 16 for k in range(1, 16))
HALF_OCTAVES = tuple(x for k in range(13) for x in (2 ** k, 3 * 2 ** k // 2 if k else 1.5))
DACS_THR = (0, *SIXTEENTHS, *HALF_OCTAVES, 8192, 16384)
# The DACS variants of the full run: the paper's 4x4 blocks and our 8x8 extension
# (a first pass of one in 64), each with the largest per-channel variance and the luma variance.
DACS_VARIANTS = (("dacs", 4, "var"), ("dacs_lumvar", 4, "lumvar"), ("dacs_B8", 8, "var"),
                 ("dacs_B8_lumvar", 8, "lumvar"))
DACS_THR_QUICK = (0, 0.1875, 0.25, 0.5, 0.75, 1, 2, 4, 8, 32, 128, 512, 2048, 8192, 16384)
VRS_THR = (1, 2, 4, 8, 16, 32, 64, 128)
VRS_THR_QUICK = (2, 4, 8, 16, 32, 64)


def fov_gain_for(width, height, tile, edge_add=16):
    """fov_gain that raises the thresholds of the outermost tiles by about `edge_add`."""
    ntx, nty = spec.tile_counts(width, height, tile)
    r2max = max(ntx - 1, nty - 1, 1)
    return int(min(255, max(1, round(edge_add * 16 / r2max))))


def level_thr(levels, s, ratio: int = 2):
    """Per-level thresholds for a scale s: s, 2s, 4s (claim 2: rising with the level), >= 1;
    ratio 4: s, 4s, 16s (the finest level, whose midpoints are one pixel from their
    neighbours, interpolates much more: noise averaged where the bias is smallest)."""
    return tuple(min(255, max(1, int(s * ratio ** k))) for k in range(levels))


@dataclass(frozen=True)
class Setting:
    """One point of the sweep: a method of msr_eval.methods with its arguments (plain data,
    so a task can travel to another machine)."""

    family: str
    label: str
    method: str                                   # a function name in msr_eval.methods
    kwargs: dict = field(default_factory=dict)    # its arguments after (renderer, W, H)
    setting: dict = field(default_factory=dict)   # what the record shows of it

    def run(self, renderer, width: int, height: int) -> M.MethodResult:
        if ":" in self.method:                    # "package.module:function"
            import importlib
            mod, fn = self.method.split(":")
            return getattr(importlib.import_module(mod), fn)(renderer, width, height, **self.kwargs)
        return getattr(M, self.method)(renderer, width, height, **self.kwargs)


def settings(width, height, scales, quick) -> list[Setting]:
    """Every setting of the sweep, in the order of the records."""
    W, H = width, height
    sparse = scales if quick else SPARSE_SCALES
    out = [Setting("full", "full", "full_render"),
           Setting("grid2", "grid 2", "coarse_grid", {"step": 2}, {"step": 2}),
           Setting("grid4", "grid 4", "coarse_grid", {"step": 4}, {"step": 4}),
           Setting("checkerboard", "checkerboard", "checkerboard")]
    for s in sparse:
        t = min(255, max(1, int(2 * s)))   # one level of stride 4: between the patent's L=2 thresholds
        out.append(Setting("single_traced", f"t={t}", "single_level",
                           {"thr": t, "stride": 4, "border": "traced", "tile": 16},
                           {"thr": t, "stride": 4, "tile": 16}))
        out.append(Setting("single_borrowed", f"t={t}", "single_level",
                           {"thr": t, "stride": 4, "border": "borrowed"}, {"thr": t, "stride": 4}))
    multi = [("L1_T16", 16, 1, 0, "patent"), ("L2_T16", 16, 2, 0, "patent"),
             ("L3_T16", 16, 3, 0, "patent"), ("L3_T32", 32, 3, 0, "patent"),
             ("L3_T16_fov", 16, 3, 16, "patent"),
             ("L3_T16_dilate", 16, 3, 0, "dilate"), ("L3_T16_linear", 16, 3, 0, "linear"),
             ("L3_T16_lindilate", 16, 3, 0, "lindilate"), ("L3_T16_diag", 16, 3, 0, "diag"),
             ("L3_T32_lindilate", 32, 3, 0, "lindilate"),
             ("L3_T16_lindilate2d", 16, 3, 0, "lindilate2d"), ("L3_T32_lindilate2d", 32, 3, 0, "lindilate2d"),
             # L = 2 (stride 4, DACS's first-pass density): each rule's best per scene may be
             # either; an aliasing texture at the stride 8 of L = 3 needs it
             ("L2_T32", 32, 2, 0, "patent"), ("L2_T16_lindilate", 16, 2, 0, "lindilate"),
             ("L2_T32_lindilate", 32, 2, 0, "lindilate"), ("L2_T16_lindilate2d", 16, 2, 0, "lindilate2d"),
             ("L2_T32_lindilate2d", 32, 2, 0, "lindilate2d"),
             # thresholds s, 4s, 16s (level_thr ratio 4)
             ("L3_T32_r4", 32, 3, 0, "patent"), ("L3_T32_lindilate_r4", 32, 3, 0, "lindilate"),
             ("L3_T32_lindilate2d_r4", 32, 3, 0, "lindilate2d"),
             ("L3_T32_r8", 32, 3, 0, "patent"), ("L3_T32_lindilate_r8", 32, 3, 0, "lindilate"),
             ("L3_T32_lindilate2d_r8", 32, 3, 0, "lindilate2d"), ("L2_T32_lindilate2d_r4", 32, 2, 0, "lindilate2d"),
             # the L = 4 extension (stride 16, evaluation only: spec.EXT_LEVEL_RANGE): a sparser
             # floor than the T = 32, L = 3 grid's 2.44 % (docs/rules.md "L = 4")
             ("L4_T32", 32, 4, 0, "patent"), ("L4_T32_lindilate2d", 32, 4, 0, "lindilate2d")]
    for name, tile, levels, fov_edge, rule in multi:
        gain = fov_gain_for(W, H, tile, fov_edge) if fov_edge else 0
        fam = f"multi_{name}"
        ratio = int(name.rsplit("_r", 1)[1]) if "_r" in name else 2      # level_thr's ratio
        for s in (scales if fam in MAIN_FAMILIES else sparse):
            p = Params(tile=tile, levels=levels, thr=level_thr(levels, s, ratio), fov_gain=gain,
                       extension=levels > max(spec.LEVEL_RANGE))
            out.append(Setting(fam, f"thr={','.join(map(str, p.thr))}", "multi_level",
                               {"params": p, "rule": rule}, {**p.as_dict(), "rule": rule}))
    for fam, block, metric in DACS_VARIANTS:
        for t in (DACS_THR_QUICK if quick else DACS_THR):
            kw = {"thr": t, "metric": metric, "block": block}
            out.append(Setting(fam, f"{metric}<={t}", "msr_eval.dacs:dacs", kw, kw))
    for tile in (8, 16):       # every tier-2 rate, a centred sample per coarse pixel
        for t in (VRS_THR_QUICK if quick else VRS_THR):
            kw = {"thr": t, "tile": tile, "rates": "tier2", "anchor": "centre"}
            out.append(Setting(f"vrs_T{tile}", f"s={t}", "msr_eval.vrs:vrs_tier2", kw, kw))
    for fam, combine in G.SWEEP_FAMILIES.items():    # the G-buffer edge rule (msr_eval.gbuffer_rule)
        for s in (scales if fam in MAIN_FAMILIES else sparse):
            p = Params(tile=16, levels=3, thr=level_thr(3, s), fov_gain=0)
            kw = {"combine": combine, "id_kind": "material", "depth_tol": G.DEFAULT_DEPTH_TOL}
            out.append(Setting(fam, f"thr={','.join(map(str, p.thr))}", G.METHOD, {"params": p, **kw},
                               {**p.as_dict(), "rule": fam.split("_")[-1], **kw}))
    return out


def find_setting(sweep: list[Setting], rec: dict) -> Setting:
    for s in sweep:
        if s.family == rec["family"] and s.label == rec["label"]:
            return s
    raise KeyError(rec["family"], rec["label"])
