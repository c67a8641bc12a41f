# make regs: everything derived from the SystemRDL register map rtl/regs/msr_regs.rdl.
# The generated SystemVerilog, C header, Python constants and docs are committed, so lint,
# synthesis and the simulations never need the generator; `make regs-check` (part of
# `make test`) regenerates into build/ and fails if the committed files are stale.
REGS_RDL  := rtl/regs/msr_regs.rdl
REGS_GEN  := rtl/regs/msr_regs.sv rtl/regs/msr_regs_pkg.sv rtl/regs/msr_err_codes.svh sim/msr_regs.h flow/msr_flow/regs.py docs/regs.md

.PHONY: regs regs-check

define regs_generate # $(1) = output root (repo root or a scratch folder)
	mkdir -p $(1)/rtl/regs $(1)/sim $(1)/flow/msr_flow $(1)/docs
	$(ENV) peakrdl regblock $(REGS_RDL) -o $(1)/rtl/regs --cpuif passthrough --default-reset arst_n \
	    --rt-read-fanin --rt-read-response \
	    --err-if-bad-addr
	$(ENV) peakrdl c-header $(REGS_RDL) -o $(1)/sim/msr_regs.h
	$(ENV) python -m msr_flow.regs_gen $(REGS_RDL) $(1)/flow/msr_flow/regs.py
	$(ENV) peakrdl markdown $(REGS_RDL) -o $(1)/docs/regs.md
	$(ENV) python -m msr_flow.regs_codes $(REGS_RDL) $(1)/rtl/regs/msr_err_codes.svh --md $(1)/docs/regs.md
endef

regs: setup
	$(call regs_generate,.)

regs-check: setup
	rm -rf build/regs-check
	$(call regs_generate,build/regs-check)
	@for f in $(REGS_GEN); do cmp -s $$f build/regs-check/$$f || \
	    { echo "regs-check: $$f is stale: run make regs and commit"; exit 1; }; done
	@echo "regs-check: generated register files are up to date"

TEST_DEPS += regs-check
