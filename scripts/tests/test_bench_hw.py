"""make bench (msr_flow.bench.hw): a tiny sweep (one engine, one small frame) through the real harness.

The one-engine harness is built by `make test` (TEST_DEPS in mk/bench.mk); a plain pytest run
without it fails with the make command to run.
"""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from msr_flow.bench import hw as bench_hw
from msr_flow.harness import GoldenFrames, MemoryLayout

ROOT = Path(__file__).resolve().parents[2]

HARNESS = bench_hw.harness_path(ROOT / "build" / "bench", 1, 16)


def _need_harness():
    if not HARNESS.is_file():
        pytest.fail(f"{HARNESS} is not built: run `make build/bench/hw_e1_mo16/Vmsr_sim_top` (make test does)")


def test_tiny_sweep_report(tmp_path):
    _need_harness()
    engine_json = tmp_path / "engine.json"
    engine_json.write_text(json.dumps({"setup": "x", "results": [
        {"latency": 0, "thr": [8, 16], "decisions_per_clock_in_pass": 0.97, "max_outstanding": 16},
        {"latency": 0, "thr": [0, 0], "decisions_per_clock_in_pass": 0.99, "max_outstanding": 16},
        {"latency": 64, "thr": [8, 16], "decisions_per_clock_in_pass": 0.5, "max_outstanding": 16}]}))
    rc = bench_hw.main(["--configs", "e1_mo16", "--width", "48", "--height", "32", "--latencies", "0,40",
                        "--tiles", "16", "--levels", "2", "--tl-engines", "1", "--tl-latencies", "0",
                        "--out", str(tmp_path), "--engine-json", str(engine_json), "--no-progress"])
    assert rc == 0
    r = json.loads((tmp_path / "report.json").read_text())
    assert (tmp_path / "pixels_per_clock.png").stat().st_size > 1000
    assert r["bit_exact"] is True and r["setup"]["rule"] == "patent"
    pts = r["engines_x_latency"]
    assert [(p["num_engines"], p["render_latency"]) for p in pts] == [(1, 0), (1, 40)]
    for p in pts + r["cycles_per_tile"]:
        assert p["bit_exact"] is True and p["mismatched_pixels"] == 0
        assert p["pixels"] == 48 * 32 and p["tiles"] == 3 * 2
        # Every pixel of the frame went through the writer exactly once.
        assert p["pixels_counted"] == p["pixels"]
        assert 0 < p["pixels_per_clock"] <= p["num_engines"]
        # The writer's 256-bit W channel: per 16-pixel tile row 2 pixel beats (64 bytes from
        # a 32-byte aligned start: stride 192) + 1 source-code beat (16 bytes from offset 0 or
        # 16: stride 48), 3 tiles a row, 32 rows = 288 beats; no frame can take fewer cycles.
        assert p["axi_w_beats"] == 3 * (2 + 1) * 32
        assert p["cycles"] >= p["axi_w_beats"]
        assert 0 < p["traced_fraction"] <= 1
        assert p["cycles_per_tile"] == pytest.approx(p["cycles"] / 6)
    # A longer render latency cannot make one engine with 16 tags faster.
    assert pts[1]["cycles"] > pts[0]["cycles"]
    # The tag bound is a true lower bound: traced * 40 / 16 cycles at latency 40.
    assert pts[1]["cycles"] >= pts[1]["traced"] * 40 / 16
    assert len(r["cycles_per_tile"]) == 1 and r["cycles_per_tile"][0]["tile"] == 16
    # The engine bench is merged: the worst in-pass decision rate at latency 0.
    g = r["goals"]["decisions_per_clock_per_engine_in_pass"]
    assert g["measured"] == pytest.approx(0.97) and g["met"] is True
    # No 4-engine point in this sweep: the pixel goal is not judged.
    assert r["goals"]["pixels_per_clock_4_engines_latency_256"]["measured"] is None


def test_traced_fraction_matches_golden_model(tmp_path):
    """The perf counters' traced count equals the golden model's traced pixels."""
    _need_harness()
    from msr_model import spec
    golden = GoldenFrames("cornell", 40, 24)
    pt = bench_hw.run_point(HARNESS, 1, 16, "cornell", 40, 24, 8, 1, 5, golden)
    g = golden.frame(bench_hw.params_for(8, 1))
    assert pt["bit_exact"] is True
    assert pt["traced"] == int((g.source < spec.SRC_INTERP_BASE).sum())


def test_w_beats_hand_counts():
    # 20 wide, T=8 (tiles 8, 8, 4 wide), 3 rows, 32-byte beats. Pixel rows start at
    # 0x1000 + 80y (+0, +32, +64): row 1 starts 16 bytes into a beat, so its two 8-pixel runs
    # take 2 beats each: 3 + 5 + 3 = 11. Codes at 0x2000 + 20y + x0: offsets 0/8/16, 20/28/36,
    # 40/48/56 (mod 32); only (y=1, x0=8) crosses a beat (28 + 8 bytes): 3 + 4 + 3 = 10.
    assert MemoryLayout(20, 3, 0x1000, 80, 0x2000, 20).w_beats(8, 32) == 21
    # 35 wide, T=32, one row: 128 pixel bytes (4 beats) + 12 (1); codes 32 bytes (1) + 4 (1).
    assert MemoryLayout(35, 1, 0x1000, 140, 0x2000, 36).w_beats(32, 32) == 7
    # Row 1 of the first case alone (pixels from 0x1050, codes from 0x2000) on a 64-byte bus:
    # pixel runs at offsets 16, 48, 16 (mod 64) of 32, 32, 16 bytes: 1 + 2 + 1 beats (5 on
    # the 32-byte bus); codes at 0, 8, 16 of 8, 8, 4 bytes: 1 + 1 + 1.
    assert MemoryLayout(20, 1, 0x1050, 80, 0x2000, 20).w_beats(8, 64) == 4 + 3
    assert MemoryLayout(20, 1, 0x1050, 80, 0x2000, 20).w_beats(8, 32) == 5 + 3


def test_stats_carry_the_build_and_the_layout(tmp_path):
    """The harness says what it is and where it wrote: the one-engine build, 16 tags, its
    memory layout, the frame's registers; the scripts take these instead of constants."""
    _need_harness()
    from msr_flow.harness import HarnessRun
    p = bench_hw.params_for(8, 2)
    rtl = HarnessRun(HARNESS, "cornell", 20, 12, p, latency=0, jitter=0, quiet=True).run()
    st = rtl.stats
    assert st["build"] == {"num_engines": 1, "max_outstanding": 16, "num_ctx": 7, "budget_en": 0,
                           "depth_en": 0, "rd_lat": 1, "tile_limit": 32, "buf_cycle": 1,
                           "axi_beat_bytes": 32}
    # frame buffer at 0x1000, stride 4 * 20; codes on the next 4 KiB page, stride 20
    assert st["layout"] == {"fb_base": 0x1000, "fb_stride": 80, "src_base": 0x2000, "src_stride": 20}
    assert st["params"] == {"width": 20, "height": 12, "tile": 8, "levels": 2, "thr": [8, 16, 0],
                            "metric": "max", "fov_gain": 0, "rule": 0}
    assert rtl.layout == MemoryLayout(20, 12, 0x1000, 80, 0x2000, 20)
    # The rule is written to CONFIG.RULE, and the stats say so.
    rtl = HarnessRun(HARNESS, "cornell", 20, 12, p, rule="lindilate", latency=0, jitter=0, quiet=True).run()
    assert rtl.stats["params"]["rule"] == 1


def test_bad_config_is_a_usage_error(capsys):
    assert bench_hw.main(["--configs", "four_engines"]) == bench_hw.EXIT_BAD_INPUT
    assert "e<engines>_mo<outstanding>" in capsys.readouterr().err


def test_configs_with_a_context_count():
    assert bench_hw.parse_cfg("e4_mo64") == (4, 64, None)
    assert bench_hw.parse_cfg("e4_mo64_c6") == (4, 64, 6)
    assert bench_hw.harness_path(Path("b"), 4, 64) == Path("b/hw_e4_mo64/Vmsr_sim_top")
    assert bench_hw.harness_path(Path("b"), 4, 64, 6) == Path("b/hw_e4_mo64_c6/Vmsr_sim_top")
    for bad in ("e4_mo64_c", "e4_mo64_cx", "e4_c6"):
        with pytest.raises(bench_hw.UsageError):
            bench_hw.parse_cfg(bad)


def test_bad_rule_is_a_usage_error(monkeypatch, capsys):
    assert bench_hw.main(["--rule", "magic"]) == bench_hw.EXIT_BAD_INPUT
    assert "magic" in capsys.readouterr().err
    monkeypatch.setenv("MSR_BENCH_RULE", "magic")
    assert bench_hw.main([]) == bench_hw.EXIT_BAD_INPUT
    assert "MSR_BENCH_RULE" in capsys.readouterr().err


def test_rule_from_the_environment(monkeypatch):
    assert bench_hw.parse([]).rule == "patent"
    monkeypatch.setenv("MSR_BENCH_RULE", "lindilate")
    assert bench_hw.parse([]).rule == "lindilate"
    assert bench_hw.parse(["--rule", "patent"]).rule == "patent"


def test_missing_harness_is_a_usage_error(tmp_path, capsys):
    rc = bench_hw.main(["--configs", "e3_mo16", "--build-dir", str(tmp_path), "--out", str(tmp_path)])
    assert rc == bench_hw.EXIT_BAD_INPUT
    assert "not built" in capsys.readouterr().err


def test_cli_runs_as_script():
    proc = subprocess.run([sys.executable, str(ROOT / "scripts" / "bench_hw.py"), "--latencies", "x"],
                          capture_output=True, text=True)
    assert proc.returncode == 2 and "--latencies" in proc.stderr
