# Standard cells: every unit, one tile engine and the default top mapped to the OSU 0.18 um
# library and timed with OpenSTA (scripts/asic.py). Report: build/asic/report.json, page
# docs/asic.md.
#   make asic                       everything: about 20 min the first time on a loaded 2-core
#                                   machine; a rerun on unchanged RTL reuses the Yosys results
#                                   (stamps in build/asic/) and only redoes the timing
#   make asic UNIT=msr_decision_pipe one unit (build/asic/report_partial.json)
#   make asic ASIC_ARGS=--period-ns=4 another clock target
ASIC_ARGS ?=
.PHONY: asic
asic: setup
	$(ENV) python scripts/asic.py $(if $(UNIT),--modules $(UNIT)) $(ASIC_ARGS)

# The gate-level netlist of one tile engine for the gate-level bench (tb/gate_level), rebuilt
# when the RTL or the flow changes (about 3 min on an idle machine). make test-gate runs the
# bench (its model's build is some ten minutes; make test leaves it out: pytest.ini's `gate`).
ASIC_GATE_NETLIST := build/asic/msr_tile_engine.sim.v
$(ASIC_GATE_NETLIST): $(MSR_RTL_FILES) scripts/asic.py scripts/synth.py syn/asic/sram_macro.json | setup
	$(ENV) python scripts/asic.py --netlist-only

.PHONY: test-gate
test-gate: setup $(ASIC_GATE_NETLIST)
	$(ENV) python -m pytest -m gate tb/gate_level $(PYTEST_ARGS)
