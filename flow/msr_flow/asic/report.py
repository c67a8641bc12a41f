"""The report: its header (library, clock, tools, the macro model, the parameters), the ECP5
figure it is compared with, and where it is kept (build/asic/ for every run, docs/asic.json
for the page)."""
from __future__ import annotations

import json
from pathlib import Path

from ..filelist import ROOT
from .config import (ABC_SCRIPT, AIM_MHZ, CORNER, DATA, LIB_NAME, LIBERTY_SRC, MACRO_JSON, OUT, SDC,
                     TARGET_MHZ, TOOLS, AsicError, rel)


def new_report(period_ns: float, nand2_um2: float, engine_params: dict, top_params: dict) -> dict:
    """Everything of a run but its rows (`modules`), its failures and its duration."""
    return {"library": LIB_NAME, "liberty": str(LIBERTY_SRC), "corner": CORNER,
            "clock": {"port": "clk_i", "period_ns": period_ns, "target_mhz": round(1000 / period_ns, 1),
                      "goal_mhz": TARGET_MHZ, "aim_mhz": AIM_MHZ, "sdc": rel(SDC)},
            "nand2_um2": nand2_um2, "abc_script": ABC_SCRIPT, "abc_delay_target_ps": round(1e6 / AIM_MHZ),
            "sram_model": json.loads(MACRO_JSON.read_text()), "tools": dict(TOOLS),
            "engine_params": engine_params, "top_params": top_params, "modules": {}, "failures": [],
            "ecp5": ecp5_figure()}


def ecp5_figure() -> dict | None:
    """The default top's ECP5 row of make synth (build/synth/report.json, else the committed
    docs/synthesis.json): LUT4, Fmax, pixels per second per LUT4. Kept in the report so that
    the page compares with the figure of the day of the run."""
    for p in (ROOT / "build" / "synth" / "report.json", ROOT / "docs" / "synthesis.json"):
        try:
            r = json.loads(p.read_text())["top_ecp5"]
            if r.get("pixels_per_second_per_lut4"):
                return {"luts": r["luts"], "fmax_mhz": r["fmax_mhz"],
                        "pixels_per_second_per_lut4": r["pixels_per_second_per_lut4"], "from": rel(p)}
        except (OSError, ValueError, KeyError, TypeError):
            continue
    return None


def write_report(report: dict, full: bool) -> Path:
    """build/asic/report.json (a full run; also the page's docs/asic.json) or, for a subset of
    the units, build/asic/report_partial.json: a subset never replaces the whole."""
    text = json.dumps(report, indent=2) + "\n"
    out = OUT / ("report.json" if full else "report_partial.json")
    out.write_text(text)
    if full:
        DATA.write_text(text)
    return out


def read_data(path: Path = DATA) -> dict:
    try:
        return json.loads(path.read_text())
    except (OSError, ValueError) as e:
        raise AsicError(f"no readable {rel(path)} ({e}): run make asic first") from None


# The memory build's parameters a partial run may set (msr_flow.asic.cli: --num-ctx, --rd-lat,
# --tile-limit, --buf-cycle) and their flags.
BUILD_FLAGS = {"NUM_CTX": "--num-ctx", "RD_LAT": "--rd-lat", "TILE_LIMIT": "--tile-limit", "BUF_CYCLE": "--buf-cycle"}
BENCH_BITS = ROOT / "data" / "bench" / "tile_bits.json"


def build_summary(partial: dict, default_top: dict, bits_record: Path = BENCH_BITS) -> dict:
    """A partial run of the engine and the top in another memory build, as the page's data keep
    it: the parameters set, the command, each unit's area, flip-flops, Fmax (logic alone and with
    the cited macro's own timing) and macros, and the pixels per clock make bench-bits measured
    for that build at latency 256 (the slower rule), which gives the pixel rates."""
    mods = partial.get("modules", {})
    rows = {u: mods.get(u) for u in ("msr_tile_engine", "msr_top")}
    bad = [u for u, r in rows.items() if not r or "error" in r]
    if bad:
        raise AsicError(f"{rel(OUT / 'report_partial.json')} has no result for {', '.join(bad)}: "
                        "make asic UNIT=msr_tile_engine,msr_top ASIC_ARGS=\"--rd-lat=... \" first")
    top_params = partial["top_params"]
    overrides = {k: top_params[k] for k in BUILD_FLAGS if top_params.get(k, default_top[k]) != default_top[k]}
    if not overrides:
        raise AsicError("the partial run is the default build: a full make asic records it")
    ppc = None
    try:
        for d in json.loads(bits_record.read_text())["design_points"]:
            point = (d["num_ctx"], d["lindilate"], d.get("rd_lat", 1), d.get("tile_limit", 32), d.get("buf_cycle", 1))
            if point == tuple(top_params.get(k, default_top[k])
                              for k in ("NUM_CTX", "LINDILATE", "RD_LAT", "TILE_LIMIT", "BUF_CYCLE")):
                ppc = min(p["pixels_per_clock"] for p in d["points"] if p["render_latency"] == 256)
    except (OSError, ValueError, KeyError):
        ppc = None
    out = {"params": overrides,
           "command": "make asic UNIT=msr_tile_engine,msr_top ASIC_ARGS=\""
                      + " ".join(f"{BUILD_FLAGS[k]}={v}" for k, v in overrides.items()) + "\"",
           "pixels_per_clock_latency_256": ppc, "pixels_per_clock_source": rel(bits_record) if bits_record.is_relative_to(ROOT) else str(bits_record),
           "modules": {}}
    for unit, r in rows.items():
        sm = r["sram_macros"]
        fmax = r.get("fmax_with_cited_sram_mhz") or r["fmax_mhz"]
        row = {"area_um2": r["area_um2"], "flip_flops": r["flip_flops"], "fmax_mhz": r["fmax_mhz"],
               "fmax_with_cited_sram_mhz": fmax, "sram_read_clocks": r.get("sram_read_clocks", 1),
               "sram_bits": sm["bits"], "sram_area_um2": sm["area_um2"], "sram_macros_1r1w": sm["macros_1r1w"],
               "sram_variants": sm["variants"]}
        if unit == "msr_top" and ppc:
            row["pixels_per_second"] = round(fmax * 1e6 * ppc)
            row["pixels_per_second_per_mm2_logic"] = round(fmax * 1e6 * ppc / (r["area_um2"] / 1e6))
            row["pixels_per_second_per_mm2_total"] = round(fmax * 1e6 * ppc / ((r["area_um2"] + sm["area_um2"]) / 1e6))
        out["modules"][unit] = row
    return out
