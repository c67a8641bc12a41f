// Decision datapath (spec section 3, claims 8-9 and 12): for one position between neighbours A
// and B, the decision  d * n_k < thr * g  (d = max or sum of the per-channel |A - B|), and
// beside it the interpolation unit msr_interp forms the colour C; one pipeline, one
// valid/ready handshake.
//
// Six register stages, each under 30 levels of generic logic, so the unit closes timing far
// above the engine's clock on an FPGA and fits a short cycle on an ASIC:
//   S0  inputs registered; g - o
//   S1  per-channel |A - B|, thr * g                      (msr_interp: the weighted neighbours)
//   S2  max and sum of the differences                    (msr_interp: numerator, RECIP[g])
//   S3  d << log2(n_k) against thr * g                    (msr_interp: the product's pieces)
//   S4  the decision carried                              (msr_interp: pieces summed in pairs)
//   S5  output register                                   (msr_interp: C)
// Global-stall pipeline: every stage advances when the output register is empty or taken.
// A trace-only step (the initial grid) passes through with any A / B; the caller ignores C.
`include "msr_assert.svh"
`include "msr_flops.svh"

module msr_decision_pipe
  import msr_pkg::*;
#(
  parameter int unsigned USER_W = 1   // sideband carried alongside each decision
) (
  input  logic              clk_i,
  input  logic              rst_ni,
  input  logic              clear_i,    // synchronous flush of the pipeline
  input  logic              valid_i,    // one position to decide
  output logic              ready_o,
  input  rgb_t              a_i,        // neighbour A (left / top)
  input  rgb_t              b_i,        // neighbour B (right / bottom)
  input  metric_e           metric_i,
  input  thr_t              thr_i,      // foveated threshold thr_k'
  input  gap_t              gap_i,      // g = b - a, 1..8
  input  gap_t              off_i,      // o = m - a, 0..g-1
  input  logic [1:0]        nshift_i,   // log2(n_k), 0..3
  input  logic [USER_W-1:0] user_i,
  output logic              valid_o,    // result ready
  input  logic              ready_i,
  output logic              interp_o,   // 1: interpolate, 0: trace
  output diff_t             diff_o,     // colour difference d (for waveforms and tests)
  output rgb_t              rgb_o,      // interpolated colour
  output logic [USER_W-1:0] user_o
);

  localparam int unsigned PROD_W = THR_W + GAP_W;  // 12 bit: thr * g <= 255 * 8
  localparam int unsigned LHS_W  = DIFF_W + 3;     // d << 3

  logic advance;
  assign advance = !valid_o || ready_i;
  assign ready_o = advance;

  // ---- S0: inputs registered, g - o formed ---------------------------------------------------
  // The S1 products then start at flip-flops: on an FPGA a multiplier block alone is ~4 ns.
  logic               s0_valid_q;
  rgb_t               s0_a_q, s0_b_q;
  metric_e            s0_metric_q;
  thr_t               s0_thr_q;
  gap_t               s0_gap_q, s0_off_q, s0_gmo_q;
  logic [1:0]         s0_nshift_q;
  logic [USER_W-1:0]  s0_user_q;

  always_ff @(posedge clk_i) begin
    if (advance && valid_i) begin
      s0_a_q      <= a_i;
      s0_b_q      <= b_i;
      s0_metric_q <= metric_i;
      s0_thr_q    <= thr_i;
      s0_gap_q    <= gap_i;
      s0_off_q    <= off_i;
      s0_gmo_q    <= gap_i - off_i;
      s0_nshift_q <= nshift_i;
      s0_user_q   <= user_i;
    end
  end

  // ---- S1 ---------------------------------------------------------------------------------------
  logic                    s1_valid_q;
  chan_t [2:0]             s1_abs_q;
  logic  [PROD_W-1:0]      s1_rhs_q;           // thr * g
  metric_e                 s1_metric_q;
  logic  [1:0]             s1_nshift_q;
  logic  [USER_W-1:0]      s1_user_q;

  always_ff @(posedge clk_i) begin
    if (advance && s0_valid_q) begin
      s1_abs_q    <= rgb_absdiff(s0_a_q, s0_b_q);
      s1_rhs_q    <= thr_times_gap(s0_thr_q, s0_gap_q);
      s1_metric_q <= s0_metric_q;
      s1_nshift_q <= s0_nshift_q;
      s1_user_q   <= s0_user_q;
    end
  end

  // ---- S2 ---------------------------------------------------------------------------------------
  logic                    s2_valid_q;
  diff_t                   s2_d_q;
  logic  [PROD_W-1:0]      s2_rhs_q;
  logic  [1:0]             s2_nshift_q;
  logic  [USER_W-1:0]      s2_user_q;
  always_ff @(posedge clk_i) begin
    if (advance && s1_valid_q) begin
      s2_d_q      <= metric_diff(s1_abs_q, s1_metric_q);
      s2_rhs_q    <= s1_rhs_q;
      s2_nshift_q <= s1_nshift_q;
      s2_user_q   <= s1_user_q;
    end
  end

  // ---- S3: the decision; S4 and S5 carry it beside the colour ------------------------------
  logic              s3_valid_q, s4_valid_q;
  logic              s3_interp_q, s4_interp_q;   // 1: interpolate, 0: trace
  diff_t             s3_d_q, s4_d_q;
  logic [USER_W-1:0] s3_user_q, s4_user_q;

  always_ff @(posedge clk_i) begin
    if (advance && s2_valid_q) begin
      s3_interp_q <= (LHS_W'(s2_d_q) << s2_nshift_q) < LHS_W'(s2_rhs_q);
      {s3_d_q, s3_user_q} <= {s2_d_q, s2_user_q};
    end
    if (advance && s3_valid_q) {s4_interp_q, s4_d_q, s4_user_q} <= {s3_interp_q, s3_d_q, s3_user_q};
    if (advance && s4_valid_q) {interp_o, diff_o, user_o} <= {s4_interp_q, s4_d_q, s4_user_q};
  end

  // ---- Interpolation unit: the colour, stage by stage beside the decision -------------------
  msr_interp u_interp (
    .clk_i,
    .advance_i     (advance),
    .stage_valid_i ({s4_valid_q, s3_valid_q, s2_valid_q, s1_valid_q, s0_valid_q}),
    .a_i           (s0_a_q),
    .b_i           (s0_b_q),
    .gap_i         (s0_gap_q),
    .off_i         (s0_off_q),
    .gmo_i         (s0_gmo_q),
    .rgb_o
  );

  // ---- Valid bits ------------------------------------------------------------------------------
  // One shift register: every stage's valid bit moves on when the pipeline advances.
  `MSR_CLR_REG(u_valid, 6, clear_i, advance,
               {s4_valid_q, s3_valid_q, s2_valid_q, s1_valid_q, s0_valid_q, valid_i},
               {valid_o, s4_valid_q, s3_valid_q, s2_valid_q, s1_valid_q, s0_valid_q})

  /* verilator lint_off SYNCASYNCNET */
  `MSR_ASSERT_NXT(a_out_hold, valid_o && !ready_i, valid_o &&
      $stable({interp_o, diff_o, rgb_o, user_o}), clk_i, !rst_ni || clear_i)
  `MSR_ASSERT_IMP(a_in_range, valid_i && ready_o, gap_i inside {[1 : 8]} && off_i < gap_i)
  `MSR_COVER(c_interp, valid_o && ready_i && interp_o)
  `MSR_COVER(c_trace, valid_o && ready_i && !interp_o)
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_decision_pipe
