# Standard cells: every unit, one tile engine and the default top mapped to the OSU 0.18 um
# library and timed with OpenSTA (the package msr_flow.asic, flow/msr_flow/asic/). Report:
# build/asic/report.json; the page docs/asic.md is rendered from docs/asic.json, which a full
# run rewrites.
#   make asic                       everything: about 20 min the first time on a loaded 2-core
#                                   machine; a rerun on unchanged RTL reuses the Yosys results
#                                   (stamps in build/asic/) and only redoes the timing
#   make asic UNIT=msr_decision_pipe one unit (build/asic/report_partial.json)
#   make asic ASIC_ARGS=--period-ns=4 another clock target
#   make asic-doc                   docs/asic.md again from docs/asic.json (seconds, no tools)
ASIC_ARGS ?=
.PHONY: asic asic-doc
asic: setup
	$(ENV) python -m msr_flow.asic $(if $(UNIT),--modules $(UNIT)) $(ASIC_ARGS)

asic-doc: setup
	$(ENV) python -m msr_flow.asic --doc-only

# The gate-level netlist of one tile engine for the gate-level bench (tb/gate_level), rebuilt
# when the RTL or the flow that maps it changes (about 3 min on an idle machine). make test-gate
# runs the bench (its model's build is some ten minutes; make test leaves it out: pytest.ini's
# `gate`).
ASIC_FLOW_FILES := $(wildcard flow/msr_flow/asic/*.py flow/msr_flow/synth/*.py) flow/msr_flow/filelist.py
# The same engine as the cited macro needs it at 200 MHz (reads of four clocks, RD_LAT 4; an
# address on a port once per five, BUF_CYCLE 5: docs/asic.md) is the bench's second netlist.
ASIC_GATE_NETLIST := build/asic/msr_tile_engine.sim.v
ASIC_GATE_NETLIST_RL4 := build/asic/msr_tile_engine_rl4_cy5.sim.v
$(ASIC_GATE_NETLIST): $(MSR_RTL_FILES) $(ASIC_FLOW_FILES) syn/asic/sram_macro.json | setup
	$(ENV) python -m msr_flow.asic --netlist-only
$(ASIC_GATE_NETLIST_RL4): $(MSR_RTL_FILES) $(ASIC_FLOW_FILES) syn/asic/sram_macro.json | setup
	$(ENV) python -m msr_flow.asic --netlist-only --rd-lat=4 --buf-cycle=5

.PHONY: test-gate
test-gate: setup $(ASIC_GATE_NETLIST) $(ASIC_GATE_NETLIST_RL4)
	$(ENV) python -m pytest -m gate tb/gate_level $(PYTEST_ARGS)
