# RTL of the tile engine: lint and the engine throughput benchmark.
# make lint: Verilator -Wall and slang per module, Verible per file, over rtl/msr.f;
# fails on any warning (waivers live in the RTL, per signal / line, each with a reason).
.PHONY: lint bench-engine
lint: setup
	$(ENV) python scripts/lint_rtl.py

# Cycles per 16x16 tile against render latency -> out/bench/engine.json
bench-engine: setup
	$(ENV) python scripts/bench_engine.py
BENCH_DEPS += bench-engine
