# make sim: one frame of a scene through the RTL (Verilator C++ harness, Embree over DPI-C)
# and the golden model; see docs/spec/contracts.md "Full simulation" and docs/system.md.
# The harness is built without tracing; WAVES=1 builds a second one with FST tracing.
SIM_WAVES_ON := $(filter 1 yes true,$(WAVES))
# BUDGET=N or BUDGET=P% (docs/budget.md): the frame holds a ray budget of N traced pixels (P % of
# the frame); the harness is then a build of msr_top with the budget controller (BUDGET_EN 1),
# in its own folder. Without BUDGET the harness is the default top, as before.
BUDGET       ?=
# FRAMES=N [CAMERA_PATH=file]: a sequence of N frames through the RTL in one harness run, the
# camera moving along the path (default: the scene's default orbit, a full turn about its framed
# centre in 96 frames, msr_model.camera_path); OUT gets sequence.json, frame_KKKK.png,
# sequence.webp / .gif, summary_strip.png. REUSE=1 (reuse across frames) is refused with exit
# status 2 until the hardware has it.
FRAMES       ?=
CAMERA_PATH  ?=
# GAZE=X,Y: the gaze point in pixels (docs/spec/contracts.md "Gaze"): the foveation (FOV_GAIN) centres
# there; empty: the default, the centre of the tile grid. run_sim.py refuses one outside the frame.
GAZE         ?=
REUSE        ?=
# Refused before the harness is built (run_sim.py --reuse refuses it too).
ifneq ($(filter sim,$(MAKECMDGOALS)),)
ifneq ($(filter-out 0 no false,$(strip $(REUSE))),)
$(error make sim: error: REUSE=$(REUSE): reuse across frames is not in the hardware yet)
endif
endif
# DEPTH=1: the engines' depth channel (docs/architecture.md "The depth channel"): the harness is a
# build of msr_top with DEPTH_EN 1 in its own folder; OUT gets depth.png and the report compares
# every pixel's inverse depth with the golden model's (msr_model.reuse, without reuse).
DEPTH        ?=
SIM_BUDGET_ON := $(strip $(BUDGET))
SIM_DEPTH_ON := $(filter 1 yes true,$(DEPTH))
SIM_BUILD    := build/sim/$(if $(SIM_WAVES_ON),waves,fast)$(if $(SIM_BUDGET_ON),_budget)$(if $(SIM_DEPTH_ON),_depth)
SIM_BIN      := $(SIM_BUILD)/Vmsr_sim_top
SIM_RTL      := $(MSR_RTL_FILES) sim/render_dpi.sv sim/msr_sim_top.sv
SIM_CPP      := sim/harness.cpp sim/msr_dpi.cpp
SIM_SCENE_LABEL = $(if $(findstring /,$(SCENE))$(findstring .,$(SCENE)),$(basename $(notdir $(SCENE))),$(SCENE))
SIM_OUT      = $(if $(OUT),$(OUT),out/sim/$(SIM_SCENE_LABEL))
SIM_THREADS  ?= 1
WAVE_TILE    ?=
# RULE= the decision rule (default patent; lindilate), written to CONFIG.RULE (harness --rule) and
# given to the golden model; run_sim.py refuses any other name with exit status 2. The script's last
# line says passed / error (bad input) / failed.
RULE         ?=
WAVE_CYCLES  ?=

# -O3 on the Verilator side, -O1 for the generated C++'s per-clock code (OPT_FAST) and -O0 for its
# set-up code (OPT_SLOW), no assertions, no tracing: measured on the default 640x480 frame, -O1
# simulates as fast as -O2 (44 000 to 48 000 cycles/s either way) and compiles in 90 CPU-seconds
# instead of 300. No -O in CFLAGS: it comes after OPT_* on the compiler's command line and would
# override both.
# The wheel's verilated.mk leaves CFG_CXXFLAGS_PCH_I empty, which breaks the precompiled header.
# --public-params: the build's parameters (NUM_ENGINES, ...) as constants the harness writes
# into its stats file, so no script repeats them.
SIM_VFLAGS := --cc --exe --build -j 2 -O3 --x-assign fast --x-initial fast --noassert -Wno-fatal \
    --top-module msr_sim_top --threads $(SIM_THREADS) --public-params \
    -CFLAGS "-I$(CURDIR)/sim -I$(CURDIR)/sw_model/renderer/include" \
    -LDFLAGS "-L$(CURDIR)/build/renderer -lmsr_render -Wl,-rpath,$(CURDIR)/build/renderer" \
    -MAKEFLAGS "OPT_FAST=-O1 OPT_SLOW=-O0 OPT_GLOBAL=-O1 PYTHON3=python3 CFG_CXXFLAGS_PCH_I=-include"

# build/sim/{fast,waves}[_budget]/: the folder names the build (tracing; the budget controller).
build/sim/%/Vmsr_sim_top: $(SIM_RTL) $(SIM_CPP) sim/msr_dpi.h sim/msr_regs.h rtl/msr.f mk/sim.mk build/renderer/libmsr_render.so
	@mkdir -p $(@D)
	@echo "make sim: building the Verilator harness into $(@D) (log: $(@D)/build.log)"
	@$(ENV) verilator $(SIM_VFLAGS) $(if $(findstring waves,$*),--trace-fst --trace-structs) \
	    $(if $(findstring budget,$*),-GBUDGET_EN=1) $(if $(findstring depth,$*),-GDEPTH_EN=1) -Mdir $(@D) -o Vmsr_sim_top $(MSR_RTL_OPTS) $(SIM_RTL) \
	    $(SIM_CPP) > $(@D)/build.log 2>&1 || { tail -40 $(@D)/build.log; exit 1; }

.PHONY: sim-build
sim-build: setup renderer $(SIM_BIN)
# The same harness with assertions on: --assert, the RTL's MSR_ASSERT/MSR_COVER and the AXI
# protocol checkers of rtl/checkers bound to msr_fb_writer and msr_regs (checkers.f, then
# msr_checker_binds.sv, after rtl/msr.f). make test runs one small frame through it
# (tb/msr_sim/test_assert_harness.py); make sim keeps the fast build above. No tracing.
# Compiled at -O1 (-O0 for set-up code), split into small files: the assertions make the model
# large, and at -O2 its two grouped files took 20 minutes of make test's set-up to compile,
# against about 2 at -O1; the test's 160x120 frame runs in seconds either way.
SIM_ASSERT_BIN := build/sim/assert/Vmsr_sim_top
SIM_CHECKERS   := $(filter-out //%,$(shell sed 's://.*::' rtl/checkers/checkers.f)) rtl/checkers/msr_checker_binds.sv
SIM_ASSERT_VFLAGS := --cc --exe --build -j 2 -O3 --x-assign fast --x-initial fast --assert -Wno-fatal \
    --output-split 20000 --output-split-cfuncs 2000 \
    --top-module msr_sim_top --threads 1 --public-params \
    -CFLAGS "-I$(CURDIR)/sim -I$(CURDIR)/sw_model/renderer/include" \
    -LDFLAGS "-L$(CURDIR)/build/renderer -lmsr_render -Wl,-rpath,$(CURDIR)/build/renderer" \
    -MAKEFLAGS "OPT_FAST=-O1 OPT_SLOW=-O0 OPT_GLOBAL=-O1 PYTHON3=python3 CFG_CXXFLAGS_PCH_I=-include"

$(SIM_ASSERT_BIN): $(MSR_RTL_FILES) $(SIM_CHECKERS) rtl/checkers/checkers.f sim/render_dpi.sv sim/msr_sim_top.sv \
        $(SIM_CPP) sim/msr_dpi.h sim/msr_regs.h rtl/msr.f mk/sim.mk build/renderer/libmsr_render.so
	@mkdir -p $(@D)
	@echo "make sim-assert-build: building the harness with assertions and checkers into $(@D) (log: $(@D)/build.log)"
	@$(ENV) verilator $(SIM_ASSERT_VFLAGS) -Mdir $(@D) -o Vmsr_sim_top $(MSR_RTL_OPTS) $(MSR_RTL_FILES) \
	    $(SIM_CHECKERS) sim/render_dpi.sv sim/msr_sim_top.sv $(SIM_CPP) > $(@D)/build.log 2>&1 || \
	    { tail -40 $(@D)/build.log; exit 1; }

.PHONY: sim-assert-build
sim-assert-build: setup renderer $(SIM_ASSERT_BIN)
TEST_DEPS += $(SIM_ASSERT_BIN)

# tb/msr_sim runs the harness: it is built before pytest starts, not inside a pytest worker
# next to the cocotb builds (two 2-3 GB compilers at once on a 2-core machine).
TEST_DEPS += build/sim/fast/Vmsr_sim_top build/sim/fast_budget/Vmsr_sim_top build/sim/fast_depth/Vmsr_sim_top

sim: setup renderer $(SIM_BIN)
	@$(ENV) python scripts/run_sim.py --harness $(SIM_BIN) --scene "$(SCENE)" --width "$(WIDTH)" \
	    --height "$(HEIGHT)" --tile "$(TILE)" --levels "$(LEVELS)" --thr "$(THR)" --metric "$(METRIC)" \
	    --fov-gain "$(FOV_GAIN)" --gaze="$(GAZE)" --rule "$(RULE)" --budget "$(BUDGET)" --frames "$(FRAMES)" --camera-path "$(CAMERA_PATH)" --reuse "$(REUSE)" $(if $(SIM_DEPTH_ON),--depth) --out "$(SIM_OUT)" --camera="$(CAMERA)" $(if $(SIM_WAVES_ON),--waves) \
	    $(if $(WAVE_TILE),--wave-tile $(WAVE_TILE)) $(if $(WAVE_CYCLES),--wave-cycles $(WAVE_CYCLES))

# make waves / waves-shot: the run named by OUT=, else the last make sim WAVES=1 (its folder is
# recorded in build/sim/last_waves), else the default scene's folder.
WAVES_DIR = $(if $(OUT),$(OUT),$(or $(shell cat build/sim/last_waves 2>/dev/null),$(SIM_OUT)))
WAVES_SHOT ?= docs/img/waves_tile.png

.PHONY: waves waves-shot
waves:
	@test -f "$(WAVES_DIR)/waves.fst" || { echo "make waves: no $(WAVES_DIR)/waves.fst: run make sim WAVES=1 first"; exit 2; }
	gtkwave --rcvar 'splash_disable on' "$(WAVES_DIR)/waves.fst" "$(WAVES_DIR)/waves.gtkw"

# The saved layout as a picture (GTKWave under Xvfb): WAVES_SHOT=, default docs/img/waves_tile.png.
waves-shot:
	@test -f "$(WAVES_DIR)/waves.fst" || { echo "make waves-shot: no $(WAVES_DIR)/waves.fst: run make sim WAVES=1 first"; exit 2; }
	@$(ENV) python scripts/waves_shot.py "$(WAVES_DIR)/waves.fst" "$(WAVES_DIR)/waves.gtkw" "$(WAVES_SHOT)"
