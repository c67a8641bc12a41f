// Negative test of msr_axil_checker: every AXI4-Lite signal free, reset in the first cycle,
// every rule but rule VIOL assumed kept; the bmc job must fail on exactly that rule's assertion.
`include "msr_chk_axi.svh"

module msr_axil_checker_neg #(
  parameter int unsigned VIOL = 0
) (
  input logic       clk_i,
  input logic       rst_ni,
  `MSR_AXIL_PORTS(input, input, 4, 8)
);
  logic [7:0] viol;
  msr_axil_checker #(.ADDR_W(4), .DATA_W(8), .MAX_OUT(3)) u_chk (
    .clk_i, .rst_ni, `MSR_AXIL_CONN(, ), .viol_o(viol)
  );
  msr_fv_init #(.ONCE(1'b1)) u_init (.clk_i, .rst_ni, .init_o());
  always_comb assume ((viol & ~(8'd1 << VIOL)) == '0);
endmodule
