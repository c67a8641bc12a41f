// The reset every formal harness under formal/ starts from: rst_ni assumed low in the first
// cycle (init_o high then); afterwards, with ONCE, assumed high for the rest of the run, else
// free (reset may come again at any time). Formal only (FORMAL, make formal).
module msr_fv_init #(
  parameter bit ONCE = 1'b0
) (
  input  logic clk_i,
  input  logic rst_ni,
  output logic init_o    // the first cycle
);
  logic init_q = 1'b1;
  always_ff @(posedge clk_i) init_q <= 1'b0;
  assign init_o = init_q;
  always_comb begin
    if (init_q) assume (!rst_ni);
    else if (ONCE) assume (rst_ni);
  end
endmodule
