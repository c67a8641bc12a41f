"""The small evaluation run (make eval) as part of make test, its analysis helpers, and the
sweep on Dask distributed against the serial sweep."""
import json
import math

import pytest

from msr_eval import sweep as S
from msr_eval.executors import SerialExecutor, make_executor
from msr_eval import cli as ev
from msr_eval.metrics import fraction_for, pareto


def test_pareto_and_fraction_for_by_hand():
    pts = [(0.10, 30.0), (0.20, 36.0), (0.15, 29.0), (0.40, 44.0), (0.30, 35.0)]
    # (0.15, 29) and (0.30, 35) are dominated
    assert pareto(pts) == [(0.10, 30.0), (0.20, 36.0), (0.40, 44.0)]
    f, how = fraction_for(pts, 40.0)      # between (0.2, 36) and (0.4, 44): 0.2 + 4/8 * 0.2
    assert how == "interp" and f == pytest.approx(0.30)
    f, how = fraction_for(pts, 35.0)      # between (0.1, 30) and (0.2, 36): 0.1 + 5/6 * 0.1
    assert how == "interp" and f == pytest.approx(0.1 + 0.1 * 5 / 6)
    assert fraction_for(pts, 25.0) == (0.10, "at_or_below")
    assert fraction_for(pts, 50.0) == (None, "not_reached")


def test_level_thresholds_and_fov_gain():
    assert S.level_thr(3, 4) == (4, 8, 16)
    assert S.level_thr(2, 200) == (200, 255)
    assert S.level_thr(3, 0.25) == (1, 1, 1) and S.level_thr(3, 0.5) == (1, 1, 2)
    # 1920 / 16 = 120 tiles: r2 up to 119 half-tiles; gain 2 adds (2 * 119) >> 4 = 14 at the edge
    assert S.fov_gain_for(1920, 1080, 16) == 2


def test_small_eval_run(tmp_path):
    """The quick run end to end on one scene (Embree when built, else the test picture), every
    metric against both references (FLIP, about 0.3 s a call whatever the size, is most of the
    time: one scene keeps it near the cost the test had before the converged reference)."""
    args = ["--width", "64", "--height", "48", "--max-scenes", "1", "--out", str(tmp_path),
            "--all-metrics", "--workers", "0", "--no-progress", "--conv-grid", "8"]
    backend = S.Backend("auto")
    if backend.embree:
        args += ["--modes", "fast"]
    res = ev.main(args)
    data = json.loads((tmp_path / "results.json").read_text())
    assert data["config"]["width"] == 64 and len(data["records"]) == len(res["records"])
    W, H = 64, 48
    for scene in data["config"]["scenes"]:
        recs = {(r["family"], r["label"]): r for r in data["records"] if r["scene"] == scene}
        full = recs[("full", "full")]
        assert full["traced"] == W * H and full["psnr"] == math.inf      # identical to the reference
        # grid 2 traces 0, 2, .., 62, 63 x 0, 2, .., 46, 47 (last row/column added)
        assert recs[("grid2", "grid 2")]["traced"] == 33 * 25
        assert recs[("checkerboard", "checkerboard")]["traced"] == W * H // 2
        for r in recs.values():
            assert 0 < r["traced_fraction"] <= 1
            assert r["psnr"] > 10
            assert 0 <= r["flip"] <= 1 and -1 <= r["ssim"] <= 1
            # scored against the converged reference too
            assert r["psnr_conv"] > 10
            assert 0 <= r["flip_conv"] <= 1 and -1 <= r["ssim_conv"] <= 1
            assert r["tile32_min_psnr_conv"] <= r["psnr_conv"] + 1e-9
        # the peers: DACS over its threshold, VRS-like at 8x8 and 16x16, honest counts
        dacs = sorted(r["traced_fraction"] for (f, _), r in recs.items() if f == "dacs")
        assert len(dacs) == len(S.DACS_THR_QUICK) and dacs[0] < dacs[-1] <= 1.0
        for fam in ("vrs_T8", "vrs_T16"):
            fr = [r["traced_fraction"] for (f, _), r in recs.items() if f == fam]
            assert len(fr) == len(S.VRS_THR_QUICK) and min(fr) >= 1 / 16 - 1e-9
        if backend.embree:      # the noise-free test picture has no converged reference to speak of
            conv = [i for i in data["full_render"] if i["scene"] == scene][0]["converged"]
            assert conv["spp"] == 64 and conv["psnr_two_seeds"] > 20
            assert recs[("full", "full")]["psnr_conv"] is not None
    assert (tmp_path / f"curves_{data['config']['modes'][0]}.png").is_file()
    assert (tmp_path / f"fronts_conv_{data['config']['modes'][0]}.png").is_file()
    assert data["converged"]["needed_fraction"] and data["converged"]["headline"]
    docs = tmp_path / "docs"
    docs.mkdir()
    ev.main(["--report-only", "--out", str(tmp_path), "--docs-dir", str(docs)])
    text = (docs / "results.md").read_text()
    assert text.index("## The question") < text.index("## How to re-run")
    assert (docs / "results" / "full_render.md").is_file()
    assert "DACS" in text and "VRS-like" in text
    assert data["needed_fraction"] and data["headline"]


def test_dask_sweep_equals_serial(tmp_path):
    """A small sweep on a LocalCluster with two workers gives the serial run's records, bit for
    bit (all but the wall times), and the per-scene cache then answers a second run."""
    backend = S.Backend("auto")
    scenes = backend.builtin_scenes()[:2]
    modes = ["fast"] if backend.embree else ["image"]

    def sweep(executor, cache):
        cfg = S.SweepConfig(64, 48, (1, 8), True, False, cache, conv_grid=4)
        try:
            recs, _, _ = S.run_sweep(backend, scenes, modes, cfg, executor, log=lambda s: None,
                                     show_progress=False)
        finally:
            executor.close()
        return [{k: v for k, v in r.items() if k != "decide_s"} for r in recs]

    serial = sweep(SerialExecutor(), tmp_path / "serial")
    dask = sweep(make_executor(workers=2), tmp_path / "dask")
    assert len(serial) == len(S.settings(64, 48, (1, 8), True)) * len(scenes) * len(modes)
    assert dask == serial
    assert any(r["key_setting"] and "ssim" in r for r in serial)
    assert all("psnr_conv" in r for r in serial) and any("ssim_conv" in r for r in serial)
    again = sweep(SerialExecutor(), tmp_path / "dask")     # every scene from the cache
    assert again == serial



def test_full_size_store_resumes_and_recomputes_only_changed_families(tmp_path, monkeypatch):
    """The full-size flow at a small size: the heavy mode alone gets a converged
    reference, its sample count from the ladder file, one seed; references and records go to
    the store; a second run takes everything from the store (nothing rendered at the converged
    count, nothing computed); a family whose signature changes is computed alone."""
    from msr_eval import conv_store as CS
    from msr_eval import reference as REF
    backend = S.Backend("auto")
    # the heavy renderer's converged flow needs Embree; make test builds it (mk/renderer.mk)
    assert backend.embree, "the renderer library is not built: make renderer"
    ladder = tmp_path / "ladder.json"
    ladder.write_text(json.dumps({"scenes": {"duck": {"spp": 16}}}))
    monkeypatch.setattr(CS, "LADDER", ladder)
    store = tmp_path / "store"

    def run(cache, log):
        cfg = S.SweepConfig(48, 32, (1, 8), False, False, cache, conv_modes=("heavy",), conv_ladder=True,
                            conv_check=False, store=store)
        recs, _, infos = S.run_sweep(backend, ["duck"], ["fast", "heavy"], cfg, SerialExecutor(),
                                     log=log.append, show_progress=False)
        return recs, infos

    log1 = []
    recs, infos = run(tmp_path / "c1", log1)
    assert infos[("duck", "heavy")]["converged"]["spp"] == 16 and "converged" not in infos[("duck", "fast")]
    assert "psnr_two_seeds" not in infos[("duck", "heavy")]["converged"]
    assert all("psnr_conv" in r for r in recs if r["mode"] == "heavy")
    assert not any("psnr_conv" in r for r in recs if r["mode"] == "fast")
    assert (store / "48x32" / "duck_heavy_conv.png").is_file()
    calls = []
    monkeypatch.setattr(REF, "task_converged", lambda *a: calls.append(a))
    log2 = []
    again, _ = run(tmp_path / "c2", log2)                 # a new cache folder: only the store
    strip = lambda rs: [{k: v for k, v in r.items() if k != "decide_s"} for r in rs]   # noqa: E731
    assert not calls and any("from" in s and "store" in s for s in log2)
    assert len(again) == len(recs)
    for a, b in zip(strip(again), strip(recs)):
        assert a.keys() == b.keys()
        for k in a:
            assert a[k] == pytest.approx(b[k], rel=1e-4) if isinstance(a[k], float) else a[k] == b[k]
    # one family's code changes: only its settings are computed again
    real = S.SweepConfig.family_signatures
    monkeypatch.setattr(S.SweepConfig, "family_signatures",
                        lambda self: {**real(self), "dacs": "changed"})
    log3 = []
    run(tmp_path / "c3", log3)
    n_dacs = sum(1 for st in S.settings(48, 32, (1, 8), False) if st.family == "dacs")
    assert any(f"{n_dacs} to compute" in s for s in log3), log3
    # a reference of another renderer output (its full-render hash differs) is not taken
    meta = store / "48x32" / "duck_heavy_conv.json"
    m = json.loads(meta.read_text())
    m["full_render_sha"] = "0" * 16
    meta.write_text(json.dumps(m))
    assert CS.Store(48, 32, store).load_ref("duck", "heavy", "1" * 16, 4, REF.CONV_SEEDS[0]) is None


def test_store_pack_round_trip():
    from msr_eval import conv_store as CS
    recs = [{"scene": "a", "family": "f", "label": "x", "psnr": 41.123456789, "setting": {"thr": 3}},
            {"scene": "a", "family": "g", "label": "y", "psnr": None, "ssim": 0.5}]
    back = CS.unpack(CS.pack(recs))
    assert back[0]["psnr"] == pytest.approx(41.123, abs=1e-3) and "ssim" not in back[0]
    assert back[1] == recs[1]


def test_family_signatures_follow_behaviour_not_source(tmp_path, monkeypatch):
    """A record is kept while its family computes the same on the probe frame: a change to one
    method's output changes that method's families' signatures and no other; the same code
    gives the same signatures in a new process (the memo is cleared here)."""
    import numpy as np
    from msr_eval import dacs as D
    from msr_eval import fingerprint as FP
    cfg = S.SweepConfig(96, 64, (1, 8), False, False, tmp_path)
    monkeypatch.setattr(S, "_SIGNATURES", {})
    before = cfg.family_signatures()
    monkeypatch.setattr(S, "_SIGNATURES", {})
    assert cfg.family_signatures() == before
    real = D.dacs

    def changed(renderer, w, h, **kw):          # one pixel of every DACS frame differs
        res = real(renderer, w, h, **kw)
        res.frame[0, 0, 0] ^= 1
        return res
    monkeypatch.setattr(D, "dacs", changed)
    monkeypatch.setattr(S, "_SIGNATURES", {})
    after = cfg.family_signatures()
    assert {f for f in before if before[f] != after[f]} == {f for f in before if f.startswith("dacs")}
    # the probe has partial tiles on both axes and G-buffer edges for the G-buffer rule
    ref, conv, (prim, mat, depth) = FP.probe()
    assert FP.PROBE_W % 32 and FP.PROBE_H % 32 and ref.shape == conv.shape
    assert len(np.unique(mat)) >= 3 and not np.array_equal(ref, conv)


def test_temporal_sequences():
    """msr_eval.temporal: the orbit keeps the eye's distance to the target and swings ORBIT_DEG
    from the first frame to the last; every setting has a PSNR and traced fraction per frame and
    a flicker per frame change; a method that traces everything has no error and no flicker."""
    import math
    import numpy as np
    from msr_eval import temporal as T
    from msr_model.embree import open_renderer
    with open_renderer("cornell", 48, 32) as r:
        view = r.view()
    p = T.orbit_path(view, 11)
    (e0, t0, _), (e1, _, _) = p.at(0), p.at(10)
    d0 = math.dist(e0, t0)
    assert math.dist(e1, t0) == pytest.approx(d0, rel=1e-9)
    v0, v1 = np.subtract(e0, t0)[[0, 2]], np.subtract(e1, t0)[[0, 2]]
    ang = math.degrees(math.acos(np.dot(v0, v1) / (np.linalg.norm(v0) * np.linalg.norm(v1))))
    assert ang == pytest.approx(T.ORBIT_DEG, abs=1e-6)
    res = T.run(("cornell",), 3, 48, 32, log=lambda m: None)
    ms = res["scenes"]["cornell"]["methods"]
    assert len(ms) == len(T.settings())
    for m in ms.values():
        assert len(m["psnr"]) == 3 and len(m["traced"]) == 3 and len(m["flicker"]) == 2
        assert all(0 < t <= 1 for t in m["traced"]) and m["flicker_mean"] >= 0
    a = np.zeros((4, 4, 3), np.int16)
    assert T.flicker(a, a) == 0 and T.flicker(a, a + 2) == pytest.approx(2.0)
    assert "Sequences" in T.markdown(res, "x.png")
