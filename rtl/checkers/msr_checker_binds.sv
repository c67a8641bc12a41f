// Binds the protocol checkers to every instance of the accelerator's two AXI ports, in any
// simulation that compiles this file after rtl/msr.f and rtl/checkers/checkers.f with
// assertions on (Verilator --assert): the AXI4 write master of msr_fb_writer and the AXI4-Lite
// slave msr_regs. A module that is not in the design is simply not bound. MAX_OUT leaves room
// above what each block can have open (msr_fb_writer: MAX_OUT bursts; msr_regs: a few reads).
// The AXI4 checker is reset with the writer's clear_i as well: a forced clear (watchdog, a soft
// reset's drain cut by force) withdraws an offered AW or W and forgets owed beats and B
// responses on purpose (AXI has no abort; docs/system.md, "Watchdog"); a normal clear comes
// only when the writer is idle, where resetting the checker changes nothing. A B response
// that arrives after a forced clear is still an orphan for the checker, as for the RTL.
`include "msr_chk_axi.svh"
bind msr_fb_writer msr_axi4_w_checker #(
  .ADDR_W(32), .DATA_W(AXI_DATA_W), .ID_W(ID_W), .MAX_OUT(2 * MAX_OUT)
) u_axi4_w_chk (
  .clk_i, .rst_ni(rst_ni && !clear_i), `MSR_AXI4_W_CONN(, m_axi_), .viol_o()
);
bind msr_axil_cpuif msr_axil_checker #(.ADDR_W(ADDR_W), .DATA_W(DATA_W), .MAX_OUT(15)) u_axil_chk (
  .clk_i, .rst_ni, `MSR_AXIL_CONN(, s_axil_), .viol_o()
);
