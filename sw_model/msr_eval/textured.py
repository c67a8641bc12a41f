"""docs/results.md sections for textured content and the G-buffer rule.

`section(result)` returns the markdown lines that report.write_docs puts after the per-scene
tables: the textured scenes' traced fraction for 35 and 40 dB by method and rule, the
headline over textured and untextured scenes apart, and the G-buffer edge rule
(msr_eval.gbuffer_rule) against the patent's rule and lindilate scene by scene.

    python -m msr_eval.textured out/eval/results.json     # the same sections on stdout
"""
from __future__ import annotations

import json
import sys

from .gbuffer_rule import DEFAULT_DEPTH_TOL, SWEEP_FAMILIES
from .metrics import rule_comparison, summarise
from .present import FAMILY_NAMES, needed_cell
from .scenes import TEXTURED_SCENES

# What carries the texture in each textured scene (docs/renderer.md, section Textures).
TEXTURES = {"duck": "`duckCM.tga` (Collada)", "teapots": "an earth map on one teapot (Collada)",
            "spider": "`SpiderTex.jpg` and `drkwood2.jpg` (OBJ + .mtl)",
            "CesiumMilkTruck": "`CesiumMilkTruck.png` (glTF 1.0)",
            "BoxTextured": "`CesiumLogoFlat.png` (glTF 2.0)"}
GB_COMPARE = ("multi_L3_T16", "multi_L3_T16_lindilate", *SWEEP_FAMILIES)


def _subset(records, scenes, modes):
    keep = set(scenes)
    recs = [r for r in records if r["scene"] in keep]
    return summarise(recs, modes) if recs else ({}, {}, {})


def _headline_line(h):
    b, c = h.get("best_psnr_at_most_15pct"), h.get("cheapest_40db_mean")
    out = []
    if b:
        out.append(f"best mean PSNR with <= 15 % traced {b['psnr_mean']:.2f} dB (worst scene {b['psnr_min']:.2f}) "
                   f"at {100 * b['traced_fraction']:.1f} %, {FAMILY_NAMES.get(b['family'], b['family'])} {b['label']}")
    if c:
        out.append(f"cheapest >= 40 dB mean {100 * c['traced_fraction']:.1f} % "
                   f"({FAMILY_NAMES.get(c['family'], c['family'])} {c['label']})")
    else:
        out.append("no setting reaches a 40 dB mean")
    return "; ".join(out)


def _f40(needed, scene, mode, fam):
    d = needed.get(scene, {}).get(mode, {}).get(fam)
    return None if d is None else d["40"]


def section(result: dict) -> list[str]:
    cfg = result["config"]
    scenes, modes, records = cfg["scenes"], cfg["modes"], result["records"]
    needed = result["needed_fraction"]
    textured = [s for s in scenes if s in TEXTURED_SCENES]
    plain = [s for s in scenes if s not in TEXTURED_SCENES]
    L = []
    w = L.append
    if textured:
        w("## Textured scenes\n")
        w(f"{len(textured)} of the {len(scenes)} scenes carry diffuse textures: "
          + ", ".join(f"`{s}` ({TEXTURES.get(s, 'textured')})" for s in textured)
          + ". Every model-file scene also stands on the renderer's procedural checker floor. "
          "Traced fraction (%) for 35 / 40 dB as in the tables above; the two mean columns are "
          "the set-mean curves over the textured and over the other scenes.\n")
        _, _, head_t = _subset(records, textured, modes)
        _, _, head_p = _subset(records, plain, modes)
        for mode in modes:
            fams = [f for f in FAMILY_NAMES if f != "full" and any(f in needed[s].get(mode, {}) for s in textured)]
            w(f"### {mode} renderer, textured scenes\n")
            w("| method | " + " | ".join(f"{s} 35 / 40" for s in textured)
              + " | textured mean 35 / 40 | other scenes' mean 35 / 40 |")
            w("|---" * (len(textured) + 3) + "|")
            for f in fams:
                cells = [needed_cell(needed[s].get(mode, {}).get(f)) for s in textured]
                cells.append(needed_cell(head_t.get(mode, {}).get("set_needed", {}).get(f)))
                cells.append(needed_cell(head_p.get(mode, {}).get("set_needed", {}).get(f)))
                w(f"| {FAMILY_NAMES[f]} | " + " | ".join(cells) + " |")
            w("")
        w("### How textures change the headline\n")
        for mode in modes:
            w(f"- **{mode}**, all {len(scenes)} scenes: {_headline_line(result['headline'].get(mode, {}))}.")
            if plain:
                w(f"  Without the textured scenes ({len(plain)}): {_headline_line(head_p.get(mode, {}))}.")
            w(f"  Textured scenes alone ({len(textured)}): {_headline_line(head_t.get(mode, {}))}.")
        w("")

    if not any(f in needed[s].get(m, {}) for s in scenes for m in modes for f in SWEEP_FAMILIES):
        return L
    w("## The G-buffer rule against the patent's rule and lindilate\n")
    w("`gbuf` = the patent's test, and a trace is forced where A and B differ in material id or "
      f"in depth by more than {DEFAULT_DEPTH_TOL:g} of the nearer one; `gbuflindilate` = the same edge test "
      "inside lindilate's base decision, then dilated (docs/rules.md, \"Rule gbuf\"; "
      "`sw_model/msr_eval/gbuffer_rule.py`). All four at L=3, T=16 over the same threshold scales. "
      "Traced fraction (%) for 35 / 40 dB per scene; `*` marks a textured scene.\n")
    wins = {}
    for mode in modes:
        w(f"### {mode} renderer\n")
        w("| scene | " + " | ".join(FAMILY_NAMES[f] for f in GB_COMPARE) + " |")
        w("|---" * (len(GB_COMPARE) + 1) + "|")
        for s in scenes:
            w(f"| {s}{' *' if s in TEXTURED_SCENES else ''} | "
              + " | ".join(needed_cell(needed[s].get(mode, {}).get(f)) for f in GB_COMPARE) + " |")
            for rule, base in (("multi_L3_T16_gbuf", "multi_L3_T16"),
                               ("multi_L3_T16_gbuflindilate", "multi_L3_T16_lindilate")):
                a, b = _f40(needed, s, mode, rule), _f40(needed, s, mode, base)
                if a is None or b is None:
                    continue
                k = wins.setdefault((mode, rule), [0, 0, 0])
                fa, fb = a["fraction"], b["fraction"]
                if fa is not None and (fb is None or fa < fb - 1e-4):
                    k[0] += 1
                elif fb is not None and (fa is None or fa > fb + 1e-4):
                    k[1] += 1
                else:
                    k[2] += 1
        w("")
    w("At 40 dB, scenes where the G-buffer rule needs fewer / more / the same traced pixels "
      "(`<=` bounds compared as values): "
      + "; ".join(f"{FAMILY_NAMES[rule]} against {'the patent' if rule.endswith('gbuf') else 'lindilate'}, "
                  f"{mode}: {k[0]} / {k[1]} / {k[2]}" for (mode, rule), k in wins.items()) + ".\n")
    w("PSNR difference at equal traced fraction (the base rule interpolated along its Pareto "
      "front, over the rule's settings inside its range), mean per scene:\n")
    cmp = {**rule_comparison(records, "multi_L3_T16", ("multi_L3_T16_gbuf",)),
           **rule_comparison(records, "multi_L3_T16_lindilate", ("multi_L3_T16_gbuflindilate",))}
    for fam, base in (("multi_L3_T16_gbuf", "patent"), ("multi_L3_T16_gbuflindilate", "lindilate")):
        for mode, per in cmp.get(fam, {}).items():
            w(f"- {FAMILY_NAMES[fam]} - {base}, {mode}: " + "; ".join(
                f"{s} {v['mean_delta_db']:+.2f} dB (min {v['min_delta_db']:+.2f}, max {v['max_delta_db']:+.2f})"
                if v["n"] else f"{s} no overlap" for s, v in sorted(per.items())))
    w("")
    return L


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if len(argv) != 1:
        print("usage: python -m msr_eval.textured RESULTS.json", file=sys.stderr)
        return 2
    print("\n".join(section(json.loads(open(argv[0]).read()))))
    return 0


if __name__ == "__main__":
    sys.exit(main())
