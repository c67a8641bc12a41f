"""The synthesis flow's bookkeeping (no Yosys run): parameters read from the RTL, the
bottom-up roll-up of the top, memory bits from an RTLIL dump, the job graph (its plan and the
order and failure rules of its runner), the report's merge and the page rendered from it."""
import json
import re
import subprocess

import pytest

from msr_flow import synth
from msr_flow.filelist import rtl_digest
from msr_flow.synth import cli, floorplan, page, report


def test_default_params_read_from_the_module_headers():
    files = synth.read_filelist()
    top = synth.default_params(files, "msr_top")
    assert {"NUM_ENGINES", "MAX_OUTSTANDING", "NUM_CTX", "AXI_DATA_W"} <= set(top)
    eng = synth.default_params(files, "msr_tile_engine")
    assert {"NUM_CTX", "MAX_OUTSTANDING"} <= set(eng)
    with pytest.raises(ValueError):
        synth.default_params(files, "no_such_module")


def part(cells, ffs, mem, levels, bb_inst=0, latches=0):
    return {"cells": cells, "flip_flops": ffs, "latches": latches, "memory_bits": mem, "logic_levels": levels,
            "blackbox": None, "blackbox_instances": bb_inst, "params": {}, "seconds": 1.0}


def test_top_is_glue_plus_n_engines():
    top = synth.compose(part(1000, 100, 50, 40, bb_inst=4), part(300, 30, 7, 60, latches=0), 4, "inferred")
    assert (top["cells"], top["flip_flops"], top["memory_bits"], top["logic_levels"]) == (2200, 220, 78, 60)
    assert synth.compose(part(1, 1, 0, 90, bb_inst=2), part(1, 1, 0, 10, latches=3), 2, "x")["latches"] == 6
    assert synth.compose(part(1, 1, 0, 90, bb_inst=2), part(1, 1, 0, 10), 2, "x")["logic_levels"] == 90


def test_compose_refuses_a_glue_with_the_wrong_number_of_engines():
    with pytest.raises(RuntimeError, match="expected 4"):
        synth.compose(part(1000, 100, 0, 40, bb_inst=3), part(300, 30, 0, 60), 4, "inferred")


def test_memory_bits_sum_every_memory_cell():
    rtlil = ("cell $mem_v2 $a\n  parameter \\SIZE 1024\n  parameter \\WIDTH 29\nend\n"
             "cell $mem_v2 $b\n  parameter \\WIDTH 8\n  parameter \\SIZE 4\nend\n")
    assert synth.memory_bits(rtlil) == 1024 * 29 + 32
    assert synth.memory_bits("") == 0


def test_pixel_rate_per_lut4(tmp_path, monkeypatch):
    monkeypatch.setattr(report, "BENCH_REPORT", tmp_path / "report.json")
    row = synth.add_pixel_rate({"fmax_mhz": 100.0, "luts": 50_000})
    assert row["pixels_per_clock"] == synth.DEFAULT_PIXELS_PER_CLOCK
    assert row["pixels_per_second_per_lut4"] == round(100e6 * synth.DEFAULT_PIXELS_PER_CLOCK / 50_000, 1)
    (tmp_path / "report.json").write_text(
        '{"goals": {"pixels_per_clock_4_engines_latency_256": {"measured": 3.7}}}')
    row = synth.add_pixel_rate({"fmax_mhz": 130.0, "luts": 65_000})
    assert row["pixels_per_clock"] == 3.7 and "may be stale" in row["pixels_per_clock_source"]
    assert row["pixels_per_second_per_lut4"] == round(130e6 * 3.7 / 65_000, 1)


def test_pixel_rate_says_when_the_bench_is_stale(tmp_path, monkeypatch):
    """The bench report names the RTL it measured; a figure of other RTL is flagged, not hidden."""
    monkeypatch.setattr(report, "BENCH_REPORT", tmp_path / "report.json")
    now = rtl_digest()
    assert len(now) == 12 and now == rtl_digest()          # deterministic
    for digest, stale in ((now, False), ("0123456789ab", True)):
        (tmp_path / "report.json").write_text(json.dumps(
            {"rtl_digest": digest, "goals": {"pixels_per_clock_4_engines_latency_256": {"measured": 3.75}}}))
        ppc, where = synth.pixels_per_clock()
        assert ppc == 3.75 and where.endswith("report.json") != stale
        assert ("stale" in where) == stale and (digest in where) == stale


def test_rtl_digest_follows_the_rtl(tmp_path, monkeypatch):
    """Any byte of a listed source or of an included header changes the digest."""
    (tmp_path / "rtl").mkdir()
    src, hdr = tmp_path / "rtl" / "a.sv", tmp_path / "rtl" / "h.svh"
    src.write_text("module a; endmodule\n")
    hdr.write_text("`define X 1\n")
    flist = tmp_path / "rtl" / "msr.f"
    flist.write_text(f"+incdir+{tmp_path / 'rtl'}\n{src}\n")
    from msr_flow import filelist as msr_runner
    monkeypatch.setattr(msr_runner, "ROOT", tmp_path)
    d0 = msr_runner.rtl_digest(flist)
    hdr.write_text("`define X 2\n")
    d1 = msr_runner.rtl_digest(flist)
    src.write_text("module a; logic b; endmodule\n")
    d2 = msr_runner.rtl_digest(flist)
    assert len({d0, d1, d2}) == 3 and d2 == msr_runner.rtl_digest(flist)


def test_top_is_placed_flat_with_its_defaults():
    assert synth.ECP5_TOP_PARAMS == {}
    assert synth.ECP5_LUTS == 83_640 and synth.ECP5_SPEED == "6"
    files = synth.read_filelist()
    units = synth.modules_in(files)
    assert set(synth.ECP5_UNITS) <= set(units)


def _netlist(tmp_path, engines, ctxs, rams=4):
    cells = {f"g_engine[{e}].u_engine.g_ctx[{c}].u_ctx.u_tile_sram.mem_q.{i // 2}.{i % 2}":
             {"type": "DP16KD", "attributes": {}} for e in range(engines) for c in range(ctxs)
             for i in range(rams)}
    cells["u_fb_writer.lut"] = {"type": "TRELLIS_COMB", "attributes": {}}
    net = tmp_path / "top.json"
    net.write_text(json.dumps({"modules": {"msr_top": {"attributes": {"top": "00000001"}, "cells": cells},
                                           "LUT4": {"attributes": {}, "cells": {}}}}))
    return net


def _bels(net):
    cells = json.loads(net.read_text())["modules"]["msr_top"]["cells"]
    return {n: c["attributes"].get("BEL") for n, c in cells.items()}


def test_floorplan_puts_each_engine_in_its_quarter(tmp_path):
    net = _netlist(tmp_path, 4, 8)
    assert synth.ecp5_floorplan(net) == {"locked": 128, "engines": 4, "contexts": 8, "rams_per_context": 4}
    bels = _bels(net)
    assert bels["u_fb_writer.lut"] is None
    sites = [b for b in bels.values() if b]
    assert len(set(sites)) == 128                                  # every site used once
    xy = {}
    for name, bel in bels.items():
        if bel:
            x, y, ebr = bel.split("/")
            e = int(name[len("g_engine["):].split("]")[0])
            xy.setdefault(e, []).append((int(x[1:]), int(y[1:])))
            base = max(b for b in floorplan.ECP5_EBR_LEFT + floorplan.ECP5_EBR_RIGHT if b <= int(x[1:]))
            assert int(ebr[3:]) == (int(x[1:]) - base) // 2           # EBRi at group + 2i
    for e, pts in xy.items():                                      # left / right, top / bottom
        xs, ys = {p[0] for p in pts}, {p[1] for p in pts}
        assert (max(xs) < 64) == (e % 2 == 0) and (min(xs) > 64) == (e % 2 == 1)
        assert ys == ({22, 46} if e < 2 else {70, 82})
    # one context's four block RAMs side by side in one row
    ctx = sorted(bels[f"g_engine[1].u_engine.g_ctx[3].u_ctx.u_tile_sram.mem_q.{i // 2}.{i % 2}"]
                 for i in range(4))
    assert [b.split("/")[1] for b in ctx] == ["Y22"] * 4


def test_floorplan_leaves_a_layout_that_does_not_fit_unconstrained(tmp_path):
    for engines, ctxs, rams in ((5, 2, 4), (2, 14, 4), (2, 10, 6), (2, 2, 25)):
        net = _netlist(tmp_path, engines, ctxs, rams)
        r = synth.ecp5_floorplan(net)
        assert r["locked"] == 0 and "does not fit" in r["why"]
        assert not any(_bels(net).values())


@pytest.mark.parametrize("ctxs", [8, 7, 6])
def test_floorplan_of_the_lindilate_engine_six_block_rams_per_context(tmp_path, ctxs):
    """Tile buffer (4 DP16KD) + the third port's colour copy (2): every context's six locked,
    a context's six side by side in one row of its engine's quarter (a group and a half)."""
    cells = {}
    for e in range(4):
        for c in range(ctxs):
            for i in range(4):
                cells[f"g_engine[{e}].u_engine.g_ctx[{c}].u_ctx.u_tile_sram.mem_q.{i // 2}.{i % 2}"] = \
                    {"type": "DP16KD", "attributes": {}}
            for i in range(2):
                cells[f"g_engine[{e}].u_engine.g_ctx[{c}].u_ctx.u_tile_sram_outer.mem_q.0.{i}"] = \
                    {"type": "DP16KD", "attributes": {}}
    net = tmp_path / "top.json"
    net.write_text(json.dumps({"modules": {"msr_top": {"attributes": {"top": "00000001"}, "cells": cells}}}))
    assert synth.ecp5_floorplan(net) == {"locked": 24 * ctxs, "engines": 4, "contexts": ctxs,
                                         "rams_per_context": 6}
    bels = _bels(net)
    assert all(bels.values()) and len(set(bels.values())) == 24 * ctxs       # every site used once
    for name, bel in bels.items():
        x, y, ebr = bel.split("/")
        e = int(name[len("g_engine["):].split("]")[0])
        base = max(b for b in floorplan.ECP5_EBR_LEFT + floorplan.ECP5_EBR_RIGHT if b <= int(x[1:]))
        assert int(ebr[3:]) == (int(x[1:]) - base) // 2
        assert (int(x[1:]) < 64) == (e % 2 == 0)
        assert int(y[1:]) in ((22, 46) if e < 2 else (70, 82))
    for e in range(4):
        for c in range(ctxs):
            mine = [b for n, b in bels.items() if n.startswith(f"g_engine[{e}].u_engine.g_ctx[{c}].")]
            assert len(mine) == 6 and len({b.split("/")[1] for b in mine}) == 1   # one row
            xs = sorted(int(b.split("/")[0][1:]) for b in mine)
            assert xs[-1] - xs[0] <= 9 + 6                                        # within two groups


def test_combine_seeds_median_best_worst():
    """The flat top over seeds: fmax_mhz is the median seed's (the lower middle for
    an even count), best and worst name their seeds, a failed seed is listed with its error."""
    rows = [{"seed": 1, "fmax_mhz": 99.5, "seconds": 10, "luts": 7}, {"seed": 2, "fmax_mhz": 103.0, "seconds": 12,
                                                                        "luts": 8},
            {"seed": 3, "fmax_mhz": 101.2, "seconds": 11, "luts": 9}]
    r = synth.combine_seeds(rows)
    assert r["fmax_mhz"] == 101.2 and r["fmax_median"] == {"seed": 3, "fmax_mhz": 101.2}
    assert r["fmax_best"]["seed"] == 2 and r["fmax_worst"]["seed"] == 1 and r["luts"] == 9
    assert [x["seed"] for x in r["fmax_seeds"]] == [1, 2, 3]
    r = synth.combine_seeds(rows[:2] + [{"seed": 3, "error": "router gave up"}])
    assert r["fmax_mhz"] == 99.5 and r["fmax_seeds"][2]["error"] == "router gave up"
    assert r["fmax_worst"] == {"seed": 3, "fmax_mhz": None, "error": "router gave up"}
    # a failed seed ranks below every routed one: with two of three failed there is no median
    r = synth.combine_seeds(rows[:1] + [{"seed": 2, "error": "did not route"}, {"seed": 3, "error": "x"}])
    assert "error" in r
    r = synth.combine_seeds([rows[1], rows[2], rows[0], {"seed": 4, "error": "did not route"}])
    assert r["fmax_median"] == {"seed": 1, "fmax_mhz": 99.5}
    assert "error" in synth.combine_seeds([{"seed": 1, "error": "x"}])


# --- the job graph: declared jobs, run in dependency order -------------------------------------

def _recording_jobs(calls, fail=()):
    def fn(name):
        def run(*a):
            calls.append((name, a))
            if name in fail:
                raise RuntimeError(f"{name} broke")
            return {"name": name, "args": a}
        return run
    return fn


def test_graph_runs_a_job_after_its_dependencies_listed_order_first():
    calls = []
    fn = _recording_jobs(calls)
    jobs = [synth.Job(("net", "a"), fn("a"), ("tag_a",), (("net", "b"),)),
            synth.Job(("net", "b"), fn("b"), (1, 2)),
            synth.Job(("ecp5", "c"), fn("c")),
            synth.Job(("ecp5", "d"), fn("d"), ("tag_d",), (("net", "a"), ("net", "b")))]
    results, failures = synth.run_graph(jobs, workers=1)
    assert failures == []
    # b is the first ready job; then a (listed before c) and c; d waits for a
    assert [name for name, _ in calls] == ["b", "a", "c", "d"]
    # the dependencies' results come first in the call, in the order named, then the job's own args
    assert dict(calls)["a"] == (results[("net", "b")], "tag_a")
    assert dict(calls)["d"] == (results[("net", "a")], results[("net", "b")], "tag_d")
    assert set(results) == {j.key for j in jobs}


def test_graph_a_failure_stops_what_needs_it_and_nothing_else():
    calls = []
    fn = _recording_jobs(calls, fail={"b"})
    jobs = [synth.Job(("net", "b"), fn("b")),
            synth.Job(("net", "a"), fn("a"), (), (("net", "b"),)),
            synth.Job(("ecp5", "d"), fn("d"), (), (("net", "a"),)),
            synth.Job(("ecp5", "c"), fn("c")),
            synth.Job(("ecp5", "e"), fn("e"), (), (("ecp5", "c"),))]
    results, failures = synth.run_graph(jobs, workers=2)
    assert sorted(name for name, _ in calls) == ["b", "c", "e"]          # a and d never run
    assert failures == ["b broke"]                                       # reported once, where it broke
    assert results[("net", "b")] == {"error": "b broke"}
    assert results[("net", "a")] == {"error": "needs a run that failed: b broke"}
    assert results[("ecp5", "d")] == {"error": "needs a run that failed: needs a run that failed: b broke"}
    assert "error" not in results[("ecp5", "e")]


def test_graph_a_dependency_no_job_provides_is_a_failure():
    calls = []
    fn = _recording_jobs(calls)
    jobs = [synth.Job(("ecp5", "x"), fn("x"), (), (("net", "nobody"),)), synth.Job(("ecp5", "y"), fn("y"))]
    results, failures = synth.run_graph(jobs, workers=2)
    assert [name for name, _ in calls] == ["y"]
    assert results[("ecp5", "x")] == {"error": "a dependency was never scheduled"}
    assert failures == ["ecp5 x: a dependency was never scheduled"]


def _plan(*argv):
    args = synth.parser().parse_args(list(argv))
    files = synth.read_filelist()
    units = [m for m in synth.modules_in(files) if not m.endswith("_pkg")]
    mods = args.modules.split(",") if args.modules else units
    return synth.plan(args, files, mods, {"NUM_CTX": 7}, "msr_tile_sram", (1, 2, 3)), units


def _check_dag(jobs):
    keys = [j.key for j in jobs]
    assert len(keys) == len(set(keys))
    done = set()
    for j in jobs:                       # as planned, every dependency is listed before its user
        assert set(j.deps) <= done, (j.key, j.deps)
        done.add(j.key)


def test_plan_of_the_whole_design():
    jobs, units = _plan()
    _check_dag(jobs)
    by_key = {j.key: j for j in jobs}
    assert jobs[0].key == ("net", synth.ENGINE) and jobs[1].key == ("net", "msr_top_glue")   # the long chain first
    assert by_key[("net", "msr_top")].deps == (("net", "msr_top_glue"), ("net", synth.ENGINE))
    for seed in (1, 2, 3):
        j = by_key[("ecp5", f"msr_top@{seed}")]
        assert j.fn is synth.ecp5_place and j.deps == (("net", "msr_top"),) and j.args[1:] == (seed, True, synth.ECP5_SEED_TIMEOUT_S, 100)
    assert by_key[("ecp5", "msr_top_glue")].deps == (("net", "msr_top_glue_cut"),)
    assert {m for (kind, m) in by_key if kind == "ecp5"} >= set(synth.ECP5_UNITS)
    generic = {w for (kind, w) in by_key if kind == "generic"}
    assert generic == ({(m, "inferred") for m in units if m != "msr_top"}
                       | {(synth.ENGINE, "black box"), ("msr_top", "glue")})


def test_plan_follows_the_options():
    jobs, _ = _plan("--no-ecp5")
    assert jobs and all(j.key[0] == "generic" and not j.deps for j in jobs)
    jobs, _ = _plan("--modules", "msr_top", "--glue-only")
    _check_dag(jobs)
    assert not any(synth.ENGINE in str(j.key) for j in jobs)
    assert ("ecp5", "msr_top_glue") in {j.key for j in jobs} and ("net", "msr_top") not in {j.key for j in jobs}
    jobs, _ = _plan("--modules", "msr_top", "--no-top-ecp5")
    _check_dag(jobs)
    assert not any(j.key[1] == "msr_top" or "@" in str(j.key[1]) for j in jobs if j.key[0] in ("net", "ecp5"))
    jobs, _ = _plan("--modules", "msr_fb_writer")
    assert [j.key for j in jobs] == [("ecp5", "msr_fb_writer"), ("generic", ("msr_fb_writer", "inferred"))]


def test_merge_rows_marks_the_unit_run():
    """--modules ... --merge: the unit run's rows replace those modules' rows, say where they come
    from, and leave every other row as it was."""
    full = {"generic": {"a": {"inferred": {"cells": 1}}, "b": {"inferred": {"error": "x"}}},
            "ecp5": {"a": {"luts": 5}}}
    unit = {"generic": {"b": {"inferred": {"cells": 7}}}, "ecp5": {"b": {"luts": 9}}}
    out = synth.merge_rows(full, unit, ["b"])
    assert out["generic"]["a"] == {"inferred": {"cells": 1}} and out["ecp5"]["a"] == {"luts": 5}
    (kind, row), = out["generic"]["b"].items()
    assert kind.startswith("inferred (unit run at ") and row == {"cells": 7}
    assert out["ecp5"]["b"]["luts"] == 9 and out["ecp5"]["b"]["merged_from"].startswith("unit run at ")
    assert full["generic"]["b"] == {"inferred": {"error": "x"}}          # the input is not changed
    assert synth.main(["--merge"]) == 2


def test_doc_pixel_rate_is_the_top_rows(monkeypatch, tmp_path):
    """A --merge rewrites docs/synthesis.md on a machine that may have no bench report: the doc's
    pixels per clock stays the one the top's row was computed with, not the fallback constant."""
    monkeypatch.setattr(report, "BENCH_REPORT", tmp_path / "absent.json")
    rep = {"ecp5": {synth.TOP: {"pixels_per_clock": 3.715, "pixels_per_clock_source": "out/bench/report.json"}}}
    assert synth.doc_pixels_per_clock(rep) == (3.715, "out/bench/report.json")
    assert synth.doc_pixels_per_clock({"ecp5": {}}) == (synth.DEFAULT_PIXELS_PER_CLOCK,
                                                        "constant (no out/bench/report.json)")


def test_run_commit_dirty_only_for_rtl(monkeypatch):
    """A run is marked dirty only when rtl/ differs from HEAD (uncommitted docs are not)."""
    calls = []

    def fake_run(cmd, **kw):
        calls.append(cmd)
        out = "abc1234\n" if cmd[1] == "describe" else (" M rtl/x.sv\n" if dirty else "")
        return subprocess.CompletedProcess(cmd, 0, stdout=out, stderr="")

    monkeypatch.setattr(report.subprocess, "run", fake_run)
    dirty = False
    assert synth.run_commit() == "abc1234"
    dirty = True
    assert synth.run_commit() == "abc1234-dirty"
    assert any(c[-1] == "rtl" for c in calls)


def test_merge_carries_the_top_summary_with_the_top_row():
    """A merged msr_top row brings its top_ecp5 summary (what outside tools read), so the two
    never disagree; a merge of other units leaves the summary alone."""
    full = {"generic": {}, "ecp5": {"msr_top": {"luts": 1}}, "top_ecp5": {"luts": 1}}
    unit = {"generic": {}, "ecp5": {"msr_top": {"luts": 2}}, "top_ecp5": {"luts": 2}}
    assert synth.merge_rows(full, unit, ["msr_top"])["top_ecp5"] == {"luts": 2}
    other = {"generic": {}, "ecp5": {"msr_regs": {"luts": 3}}}
    assert synth.merge_rows(full, other, ["msr_regs"])["top_ecp5"] == {"luts": 1}


def test_front_end_reads_every_include_folder_of_the_file_list():
    files = synth.read_filelist()
    cmd = synth.read_cmd(files, "msr_top", "msr_tile_engine", {"NUM_ENGINES": 2})
    assert {"rtl/prim", "rtl/fbw", "rtl/top"} <= set(re.findall(r"-I (\S+)", cmd))
    assert " -G NUM_ENGINES=2" in cmd and "--blackboxed-module msr_tile_engine" in cmd
    assert all(f in cmd for f in files)


# --- the page: docs/synthesis.md rendered from a report through the Jinja2 template ----------------

def _committed():
    return json.loads(synth.DOC.with_suffix(".json").read_text())


def test_page_has_a_row_per_run_with_its_figures():
    rep = _committed()
    text = synth.render(rep)
    lines = text.splitlines()
    for mod, runs in rep["generic"].items():
        for kind, r in runs.items():
            want = (f"| `{mod}` | {synth.params_text(r['params'])} | {page.UNIT_RUN.sub('', kind)}"
                    + (" (unit run)" if "unit run" in kind else "") + f" | {synth.fmt(r['cells'])} | ")
            assert sum(ln.startswith(want) for ln in lines) == 1, want
    for mod, r in rep["ecp5"].items():
        name = "`msr_top` glue" if mod == "msr_top_glue" else f"`{mod}`"
        row = [ln for ln in lines if ln.startswith(f"| {name}") and f"| {synth.fmt(r['luts'])} |" in ln
               and f"| {r['fmax_mhz']} |" in ln]
        assert len(row) == 1, mod
    top = rep["ecp5"]["msr_top"]
    assert f"median\n{top['fmax_median']['fmax_mhz']} MHz (seed {top['fmax_median']['seed']})" in text
    assert f"latches in all runs: {rep['latches_total']}." in text


def test_page_names_no_commit_and_no_issue():
    """Merged rows say they come from a unit run, not at which commit."""
    rep = _committed()
    rep["generic"]["msr_lzc"] = {"inferred (unit run at abc1234-dirty)": rep["generic"]["msr_lzc"]["inferred"]}
    rep["ecp5"]["msr_regs"]["merged_from"] = "unit run at abc1234"
    text = synth.render(rep)
    assert "| `msr_lzc` | defaults | inferred (unit run) |" in text
    assert "| `msr_regs` (unit run) |" in text
    assert not re.search(r"\bat [0-9a-f]{7}\b|abc1234|[Ii]ssue \d", text)


def test_page_of_failed_runs_and_a_top_without_seeds():
    rep = _committed()
    rep["generic"]["msr_lzc"] = {"inferred": {"error": "yosys failed for msr_lzc_inf: ERROR: boom"}}
    rep["ecp5"] = {"msr_regs": {"error": "nextpnr-ecp5 failed"}}
    text = synth.render(rep)
    assert "| `msr_lzc` | | inferred | error: yosys failed for msr_lzc_inf: ERROR: boom | | | | |" in text
    assert "| `msr_regs` | | error: nextpnr-ecp5 failed |" in text
    assert "placement seeds" not in text and "![" not in text


def test_render_option_rewrites_the_page_from_the_json(tmp_path, monkeypatch):
    doc, js = tmp_path / "synthesis.md", tmp_path / "synthesis.json"
    js.write_text(json.dumps(_committed()))
    monkeypatch.setattr(cli, "DOC", doc)
    monkeypatch.setattr(cli, "DOC_JSON", js)
    monkeypatch.setattr(cli, "write_doc", lambda rep: page.write_doc(rep, doc))
    monkeypatch.setattr(cli, "ROOT", tmp_path)
    assert synth.main(["--render"]) == 0
    assert doc.read_text() == synth.render(_committed())


def test_committed_page_is_the_committed_json_rendered():
    """docs/synthesis.md is generated: it must be what the template makes of docs/synthesis.json
    (python -m msr_flow.synth --render writes it again)."""
    assert synth.DOC.read_text() == synth.render(_committed())


def test_report_of_the_top_carries_what_outside_tools_read(tmp_path, monkeypatch):
    """build/synth/report.json of a run with msr_top: the generic top composed from glue and
    engines, the ECP5 top row of the median seed with its LUT4 against the device's, dp16kd and
    fmax_seeds, and the same figures in top_ecp5."""
    monkeypatch.setattr(report, "BENCH_REPORT", tmp_path / "absent.json")
    design = synth.Design.read()
    n = design.n_engines

    def ecp5_row(seed, fmax, luts=60_000):
        return {"device": "LFE5U-85F-CABGA381", "params": {}, "luts": luts, "device_luts": synth.ECP5_LUTS,
                "lut_utilisation": round(luts / synth.ECP5_LUTS, 4), "flip_flops": 9, "block_rams": 168,
                "dsp_mult18": 0, "fmax_mhz": fmax, "seed": seed, "seconds": 5.0}

    results = {("generic", ("msr_top", "glue")): part(1000, 100, 50, 20, bb_inst=n),
               ("generic", (synth.ENGINE, "inferred")): part(300, 30, 7, 25),
               ("generic", (synth.ENGINE, "black box")): part(310, 31, 0, 26),
               ("ecp5", "msr_top@1"): ecp5_row(1, 101.0), ("ecp5", "msr_top@2"): ecp5_row(2, 99.0, 61_000),
               ("ecp5", "msr_top@3"): ecp5_row(3, 104.0)}
    failures = []
    rep = report.assemble(results, failures, design, ["msr_top"], (1, 2, 3), False, 0.0)
    assert failures == [] and rep["latches_total"] == 0
    assert rep["generic"]["msr_top"]["inferred"]["cells"] == 1000 + n * 300
    assert list(rep["generic"]) == [synth.ENGINE, "msr_top"]                  # file-list order
    top = rep["ecp5"]["msr_top"]
    assert (top["fmax_mhz"], top["seed"], top["dp16kd"]) == (101.0, 1, 168)
    summary = rep["top_ecp5"]
    assert summary["luts"] == 60_000 and summary["device_luts"] == 83_640 and summary["fmax_mhz"] == 101.0
    assert summary["lut_utilisation"] == round(60_000 / 83_640, 4)
    assert (summary["dp16kd"], summary["device_dp16kd"]) == (168, 208)
    assert [x["seed"] for x in summary["fmax_seeds"]] == [1, 2, 3]
    assert summary["pixels_per_second_per_lut4"] == round(101e6 * report.DEFAULT_PIXELS_PER_CLOCK / 60_000, 1)
    assert list(rep)[-3:] == ["latches_total", "seconds", "failures"]


def test_report_counts_latches_once_and_fails_on_them():
    design = synth.Design.read()
    results = {("generic", ("msr_lzc", "inferred")): part(5, 0, 0, 3, latches=2)}
    failures = []
    rep = report.assemble(results, failures, design, ["msr_lzc"], (1,), False, 0.0)
    assert rep["latches_total"] == 2 and failures == ["msr_lzc (inferred): 2 latches"]
    assert "top_ecp5" not in rep and rep["ecp5"] == {}
