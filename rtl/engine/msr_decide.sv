// Decision datapath (spec section 3, claims 8-9): colour difference of the two neighbours
// A and B (metric max or sum) and the gap-weighted threshold test  d * n_k < thr * g.
// n_k = S >> (k-1) is a power of two, so the left side is a shift; the right side is an
// 8 x 4 bit product. Two register stages, one decision per clock, global-stall pipeline:
// every stage advances when the output register is empty or being taken.
module msr_decide
  import msr_pkg::*;
#(
  parameter int unsigned USER_W = 1   // sideband carried alongside each decision
) (
  input  logic              clk_i,
  input  logic              rst_ni,
  input  logic              clear_i,    // synchronous flush of the pipeline
  input  logic              valid_i,    // one decision to make
  output logic              ready_o,
  input  rgb_t              a_i,        // neighbour A (left / top)
  input  rgb_t              b_i,        // neighbour B (right / bottom)
  input  metric_e           metric_i,
  input  thr_t              thr_i,      // foveated threshold thr_k'
  input  gap_t              gap_i,      // g = b - a, 1..8
  input  logic [1:0]        nshift_i,   // log2(n_k), 0..3
  input  logic [USER_W-1:0] user_i,
  output logic              valid_o,    // decision ready
  input  logic              ready_i,
  output logic              interp_o,   // 1: interpolate, 0: trace
  output diff_t             diff_o,     // colour difference d
  output logic [USER_W-1:0] user_o
);

  // d <= 765 (10 bit), d << 3 fits 13 bits; thr * g <= 255 * 8 fits 12 bits.
  localparam int unsigned LHS_W = DIFF_W + 3;
  localparam int unsigned RHS_W = THR_W + GAP_W;

  logic advance;
  assign advance = !valid_o || ready_i;
  assign ready_o = advance;

  // ---- Stage 1: per-channel absolute differences ------------------------------------------
  logic              s1_valid_q;
  chan_t [2:0]       s1_abs_q, s1_abs_d;
  metric_e           s1_metric_q;
  logic [RHS_W-1:0]  s1_rhs_q, s1_rhs_d;
  logic [1:0]        s1_nshift_q;
  logic [USER_W-1:0] s1_user_q;

  function automatic chan_t absdiff(chan_t x, chan_t y);
    return (x > y) ? x - y : y - x;
  endfunction

  always_comb begin
    s1_abs_d[2] = absdiff(a_i.r, b_i.r);
    s1_abs_d[1] = absdiff(a_i.g, b_i.g);
    s1_abs_d[0] = absdiff(a_i.b, b_i.b);
    s1_rhs_d    = RHS_W'(thr_i) * RHS_W'(gap_i);
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      s1_valid_q <= 1'b0;
    end else if (clear_i) begin
      s1_valid_q <= 1'b0;
    end else if (advance) begin
      s1_valid_q <= valid_i;
    end
  end

  // Data registers need no reset: they are only looked at when the valid bit is set.
  always_ff @(posedge clk_i) begin
    if (advance && valid_i) begin
      s1_abs_q    <= s1_abs_d;
      s1_metric_q <= metric_i;
      s1_rhs_q    <= s1_rhs_d;
      s1_nshift_q <= nshift_i;
      s1_user_q   <= user_i;
    end
  end

  // ---- Stage 2: metric, weighting and compare ---------------------------------------------
  diff_t            d_max, d_sum, d_sel;
  logic [LHS_W-1:0] lhs;
  logic             interp_d;

  always_comb begin
    d_max = diff_t'(s1_abs_q[2]);
    if (diff_t'(s1_abs_q[1]) > d_max) d_max = diff_t'(s1_abs_q[1]);
    if (diff_t'(s1_abs_q[0]) > d_max) d_max = diff_t'(s1_abs_q[0]);
    d_sum    = diff_t'(s1_abs_q[2]) + diff_t'(s1_abs_q[1]) + diff_t'(s1_abs_q[0]);
    d_sel    = (s1_metric_q == METRIC_SUM) ? d_sum : d_max;
    lhs      = LHS_W'(d_sel) << s1_nshift_q;
    interp_d = lhs < LHS_W'(s1_rhs_q);
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      valid_o <= 1'b0;
    end else if (clear_i) begin
      valid_o <= 1'b0;
    end else if (advance) begin
      valid_o <= s1_valid_q;
    end
  end

  always_ff @(posedge clk_i) begin
    if (advance && s1_valid_q) begin
      interp_o <= interp_d;
      diff_o   <= d_sel;
      user_o   <= s1_user_q;
    end
  end

`ifndef SYNTHESIS
  // Lint: disable iff (!rst_ni) looks like a synchronous use of the asynchronous reset.
  /* verilator lint_off SYNCASYNCNET */
  // Output handshake: valid held with stable data until taken.
  property p_hold;
    @(posedge clk_i) disable iff (!rst_ni || clear_i)
      valid_o && !ready_i |=> valid_o && $stable({interp_o, diff_o, user_o});
  endproperty
  a_hold : assert property (p_hold) else $error("msr_decide: output changed while stalled");
  a_gap : assert property (@(posedge clk_i) disable iff (!rst_ni)
      valid_i && ready_o |-> gap_i inside {[1 : 8]})
    else $error("msr_decide: gap %0d outside 1..8", gap_i);
  /* verilator lint_on SYNCASYNCNET */
`endif

endmodule : msr_decide
