"""The one runner of the Verilator frame harness (sim/harness.cpp), for `make sim`
(run_sim.py), the hardware benchmark (bench_hw.py) and their tests.

    golden = GoldenFrames("cornell", 640, 480)              # one full render, then select() on it
    run = HarnessRun(harness, "cornell", 640, 480, params)  # thresholds always passed explicitly
    rtl = run.run()                                         # RtlFrame: frame, source, stats
    verdict = compare(rtl, golden.frame(params))            # bit_exact, mismatched pixels

The harness writes the facts a script needs into its stats file (sim/harness.cpp): the
build's parameters (`build`: num_engines, max_outstanding, num_ctx, axi_beat_bytes), the
memory layout it programmed (`layout`: fb_base, fb_stride, src_base, src_stride) and the
frame's register values (`params`). `RtlFrame.layout` and `RtlFrame.build` read them; no
constant of the harness is repeated here.
"""
from __future__ import annotations

import json
import subprocess
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from msr_model import ImageRenderer, Params, select, spec
from msr_model.clitools import RunFailed

ROOT = Path(__file__).resolve().parents[2]
# Rules the RTL implements, by their CONFIG.RULE value (the index); the golden model knows more.
RTL_RULES = ("patent", "lindilate")


def read_pnm(path: Path) -> np.ndarray:
    from PIL import Image
    with Image.open(path) as im:
        return np.asarray(im)


def read_pgm16(path: Path) -> np.ndarray:
    """A 16-bit binary PGM (maxval 65535, big-endian samples; the harness's --depth plane)."""
    data = Path(path).read_bytes()
    fields, pos = [], 0
    while len(fields) < 4:                 # P5, width, height, maxval; whitespace between
        while data[pos:pos + 1].isspace():
            pos += 1
        end = pos
        while not data[end:end + 1].isspace():
            end += 1
        fields.append(data[pos:end].decode())
        pos = end
    if fields[0] != "P5" or fields[3] != "65535":
        raise RunFailed(f"{path}: not a 16-bit binary PGM")
    w, h = int(fields[1]), int(fields[2])
    return np.frombuffer(data[pos + 1:pos + 1 + 2 * w * h], dtype=">u2").reshape(h, w).astype(np.uint16)


@dataclass(frozen=True)
class MemoryLayout:
    """Where the harness put the two planes of a frame, as its stats file says (`layout`)."""

    width: int
    height: int
    fb_base: int
    fb_stride: int
    src_base: int
    src_stride: int

    @classmethod
    def from_stats(cls, stats: dict) -> "MemoryLayout":
        p, lay = stats["params"], stats["layout"]
        return cls(p["width"], p["height"], lay["fb_base"], lay["fb_stride"], lay["src_base"], lay["src_stride"])

    def w_beats(self, tile: int, beat: int) -> int:
        """AXI W beats of a frame: per tile row one run of 32-bit pixels and one of 8-bit codes,
        each from the bus-aligned address below its start (the writer's bursts), i.e.
        ceil((start % beat + bytes) / beat) beats per run. The W channel moves one beat per
        clock, so this is a lower bound on cycles."""
        total = 0
        for y in range(self.height):
            for x0, wt in spec.axis_spans(self.width, tile):
                a = self.fb_base + y * self.fb_stride + 4 * x0
                total += -(-(a % beat + 4 * wt) // beat)
                s = self.src_base + y * self.src_stride + x0
                total += -(-(s % beat + 4 * -(-wt // 4)) // beat)
        return total


@dataclass
class RtlFrame:
    frame: np.ndarray          # (H, W, 3) uint8, read back from the harness's memory
    source: np.ndarray         # (H, W) uint8 source codes
    stats: dict                # the harness's stats file (cycles, perf counters, speed)
    wall_seconds: float = 0.0
    invz: np.ndarray | None = None   # (H, W) uint16: each pixel's inverse depth (a depth run)

    @property
    def layout(self) -> MemoryLayout:
        return MemoryLayout.from_stats(self.stats)

    @property
    def build(self) -> dict:
        """The harness build's parameters: num_engines, max_outstanding, num_ctx, axi_beat_bytes."""
        if "build" not in self.stats:   # a binary from before the harness wrote its build
            raise RunFailed("the harness's stats carry no build parameters: the binary predates "
                            "sim/harness.cpp; rebuild it (make bench-hw-build, or make sim)")
        return self.stats["build"]

    def w_beats(self, tile: int) -> int:
        """AXI W beats the frame needs at least (MemoryLayout.w_beats on this run's layout and bus)."""
        return self.layout.w_beats(tile, self.build["axi_beat_bytes"])

    @property
    def traced_counted(self) -> int:
        return sum(self.stats[f"traced_{k}"] for k in ("initial", "level1", "level2", "level3"))

    @property
    def interpolated_counted(self) -> int:
        return sum(self.stats[f"interpolated_level{k}"] for k in (1, 2, 3))


@dataclass
class HarnessRun:
    """One frame through one harness build."""

    harness: Path
    scene: str
    width: int
    height: int
    params: Params
    rule: str = "patent"                                # one of RTL_RULES: written to CONFIG.RULE
    quality: str = "fast"
    camera: str | None = None
    latency: int = 4
    jitter: int = 8
    quiet: bool = False
    budget: object = None                               # msr_model.budget.BudgetConfig, or None: off
    cameras: list[str] | None = None                    # a sequence: one view per frame (one run)
    gazes: list | None = None                           # ... and each frame's gaze (x, y) or None
    extra: list[str] = field(default_factory=list)     # e.g. --waves FILE --wave-tile TX,TY
    invz_exp: int | None = None                         # a DEPTH_EN harness: the depth plane at this exponent
    _proc: subprocess.Popen | None = None
    _dir: tempfile.TemporaryDirectory | None = None
    _t0: float = 0.0

    def command(self, workdir: Path) -> list[str]:
        p = self.params
        if self.rule not in RTL_RULES:
            raise spec.SpecError(f"rule {self.rule!r}: the RTL implements {', '.join(RTL_RULES)}")
        thr3 = list(p.thr) + [0] * (3 - p.levels)      # explicit: the harness has no defaults of its own
        seq = "_%04d" if self.cameras else ""
        cmd = [str(self.harness), "--width", str(self.width), "--height", str(self.height),
               "--tile", str(p.tile), "--levels", str(p.levels), "--thr", ",".join(map(str, thr3)),
               "--metric", p.metric, "--fov-gain", str(p.fov_gain), "--rule", self.rule,
               "--frame", str(workdir / f"rtl_frame{seq}.ppm"), "--source", str(workdir / f"rtl_source{seq}.pgm"),
               "--stats", str(workdir / "rtl_stats.json"),
               f"+scene={self.scene}", f"+width={self.width}", f"+height={self.height}",
               f"+quality={0 if self.quality == 'fast' else 1}",
               f"+rnd_latency={self.latency}", f"+rnd_jitter={self.jitter}"]
        if self.budget is not None and self.budget.budget:
            b = self.budget
            cmd += ["--budget", str(b.budget), "--scale-init", str(b.scale_init), "--prior-shift",
                    str(b.prior_shift), "--seeded", str(int(b.profile is not None))]
        if p.gaze is not None:
            cmd += ["--gaze", f"{p.gaze[0]},{p.gaze[1]}"]
        if self.cameras:
            cmd += ["--frames", str(len(self.cameras)), "--cameras", str(workdir / "cameras.txt")]
        if self.gazes:
            cmd += ["--gazes", str(workdir / "gazes.txt")]
        if self.camera:
            cmd.append(f"+camera={self.camera}")  # read by sim/msr_dpi.cpp, passed to the library unchanged
        if self.invz_exp is not None:
            cmd += [f"+invz_exp={self.invz_exp}", "--depth", str(workdir / "rtl_depth.pgm")]
        if self.quiet:
            cmd.append("--quiet")
        return cmd + list(self.extra)

    def start(self) -> "HarnessRun":
        """Start the harness in its own process (the caller may work meanwhile)."""
        import time
        if not Path(self.harness).is_file():
            raise spec.SpecError(f"harness {self.harness} not built")
        self._dir = tempfile.TemporaryDirectory(prefix="msr_harness_")
        if self.cameras:
            Path(self._dir.name, "cameras.txt").write_text("".join(c + "\n" for c in self.cameras))
        if self.gazes:                                  # a frame without one: "-", the run's gaze
            Path(self._dir.name, "gazes.txt").write_text(
                "".join(("-" if g is None else f"{g[0]},{g[1]}") + "\n" for g in self.gazes))
        self._t0 = time.perf_counter()
        self._proc = subprocess.Popen(self.command(Path(self._dir.name)), stderr=subprocess.PIPE if self.quiet
                                      else None, text=True)
        return self

    def wait(self):
        """The frame, source map and stats (a list of them for a sequence); RunFailed (with the
        harness's last line) if it failed."""
        import time
        assert self._proc is not None and self._dir is not None, "start() first"
        try:
            _, err = self._proc.communicate()
            wall = time.perf_counter() - self._t0
            rc = self._proc.returncode
            if rc != 0:
                last = (err or "").strip().splitlines()[-1:] or ["see its output above"]
                raise RunFailed(f"the RTL simulation failed (harness exit status {rc}): {last[0]}")
            d = Path(self._dir.name)
            if not self.cameras:
                return RtlFrame(read_pnm(d / "rtl_frame.ppm"), read_pnm(d / "rtl_source.pgm"),
                                json.loads((d / "rtl_stats.json").read_text()), round(wall, 3),
                                read_pgm16(d / "rtl_depth.pgm") if self.invz_exp is not None else None)
            # a sequence: the stats file holds one JSON object per frame, one after the other
            text, dec, pos, stats = (d / "rtl_stats.json").read_text(), json.JSONDecoder(), 0, []
            while text[pos:].strip():
                obj, pos = dec.raw_decode(text, pos + (len(text[pos:]) - len(text[pos:].lstrip())))
                stats.append(obj)
            if len(stats) != len(self.cameras):
                raise RunFailed(f"the harness wrote {len(stats)} frames of {len(self.cameras)}")
            return [RtlFrame(read_pnm(d / f"rtl_frame_{k:04d}.ppm"), read_pnm(d / f"rtl_source_{k:04d}.pgm"),
                             st, round(wall / len(stats), 3)) for k, st in enumerate(stats)]
        finally:
            self._dir.cleanup()
            self._proc = self._dir = None

    def run(self) -> RtlFrame:
        return self.start().wait()


class GoldenFrames:
    """The golden model on the same renderer as the RTL: one full render of the scene (the
    reference), then `select` answers its trace requests from it (the renderer is
    deterministic, so these are exactly the pixels the renderer would give)."""

    def __init__(self, scene: str, width: int, height: int, quality: str = "fast", camera: str | None = None,
                 renderer=None):
        from msr_model.embree import open_renderer
        r = renderer or open_renderer(scene, width, height, quality=quality, camera=camera)
        try:
            self.reference = r.render_full(progress=False)
        finally:
            r.close()
        self.width, self.height = width, height
        self._cache: dict = {}

    def frame(self, params: Params, rule: str = "patent", budget=None):
        """golden.select, or with `budget` (a msr_model.budget.BudgetConfig) select_budget."""
        from msr_model.budget import select_budget
        key = (params, rule, budget)
        if key not in self._cache:
            r = ImageRenderer(self.reference)
            self._cache[key] = (select(r, self.width, self.height, params, rule=rule) if budget is None else
                                select_budget(r, self.width, self.height, params, budget, rule=rule))
        return self._cache[key]


def compare(rtl: RtlFrame, golden) -> dict:
    """The RTL's frame and source map against the golden model's, pixel for pixel."""
    frame_ok = bool(np.array_equal(rtl.frame, golden.frame))
    source_ok = bool(np.array_equal(rtl.source, golden.source))
    return {"bit_exact": frame_ok and source_ok, "frame_equal": frame_ok, "source_map_equal": source_ok,
            "mismatched_pixels": int((rtl.frame != golden.frame).any(axis=2).sum()),
            "mismatched_codes": int((rtl.source != golden.source).sum())}
