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
bind msr_fb_writer msr_axi4_w_checker #(
  .ADDR_W(32), .DATA_W(AXI_DATA_W), .ID_W(ID_W), .MAX_OUT(2 * MAX_OUT)
) u_axi4_w_chk (
  .clk_i, .rst_ni(rst_ni && !clear_i),
  .awid(m_axi_awid), .awaddr(m_axi_awaddr), .awlen(m_axi_awlen), .awsize(m_axi_awsize),
  .awburst(m_axi_awburst), .awlock(m_axi_awlock), .awcache(m_axi_awcache),
  .awprot(m_axi_awprot), .awvalid(m_axi_awvalid), .awready(m_axi_awready),
  .wdata(m_axi_wdata), .wstrb(m_axi_wstrb), .wlast(m_axi_wlast), .wvalid(m_axi_wvalid),
  .wready(m_axi_wready), .bid(m_axi_bid), .bresp(m_axi_bresp), .bvalid(m_axi_bvalid),
  .bready(m_axi_bready), .viol_o()
);
bind msr_regs msr_axil_checker #(.ADDR_W(7), .DATA_W(32), .MAX_OUT(15)) u_axil_chk (
  .clk_i(clk), .rst_ni(arst_n),
  .awaddr(s_axil_awaddr), .awprot(s_axil_awprot), .awvalid(s_axil_awvalid),
  .awready(s_axil_awready), .wdata(s_axil_wdata), .wstrb(s_axil_wstrb),
  .wvalid(s_axil_wvalid), .wready(s_axil_wready), .bresp(s_axil_bresp),
  .bvalid(s_axil_bvalid), .bready(s_axil_bready), .araddr(s_axil_araddr),
  .arprot(s_axil_arprot), .arvalid(s_axil_arvalid), .arready(s_axil_arready),
  .rdata(s_axil_rdata), .rresp(s_axil_rresp), .rvalid(s_axil_rvalid),
  .rready(s_axil_rready), .viol_o()
);
