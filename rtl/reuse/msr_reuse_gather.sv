// Bilinear read of the previous frame (docs/spec/reuse.md section 5) and the tests that need
// only the reprojection and the taps (section 6, tests 1 and 2), bit for bit with
// msr_model.reuse.gather: from (U, V) in 1/16 pixel, taps (x0, y0), (x0+1, y0), (x0, y0+1),
// (x0+1, y0+1) with weights (16-fx)(16-fy), fx (16-fy), (16-fx) fy, fx fy, and
//   R.c = (sum wt C.c + 128) >> 8,  Wb = (sum wt W + 128) >> 8,
// the per-channel minimum and maximum and the oldest age over the used taps (weight > 0).
// geo_ok_o: the reprojection's ok, every used tap inside the frame, and for a sky pixel
// (w_m = 0) every used tap sky, otherwise every used tap 0 < W < 65535, w_m < 65535 and
// |Wb - Wp| <= (Wp >> 6) + 1. The colour tests (4, 5), the silhouette, the age bound and the
// refresh slot are the caller's: they need the pass's neighbours and thresholds.
//
// The window memory is outside: tap k's address (tap_x_o[k], tap_y_o[k]) is read when
// tap_rd_o[k] is set (a used tap of a pixel whose used taps are all inside, on the clock G0
// moves on), and its word is on tap_i[k] from the next clock until the next read of tap k
// (a synchronous memory whose output holds between reads). Unread taps' words are ignored.
//
// Six register stages, one pixel a clock, global stall (as msr_reproject):
//   G0  inputs registered; tap addresses, weights, used and inside flags; the reads
//   G1  the pixel while its tap words arrive; min, max, age and sky flags of the used taps
//   G2  the tap words weighted (an unused tap's weight is 0)
//   G3  the weighted sums
//   G4  rounded; the depth window Wp - tol, Wp + tol
//   G5  the depth test; geo_ok (output register): on the ECP5 the rounding and the test in one
//       clock held the unit to 85 MHz
`include "msr_assert.svh"

module msr_reuse_gather #(
  parameter int unsigned XY_W   = 12,   // frame coordinate bits
  parameter int unsigned W_W    = 16,   // inverse depth bits
  parameter int unsigned UV_W   = 18,   // U, V (msr_reproject's)
  parameter int unsigned WP_W   = 17,   // Wp (msr_reproject's)
  parameter int unsigned AGE_W  = 3,    // age plane bits
  parameter int unsigned USER_W = 1     // sideband carried alongside each pixel
) (
  input  logic                              clk_i,
  input  logic                              rst_ni,
  input  logic                              clear_i,     // synchronous flush
  input  logic [XY_W:0]                     width_i,     // previous frame's extent, static
  input  logic [XY_W:0]                     height_i,
  // one reprojected pixel in (msr_reproject's outputs) with its predicted inverse depth
  input  logic                              valid_i,
  output logic                              ready_o,
  input  logic                              ok_i,
  input  logic signed [UV_W-1:0]            u_i,
  input  logic signed [UV_W-1:0]            v_i,
  input  logic [WP_W-1:0]                   wp_i,
  input  logic [W_W-1:0]                    wm_i,
  input  logic [USER_W-1:0]                 user_i,
  // window memory: tap k = dy * 2 + dx
  output logic [3:0]                        tap_rd_o,
  output logic [3:0][XY_W-1:0]              tap_x_o,
  output logic [3:0][XY_W-1:0]              tap_y_o,
  input  logic [3:0][23:0]                  tap_rgb_i,   // {r, g, b}
  input  logic [3:0][W_W-1:0]               tap_w_i,
  input  logic [3:0][AGE_W-1:0]             tap_age_i,
  // result
  output logic                              valid_o,
  input  logic                              ready_i,
  output logic                              geo_ok_o,    // tests 1 and 2 and ok_i
  output logic                              inside_o,    // every used tap inside the frame
  output logic [23:0]                       rgb_o,       // R (defined where inside_o)
  output logic [W_W-1:0]                    wb_o,        // Wb
  output logic [23:0]                       lo_o,        // per-channel minimum of the used taps
  output logic [23:0]                       hi_o,        // per-channel maximum
  output logic [AGE_W-1:0]                  age_o,       // the oldest used tap's age
  output logic [USER_W-1:0]                 user_o
);

  localparam int unsigned FR_W    = 4;                  // U, V fraction bits
  localparam int unsigned TC_W    = UV_W - FR_W + 1;    // tap coordinate, signed, x0 + 1
  localparam int unsigned WT_W    = 2 * FR_W + 1;       // weight 0..256
  localparam int unsigned CACC_W  = WT_W + 8;           // sum wt C <= 256 * 255
  localparam int unsigned WACC_W  = WT_W + W_W;         // sum wt W <= 256 * 65535
  localparam int unsigned DTOL_SH = 6;                  // depth tolerance (Wp >> 6) + 1
  localparam int unsigned DTOL_W  = WP_W - DTOL_SH + 1; // its bits
  localparam logic [W_W-1:0] W_SAT = '1;                // 65535: too near, never reused

  localparam int unsigned NS      = 6;                  // register stages

  // en[k]: stage k loads; vld[k]: stage k holds a pixel (the assertions read a few)
  logic [NS-1:0] en;
  /* verilator lint_off UNUSEDSIGNAL */
  logic [NS-1:0] vld;
  /* verilator lint_on UNUSEDSIGNAL */

  msr_stall_ctrl #(.STAGES(NS)) u_ctrl (.clk_i, .rst_ni, .clear_i, .valid_i, .ready_o, .valid_o,
    .ready_i, .vld_o(vld), .en_o(en));

  // ---- G0: inputs; taps ----------------------------------------------------------------------
  logic                     g0_ok;
  logic signed [UV_W-1:0]   g0_u, g0_v;
  logic [WP_W-1:0]          g0_wp;
  logic [W_W-1:0]           g0_wm;
  logic [USER_W-1:0]        g0_user;

  msr_en_pipe #(.WIDTH(1 + 2 * UV_W + WP_W + W_W + USER_W)) u_g0 (.clk_i, .en_i(en[0]),
    .d_i({ok_i, u_i, v_i, wp_i, wm_i, user_i}), .q_o({g0_ok, g0_u, g0_v, g0_wp, g0_wm, g0_user}));

  logic [FR_W-1:0]              fx, fy;
  logic signed [1:0][TC_W-1:0]  tx, ty;        // x0, x0 + 1; y0, y0 + 1
  logic [1:0]                   in_x, in_y;
  logic [3:0]                   used, tap_in;
  logic [FR_W-1:0][2*FR_W-1:0]  fx_b;          // fx 2^b where bit b of fy is set
  logic [2*FR_W-1:0]            fxy;           // fx fy
  logic [3:0][WT_W-1:0]         wt;
  logic                         all_inside;

  assign fx = g0_u[FR_W-1:0];
  assign fy = g0_v[FR_W-1:0];

  always_comb begin
    tx[0] = TC_W'($signed(g0_u[UV_W-1:FR_W]));
    ty[0] = TC_W'($signed(g0_v[UV_W-1:FR_W]));
    tx[1] = tx[0] + TC_W'(1);
    ty[1] = ty[0] + TC_W'(1);
    // the weights (16 - fx)(16 - fy), fx (16 - fy), (16 - fx) fy, fx fy from the one product
    // fx fy, by shift and add: as a *, synthesis gives a 4 x 4 product a DSP block and its
    // delay (ECP5: the unit's critical path)
    for (int b = 0; b < FR_W; b++) begin
      fx_b[b] = fy[b] ? (2 * FR_W)'(fx) << b : '0;
    end
    fxy   = (fx_b[0] + fx_b[1]) + (fx_b[2] + fx_b[3]);
    wt[3] = WT_W'(fxy);
    wt[1] = (WT_W'(fx) << FR_W) - WT_W'(fxy);
    wt[2] = (WT_W'(fy) << FR_W) - WT_W'(fxy);
    wt[0] = WT_W'(256) - ((WT_W'(fx) + WT_W'(fy)) << FR_W) + WT_W'(fxy);
    for (int i = 0; i < 2; i++) begin
      in_x[i] = !tx[i][TC_W-1] && (TC_W'(width_i) > tx[i]);
      in_y[i] = !ty[i][TC_W-1] && (TC_W'(height_i) > ty[i]);
    end
    for (int k = 0; k < 4; k++) begin
      // tap 0 always has weight > 0; the right taps need fx > 0, the lower ones fy > 0
      used[k]   = (k[0] == 1'b0 || fx != '0) && (k[1] == 1'b0 || fy != '0);
      tap_in[k] = in_x[k[0]] && in_y[k[1]];
      tap_x_o[k] = XY_W'(tx[k[0]]);
      tap_y_o[k] = XY_W'(ty[k[1]]);
    end
    all_inside = &(tap_in | ~used);
  end

  assign tap_rd_o = {4{en[1] && all_inside}} & used;

  // ---- G1: the pixel while its tap words arrive --------------------------------------------
  logic                  g1_ok_q, g1_inside_q;
  logic [3:0]            g1_used_q;
  logic [3:0][WT_W-1:0]  g1_wt_q;
  logic [WP_W-1:0]       g1_wp_q;
  logic [W_W-1:0]        g1_wm_q;
  logic [USER_W-1:0]     g1_user_q;

  always_ff @(posedge clk_i) begin
    if (en[1]) begin
      g1_ok_q     <= g0_ok;
      g1_inside_q <= all_inside;
      g1_used_q   <= used;
      g1_wt_q     <= wt;
      g1_wp_q     <= g0_wp;
      g1_wm_q     <= g0_wm;
      g1_user_q   <= g0_user;
    end
  end

  // min, max and age as trees over the taps (an unused tap reads as the neutral value), not a
  // chain of four compare-and-selects
  function automatic logic [7:0] min8(logic [7:0] a, logic [7:0] b);
    return (a < b) ? a : b;
  endfunction

  function automatic logic [7:0] max8(logic [7:0] a, logic [7:0] b);
    return (a > b) ? a : b;
  endfunction

  function automatic logic [AGE_W-1:0] max_age(logic [AGE_W-1:0] a, logic [AGE_W-1:0] b);
    return (a > b) ? a : b;
  endfunction

  logic [3:0][23:0]      t_lo, t_hi;
  logic [3:0][AGE_W-1:0] t_age;
  logic [23:0]           lo_c, hi_c;
  logic [AGE_W-1:0]      age_c;
  logic                  sky_all_c, sky_none_c;

  always_comb begin
    sky_all_c  = 1'b1;
    sky_none_c = 1'b1;
    for (int k = 0; k < 4; k++) begin
      t_lo[k]  = g1_used_q[k] ? tap_rgb_i[k] : '1;
      t_hi[k]  = g1_used_q[k] ? tap_rgb_i[k] : '0;
      t_age[k] = g1_used_q[k] ? tap_age_i[k] : '0;
      if (g1_used_q[k]) begin
        sky_all_c  = sky_all_c && tap_w_i[k] == '0;
        sky_none_c = sky_none_c && tap_w_i[k] != '0 && tap_w_i[k] != W_SAT;
      end
    end
    for (int c = 0; c < 3; c++) begin
      lo_c[8*c +: 8] = min8(min8(t_lo[0][8*c +: 8], t_lo[1][8*c +: 8]),
                            min8(t_lo[2][8*c +: 8], t_lo[3][8*c +: 8]));
      hi_c[8*c +: 8] = max8(max8(t_hi[0][8*c +: 8], t_hi[1][8*c +: 8]),
                            max8(t_hi[2][8*c +: 8], t_hi[3][8*c +: 8]));
    end
    age_c = max_age(max_age(t_age[0], t_age[1]), max_age(t_age[2], t_age[3]));
  end

  // ---- G2: the tap words weighted (an unused tap weighs 0) -----------------------------------
  logic [3:0][2:0][CACC_W-1:0] g2_cw_q;
  logic [3:0][WACC_W-1:0]      g2_ww_q;

  always_ff @(posedge clk_i) begin
    if (en[2]) begin
      for (int k = 0; k < 4; k++) begin
        for (int c = 0; c < 3; c++) begin
          g2_cw_q[k][c] <= CACC_W'(g1_wt_q[k]) * CACC_W'(tap_rgb_i[k][8*c +: 8]);
        end
        g2_ww_q[k] <= WACC_W'(g1_wt_q[k]) * WACC_W'(tap_w_i[k]);
      end
    end
  end

  // What G1 hands on to the output unchanged (min, max, age, inside, the sideband), and to the
  // depth test: ok and inside, w_m = 0 (a sky pixel), its test (every used tap sky), the other
  // tests but the depth (no used tap sky or too near, w_m not too near), and Wp.
  logic [23:0]       g5_lo, g5_hi;
  logic [AGE_W-1:0]  g5_age;
  logic              g5_inside;
  logic [USER_W-1:0] g5_user;
  logic              g3_base_ok, g3_sky, g3_sky_ok, g3_near_ok;
  logic [WP_W-1:0]   g3_wp;

  msr_en_pipe #(.WIDTH(48 + AGE_W + 1 + USER_W), .DEPTH(4)) u_out (.clk_i, .en_i(en[5:2]),
    .d_i({lo_c, hi_c, age_c, g1_inside_q, g1_user_q}),
    .q_o({g5_lo, g5_hi, g5_age, g5_inside, g5_user}));
  msr_en_pipe #(.WIDTH(4 + WP_W), .DEPTH(2)) u_test (.clk_i, .en_i(en[3:2]),
    .d_i({g1_ok_q && g1_inside_q, g1_wm_q == '0, sky_all_c, sky_none_c && g1_wm_q != W_SAT,
          g1_wp_q}),
    .q_o({g3_base_ok, g3_sky, g3_sky_ok, g3_near_ok, g3_wp}));

  assign lo_o     = g5_lo;
  assign hi_o     = g5_hi;
  assign age_o    = g5_age;
  assign inside_o = g5_inside;
  assign user_o   = g5_user;

  // ---- G3: the weighted sums -------------------------------------------------------------------
  logic [2:0][CACC_W-1:0]  g3_cacc_q;
  logic [WACC_W-1:0]       g3_wacc_q;

  always_ff @(posedge clk_i) begin
    if (en[3]) begin
      for (int c = 0; c < 3; c++) begin
        g3_cacc_q[c] <= (g2_cw_q[0][c] + g2_cw_q[1][c]) + (g2_cw_q[2][c] + g2_cw_q[3][c]);
      end
      g3_wacc_q <= (g2_ww_q[0] + g2_ww_q[1]) + (g2_ww_q[2] + g2_ww_q[3]);
    end
  end

  // ---- G4: rounded; the depth window --------------------------------------------------------
  // |Wb - Wp| <= tol, tol = (Wp >> 6) + 1, is Wp - tol <= Wb <= Wp + tol: G5 then compares Wb
  // with two bounds side by side (the lower one clamped at 0: Wp - tol >= -1, and Wb >= 0)
  logic [DTOL_W-1:0] tol;
  logic [23:0]       g4_rgb_q;
  logic [W_W-1:0]    g4_wb_q;
  logic [WP_W-1:0]   g4_wlo_q;
  logic [WP_W:0]     g4_whi_q;
  logic              g4_base_ok_q, g4_sky_q, g4_sky_ok_q, g4_near_ok_q;

  assign tol = DTOL_W'(g3_wp >> DTOL_SH) + DTOL_W'(1);

  always_ff @(posedge clk_i) begin
    if (en[4]) begin
      for (int c = 0; c < 3; c++) begin
        g4_rgb_q[8*c +: 8] <= 8'((g3_cacc_q[c] + CACC_W'(128)) >> 8);
      end
      g4_wb_q      <= W_W'((g3_wacc_q + WACC_W'(128)) >> 8);
      g4_wlo_q     <= (g3_wp >= WP_W'(tol)) ? g3_wp - WP_W'(tol) : '0;
      g4_whi_q     <= (WP_W + 1)'(g3_wp) + (WP_W + 1)'(tol);
      g4_base_ok_q <= g3_base_ok;
      g4_sky_q     <= g3_sky;
      g4_sky_ok_q  <= g3_sky_ok;
      g4_near_ok_q <= g3_near_ok;
    end
  end

  // ---- G5 (output register): the depth test and geo_ok ----------------------------------------
  logic depth_ok;

  assign depth_ok = WP_W'(g4_wb_q) >= g4_wlo_q && (WP_W + 1)'(g4_wb_q) <= g4_whi_q;

  always_ff @(posedge clk_i) begin
    if (en[5]) begin
      rgb_o    <= g4_rgb_q;
      wb_o     <= g4_wb_q;
      geo_ok_o <= g4_base_ok_q && (g4_sky_q ? g4_sky_ok_q : (g4_near_ok_q && depth_ok));
    end
  end

  /* verilator lint_off SYNCASYNCNET */
  `MSR_ASSERT_NXT(a_out_hold, valid_o && !ready_i,
      valid_o && $stable({geo_ok_o, inside_o, rgb_o, wb_o, lo_o, hi_o, age_o, user_o}), clk_i,
      !rst_ni || clear_i)
  `MSR_ASSERT_NXT(a_extent_static, vld[0], $stable({width_i, height_i}), clk_i,
      !rst_ni || clear_i)
  // the rounded sums stay in their channels (sum of the weights 256)
  `MSR_ASSERT_IMP(a_weights, vld[0], (WT_W + 2)'(wt[0]) + (WT_W + 2)'(wt[1])
      + (WT_W + 2)'(wt[2]) + (WT_W + 2)'(wt[3]) == (WT_W + 2)'(256))
  `MSR_COVER(c_pass, valid_o && ready_i && geo_ok_o)
  `MSR_COVER(c_outside, valid_o && ready_i && !inside_o)
  `MSR_COVER(c_stall, valid_o && !ready_i)
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_reuse_gather
