"""Tile-buffer bits against throughput: `make bench-bits` (scripts/bench_bits.py).

    python scripts/bench_bits.py [--points "7:1 6:1 5:1 4:1 3:1 7:0 5:0 4:0 3:0 6:1:4 7:1:4:16 10:1:4:16:5"]
        [--latencies 64,256,1024] [--rules patent,lindilate] [--scene cornell]
        [--width 640 --height 480] [--out build/bench/tile_bits.json] [--update] [--no-build]

A design point is NUM_CTX:LINDILATE[:RD_LAT[:TILE_LIMIT[:BUF_CYCLE]]] of msr_top with 4 engines and
64 tags (MAX_OUTSTANDING); RD_LAT, the tile buffers' read latency in clocks (default 1), sets no
bits but may cost pixels per clock (a standard-cell build's macros need several clocks,
docs/asic.md); TILE_LIMIT, the largest tile edge the buffers hold (default 32, MAX_TILE), sets
the words; BUF_CYCLE, the clocks a macro's port needs between two addresses (default 1), sets no
bits but spaces each context's decisions and writes.
Each context of an engine holds a tile buffer of TILE_LIMIT^2 words of a source code and a colour
(msr_tile_ctx: a 2R1W memory, two 1R1W macros written in parallel) and, with LINDILATE 1, a
colour-only copy read by a third port (one macro). The bits (DEPTH x DATA_W of every buffer,
as docs/asic.md counts them) and the macro area (msr_flow.asic's model of
syn/asic/sram_macro.json) follow from the point; the pixels per clock are measured: one frame
per (point, rule, latency) through the harness build e4_mo64_c<N>[_rl<L>][_t<T>][_cy<Y>] (LINDILATE
1) or the same name with _l0 (LINDILATE 0: the patent rule only), made by mk/bench.mk, run by
msr_flow.bench.hw.run_point, so every frame and source map is compared with the golden model.

The choice: the point with the fewest bits whose pixels per clock at latency 256 reach the
bench's goal (3.6) in every rule swept; its macro area against the default top's (NUM_CTX 7,
LINDILATE 1). Writes the record (--out, JSON) and prints the table. --update keeps the
record's other points (same set-up), so the points can be measured one build at a time.
Bad arguments: one line on stderr, exit status 2; exit status 1 when a frame is not bit exact.
"""
from __future__ import annotations

import json
import re
import subprocess
import sys
import time
from pathlib import Path

from msr_model import spec
from msr_model.clitools import Parser, RunFailed, UsageError, int_list, run_main
from ..asic.config import MACRO_JSON
from ..asic.macros import MacroModel
from ..filelist import ROOT, rtl_digest
from ..harness import RTL_RULES, GoldenFrames
from .hw import GOAL_LATENCY, GOAL_PIXELS, bottleneck, run_point

ENGINES, TAGS = 4, 64
DEFAULT_POINT = (7, 1)            # msr_top's NUM_CTX and LINDILATE
RGB_BITS = 24                     # rgb_t: the colour-only copy's word
TARGET_REDUCTION = 0.30           # macro area at least 30 % below the default top's
PKG = ROOT / "rtl" / "pkg" / "msr_pkg.sv"
OUT = ROOT / "build" / "bench" / "tile_bits.json"


def pkg_constant(name: str, text: str | None = None) -> int:
    """A `localparam int unsigned NAME = <number>;` of rtl/pkg/msr_pkg.sv."""
    text = PKG.read_text() if text is None else text
    m = re.search(rf"localparam\s+int\s+unsigned\s+{name}\s*=\s*(\d+)\s*;", text)
    if not m:
        raise RunFailed(f"{PKG.relative_to(ROOT)} has no numeric localparam {name}")
    return int(m.group(1))


def buffers(num_ctx: int, lindilate: int, engines: int = ENGINES, tile_limit: int | None = None) -> list[dict]:
    """The tile buffers of a top: (depth, width, read ports, count), as msr_tile_ctx has them."""
    depth = (tile_limit or pkg_constant("MAX_TILE")) ** 2
    word = pkg_constant("SRC_W") + RGB_BITS          # WORD_W = $bits(src_t) + $bits(rgb_t)
    out = [{"depth": depth, "width": word, "read_ports": 2, "count": engines * num_ctx}]
    if lindilate:
        out.append({"depth": depth, "width": RGB_BITS, "read_ports": 1, "count": engines * num_ctx})
    return out


def cost(num_ctx: int, lindilate: int, engines: int = ENGINES, model: MacroModel | None = None,
         tile_limit: int | None = None) -> dict:
    """Bits and macro area of the tile buffers of a top (msr_flow.asic's macro model)."""
    model = model or MacroModel.load()
    bufs = buffers(num_ctx, lindilate, engines, tile_limit)
    area = sum(b["count"] * b["read_ports"] * model.area_1r1w(b["depth"], b["width"]) for b in bufs)
    return {"bits": sum(b["count"] * b["depth"] * b["width"] for b in bufs),
            "stored_bits": sum(b["count"] * b["read_ports"] * b["depth"] * b["width"] for b in bufs),
            "macros_1r1w": sum(b["count"] * b["read_ports"] for b in bufs),
            "variants": [f"{b['depth']}x{b['width']} ({b['read_ports']} read port{'s' if b['read_ports'] > 1 else ''})"
                         for b in bufs],
            "macro_area_mm2": round(area / 1e6, 3)}


def config_name(num_ctx: int, lindilate: int, rd_lat: int = 1, tile_limit: int = 32, cycle: int = 1) -> str:
    return (f"e{ENGINES}_mo{TAGS}_c{num_ctx}" + (f"_rl{rd_lat}" if rd_lat > 1 else "")
            + (f"_t{tile_limit}" if tile_limit != 32 else "") + (f"_cy{cycle}" if cycle > 1 else "")
            + ("" if lindilate else "_l0"))


def harness_of(build_dir: Path, num_ctx: int, lindilate: int, rd_lat: int = 1, tile_limit: int = 32,
               cycle: int = 1) -> Path:
    return Path(build_dir) / f"hw_{config_name(num_ctx, lindilate, rd_lat, tile_limit, cycle)}" / "Vmsr_sim_top"


def check_lindilate(harness: Path, lindilate: int) -> None:
    """The harness stats do not carry LINDILATE: the _l0 builds compile a copy of msr_sim_top
    giving msr_top LINDILATE (0) (mk/bench.mk), the others do not."""
    copy = harness.parent / "msr_sim_top.sv"
    has = copy.is_file() and ".LINDILATE (0)" in copy.read_text()
    if has == bool(lindilate):
        raise RunFailed(f"{harness} is not a LINDILATE {lindilate} build")


def build(harness: Path) -> None:
    target = harness.relative_to(ROOT)
    r = subprocess.run(["make", "--no-print-directory", str(target)], cwd=ROOT, capture_output=True, text=True)
    if r.returncode != 0:
        raise RunFailed(f"make {target} failed: {(r.stdout + r.stderr).strip().splitlines()[-1:]}")


def parse_points(text: str) -> list[tuple[int, int, int, int, int]]:
    pts = []
    for item in text.split():
        f = item.split(":")
        ctx, lin, lat, lim, cyc = (f + ["", "", "", "", ""])[:5]
        lat, lim, cyc = lat or "1", lim or "32", cyc or "1"
        if not (len(f) <= 5 and ctx.isdigit() and lin in ("0", "1") and 2 <= int(ctx) <= 16
                and lat in ("1", "2", "3", "4") and lim in ("8", "16", "32") and cyc in tuple("12345678")):
            raise UsageError(f"design point {item!r} is not NUM_CTX:LINDILATE[:RD_LAT[:TILE_LIMIT[:BUF_CYCLE]]] "
                             "(NUM_CTX 2..16, LINDILATE 0 or 1, RD_LAT 1..4, TILE_LIMIT 8, 16 or 32, BUF_CYCLE 1..8)")
        pts.append((int(ctx), int(lin), int(lat), int(lim), int(cyc)))
    if not pts:
        raise UsageError("no design points given (--points)")
    return pts


def parse(argv):
    ap = Parser(prog="bench_bits", description=__doc__.splitlines()[0])
    ap.add_argument("--points", default="7:1 6:1 5:1 4:1 3:1 7:0 6:0 5:0 4:0 3:0",
                    help="design points NUM_CTX:LINDILATE, space separated")
    ap.add_argument("--latencies", default="64,256,1024")
    ap.add_argument("--rules", default=",".join(RTL_RULES))
    ap.add_argument("--scene", default="cornell")
    ap.add_argument("--width", type=int, default=640)
    ap.add_argument("--height", type=int, default=480)
    ap.add_argument("--tile", type=int, default=16)
    ap.add_argument("--levels", type=int, default=2)
    ap.add_argument("--build-dir", default=str(ROOT / "build" / "bench"))
    ap.add_argument("--out", default=str(OUT))
    ap.add_argument("--update", action="store_true", help="keep the other points of the record at --out")
    ap.add_argument("--no-build", action="store_true", help="use the harnesses as they are (no make)")
    ap.add_argument("--no-progress", action="store_true")
    a = ap.parse_args(argv)
    a.design = parse_points(a.points)
    a.latencies = list(int_list(a.latencies, "--latencies", 0, 100000))
    a.rules = [r for r in a.rules.split(",") if r]
    bad = [r for r in a.rules if r not in RTL_RULES]
    if bad or not a.rules:
        raise UsageError(f"--rules {a.rules!r}: each one of {', '.join(RTL_RULES)}")
    if not (1 <= a.width <= 4096 and 1 <= a.height <= 4096):
        raise UsageError(f"frame {a.width}x{a.height} outside 1..4096")
    return a


def setup_of(a) -> dict:
    return {"scene": a.scene, "width": a.width, "height": a.height, "tile": a.tile, "levels": a.levels,
            "thr": list(spec.default_thresholds(a.levels)), "metric": "max", "fov_gain": 0,
            "num_engines": ENGINES, "max_outstanding": TAGS, "latencies": a.latencies,
            "renderer": "Embree over DPI-C (render_dpi.sv), quality fast, no jitter",
            "memory": "AXI slave always ready", "source_map": "enabled",
            "pixels_per_clock": "W*H / PERF_CYCLES (START to DONE)",
            "bit_exact_check": "every frame and source map against the golden model on the same renderer "
                               "and rule (msr_flow.bench.hw.run_point)"}


def rules_for(lindilate: int, rules: list[str]) -> list[str]:
    """The lindilate rule needs the third port: LINDILATE 0 runs the patent rule only."""
    return [r for r in rules if lindilate or r != "lindilate"]


def ppc(dp: dict, rule: str, latency: int) -> float | None:
    return next((p["pixels_per_clock"] for p in dp["points"]
                 if p["rule"] == rule and p["render_latency"] == latency), None)


def build_of(d: dict) -> tuple[int, int, int]:
    """A point's memory build: (RD_LAT, TILE_LIMIT, BUF_CYCLE)."""
    return d.get("rd_lat", 1), d.get("tile_limit", 32), d.get("buf_cycle", 1)


def choose(dps: list[dict], rules: list[str], default_area: float, rd_lat: int = 1,
           tile_limit: int = 32, cycle: int = 1) -> dict | None:
    """Fewest bits with >= GOAL_PIXELS at GOAL_LATENCY in every rule (ties: more pixels per clock),
    among the points of read latency rd_lat, tile limit tile_limit and buffer cycle cycle."""
    ok = []
    for dp in (d for d in dps if build_of(d) == (rd_lat, tile_limit, cycle)):
        got = [ppc(dp, r, GOAL_LATENCY) for r in rules]
        if all(g is not None and g >= GOAL_PIXELS for g in got):
            ok.append((dp["bits"], -min(got), dp))
    if not ok:
        return None
    dp = min(ok, key=lambda t: t[:2])[2]
    area = dp["macro_area_mm2"]
    return {"rules": rules, "criterion": f">= {GOAL_PIXELS} pixels per clock at latency {GOAL_LATENCY} "
                                         f"in {' and '.join(rules)}, fewest bits",
            "num_ctx": dp["num_ctx"], "lindilate": dp["lindilate"], "rd_lat": dp.get("rd_lat", 1),
            "tile_limit": dp.get("tile_limit", 32), "buf_cycle": dp.get("buf_cycle", 1), "config": dp["config"],
            "bits": dp["bits"], "macro_area_mm2": area, "default_macro_area_mm2": default_area,
            "area_reduction": round(1 - area / default_area, 4), "target_reduction": TARGET_REDUCTION,
            "target_met": 1 - area / default_area >= TARGET_REDUCTION,
            "pixels_per_clock_latency_256": {r: ppc(dp, r, GOAL_LATENCY) for r in rules}}


def reference() -> dict | None:
    """The default top's macros as make asic reported them (docs/asic.json), to check the model."""
    path = ROOT / "docs" / "asic.json"
    try:
        m = json.loads(path.read_text())["modules"]["msr_top"]["sram_macros"]
    except (OSError, KeyError, ValueError):
        return None
    return {"source": "docs/asic.json modules.msr_top.sram_macros", "bits": m["bits"],
            "macro_area_mm2": round(m["area_um2"] / 1e6, 3), "macros_1r1w": m["macros_1r1w"]}


def record(a, dps: list[dict], seconds: float) -> dict:
    dps = sorted(dps, key=lambda d: (d.get("buf_cycle", 1), -d.get("tile_limit", 32), d.get("rd_lat", 1),
                                     -d["lindilate"], -d["num_ctx"]))
    default_area = cost(*DEFAULT_POINT)["macro_area_mm2"]
    ref = reference()
    model = json.loads(MACRO_JSON.read_text())
    return {
        "what": "Tile-buffer bits and macro area of msr_top (4 engines, 64 tags) against its pixels per "
                "clock, over NUM_CTX and LINDILATE, both decision rules",
        "command": "make bench-bits (python scripts/bench_bits.py)",
        "setup": setup_of(a),
        "bits_model": {"max_tile": pkg_constant("MAX_TILE"), "word_bits": pkg_constant("SRC_W") + RGB_BITS,
                       "colour_copy_bits": RGB_BITS,
                       "bits": "sum over tile buffers of DEPTH x DATA_W (as docs/asic.md counts them)",
                       "stored_bits": "the same over the 1R1W macros (a 2R1W buffer is two)",
                       "macro_area": f"msr_flow.asic.macros.MacroModel.area_1r1w ({MACRO_JSON.relative_to(ROOT)}: "
                                     f"{model['source']['name']})",
                       "tile_size_limit": "msr_top TILE_LIMIT (8, 16, 32; default 32 = MAX_TILE): "
                                          "TILE_LIMIT^2 words per buffer, CONFIG.TILE above it refused",
                       "default_top": {**cost(*DEFAULT_POINT), "num_ctx": DEFAULT_POINT[0],
                                       "lindilate": DEFAULT_POINT[1]},
                       "reference": ref,
                       "matches_reference": (ref is not None and ref["bits"] == cost(*DEFAULT_POINT)["bits"]
                                             and abs(ref["macro_area_mm2"] - default_area) < 0.01)},
        "design_points": dps,
        "bit_exact": all(p.get("bit_exact", False) for d in dps for p in d["points"]),
        "choice": choose(dps, a.rules, default_area),
        "choice_patent_only": choose(dps, ["patent"], default_area) if "patent" in a.rules else None,
        # the same choice among the points of each longer read latency measured (a macro build's)
        "choice_by_rd_lat": {str(rl): choose(dps, a.rules, default_area, rl)
                             for rl in sorted({d.get("rd_lat", 1) for d in dps}) if rl > 1},
        # and among the points of each build with smaller tiles or a macro's cycle
        # ("<RD_LAT>:<TILE_LIMIT>:<BUF_CYCLE>")
        "choice_by_build": {":".join(map(str, b)): choose(dps, a.rules, default_area, *b)
                            for b in sorted({build_of(d) for d in dps}) if b[1] < 32 or b[2] > 1},
        "bench_seconds": round(seconds, 1),
    }


def grouped(n: int) -> str:
    """1605632 -> '1 605 632', as the documents write numbers."""
    return f"{n:,}".replace(",", " ")


def print_table(r: dict) -> None:
    lats = r["setup"]["latencies"]
    rules = sorted({p["rule"] for d in r["design_points"] for p in d["points"]}, key=RTL_RULES.index)
    lat = " / ".join(map(str, lats))
    print(f"\n| NUM_CTX | LINDILATE | RD_LAT | TILE_LIMIT | BUF_CYCLE | bits per top | macro mm^2 | "
          + " | ".join(f"{rule}: px/clk at {lat}" for rule in rules) + " | bit exact |")
    print("|---:|---:|---:|---:|---:|---:|---:|" + "---|" * len(rules) + "---|")
    for d in r["design_points"]:
        cells = []
        for rule in rules:
            v = [ppc(d, rule, x) for x in lats]
            cells.append("n/a" if all(x is None for x in v) else
                         " / ".join("-" if x is None else f"{x:.3f}" for x in v))
        print(f"| {d['num_ctx']} | {d['lindilate']} | {d.get('rd_lat', 1)} | {d.get('tile_limit', 32)} | "
              f"{d.get('buf_cycle', 1)} | {grouped(d['bits'])} | "
              f"{d['macro_area_mm2']:.1f} | "
              + " | ".join(cells) + f" | {all(p.get('bit_exact') for p in d['points'])} |")
    extra = [(f"choice at RD_LAT {rl}", c) for rl, c in r.get("choice_by_rd_lat", {}).items()]
    extra += [(f"choice at RD_LAT:TILE_LIMIT:BUF_CYCLE {k}", c) for k, c in r.get("choice_by_build", {}).items()]
    for key, c in [(k, r.get(k)) for k in ("choice", "choice_patent_only")] + extra:
        if c:
            print(f"{key}: NUM_CTX {c['num_ctx']} LINDILATE {c['lindilate']} RD_LAT {c['rd_lat']} "
                  f"TILE_LIMIT {c.get('tile_limit', 32)} BUF_CYCLE {c.get('buf_cycle', 1)}: "
                  f"{grouped(c['bits'])} bits, "
                  f"{c['macro_area_mm2']:.1f} mm^2 against {c['default_macro_area_mm2']:.1f} "
                  f"({c['area_reduction']:.1%} less; target {c['target_reduction']:.0%}: "
                  f"{'met' if c['target_met'] else 'NOT met'})")
        elif key in r or key.startswith("choice at"):
            print(f"{key}: no point reaches {GOAL_PIXELS} pixels per clock at latency {GOAL_LATENCY}")


def run(a) -> int:
    from tqdm import tqdm
    out = Path(a.out)
    build_dir = Path(a.build_dir)
    kept: list[dict] = []
    if a.update and out.is_file():
        old = json.loads(out.read_text())
        if old.get("setup") != setup_of(a):
            raise UsageError(f"--update: {out} was measured with another set-up (frame, latencies or scene)")
        kept = [d for d in old["design_points"]
                if (d["num_ctx"], d["lindilate"], *build_of(d)) not in a.design]
    for ctx, lin, rl, tl, cy in a.design:
        if a.tile > tl:
            raise UsageError(f"design point {ctx}:{lin}:{rl}:{tl}:{cy}: --tile {a.tile} is above its TILE_LIMIT")
        h = harness_of(build_dir, ctx, lin, rl, tl, cy)
        if a.no_build and not h.is_file():
            raise UsageError(f"harness {h} not built (make {h.relative_to(ROOT) if h.is_relative_to(ROOT) else h})")
    jobs = [(pt, rule, lat) for pt in a.design for rule in rules_for(pt[1], a.rules) for lat in a.latencies]
    golden = GoldenFrames(a.scene, a.width, a.height)
    t0 = time.perf_counter()
    dps: dict[tuple[int, int, int, int, int], dict] = {}
    bar = tqdm(jobs, desc="bench_bits", unit="frame", disable=True if a.no_progress else None, file=sys.stderr)
    for key, rule, lat in bar:
        ctx, lin, rl, tl, cy = key
        h = harness_of(build_dir, *key)
        name = config_name(*key)
        if key not in dps:
            if not a.no_build:
                bar.set_postfix_str(f"building {name}")
                build(h)
            check_lindilate(h, lin)
            dps[key] = {"num_ctx": ctx, "lindilate": lin, "rd_lat": rl, "tile_limit": tl, "buf_cycle": cy,
                        "config": name, **cost(ctx, lin, tile_limit=tl), "rtl_digest": rtl_digest(), "points": []}
        bar.set_postfix_str(f"{name} {rule} latency {lat}")
        pt = run_point(h, ENGINES, TAGS, a.scene, a.width, a.height, a.tile, a.levels, lat, golden, rule, ctx,
                       rd_lat=rl, tile_limit=tl, buf_cycle=cy)
        dps[key]["points"].append({
            "rule": rule, "render_latency": lat, "cycles": pt["cycles"], "pixels_per_clock": pt["pixels_per_clock"],
            "traced_fraction": pt["traced_fraction"], "render_stall_cycles": pt["render_stall_cycles"],
            "bit_exact": pt.get("bit_exact"), "mismatched_pixels": pt.get("mismatched_pixels"),
            "bottleneck": bottleneck(pt), "wall_seconds": pt["wall_seconds"]})
    bar.close()
    r = record(a, kept + list(dps.values()), time.perf_counter() - t0)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(r, indent=1) + "\n")
    print_table(r)
    print(f"written {out}")
    return 0 if r["bit_exact"] else 1


def main(argv=None) -> int:
    return run_main("bench_bits", lambda: run(parse(argv)))


if __name__ == "__main__":
    sys.exit(main())
