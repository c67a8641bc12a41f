// Tile engine: tiles in, their final pixels out (spec ../shared/spec/algorithm.md).
//
//   desc --> a free context c: msr_level_ctrl[c], pixel scoreboard[c], tile buffer[c]
//   issue arbiter (round robin) --> S1 (tile buffer read data, A / B)
//            --> msr_decide / msr_interp (shared, one decision per clock) --+
//   interpolate -> tile buffer[c] write; trace -> render request {x, y, tag} |
//   rsp {tag, rgb} -> tile buffer[tag's c] write (in the same clock as an    |
//                     interpolated write when the two go to other contexts) <+
//   finished contexts, round robin --> msr_tile_stream --> pix stream (row-major, whole tiles)
//
// Why contexts: the decisions of one pass are independent, but a pass needs the pixels of
// the passes before it, so a tile is a chain of 5-7 dependent passes, each waiting up to one
// render latency for its traced neighbours. One tile keeps the decision pipeline busy only
// when renders answer at once. NUM_CTX tiles are worked on at the same time, each with its
// own level controller, scoreboard and tile buffer; every clock the arbiter issues, round
// robin, the next position of a context whose two neighbours are final, so one tile's waits
// are filled with other tiles' decisions. The per-context pixel scoreboard replaces the pass
// barrier: a position goes as soon as its two neighbours are final (the values a barrier
// would give: a pass reads only pixels of earlier passes, each written once). Positions of
// one context leave in order, so each tile's render requests keep the golden model's order;
// requests of different tiles interleave. Finished tiles are streamed out whole, one after
// another, in the order they finish (roughly): a tile that waits long for its renders does
// not hold up the tiles behind it (with in-order output it did, and the engine ran dry).
//
// inflight_o counts tags handed out and not yet answered (a request waiting for
// req_ready_i counts as in flight).
module msr_tile_engine
  import msr_pkg::*;
#(
  // Tile contexts. 8 keeps one engine near one pixel per clock with a render latency of 256
  // cycles and 64 tags (docs/architecture.md); 2 suffice when renders answer within ~16.
  parameter int unsigned NUM_CTX         = 8,
  parameter int unsigned MAX_OUTSTANDING = 16,  // render requests in flight (power of two, 2..64)
  parameter int unsigned TAG_W = $clog2(MAX_OUTSTANDING)
) (
  // The port list is the interface agreed with the system top, comments included.
  // verilog_lint: waive-start line-length
  input  logic             clk_i,
  input  logic             rst_ni,
  input  logic             clear_i,        // synchronous soft reset; only asserted when no render request is in flight
  input  logic             desc_valid_i,   // tile descriptor
  output logic             desc_ready_o,
  input  tile_desc_t       desc_i,
  output logic             req_valid_o,    // render request, global frame coordinates
  input  logic             req_ready_i,
  output coord_t           req_x_o,
  output coord_t           req_y_o,
  output logic [TAG_W-1:0] req_tag_o,
  input  logic             rsp_valid_i,    // render response, any order
  output logic             rsp_ready_o,
  input  logic [TAG_W-1:0] rsp_tag_i,
  input  rgb_t             rsp_rgb_i,
  output logic             pix_valid_o,    // finished pixels of the tile, row-major, global coords
  input  logic             pix_ready_i,
  output coord_t           pix_x_o,
  output coord_t           pix_y_o,
  output rgb_t             pix_rgb_o,
  output src_t             pix_src_o,
  output logic             pix_last_o,     // last pixel of the tile
  output logic             busy_o,         // tile accepted and not yet fully emitted
  output logic [$clog2(MAX_OUTSTANDING):0] inflight_o  // render requests in flight (for the top's soft reset / perf)
  // verilog_lint: waive-stop line-length
);

  localparam int unsigned CNT_W  = $clog2(MAX_OUTSTANDING) + 1;
  localparam int unsigned WORD_W = $bits(src_t) + $bits(rgb_t);
  localparam int unsigned DEPTH  = MAX_TILE * MAX_TILE;
  localparam int unsigned CTX_W  = (NUM_CTX > 1) ? $clog2(NUM_CTX) : 1;
  // Positions of one context issued and not yet written: at most the pipeline plus its tags.
  localparam int unsigned PEND_W = $clog2(MAX_OUTSTANDING + 8) + 1;

  typedef logic [CTX_W-1:0] ctx_t;

  // ---- Elaboration-time parameter checks ---------------------------------------------------
  if (MAX_OUTSTANDING < 2 || MAX_OUTSTANDING > 64 ||
      (MAX_OUTSTANDING & (MAX_OUTSTANDING - 1)) != 0) begin : g_check_outstanding
    $fatal(1, "msr_tile_engine: MAX_OUTSTANDING %0d must be a power of two in 2..64",
           MAX_OUTSTANDING);
  end
  if (TAG_W != $clog2(MAX_OUTSTANDING)) begin : g_check_tag_w
    $fatal(1, "msr_tile_engine: TAG_W %0d must be $clog2(MAX_OUTSTANDING) = %0d", TAG_W,
           $clog2(MAX_OUTSTANDING));
  end
  if (NUM_CTX < 2 || NUM_CTX > 16) begin : g_check_ctx
    $fatal(1, "msr_tile_engine: NUM_CTX %0d must be in 2..16", NUM_CTX);
  end

  function automatic ctx_t ctx_inc(ctx_t c);
    return (32'(c) == NUM_CTX - 1) ? '0 : c + 1'b1;
  endfunction

  // ---- Context bookkeeping ------------------------------------------------------------------
  // A context is free, computing (its controller walks the tile, or all positions are
  // issued and the last results are outstanding), or full (finished, waiting for / being
  // streamed out). A new tile takes the lowest free context; the streamer takes the full
  // contexts round robin, so a tile that waits long for its renders never holds up the
  // tiles behind it (tiles may leave in another order than they came).
  ctx_t                      alloc, str_q, str_sel, str_rr_q;
  logic                      any_free;
  logic                      streaming_q;
  logic    [NUM_CTX-1:0]     comp_q, issued_q, full_q, ctx_done;
  coord_t  [NUM_CTX-1:0]     ctx_x0_q, ctx_y0_q;
  ldim_t   [NUM_CTX-1:0]     ctx_w_q, ctx_h_q;
  metric_e [NUM_CTX-1:0]     ctx_metric_q;
  thr_t    [NUM_CTX-1:0][MAX_LEVELS-1:0] ctx_thr_q;
  logic    [NUM_CTX-1:0][PEND_W-1:0]     pend_q;
  rgb_t    [NUM_CTX-1:0]     last_b_q;       // B of the context's last decision (A of its next)

  logic desc_fire, stream_start, stream_done;
  logic [NUM_CTX-1:0] ctrl_start_ready, ctrl_busy;

  always_comb begin
    alloc    = '0;
    any_free = 1'b0;
    for (int unsigned i = NUM_CTX; i > 0; i--) begin
      if (!comp_q[i-1] && !full_q[i-1] && ctrl_start_ready[i-1]) begin
        alloc    = ctx_t'(i - 1);
        any_free = 1'b1;
      end
    end
  end

  assign desc_ready_o = any_free && !clear_i;
  assign desc_fire    = desc_valid_i && desc_ready_o;

  // ---- Level processing controllers, one per context ---------------------------------------
  logic    [NUM_CTX-1:0] step_valid, step_ready, step_reuse, nb_final, cand;
  // The pass-start flag is not needed with the pixel scoreboard; kept for waveforms.
  /* verilator lint_off UNUSEDSIGNAL */
  logic    [NUM_CTX-1:0] step_first;
  /* verilator lint_on UNUSEDSIGNAL */
  lcoord_t [NUM_CTX-1:0] step_x, step_y, step_ax, step_ay, step_bx, step_by;
  gap_t    [NUM_CTX-1:0] step_gap, step_off;
  level_t  [NUM_CTX-1:0] step_level;
  logic    [NUM_CTX-1:0][1:0] step_nshift;
  dir_e    [NUM_CTX-1:0] step_dir;

  // Pixel scoreboards: final_q[c][{y, x}] is set when the pixel of context c's tile is
  // written (interpolated, or traced and answered).
  logic [NUM_CTX-1:0][DEPTH-1:0] final_q;

  for (genvar c = 0; c < NUM_CTX; c++) begin : g_ctrl
    msr_level_ctrl u_ctrl (
      .clk_i         (clk_i),
      .rst_ni        (rst_ni),
      .clear_i       (clear_i),
      .start_valid_i (desc_fire && (alloc == ctx_t'(c))),
      .start_ready_o (ctrl_start_ready[c]),
      .w_i           (desc_i.w),
      .h_i           (desc_i.h),
      .levels_i      (desc_i.levels),
      .step_valid_o  (step_valid[c]),
      .step_ready_i  (step_ready[c]),
      .step_x_o      (step_x[c]),
      .step_y_o      (step_y[c]),
      .step_ax_o     (step_ax[c]),
      .step_ay_o     (step_ay[c]),
      .step_bx_o     (step_bx[c]),
      .step_by_o     (step_by[c]),
      .step_gap_o    (step_gap[c]),
      .step_off_o    (step_off[c]),
      .step_level_o  (step_level[c]),
      .step_nshift_o (step_nshift[c]),
      .step_dir_o    (step_dir[c]),
      .step_first_o  (step_first[c]),
      .step_reuse_o  (step_reuse[c]),
      .busy_o        (ctrl_busy[c])
    );
    assign nb_final[c] = (step_dir[c] == DIR_INIT) ||
                         (final_q[c][{step_ay[c], step_ax[c]}] &&
                          final_q[c][{step_by[c], step_bx[c]}]);
    assign cand[c]     = step_valid[c] && nb_final[c];
  end

  // ---- Issue arbiter: round robin over the contexts with a ready position -------------------
  // Round robin, not oldest first: a young context's initial-grid traces start its first
  // render latency early; under oldest-first priority they waited behind the old contexts'
  // interpolations, and one engine topped out at ~0.8 pixels per clock at latency 256.
  logic s1_valid_q, s1_ready, unit_ready, unit_ready_i;
  logic issue;
  ctx_t gnt, rr_q;

  always_comb begin
    gnt   = rr_q;
    issue = 1'b0;
    for (int unsigned i = NUM_CTX; i > 0; i--) begin
      // rr_q + i - 1 (mod NUM_CTX); the loop runs backwards so the first candidate wins
      int unsigned c;
      c = 32'(rr_q) + i - 1;
      if (c >= NUM_CTX) c -= NUM_CTX;
      if (cand[c]) begin
        gnt   = ctx_t'(c);
        issue = s1_ready;
      end
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      rr_q <= '0;
    end else if (clear_i) begin
      rr_q <= '0;
    end else if (issue) begin
      rr_q <= ctx_inc(gnt);
    end
  end

  assign s1_ready = !s1_valid_q || unit_ready;
  for (genvar c = 0; c < NUM_CTX; c++) begin : g_step_ready
    assign step_ready[c] = issue && (gnt == ctx_t'(c));
  end

  // The granted position.
  lcoord_t g_x, g_y, g_ax, g_ay, g_bx, g_by;
  gap_t    g_gap, g_off;
  level_t  g_level;
  logic [1:0] g_nshift;
  dir_e    g_dir;
  logic    g_reuse;
  assign g_x      = step_x[gnt];
  assign g_y      = step_y[gnt];
  assign g_ax     = step_ax[gnt];
  assign g_ay     = step_ay[gnt];
  assign g_bx     = step_bx[gnt];
  assign g_by     = step_by[gnt];
  assign g_gap    = step_gap[gnt];
  assign g_off    = step_off[gnt];
  assign g_level  = step_level[gnt];
  assign g_nshift = step_nshift[gnt];
  assign g_dir    = step_dir[gnt];
  assign g_reuse  = step_reuse[gnt];

  // Engine-side read ports: both go to the granted context's buffer.
  logic                 e_re0, e_re1;
  logic [TADDR_W-1:0]   e_raddr0, e_raddr1;
  // A decision only needs the colours of its neighbours, not their source codes.
  /* verilator lint_off UNUSEDSIGNAL */
  logic [WORD_W-1:0]    e_rdata0, e_rdata1;
  /* verilator lint_on UNUSEDSIGNAL */

  assign e_re0    = issue && (g_dir != DIR_INIT);
  assign e_re1    = issue && (g_dir != DIR_INIT) && !g_reuse;
  assign e_raddr0 = {g_by, g_bx};
  assign e_raddr1 = {g_ay, g_ax};

  // ---- S1: read data arrives, A / B formed ---------------------------------------------------
  typedef struct packed {
    lcoord_t x;
    lcoord_t y;
    level_t  level;
    logic    init;
    ctx_t    ctx;
  } side_t;

  side_t      s1_side_q;
  gap_t       s1_gap_q, s1_off_q;
  logic [1:0] s1_nshift_q;
  logic       s1_reuse_q;
  rgb_t       s1_a, s1_b;

  assign s1_b = rgb_t'(e_rdata0[$bits(rgb_t)-1:0]);
  assign s1_a = s1_reuse_q ? last_b_q[s1_side_q.ctx] : rgb_t'(e_rdata1[$bits(rgb_t)-1:0]);

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      s1_valid_q <= 1'b0;
    end else if (clear_i) begin
      s1_valid_q <= 1'b0;
    end else if (s1_ready) begin
      s1_valid_q <= issue;
    end
  end

  always_ff @(posedge clk_i) begin
    if (issue) begin
      s1_side_q   <= '{x: g_x, y: g_y, level: g_level, init: (g_dir == DIR_INIT), ctx: gnt};
      s1_gap_q    <= g_gap;
      s1_off_q    <= g_off;
      s1_nshift_q <= g_nshift;
      s1_reuse_q  <= g_reuse;
    end
    // B of this decision is A of the context's next one along the row / column.
    if (s1_valid_q && unit_ready && !s1_side_q.init) begin
      last_b_q[s1_side_q.ctx] <= s1_b;
    end
  end

  // ---- Decision and interpolation (two stages each, in lock-step) -----------------------------
  logic  out_valid, out_valid_i, out_interp, out_ready;
  // d itself is only for waveforms; the engine acts on the decision bit.
  /* verilator lint_off UNUSEDSIGNAL */
  diff_t out_diff;
  logic  interp_user;   // the interpolation unit's sideband: the decision unit carries it
  /* verilator lint_on UNUSEDSIGNAL */
  side_t out_side;
  rgb_t  out_rgb;
  thr_t  s1_thr;

  assign s1_thr = (s1_side_q.level == '0) ? '0
                                           : ctx_thr_q[s1_side_q.ctx][s1_side_q.level - 1'b1];

  msr_decide #(
    .USER_W ($bits(side_t))
  ) u_decide (
    .clk_i    (clk_i),
    .rst_ni   (rst_ni),
    .clear_i  (clear_i),
    .valid_i  (s1_valid_q),
    .ready_o  (unit_ready),
    .a_i      (s1_a),
    .b_i      (s1_b),
    .metric_i (ctx_metric_q[s1_side_q.ctx]),
    .thr_i    (s1_thr),
    .gap_i    (s1_side_q.init ? gap_t'(1) : s1_gap_q),
    .nshift_i (s1_nshift_q),
    .user_i   (s1_side_q),
    .valid_o  (out_valid),
    .ready_i  (out_ready),
    .interp_o (out_interp),
    .diff_o   (out_diff),
    .user_o   (out_side)
  );

  msr_interp #(
    .USER_W (1)
  ) u_interp (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .clear_i (clear_i),
    .valid_i (s1_valid_q),
    .ready_o (unit_ready_i),
    .a_i     (s1_a),
    .b_i     (s1_b),
    .gap_i   (s1_side_q.init ? gap_t'(2) : s1_gap_q),
    .off_i   (s1_side_q.init ? gap_t'(0) : s1_off_q),
    .user_i  (1'b0),
    .valid_o (out_valid_i),
    .ready_i (out_ready),
    .rgb_o   (out_rgb),
    .user_o  (interp_user)
  );

  // ---- Output: interpolate -> write, trace -> render request ---------------------------------
  logic out_trace, out_write, req_fire, rsp_fire, tag_avail;
  logic [TAG_W-1:0] free_head;
  logic [CNT_W-1:0] free_cnt_q;  // free tags

  assign out_trace   = out_side.init || !out_interp;
  assign tag_avail   = (free_cnt_q != '0);
  assign req_valid_o = out_valid && out_trace && tag_avail;
  assign req_fire    = req_valid_o && req_ready_i;
  assign out_write   = out_valid && !out_trace;
  assign out_ready   = !out_trace || req_fire;
  assign req_x_o     = ctx_x0_q[out_side.ctx] + coord_t'(out_side.x);
  assign req_y_o     = ctx_y0_q[out_side.ctx] + coord_t'(out_side.y);
  assign req_tag_o   = free_head;

  // ---- Tags: free list, and where each answer goes -------------------------------------------
  logic [MAX_OUTSTANDING-1:0][TAG_W-1:0] free_q;
  logic [TAG_W-1:0] free_rptr_q, free_wptr_q;
  logic [MAX_OUTSTANDING-1:0][TADDR_W-1:0] tag_addr_q;
  level_t [MAX_OUTSTANDING-1:0] tag_level_q;
  ctx_t   [MAX_OUTSTANDING-1:0] tag_ctx_q;
  logic [MAX_OUTSTANDING-1:0] tag_busy_q;
  ctx_t rsp_ctx;

  assign free_head   = free_q[free_rptr_q];
  assign rsp_ctx     = tag_ctx_q[rsp_tag_i];
  // Each context's buffer has one write port: the decision pipeline has it first.
  assign rsp_ready_o = !(out_write && (out_side.ctx == rsp_ctx));
  assign rsp_fire    = rsp_valid_i && rsp_ready_o;
  assign inflight_o  = CNT_W'(MAX_OUTSTANDING) - free_cnt_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      for (int unsigned i = 0; i < MAX_OUTSTANDING; i++) free_q[i] <= TAG_W'(i);
      free_rptr_q <= '0;
      free_wptr_q <= '0;
      free_cnt_q  <= CNT_W'(MAX_OUTSTANDING);
      tag_busy_q  <= '0;
    end else if (clear_i) begin
      for (int unsigned i = 0; i < MAX_OUTSTANDING; i++) free_q[i] <= TAG_W'(i);
      free_rptr_q <= '0;
      free_wptr_q <= '0;
      free_cnt_q  <= CNT_W'(MAX_OUTSTANDING);
      tag_busy_q  <= '0;
    end else begin
      if (req_fire) begin
        free_rptr_q           <= free_rptr_q + 1'b1;
        tag_busy_q[free_head] <= 1'b1;
      end
      if (rsp_fire) begin
        free_q[free_wptr_q]   <= rsp_tag_i;
        free_wptr_q           <= free_wptr_q + 1'b1;
        tag_busy_q[rsp_tag_i] <= 1'b0;
      end
      free_cnt_q <= free_cnt_q - CNT_W'(req_fire) + CNT_W'(rsp_fire);
    end
  end

  always_ff @(posedge clk_i) begin
    if (req_fire) begin
      tag_addr_q[free_head]  <= {out_side.y, out_side.x};
      tag_level_q[free_head] <= out_side.level;
      tag_ctx_q[free_head]   <= out_side.ctx;
    end
  end

  // Writes: an interpolated value to its context, a render response to its tag's context.
  logic [NUM_CTX-1:0]              b_we;
  logic [NUM_CTX-1:0][TADDR_W-1:0] b_waddr;
  logic [NUM_CTX-1:0][WORD_W-1:0]  b_wdata;

  always_comb begin
    for (int unsigned c = 0; c < NUM_CTX; c++) begin
      b_we[c]    = 1'b0;
      b_waddr[c] = tag_addr_q[rsp_tag_i];
      b_wdata[c] = {src_traced(tag_level_q[rsp_tag_i]), rsp_rgb_i};
      if (rsp_fire && rsp_ctx == ctx_t'(c)) b_we[c] = 1'b1;
      if (out_write && out_side.ctx == ctx_t'(c)) begin
        b_we[c]    = 1'b1;
        b_waddr[c] = {out_side.y, out_side.x};
        b_wdata[c] = {src_interp(out_side.level), out_rgb};
      end
    end
  end

  // Scoreboard update: a written pixel is final; a new tile starts with none.
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      final_q <= '0;
    end else if (clear_i) begin
      final_q <= '0;
    end else begin
      for (int unsigned c = 0; c < NUM_CTX; c++) begin
        if (desc_fire && alloc == ctx_t'(c)) begin
          final_q[c] <= '0;
        end else if (b_we[c]) begin
          final_q[c][b_waddr[c]] <= 1'b1;
        end
      end
    end
  end

  // ---- Tile start / end ----------------------------------------------------------------------
  for (genvar c = 0; c < NUM_CTX; c++) begin : g_done
    assign ctx_done[c] = comp_q[c] && issued_q[c] && (pend_q[c] == '0);
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      str_q        <= '0;
      str_rr_q     <= '0;
      streaming_q  <= 1'b0;
      comp_q       <= '0;
      issued_q     <= '0;
      full_q       <= '0;
      pend_q       <= '0;
      ctx_x0_q     <= '0;
      ctx_y0_q     <= '0;
      ctx_w_q      <= '0;
      ctx_h_q      <= '0;
      ctx_metric_q <= {NUM_CTX{METRIC_MAX}};
      ctx_thr_q    <= '0;
    end else if (clear_i) begin
      str_q       <= '0;
      str_rr_q    <= '0;
      streaming_q <= 1'b0;
      comp_q      <= '0;
      issued_q    <= '0;
      full_q      <= '0;
      pend_q      <= '0;
    end else begin
      if (desc_fire) begin
        comp_q[alloc]       <= 1'b1;
        ctx_x0_q[alloc]     <= desc_i.x0;
        ctx_y0_q[alloc]     <= desc_i.y0;
        ctx_w_q[alloc]      <= desc_i.w;
        ctx_h_q[alloc]      <= desc_i.h;
        ctx_metric_q[alloc] <= desc_i.metric;
        ctx_thr_q[alloc]    <= desc_i.thr;
      end
      for (int unsigned c = 0; c < NUM_CTX; c++) begin
        // the controller has issued every position of its tile (it goes idle after the last;
        // it is busy from the clock after the start, when comp_q is set)
        if (comp_q[c] && !issued_q[c] && !ctrl_busy[c]) issued_q[c] <= 1'b1;
        // issued +1; interpolated and written -1; trace answered and written -1
        pend_q[c] <= pend_q[c] + PEND_W'(issue && gnt == ctx_t'(c))
                               - PEND_W'(out_write && out_side.ctx == ctx_t'(c))
                               - PEND_W'(rsp_fire && rsp_ctx == ctx_t'(c));
        if (ctx_done[c]) begin
          comp_q[c]   <= 1'b0;
          issued_q[c] <= 1'b0;
          full_q[c]   <= 1'b1;
        end
      end
      if (stream_done) full_q[str_q] <= 1'b0;   // the streamed context is free again
      if (stream_start) begin
        streaming_q <= 1'b1;
        str_q       <= str_sel;
        str_rr_q    <= ctx_inc(str_sel);
      end
      if (stream_done) streaming_q <= 1'b0;
    end
  end

  // ---- Output streamer -----------------------------------------------------------------------
  logic               s_re, s_start_ready;
  logic [TADDR_W-1:0] s_raddr;
  logic [WORD_W-1:0]  s_rdata;

  // Next tile to stream: the first full context from str_rr_q on.
  always_comb begin
    str_sel = str_rr_q;
    for (int unsigned i = NUM_CTX; i > 0; i--) begin
      int unsigned c;
      c = 32'(str_rr_q) + i - 1;
      if (c >= NUM_CTX) c -= NUM_CTX;
      if (full_q[c]) str_sel = ctx_t'(c);
    end
  end

  assign stream_start = !streaming_q && (full_q != '0) && s_start_ready;

  msr_tile_stream u_stream (
    .clk_i         (clk_i),
    .rst_ni        (rst_ni),
    .clear_i       (clear_i),
    .start_valid_i (!streaming_q && (full_q != '0)),
    .start_ready_o (s_start_ready),
    .x0_i          (ctx_x0_q[str_sel]),
    .y0_i          (ctx_y0_q[str_sel]),
    .w_i           (ctx_w_q[str_sel]),
    .h_i           (ctx_h_q[str_sel]),
    .re_o          (s_re),
    .raddr_o       (s_raddr),
    .rdata_rgb_i   (rgb_t'(s_rdata[$bits(rgb_t)-1:0])),
    .rdata_src_i   (src_t'(s_rdata[WORD_W-1:$bits(rgb_t)])),
    .pix_valid_o   (pix_valid_o),
    .pix_ready_i   (pix_ready_i),
    .pix_x_o       (pix_x_o),
    .pix_y_o       (pix_y_o),
    .pix_rgb_o     (pix_rgb_o),
    .pix_src_o     (pix_src_o),
    .pix_last_o    (pix_last_o),
    .done_o        (stream_done)
  );

  assign busy_o = (comp_q != '0) || (full_q != '0);

  // ---- Tile buffers, one per context ---------------------------------------------------------
  // Port 0 of a buffer belongs to the streamer while it empties that buffer, else to the
  // decision reads; a full buffer is never read for decisions, so the two never collide.
  logic [NUM_CTX-1:0][WORD_W-1:0] b_rdata0, b_rdata1;

  for (genvar c = 0; c < NUM_CTX; c++) begin : g_buf
    logic str_owns, eng_owns;
    assign str_owns = streaming_q && (str_q == ctx_t'(c));
    assign eng_owns = (gnt == ctx_t'(c));

    msr_tile_sram #(
      .DEPTH  (DEPTH),
      .DATA_W (WORD_W)
    ) u_sram (
      .clk_i    (clk_i),
      .re0_i    (str_owns ? s_re : (eng_owns && e_re0)),
      .raddr0_i (str_owns ? s_raddr : e_raddr0),
      .rdata0_o (b_rdata0[c]),
      .re1_i    (eng_owns && e_re1),
      .raddr1_i (e_raddr1),
      .rdata1_o (b_rdata1[c]),
      .we_i     (b_we[c]),
      .waddr_i  (b_waddr[c]),
      .wdata_i  (b_wdata[c])
    );
  end

  assign e_rdata0 = b_rdata0[s1_side_q.ctx];
  assign e_rdata1 = b_rdata1[s1_side_q.ctx];
  assign s_rdata  = b_rdata0[str_q];

`ifndef SYNTHESIS
  // Lint: disable iff (!rst_ni) looks like a synchronous use of the asynchronous reset.
  /* verilator lint_off SYNCASYNCNET */
  // Handshakes (outputs): valid held until ready, data stable.
  a_req_hold : assert property (@(posedge clk_i) disable iff (!rst_ni || clear_i)
      req_valid_o && !req_ready_i |=> req_valid_o && $stable({req_x_o, req_y_o, req_tag_o}))
    else $error("msr_tile_engine: render request changed while stalled");
  a_pix_hold : assert property (@(posedge clk_i) disable iff (!rst_ni || clear_i)
      pix_valid_o && !pix_ready_i |=> pix_valid_o &&
        $stable({pix_x_o, pix_y_o, pix_rgb_o, pix_src_o, pix_last_o}))
    else $error("msr_tile_engine: pixel changed while stalled");
  // Handshakes (inputs): the environment holds what it offers.
  a_desc_hold : assert property (@(posedge clk_i) disable iff (!rst_ni || clear_i)
      desc_valid_i && !desc_ready_o |=> desc_valid_i && $stable(desc_i))
    else $error("msr_tile_engine: descriptor changed while waiting");
  a_rsp_hold : assert property (@(posedge clk_i) disable iff (!rst_ni || clear_i)
      rsp_valid_i && !rsp_ready_o |=> rsp_valid_i && $stable({rsp_tag_i, rsp_rgb_i}))
    else $error("msr_tile_engine: response changed while waiting");
  // Tags: no response without a request, no tag reused while in flight.
  a_rsp_known : assert property (@(posedge clk_i) disable iff (!rst_ni)
      rsp_valid_i |-> tag_busy_q[rsp_tag_i])
    else $error("msr_tile_engine: response with tag %0d that is not in flight", rsp_tag_i);
  a_tag_free : assert property (@(posedge clk_i) disable iff (!rst_ni)
      req_valid_o |-> !tag_busy_q[req_tag_o])
    else $error("msr_tile_engine: tag %0d reused while in flight", req_tag_o);
  a_clear_idle : assert property (@(posedge clk_i) disable iff (!rst_ni)
      clear_i |-> inflight_o == '0)
    else $error("msr_tile_engine: clear_i with %0d requests in flight", inflight_o);
  a_desc_legal : assert property (@(posedge clk_i) disable iff (!rst_ni)
      desc_fire |-> desc_i.w inside {[1 : MAX_TILE]} && desc_i.h inside {[1 : MAX_TILE]} &&
        desc_i.levels inside {[1 : MAX_LEVELS]})
    else $error("msr_tile_engine: descriptor %0dx%0d L=%0d out of range", desc_i.w, desc_i.h,
                desc_i.levels);
  a_units_lockstep : assert property (@(posedge clk_i) disable iff (!rst_ni)
      unit_ready == unit_ready_i && out_valid == out_valid_i)
    else $error("msr_tile_engine: decision and interpolation units out of step");
  a_reads_own : assert property (@(posedge clk_i) disable iff (!rst_ni || clear_i)
      issue |-> comp_q[gnt] && !issued_q[gnt] && !full_q[gnt])
    else $error("msr_tile_engine: position issued into a context that is not being computed");

  // Invariant: every pixel of a tile is written exactly once, and only pixels of the tile.
  logic [NUM_CTX-1:0][DEPTH-1:0] written_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      written_q <= '0;
    end else begin
      for (int unsigned c = 0; c < NUM_CTX; c++) begin
        if (desc_fire && alloc == ctx_t'(c)) written_q[c] <= '0;
        if (b_we[c]) written_q[c][b_waddr[c]] <= 1'b1;
      end
    end
  end
  function automatic logic all_written(logic [DEPTH-1:0] wr, ldim_t w, ldim_t h);
    logic ok = 1'b1;
    for (int unsigned y = 0; y < MAX_TILE; y++) begin
      for (int unsigned x = 0; x < MAX_TILE; x++) begin
        if (x < 32'(w) && y < 32'(h)) ok &= wr[y*MAX_TILE+x];
      end
    end
    return ok;
  endfunction
  for (genvar c = 0; c < NUM_CTX; c++) begin : g_assert_ctx
    a_write_once : assert property (@(posedge clk_i) disable iff (!rst_ni || clear_i)
        b_we[c] |-> comp_q[c] && !written_q[c][b_waddr[c]] &&
          32'(b_waddr[c][LCOORD_W-1:0]) < 32'(ctx_w_q[c]) &&
          32'(b_waddr[c][TADDR_W-1:LCOORD_W]) < 32'(ctx_h_q[c]))
      else $error("msr_tile_engine: pixel (%0d,%0d) of context %0d written twice or outside the tile",
                  b_waddr[c][LCOORD_W-1:0], b_waddr[c][TADDR_W-1:LCOORD_W], c);
    a_all_written : assert property (@(posedge clk_i) disable iff (!rst_ni || clear_i)
        ctx_done[c] |-> all_written(written_q[c], ctx_w_q[c], ctx_h_q[c]))
      else $error("msr_tile_engine: tile of context %0d finished with pixels never written", c);
  end
  /* verilator lint_on SYNCASYNCNET */
`endif

endmodule : msr_tile_engine
