# make coverage: the cocotb benches built with Verilator --coverage-line --coverage-user
# (MSR_COVERAGE=1 in flow/msr_flow/runner.py: builds under build/tb_cov/, one coverage.dat
# per simulation run under build/coverage/dat/, functional bins under build/coverage/func/),
# then scripts/coverage_report.py merges them into build/coverage/summary.json (line_percent
# over rtl/, cover_points_hit, cover_points_total, per file, functional bins) and
# build/coverage/report.md (missed lines with their source). The Verilator frame harness
# (tb/msr_sim) is not instrumented. A failing bench fails the target after the report.
#   make coverage                          every bench (about 70 min on 2 shared cores)
#   make coverage COVERAGE_TESTS=tb/msr_top  some benches (a partial report)
# make soak: scripts/soak.py, random frames through tb/msr_top until SOAK_MINUTES (default 10),
# seeds and results in build/soak/; a one-minute soak is part of make test
# (scripts/tests/test_soak.py).
COVERAGE_TESTS ?= tb
SOAK_MINUTES   ?= 10

.PHONY: coverage soak
coverage: setup
	rm -rf build/coverage
	@status=0; $(ENV) MSR_COVERAGE=1 nice -n 10 python -m pytest -q $(COVERAGE_TESTS) \
	    --ignore=tb/msr_sim -k 'not bad_parameters' || status=$$?; \
	$(ENV) python scripts/coverage_report.py; exit $$status

soak: setup
	$(ENV) nice -n 10 python scripts/soak.py --minutes $(SOAK_MINUTES) $(if $(SEED),--seed $(SEED))
