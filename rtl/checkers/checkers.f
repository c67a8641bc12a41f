// Protocol checkers: simulation and formal only, never synthesised (not in rtl/msr.f).
// Add this list after rtl/msr.f and build with assertions on (Verilator --assert); then
// rtl/checkers/msr_checker_binds.sv binds them to msr_fb_writer and msr_regs.
// msr_chk_axi.svh: the AXI port-list macros the checkers and their binds include (listed
// first so that a build that depends on this list sees it change).
rtl/checkers/msr_chk_axi.svh
rtl/checkers/msr_chk_stable.sv
rtl/checkers/msr_axi4_w_checker.sv
rtl/checkers/msr_axil_checker.sv
