// Tile generation unit (spec section 1, claims 1, 3 and 12): walks the tiles of a frame
// row by row from the top-left, computes each tile's extent and foveated per-level thresholds,
// and hands the descriptor to the lowest-numbered engine that can take it.
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
// A unit between the generator and the engines (the ray budget's msr_budget_stage) may take
// the walk's row order (EXT_ORDER: row_next_i, row_last_i; else row-major), pace it by rows
// (row_go_i; tie it high for a free walk) and add TAIL_STAGES stages after the descriptor
// register: they move with this pipeline (adv_o), take its descriptor (pipe_desc_o) and hand
// back the one dispatched (tail_desc_i); the valid flags of every stage stay here.
`include "msr_assert.svh"
`include "msr_flops.svh"

module msr_tile_gen import msr_pkg::*; #(
  parameter int unsigned NUM_ENGINES = 4,
  parameter bit          EXT_ORDER   = 1'b0,      // the row order from row_next_i, row_last_i
  parameter int unsigned TAIL_STAGES = 0,         // stages after the descriptor register
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
  // The frame's tile grid (registers; from the clock after start_i).
  output logic [TROW_W:0]        ntx_o,         // tiles per row
  output logic [TROW_W:0]        nty_o,         // tile rows
  // The walker: its next tile, its rows' order and pace.
  output logic [TROW_W-1:0]      tx_o,          // the walker's next tile
  output logic [TROW_W-1:0]      ty_o,
  output logic                   row_step_o,    // it hands out its row's last tile this clock
  input  logic [TROW_W-1:0]      row_next_i,    // EXT_ORDER: the row after ty_o
  input  logic                   row_last_i,    // EXT_ORDER: ty_o is the frame's last row
  input  logic                   row_go_i,      // it may hand out a tile of ty_o this clock
  // The tail (TAIL_STAGES): it moves with the pipeline.
  output logic                   adv_o,         // every stage moves this clock
  output tile_desc_t             pipe_desc_o,   // the descriptor register (S5)
  input  tile_desc_t             tail_desc_i,   // the tail's last stage
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
  localparam int unsigned NST    = TILE_GEN_DEPTH + TAIL_STAGES;   // pipeline stages
  localparam int unsigned R2_W   = TIDX_W + 1;      // |2t + 1 - c| <= 1024
  localparam int unsigned PROD_W = R2_W + 8;        // gain * r2 < 2^18

  // ---- Frame set-up (latched at start) ----------------------------------------------------
  logic [2:0]        lg_q, lg_d;                    // log2 T
  logic [TIDX_W:0]   ntx_q, nty_q;                  // tile counts, 1..512
  logic [TIDX_W:0]   cx_q, cy_q;                    // the gaze in half tiles, 0..1024
  // Control state: the walker (row by row over the tile grid) and the stages' flags.
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
  assign walk_go   = ctl_q.run && row_go_i;

  // The row order: row-major, or the instantiating unit's (EXT_ORDER).
  logic [TIDX_W-1:0] ty_next;
  logic              row_end;                       // the walker's tile is its row's last
  assign row_end   = {1'b0, ctl_q.tx} + 1'b1 == ntx_q;
  assign ty_next   = EXT_ORDER ? row_next_i : ctl_q.ty + 1'b1;
  assign walk_last = row_end && (EXT_ORDER ? row_last_i : {1'b0, ctl_q.ty} + 1'b1 == nty_q);
  assign ntx_o      = ntx_q;
  assign nty_o      = nty_q;
  assign tx_o       = ctl_q.tx;
  assign ty_o       = ctl_q.ty;
  assign row_step_o = en && walk_go && row_end;
  assign adv_o      = en;

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

  // ---- The tail (TAIL_STAGES): its last stage is dispatched ---------------------------------
  assign pipe_desc_o = desc_q;
  if (TAIL_STAGES != 0) begin : g_tail
    assign desc_o = tail_desc_i;
  end else begin : g_no_tail
    logic unused_tail;
    assign unused_tail = ^tail_desc_i;
    assign desc_o      = desc_q;
  end
  if (!EXT_ORDER) begin : g_raster
    logic unused_order;
    assign unused_order = ^{row_next_i, row_last_i};
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
