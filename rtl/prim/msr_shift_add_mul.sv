// Sequential shift-add multiplier: one multiplier bit per clock, stopping as soon as the
// multiplier's remaining bits are zero (a product by a small number is fast). For units that
// need a few products per thousands of clocks (the ray-budget controller): a few hundred LUTs
// instead of a DSP array.
//
// load_i takes a_i and b_i and clears the product; done_o is high once the product is complete
// (at once for b_i = 0, after at most B_W clocks otherwise) and it holds until the next load.
// A clear stops a product in flight (done_o rises, the product is not meaningful).
`include "msr_assert.svh"
`include "msr_flops.svh"

module msr_shift_add_mul #(
  parameter int unsigned A_W = 36,               // multiplicand bits
  parameter int unsigned B_W = 25,               // multiplier bits
  localparam int unsigned P_W = A_W + B_W        // product bits (holds any product)
) (
  input  logic           clk_i,       // clock
  input  logic           rst_ni,      // asynchronous reset, active low
  input  logic           clear_i,     // synchronous: stop
  input  logic           load_i,      // start a product (has priority over the steps)
  input  logic [A_W-1:0] a_i,         // multiplicand
  input  logic [B_W-1:0] b_i,         // multiplier
  output logic           done_o,      // the product is complete
  output logic [P_W-1:0] prod_o       // a_i * b_i once done_o
);
  logic [P_W-1:0] mc_q, acc_q;        // the multiplicand shifted to the next bit; the sum
  logic [B_W-1:0] mp_q;               // the multiplier bits left

  // done_o is a flip-flop, set from the next value of the multiplier bits: the zero test of a
  // B_W-bit register drove the divider's loads straight from the product's state (the budget
  // unit's worst path on ECP5, 91.8 MHz).
  logic done_q;
  `MSR_CLR_REG_RST(u_done_q, 1, 1'b1, clear_i, load_i || !done_q,
                   load_i ? (b_i == '0) : (mp_q[B_W-1:1] == '0), done_q)

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      mc_q  <= '0;
      mp_q  <= '0;
      acc_q <= '0;
    end else if (clear_i) begin
      mp_q  <= '0;
    end else if (load_i) begin
      mc_q  <= P_W'(a_i);
      mp_q  <= b_i;
      acc_q <= '0;
    end else if (!done_q) begin
      if (mp_q[0]) acc_q <= acc_q + mc_q;
      mc_q <= mc_q << 1;
      mp_q <= mp_q >> 1;
    end
  end

  assign done_o = done_q;
  assign prod_o = acc_q;

  /* verilator lint_off SYNCASYNCNET */
  `MSR_ASSERT(a_done_is_zero, done_q == (mp_q == '0))
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_shift_add_mul
