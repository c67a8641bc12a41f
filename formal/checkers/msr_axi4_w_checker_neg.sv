// Negative test of msr_axi4_w_checker: every AXI signal free, reset in the first cycle, and
// every rule but rule VIOL assumed kept. The bmc job must then fail on exactly the assertion
// of rule VIOL (formal/run_formal.py checks the label): each assertion can fire, and fires on
// its own rule.
`include "msr_chk_axi.svh"

module msr_axi4_w_checker_neg #(
  parameter int unsigned VIOL = 0
) (
  input logic       clk_i,
  input logic       rst_ni,
  `MSR_AXI4_W_PORTS(input, input, 16, 8, 2)
);
  logic [8:0] viol;
  msr_axi4_w_checker #(.ADDR_W(16), .DATA_W(8), .ID_W(2), .MAX_OUT(2)) u_chk (
    .clk_i, .rst_ni, `MSR_AXI4_W_CONN(, ), .viol_o(viol)
  );
  msr_fv_init #(.ONCE(1'b1)) u_init (.clk_i, .rst_ni, .init_o());
  always_comb assume ((viol & ~(9'd1 << VIOL)) == '0);
endmodule
