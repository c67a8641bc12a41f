"""Screenshot of the saved GTKWave layout of a `make sim WAVES=1` run, for docs/.

    python scripts/waves_shot.py OUT/waves.fst OUT/waves.gtkw docs/img/waves_tile.png

Starts a virtual X server (Xvfb, Debian package xvfb), opens GTKWave on the FST with the save
file written by scripts/gen_gtkw.py (zoomed on the recorded tile window, marker A at the tile's
start, B at its end), takes the screen with scrot, cuts out the GTKWave window and writes it
with a caption line that says what the markers are. Nothing is shown on the real display.
Exit status 2 when a tool is missing or the window never appears.
"""
from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw

from .waves import WINDOW_SIZE, Dump

SCREEN = (WINDOW_SIZE[0], WINDOW_SIZE[1])


def start_xvfb() -> tuple[subprocess.Popen, str]:
    """Xvfb on the first free display it finds (-displayfd), its process and DISPLAY."""
    r, w = os.pipe()
    proc = subprocess.Popen(["Xvfb", "-displayfd", str(w), "-screen", "0", f"{SCREEN[0]}x{SCREEN[1]}x24",
                             "-nolisten", "tcp"], pass_fds=(w,), stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    os.close(w)
    with os.fdopen(r) as f:
        num = f.readline().strip()
    if not num:
        proc.kill()
        raise RuntimeError("Xvfb did not start")
    return proc, f":{num}"


def grab(display: str, path: Path) -> np.ndarray:
    subprocess.run(["scrot", "-o", str(path)], env={**os.environ, "DISPLAY": display}, check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return np.asarray(Image.open(path).convert("RGB"))


MARKER_RGB = (255, 255, 128)      # GTKWave's named markers (A, B): dotted lines in this colour


def marker_columns(win: np.ndarray) -> list[int]:
    """x of the named-marker lines in the window (columns mostly of the marker colour)."""
    m = (win == MARKER_RGB).all(axis=2)
    h = win.shape[0]
    counts = m[h // 8: h - 20].sum(axis=0)
    return [int(x) for x in np.flatnonzero(counts > 0.4 * (h - 20 - h // 8))]


def ns(dump: Dump, t: int) -> str:
    scale = {"1ps": 1e-3, "1ns": 1.0}.get(dump.timescale.replace(" ", ""))
    return f"{t * scale:,.0f} ns".replace(",", " ") if scale else f"{t} ({dump.timescale})"


def annotate(win: Image.Image, dump: Dump) -> Image.Image:
    """The screenshot with a band under it: a bracket from marker A to marker B (the tile's
    life) and a line that says what they are."""
    from msr_model.palette import font
    f, band = font(18), 78
    out = Image.new("RGB", (win.width, win.height + band), (255, 255, 255))
    out.paste(win, (0, 0))
    d = ImageDraw.Draw(out)
    end = dump.done if dump.done is not None else dump.last
    cycles = ""
    if dump.timescale.replace(" ", "") in ("1ps", "1ns"):
        per_ns = 1000 if dump.timescale.replace(" ", "") == "1ps" else 1
        cycles = f", {round((end - dump.first) / per_ns / 10)} cycles of 10 ns"
    xs = marker_columns(np.asarray(win))
    y = win.height + 18
    if len(xs) >= 2:
        xa, xb = xs[0], xs[-1]
        col = (200, 40, 40)
        d.line((xa, win.height, xa, y + 8), fill=col, width=3)
        d.line((xb, win.height, xb, y + 8), fill=col, width=3)
        d.line((xa, y + 8, xb, y + 8), fill=col, width=3)
        eng = f" on engine {dump.engine}" if dump.engine is not None else ""
        d.text(((xa + xb) // 2, y), f"the life of one tile{eng}: {ns(dump, end - dump.first)}{cycles}",
               fill=col, font=f, anchor="ms")
    d.text((12, win.height + band - 18),
           f"A ({ns(dump, dump.first)}): the tile is handed to an engine.   B ({ns(dump, end)}): its last pixel "
           "is taken by the frame-buffer writer.   Made by scripts/waves_shot.py from make sim WAVES=1.",
           fill=(0, 0, 0), font=font(16), anchor="lm")
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("fst")
    ap.add_argument("gtkw")
    ap.add_argument("png")
    ap.add_argument("--wait", type=float, default=60.0, help="seconds to wait for the window")
    a = ap.parse_args(argv)
    for tool in ("Xvfb", "scrot", "gtkwave"):
        if shutil.which(tool) is None:
            print(f"waves_shot: error: {tool} not found (scripts/setup.sh installs it)", file=sys.stderr)
            return 2
    dump = Dump(Path(a.fst))
    xvfb, display = start_xvfb()
    gtk = None
    try:
        env = {**os.environ, "DISPLAY": display}
        gtk = subprocess.Popen(["gtkwave", "--rcvar", "splash_disable on", a.fst, a.gtkw], env=env,
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        with tempfile.TemporaryDirectory() as tmp:
            shot, last, deadline = None, None, time.monotonic() + a.wait
            # The window is drawn when two grabs a second apart agree and it is not blank.
            while time.monotonic() < deadline:
                time.sleep(1.0)
                if gtk.poll() is not None:
                    print("waves_shot: error: gtkwave exited", file=sys.stderr)
                    return 2
                img = grab(display, Path(tmp) / "s.png")
                busy = len(np.unique(img[::8, ::8].reshape(-1, 3), axis=0)) > 8
                if busy and last is not None and (img == last).all():
                    shot = img
                    break
                last = img
            if shot is None:
                print("waves_shot: error: the GTKWave window did not settle", file=sys.stderr)
                return 2
    finally:
        for p in (gtk, xvfb):
            if p is not None and p.poll() is None:
                p.terminate()
                try:
                    p.wait(5)
                except subprocess.TimeoutExpired:
                    p.kill()
    # The window sits at the top-left corner (no window manager): cut out its size.
    out = annotate(Image.fromarray(shot[: WINDOW_SIZE[1], : WINDOW_SIZE[0]]), dump)
    Path(a.png).parent.mkdir(parents=True, exist_ok=True)
    out.save(a.png, optimize=True)
    print(f"waves_shot: {a.png} ({out.width}x{out.height})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
