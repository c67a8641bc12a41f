"""The sweep's hole check (msr_eval.sweep_gaps) and the peers' threshold ladders."""
from msr_eval import sweep_gaps as SG
from msr_eval import sweep_space as S


def test_family_gaps_by_hand():
    pts = [SG.Point("a", "fast", "dacs", lab, f) for lab, f in (("t0", 0.70), ("t1", 0.31), ("t2", 0.25))]
    pts += [SG.Point("b", "fast", "dacs", lab, f) for lab, f in (("t0", 0.50), ("t1", 0.45), ("t2", 0.40))]
    pts += [SG.Point("a", "fast", "full", "full", 1.0)]
    gaps = SG.family_gaps(pts)
    g = gaps["dacs"]
    assert abs(g.points - 39.0) < 1e-9 and (g.scene, g.below, g.above) == ("a", "t1", "t0")
    assert gaps["full"].points == 0 and "dacs" in SG.report(gaps).splitlines()[1]


def test_dacs_gaps_on_the_test_picture():
    """Every DACS setting of the full sweep on the built-in test picture: each family's points
    are ordered and its largest gap is reported."""
    from msr_eval.sweep import Backend
    sweep = [st for st in S.settings(96, 54, S.FULL_SCALES, False) if st.family.startswith("dacs")]
    pts = SG.measure(["testimage"], ["fast"], 96, 54, sweep, Backend("image"), log=lambda m: None)
    gaps = SG.family_gaps(pts)
    assert set(gaps) == {"dacs", "dacs_lumvar", "dacs_B8", "dacs_B8_lumvar"}
    assert all(0 < g.points < 100 for g in gaps.values())


def test_dacs_ladder_has_every_sixteenth_below_one():
    fr = [t for t in S.DACS_THR if t < 1]
    assert fr == [k / 16 for k in range(16)]
    assert list(S.DACS_THR) == sorted(S.DACS_THR) and S.DACS_THR[-1] == 16384
    above = [t for t in S.DACS_THR if 1 <= t <= 8192]
    assert all(b / a <= 2 for a, b in zip(above, above[1:]))
    assert set(S.DACS_THR_QUICK) <= set(S.DACS_THR)


def test_gaps_from_records(tmp_path, capsys):
    """--records reads an evaluation's results.json (no rendering): the same gaps as the points,
    exit 1 above the limit, 2 on a file that is not one."""
    import json
    recs = [{"scene": "a", "mode": "heavy", "family": "dacs", "label": lab, "traced_fraction": f}
            for lab, f in (("t0", 0.73), ("t1", 0.60), ("t2", 0.55))]
    recs += [{"scene": "a", "mode": "heavy", "family": "multi_L2_T16", "label": "x", "traced_fraction": 0.2}]
    f = tmp_path / "results.json"
    f.write_text(json.dumps({"records": recs}))
    pts = SG.record_points(f, ("dacs",))
    assert [p.label for p in pts] == ["t0", "t1", "t2"]
    gaps = SG.family_gaps(SG.record_points(f))
    assert abs(gaps["dacs"].points - 13.0) < 1e-9 and gaps["multi_L2_T16"].points == 0
    assert SG.main(["--records", str(f)]) == 1
    assert "dacs" in capsys.readouterr().out
    assert SG.main(["--records", str(f), "--limit", "20"]) == 0
    bad = tmp_path / "bad.json"
    bad.write_text("{}")
    assert SG.main(["--records", str(bad)]) == 2
