"""A flow's time limit ends everything it started: a job that leaves a sleeping grandchild (as
sby leaves its provers and solvers) times out, and the grandchild is gone with it."""
from __future__ import annotations

import os
import stat
import sys
import time
from pathlib import Path

from msr_flow import formal, proc

# Starts a grandchild that sleeps, prints its pid, then sleeps itself: only a kill of the whole
# process group ends both.
JOB = """
import subprocess, sys, time
g = subprocess.Popen(["sleep", "300"])
print("GRANDCHILD", g.pid, flush=True)
time.sleep(300)
"""


def alive(pid: int) -> bool:
    """Running, not merely a zombie waiting for its reaper."""
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except (FileNotFoundError, ProcessLookupError):
        return False
    return state != "Z"


def grandchild_of(output: str) -> int:
    line = next(ln for ln in output.splitlines() if ln.startswith("GRANDCHILD"))
    return int(line.split()[1])


def gone_soon(pid: int, within: float = 5.0) -> bool:
    deadline = time.monotonic() + within
    while time.monotonic() < deadline:
        if not alive(pid):
            return True
        time.sleep(0.05)
    return False


def test_timeout_ends_the_grandchild():
    t0 = time.monotonic()
    done = proc.run([sys.executable, "-c", JOB], timeout=2, grace=1)
    assert done.timed_out and done.returncode is None
    assert time.monotonic() - t0 < 10
    pid = grandchild_of(done.stdout)
    assert gone_soon(pid), f"grandchild {pid} outlived the time limit"


def test_a_job_in_time_is_untouched():
    done = proc.run([sys.executable, "-c", "print('ok')"], timeout=30)
    assert (done.returncode, done.stdout.strip(), done.timed_out) == (0, "ok", False)


def test_formal_timeout_ends_the_provers(tmp_path, monkeypatch):
    """msr_flow.formal (make formal) on a stand-in for sby that starts a 'prover' and hangs."""
    fake = tmp_path / "fake-sby"
    fake.write_text(f"#!{sys.executable}\n{JOB}")
    fake.chmod(fake.stat().st_mode | stat.S_IXUSR)
    monkeypatch.setattr(formal, "BUILD", tmp_path / "formal")
    monkeypatch.setattr(formal, "tool", lambda name: str(fake))
    (tmp_path / "formal").mkdir()
    sby = next((formal.ROOT / "formal").glob("*/*.sby"))
    job = formal.Job(sby, sby.read_text(), formal.sby_tasks(sby.read_text())[0])
    row = formal.run_task(job, None, timeout=2)
    assert row["status"] == "TIMEOUT" and row["result"] == "FAIL"
    pid = grandchild_of((tmp_path / "formal" / f"{job.name}.log").read_text())
    assert gone_soon(pid), f"prover stand-in {pid} outlived the formal time limit"
    assert os.path.exists(tmp_path / "formal" / f"{job.name}.log")
