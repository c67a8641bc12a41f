// Formal harness of msr_shift_add_mul (small widths; the design is the same at every width):
// loads of any operands and step counts at any moment, clears at any moment. Proves: done_o
// rises exactly steps_i clocks after a load (at once for 0) and holds until the next load or
// clear; once done after a load with no clear since, the product is a * (b >> (B_W - steps)),
// the multiplier left-aligned as the budget controller hands it over.
`include "msr_flops.svh"

module msr_shift_add_mul_fv #(
  parameter int unsigned A_W = 5,
  parameter int unsigned B_W = 4,
  localparam int unsigned P_W = A_W + B_W,
  localparam int unsigned S_W = $clog2(B_W + 1)
) (
  input logic           clk_i, rst_ni,
  input logic           clear_i, load_i,
  input logic [A_W-1:0] a_i,
  input logic [B_W-1:0] b_i,
  input logic [S_W-1:0] steps_i
);
  logic           done;
  logic [P_W-1:0] prod;

  msr_fv_init #(.ONCE(1'b1)) u_init (.clk_i, .rst_ni, .init_o());

  always_comb if (load_i) assume (steps_i <= S_W'(B_W));

  msr_shift_add_mul #(.A_W(A_W), .B_W(B_W)) dut (
    .clk_i, .rst_ni, .clear_i, .load_i, .a_i, .b_i, .steps_i, .done_o(done), .prod_o(prod)
  );

  // The harness's record of the last load: its operands, the product expected and the clocks
  // left; valid until a clear.
  logic           rec_q;
  logic [P_W-1:0] want_q;
  logic [S_W-1:0] left_q;
  logic           one_q;                    // the last load was of one step
  wire  [P_W-1:0] want = P_W'(a_i) * P_W'(b_i >> (S_W'(B_W) - steps_i));
  `MSR_CLR_REG(u_rec_q, 1, clear_i, load_i, 1'b1, rec_q)
  `MSR_CLR_REG(u_left_q, S_W, clear_i, load_i || left_q != '0,
               load_i ? steps_i : left_q - S_W'(1), left_q)
  always_ff @(posedge clk_i) begin
    if (load_i) begin
      want_q <= want;
      one_q  <= steps_i == S_W'(1);
    end
  end

  a_done:    assert property (@(posedge clk_i) disable iff (!rst_ni) done == (left_q == '0));
  a_product: assert property (@(posedge clk_i) disable iff (!rst_ni) !(rec_q && done) || prod == want_q);

  // Non-vacuity: a full-width product of the largest operands, and a short one.
  c_full:  cover property (@(posedge clk_i) disable iff (!rst_ni)
                           rec_q && done && want_q == P_W'((2**A_W - 1) * (2**B_W - 1)));
  c_short: cover property (@(posedge clk_i) disable iff (!rst_ni)
                           rec_q && done && one_q && prod != '0);
endmodule
