"""make bench-bits (msr_flow.bench.bits): the bits and area model, the choice, and the shape of
the committed record data/bench/tile_bits.json. No simulation."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from msr_flow.bench import bits
from msr_model.clitools import UsageError

ROOT = Path(__file__).resolve().parents[2]
RECORD = ROOT / "data" / "bench" / "tile_bits.json"


def test_default_top_matches_make_asic():
    """The default top (NUM_CTX 7, LINDILATE 1) costs what make asic reported (docs/asic.json)."""
    ref = bits.reference()
    c = bits.cost(*bits.DEFAULT_POINT)
    assert ref is not None
    assert c["bits"] == ref["bits"]
    assert c["macros_1r1w"] == ref["macros_1r1w"]
    assert c["macro_area_mm2"] == pytest.approx(ref["macro_area_mm2"], abs=0.01)


def test_tile_limit_quarters_the_words():
    """TILE_LIMIT 16: 256-word buffers, a quarter of the bits; the macros shrink less (periphery)."""
    full, small = bits.cost(7, 1), bits.cost(7, 1, tile_limit=16)
    assert small["bits"] * 4 == full["bits"] and small["macros_1r1w"] == full["macros_1r1w"]
    assert full["macro_area_mm2"] / 4 < small["macro_area_mm2"] < full["macro_area_mm2"] * 0.7


def test_bits_scale():
    word = bits.pkg_constant("SRC_W") + bits.RGB_BITS
    depth = bits.pkg_constant("MAX_TILE") ** 2
    assert bits.cost(3, 0)["bits"] == 4 * 3 * depth * word
    assert bits.cost(3, 1)["bits"] == 4 * 3 * depth * (word + bits.RGB_BITS)
    assert bits.cost(3, 1)["stored_bits"] == 4 * 3 * depth * (2 * word + bits.RGB_BITS)
    assert bits.cost(4, 1)["macro_area_mm2"] < bits.cost(5, 1)["macro_area_mm2"] < bits.cost(7, 1)["macro_area_mm2"]


def test_points_and_names(tmp_path):
    assert bits.parse_points("7:1 4:0 6:1:4 7:1:4:16 10:1:4:16:5") == [
        (7, 1, 1, 32, 1), (4, 0, 1, 32, 1), (6, 1, 4, 32, 1), (7, 1, 4, 16, 1), (10, 1, 4, 16, 5)]
    for bad in ("7", "4:2", "1:1", "x:1", "", "6:1:5", "6:1:0", "6:1:x", "6:1:4:64", "6:1:4:4", "6:1::16x",
                "6:1:4:16:9", "6:1:4:16:0", "6:1:4:16:5:1"):
        with pytest.raises(UsageError):
            bits.parse_points(bad)
    assert bits.config_name(5, 1) == "e4_mo64_c5"
    assert bits.config_name(5, 0) == "e4_mo64_c5_l0"
    assert bits.harness_of(tmp_path, 5, 0) == tmp_path / "hw_e4_mo64_c5_l0" / "Vmsr_sim_top"
    assert bits.harness_of(tmp_path, 5, 1) == tmp_path / "hw_e4_mo64_c5" / "Vmsr_sim_top"
    # RD_LAT before LINDILATE's suffix: mk/bench.mk's rules read both
    assert bits.config_name(6, 0, 4) == "e4_mo64_c6_rl4_l0"
    assert bits.harness_of(tmp_path, 6, 1, 2) == tmp_path / "hw_e4_mo64_c6_rl2" / "Vmsr_sim_top"
    # TILE_LIMIT after RD_LAT, before LINDILATE's suffix (mk/bench.mk's bench_gflags)
    assert bits.config_name(7, 1, 4, 16) == "e4_mo64_c7_rl4_t16"
    assert bits.config_name(7, 0, 1, 16) == "e4_mo64_c7_t16_l0"
    assert bits.config_name(10, 1, 4, 16, 5) == "e4_mo64_c10_rl4_t16_cy5"
    assert bits.rules_for(0, ["patent", "lindilate"]) == ["patent"]


def _dp(ctx, lin, ppc256, rd_lat=1, tile_limit=32, cycle=1):
    pts = [{"rule": r, "render_latency": 256, "pixels_per_clock": v} for r, v in ppc256.items()]
    return {"num_ctx": ctx, "lindilate": lin, "rd_lat": rd_lat, "tile_limit": tile_limit, "buf_cycle": cycle,
            "config": bits.config_name(ctx, lin, rd_lat, tile_limit, cycle),
            **bits.cost(ctx, lin, tile_limit=tile_limit), "points": pts}


def test_choice_fewest_bits_meeting_goal_in_every_rule():
    dps = [_dp(7, 1, {"patent": 3.71, "lindilate": 3.70}), _dp(4, 1, {"patent": 3.65, "lindilate": 3.61}),
           _dp(3, 1, {"patent": 3.62, "lindilate": 3.50}), _dp(3, 0, {"patent": 3.62})]
    default = bits.cost(*bits.DEFAULT_POINT)["macro_area_mm2"]
    c = bits.choose(dps, ["patent", "lindilate"], default)
    assert (c["num_ctx"], c["lindilate"]) == (4, 1)
    assert c["area_reduction"] == pytest.approx(1 - bits.cost(4, 1)["macro_area_mm2"] / default, abs=1e-4)
    assert (bits.choose(dps, ["patent"], default)["num_ctx"], bits.choose(dps, ["patent"], default)["lindilate"]) == (3, 0)
    assert bits.choose(dps[2:3], ["lindilate"], default) is None
    # a longer read latency is a choice of its own: its points only
    slow = dps + [_dp(3, 1, {"patent": 3.61, "lindilate": 3.60}, rd_lat=4), _dp(5, 1, {"patent": 3.7, "lindilate": 3.7}, 4)]
    assert bits.choose(slow, ["patent", "lindilate"], default)["num_ctx"] == 4
    c4 = bits.choose(slow, ["patent", "lindilate"], default, rd_lat=4)
    assert (c4["num_ctx"], c4["rd_lat"]) == (3, 4)
    # and so is a smaller tile limit
    small = slow + [_dp(7, 1, {"patent": 3.69, "lindilate": 3.69}, 4, 16)]
    assert bits.choose(small, ["patent", "lindilate"], default, rd_lat=4)["tile_limit"] == 32
    c16 = bits.choose(small, ["patent", "lindilate"], default, rd_lat=4, tile_limit=16)
    assert (c16["num_ctx"], c16["tile_limit"], c16["target_met"]) == (7, 16, True)
    # and a macro's cycle
    cyc = small + [_dp(10, 1, {"patent": 3.65, "lindilate": 3.62}, 4, 16, 5), _dp(8, 1, {"patent": 3.4, "lindilate": 3.4}, 4, 16, 5)]
    c5 = bits.choose(cyc, ["patent", "lindilate"], default, 4, 16, 5)
    assert (c5["num_ctx"], c5["buf_cycle"]) == (10, 5)
    assert bits.choose(cyc, ["patent", "lindilate"], default, 4, 16)["num_ctx"] == 7


def test_committed_record_shape():
    assert RECORD.is_file(), f"{RECORD.relative_to(ROOT)} missing (make bench-bits, then copy it)"
    r = json.loads(RECORD.read_text())
    for k in ("setup", "bits_model", "design_points", "bit_exact", "choice", "choice_patent_only"):
        assert k in r
    assert r["bits_model"]["matches_reference"] is True
    lats = r["setup"]["latencies"]
    assert 256 in lats
    for d in r["design_points"]:
        c = bits.cost(d["num_ctx"], d["lindilate"], tile_limit=d.get("tile_limit", 32))
        assert (d["bits"], d["macro_area_mm2"]) == (c["bits"], c["macro_area_mm2"])
        rules = {p["rule"] for p in d["points"]}
        assert rules <= {"patent", "lindilate"} and (d["lindilate"] or rules == {"patent"})
        for p in d["points"]:
            assert p["render_latency"] in lats and 0 < p["pixels_per_clock"] < 8
            assert p["bit_exact"] is True
    ch = r["choice"]
    if ch is not None:
        best = next(d for d in r["design_points"]
                    if (d["num_ctx"], d["lindilate"], *bits.build_of(d))
                    == (ch["num_ctx"], ch["lindilate"], *bits.build_of(ch)))
        assert all(bits.ppc(best, rule, 256) >= 3.6 for rule in ch["rules"])
