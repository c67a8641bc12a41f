"""The short soak of make test: scripts/soak.py for SOAK_MINUTES (default 1) with a random
seed (SEED to fix it) and a random initial state; it must check frames and pass. The seed of a
failing chunk is in the output and in build/soak/soak.jsonl."""
from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def test_short_soak():
    log = ROOT / "build" / "soak" / "soak.jsonl"
    before = len(log.read_text().splitlines()) if log.exists() else 0
    cmd = [sys.executable, str(ROOT / "scripts" / "soak.py"), "--minutes", os.environ.get("SOAK_MINUTES", "1")]
    p = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    lines = [ln for ln in p.stdout.splitlines() if ln.startswith("soak:")]
    assert p.returncode == 0, "\n".join(lines) + "\n" + p.stdout[-4000:] + p.stderr[-2000:]
    chunks = [json.loads(ln) for ln in log.read_text().splitlines()[before:]]
    assert chunks and all(c["result"] == "pass" and c["frames"] > 0 for c in chunks), chunks
    print("\n".join(lines))
