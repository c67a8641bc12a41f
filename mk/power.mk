# make power: power from simulated switching activity (docs/asic.md "Power"; the package
# msr_flow.power, flow/msr_flow/power/). A harness built with FST tracing of plain vectors (no
# --trace-structs, so a packed struct is one vector, as in the mapped netlist) renders a small
# frame per decision rule; the toggles and high times of every register go into OpenSTA
# (set_power_activity -pins) on the mapped engine and top; the tile-buffer accesses are priced
# with the cited SRAM figures. Writes build/asic/power.json and the power section of docs/asic.md.
#   make power                       about 15 min on an idle 2-core machine when make asic's
#                                    netlists are cached (build/asic/*.stamp); longer otherwise
#   make power POWER_ARGS="--width 96 --height 64"   a smaller activity frame
#   make power-doc                   docs/asic.md's power section again from docs/asic.json
POWER_ARGS ?=
POWER_HARNESS := build/power/harness/Vmsr_sim_top
$(POWER_HARNESS): $(SIM_RTL) $(SIM_CPP) sim/msr_dpi.h sim/msr_regs.h rtl/msr.f mk/sim.mk mk/power.mk build/renderer/libmsr_render.so
	@mkdir -p $(@D)
	@echo "make power: building the traced harness into $(@D) (log: $(@D)/build.log)"
	@$(ENV) verilator $(SIM_VFLAGS) --trace-fst -Mdir $(@D) -o Vmsr_sim_top $(MSR_RTL_OPTS) $(SIM_RTL) \
	    $(SIM_CPP) > $(@D)/build.log 2>&1 || { tail -40 $(@D)/build.log; exit 1; }

.PHONY: power power-doc power-harness
power-harness: setup renderer $(POWER_HARNESS)

power: setup renderer $(POWER_HARNESS)
	$(ENV) python scripts/power.py --harness $(POWER_HARNESS) $(POWER_ARGS)

power-doc: setup
	$(ENV) python scripts/power.py --doc-only
