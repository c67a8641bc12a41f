# Multi-level selective rendering accelerator: the project's entry points.
# `make sim` and `make test` set up everything they need on a fresh Debian machine.
SHELL        := /bin/bash
.SHELLFLAGS  := -eo pipefail -c
.DEFAULT_GOAL := help

PY   := .venv/bin/python
ENV  := source scripts/env.sh &&

# make sim parameters (see docs/spec/contracts.md); empty means the tool's default.
SCENE    ?= cornell
WIDTH    ?= 640
HEIGHT   ?= 480
TILE     ?= 16
LEVELS   ?= 2
THR      ?=
METRIC   ?= max
FOV_GAIN ?= 0
OUT      ?=
WAVES    ?= 0
PYTEST_ARGS ?=
# pytest-xdist: one worker per CPU (the benches are single-threaded simulations)
PYTEST_JOBS ?= -n auto

.PHONY: help setup sim test lint synth bench eval waves clean

help: ## list the targets
	@echo "Multi-level selective rendering accelerator"
	@echo
	@echo "  make sim    set up, then render the default scene (SCENE=, WIDTH=, HEIGHT=, TILE=, LEVELS=,"
	@echo "              THR=a,b,.., METRIC=max|sum, FOV_GAIN=, RULE=patent, CAMERA=, OUT=dir, WAVES=1,"
	@echo "              BUDGET=N|P% a ray budget, FRAMES=N [CAMERA_PATH=file] a sequence,"
	@echo "              DEPTH=1 the engines' depth channel, each pixel's inverse depth checked)"
	@echo "  make waves  GTKWave on the last make sim WAVES=1 (OUT= to pick one); waves-shot: its picture"
	@echo "  make test   set up, then run every test (pytest, cocotb on Verilator)"
	@echo "  make lint   Verilator -Wall, Verible and slang on every RTL module"
	@echo "  make synth  Yosys synthesis reports"
	@echo "  make asic   OSU 0.18 um standard cells + OpenSTA -> build/asic/report.json, docs/asic.md"
	@echo "  make test-gate  the gate-level bench of the mapped tile engine (tb/gate_level)"
	@echo "  make formal SymbiYosys proofs of the primitives, tag pool and register block (part of make test)"
	@echo "  make coverage  line, cover-point and functional coverage of the benches -> build/coverage/"
	@echo "  make soak   random frames through msr_top until SOAK_MINUTES (default 10), seeds in build/soak/"
	@echo "  make bench  golden-model and hardware throughput benchmarks"
	@echo "  make eval   quality against traced pixels (FULL=1 for 1920x1080; DASK_SCHEDULER=tcp://host:port)"
	@echo "  make setup  only install what is missing (apt-get, .venv)"
	@echo "  make clean  remove build outputs"

setup:
	@bash scripts/setup.sh

# rtl/msr.f, read once for every flow by its one reader (flow/msr_flow/filelist.py):
# MSR_RTL_FILES the sources in order, MSR_RTL_OPTS its tool options (+incdir+...).
MSR_RTL_ARGS  := $(shell python3 flow/msr_flow/filelist.py)
MSR_RTL_FILES := $(filter-out +% -%,$(MSR_RTL_ARGS))
MSR_RTL_OPTS  := $(filter +% -%,$(MSR_RTL_ARGS))

include mk/*.mk

bench: setup $(BENCH_DEPS)

# The builds and proofs the tests need run two at a time (the formal jobs on one core beside
# the harness builds), then pytest.
test: setup
	@$(MAKE) --no-print-directory -j 2 test-deps
	$(ENV) python -m pytest $(PYTEST_JOBS) $(PYTEST_ARGS)

.PHONY: test-deps
test-deps: $(TEST_DEPS)

clean:
	rm -rf build out sim_build
	find . -name __pycache__ -prune -exec rm -rf {} + 2>/dev/null || true
