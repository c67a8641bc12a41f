# Synthesis reports: Yosys generic per module and the top (bottom-up), the default top placed
# and routed flat on the LFE5U-85F, the glue and every system unit on ECP5.
# Report: build/synth/report.json, tables in docs/synthesis.md.
#   make synth                   everything (about 45 min on 2 cores)
#   make synth UNIT=msr_fb_writer one unit: its generic and ECP5 rows (a few minutes)
#   make synth SYNTH_ARGS=--no-ecp5   the generic runs only
UNIT ?=
.PHONY: synth
synth: setup
	$(ENV) nice -n 5 python scripts/synth.py $(if $(UNIT),--modules $(UNIT)) $(SYNTH_ARGS)
