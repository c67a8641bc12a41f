// Reprojection into the previous frame (docs/spec/reuse.md section 4), bit for bit with
// msr_model.reuse.reproject: for pixel (x, y) with inverse depth w and the frame's camera map
// (M, b: 12 registers, rows 0 and 1 in Q13.18, row 2 in Q2.29)
//   P_r = ((m_r0 x + m_r1 y + m_r2) << 16) + b_r w                 (63-bit signed)
//   1 / P2 ~= r 2^-(n + 23)  (n = bit length of P2; r from a 256-entry seed and one Newton step)
//   U = (p0s r + 2^(n-15)) >> (n - 14),  V likewise,  Wp = (w r + 2^(n-23)) >> (n - 22)
// with p0s, p1s = P0, P1 >> 22. ok_o: P2 >= 2^22 (in front, n >= 23) and |p0s|, |p1s| < 2^37.
// U, V leave saturated to UV_W bits (signed) and Wp to WP_W bits (unsigned), as the spec allows:
// a saturated position lies outside every frame and a saturated Wp fails the depth test, as
// the exact values do. U, V and Wp are defined only where ok_o is set.
//
// Fifteen register stages, one pixel a clock (each wide product takes two: the products of its
// 17-bit pieces in one, their sum in the next; in one clock they held the ECP5 to 64 MHz):
//   S0  inputs registered
//   S1  the pieces of the nine products m_r0 x, m_r1 y, b_r w
//   S2  the nine products
//   S3  P0, P1, P2
//   S4  leading-zero count of P2; the validity tests; p0s, p1s; the shift amount n - 23
//   S5  d = P2 normalised to 24 bits (top bit set); the seed T[d bits 22..15]
//   S6  the seed again, in flip-flops: a table mapped to a block RAM has a slow output
//   S7  the pieces of d t
//   S8  e = 2^40 - d t
//   S9  the pieces of t e
//   S10 r = (t e) >> 31
//   S11 the pieces of p0s r, p1s r, w r
//   S12 p0s r, p1s r, w r
//   S13 the same shifted right by n - 15 (U, V) and n - 23 (Wp): the rounding shift less one bit
//   S14 rounded (+1, >> 1) and saturated (output register)
// Global-stall pipeline: every stage advances when the output register is empty or taken.
// The camera map is static while a pixel is in S0 to S2 (the stages that read it).
`include "msr_assert.svh"

module msr_reproject #(
  parameter int unsigned XY_W   = 12,   // pixel coordinate bits (frames up to 2^XY_W wide)
  parameter int unsigned W_W    = 16,   // inverse depth bits
  parameter int unsigned UV_W   = 18,   // U, V: signed, 1/16 pixel, saturated
  parameter int unsigned WP_W   = 17,   // Wp: unsigned, saturated
  parameter int unsigned USER_W = 1     // sideband carried alongside each pixel
) (
  input  logic                     clk_i,
  input  logic                     rst_ni,
  input  logic                     clear_i,   // synchronous flush of the pipeline
  // the frame's camera map: m_i[r][c] = m_rc, b_i[r] = b_r (signed 32-bit registers)
  input  logic [2:0][2:0][31:0]    m_i,
  input  logic [2:0][31:0]         b_i,
  // one pixel in
  input  logic                     valid_i,
  output logic                     ready_o,
  input  logic [XY_W-1:0]          x_i,
  input  logic [XY_W-1:0]          y_i,
  input  logic [W_W-1:0]           w_i,       // predicted inverse depth w_m; 0: sky
  input  logic [USER_W-1:0]        user_i,
  // its previous-frame position
  output logic                     valid_o,
  input  logic                     ready_i,
  output logic                     ok_o,      // in front of the previous camera, in range
  output logic signed [UV_W-1:0]   u_o,       // previous x in 1/16 pixel (x0 = u >> 4, fx = u & 15)
  output logic signed [UV_W-1:0]   v_o,       // previous y in 1/16 pixel
  output logic [WP_W-1:0]          wp_o,      // inverse depth seen from the previous camera
  output logic [USER_W-1:0]        user_o
);

  // ---- formats (docs/spec/reuse.md sections 2 and 4) -----------------------------------------
  localparam int unsigned REG_W   = 32;                 // camera map register
  localparam int unsigned W_FRAC  = 16;                 // b_r w reads w as w / 2^16
  localparam int unsigned MX_W    = REG_W + XY_W;       // m x, |m x| < 2^(31 + XY_W)
  localparam int unsigned BW_W    = REG_W + W_W;        // b w
  localparam int unsigned A_W     = MX_W + 2;           // m_r0 x + m_r1 y + m_r2
  localparam int unsigned P_W     = A_W + W_FRAC + 1;   // P_r: 63 bits for 12-bit coordinates
  localparam int unsigned MAG_W   = P_W - 1;            // P2's magnitude bits (P2 > 0)
  localparam int unsigned CNT_W   = $clog2(MAG_W);
  localparam int unsigned D_W     = 24;                 // normalised P2
  localparam int unsigned IDX_W   = 8;                  // seed table index: d bits 22..15
  localparam int unsigned T_W     = 16;                 // seed
  localparam int unsigned DT_W    = D_W + T_W;          // d t < 2^40
  localparam int unsigned R_W     = 25;                 // r <= 2^24
  localparam int unsigned NEWTON  = 31;                 // r = (t (2^40 - d t)) >> 31
  localparam int unsigned PS_SH   = 22;                 // p0s = P0 >> 22 (LSB 2^-12)
  localparam int unsigned PS_LIM  = 37;                 // valid only if |p0s| < 2^37
  localparam int unsigned PS_W    = PS_LIM + 1;         // p0s in range: 38-bit signed
  localparam int unsigned N_MIN   = 23;                 // valid only if n >= 23
  localparam int unsigned PR_W    = PS_W + R_W + 1;     // p0s r (signed)
  localparam int unsigned WR_W    = W_W + R_W;          // w r
  localparam int unsigned UV_SH0  = N_MIN - 15;         // U's shift less one: n - 15 = 8 + (n - 23)
  localparam int unsigned Q_W     = PR_W - UV_SH0;      // p0s r >> 8
  localparam int unsigned SA_W    = CNT_W;              // n - 23 in 0..MAG_W - 23

  if (P_W > 64) begin : g_check_width
    $fatal(1, "msr_reproject: P_r needs %0d bits, the golden model computes in 64", P_W);
  end

  localparam int unsigned NS      = 15;                 // register stages

  // en[k]: stage k loads; vld[k]: stage k holds a pixel (the assertions read a few)
  logic [NS-1:0] en;
  /* verilator lint_off UNUSEDSIGNAL */
  logic [NS-1:0] vld;
  /* verilator lint_on UNUSEDSIGNAL */

  msr_stall_ctrl #(.STAGES(NS)) u_ctrl (.clk_i, .rst_ni, .clear_i, .valid_i, .ready_o, .valid_o,
    .ready_i, .vld_o(vld), .en_o(en));

  // ---- S0: inputs registered: the S1 products start at flip-flops ----------------------------
  logic [XY_W-1:0]   s0_x, s0_y;
  logic [W_W-1:0]    s0_w;
  logic [USER_W-1:0] s0_user;

  msr_en_pipe #(.WIDTH(2 * XY_W + W_W + USER_W)) u_s0 (.clk_i, .en_i(en[0]),
    .d_i({x_i, y_i, w_i, user_i}), .q_o({s0_x, s0_y, s0_w, s0_user}));

  // ---- S1, S2: the nine products, pieces in S1, products in S2 ------------------------------
  logic signed [2:0][MX_W-1:0] s2_mx, s2_my;
  logic signed [2:0][BW_W-1:0] s2_bw;

  for (genvar r = 0; r < 3; r++) begin : g_row
    msr_pipe_mul #(.A_W(REG_W), .B_W(XY_W), .A_SIGNED(1'b1), .P_W(MX_W)) u_mx (.clk_i,
      .en_i(en[2:1]), .a_i(m_i[r][0]), .b_i(s0_x), .p_o(s2_mx[r]));
    msr_pipe_mul #(.A_W(REG_W), .B_W(XY_W), .A_SIGNED(1'b1), .P_W(MX_W)) u_my (.clk_i,
      .en_i(en[2:1]), .a_i(m_i[r][1]), .b_i(s0_y), .p_o(s2_my[r]));
    msr_pipe_mul #(.A_W(REG_W), .B_W(W_W), .A_SIGNED(1'b1), .P_W(BW_W)) u_bw (.clk_i,
      .en_i(en[2:1]), .a_i(b_i[r]), .b_i(s0_w), .p_o(s2_bw[r]));
  end

  // w and the sideband alongside, to S3
  logic [W_W-1:0]    s3_w;
  logic [USER_W-1:0] s3_user;

  msr_en_pipe #(.WIDTH(W_W + USER_W), .DEPTH(3)) u_carry_p (.clk_i, .en_i(en[3:1]),
    .d_i({s0_w, s0_user}), .q_o({s3_w, s3_user}));

  // ---- S3: P_r ----------------------------------------------------------------------------------
  logic signed [2:0][P_W-1:0] s3_p_q;

  function automatic logic signed [P_W-1:0] row_p(logic signed [MX_W-1:0] mx,
      logic signed [MX_W-1:0] my, logic signed [REG_W-1:0] m2, logic signed [BW_W-1:0] bw);
    logic signed [A_W-1:0] a;
    a = A_W'(mx) + A_W'(my) + A_W'(m2);
    return (P_W'(a) <<< W_FRAC) + P_W'(bw);
  endfunction

  always_ff @(posedge clk_i) begin
    if (en[3]) begin
      for (int r = 0; r < 3; r++) begin
        s3_p_q[r] <= row_p(s2_mx[r], s2_my[r], m_i[r][2], s2_bw[r]);
      end
    end
  end

  // ---- S4: leading zeros of P2, validity, p0s and p1s, the shift amount n - 23 --------------
  // msr_lzc finds the lowest set bit: it reads P2's magnitude bit-reversed.
  logic [MAG_W-1:0] p2_rev;
  logic [CNT_W-1:0] p2_lz;
  /* verilator lint_off UNUSEDSIGNAL */
  logic             p2_zero;    // P2 = 0 fails the validity test by itself
  /* verilator lint_on UNUSEDSIGNAL */

  for (genvar i = 0; i < MAG_W; i++) begin : g_rev
    assign p2_rev[i] = s3_p_q[2][MAG_W-1-i];
  end

  msr_lzc #(.WIDTH(MAG_W)) u_lzc (
    .in_i    (p2_rev),
    .cnt_o   (p2_lz),
    .empty_o (p2_zero)
  );

  // |P_r >> 22| < 2^37: the bits above PS_W - 1 repeat its sign and it is not -2^37
  function automatic logic ps_in_range(logic [P_W-PS_SH-1:0] ps);
    return (ps[P_W-PS_SH-1:PS_W-1] == {(P_W - PS_SH - PS_W + 1){ps[PS_W-1]}})
        && !(ps[PS_W-1] && ps[PS_W-2:0] == '0);
  endfunction

  // what S4 hands on unchanged to S10, r's stage: ok, the shift amount, p0s and p1s
  // (one a position axis), w and the sideband
  typedef struct packed {
    logic                         ok;
    logic [SA_W-1:0]              sa;
    logic [1:0][PS_W-1:0]         ps;
    logic [W_W-1:0]               w;
    logic [USER_W-1:0]            user;
  } carry_t;

  carry_t           s4_c_q, s10_c;
  logic [CNT_W-1:0] s4_lz_q;
  logic [MAG_W-1:0] s4_p2_q;

  always_ff @(posedge clk_i) begin
    if (en[4]) begin
      // P2 > 0 and n >= 23 is P2 >= 2^22
      s4_c_q.ok   <= !s3_p_q[2][P_W-1] && (|s3_p_q[2][MAG_W-1:N_MIN-1])
                     && ps_in_range(s3_p_q[0][P_W-1:PS_SH]) && ps_in_range(s3_p_q[1][P_W-1:PS_SH]);
      s4_c_q.sa   <= SA_W'(MAG_W - N_MIN) - p2_lz;
      for (int a = 0; a < 2; a++) begin
        s4_c_q.ps[a] <= s3_p_q[a][PS_SH+PS_W-1:PS_SH];
      end
      s4_c_q.w    <= s3_w;
      s4_c_q.user <= s3_user;
      s4_lz_q     <= p2_lz;
      s4_p2_q     <= s3_p_q[2][MAG_W-1:0];
    end
  end

  msr_en_pipe #(.WIDTH($bits(carry_t)), .DEPTH(6)) u_carry (.clk_i, .en_i(en[10:5]),
    .d_i(s4_c_q), .q_o(s10_c));

  // ---- the seed table: T[i] = floor(2^24 / (256.5 + i) + 0.5) = (2^26 + 513 + 2i) div (1026 + 4i)
  logic [2**IDX_W-1:0][T_W-1:0] seed_rom;

  for (genvar i = 0; i < 2 ** IDX_W; i++) begin : g_seed
    localparam int unsigned SEED = ((1 << 26) + 513 + 2 * i) / (1026 + 4 * i);
    assign seed_rom[i] = T_W'(SEED);
  end

  // ---- S5: d = P2 normalised, and the seed; S6: the seed in flip-flops --------------------
  // (a table mapped to a block RAM has a slow output)
  /* verilator lint_off UNUSEDSIGNAL */
  logic [MAG_W-1:0] p2_norm;    // its top D_W bits are d
  /* verilator lint_on UNUSEDSIGNAL */
  assign p2_norm = s4_p2_q << s4_lz_q;

  logic [D_W-1:0] s5_d_q, s6_d_q;
  logic [T_W-1:0] s5_t_q, s6_t_q;

  always_ff @(posedge clk_i) begin
    if (en[5]) begin
      s5_d_q <= p2_norm[MAG_W-1:MAG_W-D_W];
      s5_t_q <= seed_rom[p2_norm[MAG_W-2:MAG_W-1-IDX_W]];
    end
    if (en[6]) begin
      s6_d_q <= s5_d_q;
      s6_t_q <= s5_t_q;
    end
  end

  // ---- S7, S8: e = 2^40 - d t, pieces in S7 -----------------------------------------------------
  // d t < 2^40 (d < 2^24, t < 2^16), so e is d t's 40-bit two's complement
  logic [DT_W-1:0] s8_e;
  logic [T_W-1:0]  s8_t;

  msr_pipe_mul #(.A_W(D_W), .B_W(T_W), .NEGATE(1'b1), .P_W(DT_W)) u_dt (.clk_i, .en_i(en[8:7]),
    .a_i(s6_d_q), .b_i(s6_t_q), .p_o(s8_e));
  msr_en_pipe #(.WIDTH(T_W), .DEPTH(2)) u_carry_t (.clk_i, .en_i(en[8:7]), .d_i(s6_t_q),
    .q_o(s8_t));

  // ---- S9, S10: r = (t e) >> 31, pieces in S9 ---------------------------------------------------
  /* verilator lint_off UNUSEDSIGNAL */
  logic [DT_W+T_W-1:0] s10_newton;   // r is its bits 31 and up
  /* verilator lint_on UNUSEDSIGNAL */
  logic [R_W-1:0]      s10_r;

  msr_pipe_mul #(.A_W(DT_W), .B_W(T_W)) u_newton (.clk_i, .en_i(en[10:9]), .a_i(s8_e),
    .b_i(s8_t), .p_o(s10_newton));
  assign s10_r = s10_newton[NEWTON+R_W-1:NEWTON];

  // ---- S11, S12: p0s r, p1s r, w r, pieces in S11 ---------------------------------------------
  /* verilator lint_off UNUSEDSIGNAL */
  logic [1:0][PR_W-1:0] s12_x;   // bits 0..7 fall off every shift
  /* verilator lint_on UNUSEDSIGNAL */
  logic [WR_W-1:0]      s12_xw;

  for (genvar a = 0; a < 2; a++) begin : g_axis
    msr_pipe_mul #(.A_W(PS_W), .B_W(R_W), .A_SIGNED(1'b1), .P_W(PR_W)) u_mul (.clk_i,
      .en_i(en[12:11]), .a_i(s10_c.ps[a]), .b_i(s10_r), .p_o(s12_x[a]));
  end
  msr_pipe_mul #(.A_W(W_W), .B_W(R_W)) u_mul_w (.clk_i, .en_i(en[12:11]), .a_i(s10_c.w),
    .b_i(s10_r), .p_o(s12_xw));

  // ok, the shift amount and the sideband alongside the products
  logic              s12_ok;
  logic [SA_W-1:0]   s12_sa;
  logic [USER_W-1:0] s12_user;

  msr_en_pipe #(.WIDTH(1 + SA_W + USER_W), .DEPTH(2)) u_carry_mul (.clk_i, .en_i(en[12:11]),
    .d_i({s10_c.ok, s10_c.sa, s10_c.user}), .q_o({s12_ok, s12_sa, s12_user}));

  // ---- S13: the rounding shifts less their last bit --------------------------------------------
  // (X + 2^(s-1)) >> s = ((X >> (s-1)) + 1) >> 1 for the floor shift: S13 shifts by s - 1,
  // S14 adds the one and drops the bit.
  logic signed [1:0][Q_W-1:0] s13_q_q;
  logic [WR_W-1:0]            s13_qw_q;
  logic                       s13_ok_q;
  logic [USER_W-1:0]          s13_user_q;

  always_ff @(posedge clk_i) begin
    if (en[13]) begin
      for (int a = 0; a < 2; a++) begin
        s13_q_q[a] <= $signed(s12_x[a][PR_W-1:UV_SH0]) >>> s12_sa;
      end
      s13_qw_q   <= s12_xw >> s12_sa;
      s13_ok_q   <= s12_ok;
      s13_user_q <= s12_user;
    end
  end

  // ---- S14: rounded and saturated ---------------------------------------------------------------
  // Clamping q to [-2^UV_W, 2^UV_W - 2] before (q + 1) >> 1 gives the saturated result: 2^17 - 1
  // above, -2^17 below, and in range the sum fits UV_W + 1 bits (likewise Wp: 2^WP_W - 1 once
  // q >= 2^(WP_W+1) - 1). The range tests read q's bits (no wide comparison: this is the
  // output stage).
  function automatic logic signed [UV_W-1:0] round_uv(logic signed [Q_W-1:0] q);
    logic                 hi, lo;
    logic signed [UV_W:0] s;
    hi = !q[Q_W-1] && ((|q[Q_W-2:UV_W]) || (&q[UV_W-1:0]));   // q >= 2^UV_W - 1
    lo = q[Q_W-1] && !(&q[Q_W-2:UV_W]);                        // q < -2^UV_W
    s  = (UV_W + 1)'(q) + (UV_W + 1)'(1);
    return hi ? UV_W'((1 << (UV_W - 1)) - 1) : lo ? UV_W'(1 << (UV_W - 1)) : UV_W'(s >>> 1);
  endfunction

  function automatic logic [WP_W-1:0] round_wp(logic [WR_W-1:0] q);
    logic          hi;
    logic [WP_W:0] s;
    hi = (|q[WR_W-1:WP_W+1]) || (&q[WP_W:0]);                 // q >= 2^(WP_W+1) - 1
    s  = (WP_W + 1)'(q) + (WP_W + 1)'(1);
    return hi ? '1 : WP_W'(s >> 1);
  endfunction

  always_ff @(posedge clk_i) begin
    if (en[14]) begin
      ok_o   <= s13_ok_q;
      u_o    <= round_uv(s13_q_q[0]);
      v_o    <= round_uv(s13_q_q[1]);
      wp_o   <= round_wp(s13_qw_q);
      user_o <= s13_user_q;
    end
  end

  /* verilator lint_off SYNCASYNCNET */
  `MSR_ASSERT_NXT(a_out_hold, valid_o && !ready_i,
      valid_o && $stable({ok_o, u_o, v_o, wp_o, user_o}), clk_i, !rst_ni || clear_i)
  `MSR_ASSERT_NXT(a_cam_static, |vld[2:0], $stable({m_i, b_i}), clk_i,
      !rst_ni || clear_i)
  // the Newton step's result over every d in [2^23, 2^24): 2^23 - 8 <= r <= 2^24 (R_W bits)
  `MSR_ASSERT_IMP(a_recip_range, vld[10] && s10_c.ok,
      s10_r >= R_W'((1 << 23) - 8) && s10_r <= R_W'(1 << 24))
  `MSR_COVER(c_ok, valid_o && ready_i && ok_o)
  `MSR_COVER(c_not_ok, valid_o && ready_i && !ok_o)
  `MSR_COVER(c_stall, valid_o && !ready_i)
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_reproject
