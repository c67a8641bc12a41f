// Negative test of msr_axil_checker: every AXI4-Lite signal free, reset in the first cycle,
// every rule but rule VIOL assumed kept; the bmc job must fail on exactly that rule's assertion.
module msr_axil_checker_neg #(
  parameter int unsigned VIOL = 0
) (
  input logic       clk_i,
  input logic       rst_ni,
  input logic [3:0] awaddr,
  input logic [2:0] awprot,
  input logic       awvalid,
  input logic       awready,
  input logic [7:0] wdata,
  input logic [0:0] wstrb,
  input logic       wvalid,
  input logic       wready,
  input logic [1:0] bresp,
  input logic       bvalid,
  input logic       bready,
  input logic [3:0] araddr,
  input logic [2:0] arprot,
  input logic       arvalid,
  input logic       arready,
  input logic [7:0] rdata,
  input logic [1:0] rresp,
  input logic       rvalid,
  input logic       rready
);
  logic [7:0] viol;
  msr_axil_checker #(.ADDR_W(4), .DATA_W(8), .MAX_OUT(3)) u_chk (
    .clk_i, .rst_ni, .awaddr, .awprot, .awvalid, .awready, .wdata, .wstrb, .wvalid, .wready,
    .bresp, .bvalid, .bready, .araddr, .arprot, .arvalid, .arready, .rdata, .rresp, .rvalid,
    .rready, .viol_o(viol)
  );
  logic init_q = 1'b1;
  always_ff @(posedge clk_i) init_q <= 1'b0;
  always_comb begin
    if (init_q) assume (!rst_ni);
    else assume (rst_ni);
    assume ((viol & ~(8'd1 << VIOL)) == '0);
  end
endmodule
