// Ray budget: the seed pass's weight (docs/budget.md section 4, "The seed pass above the seed").
// A seeded start rewrites every row's memory word {u'_k, a'_k} as b_k = a'_k * w(u'_k, u0):
//
//   w = u'_k                     at or below the seed u0
//   w = u0                       above it, when the row was floored (a'_k = (p_k >> 7) * u'_k)
//                                or u0 < 128
//   w = u0 + (d >> 1)            above it, u0 >= 256,   d = min(u'_k - u0, u0 >> 1)
//   w = u0 + (d >> 2)            above it, 128 <= u0 < 256
//
// w <= min(max(u'_k, u0), 1.25 u0) <= 1448. The controller (msr_budget_ctrl) loads the floor
// product (p_k >> FLOOR_SHIFT) * u'_k from floor_o on its shared multiplier, and hands the
// product back with take_i: w is registered then, for the b_k product.
//
// Timing: u0 + ((u' - u0) >> 1) = (u' + u0) >> 1 and u0 + ((u' - u0) >> 2) = (u' + 3 u0) >> 2,
// so each uncapped weight is one add of u'_k and a constant of the frame; the cap's line
// u0 + (u0 >> 1), 3 u0 and the capped weight are registers of u0 (fixed from the start, and the
// pass begins after the start's chain of products). Combinational, the weight put compare ->
// subtract -> add into the multiplier's load: the BUDGET_EN = 1 top's worst path (100.89 MHz).
module msr_budget_seed_w import msr_budget_pkg::*; #(
  parameter int unsigned PROD_W = 61                    // the multiplier's product
) (
  input  logic              clk_i,        // clock (plain flip-flops: the pass says when they hold)
  input  logic [10:0]       u0_i,         // the frame's seed
  input  logic [17:0]       p_full_i,     // pixels of a full tile row
  input  logic [17:0]       p_last_i,     // pixels of the last tile row
  input  logic              row_last_i,   // row k is the last tile row
  input  logic [10:0]       u_prev_i,     // u'_k, from the memory word's register
  input  logic [27:0]       a_prev_i,     // a'_k
  input  logic              take_i,       // the floor product is done: register w
  input  logic [PROD_W-1:0] prod_i,       // ... the multiplier's product, (p_k >> 7) * u'_k
  output logic [10:0]       floor_o,      // p_k >> FLOOR_SHIFT, for the floor product
  output logic [10:0]       w_o           // w(u'_k, u0), from take_i on
);

  logic [11:0] line_q;          // u0 + (u0 >> 1): beyond it the distance is capped
  logic [12:0] x3_q;            // 3 u0
  logic [10:0] cap_q;           // the capped weight
  logic        half_q, qtr_q;   // u0 >= 256; 128 <= u0 < 256
  logic        half, qtr;
  assign half = u0_i >= SEED_ABOVE_HALF;
  assign qtr  = u0_i >= SEED_ABOVE_QUARTER && !half;
  always_ff @(posedge clk_i) begin
    line_q <= 12'(u0_i) + 12'(u0_i >> 1);
    x3_q   <= 13'(u0_i) + 13'({u0_i, 1'b0});
    half_q <= half;
    qtr_q  <= qtr;
    cap_q  <= u0_i + (half ? (u0_i >> 2) : qtr ? (u0_i >> 3) : 11'd0);
  end

  logic [11:0] w_half;
  logic [12:0] w_qtr;
  logic [10:0] w;
  logic        above, capped, floored;
  assign above   = u_prev_i > u0_i;
  assign capped  = 12'(u_prev_i) > line_q;
  assign floored = prod_i == PROD_W'(a_prev_i);
  assign w_half  = 12'(u_prev_i) + 12'(u0_i);
  assign w_qtr   = 13'(u_prev_i) + x3_q;
  assign w       = !above                         ? u_prev_i :
                   (floored || !(half_q || qtr_q)) ? u0_i :
                   capped                         ? cap_q :
                   half_q                         ? w_half[11:1] : w_qtr[12:2];

  always_ff @(posedge clk_i) begin
    // row k's floor is ready a clock after the pass moves to row k (it moves only at b_k)
    floor_o <= 11'((row_last_i ? p_last_i : p_full_i) >> FLOOR_SHIFT);
    if (take_i) w_o <= w;
  end

  logic unused;                 // the bits the shifts drop
  assign unused = ^{w_half[0], w_qtr[1:0]};

endmodule : msr_budget_seed_w
