# Hardware throughput of the whole accelerator (`make bench`): msr_top through the
# Verilator harness, one harness per (NUM_ENGINES, MAX_OUTSTANDING) under build/bench/, swept by
# scripts/bench_hw.py -> out/bench/report.json and out/bench/pixels_per_clock.png.
# Same flags as `make sim` (SIM_VFLAGS of mk/sim.mk, used in the recipe, so it is expanded late);
# the source lists are named here because mk/sim.mk is included after this file and
# prerequisites are expanded when the rule is read (MSR_RTL_FILES: the top Makefile).
BENCH_HW_RTL  := $(MSR_RTL_FILES) sim/render_dpi.sv sim/msr_sim_top.sv
BENCH_HW_CPP  := sim/harness.cpp sim/msr_dpi.cpp
# Harness builds: e<N>_mo<M>[_c<C>][_rl<L>][_t<T>][_cy<Y>] = NUM_ENGINES N, MAX_OUTSTANDING M (64 is the default of msr_top;
# e1_mo16 shows what fewer tags cost one engine at long latencies, and is the one build
# scripts/tests/test_bench_hw.py needs), NUM_CTX C, the tile buffers' read latency L (RD_LAT),
# the largest tile T the buffers hold (TILE_LIMIT), the buffers' cycle Y (BUF_CYCLE).
BENCH_HW_CFGS ?= e1_mo16 e1_mo64 e2_mo64 e4_mo64
# The -G flags of a build name's stem (e4_mo64_c6_rl4_t16_cy5 -> NUM_ENGINES 4, MAX_OUTSTANDING 64,
# NUM_CTX 6, RD_LAT 4, TILE_LIMIT 16, BUF_CYCLE 5), for both build rules below.
bench_nocy    = $(firstword $(subst _cy, ,$(1)))
bench_base    = $(firstword $(subst _rl, ,$(firstword $(subst _t, ,$(call bench_nocy,$(1))))))
bench_gflags  = -GNUM_ENGINES=$(word 1,$(subst _mo, ,$(patsubst e%,%,$(1)))) \
    -GMAX_OUTSTANDING=$(word 1,$(subst _c, ,$(word 2,$(subst _mo, ,$(call bench_base,$(1)))))) \
    $(if $(findstring _c,$(1)),-GNUM_CTX=$(lastword $(subst _c, ,$(call bench_base,$(1))))) \
    $(if $(findstring _rl,$(1)),-GRD_LAT=$(firstword $(subst _t, ,$(lastword $(subst _rl, ,$(call bench_nocy,$(1))))))) \
    $(if $(findstring _t,$(1)),-GTILE_LIMIT=$(lastword $(subst _t, ,$(call bench_nocy,$(1))))) \
    $(if $(findstring _cy,$(1)),-GBUF_CYCLE=$(lastword $(subst _cy, ,$(1))))
BENCH_HW_BINS  = $(foreach c,$(BENCH_HW_CFGS),build/bench/hw_$(c)/Vmsr_sim_top)
BENCH_HW_ARGS ?=
# MSR_BENCH_RULE=lindilate (the environment, or --rule in BENCH_HW_ARGS): the decision rule of every
# point, CONFIG.RULE and the golden model's; default patent. report.json's setup records it.

build/bench/hw_%/Vmsr_sim_top: $(BENCH_HW_RTL) $(BENCH_HW_CPP) sim/msr_dpi.h sim/msr_regs.h rtl/msr.f \
        mk/sim.mk build/renderer/libmsr_render.so
	@mkdir -p $(@D)
	@echo "make bench: building the Verilator harness $* into $(@D) (log: $(@D)/build.log)"
	@$(ENV) verilator $(SIM_VFLAGS) $(call bench_gflags,$*) -Mdir $(@D) -o Vmsr_sim_top \
	    $(MSR_RTL_OPTS) $(BENCH_HW_RTL) $(BENCH_HW_CPP) > $(@D)/build.log 2>&1 || { tail -40 $(@D)/build.log; exit 1; }

.PHONY: bench-hw bench-hw-build
bench-hw-build: setup renderer $(BENCH_HW_BINS)

# After bench-engine: its out/bench/engine.json (decisions per clock in a pass) is merged in.
bench-hw: setup renderer $(BENCH_HW_BINS) bench-engine
	$(ENV) python scripts/bench_hw.py --configs "$(BENCH_HW_CFGS)" $(BENCH_HW_ARGS)
BENCH_DEPS += bench-hw
# scripts/tests/test_bench_hw.py runs a tiny sweep on the one-engine harness.
TEST_DEPS += build/bench/hw_e1_mo16/Vmsr_sim_top

# Tile-buffer bits against throughput (`make bench-bits`, not part of make test):
# scripts/bench_bits.py sweeps NUM_CTX, and LINDILATE 0 against 1 for the patent rule, on 4
# engines at render latencies 64, 256 and 1024 in both rules; it builds the harnesses it needs
# one at a time (this file's rules) -> build/bench/tile_bits.json, committed as data/bench/tile_bits.json.
# e<N>_mo<M>_c<C>_l0: the same harness with msr_top's LINDILATE 0 (no third tile-buffer port,
# the patent rule only). msr_sim_top has no LINDILATE parameter, so the build compiles a copy
# of it with LINDILATE (0) given to msr_top; sim/ is left as it is. The shorter stem makes make
# pick this rule over the one above for these names.
build/bench/hw_%_l0/Vmsr_sim_top: $(BENCH_HW_RTL) $(BENCH_HW_CPP) sim/msr_dpi.h sim/msr_regs.h rtl/msr.f \
        mk/sim.mk build/renderer/libmsr_render.so
	@mkdir -p $(@D)
	@echo "make bench: building the Verilator harness $*_l0 (LINDILATE 0) into $(@D) (log: $(@D)/build.log)"
	@sed 's/^\(\s*\.NUM_CTX\s*(NUM_CTX),\)/\1 .LINDILATE (0),/' sim/msr_sim_top.sv > $(@D)/msr_sim_top.sv
	@grep -q '\.LINDILATE (0)' $(@D)/msr_sim_top.sv || { echo "no .NUM_CTX (NUM_CTX), line in sim/msr_sim_top.sv"; exit 1; }
	@$(ENV) verilator $(SIM_VFLAGS) $(call bench_gflags,$*) -Mdir $(@D) -o Vmsr_sim_top \
	    $(MSR_RTL_OPTS) $(filter-out sim/msr_sim_top.sv,$(BENCH_HW_RTL)) $(@D)/msr_sim_top.sv \
	    $(BENCH_HW_CPP) > $(@D)/build.log 2>&1 || { tail -40 $(@D)/build.log; exit 1; }

BENCH_BITS_ARGS ?=
.PHONY: bench-bits
bench-bits: setup renderer
	$(ENV) python scripts/bench_bits.py $(BENCH_BITS_ARGS)
