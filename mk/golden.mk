# Golden model benchmark: 1080p wall time of the vectorised model.
.PHONY: bench-golden
bench-golden: setup
	$(ENV) python scripts/bench_golden.py
BENCH_DEPS += bench-golden
