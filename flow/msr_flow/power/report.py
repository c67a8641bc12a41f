"""build/asic/power.json from the rules' results; the balance of decision energy against the
energy of the rays the decisions save (per scene of the 1080p head-to-head); its plot."""
from __future__ import annotations

import json
import re
from pathlib import Path

from ..filelist import ROOT
from . import memory, scaling
from .model import SLEW_NS, UTILISATION, VDD, WIRE_PF_PER_UM
from .run import RuleResult

RESULTS = ROOT / "data" / "results.json"
PLOT = ROOT / "docs" / "img" / "power_balance.png"
# RayCore (J.-H. Nah et al., "RayCore: A ray-tracing hardware architecture for mobile devices", ACM
# Transactions on Graphics 33(5), 2014): about 1 W for 239 Mrays/s at 28 nm.
RAYCORE = {"nj_per_ray": 1.0 / 239e6 * 1e9, "node_nm": 28,
           "source": "J.-H. Nah et al., \"RayCore: A ray-tracing hardware architecture for mobile devices\", "
                     "ACM TOG 33(5), 2014: about 1 W for 239 Mrays/s at 28 nm"}
NODES = (28, 7)


def mw(pj_per_clock: float, mhz: float) -> float:
    return pj_per_clock * mhz * 1e-3


def rule_summary(r: RuleResult) -> dict:
    f = r.clock_mhz
    n_eng = len(r.engines)
    engs = list(r.engines.values())
    eng_dyn_pj = sum(e.dynamic_pj for e in engs) / n_eng                 # per engine, per clock
    eng_sram_pj = sum(r.sram_pj.values()) / n_eng / r.cycles
    eng_leak_mw = engs[0].leakage_nw * 1e-6
    glue = r.glue
    frame_s = r.cycles / (f * 1e6)
    eng_frame_pj = sum(e.dynamic_pj for e in engs) * r.cycles + sum(r.sram_pj.values()) \
        + n_eng * eng_leak_mw * 1e-3 * frame_s * 1e12
    top_frame_pj = eng_frame_pj + glue.dynamic_pj * r.cycles + glue.leakage_nw * 1e-9 * frame_s * 1e12
    units: dict[str, float] = {}
    for e in engs:
        for u, v in e.by_unit.items():
            units[u] = units.get(u, 0.0) + v / n_eng
    flops = sum(e.flops for e in engs) + glue.flops
    traced = sum(e.flops_traced for e in engs) + glue.flops_traced
    act = f"vcd: cornell {r.width}x{r.height} frame, rule {r.rule} ({r.cycles} clocks, make sim harness with FST)"
    logic_only = sum(e.dynamic_pj for e in engs) * r.cycles + n_eng * eng_leak_mw * 1e-3 * frame_s * 1e12
    return {
        "rule": r.rule, "width": r.width, "height": r.height, "cycles": r.cycles, "pixels": r.pixels,
        "decisions": r.decisions, "frame_us_at_clock": round(frame_s * 1e6, 3),
        "modules": {
            "msr_tile_engine": {
                "dynamic_mw": round(mw(eng_dyn_pj + eng_sram_pj, f), 3),
                "logic_dynamic_mw": round(mw(eng_dyn_pj, f), 3),
                "clock_mw": round(mw(sum(e.clock_pj for e in engs) / n_eng, f), 3),
                "tile_buffer_mw": round(mw(eng_sram_pj, f), 3),
                "leakage_mw": round(eng_leak_mw, 4), "clock_mhz": f, "activity": act,
                "flip_flops": engs[0].flops, "flip_flops_traced": round(sum(e.flops_traced for e in engs) / n_eng),
                "mean_flop_toggles_per_clock": round(sum(e.mean_flop_toggle for e in engs) / n_eng, 5),
                "by_unit_mw": {u: round(mw(v, f), 3) for u, v in sorted(units.items(), key=lambda x: -x[1])},
                "tile_buffer_accesses_per_engine": {
                    k: round(sum(a[k] for a in r.sram_accesses.values()) / n_eng) for k in ("reads", "writes")},
            },
            "msr_top": {
                "dynamic_mw": round(mw(sum(e.dynamic_pj for e in engs) + glue.dynamic_pj, f)
                                    + mw(sum(r.sram_pj.values()) / r.cycles, f), 3),
                "glue_dynamic_mw": round(mw(glue.dynamic_pj, f), 3),
                "glue_clock_mw": round(mw(glue.clock_pj, f), 3),
                "leakage_mw": round(n_eng * eng_leak_mw + glue.leakage_nw * 1e-6, 4), "clock_mhz": f,
                "activity": act, "flip_flops": flops, "flip_flops_traced": traced,
                "glue_by_unit_mw": {u: round(mw(v, f), 3) for u, v in
                                    sorted(glue.by_unit.items(), key=lambda x: -x[1])[:12]},
            },
        },
        "activity_coverage": round(traced / flops, 4) if flops else 0.0,
        "pj_per_decision": round(eng_frame_pj / r.decisions, 2),
        "pj_per_decision_logic_only": round(logic_only / r.decisions, 2),
        "pj_per_pixel": round(top_frame_pj / r.pixels, 2),
        "seconds": r.seconds,
    }


def family_params(family: str) -> tuple[int, int]:
    m = re.match(r"multi_L(\d)_T(\d+)", family)
    return (int(m.group(1)), int(m.group(2))) if m else (3, 16)


def balance(pj_per_decision: dict[str, float]) -> list[dict]:
    """Per scene and rule of the 1080p head-to-head: decision energy per frame against the energy
    of the rays it saves at RayCore's cost (both at 28 nm: ours scaled)."""
    from msr_model.budget import grid_count
    from msr_model.spec import Params
    data = json.loads(RESULTS.read_text())
    W, H = data["config"]["width"], data["config"]["height"]
    f28 = scaling.from_180(28)
    rows = []
    for scene, h in data["head_to_head"].items():
        for rule, pj in pj_per_decision.items():
            need = h["groups"].get(rule, {}).get("needed", {}).get("eq-1", {})
            frac = need.get("fraction")
            if frac is None:
                continue
            levels, tile = family_params(need.get("family", ""))
            grid = grid_count(W, H, Params(tile=tile, levels=levels, thr=(0,) * levels, extension=levels > 3))
            decisions = W * H - grid
            saved = (1.0 - frac) * W * H
            dec_uj = pj * decisions * 1e-6
            rows.append({"scene": scene, "rule": rule, "family": need.get("family"), "traced_fraction": frac,
                         "decisions": decisions, "decision_uj_180nm": round(dec_uj, 1),
                         "decision_uj_28nm": round(dec_uj * f28, 2), "rays_saved": round(saved),
                         "rays_saved_uj_28nm": round(saved * RAYCORE["nj_per_ray"] * 1e-3, 1),
                         "ratio_28nm": round(saved * RAYCORE["nj_per_ray"] * 1e3 / (pj * f28 * decisions), 1)})
    return rows


def build(results: dict[str, RuleResult], stamp: dict) -> dict:
    rules = {k: rule_summary(v) for k, v in results.items()}
    head = rules.get("patent") or next(iter(rules.values()))
    out = {
        "what": "Power of the tile engine and the default top at the OSU 0.18 um library's typical corner "
                "from the switching activity of a simulated frame (make power, msr_flow.power)",
        "modules": head["modules"],
        "pj_per_decision": head["pj_per_decision"],
        "pj_per_decision_logic_only": head["pj_per_decision_logic_only"],
        "pj_per_pixel": head["pj_per_pixel"],
        "activity_coverage": head["activity_coverage"],
        "headline_rule": head["rule"],
        "scaled": [{"node_nm": n, "pj_per_decision": round(head["pj_per_decision"] * scaling.from_180(n), 3),
                    "pj_per_decision_logic_only": round(head["pj_per_decision_logic_only"] * scaling.from_180(n), 3),
                    "source": scaling.source(n)} for n in NODES],
        "rules": rules,
        "raycore": RAYCORE,
        "balance": balance({k: v["pj_per_decision"] for k, v in rules.items()}),
        "method": {
            "activity": "every flip-flop output, input and macro output from the frame's FST (toggles per clock, "
                        "time at 1), keyed by the register names the mapped netlist keeps; combinational nets by "
                        "propagation through the liberty functions (transition density, independent inputs); "
                        "a flip-flop not found in the dump takes the mean toggle rate of its module",
            "energy": f"liberty internal energy per transition at the net's load and a {SLEW_NS} ns input slew; "
                      f"C V^2 / 2 per toggle at {VDD} V; leakage: cell_leakage_power",
            "loads": f"pin capacitances plus a wire estimate of one cell pitch per pin on the net (pitch of the "
                     f"mean cell at {UTILISATION:.0%} utilisation), {WIRE_PF_PER_UM * 1e3:.3f} fF/um (metal2 of "
                     "osu018_stdcells.lef: area and two edges); the library has no wire-load model",
            "clock": "ideal clock net (two toggles per clock, its wire estimate), every flip-flop clocked every "
                     "clock: no clock gating in the RTL",
            "opensta": "OpenSTA 2.0.17's set_power_activity -pins fails (its Tcl calls a missing get_pins_error) and "
                       "sta::set_power_pin_activity is ignored by its report_power: per-net activity from a "
                       "simulation cannot enter it, so the same liberty figures are applied here",
            "tile_buffers": memory.RULE, "tile_buffer_source": memory.SOURCE,
            "not_counted": "the tile-buffer macros' leakage; the frame-buffer writer's and FIFOs' arrays are "
                           "flip-flops (counted in the logic)",
        },
        **stamp,
    }
    return out


def plot(rows: list[dict], path: Path = PLOT) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rules = sorted({r["rule"] for r in rows})
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    fig, ax = plt.subplots(figsize=(11, 4.5))
    w = 0.8 / (2 * len(rules))
    for k, rule in enumerate(rules):
        by = {r["scene"]: r for r in rows if r["rule"] == rule}
        xs = [i + (2 * k) * w - 0.4 + w / 2 for i in range(len(scenes))]
        ax.bar(xs, [by[s]["decision_uj_28nm"] if s in by else 0 for s in scenes], w,
               label=f"{rule}: decisions (28 nm, scaled)")
        ax.bar([x + w for x in xs], [by[s]["rays_saved_uj_28nm"] if s in by else 0 for s in scenes], w,
               label=f"{rule}: rays saved at RayCore's 4.2 nJ")
    ax.set_yscale("log")
    ax.set_xticks(range(len(scenes)))
    ax.set_xticklabels(scenes, rotation=30, ha="right")
    ax.set_ylabel("energy per 1920x1080 frame (uJ)")
    ax.set_title("What deciding costs against the rays it saves (quality: full render less 1 dB)")
    ax.legend(fontsize=8, ncol=2)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)
