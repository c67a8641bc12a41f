"""Floorplan of the flat top on the LFE5U-85F, and the picture of its placement.

The tile buffers' block RAMs of each engine are locked into one quarter of the die (engine e:
rows of pair e // 2, side e % 2), a context's block RAMs side by side. Unconstrained, the
placer scatters each engine's block RAMs over the whole width of the die (they are 62 % of
the device's with 4 per context, 92 % with the lindilate rule's 6), and with them the
contexts that read them: wires from the die's corners into the engine's arbiter and read mux.
The device's DP16KD sites: four rows, each 13 groups of four (EBR0..3 at x, x+2, x+4, x+6),
group columns below; the engines take the outer groups, the glue keeps the middle. A
quarter's row is a run of sites (its groups from the die's edge inwards, EBR0..3 in each): a
context takes the next `rams` sites of its row, so a context of 4 fills one group and one of
6 (tile buffer + lindilate's third-port copy) a group and a half. Half the contexts go in
each row."""
from __future__ import annotations

import json
import re
from pathlib import Path

ECP5_EBR_ROWS = (22, 46, 70, 82)
ECP5_EBR_LEFT = (4, 13, 22, 31, 40, 49, 58)
ECP5_EBR_RIGHT = (114, 105, 96, 87, 78, 69)
ECP5_EBR_PER_GROUP = 4
TILE_RAM = re.compile(r"g_engine\[(\d+)\]\.u_engine\.g_ctx\[(\d+)\]\.")
ENGINE_CELL = re.compile(r"g_engine\[(\d+)\]\.")


def _top_module(d: dict) -> str:
    return next(m for m, v in d["modules"].items() if v["attributes"].get("top"))


def ecp5_ebr_site(cols: tuple[int, ...], row: int, i: int) -> str:
    """The i-th DP16KD site of a quarter's row (cols: its group columns, from the edge in)."""
    g, k = divmod(i, ECP5_EBR_PER_GROUP)
    return f"X{cols[g] + 2 * k}/Y{row}/EBR{k}"


def ecp5_floorplan(net: Path) -> dict:
    """Lock the tile buffers' DP16KDs of the flat top's netlist (BEL attributes, which nextpnr
    places first); returns what was locked, or why nothing was (a layout that does not fit)."""
    d = json.loads(net.read_text())
    cells = d["modules"][_top_module(d)]["cells"]
    groups: dict[tuple[int, int], list[str]] = {}
    for name, cell in cells.items():
        m = TILE_RAM.match(name) if cell["type"] == "DP16KD" else None
        if m:
            groups.setdefault((int(m.group(1)), int(m.group(2))), []).append(name)
    engines = sorted({e for e, _ in groups})
    n_ctx = max((c for _, c in groups), default=-1) + 1
    per_row = (n_ctx + 1) // 2
    rams = max((len(v) for v in groups.values()), default=0)
    row_sites = ECP5_EBR_PER_GROUP * min(len(ECP5_EBR_LEFT), len(ECP5_EBR_RIGHT))
    if not groups or len(engines) > 4 or per_row * rams > row_sites:
        return {"locked": 0, "why": "layout does not fit the floorplan (at most 4 engines; per row of a "
                f"quarter {row_sites} block RAMs: half the contexts x their block RAMs, here "
                f"{per_row} x {rams})"}
    for (e, c), names in groups.items():
        row = ECP5_EBR_ROWS[2 * (e // 2) + c // per_row]
        cols = ECP5_EBR_LEFT if e % 2 == 0 else ECP5_EBR_RIGHT
        for i, name in enumerate(sorted(names)):
            cells[name]["attributes"]["BEL"] = ecp5_ebr_site(cols, row, (c % per_row) * rams + i)
    net.write_text(json.dumps(d))
    return {"locked": sum(len(v) for v in groups.values()), "engines": len(engines), "contexts": n_ctx,
            "rams_per_context": rams}


def placed_cells(routed: Path) -> tuple[dict, dict]:
    """Site (x, y) of every placed cell of a routed netlist, by part ("engine e" or "glue"):
    logic cells and block RAMs apart."""
    d = json.loads(routed.read_text())
    pts: dict[str, list[tuple[int, int]]] = {}
    rams: dict[str, list[tuple[int, int]]] = {}
    site = re.compile(r"X(\d+)/Y(\d+)/")
    for name, cell in d["modules"][_top_module(d)]["cells"].items():
        bel = cell.get("attributes", {}).get("NEXTPNR_BEL") or cell.get("attributes", {}).get("BEL")
        m = site.match(bel or "")
        if not m:
            continue
        e = ENGINE_CELL.match(name)
        part = f"engine {e.group(1)}" if e else "glue"
        (rams if cell["type"] == "DP16KD" else pts).setdefault(part, []).append((int(m.group(1)), int(m.group(2))))
    return pts, rams


def floorplan_picture(routed: Path, png: Path, title: str) -> dict:
    """A picture of the placed top: every placed cell at its BEL's site, coloured by engine
    (the glue grey), the tile buffers' block RAMs as squares. Returns cells per part."""
    import matplotlib        # only the full run draws: keep the import off the common path
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    pts, rams = placed_cells(routed)
    colours = {"engine 0": "tab:blue", "engine 1": "tab:orange", "engine 2": "tab:green", "engine 3": "tab:red",
               "glue": "0.55"}
    fig, ax = plt.subplots(figsize=(9, 7.5))
    for part in sorted(pts):
        xs, ys = zip(*pts[part])
        ax.scatter(xs, ys, s=1.2, color=colours.get(part, "k"), alpha=0.25, lw=0,
                   label=f"{part}: {len(pts[part])} cells")
    for part in sorted(rams):
        xs, ys = zip(*rams[part])
        ax.scatter(xs, ys, s=18, marker="s", color=colours.get(part, "k"), edgecolor="k", lw=0.4)
    ax.set_xlabel("site x")
    ax.set_ylabel("site y")
    ax.invert_yaxis()
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=7, markerscale=8, loc="upper right")
    png.parent.mkdir(parents=True, exist_ok=True)
    fig.tight_layout()
    fig.savefig(png, dpi=80)
    plt.close(fig)
    return {p: len(v) for p, v in pts.items()} | {f"{p} block RAMs": len(v) for p, v in rams.items()}
