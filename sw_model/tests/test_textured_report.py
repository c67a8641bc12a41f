"""msr_eval.textured: the results.md sections on textured scenes and the G-buffer rule, on a
hand-made result (two scenes, four families, two settings each)."""
from msr_eval.metrics import summarise
from msr_eval.textured import section


def _rec(scene, fam, frac, db, label):
    return {"scene": scene, "mode": "fast", "family": fam, "label": label, "traced_fraction": frac, "psnr": db, "setting": {}}


def _result():
    recs = []
    # (family, [(fraction, dB) at the two settings a, b]) for the textured duck and the plain cornell
    duck = {"multi_L3_T16": [(0.10, 30.0), (0.30, 50.0)],            # 40 dB at 0.20
            "multi_L3_T16_lindilate": [(0.10, 32.0), (0.20, 42.0)],  # 40 dB at 0.18
            "multi_L3_T16_gbuf": [(0.12, 40.0), (0.20, 45.0)],       # 40 dB at <= 0.12
            "multi_L3_T16_gbuflindilate": [(0.10, 30.0), (0.20, 36.0)]}   # not reached
    cornell = {"multi_L3_T16": [(0.05, 38.0), (0.07, 42.0)],         # 40 dB at 0.06
               "multi_L3_T16_lindilate": [(0.05, 40.0), (0.07, 44.0)],    # <= 0.05
               "multi_L3_T16_gbuf": [(0.05, 36.0), (0.09, 44.0)],    # 0.07
               "multi_L3_T16_gbuflindilate": [(0.05, 40.0), (0.07, 45.0)]}  # <= 0.05
    for scene, fams in (("cornell", cornell), ("duck", duck)):
        for fam, pts in fams.items():
            for label, (f, db) in zip("ab", pts):
                recs.append(_rec(scene, fam, f, db, label))
    needed, curves, head = summarise(recs, ["fast"])
    return {"config": {"scenes": ["cornell", "duck"], "modes": ["fast"]}, "records": recs,
            "needed_fraction": needed, "headline": head}


def test_sections_by_hand():
    md = "\n".join(section(_result()))
    assert "## Textured scenes" in md and "1 of the 2 scenes carry diffuse textures: `duck`" in md
    rows = {line.split(" | ")[0].lstrip("| "): line for line in md.splitlines() if line.startswith("| ")}
    # 35 dB on duck: patent 0.10 + 5/20 * 0.20, lindilate 0.10 + 3/10 * 0.10, gbuflindilate
    # 0.10 + 5/6 * 0.10; textured table: duck's 35 / 40, then the textured mean (duck alone), then the others' mean (cornell)
    assert rows["patent, L=3, T=16"].startswith("| patent, L=3, T=16 | 15.0 / 20.0 | 15.0 / 20.0 | <= 5.0 / 6.0 |")
    # the G-buffer table: cornell then duck (marked textured), four families each
    assert "| cornell | <= 5.0 / 6.0 | <= 5.0 / <= 5.0 | <= 5.0 / 7.0 | <= 5.0 / <= 5.0 |" in md
    assert "| duck * | 15.0 / 20.0 | 13.0 / 18.0 | <= 12.0 / <= 12.0 | 18.3 / not reached |" in md
    # 40 dB: gbuf beats the patent on duck (0.12 < 0.20), loses on cornell (0.07 > 0.06);
    # gbuflindilate ties lindilate on cornell (both <= 0.05) and misses 40 dB on duck
    assert "G-buffer rule (gbuf), L=3, T=16 against the patent, fast: 1 / 1 / 0" in md
    assert "gbuflindilate), L=3, T=16 against lindilate, fast: 0 / 1 / 1" in md
    assert "### How textures change the headline" in md and "Textured scenes alone (1)" in md


def test_no_textured_scene_no_gbuffer_family_no_section():
    r = _result()
    r["config"]["scenes"] = ["cornell"]
    r["records"] = [x for x in r["records"] if x["scene"] == "cornell" and x["family"] == "multi_L3_T16"]
    r["needed_fraction"], _, r["headline"] = summarise(r["records"], ["fast"])
    assert section(r) == []
