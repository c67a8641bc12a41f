"""scripts/run_sim.py (make sim) without a Verilator build: its exit status and last line for
bad input (2, "error"), a failing harness and a frame that is not bit exact (1, "failed"),
with stand-in harnesses; the real harness runs in tb/msr_sim."""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

FAKE = '''#!{python}
import json, sys
a = sys.argv[1:]
def opt(name):
    return a[a.index(name) + 1]
w, h = int(opt("--width")), int(opt("--height"))
assert opt("--thr").count(",") == 2, "thresholds are always passed, three of them"
rule = ("patent", "lindilate").index(opt("--rule"))   # always passed, a name the harness knows
if "{mode}" == "rule0":
    rule = 0                                          # a harness that ignores --rule
if "{mode}" == "crash":
    print("harness: error: STATUS.ERROR = 8", file=sys.stderr)
    sys.exit(1)
open(opt("--frame"), "wb").write(b"P6\\n%d %d\\n255\\n" % (w, h) + bytes(3 * w * h))
open(opt("--source"), "wb").write(b"P5\\n%d %d\\n255\\n" % (w, h) + bytes(w * h))
st = dict(cycles=w * h, sim_cycles_total=w * h, sim_seconds=0.1, sim_cycles_per_second=1e6, status=2, error=0,
          render_stall_cycles=0, memory_stall_cycles=0, traced_initial=w * h, traced_level1=0, traced_level2=0,
          traced_level3=0, interpolated_level1=0, interpolated_level2=0, interpolated_level3=0,
          build=dict(num_engines=3, max_outstanding=16, num_ctx=8, axi_beat_bytes=32),
          layout=dict(fb_base=4096, fb_stride=4 * w, src_base=8192, src_stride=w),
          params=dict(width=w, height=h, rule=rule))
open(opt("--stats"), "w").write(json.dumps(st))
'''


def fake_harness(tmp_path, mode):
    p = tmp_path / f"fake_{mode}"
    p.write_text(FAKE.format(python=sys.executable, mode=mode))
    p.chmod(0o755)
    return p


def run_sim(harness, *args):
    return subprocess.run([sys.executable, str(ROOT / "scripts" / "run_sim.py"), "--harness", str(harness), *args],
                          cwd=ROOT, capture_output=True, text=True)


def last_line(r):
    lines = (r.stdout + r.stderr).strip().splitlines()
    return r.stderr.strip().splitlines()[-1] if r.stderr.strip() else lines[-1]


@pytest.mark.parametrize("args, word", [
    (["--rule", "magic"], "not a decision rule"),
    (["--rule", "1"], "not a decision rule"),
    (["--levels", "2", "--thr", "8"], "THR"),
    (["--width", "0"], "WIDTH"),
    (["--tile", "x"], "TILE"),
    (["--metric", "mean"], "metric"),
])
def test_bad_input_is_exit_2_and_says_error(tmp_path, args, word):
    r = run_sim(fake_harness(tmp_path, "zeros"), "--width", "16", "--height", "16", "--out",
                str(tmp_path / "out"), *args)        # a flag given twice: the last one counts
    assert r.returncode == 2, r.stderr
    assert len(r.stderr.strip().splitlines()) == 1
    assert last_line(r).startswith("make sim: error:") and word in last_line(r), r.stderr
    assert not (tmp_path / "out").exists()


def test_missing_harness_is_bad_input(tmp_path):
    r = run_sim(tmp_path / "nothing", "--width", "16", "--height", "16")
    assert r.returncode == 2 and "not built" in last_line(r)


# The next two run the golden model on the renderer: make test builds it first (TEST_DEPS).
def test_failing_harness_is_exit_1_and_says_failed(tmp_path):
    r = run_sim(fake_harness(tmp_path, "crash"), "--width", "16", "--height", "16", "--out", str(tmp_path / "o"))
    assert r.returncode == 1, r.stderr
    assert last_line(r).startswith("make sim: failed: the RTL simulation failed"), r.stderr


def test_not_bit_exact_is_exit_1_and_says_failed(tmp_path):
    out = tmp_path / "o"
    r = run_sim(fake_harness(tmp_path, "zeros"), "--width", "24", "--height", "16", "--out", str(out))
    assert r.returncode == 1, r.stderr
    assert last_line(r).startswith("make sim: failed: not bit exact"), r.stderr
    rep = json.loads((out / "report.json").read_text())
    assert rep["bit_exact"] is False and rep["rule"] == "patent"
    assert rep["params"]["thr"] == [8, 16]
    # the engine count is the harness build's (its stats file), not a constant of the script
    assert rep["num_engines"] == 3


def test_rule_reaches_the_harness_and_the_report(tmp_path):
    """RULE=lindilate: the harness gets --rule lindilate (the fake refuses anything else but the
    two names), report.json says lindilate; compared with the lindilate golden frame (the fake's
    zeros are not bit exact, so exit 1)."""
    out = tmp_path / "o"
    r = run_sim(fake_harness(tmp_path, "zeros"), "--width", "24", "--height", "16", "--rule", "lindilate",
                "--out", str(out))
    assert r.returncode == 1 and last_line(r).startswith("make sim: failed: not bit exact"), r.stderr
    rep = json.loads((out / "report.json").read_text())
    assert rep["rule"] == "lindilate" and rep["bit_exact"] is False


def test_rule_not_written_is_a_failure(tmp_path):
    """A harness whose stats say it wrote another CONFIG.RULE than asked: exit 1, and no verdict."""
    out = tmp_path / "o"
    r = run_sim(fake_harness(tmp_path, "rule0"), "--width", "24", "--height", "16", "--rule", "lindilate",
                "--out", str(out))
    assert r.returncode == 1 and "CONFIG.RULE = 0" in last_line(r), r.stderr
    assert not (out / "report.json").exists()
