# Synthesis reports (issue 6): Yosys generic per module and top, SRAM black box and
# inferred, ECP5 place and route for one engine and the top. Report: build/synth/report.json.
.PHONY: synth
synth: setup
	$(ENV) python scripts/synth.py $(SYNTH_ARGS)
