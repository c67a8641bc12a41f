"""GTKWave save file for a `make sim WAVES=1` FST: the signals of a tile's life, grouped by unit.

    python scripts/gen_gtkw.py OUT/waves.fst OUT/waves.gtkw

Reads the FST's signal list (fst2vcd header) so every name matches the dump exactly, then
writes groups: clock/control, tile generation, render port, each engine, frame-buffer writer,
AXI write channels. docs/waves.md explains how to read them.

The view opens on the recorded window: zoomed so the window fills the wave pane, marker A at
the tile's start (the first dumped time: the cycle its descriptor is handed out) and marker B
at its end (the simulation top's `dbg_watch_done_o` rising: its last pixel taken by the
writer); a cycle window (`--wave-cycles`) gets A and B at its first and last time.
"""
from __future__ import annotations

import argparse
import math
import re
import subprocess
import sys
from pathlib import Path

# Names of the system top and the engine as they are now; a name missing from the dump is
# skipped, so the file still loads when a unit renames a signal.
ENGINE_SIGS = ["desc_valid_i", "desc_ready_o", "u_ctx_alloc.alloc_q", "busy_o", "ctx_start", "ctx_free", "ctx_full",
               "issue", "u_ctx_issue.gnt", "gr_gnt", "u_req_out.out_trace_i", "retro_phase",
               "req_valid_o", "req_ready_i", "req_x_o", "req_y_o", "req_tag_o", "rsp_valid_i", "rsp_tag_i",
               "inflight_o", "ctx_str_done", "ctx_str_own", "pix_valid_o",
               "pix_ready_i", "pix_x_o", "pix_y_o", "pix_src_o", "pix_last_o"]
GROUPS = [
    ("Clock and control", "u_top", ["clk_i", "rst_ni", "irq_o"]),
    ("Clock and control", "u_top.u_ctrl", ["state_q", "tif_q", "busy_o", "run_o", "drain_o", "done_set_o"]),
    ("Tile generation", "u_top.u_tile_gen", ["tx_q", "ty_q", "desc_valid_o", "desc_ready_i"]),
    ("Render port", "u_top", ["rnd_req_valid_o", "rnd_req_ready_i", "rnd_req_x_o", "rnd_req_y_o", "rnd_req_tag_o",
                              "rnd_rsp_valid_i", "rnd_rsp_ready_o", "rnd_rsp_tag_i", "rnd_rsp_rgb_i"]),
    ("Frame-buffer writer", "u_top.u_fb_writer", ["pix_valid_i", "pix_ready_o", "pix_last_i", "full_q",
                                                  "outst_q", "idle_o"]),
    ("AXI write", "u_top", ["m_axi_awvalid", "m_axi_awready", "m_axi_awaddr", "m_axi_awlen", "m_axi_wvalid",
                            "m_axi_wready", "m_axi_wdata", "m_axi_wstrb", "m_axi_wlast", "m_axi_bvalid",
                            "m_axi_bresp"]),
]


# The window and the view of the save file.
WINDOW_SIZE = (1600, 1000)        # GTKWave main window (pixels)
SST_WIDTH = 260                   # the (collapsed) signal search tree column
SIGNALS_WIDTH = 330               # signal-name pane
WAVE_PANE = WINDOW_SIZE[0] - SST_WIDTH - SIGNALS_WIDTH - 30   # what is left for the waves (measured: ~990)
PIXELS_PER_FRAME = 200           # GTKWave (calczoom): 2^-zoom time units per 200 pixels
DONE_SIGNAL = "dbg_watch_done_o"  # msr_sim_top: the watched tile's last pixel was taken
ENGINE_DONE = "dbg_tile_done"     # msr_sim_top: engine i's tile ends (one bit per engine)


class Dump:
    """What gen_gtkw needs from an FST: signal names, the time span, the tile's end."""

    def __init__(self, fst: Path):
        self.names: list[str] = []
        self.first = self.last = self.done = None
        self.engine = None            # the engine that worked on the watched tile, when known
        self.timescale = ""
        self._read(fst)

    def _read(self, fst: Path):
        proc = subprocess.Popen(["fst2vcd", "-f", str(fst)], stdout=subprocess.PIPE, text=True)
        scope, done_ids, eng_ids, in_ts, now, eng_val = [], set(), set(), False, None, ""
        for line in proc.stdout:
            t = line.split()
            if not t:
                continue
            if now is None:                                  # header
                if in_ts:
                    self.timescale += " ".join(x for x in t if x != "$end")
                    in_ts = "$end" not in t
                elif t[0] == "$timescale":
                    self.timescale = " ".join(x for x in t[1:] if x != "$end")
                    in_ts = "$end" not in t
                elif t[0] == "$scope":
                    scope.append(t[2])
                elif t[0] == "$upscope":
                    scope.pop()
                elif t[0] == "$var":
                    name = t[4] + (t[5] if len(t) > 6 and t[5].startswith("[") else "")
                    self.names.append(".".join(scope + [name]))
                    if t[4] == DONE_SIGNAL and len(scope) <= 2:
                        done_ids.add(t[3])
                    if t[4] == ENGINE_DONE and len(scope) == 2:
                        eng_ids.add(t[3])
                elif t[0] == "$enddefinitions":
                    now = -1
                continue
            if t[0].startswith("#"):
                now = int(t[0][1:])
                if self.first is None:
                    self.first = now
                self.last = now
            elif self.done is None and len(t) == 2 and t[1] in eng_ids:
                eng_val = t[0][1:]
            elif self.done is None and len(t) == 1 and t[0][:1] == "1" and t[0][1:] in done_ids:
                self.done = now
                bits = [i for i, b in enumerate(reversed(eng_val)) if b == "1"]
                self.engine = bits[0] if len(bits) == 1 else None
        proc.wait()


def signal_names(fst: Path) -> list[str]:
    """Full dotted names (with [msb:lsb] for vectors) of every signal in the FST."""
    return Dump(fst).names


def view_lines(dump: Dump) -> list[str]:
    """[timestart], zoom and markers: the recorded window fills the wave pane, A = start, B = end."""
    if dump.first is None:
        return []
    start = dump.first
    end = dump.done if dump.done is not None and dump.done > start else dump.last
    span = max(1, dump.last - start)
    margin = span // 50
    zoom = -math.log2(PIXELS_PER_FRAME * (span + 2 * margin) / WAVE_PANE)
    markers = [start, end] + [-1] * 24
    return [f"[timestart] {max(0, start - margin)}", f"[size] {WINDOW_SIZE[0]} {WINDOW_SIZE[1]}", "[pos] 0 0",
            f"*{zoom:.6f} -1 " + " ".join(map(str, markers))]


def write_view(fst: str, out: str) -> int:
    """The save file `out` for the dump `fst`; 2 when the dump has no simulation top."""
    dump = Dump(Path(fst))
    names = dump.names
    by_base = {}
    for n in names:
        by_base.setdefault(re.sub(r"\[\d+:\d+\]$", "", n), n)
    root = next((n.rsplit(".u_top.", 1)[0] for n in names if ".u_top." in n), None)
    if root is None:
        print(f"gen_gtkw: error: {fst} has no u_top scope", file=sys.stderr)
        return 2
    groups = list(GROUPS)
    engines = []
    for i in range(16):
        for gen in ("g_engine", "gen_engine"):
            scope = f"u_top.{gen}[{i}].u_engine"
            if f"{root}.{scope}.busy_o" in by_base:
                engines.append((i, (f"Engine {i}", scope, ENGINE_SIGS)))
    # The watched tile's engine right after the tile generation, open; the others closed at the end.
    closed = set()
    for i, g in engines:
        if i == dump.engine:
            groups.insert(3, (f"Engine {i} (the watched tile)", g[1], g[2]))
        else:
            groups.append(g)
            if dump.engine is not None:
                closed.add(g[0])
    lines = ["[*] GTKWave save file generated by scripts/gen_gtkw.py (see docs/waves.md)",
             f'[dumpfile] "{Path(fst).resolve()}"', *view_lines(dump), f"[sst_width] {SST_WIDTH}", "[sst_expanded] 0",
             f"[signals_width] {SIGNALS_WIDTH}"]
    titles = list(dict.fromkeys(t for t, _, _ in groups))    # one group per title, in order
    for title in titles:
        lines += ["@c00200" if title in closed else "@800200", f"-{title}"]
        for _, scope, sigs in (g for g in groups if g[0] == title):
            for s in sigs:
                full = by_base.get(f"{root}.{scope}.{s}")
                if full is None:
                    continue
                lines += ["@28" if "[" not in full.rsplit(".", 1)[-1] else "@22", full]
        lines += ["@1400200" if title in closed else "@1000200", f"-{title}"]
    Path(out).write_text("\n".join(lines) + "\n")
    return 0


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("fst", help="the FST of make sim WAVES=1")
    ap.add_argument("out", help="the GTKWave save file to write")
    args = ap.parse_args(argv)
    return write_view(args.fst, args.out)


if __name__ == "__main__":
    sys.exit(main())
