// Sequential multiplier, most significant multiplier bit first (Horner: acc = 2 acc + bit * a),
// one bit per clock. For units that need a few products per thousands of clocks (the ray-budget
// controller): one accumulate adder and no shifting multiplicand, instead of a DSP array.
//
// The caller gives the multiplier left-aligned: its steps_i bits at the top of b_i (bits below
// them are ignored), so a narrow operand takes only its own width in clocks and the alignment is
// wiring at the caller (each product there has a fixed operand width).
//
// load_i takes a_i, b_i and steps_i and clears the product; done_o is high once the product
// a_i * (b_i >> (B_W - steps_i)) is complete (at once for steps_i = 0, after steps_i clocks
// otherwise) and it holds until the next load. A clear stops a product in flight (done_o
// rises, the product is not meaningful).
`include "msr_assert.svh"
`include "msr_flops.svh"

module msr_shift_add_mul #(
  parameter int unsigned A_W = 36,               // multiplicand bits
  parameter int unsigned B_W = 25,               // multiplier bits
  localparam int unsigned P_W = A_W + B_W,       // product bits (holds any product)
  localparam int unsigned S_W = $clog2(B_W + 1)  // step count
) (
  input  logic           clk_i,       // clock
  input  logic           rst_ni,      // asynchronous reset, active low
  input  logic           clear_i,     // synchronous: stop
  input  logic           load_i,      // start a product (has priority over the steps)
  input  logic [A_W-1:0] a_i,         // multiplicand
  input  logic [B_W-1:0] b_i,         // multiplier, left-aligned: its top steps_i bits
  input  logic [S_W-1:0] steps_i,     // multiplier bits, 0..B_W
  output logic           done_o,      // the product is complete
  output logic [P_W-1:0] prod_o       // a_i * (b_i >> (B_W - steps_i)) once done_o
);
  logic [A_W-1:0] mc_q;               // the multiplicand, held
  logic [B_W-1:0] mp_q;               // the multiplier bits left, the next one at the top
  logic [P_W-1:0] acc_q;              // the sum
  logic [S_W-1:0] cnt_q;              // steps left

  // done_o is a flip-flop, set from the next step count: a zero test of the count register
  // drove the divider's loads straight from the product's state (the budget unit's worst path
  // on ECP5).
  logic done_q;
  `MSR_CLR_REG_RST(u_done_q, 1, 1'b1, clear_i, load_i || !done_q,
                   load_i ? (steps_i == '0) : (cnt_q == S_W'(1)), done_q)
  `MSR_CLR_REG(u_cnt_q, S_W, clear_i, load_i || !done_q, load_i ? steps_i : cnt_q - S_W'(1), cnt_q)

  // The data: no reset (a load sets every bit the steps read); the load's clear of the sum is
  // the flip-flops' synchronous reset, and the multiplicand only loads (no adder input mux).
  always_ff @(posedge clk_i) begin
    if (load_i) begin
      mc_q  <= a_i;
      mp_q  <= b_i;
      acc_q <= '0;
    end else if (!done_q) begin
      acc_q <= (acc_q << 1) + (mp_q[B_W-1] ? P_W'(mc_q) : '0);
      mp_q  <= mp_q << 1;
    end
  end

  assign done_o = done_q;
  assign prod_o = acc_q;

  /* verilator lint_off SYNCASYNCNET */
  `MSR_ASSERT(a_done_is_zero, done_q == (cnt_q == '0))
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_shift_add_mul
