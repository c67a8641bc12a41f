// Tile engine: one tile in, its final pixels out (spec ../shared/spec/algorithm.md).
//
//   desc --> msr_level_ctrl --issue--> S1 (tile buffer read data) --> msr_decide ---+
//                 positions    |                                    \-> msr_interp -+-> out
//                              +-- port 0: B, port 1: A (if not reused)            |
//   out: interpolate -> tile buffer write; trace -> render request {x, y, tag}      |
//   rsp {tag, rgb}   -> tile buffer write (when the write port is free)  <----------+
//   finished tile    -> msr_tile_stream --> pix stream (row-major)
//
// Decisions of one pass are independent, so positions are issued back to back while render
// requests are outstanding. Instead of a pass barrier, a pixel scoreboard lets a position go
// as soon as its two neighbours are final (same values as after a barrier, in order). Two
// tile buffers, each with its own tile context: the next tile starts as soon as every
// position of the current one is issued, and the streamer empties a finished buffer while
// the engine fills the other.
//
// inflight_o counts tags handed out and not yet answered (a request waiting for
// req_ready_i counts as in flight).
module tile_engine
  import msr_pkg::*;
#(
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

  // ---- Elaboration-time parameter checks ---------------------------------------------------
  if (MAX_OUTSTANDING < 2 || MAX_OUTSTANDING > 64 ||
      (MAX_OUTSTANDING & (MAX_OUTSTANDING - 1)) != 0) begin : g_check_outstanding
    $fatal(1, "tile_engine: MAX_OUTSTANDING %0d must be a power of two in 2..64",
           MAX_OUTSTANDING);
  end
  if (TAG_W != $clog2(MAX_OUTSTANDING)) begin : g_check_tag_w
    $fatal(1, "tile_engine: TAG_W %0d must be $clog2(MAX_OUTSTANDING) = %0d", TAG_W,
           $clog2(MAX_OUTSTANDING));
  end

  // ---- Tile bookkeeping: two buffers, one tile context each ---------------------------------
  // A buffer is free, computing (its tile's positions are being issued, or issued and
  // waiting for their last results), or full (finished, waiting for / being streamed).
  // The controller moves on to the next tile, in the other buffer, as soon as it has issued
  // every position of the current one, so the tail of one tile overlaps the next.
  localparam int unsigned PEND_W = $clog2(MAX_OUTSTANDING + 8) + 1;

  logic       eng_bank_q;        // buffer of the tile the controller walks / will walk
  logic [1:0] comp_q;            // buffer's tile is being computed
  logic [1:0] issued_q;          // ... and all its positions are issued
  logic [1:0] full_q;            // buffer holds a finished tile not yet streamed out
  logic       str_bank_q;        // next buffer to stream (tiles leave in order)
  logic       streaming_q;
  coord_t [1:0] bank_x0_q, bank_y0_q;
  ldim_t  [1:0] bank_w_q, bank_h_q;
  metric_e [1:0] bank_metric_q;
  thr_t [1:0][MAX_LEVELS-1:0] bank_thr_q;
  logic [1:0][PEND_W-1:0] pend_q; // positions issued and not yet final (pipeline or tag)
  logic [1:0] bank_done;

  logic ctrl_start_ready, ctrl_busy, ctrl_fin;
  logic desc_fire, stream_start, stream_done;

  assign desc_ready_o = ctrl_start_ready && !comp_q[eng_bank_q] && !full_q[eng_bank_q] &&
                        !clear_i;
  assign desc_fire    = desc_valid_i && desc_ready_o;

  // ---- Level processing controller -----------------------------------------------------------
  logic    step_valid, step_ready, step_reuse;
  // The pass-start flag is not needed with the pixel scoreboard; kept for waveforms and
  // the throughput benchmark, which counts decisions per pass with it.
  /* verilator lint_off UNUSEDSIGNAL */
  logic    step_first;
  /* verilator lint_on UNUSEDSIGNAL */
  lcoord_t step_x, step_y, step_ax, step_ay, step_bx, step_by;
  gap_t    step_gap, step_off;
  level_t  step_level;
  logic [1:0] step_nshift;
  dir_e    step_dir;

  msr_level_ctrl u_ctrl (
    .clk_i         (clk_i),
    .rst_ni        (rst_ni),
    .clear_i       (clear_i),
    .start_valid_i (desc_valid_i && desc_ready_o),
    .start_ready_o (ctrl_start_ready),
    .w_i           (desc_i.w),
    .h_i           (desc_i.h),
    .levels_i      (desc_i.levels),
    .step_valid_o  (step_valid),
    .step_ready_i  (step_ready),
    .step_x_o      (step_x),
    .step_y_o      (step_y),
    .step_ax_o     (step_ax),
    .step_ay_o     (step_ay),
    .step_bx_o     (step_bx),
    .step_by_o     (step_by),
    .step_gap_o    (step_gap),
    .step_off_o    (step_off),
    .step_level_o  (step_level),
    .step_nshift_o (step_nshift),
    .step_dir_o    (step_dir),
    .step_first_o  (step_first),
    .step_reuse_o  (step_reuse),
    .busy_o        (ctrl_busy)
  );

  // ---- Issue: scoreboard and tile buffer reads ---------------------------------------------
  logic [CNT_W-1:0] free_cnt_q;  // free tags
  logic s1_valid_q, s1_ready, unit_ready, unit_ready_i;
  logic issue;

  // Pixel scoreboard: final_q[{y, x}] is set when the pixel of the current tile is written
  // (interpolated, or traced and answered). A position is issued as soon as both its
  // neighbours are final; that is exactly what a pass barrier guarantees (a pass reads only
  // pixels of earlier passes, which are written once and never change), without waiting
  // for the rest of the previous pass. Positions still leave in order, so the render
  // requests keep the golden model's order.
  logic [DEPTH-1:0] final_q;
  logic             nb_final;

  assign nb_final   = (step_dir == DIR_INIT) ||
                      (final_q[{step_ay, step_ax}] && final_q[{step_by, step_bx}]);
  assign s1_ready   = !s1_valid_q || unit_ready;
  assign issue      = step_valid && s1_ready && nb_final;
  assign step_ready = s1_ready && nb_final;

  // Engine-side ports: reads go to the controller's buffer, writes to the position's.
  logic                 e_re0, e_re1, e_we;
  logic [TADDR_W-1:0]   e_raddr0, e_raddr1, e_waddr;
  logic                 e_wbank;
  logic [WORD_W-1:0]    e_wdata;
  // A decision only needs the colours of its neighbours, not their source codes.
  /* verilator lint_off UNUSEDSIGNAL */
  logic [WORD_W-1:0]    e_rdata0, e_rdata1;
  /* verilator lint_on UNUSEDSIGNAL */

  assign e_re0    = issue && (step_dir != DIR_INIT);
  assign e_re1    = issue && (step_dir != DIR_INIT) && !step_reuse;
  assign e_raddr0 = {step_by, step_bx};
  assign e_raddr1 = {step_ay, step_ax};

  // ---- S1: read data arrives, A / B formed ---------------------------------------------------
  typedef struct packed {
    lcoord_t x;
    lcoord_t y;
    level_t  level;
    logic    init;
    logic    bank;
  } side_t;

  side_t      s1_side_q;
  gap_t       s1_gap_q, s1_off_q;
  logic [1:0] s1_nshift_q;
  logic       s1_reuse_q;
  rgb_t       last_b_q, s1_a, s1_b;

  assign s1_b = rgb_t'(e_rdata0[$bits(rgb_t)-1:0]);
  assign s1_a = s1_reuse_q ? last_b_q : rgb_t'(e_rdata1[$bits(rgb_t)-1:0]);

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
      s1_side_q   <= '{x: step_x, y: step_y, level: step_level, init: (step_dir == DIR_INIT),
                       bank: eng_bank_q};
      s1_gap_q    <= step_gap;
      s1_off_q    <= step_off;
      s1_nshift_q <= step_nshift;
      s1_reuse_q  <= step_reuse;
    end
    // B of this decision is A of the next one along the row / column.
    if (s1_valid_q && unit_ready && !s1_side_q.init) begin
      last_b_q <= s1_b;
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
                                           : bank_thr_q[s1_side_q.bank][s1_side_q.level - 1'b1];

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
    .metric_i (bank_metric_q[s1_side_q.bank]),
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

  assign out_trace   = out_side.init || !out_interp;
  assign tag_avail   = (free_cnt_q != '0);
  assign req_valid_o = out_valid && out_trace && tag_avail;
  assign req_fire    = req_valid_o && req_ready_i;
  assign out_write   = out_valid && !out_trace;
  assign out_ready   = !out_trace || req_fire;
  assign req_x_o     = bank_x0_q[out_side.bank] + coord_t'(out_side.x);
  assign req_y_o     = bank_y0_q[out_side.bank] + coord_t'(out_side.y);
  assign req_tag_o   = free_head;

  // ---- Tags: free list, and where each answer goes -------------------------------------------
  logic [MAX_OUTSTANDING-1:0][TAG_W-1:0] free_q;
  logic [TAG_W-1:0] free_rptr_q, free_wptr_q;
  logic [MAX_OUTSTANDING-1:0][TADDR_W-1:0] tag_addr_q;
  level_t [MAX_OUTSTANDING-1:0] tag_level_q;
  logic   [MAX_OUTSTANDING-1:0] tag_bank_q;
  logic [MAX_OUTSTANDING-1:0] tag_busy_q;

  assign free_head   = free_q[free_rptr_q];
  assign rsp_ready_o = !out_write;           // the decision pipeline has the write port first
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
      tag_bank_q[free_head]  <= out_side.bank;
    end
  end

  // One write port: an interpolated value, else a render response.
  assign e_we    = out_write || rsp_fire;
  assign e_wbank = out_write ? out_side.bank : tag_bank_q[rsp_tag_i];
  assign e_waddr = out_write ? {out_side.y, out_side.x} : tag_addr_q[rsp_tag_i];
  assign e_wdata = out_write ? {src_interp(out_side.level), out_rgb}
                             : {src_traced(tag_level_q[rsp_tag_i]), rsp_rgb_i};

  // Scoreboard update: a written pixel is final. It only tracks the controller's buffer
  // (late results of the previous tile go to the other buffer).
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      final_q <= '0;
    end else if (clear_i || desc_fire) begin
      final_q <= '0;
    end else if (e_we && e_wbank == eng_bank_q) begin
      final_q[e_waddr] <= 1'b1;
    end
  end

  // ---- Tile start / end ----------------------------------------------------------------------
  // The controller has issued every position of its tile (it goes idle only after the last).
  assign ctrl_fin = comp_q[eng_bank_q] && !issued_q[eng_bank_q] && !ctrl_busy;

  for (genvar b = 0; b < 2; b++) begin : g_done
    assign bank_done[b] = comp_q[b] && issued_q[b] && (pend_q[b] == '0);
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      eng_bank_q    <= 1'b0;
      comp_q        <= '0;
      issued_q      <= '0;
      full_q        <= '0;
      pend_q        <= '0;
      str_bank_q    <= 1'b0;
      streaming_q   <= 1'b0;
      bank_x0_q     <= '0;
      bank_y0_q     <= '0;
      bank_w_q      <= '0;
      bank_h_q      <= '0;
      bank_metric_q <= {2{METRIC_MAX}};
      bank_thr_q    <= '0;
    end else if (clear_i) begin
      eng_bank_q  <= 1'b0;
      comp_q      <= '0;
      issued_q    <= '0;
      full_q      <= '0;
      pend_q      <= '0;
      str_bank_q  <= 1'b0;
      streaming_q <= 1'b0;
    end else begin
      if (desc_fire) begin
        comp_q[eng_bank_q]        <= 1'b1;
        bank_x0_q[eng_bank_q]     <= desc_i.x0;
        bank_y0_q[eng_bank_q]     <= desc_i.y0;
        bank_w_q[eng_bank_q]      <= desc_i.w;
        bank_h_q[eng_bank_q]      <= desc_i.h;
        bank_metric_q[eng_bank_q] <= desc_i.metric;
        bank_thr_q[eng_bank_q]    <= desc_i.thr;
      end
      if (ctrl_fin) begin
        issued_q[eng_bank_q] <= 1'b1;
        eng_bank_q           <= !eng_bank_q;
      end
      for (int unsigned b = 0; b < 2; b++) begin
        // issued +1; interpolated and written -1; trace answered and written -1
        pend_q[b] <= pend_q[b] + PEND_W'(issue && eng_bank_q == 1'(b))
                               - PEND_W'(out_write && out_side.bank == 1'(b))
                               - PEND_W'(rsp_fire && tag_bank_q[rsp_tag_i] == 1'(b));
        if (bank_done[b]) begin
          comp_q[b]   <= 1'b0;
          issued_q[b] <= 1'b0;
          full_q[b]   <= 1'b1;
        end
        if (stream_done && str_bank_q == 1'(b)) full_q[b] <= 1'b0;
      end
      if (stream_start) streaming_q <= 1'b1;
      if (stream_done) begin
        streaming_q <= 1'b0;
        str_bank_q  <= !str_bank_q;
      end
    end
  end

  // ---- Output streamer -----------------------------------------------------------------------
  logic               s_re, s_start_ready;
  logic [TADDR_W-1:0] s_raddr;
  logic [WORD_W-1:0]  s_rdata;

  assign stream_start = !streaming_q && full_q[str_bank_q] && s_start_ready;

  msr_tile_stream u_stream (
    .clk_i         (clk_i),
    .rst_ni        (rst_ni),
    .clear_i       (clear_i),
    .start_valid_i (!streaming_q && full_q[str_bank_q]),
    .start_ready_o (s_start_ready),
    .x0_i          (bank_x0_q[str_bank_q]),
    .y0_i          (bank_y0_q[str_bank_q]),
    .w_i           (bank_w_q[str_bank_q]),
    .h_i           (bank_h_q[str_bank_q]),
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

  // ---- Tile buffers (ping-pong) --------------------------------------------------------------
  // Port 0 of a buffer belongs to the streamer while it empties that buffer, else to the
  // engine; the engine never works on a buffer that is full, so the two never collide.
  logic [1:0][WORD_W-1:0] b_rdata0, b_rdata1;

  for (genvar b = 0; b < 2; b++) begin : g_bank
    logic str_owns, eng_owns;
    assign str_owns = streaming_q && (str_bank_q == 1'(b));
    assign eng_owns = (eng_bank_q == 1'(b));

    msr_tile_sram #(
      .DEPTH  (DEPTH),
      .DATA_W (WORD_W)
    ) u_sram (
      .clk_i    (clk_i),
      .re0_i    (str_owns ? s_re : (eng_owns && e_re0)),
      .raddr0_i (str_owns ? s_raddr : e_raddr0),
      .rdata0_o (b_rdata0[b]),
      .re1_i    (eng_owns && e_re1),
      .raddr1_i (e_raddr1),
      .rdata1_o (b_rdata1[b]),
      .we_i     (e_we && (e_wbank == 1'(b))),
      .waddr_i  (e_waddr),
      .wdata_i  (e_wdata)
    );
  end

  assign e_rdata0 = b_rdata0[s1_side_q.bank];
  assign e_rdata1 = b_rdata1[s1_side_q.bank];
  assign s_rdata  = b_rdata0[str_bank_q];

`ifndef SYNTHESIS
  // Lint: disable iff (!rst_ni) looks like a synchronous use of the asynchronous reset.
  /* verilator lint_off SYNCASYNCNET */
  // Handshakes (outputs): valid held until ready, data stable.
  a_req_hold : assert property (@(posedge clk_i) disable iff (!rst_ni || clear_i)
      req_valid_o && !req_ready_i |=> req_valid_o && $stable({req_x_o, req_y_o, req_tag_o}))
    else $error("tile_engine: render request changed while stalled");
  a_pix_hold : assert property (@(posedge clk_i) disable iff (!rst_ni || clear_i)
      pix_valid_o && !pix_ready_i |=> pix_valid_o &&
        $stable({pix_x_o, pix_y_o, pix_rgb_o, pix_src_o, pix_last_o}))
    else $error("tile_engine: pixel changed while stalled");
  // Handshakes (inputs): the environment holds what it offers.
  a_desc_hold : assert property (@(posedge clk_i) disable iff (!rst_ni || clear_i)
      desc_valid_i && !desc_ready_o |=> desc_valid_i && $stable(desc_i))
    else $error("tile_engine: descriptor changed while waiting");
  a_rsp_hold : assert property (@(posedge clk_i) disable iff (!rst_ni || clear_i)
      rsp_valid_i && !rsp_ready_o |=> rsp_valid_i && $stable({rsp_tag_i, rsp_rgb_i}))
    else $error("tile_engine: response changed while waiting");
  // Tags: no response without a request, no tag reused while in flight.
  a_rsp_known : assert property (@(posedge clk_i) disable iff (!rst_ni)
      rsp_valid_i |-> tag_busy_q[rsp_tag_i])
    else $error("tile_engine: response with tag %0d that is not in flight", rsp_tag_i);
  a_tag_free : assert property (@(posedge clk_i) disable iff (!rst_ni)
      req_valid_o |-> !tag_busy_q[req_tag_o])
    else $error("tile_engine: tag %0d reused while in flight", req_tag_o);
  a_clear_idle : assert property (@(posedge clk_i) disable iff (!rst_ni)
      clear_i |-> inflight_o == '0)
    else $error("tile_engine: clear_i with %0d requests in flight", inflight_o);
  a_desc_legal : assert property (@(posedge clk_i) disable iff (!rst_ni)
      desc_fire |-> desc_i.w inside {[1 : MAX_TILE]} && desc_i.h inside {[1 : MAX_TILE]} &&
        desc_i.levels inside {[1 : MAX_LEVELS]})
    else $error("tile_engine: descriptor %0dx%0d L=%0d out of range", desc_i.w, desc_i.h,
                desc_i.levels);
  a_units_lockstep : assert property (@(posedge clk_i) disable iff (!rst_ni)
      unit_ready == unit_ready_i && out_valid == out_valid_i)
    else $error("tile_engine: decision and interpolation units out of step");

  // Invariant: every pixel of a tile is written exactly once, and only pixels of the tile.
  logic [1:0][DEPTH-1:0] written_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      written_q <= '0;
    end else begin
      if (desc_fire) written_q[eng_bank_q] <= '0;
      if (e_we) written_q[e_wbank][e_waddr] <= 1'b1;
    end
  end
  a_write_once : assert property (@(posedge clk_i) disable iff (!rst_ni || clear_i)
      e_we |-> comp_q[e_wbank] && !written_q[e_wbank][e_waddr] &&
        32'(e_waddr[LCOORD_W-1:0]) < 32'(bank_w_q[e_wbank]) &&
        32'(e_waddr[TADDR_W-1:LCOORD_W]) < 32'(bank_h_q[e_wbank]))
    else $error("tile_engine: pixel (%0d,%0d) of buffer %0d written twice or outside the tile",
                e_waddr[LCOORD_W-1:0], e_waddr[TADDR_W-1:LCOORD_W], e_wbank);
  function automatic logic all_written(logic [DEPTH-1:0] wr, ldim_t w, ldim_t h);
    logic ok = 1'b1;
    for (int unsigned y = 0; y < MAX_TILE; y++) begin
      for (int unsigned x = 0; x < MAX_TILE; x++) begin
        if (x < 32'(w) && y < 32'(h)) ok &= wr[y*MAX_TILE+x];
      end
    end
    return ok;
  endfunction
  for (genvar b = 0; b < 2; b++) begin : g_assert_bank
    a_all_written : assert property (@(posedge clk_i) disable iff (!rst_ni || clear_i)
        bank_done[b] |-> all_written(written_q[b], bank_w_q[b], bank_h_q[b]))
      else $error("tile_engine: tile of buffer %0d finished with pixels never written", b);
  end
  a_reads_own : assert property (@(posedge clk_i) disable iff (!rst_ni || clear_i)
      issue |-> comp_q[eng_bank_q] && !issued_q[eng_bank_q] && !full_q[eng_bank_q])
    else $error("tile_engine: position issued into a buffer that is not being computed");
  /* verilator lint_on SYNCASYNCNET */
`endif

endmodule : tile_engine
