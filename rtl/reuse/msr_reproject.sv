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
// Eleven register stages, one pixel a clock:
//   S0  inputs registered
//   S1  the nine products m_r0 x, m_r1 y, b_r w
//   S2  P0, P1, P2
//   S3  leading-zero count of P2; the validity tests; p0s, p1s
//   S4  d = P2 normalised to 24 bits (top bit set); shift amount n - 23; the seed T[d bits 22..15]
//   S5  the seed again, in flip-flops: a table mapped to a block RAM has a slow output
//   S6  d t
//   S7  r = (t (2^40 - d t)) >> 31
//   S8  p0s r, p1s r, w r
//   S9  the same shifted right by n - 15 (U, V) and n - 23 (Wp): the rounding shift less one bit
//   S10 rounded (+1, >> 1) and saturated (output register)
// Global-stall pipeline: every stage advances when the output register is empty or taken.
// The camera map is static while a pixel is in S0 or S1 (the stages that read it).
`include "msr_assert.svh"
`include "msr_flops.svh"

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

  logic advance;
  assign advance = !valid_o || ready_i;
  assign ready_o = advance;

  logic s0_valid_q, s1_valid_q, s2_valid_q, s3_valid_q, s4_valid_q;
  logic s5_valid_q, s6_valid_q, s7_valid_q, s8_valid_q, s9_valid_q;

  // ---- S0: inputs registered: the S1 products start at flip-flops ----------------------------
  logic [XY_W-1:0]   s0_x_q, s0_y_q;
  logic [W_W-1:0]    s0_w_q;
  logic [USER_W-1:0] s0_user_q;

  always_ff @(posedge clk_i) begin
    if (advance && valid_i) begin
      s0_x_q    <= x_i;
      s0_y_q    <= y_i;
      s0_w_q    <= w_i;
      s0_user_q <= user_i;
    end
  end

  // ---- S1: products ---------------------------------------------------------------------------
  logic signed [2:0][MX_W-1:0] s1_mx_q, s1_my_q;
  logic signed [2:0][BW_W-1:0] s1_bw_q;
  logic [W_W-1:0]              s1_w_q;
  logic [USER_W-1:0]           s1_user_q;

  always_ff @(posedge clk_i) begin
    if (advance && s0_valid_q) begin
      for (int r = 0; r < 3; r++) begin
        s1_mx_q[r] <= MX_W'($signed(m_i[r][0]) * $signed({1'b0, s0_x_q}));
        s1_my_q[r] <= MX_W'($signed(m_i[r][1]) * $signed({1'b0, s0_y_q}));
        s1_bw_q[r] <= BW_W'($signed(b_i[r]) * $signed({1'b0, s0_w_q}));
      end
      s1_w_q    <= s0_w_q;
      s1_user_q <= s0_user_q;
    end
  end

  // ---- S2: P_r ----------------------------------------------------------------------------------
  logic signed [2:0][P_W-1:0] s2_p_q;
  logic [W_W-1:0]             s2_w_q;
  logic [USER_W-1:0]          s2_user_q;

  function automatic logic signed [P_W-1:0] row_p(logic signed [MX_W-1:0] mx,
      logic signed [MX_W-1:0] my, logic signed [REG_W-1:0] m2, logic signed [BW_W-1:0] bw);
    logic signed [A_W-1:0] a;
    a = A_W'(mx) + A_W'(my) + A_W'(m2);
    return (P_W'(a) <<< W_FRAC) + P_W'(bw);
  endfunction

  always_ff @(posedge clk_i) begin
    if (advance && s1_valid_q) begin
      for (int r = 0; r < 3; r++) begin
        s2_p_q[r] <= row_p(s1_mx_q[r], s1_my_q[r], m_i[r][2], s1_bw_q[r]);
      end
      s2_w_q    <= s1_w_q;
      s2_user_q <= s1_user_q;
    end
  end

  // ---- S3: leading zeros of P2, validity, p0s and p1s ---------------------------------------
  // msr_lzc finds the lowest set bit: it reads P2's magnitude bit-reversed.
  logic [MAG_W-1:0] p2_rev;
  logic [CNT_W-1:0] p2_lz;
  /* verilator lint_off UNUSEDSIGNAL */
  logic             p2_zero;    // P2 = 0 fails the validity test by itself
  /* verilator lint_on UNUSEDSIGNAL */

  for (genvar i = 0; i < MAG_W; i++) begin : g_rev
    assign p2_rev[i] = s2_p_q[2][MAG_W-1-i];
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

  logic                    s3_ok_q;
  logic [CNT_W-1:0]        s3_lz_q;
  logic [MAG_W-1:0]        s3_p2_q;
  logic signed [PS_W-1:0]  s3_p0s_q, s3_p1s_q;
  logic [W_W-1:0]          s3_w_q;
  logic [USER_W-1:0]       s3_user_q;

  always_ff @(posedge clk_i) begin
    if (advance && s2_valid_q) begin
      // P2 > 0 and n >= 23 is P2 >= 2^22
      s3_ok_q   <= !s2_p_q[2][P_W-1] && (|s2_p_q[2][MAG_W-1:N_MIN-1])
                   && ps_in_range(s2_p_q[0][P_W-1:PS_SH]) && ps_in_range(s2_p_q[1][P_W-1:PS_SH]);
      s3_lz_q   <= p2_lz;
      s3_p2_q   <= s2_p_q[2][MAG_W-1:0];
      s3_p0s_q  <= s2_p_q[0][PS_SH+PS_W-1:PS_SH];
      s3_p1s_q  <= s2_p_q[1][PS_SH+PS_W-1:PS_SH];
      s3_w_q    <= s2_w_q;
      s3_user_q <= s2_user_q;
    end
  end

  // ---- the seed table: T[i] = floor(2^24 / (256.5 + i) + 0.5) = (2^26 + 513 + 2i) div (1026 + 4i)
  logic [2**IDX_W-1:0][T_W-1:0] seed_rom;

  for (genvar i = 0; i < 2 ** IDX_W; i++) begin : g_seed
    localparam int unsigned SEED = ((1 << 26) + 513 + 2 * i) / (1026 + 4 * i);
    assign seed_rom[i] = T_W'(SEED);
  end

  // ---- S4: d, the seed, and the shift amount n - 23 = (MAG_W - lz) - 23 -----------------------
  /* verilator lint_off UNUSEDSIGNAL */
  logic [MAG_W-1:0] p2_norm;    // its top D_W bits are d
  /* verilator lint_on UNUSEDSIGNAL */
  assign p2_norm = s3_p2_q << s3_lz_q;

  logic                    s4_ok_q;
  logic [D_W-1:0]          s4_d_q;
  logic [T_W-1:0]          s4_t_q;
  logic [SA_W-1:0]         s4_sa_q;
  logic signed [PS_W-1:0]  s4_p0s_q, s4_p1s_q;
  logic [W_W-1:0]          s4_w_q;
  logic [USER_W-1:0]       s4_user_q;

  always_ff @(posedge clk_i) begin
    if (advance && s3_valid_q) begin
      s4_ok_q   <= s3_ok_q;
      s4_d_q    <= p2_norm[MAG_W-1:MAG_W-D_W];
      s4_t_q    <= seed_rom[p2_norm[MAG_W-2:MAG_W-1-IDX_W]];
      s4_sa_q   <= SA_W'(MAG_W - N_MIN) - s3_lz_q;
      s4_p0s_q  <= s3_p0s_q;
      s4_p1s_q  <= s3_p1s_q;
      s4_w_q    <= s3_w_q;
      s4_user_q <= s3_user_q;
    end
  end

  // ---- S5: the seed in flip-flops --------------------------------------------------------------
  logic                    s5_ok_q;
  logic [D_W-1:0]          s5_d_q;
  logic [T_W-1:0]          s5_t_q;
  logic [SA_W-1:0]         s5_sa_q;
  logic signed [PS_W-1:0]  s5_p0s_q, s5_p1s_q;
  logic [W_W-1:0]          s5_w_q;
  logic [USER_W-1:0]       s5_user_q;

  always_ff @(posedge clk_i) begin
    if (advance && s4_valid_q) begin
      s5_ok_q   <= s4_ok_q;
      s5_d_q    <= s4_d_q;
      s5_t_q    <= s4_t_q;
      s5_sa_q   <= s4_sa_q;
      s5_p0s_q  <= s4_p0s_q;
      s5_p1s_q  <= s4_p1s_q;
      s5_w_q    <= s4_w_q;
      s5_user_q <= s4_user_q;
    end
  end

  // ---- S6: d t ----------------------------------------------------------------------------------
  logic                    s6_ok_q;
  logic [DT_W-1:0]         s6_dt_q;
  logic [T_W-1:0]          s6_t_q;
  logic [SA_W-1:0]         s6_sa_q;
  logic signed [PS_W-1:0]  s6_p0s_q, s6_p1s_q;
  logic [W_W-1:0]          s6_w_q;
  logic [USER_W-1:0]       s6_user_q;

  always_ff @(posedge clk_i) begin
    if (advance && s5_valid_q) begin
      s6_ok_q   <= s5_ok_q;
      s6_dt_q   <= DT_W'(s5_d_q) * DT_W'(s5_t_q);
      s6_t_q    <= s5_t_q;
      s6_sa_q   <= s5_sa_q;
      s6_p0s_q  <= s5_p0s_q;
      s6_p1s_q  <= s5_p1s_q;
      s6_w_q    <= s5_w_q;
      s6_user_q <= s5_user_q;
    end
  end

  // ---- S7: r = (t (2^40 - d t)) >> 31 ----------------------------------------------------------
  // d t < 2^40 (d < 2^24, t < 2^16), so 2^40 - d t is its 40-bit two's complement
  logic [DT_W-1:0]      newton_e;
  /* verilator lint_off UNUSEDSIGNAL */
  logic [DT_W+T_W-1:0]  newton_p;   // r is its bits 31 and up
  /* verilator lint_on UNUSEDSIGNAL */
  assign newton_e = -s6_dt_q;
  assign newton_p = (DT_W + T_W)'(newton_e) * (DT_W + T_W)'(s6_t_q);

  logic                    s7_ok_q;
  logic [R_W-1:0]          s7_r_q;
  logic [SA_W-1:0]         s7_sa_q;
  logic signed [PS_W-1:0]  s7_p0s_q, s7_p1s_q;
  logic [W_W-1:0]          s7_w_q;
  logic [USER_W-1:0]       s7_user_q;

  always_ff @(posedge clk_i) begin
    if (advance && s6_valid_q) begin
      s7_ok_q   <= s6_ok_q;
      s7_r_q    <= newton_p[NEWTON+R_W-1:NEWTON];
      s7_sa_q   <= s6_sa_q;
      s7_p0s_q  <= s6_p0s_q;
      s7_p1s_q  <= s6_p1s_q;
      s7_w_q    <= s6_w_q;
      s7_user_q <= s6_user_q;
    end
  end

  // ---- S8: p0s r, p1s r, w r ------------------------------------------------------------------
  logic                    s8_ok_q;
  /* verilator lint_off UNUSEDSIGNAL */
  logic signed [PR_W-1:0]  s8_x0_q, s8_x1_q;   // bits 0..7 fall off every shift
  /* verilator lint_on UNUSEDSIGNAL */
  logic [WR_W-1:0]         s8_xw_q;
  logic [SA_W-1:0]         s8_sa_q;
  logic [USER_W-1:0]       s8_user_q;

  always_ff @(posedge clk_i) begin
    if (advance && s7_valid_q) begin
      s8_ok_q   <= s7_ok_q;
      s8_x0_q   <= PR_W'(s7_p0s_q) * PR_W'($signed({1'b0, s7_r_q}));
      s8_x1_q   <= PR_W'(s7_p1s_q) * PR_W'($signed({1'b0, s7_r_q}));
      s8_xw_q   <= WR_W'(s7_w_q) * WR_W'(s7_r_q);
      s8_sa_q   <= s7_sa_q;
      s8_user_q <= s7_user_q;
    end
  end

  // ---- S9: the rounding shifts less their last bit ---------------------------------------------
  // (X + 2^(s-1)) >> s = ((X >> (s-1)) + 1) >> 1 for the floor shift: S9 shifts by s - 1,
  // S10 adds the one and drops the bit.
  logic signed [Q_W-1:0] s9_q0_q, s9_q1_q;
  logic [WR_W-1:0]       s9_qw_q;
  logic                  s9_ok_q;
  logic [USER_W-1:0]     s9_user_q;

  always_ff @(posedge clk_i) begin
    if (advance && s8_valid_q) begin
      s9_ok_q   <= s8_ok_q;
      s9_q0_q   <= $signed(s8_x0_q[PR_W-1:UV_SH0]) >>> s8_sa_q;
      s9_q1_q   <= $signed(s8_x1_q[PR_W-1:UV_SH0]) >>> s8_sa_q;
      s9_qw_q   <= s8_xw_q >> s8_sa_q;
      s9_user_q <= s8_user_q;
    end
  end

  // ---- S10: rounded and saturated ---------------------------------------------------------------
  // Clamping q to [-2^UV_W, 2^UV_W - 2] before (q + 1) >> 1 gives the saturated result, and the
  // sum then fits UV_W + 1 bits (likewise Wp with q <= 2^(WP_W+1) - 2).
  function automatic logic signed [UV_W-1:0] round_uv(logic signed [Q_W-1:0] q);
    logic signed [UV_W:0] c;
    logic signed [UV_W:0] s;
    if (q > Q_W'((1 << UV_W) - 2)) begin
      c = (UV_W + 1)'((1 << UV_W) - 2);
    end else if (q < -Q_W'(1 << UV_W)) begin
      c = -(UV_W + 1)'(1 << UV_W);
    end else begin
      c = (UV_W + 1)'(q);
    end
    s = c + (UV_W + 1)'(1);
    return UV_W'(s >>> 1);
  endfunction

  function automatic logic [WP_W-1:0] round_wp(logic [WR_W-1:0] q);
    logic [WP_W:0] c;
    logic [WP_W:0] s;
    c = (q > WR_W'((1 << (WP_W + 1)) - 2)) ? (WP_W + 1)'((1 << (WP_W + 1)) - 2) : (WP_W + 1)'(q);
    s = c + (WP_W + 1)'(1);
    return WP_W'(s >> 1);
  endfunction

  always_ff @(posedge clk_i) begin
    if (advance && s9_valid_q) begin
      ok_o   <= s9_ok_q;
      u_o    <= round_uv(s9_q0_q);
      v_o    <= round_uv(s9_q1_q);
      wp_o   <= round_wp(s9_qw_q);
      user_o <= s9_user_q;
    end
  end

  // ---- Valid bits: one shift register that moves when the pipeline advances ------------------
  `MSR_CLR_REG(u_valid, 11, clear_i, advance,
               {s9_valid_q, s8_valid_q, s7_valid_q, s6_valid_q, s5_valid_q,
                s4_valid_q, s3_valid_q, s2_valid_q, s1_valid_q, s0_valid_q, valid_i},
               {valid_o, s9_valid_q, s8_valid_q, s7_valid_q, s6_valid_q,
                s5_valid_q, s4_valid_q, s3_valid_q, s2_valid_q, s1_valid_q, s0_valid_q})

  /* verilator lint_off SYNCASYNCNET */
  `MSR_ASSERT_NXT(a_out_hold, valid_o && !ready_i,
      valid_o && $stable({ok_o, u_o, v_o, wp_o, user_o}), clk_i, !rst_ni || clear_i)
  `MSR_ASSERT_NXT(a_cam_static, s0_valid_q || s1_valid_q, $stable({m_i, b_i}), clk_i,
      !rst_ni || clear_i)
  // the Newton step's result over every d in [2^23, 2^24): 2^23 - 8 <= r <= 2^24 (R_W bits)
  `MSR_ASSERT_IMP(a_recip_range, s7_valid_q && s7_ok_q,
      s7_r_q >= R_W'((1 << 23) - 8) && s7_r_q <= R_W'(1 << 24))
  `MSR_COVER(c_ok, valid_o && ready_i && ok_o)
  `MSR_COVER(c_not_ok, valid_o && ready_i && !ok_o)
  `MSR_COVER(c_stall, valid_o && !ready_i)
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_reproject
