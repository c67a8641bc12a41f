"""Functional coverage bins of the benches: a small bin counter (no cocotb-coverage needed).

A bench calls `record(bench, axis=value, ...)` once per frame or tile it checked (after the
check passed, so a bin counts only checked stimulus). Records go as JSON lines to the file named
by MSR_FUNCOV_FILE (set by the runner under `make coverage` and by `make soak`); without it
nothing is written. scripts/coverage_report.py counts, per bench, the values of each axis
below that occurred and the combinations of each cross."""
from __future__ import annotations

import json
import os

# Per bench: axis -> every value it can take (the bins).
AXES = {
    "msr_top": {
        "tile": [8, 16, 32],
        "levels": [1, 2, 3],
        "metric": ["max", "sum"],
        "fov": ["off", "on"],
        "partial": ["none", "x", "y", "xy"],          # frame edge cuts the last tile column / row
        "engines": [2, 3, 4],                        # 2: the patent-only build (LINDILATE 0)
        "backpressure": ["none", "some", "heavy"],    # memory pauses and render-port readiness
        "src": ["on", "off"],
    },
    "msr_tile_engine": {
        "levels": [1, 2, 3],
        "metric": ["max", "sum"],
        "w": ["1", "2-7", "8", "9-15", "16", "17-31", "32"],
        "h": ["1", "2-7", "8", "9-15", "16", "17-31", "32"],
        "profile": ["fast", "jitter", "long"],
        "max_out": [2, 16, 64],
        "rule": ["patent", "lindilate"],
    },
    "msr_fb_writer": {
        "tile": [8, 16, 32],
        "bus": [32, 64, 128, 256],
        "inputs": [1, 2, 3, 4],
        "src": ["on", "off"],
        "backpressure": ["none", "some", "heavy"],
    },
    "msr_tile_gen": {
        "engines": [1, 3, 4],
        "tile": [8, 16, 32],
        "fov": ["off", "on"],
        "partial": ["none", "x", "y", "xy"],
    },
}

# Crosses reported besides the single axes (the full product of the list for msr_top).
CROSSES = {
    "msr_top": {
        "all": ("tile", "levels", "metric", "fov", "partial", "engines", "backpressure"),
        "tile_levels_metric": ("tile", "levels", "metric"),
        "engines_backpressure": ("engines", "backpressure"),
        "tile_partial": ("tile", "partial"),
    },
    "msr_tile_engine": {
        "levels_metric_profile": ("levels", "metric", "profile"),
        "w_h": ("w", "h"),
        "rule_levels_profile": ("rule", "levels", "profile"),
    },
    "msr_fb_writer": {"bus_inputs": ("bus", "inputs")},
    "msr_tile_gen": {"engines_tile": ("engines", "tile")},
}


def size_class(n: int) -> str:
    """Bin of a tile side 1..32: the powers of two the hardware special-cases and between."""
    for lo, hi, name in ((1, 1, "1"), (2, 7, "2-7"), (8, 8, "8"), (9, 15, "9-15"), (16, 16, "16"),
                         (17, 31, "17-31"), (32, 32, "32")):
        if lo <= n <= hi:
            return name
    raise ValueError(n)


def partial(w: int, h: int, tile: int) -> str:
    """Which frame edges cut a tile: none, x (last column narrower), y (last row), xy."""
    return {(False, False): "none", (True, False): "x", (False, True): "y", (True, True): "xy"}[
        (w % tile != 0, h % tile != 0)]


def backpressure(p: float) -> str:
    """Bin of a stall probability (0 = never stalled)."""
    return "none" if p <= 0.0 else ("some" if p < 0.4 else "heavy")


def record(bench: str, **bins) -> None:
    path = os.environ.get("MSR_FUNCOV_FILE")
    if not path:
        return
    for axis, value in bins.items():
        domain = AXES[bench][axis]
        if value not in domain:
            raise ValueError(f"funcov {bench}.{axis}: {value!r} is not a bin of {domain}")
    with open(path, "a") as fh:
        fh.write(json.dumps({"bench": bench, "bins": bins}) + "\n")
