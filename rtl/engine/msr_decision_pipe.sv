// Decision pipeline (spec section 3, claims 8-9 and 12): for one position between neighbours A
// and B, the decision  d * n_k < thr * g  (d = max or sum of the per-channel |A - B|) and the
// interpolated colour  C = ((g - o) * A + o * B + floor(g / 2)) / g,  in one pipeline with one
// valid/ready handshake. Division by g in 2..8 is a multiply by RECIP[g] = ceil(2^14 / g) and
// a shift by 14, exact for every numerator 0..2047 (tb/interp proves it over the whole range).
//
// Six register stages, each under 30 levels of generic logic, so the unit closes timing far
// above the engine's clock on an FPGA and fits a short cycle on an ASIC:
//   S0  inputs registered; g - o
//   S1  per-channel |A - B|, thr * g, (g - o) * A and o * B (4-bit factors: adds, no multiplier)
//   S2  max and sum of the differences, numerator (g - o) * A + o * B + floor(g / 2)
//   S3  d << log2(n_k) against thr * g; numerator times the four 4-bit pieces of RECIP[g]
//   S4  pieces summed in pairs: p0 + p1 << 4, p2 + p3 << 4
//   S5  product = pair0 + pair1 << 8; C is its bits 14..21 (output register)
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

  localparam int unsigned PROD_W = THR_W + GAP_W;  // 12 bit: 255 * 8, 255 * 7 + 255 * 1
  localparam int unsigned NUM_W  = 11;             // numerator <= 8 * 255 + 4 = 2044
  localparam int unsigned LHS_W  = DIFF_W + 3;     // d << 3
  localparam int unsigned SHIFT  = 14;
  localparam int unsigned PIECE_W = 4;
  localparam int unsigned PART_W  = NUM_W + PIECE_W;  // 15: an 11-bit value times 4 bits

  // ceil(2^SHIFT / g); entries 0 and 1 are never used (g >= 2 wherever C is used).
  function automatic logic [15:0] recip(gap_t g);
    unique case (g)
      4'd2:    return 16'd8192;
      4'd3:    return 16'd5462;
      4'd4:    return 16'd4096;
      4'd5:    return 16'd3277;
      4'd6:    return 16'd2731;
      4'd7:    return 16'd2341;
      4'd8:    return 16'd2048;
      default: return 16'd0;
    endcase
  endfunction

  // m * x for a 4-bit m, as two levels of adds of shifted copies of x. Every product in this
  // pipeline has a 4-bit factor, and written this way it stays in the logic next to its
  // registers: an FPGA multiplier block sits in a fixed row, and the wires to and from it
  // were 8 of the 12.7 ns of the placed top's worst path (docs/handoff.md section 6).
  function automatic logic [PART_W-1:0] mul4(logic [PIECE_W-1:0] m, logic [NUM_W-1:0] x);
    logic [PART_W-1:0] t0, t1, t2, t3;
    t0 = m[0] ? PART_W'(x)       : '0;
    t1 = m[1] ? PART_W'(x) << 1  : '0;
    t2 = m[2] ? PART_W'(x) << 2  : '0;
    t3 = m[3] ? PART_W'(x) << 3  : '0;
    return (t0 + t1) + (t2 + t3);
  endfunction

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
  logic  [2:0][PROD_W-1:0] s1_pa_q, s1_pb_q;   // (g - o) * A, o * B per channel
  logic  [PROD_W-1:0]      s1_rhs_q;           // thr * g
  metric_e                 s1_metric_q;
  logic  [1:0]             s1_nshift_q;
  gap_t                    s1_gap_q;
  logic  [USER_W-1:0]      s1_user_q;

  always_ff @(posedge clk_i) begin
    if (advance && s0_valid_q) begin
      s1_abs_q[2] <= chan_absdiff(s0_a_q.r, s0_b_q.r);
      s1_abs_q[1] <= chan_absdiff(s0_a_q.g, s0_b_q.g);
      s1_abs_q[0] <= chan_absdiff(s0_a_q.b, s0_b_q.b);
      s1_pa_q[2]  <= PROD_W'(mul4(s0_gmo_q, NUM_W'(s0_a_q.r)));
      s1_pa_q[1]  <= PROD_W'(mul4(s0_gmo_q, NUM_W'(s0_a_q.g)));
      s1_pa_q[0]  <= PROD_W'(mul4(s0_gmo_q, NUM_W'(s0_a_q.b)));
      s1_pb_q[2]  <= PROD_W'(mul4(s0_off_q, NUM_W'(s0_b_q.r)));
      s1_pb_q[1]  <= PROD_W'(mul4(s0_off_q, NUM_W'(s0_b_q.g)));
      s1_pb_q[0]  <= PROD_W'(mul4(s0_off_q, NUM_W'(s0_b_q.b)));
      s1_rhs_q    <= thr_times_gap(s0_thr_q, s0_gap_q);
      s1_metric_q <= s0_metric_q;
      s1_nshift_q <= s0_nshift_q;
      s1_gap_q    <= s0_gap_q;
      s1_user_q   <= s0_user_q;
    end
  end

  // ---- S2 ---------------------------------------------------------------------------------------
  logic                    s2_valid_q;
  diff_t                   s2_d_q;
  logic  [2:0][NUM_W-1:0]  s2_num_q;
  logic  [PROD_W-1:0]      s2_rhs_q;
  logic  [1:0]             s2_nshift_q;
  logic  [15:0]            s2_recip_q;   // 14 bits and two zeros: four 4-bit pieces
  logic  [USER_W-1:0]      s2_user_q;
  diff_t                   d_max, d_sum;

  always_comb begin
    d_max = diff_t'(s1_abs_q[2]);
    if (diff_t'(s1_abs_q[1]) > d_max) d_max = diff_t'(s1_abs_q[1]);
    if (diff_t'(s1_abs_q[0]) > d_max) d_max = diff_t'(s1_abs_q[0]);
    d_sum = diff_t'(s1_abs_q[2]) + diff_t'(s1_abs_q[1]) + diff_t'(s1_abs_q[0]);
  end

  always_ff @(posedge clk_i) begin
    if (advance && s1_valid_q) begin
      s2_d_q      <= (s1_metric_q == METRIC_SUM) ? d_sum : d_max;
      for (int unsigned c = 0; c < 3; c++) begin
        s2_num_q[c] <= NUM_W'(s1_pa_q[c]) + NUM_W'(s1_pb_q[c]) + NUM_W'(s1_gap_q >> 1);
      end
      s2_rhs_q    <= s1_rhs_q;
      s2_nshift_q <= s1_nshift_q;
      s2_recip_q  <= recip(s1_gap_q);
      s2_user_q   <= s1_user_q;
    end
  end

  // ---- S3: the numerator times four 4-bit pieces of RECIP[g] -----------------------------------
  // No stage holds more than an 11 x 4 product or a 15-bit sum: both are under 30 levels of
  // generic logic (an 11 x 7 product is 34), which is what an ASIC clock of several hundred
  // MHz asks for; mul4 keeps the products out of the FPGA's multiplier blocks.
  localparam int unsigned PAIR_W  = PART_W + PIECE_W;         // 19: p0 + p1 << 4
  localparam int unsigned OUT_MSB = SHIFT + 8;                 // bits 14..21 hold C
  logic                        s3_valid_q;
  logic                        s3_interp_q;
  diff_t                       s3_d_q;
  logic  [2:0][3:0][PART_W-1:0] s3_part_q;
  logic  [USER_W-1:0]          s3_user_q;

  always_ff @(posedge clk_i) begin
    if (advance && s2_valid_q) begin
      s3_interp_q <= (LHS_W'(s2_d_q) << s2_nshift_q) < LHS_W'(s2_rhs_q);
      s3_d_q      <= s2_d_q;
      for (int unsigned c = 0; c < 3; c++) begin
        for (int unsigned k = 0; k < 4; k++) begin
          s3_part_q[c][k] <= mul4(s2_recip_q[PIECE_W*k +: PIECE_W], s2_num_q[c]);
        end
      end
      s3_user_q   <= s2_user_q;
    end
  end

  // ---- S4: pairs of pieces summed ----------------------------------------------------------
  logic                        s4_valid_q;
  logic                        s4_interp_q;
  diff_t                       s4_d_q;
  logic  [2:0][1:0][PAIR_W-1:0] s4_pair_q;   // p0 + p1 << 4, p2 + p3 << 4
  logic  [USER_W-1:0]          s4_user_q;

  always_ff @(posedge clk_i) begin
    if (advance && s3_valid_q) begin
      s4_interp_q <= s3_interp_q;
      s4_d_q      <= s3_d_q;
      for (int unsigned c = 0; c < 3; c++) begin
        for (int unsigned j = 0; j < 2; j++) begin
          s4_pair_q[c][j] <= PAIR_W'(s3_part_q[c][2*j]) +
                             (PAIR_W'(s3_part_q[c][2*j+1]) << PIECE_W);
        end
      end
      s4_user_q   <= s3_user_q;
    end
  end

  // ---- S5: output register; product = pair0 + pair1 << 8 -----------------------------------
  // Only bits up to 21 are formed: the quotient is <= 255, so the 8 bits above the shift are
  // the whole result and nothing above them is ever set.
  logic [2:0][OUT_MSB-1:0] prod;

  always_comb begin
    for (int unsigned c = 0; c < 3; c++) begin
      prod[c] = OUT_MSB'(s4_pair_q[c][0]) + (OUT_MSB'(s4_pair_q[c][1]) << (2 * PIECE_W));
    end
  end

  always_ff @(posedge clk_i) begin
    if (advance && s4_valid_q) begin
      interp_o <= s4_interp_q;
      diff_o   <= s4_d_q;
      rgb_o    <= '{r: prod[2][SHIFT +: 8], g: prod[1][SHIFT +: 8], b: prod[0][SHIFT +: 8]};
      user_o   <= s4_user_q;
    end
  end

  // ---- Valid bits ------------------------------------------------------------------------------
  // One shift register: every stage's valid bit moves on when the pipeline advances.
  `MSR_CLR_REG(u_valid, 6, clear_i, advance,
               {s4_valid_q, s3_valid_q, s2_valid_q, s1_valid_q, s0_valid_q, valid_i},
               {valid_o, s4_valid_q, s3_valid_q, s2_valid_q, s1_valid_q, s0_valid_q})

  /* verilator lint_off SYNCASYNCNET */
  `MSR_ASSERT(a_out_hold, valid_o && !ready_i |=> valid_o &&
      $stable({interp_o, diff_o, rgb_o, user_o}), clk_i, !rst_ni || clear_i)
  `MSR_ASSERT(a_in_range, valid_i && ready_o |-> gap_i inside {[1 : 8]} && off_i < gap_i)
  `MSR_COVER(c_interp, valid_o && ready_i && interp_o)
  `MSR_COVER(c_trace, valid_o && ready_i && !interp_o)
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_decision_pipe
