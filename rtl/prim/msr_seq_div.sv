// Sequential restoring divider with a saturating quotient: Q_W quotient bits, one per clock,
// after a first step that tests num >= den << Q_W (a quotient of 2^Q_W or more). For units that
// divide a few times per thousands of clocks (the ray-budget controller): one subtract instead
// of a divider array.
//
// The caller loads the numerator and the divisor (load_num_i, load_den_i) in any order, and
// init_i presets the quotient and the step count. Then step_i on Q_W + 1 consecutive clocks: the
// first is the saturation test, the others give the quotient bits Q_W-1..0; last_o is high on
// the last of them. The quotient (quo_o, valid after the last step) is quo_init_i with the bits
// shifted in, or Q_SAT when the test found num >= den << Q_W. The step count does not depend on
// the data. No reset on the data: init_i and the loads set everything the steps read.
//
// Long division on a partial remainder: the divisor stays where it is loaded and the
// numerator's bits below the divisor's width shift in one per step (its top bits are the first
// partial remainder). Every step is the same compare of the shifted partial remainder with the
// divisor, the first one's answer being the saturation test; once it fails the partial
// remainder stays below the divisor, so R_W - Q_W + 1 bits hold it. Against shifting the divisor
// right under a full-width remainder this saves the divisor's shift multiplexer and Q_W bits of
// the subtract and the remainder (the ray-budget controller's largest arithmetic).
`include "msr_assert.svh"

module msr_seq_div #(
  parameter int unsigned      R_W   = 62,      // numerator bits
  parameter int unsigned      Q_W   = 11,      // quotient bits
  parameter logic [Q_W-1:0]   Q_SAT = '1,      // the quotient when num >= den << Q_W
  localparam int unsigned     D_W   = R_W - Q_W,  // divisor bits: den << Q_W fits R_W bits
  localparam int unsigned     CNT_W = $clog2(Q_W + 2)
) (
  input  logic           clk_i,        // clock
  input  logic           rst_ni,       // asynchronous reset, active low
  input  logic           init_i,       // preset the quotient and the step count
  input  logic [Q_W-1:0] quo_init_i,   // the quotient preset (a caller's own saturation)
  input  logic           load_num_i,   // the numerator <= num_i
  input  logic [R_W-1:0] num_i,        // numerator
  input  logic           load_den_i,   // the divisor <= den_i
  input  logic [R_W-1:0] den_i,        // denominator, den_i << Q_W must fit R_W bits
  input  logic           step_i,       // one step (Q_W + 1 of them after init_i)
  output logic           last_o,       // this step is the last
  output logic [Q_W-1:0] quo_o         // the quotient, after the last step
);
  logic [D_W-1:0]   rem_q;             // the partial remainder (below den once not saturated)
  logic [Q_W:0]     low_q;             // the numerator's bits still to shift in, next at the top
  logic [D_W-1:0]   den_q;             // the divisor
  logic [Q_W-1:0]   quo_q;
  logic             sat_q;             // the quotient is >= 2^Q_W
  logic [CNT_W-1:0] cnt_q;             // steps left
  logic [D_W:0]     rem_sh;            // the partial remainder with the next bit shifted in
  logic [D_W+1:0]   diff;              // rem_sh - divisor: its borrow is the compare
  logic             ge, first;
  assign rem_sh = {rem_q, low_q[Q_W]};
  assign diff   = {1'b0, rem_sh} - {2'b00, den_q};
  assign ge     = !diff[D_W+1];
  assign first  = cnt_q == CNT_W'(Q_W + 1);
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      cnt_q <= '0;
    end else if (init_i) begin
      cnt_q <= CNT_W'(Q_W + 1);
    end else if (step_i) begin
      cnt_q <= cnt_q - CNT_W'(1);
    end
  end
  always_ff @(posedge clk_i) begin
    if (init_i) begin
      quo_q <= quo_init_i;
      sat_q <= 1'b0;
    end else if (step_i && first) begin
      sat_q <= ge;
    end else if (step_i) begin
      quo_q <= (last_o && sat_q) ? Q_SAT : {quo_q[Q_W-2:0], ge};
    end
    // (after a saturated first step the partial remainder may overflow: the quotient is Q_SAT)
    if (load_num_i) begin
      {rem_q, low_q} <= {1'b0, num_i};      // rem = num >> (Q_W + 1) < 2^(D_W - 1)
    end else if (step_i) begin
      rem_q <= ge ? diff[D_W-1:0] : rem_sh[D_W-1:0];
      low_q <= low_q << 1;
    end
    if (load_den_i) den_q <= D_W'(den_i);
  end
  assign last_o = cnt_q == CNT_W'(1);
  assign quo_o  = quo_q;

  // (den_i's top Q_W bits are zero by the contract; a_den_fits checks it)
  logic unused_den;
  assign unused_den = ^den_i[R_W-1:D_W];

  /* verilator lint_off SYNCASYNCNET */
  `MSR_ASSERT_IMP(a_steps_after_init, step_i, cnt_q != '0)
  `MSR_ASSERT_IMP(a_den_nonzero, step_i && first, den_q != '0)
  `MSR_ASSERT_IMP(a_den_fits, load_den_i, den_i[R_W-1:D_W] == '0)
  `MSR_ASSERT_IMP(a_below_den, step_i && !first && !sat_q, rem_q < den_q)
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_seq_div
