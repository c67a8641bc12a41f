// The tests of a reuse that need the pass (docs/spec/reuse.md section 6, tests 3 to 7), bit for
// bit with msr_model.reuse._reuse_decision: after msr_reuse_gather, for a position the rule
// traces at level k, between neighbours A and B, whose previous-frame read R passed tests 1
// and 2 (geo_ok_i):
//   3  silhouette:  not exactly one of w_A, w_B is 0
//   4  colour:      d(R, A) n_k < thr g  or  d(R, B) n_k < thr g
//   5  taps agree:  d(hi, lo) n_k < thr g
//   6  age:         the oldest used tap's age < AGE_MAX
//   7  refresh:     (f + phase(x, y)) mod 8 != 0, the staggered expiry
// ok_o: all of them and geo_ok_i; the pixel then takes R with age (oldest + 1) and no ray.
// d is the pass's metric (max or sum of the per-channel |differences|), thr g the threshold
// test of the decision unit (msr_decision_pipe), n_k = 2^nshift.
//
// Four register stages, one position a clock, global stall (as msr_reuse_gather):
//   C0  inputs registered
//   C1  per-channel |R - A|, |R - B|, hi - lo; thr g; the refresh phase's hash; tests 3 and 6
//   C2  the metric over the channels; the refresh slot (test 7)
//   C3  the threshold tests (4, 5); ok (output register)
`include "msr_assert.svh"

module msr_reuse_check
  import msr_pkg::*;
#(
  parameter int unsigned XY_W    = 12,  // frame coordinate bits
  parameter int unsigned W_W     = 16,  // inverse depth bits
  parameter int unsigned AGE_W   = 3,   // age plane bits
  parameter int unsigned AGE_MAX = 7,   // reuse only from taps younger than this
  parameter int unsigned USER_W  = 1    // sideband carried alongside each position
) (
  input  logic              clk_i,
  input  logic              rst_ni,
  input  logic              clear_i,     // synchronous flush
  input  logic              valid_i,
  output logic              ready_o,
  // msr_reuse_gather's result for the position
  input  logic              geo_ok_i,    // tests 1 and 2 (and the reprojection's ok)
  input  rgb_t              r_i,         // R, the bilinear read
  input  rgb_t              lo_i,        // per-channel minimum of the used taps
  input  rgb_t              hi_i,        // per-channel maximum
  input  logic [AGE_W-1:0]  age_i,       // the oldest used tap's age
  // the decision it replaces
  input  rgb_t              a_i,         // neighbours A and B
  input  rgb_t              b_i,
  input  logic [W_W-1:0]    wa_i,        // their inverse depth (0: sky)
  input  logic [W_W-1:0]    wb_i,
  input  metric_e           metric_i,
  input  thr_t              thr_i,       // the tile's threshold at the position's level
  input  gap_t              gap_i,       // g
  input  logic [1:0]        nshift_i,    // log2(n_k)
  input  logic [XY_W-1:0]   x_i,         // the position, global
  input  logic [XY_W-1:0]   y_i,
  input  logic [2:0]        tile_lg_i,   // log2(T): 3, 4 or 5
  input  logic [2:0]        frame_i,     // f mod 8, f the frame's number in the sequence
  input  logic [USER_W-1:0] user_i,
  // result
  output logic              valid_o,
  input  logic              ready_i,
  output logic              ok_o,        // reuse: take R, no ray
  output rgb_t              rgb_o,       // R
  output logic [AGE_W-1:0]  age_o,       // the pixel's age if reused: age_i + 1
  output logic [USER_W-1:0] user_o
);

  localparam int unsigned NS     = 4;              // register stages
  localparam int unsigned PROD_W = THR_W + GAP_W;  // thr g
  localparam int unsigned LHS_W  = DIFF_W + 3;     // d << 3

  if (AGE_MAX < 1 || AGE_MAX >= (1 << AGE_W)) begin : g_check_age
    $fatal(1, "msr_reuse_check: AGE_MAX %0d must be in 1..2^AGE_W - 1", AGE_MAX);
  end

  logic [NS-1:0] en;
  /* verilator lint_off UNUSEDSIGNAL */
  logic [NS-1:0] vld;
  /* verilator lint_on UNUSEDSIGNAL */

  msr_stall_ctrl #(.STAGES(NS)) u_ctrl (.clk_i, .rst_ni, .clear_i, .valid_i, .ready_o, .valid_o,
    .ready_i, .vld_o(vld), .en_o(en));

  // ---- C0: inputs ------------------------------------------------------------------------------
  typedef struct packed {
    logic              geo_ok;
    rgb_t              r, lo, hi;
    logic [AGE_W-1:0]  age;
    rgb_t              a, b;
    logic              sil_ok;      // test 3 needs only which of w_A, w_B is 0
    metric_e           metric;
    thr_t              thr;
    gap_t              gap;
    logic [1:0]        nshift;
    logic [XY_W-1:0]   x, y;
    logic [2:0]        tile_lg;
    logic [2:0]        frame;
    logic [USER_W-1:0] user;
  } c0_t;
  c0_t c0;

  msr_en_pipe #(.WIDTH($bits(c0_t))) u_c0 (.clk_i, .en_i(en[0]),
    .d_i({geo_ok_i, r_i, lo_i, hi_i, age_i, a_i, b_i, (wa_i == '0) == (wb_i == '0), metric_i,
          thr_i, gap_i, nshift_i, x_i, y_i, tile_lg_i, frame_i, user_i}),
    .q_o(c0));

  // ---- C1: differences, thr g, the phase's hash -------------------------------------------------
  // The refresh phase, mod 8 (every term is): xl, yl the position inside its tile,
  //   h = (xl ^ xl >> 2 ^ xl >> 4) + 2 (yl ^ yl >> 2 ^ yl >> 4) + (yl >> 1) + 3 (xl >> 1)
  //   phase = h + x div T + 2 (y div T)
  // only the low bits of each term count: 3 of a term added once, 2 of one added doubled
  logic [4:0] xl, yl;
  logic [2:0] hash, xl_mix, tx3;
  logic [1:0] yl_mix, ty2;
  always_comb begin
    xl     = 5'(c0.x & ((XY_W'(1) << c0.tile_lg) - 1'b1));
    yl     = 5'(c0.y & ((XY_W'(1) << c0.tile_lg) - 1'b1));
    xl_mix = 3'(xl ^ (xl >> 5'd2) ^ (xl >> 5'd4));
    yl_mix = 2'(yl ^ (yl >> 5'd2) ^ (yl >> 5'd4));
    tx3    = 3'(c0.x >> c0.tile_lg);
    ty2    = 2'(c0.y >> c0.tile_lg);
    hash   = xl_mix + {yl_mix, 1'b0} + 3'(yl >> 5'd1) + 3'(xl >> 5'd1) + {xl[2:1], 1'b0}
           + tx3 + {ty2, 1'b0};
  end

  typedef struct packed {
    logic                    pre_ok;  // tests 1, 2 (geo_ok), 3 and 6
    chan_t [2:0]             ra, rb, hl;
    logic [PROD_W-1:0]       rhs;
    metric_e                 metric;
    logic [1:0]              nshift;
    logic [2:0]              slot;    // (f + phase) mod 8
  } c1_t;
  c1_t c1;

  msr_en_pipe #(.WIDTH($bits(c1_t))) u_c1 (.clk_i, .en_i(en[1]),
    .d_i({c0.geo_ok && c0.sil_ok && 32'(c0.age) < AGE_MAX,
          rgb_absdiff(c0.r, c0.a), rgb_absdiff(c0.r, c0.b), rgb_absdiff(c0.hi, c0.lo),
          thr_times_gap(c0.thr, c0.gap), c0.metric, c0.nshift, c0.frame + hash}),
    .q_o(c1));

  // R, the new age and the sideband ride from C1 to the output unchanged.
  msr_en_pipe #(.WIDTH($bits(rgb_t) + AGE_W + USER_W), .DEPTH(3)) u_carry (.clk_i, .en_i(en[3:1]),
    .d_i({c0.r, c0.age + 1'b1, c0.user}), .q_o({rgb_o, age_o, user_o}));

  // ---- C2: the metric; the refresh slot ----------------------------------------------------------
  typedef struct packed {
    logic              pre_ok;  // tests 1, 2, 3, 6 and 7
    diff_t             dra, drb, dhl;
    logic [PROD_W-1:0] rhs;
    logic [1:0]        nshift;
  } c2_t;
  c2_t c2;

  msr_en_pipe #(.WIDTH($bits(c2_t))) u_c2 (.clk_i, .en_i(en[2]),
    .d_i({c1.pre_ok && c1.slot != '0, metric_diff(c1.ra, c1.metric), metric_diff(c1.rb, c1.metric),
          metric_diff(c1.hl, c1.metric), c1.rhs, c1.nshift}),
    .q_o(c2));

  // ---- C3: the threshold tests (output register) -------------------------------------------------
  function automatic logic below(diff_t d, logic [1:0] nshift, logic [PROD_W-1:0] rhs);
    return (LHS_W'(d) << nshift) < LHS_W'(rhs);
  endfunction

  msr_en_pipe #(.WIDTH(1)) u_c3 (.clk_i, .en_i(en[3]),
    .d_i(c2.pre_ok && (below(c2.dra, c2.nshift, c2.rhs) || below(c2.drb, c2.nshift, c2.rhs)) &&
         below(c2.dhl, c2.nshift, c2.rhs)),
    .q_o(ok_o));

  /* verilator lint_off SYNCASYNCNET */
  `MSR_ASSUME_IMP(m_tile, valid_i, tile_lg_i inside {3'd3, 3'd4, 3'd5})
  `MSR_ASSUME_IMP(m_taps_ordered, valid_i, lo_i.r <= hi_i.r && lo_i.g <= hi_i.g && lo_i.b <= hi_i.b)
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_reuse_check
