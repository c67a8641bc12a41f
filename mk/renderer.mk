# The rendering unit: the Embree 3 ray tracer as one shared library, used by the
# Python golden model (ctypes) and the RTL simulation (DPI-C), plus its GoogleTest unit tests.
# One set of flags for every object, so every flow gets bit-identical pixels.
RENDER_DIR      := sw_model/renderer
RENDER_BUILD    := build/renderer
RENDER_LIB      := $(RENDER_BUILD)/libmsr_render.so
RENDER_TEST_BIN := $(RENDER_BUILD)/renderer_tests
RENDER_SRCS     := $(wildcard $(RENDER_DIR)/src/*.cpp)
RENDER_OBJS     := $(patsubst $(RENDER_DIR)/src/%.cpp,$(RENDER_BUILD)/obj/%.o,$(RENDER_SRCS))
RENDER_TSRCS    := $(wildcard $(RENDER_DIR)/tests/*.cpp)
RENDER_TOBJS    := $(patsubst $(RENDER_DIR)/tests/%.cpp,$(RENDER_BUILD)/test_obj/%.o,$(RENDER_TSRCS))
RENDER_CXX      ?= g++
RENDER_CXXFLAGS := -std=c++17 -O2 -ffp-contract=off -fPIC -Wall -Wextra -MMD -MP -I$(RENDER_DIR)/include
RENDER_LDLIBS   := -lembree3 -lassimp

.PHONY: renderer renderer-tests
renderer: setup $(RENDER_LIB)

renderer-tests: setup $(RENDER_LIB) $(RENDER_TEST_BIN)

$(RENDER_BUILD)/obj/%.o: $(RENDER_DIR)/src/%.cpp mk/renderer.mk
	@mkdir -p $(@D)
	$(RENDER_CXX) $(RENDER_CXXFLAGS) -c $< -o $@

$(RENDER_BUILD)/test_obj/%.o: $(RENDER_DIR)/tests/%.cpp mk/renderer.mk
	@mkdir -p $(@D)
	$(RENDER_CXX) $(RENDER_CXXFLAGS) -I$(RENDER_DIR)/src -c $< -o $@

# Linked to a temporary name and renamed, so a process loading the library never sees half a file.
$(RENDER_LIB): $(RENDER_OBJS) $(RENDER_DIR)/src/exports.map
	$(RENDER_CXX) -shared -Wl,-Bsymbolic -Wl,--version-script=$(RENDER_DIR)/src/exports.map \
	    -o $@.tmp $(RENDER_OBJS) $(RENDER_LDLIBS)
	mv -f $@.tmp $@

$(RENDER_TEST_BIN): $(RENDER_TOBJS) $(RENDER_OBJS)
	$(RENDER_CXX) -o $@ $(RENDER_TOBJS) $(RENDER_OBJS) -lgtest -lgtest_main -pthread $(RENDER_LDLIBS)

-include $(RENDER_OBJS:.o=.d) $(RENDER_TOBJS:.o=.d)

TEST_DEPS += renderer renderer-tests

# Renderer benchmark: 1920x1080 reference render time and rays/s per built-in scene.
.PHONY: bench-renderer
bench-renderer: renderer
	$(ENV) python scripts/bench_renderer.py
BENCH_DEPS += bench-renderer
