// The one source-of-truth file list (package first, then primitives, engine, system).
// Every flow reads it: cocotb, the Verilator harness, make lint, make synth, msr.core.
+incdir+rtl/prim
rtl/msr_pkg.sv
rtl/prim/msr_lzc.sv
rtl/prim/msr_clr_reg.sv
rtl/prim/msr_seg_add.sv
rtl/prim/msr_rr_arb.sv
rtl/prim/msr_fifo.sv
rtl/prim/msr_spill_reg.sv
rtl/prim/msr_tile_sram.sv
rtl/engine/msr_base_decision.sv
rtl/engine/msr_decision_pipe.sv
rtl/engine/msr_level_ctrl.sv
rtl/engine/msr_tile_stream.sv
rtl/engine/msr_tag_pool.sv
rtl/engine/msr_tile_ctx.sv
rtl/engine/msr_tile_engine.sv
rtl/regs/msr_regs_pkg.sv
rtl/regs/msr_regs.sv
rtl/system/msr_sys_pkg.sv
rtl/system/msr_sat_counter.sv
rtl/system/msr_cfg_ctrl.sv
rtl/system/msr_tile_gen.sv
rtl/system/msr_render_mux.sv
rtl/system/msr_fb_writer.sv
rtl/system/msr_perf_counters.sv
rtl/system/msr_top.sv
