// Negative test of msr_axi4_w_checker: every AXI signal free, reset in the first cycle, and
// every rule but rule VIOL assumed kept. The bmc job must then fail on exactly the assertion
// of rule VIOL (formal/run_formal.py checks the label): each assertion can fire, and fires on
// its own rule.
module msr_axi4_w_checker_neg #(
  parameter int unsigned VIOL = 0
) (
  input logic       clk_i,
  input logic       rst_ni,
  input logic [1:0] awid,
  input logic [15:0] awaddr,
  input logic [7:0] awlen,
  input logic [2:0] awsize,
  input logic [1:0] awburst,
  input logic       awlock,
  input logic [3:0] awcache,
  input logic [2:0] awprot,
  input logic       awvalid,
  input logic       awready,
  input logic [7:0] wdata,
  input logic [0:0] wstrb,
  input logic       wlast,
  input logic       wvalid,
  input logic       wready,
  input logic [1:0] bid,
  input logic [1:0] bresp,
  input logic       bvalid,
  input logic       bready
);
  logic [8:0] viol;
  msr_axi4_w_checker #(.ADDR_W(16), .DATA_W(8), .ID_W(2), .MAX_OUT(2)) u_chk (
    .clk_i, .rst_ni, .awid, .awaddr, .awlen, .awsize, .awburst, .awlock, .awcache, .awprot,
    .awvalid, .awready, .wdata, .wstrb, .wlast, .wvalid, .wready, .bid, .bresp, .bvalid, .bready,
    .viol_o(viol)
  );
  logic init_q = 1'b1;
  always_ff @(posedge clk_i) init_q <= 1'b0;
  always_comb begin
    if (init_q) assume (!rst_ni);
    else assume (rst_ni);
    assume ((viol & ~(9'd1 << VIOL)) == '0);
  end
endmodule
