// The register interface of the accelerator: the AXI4-Lite front end (msr_axil_cpuif) in
// front of the register block generated from rtl/regs/msr_regs.rdl (msr_regs, PeakRDL's
// passthrough CPU interface). Every request reaches the block from a flip-flop of the front
// end, so a write reaches a field through its address compare and enable only (docs/system.md).
module msr_reg_if (
  input  logic                         clk_i,     // clock
  input  logic                         rst_ni,    // asynchronous reset, active low
  // AXI4-Lite slave (7-bit byte address)
  input  logic                         s_axil_awvalid,
  output logic                         s_axil_awready,
  input  logic [6:0]                   s_axil_awaddr,
  input  logic [2:0]                   s_axil_awprot,
  input  logic                         s_axil_wvalid,
  output logic                         s_axil_wready,
  input  logic [31:0]                  s_axil_wdata,
  input  logic [3:0]                   s_axil_wstrb,
  output logic                         s_axil_bvalid,
  input  logic                         s_axil_bready,
  output logic [1:0]                   s_axil_bresp,
  input  logic                         s_axil_arvalid,
  output logic                         s_axil_arready,
  input  logic [6:0]                   s_axil_araddr,
  input  logic [2:0]                   s_axil_arprot,
  output logic                         s_axil_rvalid,
  input  logic                         s_axil_rready,
  output logic [31:0]                  s_axil_rdata,
  output logic [1:0]                   s_axil_rresp,
  // the fields, to and from the hardware
  input  msr_regs_pkg::msr_regs__in_t  hwif_in_i,
  output msr_regs_pkg::msr_regs__out_t hwif_out_o
);

  // The AXI4-Lite front end registers every request before the block decodes it.
  logic                 cpuif_req, cpuif_req_is_wr, cpuif_stall_wr, cpuif_stall_rd;
  logic [6:0]           cpuif_addr;
  logic [31:0]          cpuif_wr_data, cpuif_wr_biten, cpuif_rd_data;
  logic                 cpuif_rd_ack, cpuif_rd_err, cpuif_wr_ack, cpuif_wr_err;

  msr_axil_cpuif #(.ADDR_W(7), .DATA_W(32)) u_axil (
    .clk_i, .rst_ni,
    .s_axil_awvalid, .s_axil_awready, .s_axil_awaddr, .s_axil_awprot,
    .s_axil_wvalid, .s_axil_wready, .s_axil_wdata, .s_axil_wstrb,
    .s_axil_bvalid, .s_axil_bready, .s_axil_bresp,
    .s_axil_arvalid, .s_axil_arready, .s_axil_araddr, .s_axil_arprot,
    .s_axil_rvalid, .s_axil_rready, .s_axil_rdata, .s_axil_rresp,
    .cpuif_req_o          (cpuif_req),
    .cpuif_req_is_wr_o    (cpuif_req_is_wr),
    .cpuif_addr_o         (cpuif_addr),
    .cpuif_wr_data_o      (cpuif_wr_data),
    .cpuif_wr_biten_o     (cpuif_wr_biten),
    .cpuif_req_stall_wr_i (cpuif_stall_wr),
    .cpuif_req_stall_rd_i (cpuif_stall_rd),
    .cpuif_rd_ack_i       (cpuif_rd_ack),
    .cpuif_rd_err_i       (cpuif_rd_err),
    .cpuif_rd_data_i      (cpuif_rd_data),
    .cpuif_wr_ack_i       (cpuif_wr_ack),
    .cpuif_wr_err_i       (cpuif_wr_err)
  );

  msr_regs u_regs (
    .clk                  (clk_i),
    .arst_n               (rst_ni),
    .s_cpuif_req          (cpuif_req),
    .s_cpuif_req_is_wr    (cpuif_req_is_wr),
    .s_cpuif_addr         (cpuif_addr),
    .s_cpuif_wr_data      (cpuif_wr_data),
    .s_cpuif_wr_biten     (cpuif_wr_biten),
    .s_cpuif_req_stall_wr (cpuif_stall_wr),
    .s_cpuif_req_stall_rd (cpuif_stall_rd),
    .s_cpuif_rd_ack       (cpuif_rd_ack),
    .s_cpuif_rd_err       (cpuif_rd_err),
    .s_cpuif_rd_data      (cpuif_rd_data),
    .s_cpuif_wr_ack       (cpuif_wr_ack),
    .s_cpuif_wr_err       (cpuif_wr_err),
    .hwif_in              (hwif_in_i),
    .hwif_out             (hwif_out_o)
  );

endmodule : msr_reg_if
