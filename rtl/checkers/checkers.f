// Protocol checkers: simulation and formal only, never synthesised (not in rtl/msr.f).
// Add this list after rtl/msr.f and build with assertions on (Verilator --assert); then
// rtl/checkers/msr_checker_binds.sv binds them to msr_fb_writer and msr_regs.
rtl/checkers/msr_chk_stable.sv
rtl/checkers/msr_axi4_w_checker.sv
rtl/checkers/msr_axil_checker.sv
