"""Child processes of the flows with a time limit that ends everything they started.

subprocess.run(timeout=...) kills only its direct child: a tool's own children (sby's provers
and solvers, yosys-abc, a simulator under make) keep running. So every job starts in a session
of its own (its own process group) and a timeout, an exception or Ctrl-C in the flow ends the
whole group: SIGTERM first (tools clean up their work folders), SIGKILL after `grace` seconds."""
from __future__ import annotations

import os
import signal
import subprocess
import time
from dataclasses import dataclass
from pathlib import Path

GRACE_S = 5.0


@dataclass
class Finished:
    """What a job left: its exit status (None when the time limit ended it) and its output."""
    returncode: int | None
    stdout: str
    stderr: str
    timed_out: bool = False

    @property
    def output(self) -> str:
        return self.stdout + self.stderr


def _group_alive(pgid: int) -> bool:
    try:
        os.killpg(pgid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:       # a member changed its user: still there
        return True
    return True


def end_group(proc: subprocess.Popen, grace: float = GRACE_S) -> None:
    """SIGTERM to the job's process group, SIGKILL to what is left after `grace` seconds."""
    for sig in (signal.SIGTERM, signal.SIGKILL):
        try:
            os.killpg(proc.pid, sig)
        except ProcessLookupError:
            break
        deadline = time.monotonic() + grace
        while time.monotonic() < deadline:
            proc.poll()           # reap the leader, so a dead group reads as gone
            if not _group_alive(proc.pid):
                break
            time.sleep(0.05)
        else:
            continue
        break
    proc.poll()


def run(cmd: list[str], *, cwd: Path | str | None = None, timeout: float | None = None,
        env: dict | None = None, grace: float = GRACE_S, capture: bool = True) -> Finished:
    """Run `cmd` in its own session, its output captured as text (or passed through to ours
    when not `capture`); on timeout end its whole group."""
    pipe = subprocess.PIPE if capture else None
    proc = subprocess.Popen(cmd, cwd=cwd, env=env, stdout=pipe, stderr=pipe,
                            text=True, errors="replace", start_new_session=True)
    try:
        out, err = proc.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        end_group(proc, grace)
        try:
            out, err = proc.communicate(timeout=grace)
        except subprocess.TimeoutExpired:   # a member left the group and holds the pipes
            proc.kill()
            out, err = "", ""
        return Finished(None, out or "", err or "", timed_out=True)
    except BaseException:
        end_group(proc, grace)
        raise
    # the leader is done; helpers it left behind in its group must not outlive the job
    if _group_alive(proc.pid):
        end_group(proc, grace)
    return Finished(proc.returncode, out or "", err or "")
