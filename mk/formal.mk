# make formal: SymbiYosys proofs of the primitives, the tag pool, the AXI4-Lite register block,
# the AXI4 write master, and negative tests of the protocol checkers (rtl/checkers/), one job
# per .sby task under formal/, run one at a time by formal/run_formal.py (nice 10); each job
# builds into build/formal/<job>/, the table lands in build/formal/summary.json.
#   make formal                      every job
#   make formal FORMAL_JOBS='fifo_*'   some jobs (shell patterns over the job names)
#   make formal FORMAL_SOLVER=z3      another smtbmc solver than the .sby's own (cvc4)
# Part of make test (TEST_DEPS): a few minutes on one core.
FORMAL_JOBS   ?=
FORMAL_SOLVER ?=

.PHONY: formal
formal: setup
	$(ENV) python formal/run_formal.py $(if $(FORMAL_SOLVER),--solver $(FORMAL_SOLVER)) $(FORMAL_JOBS)

TEST_DEPS += formal
