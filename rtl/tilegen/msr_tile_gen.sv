// Tile generation unit (spec section 1, claims 1, 3 and 12): walks the tiles of a frame
// row-major from the top-left, computes each tile's extent and foveated per-level
// thresholds, and hands the descriptor to the lowest-numbered engine that can take it.
//
// Timing: a five-stage pipeline with one enable (it moves when the output register is empty;
// the engines' ready only empties it, so it never reaches the stages' enables), no carry
// longer than 13 bits per clock: S1 the tile origin, its extent left in the frame and its
// distances r2x, r2y from the gaze in half-tiles; S2 both foveation
// products gain * r2x and gain * r2y as carry-save pairs (ten partial products in five 3:2
// levels; gain * max(r2x, r2y) = the larger product, so the compare runs beside them) and the
// clamped extent; S3 / S4 the chosen product's carry-propagate add in two 9-bit halves, then
// (gain * r2) >> 4 saturated at 255; S5 the descriptor register with the thresholds
// thr + that, saturated at 255. The walker fills the pipeline while a descriptor waits, so
// an engine that asks is served at once, the next one two clocks later; the engines take a
// tile per 64 or more clocks.
//
// Gaze (algorithm.md section 1): r2x = |2 tx + 1 - cx|, r2y = |2 ty + 1 - cy|, (cx, cy) the gaze
// in half tiles, latched at start: the controller's (from GAZE) with gaze_en_i, else (ntx, nty),
// the default gaze (ntx T / 2, nty T / 2), which gives the frame centre's |2t - (n - 1)|. The
// subtract and absolute value are today's half_dist with the latched centre for the count.
//
// Ray budget (BUDGET_EN, docs/budget.md): a budget frame's walker takes the tile rows
// interleaved (rows 0, S, 2S, .., then 1, 1 + S, ..; msr_budget_pkg::next_row), so the rows the
// controller has seen are spread over the frame; it starts a row only when the controller knows
// its scale (row_ok_i for row_idx_o, the row's position in that order), every tile carries its
// row's threshold multiplier m down the pipeline, and S6 / S7 scale the thresholds,
// thr'' = min(255, (thr' * m + d) >> 8), d the tile's dither (bit-reversed (tx + ty) mod 256,
// whose mean is the rounding's 128: a row's mean threshold then moves smoothly with m instead
// of in integer steps): S6 the products (multiplier blocks on an FPGA), registered straight out
// of them, and d, S7 the add and the saturation (in one clock, the block and its wires in and
// out made the top's worst path). With bud_en_i low the frame is walked row-major and
// m = 256 (every thr'' = thr' whatever d), so its descriptors are those of a top without it; a
// top built without it (BUDGET_EN = 0) has neither stage nor the wait nor the order.
`include "msr_assert.svh"
`include "msr_flops.svh"

module msr_tile_gen import msr_pkg::*; import msr_budget_pkg::row_stride_log2; #(
  parameter int unsigned NUM_ENGINES = 4,
  parameter bit          BUDGET_EN   = 1'b0,                 // the ray-budget stage and row wait
  localparam int unsigned TROW_W     = COORD_W - 2          // tile row index (as the walker's)
) (
  input  logic                   clk_i,         // clock
  input  logic                   rst_ni,        // asynchronous reset, active low
  input  logic                   clear_i,       // synchronous clear: forget the frame
  input  logic                   start_i,       // pulse: begin a frame with the cfg below
  // Frame configuration, checked by the caller and stable from start_i to done_o.
  input  dim_t                   width_i,       // W, 1..4096
  input  dim_t                   height_i,      // H, 1..4096
  input  tile_size_e             tile_i,        // T
  input  level_t                 levels_i,      // L, 1..3
  input  metric_e                metric_i,      // colour difference metric
  input  rule_e                  rule_i,        // decision rule
  input  thr_t [MAX_LEVELS-1:0]  thr_i,         // base thresholds, thr_i[k-1] for level k
  input  logic [7:0]             fov_gain_i,    // foveation gain, 0 = uniform
  input  logic                   gaze_en_i,     // foveate around (cx, cy), else the centre
  input  logic [COORD_W-2:0]     gaze_cx_i,     // the gaze in half tiles, (2X + T/2) div T
  input  logic [COORD_W-2:0]     gaze_cy_i,     // (2Y + T/2) div T
  // Ray budget (BUDGET_EN): the controller's scale of the row the walker is in.
  input  logic                   bud_en_i,      // this frame holds a budget
  output logic [TROW_W-1:0]      row_idx_o,     // the walker's row: its position in the order
  input  logic                   row_ok_i,      // its scale is known (this clock)
  input  logic [12:0]            row_m_i,       // its threshold multiplier m (1.0 = 256)
  // The frame's tile grid and row order (registers; from the second clock after start_i):
  // the budget's row counters follow the same order (msr_budget_rows).
  output logic [TROW_W:0]        ntx_o,         // tiles per row
  output logic [TROW_W:0]        nty_o,         // tile rows
  output logic [TROW_W-1:0]      smask_o,       // the order's stride S, less one
  output logic [TROW_W:0]        nty_s_o,       // nty - S
  // Descriptor to the engines: valid goes to exactly one engine that is ready.
  output logic [NUM_ENGINES-1:0] desc_valid_o,  // offer to engine i
  input  logic [NUM_ENGINES-1:0] desc_ready_i,  // engine i can take a tile
  output tile_desc_t             desc_o,        // the tile (shared by all engines)
  output logic                   busy_o,        // tiles left to hand out
  output logic                   done_o         // every tile of the frame handed out
);
  if (NUM_ENGINES < 1 || NUM_ENGINES > 16) begin : g_check_engines
    $fatal(1, "msr_tile_gen: NUM_ENGINES must be 1..16, got %0d", NUM_ENGINES);
  end

  localparam int unsigned TIDX_W = COORD_W - 2;     // tile index, up to 4096/8 = 512 tiles
  localparam int unsigned NST    = BUDGET_EN ? 7 : 5;   // pipeline stages
  localparam int unsigned R2_W   = TIDX_W + 1;      // |2t + 1 - c| <= 1024
  localparam int unsigned PROD_W = R2_W + 8;        // gain * r2 < 2^18

  // ---- Frame set-up (latched at start) ----------------------------------------------------
  logic [2:0]        lg_q, lg_d;                    // log2 T
  logic [TIDX_W:0]   ntx_q, nty_q;                  // tile counts, 1..512
  logic [TIDX_W:0]   cx_q, cy_q;                    // the gaze in half tiles, 0..1024
  // Control state: the walker (row-major over the tile grid) and the stages' flags.
  typedef struct packed {
    logic              run;                         // the walker has tiles left
    logic              done;                        // every tile handed out
    logic [TIDX_W-1:0] tx, ty;                      // the walker's next tile
    logic [NST-1:0]    v, last;                     // stage k valid / holds the frame's last tile
  } ctl_t;
  ctl_t              ctl_q, ctl_d;

  always_comb begin
    unique case (tile_i)
      TILE_8:  lg_d = 3'd3;
      TILE_16: lg_d = 3'd4;
      TILE_32: lg_d = 3'd5;
      default: lg_d = 3'd4;
    endcase
  end

  // ceil(n / T) for n = 1..4096: at most 512 tiles per axis; (n >> lg) + (any bit below lg),
  // a 10-bit increment instead of a 14-bit add.
  function automatic logic [TIDX_W:0] tile_count(dim_t n, logic [2:0] lg);
    logic [TIDX_W:0] q;
    logic            rem;
    q   = (TIDX_W+1)'(n >> lg);
    rem = (n & ((dim_t'(1) << lg) - 1'b1)) != '0;
    return q + (TIDX_W+1)'(rem);
  endfunction

  // r2 = |2t + 1 - c|: distance of tile t from the gaze c in half-tiles (c = n: the centre).
  function automatic logic [R2_W-1:0] half_dist(logic [TIDX_W-1:0] t, logic [TIDX_W:0] c);
    logic signed [R2_W+1:0] v;
    v = $signed({2'b0, t, 1'b1}) - $signed({2'b0, c});
    return (v < 0) ? R2_W'(-v) : R2_W'(v);
  endfunction

  // ---- Pipeline -----------------------------------------------------------------------------
  typedef struct packed {
    logic [PROD_W-1:0] s;
    logic [PROD_W-1:0] c;
  } cs_t;

  // Carry-save 3:2 compression.
  function automatic cs_t csa(logic [PROD_W-1:0] a, logic [PROD_W-1:0] b, logic [PROD_W-1:0] c);
    cs_t r;
    r.s = a ^ b ^ c;
    r.c = ((a & b) | (a & c) | (b & c)) << 1;
    return r;
  endfunction

  // gain * r as a carry-save pair: eleven partial products in an 11-8-6-4-3-2 tree.
  function automatic cs_t mul_cs(logic [7:0] g, logic [R2_W-1:0] r);
    logic [R2_W-1:0][PROD_W-1:0] pp;
    cs_t a, b, c, d, e, f, h, k;
    for (int unsigned j = 0; j < R2_W; j++) pp[j] = r[j] ? (PROD_W'(g) << j) : '0;
    a = csa(pp[0], pp[1], pp[2]);
    b = csa(pp[3], pp[4], pp[5]);
    c = csa(pp[6], pp[7], pp[8]);
    d = csa(a.s, a.c, b.s);
    e = csa(b.c, c.s, c.c);
    f = csa(d.s, d.c, e.s);
    h = csa(e.c, pp[9], pp[10]);
    k = csa(f.s, f.c, h.s);
    return csa(k.s, k.c, h.c);
  endfunction

  localparam int unsigned LO_W = PROD_W / 2;         // 9
  localparam int unsigned HI_W = PROD_W - LO_W;      // 9

  logic              en;                            // every stage moves
  logic              taken;                         // the output descriptor goes this clock
  coord_t [3:0]      x0_q, y0_q;                    // origin through S1..S4
  dim_t              s1_rw_q, s1_rh_q;              // frame extent right of / below the origin
  logic [R2_W-1:0]   s1_r2x_q, s1_r2y_q;
  cs_t               s2_px_q, s2_py_q;              // gain * r2x, gain * r2y (carry-save)
  logic              s2_xgt_q;                      // r2x > r2y
  ldim_t [2:0]       w_q, h_q;                      // extent through S2..S4
  cs_t               s3_p_q;                        // the larger product
  logic [LO_W-1:4]   s3_lo_q;                      // product bits [8:4] ([3:0] are shifted out)
  logic              s3_cy_q;
  thr_t              s4_fov_q;                      // min(255, (gain * r2) >> 4)
  tile_desc_t        desc_q, desc_d;
  logic              walk_last;
  cs_t               s3_p_next;                     // the larger product, from S2
  // Low half of the product; its bits [3:0] are shifted out of (gain * r2) >> 4.
  /* verilator lint_off UNUSEDSIGNAL */
  logic [LO_W:0]     lo_sum;
  /* verilator lint_on UNUSEDSIGNAL */
  logic [HI_W-1:0]   prod_hi;
  thr_t              fov_d;

  logic              walk_go;                       // the walker hands a tile into S1
  // The stages move only while the output register is empty: `taken` (the engines' ready,
  // from across the die) clears that register's flag alone and never reaches the stages'
  // enables. A tile leaves at most every second clock, far above what four engines take.
  assign en        = !ctl_q.v[NST-1];
  logic              order_set;                     // the order's stride is set (below)
  assign walk_go   = ctl_q.run && (!BUDGET_EN || !bud_en_i || (row_ok_i && order_set));

  // The row order: S = smask_q + 1, rows r, r + S, .. of phase r mod S, then the next phase. A
  // frame without a budget (or a top without the budget) has S = 1: row-major. The last
  // row in that order is the last of phase S - 1.
  logic [TIDX_W-1:0] smask_q;                       // S - 1
  logic [TIDX_W:0]   nty_s_q;                       // nty - S: ty < nty_s_q is ty + S < nty
  logic [TIDX_W-1:0] pos_q;                         // the walker's row position in the order
  logic [TIDX_W-1:0] ty_next;
  logic              row_end;                       // the walker's tile is its row's last
  assign row_end   = {1'b0, ctl_q.tx} + 1'b1 == ntx_q;
  // (a top without the budget keeps the row-major walker's own logic, gate for gate)
  assign ty_next   = !BUDGET_EN                      ? ctl_q.ty + 1'b1 :
                     ({1'b0, ctl_q.ty} < nty_s_q)    ? ctl_q.ty + (smask_q + 1'b1)
                                                     : (ctl_q.ty & smask_q) + 1'b1;
  assign walk_last = row_end && (!BUDGET_EN ? {1'b0, ctl_q.ty} + 1'b1 == nty_q
                                            : (ctl_q.ty & smask_q) == smask_q &&
                                              !({1'b0, ctl_q.ty} < nty_s_q));
  assign row_idx_o = BUDGET_EN ? pos_q : ctl_q.ty;
  assign ntx_o     = ntx_q;
  assign nty_o     = nty_q;
  assign smask_o   = smask_q;
  assign nty_s_o   = nty_s_q;

  // The frame's tile grid and gaze, latched at START (a clear leaves them: only a START reads
  // them). The default gaze is the tile count itself: no second count for it.
  logic [TIDX_W:0] ntx_d, nty_d;
  assign ntx_d = tile_count(width_i, lg_d);
  assign nty_d = tile_count(height_i, lg_d);
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      lg_q  <= 3'd4;
      ntx_q <= '0;
      nty_q <= '0;
      cx_q  <= '0;
      cy_q  <= '0;
    end else if (start_i && !clear_i) begin
      lg_q  <= lg_d;
      ntx_q <= ntx_d;
      nty_q <= nty_d;
      cx_q  <= gaze_en_i ? gaze_cx_i : ntx_d;
      cy_q  <= gaze_en_i ? gaze_cy_i : nty_d;
    end
  end

  // The order's stride, the clock after the start (from nty_q): row-major until then, and a
  // budget frame's walker waits for it (in the top it waits far longer, for the first scale).
  if (BUDGET_EN) begin : g_order
    logic       set_q;
    logic [2:0] lgs_d;                              // log2 S
    assign lgs_d = (set_q && bud_en_i) ? row_stride_log2(TIDX_W'(nty_q)) : 3'd0;
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        set_q   <= 1'b0;
        smask_q <= '0;
        nty_s_q <= '0;
        pos_q   <= '0;
      end else begin
        set_q <= start_i && !clear_i;
        if ((start_i && !clear_i) || set_q) begin
          smask_q <= TIDX_W'((TIDX_W+1)'(1) << lgs_d) - 1'b1;
          nty_s_q <= (start_i ? tile_count(height_i, lg_d) : nty_q) - ((TIDX_W+1)'(1) << lgs_d);
        end
        if (start_i) pos_q <= '0;
        else if (en && walk_go && row_end) pos_q <= pos_q + 1'b1;
      end
    end
    assign order_set = !set_q;
  end else begin : g_raster
    assign order_set = 1'b1;
    assign smask_q = '0;
    assign nty_s_q = nty_q - 1'b1;
    assign pos_q   = '0;
  end

  always_comb begin
    ctl_d = ctl_q;
    if (start_i) begin
      ctl_d.run  = 1'b1;
      ctl_d.done = 1'b0;
      ctl_d.tx   = '0;
      ctl_d.ty   = '0;
    end else begin
      if (taken && ctl_q.last[NST-1]) ctl_d.done = 1'b1;
      if (taken) begin
        ctl_d.v[NST-1]    = 1'b0;
        ctl_d.last[NST-1] = 1'b0;
      end
      if (en) begin
        ctl_d.v    = {ctl_q.v[NST-2:0], walk_go};
        ctl_d.last = {ctl_q.last[NST-2:0], walk_go && walk_last};
        if (walk_go) begin
          if (walk_last) ctl_d.run = 1'b0;
          if (row_end) begin
            ctl_d.tx = '0;
            ctl_d.ty = ty_next;
          end else begin
            ctl_d.tx = ctl_q.tx + 1'b1;
          end
        end
      end
    end
  end

  `MSR_CLR_REG(u_ctl, $bits(ctl_t), clear_i, 1'b1, ctl_d, ctl_q)

  // Data registers: read only under their valid flags.
  always_ff @(posedge clk_i) begin
    if (en) begin
      // S1
      x0_q[0]  <= coord_t'(ctl_q.tx) << lg_q;
      y0_q[0]  <= coord_t'(ctl_q.ty) << lg_q;
      s1_rw_q  <= width_i - (dim_t'(ctl_q.tx) << lg_q);
      s1_rh_q  <= height_i - (dim_t'(ctl_q.ty) << lg_q);
      s1_r2x_q <= half_dist(ctl_q.tx, cx_q);
      s1_r2y_q <= half_dist(ctl_q.ty, cy_q);
      // S2
      x0_q[1]  <= x0_q[0];
      y0_q[1]  <= y0_q[0];
      s2_px_q  <= mul_cs(fov_gain_i, s1_r2x_q);
      s2_py_q  <= mul_cs(fov_gain_i, s1_r2y_q);
      s2_xgt_q <= s1_r2x_q > s1_r2y_q;
      w_q[0]   <= (s1_rw_q > (dim_t'(1) << lg_q)) ? ldim_t'(1) << lg_q : ldim_t'(s1_rw_q);
      h_q[0]   <= (s1_rh_q > (dim_t'(1) << lg_q)) ? ldim_t'(1) << lg_q : ldim_t'(s1_rh_q);
      // S3
      x0_q[2]  <= x0_q[1];
      y0_q[2]  <= y0_q[1];
      w_q[1]   <= w_q[0];
      h_q[1]   <= h_q[0];
      s3_p_q   <= s2_xgt_q ? s2_px_q : s2_py_q;
      {s3_cy_q, s3_lo_q} <= lo_sum[LO_W:4];
      // S4
      x0_q[3]  <= x0_q[2];
      y0_q[3]  <= y0_q[2];
      w_q[2]   <= w_q[1];
      h_q[2]   <= h_q[1];
      s4_fov_q <= fov_d;
      // S5: the descriptor
      desc_q   <= desc_d;
    end
  end

  always_comb begin
    s3_p_next = s2_xgt_q ? s2_px_q : s2_py_q;
    lo_sum    = (LO_W+1)'(s3_p_next.s[LO_W-1:0]) + (LO_W+1)'(s3_p_next.c[LO_W-1:0]);
    prod_hi   = s3_p_q.s[PROD_W-1:LO_W] + s3_p_q.c[PROD_W-1:LO_W] + HI_W'(s3_cy_q);
    // (gain * r2) >> 4 = {prod_hi, s3_lo_q} >> 4, saturated at 255 (bits 12 and up)
    fov_d     = (prod_hi[HI_W-1:12-LO_W] != '0) ? thr_t'(255)
                                                 : {prod_hi[12-LO_W-1:0], s3_lo_q[LO_W-1:4]};
  end

  always_comb begin
    desc_d        = '0;
    desc_d.x0     = x0_q[3];
    desc_d.y0     = y0_q[3];
    desc_d.w      = w_q[2];
    desc_d.h      = h_q[2];
    desc_d.levels = levels_i;
    desc_d.metric = metric_i;
    desc_d.rule   = rule_i;
    for (int k = 0; k < MAX_LEVELS; k++) begin
      logic [THR_W:0] t;
      t = (THR_W+1)'(thr_i[k]) + (THR_W+1)'(s4_fov_q);
      desc_d.thr[k] = t[THR_W] ? thr_t'(255) : thr_t'(t);
    end
  end

  // ---- S6, S7 (BUDGET_EN): the row's threshold multiplier -----------------------------------
  if (BUDGET_EN) begin : g_budget
    localparam int unsigned P_W = THR_W + 13;       // thr' * m
    logic [4:0][12:0]                m_q;           // m of the tile in S1..S5
    logic [4:0][7:0]                 dith_q;        // its dither d in S1..S5
    logic [MAX_LEVELS-1:0][P_W-1:0] prod6_q;       // S6: thr' * m per level
    logic [7:0]                      dith6_q;       // S6: the tile's dither d
    tile_desc_t                      desc6_q, desc7_q, desc7_d;
    // d = bit-reversed (tx + ty) mod 256: neighbouring tiles far apart in [0, 255]. Formed from
    // the walker's tile indices as the tile enters S1 and carried with it, not from the
    // descriptor's origin (x0 >> lg, y0 >> lg: two shifts by the tile size in front of the add).
    logic [7:0] txy, txy_rev;
    assign txy     = 8'(ctl_q.tx) + 8'(ctl_q.ty);
    assign txy_rev = {<<{txy}};
    always_comb begin
      desc7_d = desc6_q;
      for (int k = 0; k < MAX_LEVELS; k++) begin
        logic [P_W-1:0] p;
        p = prod6_q[k] + P_W'(dith6_q);
        desc7_d.thr[k] = (p[P_W-1:THR_W+8] != '0) ? thr_t'(255) : thr_t'(p[THR_W+8-1:8]);
      end
    end
    always_ff @(posedge clk_i) begin
      if (en) begin
        m_q     <= {m_q[3:0], bud_en_i ? row_m_i : 13'd256};
        dith_q  <= {dith_q[3:0], txy_rev};
        desc6_q <= desc_q;
        dith6_q <= dith_q[4];
        for (int k = 0; k < MAX_LEVELS; k++) prod6_q[k] <= P_W'(desc_q.thr[k]) * P_W'(m_q[4]);
        desc7_q <= desc7_d;
      end
    end
    assign desc_o = desc7_q;
  end else begin : g_no_budget
    logic unused_budget;
    assign unused_budget = ^{bud_en_i, row_ok_i, row_m_i, pos_q};
    assign desc_o        = desc_q;
  end

  // ---- Dispatch: the lowest-numbered ready engine takes the offered tile --------------------
  logic [NUM_ENGINES-1:0] pick;
  assign pick         = desc_ready_i & (~desc_ready_i + 1'b1);
  assign desc_valid_o = ctl_q.v[NST-1] ? pick : '0;
  assign taken        = |desc_valid_o;
  assign busy_o       = ctl_q.run || (ctl_q.v != '0);
  assign done_o       = ctl_q.done;

  /* verilator lint_off SYNCASYNCNET */
  // At most one engine is offered a tile, and only one that is ready.
  `MSR_ASSERT(a_desc_onehot, $onehot0(desc_valid_o))
  `MSR_ASSERT(a_desc_ready, (desc_valid_o & ~desc_ready_i) == '0)
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_tile_gen
