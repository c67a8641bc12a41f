rtl/msr_pkg.sv
rtl/msr_decide.sv
rtl/msr_interp.sv
rtl/msr_tile_sram.sv
rtl/msr_level_ctrl.sv
rtl/msr_tile_stream.sv
rtl/tile_engine.sv
