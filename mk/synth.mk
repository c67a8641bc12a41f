# Synthesis reports: Yosys generic per module and the top (bottom-up), the default top placed
# and routed flat on the LFE5U-85F, the glue and every system unit on ECP5. The flow is the
# package msr_flow.synth (flow/msr_flow/synth/); scripts/synth.py is its entry point.
# Report: build/synth/report.json, tables in docs/synthesis.md (template
# flow/msr_flow/templates/synthesis.md.j2).
#   make synth                   everything (about 45 min on 2 cores)
#   make synth UNIT=msr_fb_writer one unit: its generic and ECP5 rows (a few minutes)
#   make synth SYNTH_ARGS=--no-ecp5   the generic runs only
#   make synth-doc               docs/synthesis.md again from docs/synthesis.json (no tool runs)
UNIT ?=
.PHONY: synth synth-doc
synth: setup
	$(ENV) nice -n 5 python -m msr_flow.synth $(if $(UNIT),--modules $(UNIT)) $(SYNTH_ARGS)
synth-doc: setup
	$(ENV) python -m msr_flow.synth --render
