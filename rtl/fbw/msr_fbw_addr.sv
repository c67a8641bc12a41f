// Frame-buffer writer, address pipeline: one complete row per clock from the row buffers to
// its plane addresses and burst shapes.
//
// Pick (round robin over the inputs with a complete row, msr_rr_arb; registered) -> the row's
// y, x0 and length -> the row address of each plane, base + y*stride + x0 term, with y*stride
// a radix-8 sum of stride multiples (no multiplier: 3x, 5x and 7x are registers), the six
// addends compressed to a carry-save pair and added in 12/10/10-bit segments over three clocks,
// beside them the plane's burst shape (first-beat offset, beats, the 4 KiB split) -> a short
// queue (S5) that the AW side takes from (row_valid_o / row_ready_i).
`include "msr_assert.svh"
`include "msr_flops.svh"
`include "msr_fbw_types.svh"

module msr_fbw_addr import msr_pkg::*; import msr_fbw_pkg::*; #(
  parameter int unsigned NUM_IN     = 4,     // pixel streams (engines)
  parameter int unsigned AXI_DATA_W = 256,   // AXI data width: 32, 64, 128 or 256
  localparam int unsigned IN_W      = (NUM_IN > 1) ? $clog2(NUM_IN) : 1,
  localparam int unsigned MA_W      = $clog2(NBUF * pix_beats(AXI_DATA_W / 32)),
  localparam int unsigned BB_W      = $clog2(AXI_DATA_W / 8),        // byte offset in a beat
  parameter  type         row_t     = `MSR_FBW_ROW_T(IN_W, MA_W, BB_W)  // the writer's
) (
  input  logic              clk_i,           // clock
  input  logic              rst_ni,          // asynchronous reset, active low
  input  logic              clear_i,         // synchronous clear
  input  fb_cfg_t           fb_i,            // frame-buffer settings, stable during a frame
  // Complete rows from the row buffers.
  input  logic [NUM_IN-1:0] req_i,           // per input: its next row is complete
  input  buf_t [NUM_IN-1:0] pick_i,          // per input: the buffer of that row
  output logic [NUM_IN-1:0] take_o,          // that row is taken (one-hot)
  output logic [IN_W-1:0]   meta_in_o,       // metadata read: input
  output buf_t              meta_buf_o,      // and buffer of the row picked last clock
  input  row_meta_t         meta_i,          // the row there
  // Addressed rows to the AW side.
  output logic              row_valid_o,     // an addressed row
  input  logic              row_ready_i,     // the AW side takes it
  output row_t              row_o,           // the row
  // Status.
  output logic              idle_o           // no row in the pipeline or its queue
);
  localparam int unsigned WPB    = AXI_DATA_W / 32;
  localparam int unsigned PB     = pix_beats(WPB);
  localparam int unsigned SB     = code_beats(WPB);
  localparam int unsigned B4K_W  = 12 - BB_W;                       // beat index in a 4 KiB page

  typedef logic [IN_W-1:0] in_t;
  typedef logic [MA_W-1:0] maddr_t;
  typedef `MSR_FBW_SHAPE_T(BB_W) shape_t;

  logic arb_valid, arb_ready, arb_take;
  in_t  arb_idx;
  logic [NUM_IN-1:0] arb_gnt;

  msr_rr_arb #(.N(NUM_IN), .LOCK(1'b0), .IDX_W(IN_W)) u_row_arb (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .clear_i (clear_i),
    .req_i   (req_i),
    .gnt_o   (arb_gnt),
    .idx_o   (arb_idx),
    .valid_o (arb_valid),
    .ready_i (arb_ready)
  );
  assign arb_take = arb_valid && arb_ready;
  assign take_o   = arb_take ? arb_gnt : '0;

  // Stride multiples 3s, 5s, 7s for y * stride (radix 8: y*s = sum_k digit_k(y) * s << 3k).
  // The strides are constant during a frame, so these adders are segmented with a registered
  // carry between 8-bit segments: the products settle four clocks after a stride changes
  // (the configuration is latched at START; the first row completes much later).
  localparam int unsigned NMUL = 6;   // fb 3s, 5s, 7s, src 3s, 5s, 7s
  logic [NMUL-1:0][31:0] mul_a, mul_b;
  logic [NMUL-1:0]       mul_ci;
  logic [NMUL-1:0][31:0] mul_q;
  logic [NMUL-1:0][4:0]  mul_c_q;     // carry into segment k (k = 1..3)

  always_comb begin
    for (int unsigned p = 0; p < 2; p++) begin
      logic [31:0] st;
      st = (p != 0) ? fb_i.src_stride : fb_i.fb_stride;
      mul_a[3*p]     = st;
      mul_b[3*p]     = st << 1;
      mul_ci[3*p]    = 1'b0;
      mul_a[3*p+1]   = st;
      mul_b[3*p+1]   = st << 2;
      mul_ci[3*p+1]  = 1'b0;
      mul_a[3*p+2]   = st << 3;       // 8s - s = 8s + ~s + 1
      mul_b[3*p+2]   = ~st;
      mul_ci[3*p+2]  = 1'b1;
    end
  end

  logic [NMUL-1:0][31:0] mul_d;
  logic [NMUL-1:0][4:0]  mul_c_d;
  for (genvar v = 0; v < NMUL; v++) begin : g_mul
    logic [3:0] co;
    msr_seg_add #(.WIDTH(32), .SEG_W(8)) u_add (
      .a_i (mul_a[v]),
      .b_i (mul_b[v]),
      .c_i ({mul_c_q[v][3:1], mul_ci[v]}),
      .s_o (mul_d[v]),
      .c_o (co)
    );
    assign mul_c_d[v] = {co, 1'b0};
  end

  // Reset but never cleared: the products follow the strides whatever the frame does.
  `MSR_CLR_REG(u_mul, NMUL * (32 + 5), 1'b0, 1'b1, {mul_d, mul_c_d}, {mul_q, mul_c_q})

  function automatic logic [31:0] mult8(logic [2:0] d, logic [31:0] s, logic [31:0] s3,
                                        logic [31:0] s5, logic [31:0] s7);
    unique case (d)
      3'd0:    return '0;
      3'd1:    return s;
      3'd2:    return s << 1;
      3'd3:    return s3;
      3'd4:    return s << 2;
      3'd5:    return s5;
      3'd6:    return s3 << 1;
      default: return s7;
    endcase
  endfunction

  // Carry-save 3:2 compression of three addends.
  typedef struct packed {
    logic [31:0] s;
    logic [31:0] c;
  } cs_t;
  function automatic cs_t csa(logic [31:0] a, logic [31:0] b, logic [31:0] c);
    cs_t r;
    r.s = a ^ b ^ c;
    r.c = ((a & b) | (a & c) | (b & c)) << 1;
    return r;
  endfunction

  // Row address of plane p (0 pixels, 1 codes):
  //   S0 the arbiter's pick; S1 the picked row; S1m the four stride multiples; S1.5 / S2 six
  //   addends (the multiples, base, x0 term) compressed to a carry-save pair in three 3:2
  //   levels; S3, S4, S5 the carry-propagate add in segments [11:0], [21:12], [31:22] with the
  //   carry registered between them; beside S4 / S5 the plane's burst shape from the low 12
  //   bits (first-beat offset, beats, the 4 KiB split), with no add wider than 12 bits.
  logic   s0_v_q;                               // S0: the arbiter's pick, registered
  in_t    s0_in_q;
  buf_t   s0_buf_q;
  logic   s1_v_q, s1m_v_q, s15_v_q, s2_v_q, s3_v_q, s4_v_q;
  in_t    s1m_in_q, s15_in_q;
  buf_t   s1m_buf_q, s15_buf_q;
  lcoord_t s1m_l_q, s15_l_q;
  coord_t s1m_x0_q;
  logic   [1:0][3:0][31:0] s1m_m_q, s1m_m_d;     // per plane: the four stride multiples
  cs_t    [1:0][1:0] s15_cs_q, s15_cs_d;         // per plane: two carry-save pairs
  in_t    s1_in_q, s2_in_q, s3_in_q, s4_in_q;
  buf_t   s1_buf_q, s2_buf_q, s3_buf_q, s4_buf_q;
  lcoord_t s1_l_q, s2_l_q, s3_l_q;             // pixels of the row - 1
  coord_t s1_y_q, s1_x0_q;
  cs_t    [1:0] s2_cs_q, s3_cs_q, s4_cs_q;
  logic   [1:0][11:0] s3_lo_q, s4_lo_q;         // address bits [11:0]
  logic   [1:0][9:0]  s4_mid_q;                 // address bits [21:12]
  logic   [1:0]       s3_cy_q, s4_cy_q;
  logic   [1:0][8:0]  s4_em1_q;                 // first-beat offset + bytes - 1
  logic   [1:0][12:0] s4_pe_q;                  // address [11:0] + bytes - 1
  // S0..S4 never stall: a row enters S0 only with a place reserved for it in the S5 queue
  // (a credit), so the stage registers load every clock, without an enable. (A ready chain
  // back through the stages was an enable on some 600 flip-flops, and its fan-out net alone
  // was a long path after placement.) S5 is a short FIFO; AWREADY's way back ends at its pop.
  row_t               s5_d;
  cs_t    [1:0]       s2_cs_d;
  logic   [1:0][11:0] s3_lo_d;
  logic   [1:0][9:0]  s4_mid_d;
  logic   [1:0]       s3_cy_d, s4_cy_d;
  logic   [1:0][8:0]  s4_em1_d;
  logic   [1:0][12:0] s4_pe_d;
  logic   [1:0][31:0] s5_a_d;
  shape_t [1:0]       s5_shape_d;
  logic   [1:0][MA_W-1:0] s5_mb1_d;
  // Beats before the 4 KiB boundary - 1; when a plane is split it is < 32, so on narrow buses
  // its upper bits are not needed.
  /* verilator lint_off UNUSEDSIGNAL */
  logic   [1:0][B4K_W-1:0] to4k_m1;
  /* verilator lint_on UNUSEDSIGNAL */

  // Rows between the arbiter and the end of the S5 queue, at most S5_D: a row is taken only
  // while that count is below S5_D (a compare of a register), so the queue always has room.
  localparam int unsigned S5_D = 8;   // >= the 7 stages S0..S4 + 1 for a row per clock
  logic [$clog2(S5_D):0] s5_credit_q;
  logic                  s5_take;
  assign arb_ready = (s5_credit_q != ($clog2(S5_D) + 1)'(S5_D));
  assign s5_take   = row_valid_o && row_ready_i;

  `MSR_CLR_REG(u_s5_credit, $clog2(S5_D) + 1, clear_i, 1'b1,
               s5_credit_q + ($clog2(S5_D) + 1)'(arb_take) - ($clog2(S5_D) + 1)'(s5_take),
               s5_credit_q)

  // The stages' valid bits, one shift register.
  `MSR_CLR_REG(u_stage_v, 7, clear_i, 1'b1,
               {s3_v_q, s2_v_q, s15_v_q, s1m_v_q, s1_v_q, s0_v_q, arb_take},
               {s4_v_q, s3_v_q, s2_v_q, s15_v_q, s1m_v_q, s1_v_q, s0_v_q})

  assign meta_in_o  = s0_in_q;
  assign meta_buf_o = s0_buf_q;

  // No enables: each stage's valid bit says whether its registers hold a row.
  always_ff @(posedge clk_i) begin
    s0_in_q   <= arb_idx;
    s0_buf_q  <= pick_i[arb_idx];
    s1_in_q   <= s0_in_q;
    s1_buf_q  <= s0_buf_q;
    s1_y_q    <= meta_i.y;
    s1_x0_q   <= meta_i.x0;
    s1_l_q    <= meta_i.l;
    s1m_in_q  <= s1_in_q;
    s1m_buf_q <= s1_buf_q;
    s1m_l_q   <= s1_l_q;
    s1m_x0_q  <= s1_x0_q;
    s1m_m_q   <= s1m_m_d;
    s15_in_q  <= s1m_in_q;
    s15_buf_q <= s1m_buf_q;
    s15_l_q   <= s1m_l_q;
    s15_cs_q  <= s15_cs_d;
    s2_in_q   <= s15_in_q;
    s2_buf_q  <= s15_buf_q;
    s2_l_q    <= s15_l_q;
    s2_cs_q   <= s2_cs_d;
    s3_in_q   <= s2_in_q;
    s3_buf_q  <= s2_buf_q;
    s3_l_q    <= s2_l_q;
    s3_cs_q   <= s2_cs_q;
    s3_lo_q   <= s3_lo_d;
    s3_cy_q   <= s3_cy_d;
    s4_in_q   <= s3_in_q;
    s4_buf_q  <= s3_buf_q;
    s4_cs_q   <= s3_cs_q;
    s4_lo_q   <= s3_lo_q;
    s4_mid_q  <= s4_mid_d;
    s4_cy_q   <= s4_cy_d;
    s4_em1_q  <= s4_em1_d;
    s4_pe_q   <= s4_pe_d;
  end

  // The stages' arithmetic, per plane.
  always_comb begin
    for (int unsigned p = 0; p < 2; p++) begin
      logic [31:0] st, base, xt;
      cs_t         c1, c2, c3;
      logic [12:0] lo_sum;
      logic [10:0] mid_sum;
      logic [9:0]  hi_sum;
      logic [7:0]  nbm1;    // bytes of the plane - 1
      logic [MA_W-1:0] mb;
      // S2: six addends to a carry-save pair
      st   = (p != 0) ? fb_i.src_stride : fb_i.fb_stride;
      // S1m: the stride multiples, registered: each y bit selects in 64 multiplexers, and
      // that fan-out alone was most of the glue's worst placed path when the
      // carry-save level sat behind it in the same clock.
      // Radix-8 digit k of y selects its multiple, shifted to its weight 8^k.
      for (int unsigned k = 0; k < 4; k++) begin
        s1m_m_d[p][k] = mult8(s1_y_q[3*k +: 3], st, mul_q[3*p], mul_q[3*p+1], mul_q[3*p+2])
                        << (3 * k);
      end
      base = (p != 0) ? fb_i.src_base : fb_i.fb_base;
      xt   = (p != 0) ? {20'b0, s1m_x0_q} : {18'b0, s1m_x0_q, 2'b0};
      s15_cs_d[p][0] = csa(s1m_m_q[p][0], s1m_m_q[p][1], s1m_m_q[p][2]);
      s15_cs_d[p][1] = csa(s1m_m_q[p][3], base, xt);
      c1   = s15_cs_q[p][0];
      c2   = s15_cs_q[p][1];
      c3   = csa(c1.s, c1.c, c2.s);
      s2_cs_d[p] = csa(c3.s, c3.c, c2.c);
      // S3: bits [11:0]
      lo_sum     = {1'b0, s2_cs_q[p].s[11:0]} + {1'b0, s2_cs_q[p].c[11:0]};
      s3_lo_d[p] = lo_sum[11:0];
      s3_cy_d[p] = lo_sum[12];
      // S4: bits [21:12]; the plane's end from the low bits
      mid_sum     = {1'b0, s3_cs_q[p].s[21:12]} + {1'b0, s3_cs_q[p].c[21:12]} + 11'(s3_cy_q[p]);
      nbm1        = (p != 0) ? 8'(s3_l_q) : {1'b0, s3_l_q, 2'b11};
      s4_mid_d[p] = mid_sum[9:0];
      s4_cy_d[p]  = mid_sum[10];
      s4_em1_d[p] = 9'(s3_lo_q[p][BB_W-1:0]) + 9'(nbm1);
      s4_pe_d[p]  = {1'b0, s3_lo_q[p]} + 13'(nbm1);
      // S5: bits [31:22]; the burst shape
      hi_sum     = s4_cs_q[p].s[31:22] + s4_cs_q[p].c[31:22] + 10'(s4_cy_q[p]);
      to4k_m1[p] = ~s4_lo_q[p][11:BB_W];
      mb         = maddr_t'(buf_base(s4_buf_q, (p != 0) ? SB : PB));
      s5_a_d[p]          = {hi_sum, s4_mid_q[p], s4_lo_q[p]};
      s5_shape_d[p].two  = s4_pe_q[p][12];
      s5_shape_d[p].len0 = s4_pe_q[p][12] ? 8'(to4k_m1[p]) : 8'(s4_em1_q[p] >> BB_W);
      s5_shape_d[p].len1 = 8'(s4_pe_q[p][11:0] >> BB_W);
      s5_shape_d[p].lo   = s4_lo_q[p][BB_W-1:0];
      s5_shape_d[p].hi   = s4_em1_q[p][BB_W-1:0];
      s5_mb1_d[p]        = mb + maddr_t'(to4k_m1[p]) + 1'b1;
    end
  end

  assign s5_d = '{in: s4_in_q, bufi: s4_buf_q, a: s5_a_d, shape: s5_shape_d, mb1: s5_mb1_d};

  logic                  s5_room;   // always 1 (credits): checked below
  logic [$clog2(S5_D):0] s5_count;
  msr_fifo #(.WIDTH($bits(row_t)), .DEPTH(S5_D)) u_s5_queue (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .flush_i (clear_i),
    .valid_i (s4_v_q),
    .ready_o (s5_room),
    .data_i  (s5_d),
    .valid_o (row_valid_o),
    .ready_i (s5_take),
    .data_o  (row_o),
    .count_o (s5_count)
  );

  assign idle_o = !s0_v_q && !s1_v_q && !s1m_v_q && !s15_v_q && !s2_v_q && !s3_v_q && !s4_v_q &&
                  !row_valid_o;

  logic unused;
  assign unused = ^{s5_count, fb_i.src_en};   // both planes are addressed; the AW side drops one

  /* verilator lint_off SYNCASYNCNET */
  `MSR_ASSERT_IMP(a_s5_room, s4_v_q, s5_room)
  `MSR_ASSERT(a_s5_credit, s5_credit_q <= ($clog2(S5_D) + 1)'(S5_D))
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_fbw_addr
