// Reuse's path for one engine (docs/spec/reuse.md sections 4 to 6): a position the rule would
// trace goes through msr_reproject (where it was in the previous frame), msr_reuse_gather (the
// bilinear read there, tests 1 and 2) and msr_reuse_check (tests 3 to 7), one position a clock,
// 25 register stages; bit for bit with msr_model.reuse._reuse_decision. ok_o: take rgb_o with
// age age_o and ask no ray; else trace as without reuse.
//
// The previous frame's colour, inverse depth and age are read through the window port (tap k
// at tap_x_o[k], tap_y_o[k] when tap_rd_o[k]; its word from the next clock until the next read
// of tap k: msr_reuse_gather's contract). The decision's own fields (A, B, their depths, the
// threshold test's operands, the position) ride along the first two units as their sideband.
// The camera map, the previous frame's extent, the frame's number and the tile size are the
// frame's: static while positions are in flight.

module msr_reuse_path
  import msr_pkg::*;
#(
  parameter int unsigned XY_W   = 12,   // frame coordinate bits
  parameter int unsigned W_W    = 16,   // inverse depth bits
  parameter int unsigned AGE_W  = 3,    // age plane bits
  parameter int unsigned USER_W = 1     // the caller's sideband
) (
  input  logic                      clk_i,
  input  logic                      rst_ni,
  input  logic                      clear_i,     // synchronous flush
  // the frame's
  input  logic [2:0][2:0][31:0]     cam_m_i,     // camera map M, b (docs/spec/reuse.md section 2)
  input  logic [2:0][31:0]          cam_b_i,
  input  logic [XY_W:0]             width_i,     // previous frame's extent
  input  logic [XY_W:0]             height_i,
  input  logic [2:0]                tile_lg_i,   // log2(T)
  input  logic [2:0]                frame_i,     // the frame's number mod 8
  // a position the rule traces
  input  logic                      valid_i,
  output logic                      ready_o,
  input  logic [XY_W-1:0]           x_i,         // global
  input  logic [XY_W-1:0]           y_i,
  input  logic [W_W-1:0]            wm_i,        // its interpolated inverse depth w_m
  input  rgb_t                      a_i,         // neighbours A, B and their inverse depths
  input  rgb_t                      b_i,
  input  logic [W_W-1:0]            wa_i,
  input  logic [W_W-1:0]            wb_i,
  input  metric_e                   metric_i,
  input  thr_t                      thr_i,
  input  gap_t                      gap_i,
  input  logic [1:0]                nshift_i,
  input  logic [USER_W-1:0]         user_i,
  // window memory (msr_reuse_gather's)
  output logic [3:0]                tap_rd_o,
  output logic [3:0][XY_W-1:0]      tap_x_o,
  output logic [3:0][XY_W-1:0]      tap_y_o,
  input  logic [3:0][23:0]          tap_rgb_i,
  input  logic [3:0][W_W-1:0]       tap_w_i,
  input  logic [3:0][AGE_W-1:0]     tap_age_i,
  // the verdict
  output logic                      valid_o,
  input  logic                      ready_i,
  output logic                      ok_o,
  output rgb_t                      rgb_o,
  output logic [AGE_W-1:0]          age_o,
  output logic [USER_W-1:0]         user_o
);

  localparam int unsigned UV_W = 18, WP_W = 17;

  // What msr_reuse_check needs besides the gather's result, carried through the first two.
  typedef struct packed {
    rgb_t              a, b;
    logic              wa_zero, wb_zero;   // the silhouette test reads only these
    metric_e           metric;
    thr_t              thr;
    gap_t              gap;
    logic [1:0]        nshift;
    logic [XY_W-1:0]   x, y;
    logic [USER_W-1:0] user;
  } side_t;

  side_t                  side_in, rp_side, ga_side;
  logic                   rp_valid, rp_ready, rp_ok, ga_valid, ga_ready, ga_geo_ok;
  logic signed [UV_W-1:0] rp_u, rp_v;
  logic [WP_W-1:0]        rp_wp;
  logic [W_W-1:0]         rp_wm;
  logic [23:0]            ga_rgb, ga_lo, ga_hi;
  logic [AGE_W-1:0]       ga_age;
  // the gather's inside flag and Wb are for tests and waveforms
  /* verilator lint_off UNUSEDSIGNAL */
  logic                   ga_inside;
  logic [W_W-1:0]         ga_wb;
  /* verilator lint_on UNUSEDSIGNAL */

  assign side_in = '{a: a_i, b: b_i, wa_zero: wa_i == '0, wb_zero: wb_i == '0, metric: metric_i,
                     thr: thr_i, gap: gap_i, nshift: nshift_i, x: x_i, y: y_i, user: user_i};

  msr_reproject #(.XY_W(XY_W), .W_W(W_W), .UV_W(UV_W), .WP_W(WP_W),
                  .USER_W($bits(side_t) + W_W)) u_reproject (
    .clk_i, .rst_ni, .clear_i, .m_i (cam_m_i), .b_i (cam_b_i),
    .valid_i, .ready_o, .x_i, .y_i, .w_i (wm_i), .user_i ({side_in, wm_i}),
    .valid_o (rp_valid), .ready_i (rp_ready), .ok_o (rp_ok), .u_o (rp_u), .v_o (rp_v),
    .wp_o (rp_wp), .user_o ({rp_side, rp_wm})
  );

  msr_reuse_gather #(.XY_W(XY_W), .W_W(W_W), .UV_W(UV_W), .WP_W(WP_W), .AGE_W(AGE_W),
                     .USER_W($bits(side_t))) u_gather (
    .clk_i, .rst_ni, .clear_i, .width_i, .height_i,
    .valid_i (rp_valid), .ready_o (rp_ready), .ok_i (rp_ok), .u_i (rp_u), .v_i (rp_v),
    .wp_i (rp_wp), .wm_i (rp_wm), .user_i (rp_side),
    .tap_rd_o, .tap_x_o, .tap_y_o, .tap_rgb_i, .tap_w_i, .tap_age_i,
    .valid_o (ga_valid), .ready_i (ga_ready), .geo_ok_o (ga_geo_ok), .inside_o (ga_inside),
    .rgb_o (ga_rgb), .wb_o (ga_wb), .lo_o (ga_lo), .hi_o (ga_hi), .age_o (ga_age),
    .user_o (ga_side)
  );

  // The check reads the depths only as "sky or not": 1 stands for any surface.
  msr_reuse_check #(.XY_W(XY_W), .W_W(1), .AGE_W(AGE_W), .USER_W(USER_W)) u_check (
    .clk_i, .rst_ni, .clear_i,
    .valid_i (ga_valid), .ready_o (ga_ready),
    .geo_ok_i (ga_geo_ok), .r_i (rgb_t'(ga_rgb)), .lo_i (rgb_t'(ga_lo)), .hi_i (rgb_t'(ga_hi)),
    .age_i (ga_age), .a_i (ga_side.a), .b_i (ga_side.b),
    .wa_i (!ga_side.wa_zero), .wb_i (!ga_side.wb_zero),
    .metric_i (ga_side.metric), .thr_i (ga_side.thr), .gap_i (ga_side.gap),
    .nshift_i (ga_side.nshift), .x_i (ga_side.x), .y_i (ga_side.y), .tile_lg_i, .frame_i,
    .user_i (ga_side.user),
    .valid_o, .ready_i, .ok_o, .rgb_o, .age_o, .user_o
  );

endmodule : msr_reuse_path
