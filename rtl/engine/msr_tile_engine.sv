// Tile engine: tiles in, their final pixels out (spec ../shared/spec/algorithm.md).
//
//   desc --> lowest free context c (msr_tile_ctx: descriptor, level controller, pass
//            barrier, tile buffer)
//   issue: round robin (msr_rr_arb) over the contexts whose next position may go; the grant
//          is registered (GR), then the context's head leaves and its own tile buffer reads
//          B (port 0) and A (port 1) at the head's registered addresses
//   IS   : the issued position (AND-OR over the registered one-hot grant)
//   RD   : the context's descriptor fields (global coordinates, level threshold), registered
//          while the read data pass the block RAM and the register beside it
//   AB   : the issued context's read data, registered
//   msr_decision_pipe (6 stages): decide and interpolate; never stalls: a position is issued
//          only with a slot of the 16-entry output buffer reserved (credits)
//   out  : msr_req_out: interpolate -> write {16+k, C} into the context's buffer (a registered
//          port); trace -> tag -> render request {x0+x, y0+y, tag} (spill register)
//   rsp  : msr_rsp_check: the tag pool, and each response checked -> write {k, rgb} into the
//          tag's context, unless the pipeline writes that context in the same cycle
//   full contexts, round robin --> msr_tile_stream --> pix stream (row-major, whole tiles)
//
// Why contexts: a tile is a chain of 5-7 dependent passes, each waiting up to one render
// latency for its traced neighbours. NUM_CTX tiles are worked on at once; every clock the
// arbiter issues the next position of a context that may go, so one tile's waits are filled
// with other tiles' decisions. Every path between registers is a few LUT levels: the
// controllers' outputs, the candidate bits and the arbiter's pointer are registers, the
// buffer addresses need no multiplexer (each context addresses its own buffer), and the read
// data, the decision and the interpolation each get their own stages.
//
// Render responses are checked: one whose tag is not in flight (stale, duplicate, invented)
// is dropped and counted (rsp_drop_o pulses); nothing is written and no tag is freed twice.
// inflight_o counts tags handed out and not yet answered (a request waiting for req_ready_i
// counts as in flight); tags_out_o is a register that is clear only when none is (the top's
// drain check reads it across the die).
//
// lindilate (LINDILATE 1, docs/rules.md) lives in units beside these stages: msr_lin_track
// (IS -> RD -> AB: line tracking, the outer samples A', B' and their existence),
// msr_base_decision (beside the decision pipeline: Q) and msr_lin_dilate (the dilation's line
// store as decisions leave the pipeline, the retro request at the output).
//
// Registers: control flip-flops (valid bits, flags, counts) are msr_clr_reg instances (reset
// and clear_i); data registers that a valid bit qualifies are plain flip-flops without reset.
`include "msr_assert.svh"

module msr_tile_engine
  import msr_pkg::*;
#(
  // Tile contexts (2..16). 8 keeps one engine near one pixel per clock at a render latency of
  // 256 cycles with 64 tags (docs/performance.md); 2 suffice when renders answer within ~16.
  parameter int unsigned NUM_CTX         = 8,
  parameter int unsigned MAX_OUTSTANDING = 16,  // render requests in flight (power of two, 2..64)
  // 1: the lindilate rule is built (a third tile-buffer read port per context: 2 DP16KD each,
  // the base decision, the dilation); 0: patent only, every descriptor decided by the patent
  // rule (the top refuses CONFIG.RULE 1 then) and synthesis drops the rule's logic.
  parameter int unsigned LINDILATE       = 1,
  parameter int unsigned TAG_W = $clog2(MAX_OUTSTANDING)
) (
  // The port list is the interface agreed with the system top, comments included.
  // verilog_lint: waive-start line-length
  input  logic             clk_i,
  input  logic             rst_ni,
  input  logic             clear_i,        // synchronous soft reset; every tag is free again MAX_OUTSTANDING cycles later
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
  output logic             busy_o,         // tile accepted and not yet fully emitted, or tags being reset
  output logic             rsp_drop_o,     // pulse: a response whose tag was not in flight was dropped
  output logic [$clog2(MAX_OUTSTANDING):0] inflight_o, // render requests in flight (tests, waves)
  output logic             tags_out_o      // registered: a request may be in flight (0: none is)
  // verilog_lint: waive-stop line-length
);

  localparam int unsigned CTX_W  = (NUM_CTX > 1) ? $clog2(NUM_CTX) : 1;
  // Positions of one context issued and not yet written: at most the pipeline plus its tags.
  localparam int unsigned PEND_W = $clog2(MAX_OUTSTANDING + 16) + 1;

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
  if (LINDILATE > 1) begin : g_check_lindilate
    $fatal(1, "msr_tile_engine: LINDILATE %0d must be 0 or 1", LINDILATE);
  end


  // ---- Contexts ---------------------------------------------------------------------------------
  logic       [NUM_CTX-1:0] ctx_free, ctx_full, ctx_cand, ctx_start, ctx_issue;
  // the head is the first position of its pass (waveforms, scripts/bench_engine.py)
  /* verilator lint_off UNUSEDSIGNAL */
  logic       [NUM_CTX-1:0] ctx_first;
  /* verilator lint_on UNUSEDSIGNAL */
  tile_desc_t [NUM_CTX-1:0] ctx_desc;
  eng_pos_t   [NUM_CTX-1:0] ctx_pos;
  rgb_t       [NUM_CTX-1:0] ctx_rd_a, ctx_rd_b, ctx_rd_o2, ctx_str_rgb;
  src_t       [NUM_CTX-1:0] ctx_str_src;
  logic       [NUM_CTX-1:0] ctx_str_own, ctx_str_done;
  logic       [NUM_CTX-1:0] ctx_we_q, ctx_retro_q;
  logic       [NUM_CTX-1:0][TADDR_W-1:0] ctx_waddr_q;
  src_t       [NUM_CTX-1:0] ctx_wsrc_q;
  rgb_t       [NUM_CTX-1:0] ctx_wrgb_q;

  // ---- Tile start: the lowest free context, chosen a clock ahead --------------------------------
  // The choice is registered: the lowest context that is free and neither starting nor being
  // handed a descriptor this cycle. The hand-off itself is registered too: a handshake loads
  // desc_q and one bit of start_q, and the context starts from those flip-flops a clock later.
  // So the descriptor handshake (which crosses the die from the generator) ends in a few
  // registers, and the eight level controllers load from registers beside the contexts.
  // desc_ready_o is a function of flip-flops only; the soft reset is kept out of it (it is one
  // net to every flip-flop of the engine): a descriptor taken during a clear is dropped by the
  // clear of start_q, as everything else in flight is.
  logic [CTX_W-1:0]   alloc, alloc_q;
  logic               none_avail, any_free_q, tags_init, desc_hs;
  logic [NUM_CTX-1:0] hs_onehot, start_q;
  tile_desc_t         desc_q;

  assign desc_ready_o = any_free_q && !tags_init;
  assign desc_hs      = desc_valid_i && desc_ready_o;
  for (genvar c = 0; c < NUM_CTX; c++) begin : g_start
    assign hs_onehot[c] = desc_hs && (alloc_q == ctx_t'(c));
  end

  msr_lzc #(.WIDTH(NUM_CTX), .CNT_W(CTX_W)) u_alloc (
    .in_i    (ctx_free & ~start_q & ~hs_onehot),
    .cnt_o   (alloc),
    .empty_o (none_avail)
  );

  // the choice is remade every clock, so a clear need not reset it
  msr_clr_reg #(.WIDTH(CTX_W)) u_alloc_q (
    .clk_i, .rst_ni, .clear_i (1'b0), .en_i (1'b1), .d_i (alloc), .q_o (alloc_q)
  );
  msr_clr_reg #(.WIDTH(1 + NUM_CTX)) u_start_q (
    .clk_i, .rst_ni, .clear_i, .en_i (1'b1), .d_i ({!none_avail, hs_onehot}),
    .q_o ({any_free_q, start_q})
  );

  always_ff @(posedge clk_i) begin
    if (desc_hs) desc_q <= desc_i;
  end

  assign ctx_start = start_q;

  // ---- Issue ----------------------------------------------------------------------------------
  // No stage between the issue and the output buffer ever stalls: a position is granted only
  // with a free slot in that buffer reserved for it (a credit), so the pipeline registers need
  // no enable and the issue does not wait on the output's handshake.
  //
  // The grant is registered (GR): the arbiter's output goes into flip-flops beside it, and the
  // contexts, spread over the die with their tile buffers, see a register one clock later
  // (their issue_i: the head leaves, the buffer reads it). The contexts' candidate bits know
  // about the grant in flight, so a context can still win every clock.
  logic               arb_valid, can_issue, issue;
  logic [CTX_W-1:0]   gnt_idx;
  logic [NUM_CTX-1:0] gnt, gr_gnt_q;
  logic               gr_valid_q;
  ctx_t               gr_ctx;

  msr_rr_arb #(.N(NUM_CTX), .IDX_W(CTX_W)) u_issue_arb (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .clear_i (clear_i),
    .req_i   (ctx_cand),
    .gnt_o   (gnt),
    .idx_o   (gnt_idx),
    .valid_o (arb_valid),
    .ready_i (can_issue)
  );

  assign issue = arb_valid && can_issue;

  msr_clr_reg #(.WIDTH(1 + NUM_CTX)) u_gr_q (
    .clk_i, .rst_ni, .clear_i, .en_i (1'b1), .d_i ({issue, gnt & {NUM_CTX{can_issue}}}),
    .q_o ({gr_valid_q, gr_gnt_q})
  );

  // The granted context's index, encoded from the registered one-hot grant (one LUT level in
  // the short GR -> IS path) rather than registered from the arbiter's index output (two LUT
  // levels more behind its carry chain, the engine's longest path).
  always_comb begin
    gr_ctx = '0;
    for (int unsigned c = 0; c < NUM_CTX; c++) begin
      if (gr_gnt_q[c]) gr_ctx |= ctx_t'(c);
    end
  end
  logic unused_gnt_idx;
  assign unused_gnt_idx = ^gnt_idx;

  assign ctx_issue = gr_gnt_q;

  // The issued position, picked with the one-hot grant (an AND-OR, not an index multiplexer).
  eng_pos_t iss_pos;
  always_comb begin
    iss_pos = '0;
    for (int unsigned c = 0; c < NUM_CTX; c++) begin
      iss_pos |= ctx_pos[c] & {$bits(eng_pos_t){gr_gnt_q[c]}};
    end
  end

  // ---- Stage valid bits: IS (the buffer reads happen in the GR cycle), RD, AB -----------------
  logic is_valid_q, rd_valid_q, ab_valid_q;

  msr_clr_reg #(.WIDTH(3)) u_valid_q (
    .clk_i, .rst_ni, .clear_i, .en_i (1'b1), .d_i ({gr_valid_q, is_valid_q, rd_valid_q}),
    .q_o ({is_valid_q, rd_valid_q, ab_valid_q})
  );

  // ---- IS: the issue registers ----------------------------------------------------------------
  // No enable: is_valid_q says whether they hold an issue (an enable would hang the grant's
  // fan-out on every one of these flip-flops).
  ctx_t     is_ctx_q;
  eng_pos_t is_pos_q;

  always_ff @(posedge clk_i) begin
    is_ctx_q <= gr_ctx;
    is_pos_q <= iss_pos;
  end

  // What travels with a decision to the output. For lindilate (lin): the position on its
  // line (m >> 1: new positions of a level are at least 2 apart) and the first-line flag
  // address the dilation's line store; the pass direction and the distance to the previous
  // line (1..8) address a retro trace.
  // The part the output needs (the dilation's fields below stay before the output buffer).
  typedef struct packed {
    ctx_t       ctx;
    lcoord_t    x;
    lcoord_t    y;
    coord_t     gx;
    coord_t     gy;
    level_t     level;
    logic       vert;
    logic [3:0] ldelta;
  } oside_t;

  typedef struct packed {
    oside_t     o;
    logic       init;
    logic       lin;
    logic [3:0] mh;
    logic       fline;
  } side_t;

  // ---- RD: the context's descriptor fields, registered (the read data is on its way) ---------
  // The tile buffer's data arrive two clocks after the read (GR): the block RAM's registered
  // read, then the register beside it in the context. This stage uses the wait for the
  // descriptor: global coordinates and the threshold of the position's level.
  ctx_t       rd_ctx_q;
  side_t      rd_side_q;
  metric_e    rd_metric_q;
  thr_t       rd_thr_q;
  // Each of these is read in part: the position's x / y and the tile's size go elsewhere.
  /* verilator lint_off UNUSEDSIGNAL */
  eng_pos_t   rd_pos_q;
  tile_desc_t is_desc;
  /* verilator lint_on UNUSEDSIGNAL */
  logic [LCOORD_W-2:0] is_mh;

  assign is_desc = ctx_desc[is_ctx_q];

  always_ff @(posedge clk_i) begin
    if (is_valid_q) begin
      rd_ctx_q    <= is_ctx_q;
      rd_pos_q    <= is_pos_q;
      rd_side_q   <= '{o: '{ctx: is_ctx_q, x: is_pos_q.x, y: is_pos_q.y,
                            gx: is_desc.x0 + coord_t'(is_pos_q.x),
                            gy: is_desc.y0 + coord_t'(is_pos_q.y), level: is_pos_q.level,
                            vert: is_pos_q.dir == DIR_V, ldelta: '0},  // ldelta, fline: RD -> AB
                       init: is_pos_q.init,
                       lin: LINDILATE != 0 && is_desc.rule == RULE_LINDILATE && !is_pos_q.init,
                       mh: is_mh, fline: 1'b0};
      rd_metric_q <= is_desc.metric;
      // threshold of the position's level; an initial-grid position gets 0 (always trace)
      rd_thr_q    <= is_pos_q.init ? '0 : is_desc.thr[is_pos_q.level - 1'b1];
    end
  end

  // lindilate: line tracking, the outer samples' existence (IS -> RD) and A' (RD)
  logic       rd_fline, rd_oka, rd_okb;
  logic [3:0] rd_ldelta;
  rgb_t       rd_a, rd_o2, rd_oa;

  assign rd_a  = ctx_rd_a[rd_ctx_q];
  assign rd_o2 = ctx_rd_o2[rd_ctx_q];

  msr_lin_track #(.NUM_CTX(NUM_CTX), .CTX_W(CTX_W)) u_lin_track (
    .clk_i       (clk_i),
    .rst_ni      (rst_ni),
    .clear_i     (clear_i),
    .gr_valid_i  (gr_valid_q),
    .gr_gnt_i    (gr_gnt_q),
    .gr_pos_i    (iss_pos),
    .is_valid_i  (is_valid_q),
    .is_ctx_i    (is_ctx_q),
    .is_pos_i    (is_pos_q),
    .is_desc_i   (is_desc),
    .is_mh_o     (is_mh),
    .rd_valid_i  (rd_valid_q),
    .rd_ctx_i    (rd_ctx_q),
    .rd_o2a_i    (rd_pos_q.o2a),
    .rd_a_i      (rd_a),
    .rd_o2_i     (rd_o2),
    .rd_fline_o  (rd_fline),
    .rd_ldelta_o (rd_ldelta),
    .rd_oka_o    (rd_oka),
    .rd_okb_o    (rd_okb),
    .rd_oa_o     (rd_oa)
  );

  // ---- AB: the issued context's read data, registered -----------------------------------------
  logic       ab_oka_q, ab_okb_q;
  rgb_t       ab_a_q, ab_b_q, ab_oa_q, ab_ob_q;
  side_t      ab_side_q;
  metric_e    ab_metric_q;
  thr_t       ab_thr_q;
  // Each of these is read in part: the position's x / y go elsewhere.
  /* verilator lint_off UNUSEDSIGNAL */
  eng_pos_t   ab_pos_q;
  /* verilator lint_on UNUSEDSIGNAL */

  always_ff @(posedge clk_i) begin
    if (rd_valid_q) begin
      ab_a_q      <= rd_a;
      ab_b_q      <= ctx_rd_b[rd_ctx_q];
      ab_oa_q     <= rd_oa;     // A': port 2 where o2a, else the context's previous A
      ab_ob_q     <= rd_o2;     // B': port 2
      ab_oka_q    <= rd_oka;
      ab_okb_q    <= rd_okb;
      ab_pos_q    <= rd_pos_q;
      ab_side_q   <= rd_side_q;
      ab_side_q.fline    <= rd_fline;
      ab_side_q.o.ldelta <= rd_ldelta;
      ab_metric_q <= rd_metric_q;
      ab_thr_q    <= rd_thr_q;
    end
  end

  // ---- Decision pipeline and output buffer ----------------------------------------------------
  // Credits in flight per position: grant -> GR -> IS -> RD -> AB -> S0..S5 -> buffer -> out,
  // ~12 clocks; 16 (the next power of two) keeps one grant per clock.
  localparam int unsigned OUT_DEPTH = 16;

  // trace is formed before the output buffer, so the tag allocation starts at a register.
  typedef struct packed {
    logic   trace;
    logic   retro;      // lindilate: first a trace of the previous line's pixel
    rgb_t   rgb;
    oside_t side;
  } result_t;

  logic    pv_valid, pv_interp, out_valid, out_ready, ob_ready;
  logic    ob_valid, os_ready;
  side_t   pv_side;
  oside_t  out_side;
  rgb_t    pv_rgb, out_rgb;
  result_t pv_result, ob_result, out_result;
  logic [$clog2(OUT_DEPTH):0] credit_q, ob_count;
  // d is carried for waveforms only, and the pipeline never waits (ready_i is 1).
  /* verilator lint_off UNUSEDSIGNAL */
  diff_t   pv_diff;
  logic    pv_ready;
  /* verilator lint_on UNUSEDSIGNAL */

  msr_decision_pipe #(
    .USER_W ($bits(side_t))
  ) u_decision_pipe (
    .clk_i    (clk_i),
    .rst_ni   (rst_ni),
    .clear_i  (clear_i),
    .valid_i  (ab_valid_q),
    .ready_o  (pv_ready),
    .a_i      (ab_a_q),
    .b_i      (ab_b_q),
    .metric_i (ab_metric_q),
    .thr_i    (ab_thr_q),
    .gap_i    (ab_pos_q.init ? gap_t'(2) : ab_pos_q.gap),
    .off_i    (ab_pos_q.init ? gap_t'(1) : ab_pos_q.off),
    .nshift_i (ab_pos_q.nshift),
    .user_i   (ab_side_q),
    .valid_o  (pv_valid),
    .ready_i  (1'b1),
    .interp_o (pv_interp),
    .diff_o   (pv_diff),
    .rgb_o    (pv_rgb),
    .user_o   (pv_side)
  );

  // lindilate: msr_base_decision takes the same AB registers plus A' and B' and answers four
  // clocks later with Q; msr_lin_dilate aligns it with the pipeline and forms D = P or Q with
  // the pipeline's own P (the unit's P and D outputs are left open: synthesis drops them).
  logic base_q, pv_lin_interp, pv_retro;
  /* verilator lint_off UNUSEDSIGNAL */
  logic base_p, base_d;
  /* verilator lint_on UNUSEDSIGNAL */

  msr_base_decision u_base_decision (
    .clk_i        (clk_i),
    .en_i         (1'b1),
    .outer_a_i    (ab_oa_q),
    .outer_a_ok_i (ab_oka_q),
    .a_i          (ab_a_q),
    .b_i          (ab_b_q),
    .outer_b_i    (ab_ob_q),
    .outer_b_ok_i (ab_okb_q),
    .metric_i     (ab_metric_q),
    .thr_i        (ab_thr_q),
    .gap_i        (ab_pos_q.gap),
    .nshift_i     (ab_pos_q.nshift),
    .base_o       (base_d),
    .patent_o     (base_p),
    .second_o     (base_q)
  );

  assign pv_result = '{trace: pv_side.init || !(pv_side.lin ? pv_lin_interp : pv_interp),
                       retro: pv_retro, rgb: pv_rgb,
                       side: pv_side.o};

  msr_fifo #(
    .WIDTH ($bits(result_t)),
    .DEPTH (OUT_DEPTH)
  ) u_out_buf (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .flush_i (clear_i),
    .valid_i (pv_valid),
    .ready_o (ob_ready),
    .data_i  (pv_result),
    .valid_o (ob_valid),
    .ready_i (os_ready),
    .data_o  (ob_result),
    .count_o (ob_count)
  );

  // The output logic works on a register, not on the buffer's read multiplexer.
  msr_spill_reg #(
    .WIDTH ($bits(result_t))
  ) u_out_spill (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .clear_i (clear_i),
    .valid_i (ob_valid),
    .ready_o (os_ready),
    .data_i  (ob_result),
    .valid_o (out_valid),
    .ready_i (out_ready),
    .data_o  (out_result)
  );

  assign out_rgb  = out_result.rgb;
  assign out_side = out_result.side;

  // Credits: output-buffer slots not yet reserved by an issued position.
  localparam int unsigned CRED_W = $clog2(OUT_DEPTH) + 1;
  msr_clr_reg #(.WIDTH(CRED_W), .RESET(CRED_W'(OUT_DEPTH))) u_credit_q (
    .clk_i, .rst_ni, .clear_i, .en_i (1'b1),
    .d_i   (credit_q - CRED_W'(issue) + CRED_W'(ob_valid && os_ready)),
    .q_o   (credit_q)
  );

  assign can_issue = (credit_q != '0);

  // ---- Output: interpolate -> write, trace -> tag and render request -----------------------------
  logic               out_trace, out_write, retro_phase, alloc_tag, tag_avail;
  logic [TAG_W-1:0]   free_tag;
  coord_t             req_x, req_y;
  logic [TADDR_W-1:0] req_addr;

  assign out_trace = out_result.trace;

  msr_lin_dilate #(.NUM_CTX(NUM_CTX), .CTX_W(CTX_W)) u_lin_dilate (
    .clk_i           (clk_i),
    .rst_ni          (rst_ni),
    .clear_i         (clear_i),
    .base_q_i        (base_q),
    .pv_valid_i      (pv_valid),
    .pv_interp_i     (pv_interp),
    .pv_lin_i        (pv_side.lin),
    .pv_fline_i      (pv_side.fline),
    .pv_ctx_i        (pv_side.o.ctx),
    .pv_mh_i         (pv_side.mh),
    .pv_lin_interp_o (pv_lin_interp),
    .pv_retro_o      (pv_retro),
    .out_valid_i     (out_valid),
    .out_retro_i     (out_result.retro),
    .out_done_i      (out_valid && out_ready),
    .alloc_i         (alloc_tag),
    .out_vert_i      (out_side.vert),
    .out_x_i         (out_side.x),
    .out_y_i         (out_side.y),
    .out_gx_i        (out_side.gx),
    .out_gy_i        (out_side.gy),
    .out_ldelta_i    (out_side.ldelta),
    .retro_phase_o   (retro_phase),
    .req_x_o         (req_x),
    .req_y_o         (req_y),
    .req_addr_o      (req_addr)
  );

  msr_req_out #(.TAG_W(TAG_W)) u_req_out (
    .clk_i         (clk_i),
    .rst_ni        (rst_ni),
    .clear_i       (clear_i),
    .out_valid_i   (out_valid),
    .out_ready_o   (out_ready),
    .out_trace_i   (out_trace),
    .retro_phase_i (retro_phase),
    .out_write_o   (out_write),
    .req_x_i       (req_x),
    .req_y_i       (req_y),
    .tag_avail_i   (tag_avail),
    .free_tag_i    (free_tag),
    .alloc_tag_o   (alloc_tag),
    .req_valid_o   (req_valid_o),
    .req_ready_i   (req_ready_i),
    .req_x_o       (req_x_o),
    .req_y_o       (req_y_o),
    .req_tag_o     (req_tag_o)
  );

  // ---- Responses and tags -----------------------------------------------------------------------
  logic               r2_write;
  ctx_t               rsp_wctx;
  logic [TADDR_W-1:0] rsp_waddr;
  level_t             rsp_wlevel;
  rgb_t               rsp_wrgb;

  msr_rsp_check #(
    .MAX_OUTSTANDING (MAX_OUTSTANDING),
    .TAG_W           (TAG_W),
    .CTX_W           (CTX_W)
  ) u_rsp_check (
    .clk_i         (clk_i),
    .rst_ni        (rst_ni),
    .clear_i       (clear_i),
    .rsp_valid_i   (rsp_valid_i),
    .rsp_ready_o   (rsp_ready_o),
    .rsp_tag_i     (rsp_tag_i),
    .rsp_rgb_i     (rsp_rgb_i),
    .tag_avail_o   (tag_avail),
    .free_tag_o    (free_tag),
    .alloc_i       (alloc_tag),
    .alloc_ctx_i   (out_side.ctx),
    .alloc_addr_i  (req_addr),
    .alloc_level_i (out_side.level),
    .pipe_we_i     (out_write),
    .pipe_ctx_i    (out_side.ctx),
    .we_o          (r2_write),
    .wctx_o        (rsp_wctx),
    .waddr_o       (rsp_waddr),
    .wlevel_o      (rsp_wlevel),
    .wrgb_o        (rsp_wrgb),
    .drop_o        (rsp_drop_o),
    .inflight_o    (inflight_o),
    .tags_out_o    (tags_out_o),
    .init_o        (tags_init)
  );

  // ---- Writes: each context's one port, registered -----------------------------------------
  // The write reaches its context a clock after the output or R2 decided it: the contexts sit
  // across the engine's area, and the decision -> context path (its pending count's adder
  // behind) was the placed top's worst path at 10.9 ns. Nothing waits on a write but the
  // context itself (its pending count and pass barrier see the write when it lands), so the
  // register only delays a barrier by one clock. A clear drops a write on its way. A retro
  // request is one more pending write of its context (registered like the write).
  logic [NUM_CTX-1:0] ctx_we_d, ctx_retro_d;

  for (genvar c = 0; c < NUM_CTX; c++) begin : g_write
    logic pipe_we, rsp_we;
    assign pipe_we        = out_write && (out_side.ctx == ctx_t'(c));
    assign rsp_we         = r2_write && (rsp_wctx == ctx_t'(c));
    assign ctx_we_d[c]    = pipe_we || rsp_we;
    assign ctx_retro_d[c] = retro_phase && alloc_tag && (out_side.ctx == ctx_t'(c));

    // Data without an enable: it is used only with ctx_we_q.
    always_ff @(posedge clk_i) begin
      ctx_waddr_q[c] <= pipe_we ? {out_side.y, out_side.x} : rsp_waddr;
      ctx_wsrc_q[c]  <= pipe_we ? src_interp(out_side.level) : src_traced(rsp_wlevel);
      ctx_wrgb_q[c]  <= pipe_we ? out_rgb : rsp_wrgb;
    end
  end

  msr_clr_reg #(.WIDTH(2 * NUM_CTX)) u_write_q (
    .clk_i, .rst_ni, .clear_i, .en_i (1'b1), .d_i ({ctx_we_d, ctx_retro_d}),
    .q_o ({ctx_we_q, ctx_retro_q})
  );

  // ---- Output streamer ----------------------------------------------------------------------
  // Pick a full context (one cycle), start the streamer on it (next cycle), free it when its
  // last pixel has left.
  logic               str_arb_valid, streaming_q, str_start_q, str_start_ready;
  logic               streaming_d, str_start_d, str_pick;
  logic               str_re, str_done;
  logic [CTX_W-1:0]   str_sel, str_q, str_d;
  logic [TADDR_W-1:0] str_raddr;
  // The streamer needs the winner's index and the tile's origin and size only.
  /* verilator lint_off UNUSEDSIGNAL */
  tile_desc_t         str_desc;
  logic [NUM_CTX-1:0] str_gnt;
  /* verilator lint_on UNUSEDSIGNAL */

  msr_rr_arb #(.N(NUM_CTX), .IDX_W(CTX_W)) u_stream_arb (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .clear_i (clear_i),
    .req_i   (ctx_full),
    .gnt_o   (str_gnt),
    .idx_o   (str_sel),
    .valid_o (str_arb_valid),
    .ready_i (!streaming_q)
  );

  always_comb begin
    str_pick    = !streaming_q && str_arb_valid;
    streaming_d = !str_done && (str_pick || streaming_q);
    str_start_d = !(str_start_q && str_start_ready) && (str_pick || str_start_q);
    str_d       = str_pick ? str_sel : str_q;
  end

  msr_clr_reg #(.WIDTH(2 + CTX_W)) u_stream_q (
    .clk_i, .rst_ni, .clear_i, .en_i (1'b1), .d_i ({streaming_d, str_start_d, str_d}),
    .q_o ({streaming_q, str_start_q, str_q})
  );

  assign str_desc = ctx_desc[str_q];

  msr_tile_stream u_stream (
    .clk_i         (clk_i),
    .rst_ni        (rst_ni),
    .clear_i       (clear_i),
    .start_valid_i (str_start_q),
    .start_ready_o (str_start_ready),
    .x0_i          (str_desc.x0),
    .y0_i          (str_desc.y0),
    .w_i           (str_desc.w),
    .h_i           (str_desc.h),
    .re_o          (str_re),
    .raddr_o       (str_raddr),
    .rdata_rgb_i   (ctx_str_rgb[str_q]),
    .rdata_src_i   (ctx_str_src[str_q]),
    .pix_valid_o   (pix_valid_o),
    .pix_ready_i   (pix_ready_i),
    .pix_x_o       (pix_x_o),
    .pix_y_o       (pix_y_o),
    .pix_rgb_o     (pix_rgb_o),
    .pix_src_o     (pix_src_o),
    .pix_last_o    (pix_last_o),
    .done_o        (str_done)
  );

  for (genvar c = 0; c < NUM_CTX; c++) begin : g_stream_own
    assign ctx_str_own[c]  = streaming_q && (str_q == ctx_t'(c));
    assign ctx_str_done[c] = str_done && (str_q == ctx_t'(c));
  end

  // ---- The contexts themselves ----------------------------------------------------------------
  for (genvar c = 0; c < NUM_CTX; c++) begin : g_ctx
    msr_tile_ctx #(
      .PEND_W    (PEND_W),
      .LINDILATE (LINDILATE)
    ) u_ctx (
      .clk_i         (clk_i),
      .rst_ni        (rst_ni),
      .clear_i       (clear_i),
      .start_i       (ctx_start[c]),
      .desc_i        (desc_q),
      .free_o        (ctx_free[c]),
      .desc_o        (ctx_desc[c]),
      .cand_o        (ctx_cand[c]),
      .step_first_o  (ctx_pos[c].first),
      .step_x_o      (ctx_pos[c].x),
      .step_y_o      (ctx_pos[c].y),
      .step_gap_o    (ctx_pos[c].gap),
      .step_off_o    (ctx_pos[c].off),
      .step_level_o  (ctx_pos[c].level),
      .step_nshift_o (ctx_pos[c].nshift),
      .step_init_o   (ctx_pos[c].init),
      .step_dir_o    (ctx_pos[c].dir),
      .step_o2a_o    (ctx_pos[c].o2a),
      .issue_i       (ctx_issue[c]),
      .rd_a_o        (ctx_rd_a[c]),
      .rd_b_o        (ctx_rd_b[c]),
      .rd_o2_o       (ctx_rd_o2[c]),
      .retro_i       (ctx_retro_q[c]),
      .we_i          (ctx_we_q[c]),
      .waddr_i       (ctx_waddr_q[c]),
      .wsrc_i        (ctx_wsrc_q[c]),
      .wrgb_i        (ctx_wrgb_q[c]),
      .full_o        (ctx_full[c]),
      .str_own_i     (ctx_str_own[c]),
      .str_re_i      (str_re),
      .str_raddr_i   (str_raddr),
      .str_rgb_o     (ctx_str_rgb[c]),
      .str_src_o     (ctx_str_src[c]),
      .str_done_i    (ctx_str_done[c])
    );
    assign ctx_first[c] = ctx_pos[c].first;
  end

  assign busy_o = !(&ctx_free) || (|start_q) || tags_init;

  // ---- Checks -------------------------------------------------------------------------------------
  /* verilator lint_off SYNCASYNCNET */
  // Handshakes (outputs): valid held until ready, data stable.
  `MSR_ASSERT(a_req_hold, req_valid_o && !req_ready_i |=> req_valid_o &&
      $stable({req_x_o, req_y_o, req_tag_o}), clk_i, !rst_ni || clear_i)
  `MSR_ASSERT(a_pix_hold, pix_valid_o && !pix_ready_i |=> pix_valid_o &&
      $stable({pix_x_o, pix_y_o, pix_rgb_o, pix_src_o, pix_last_o}), clk_i, !rst_ni || clear_i)
  // Handshakes (inputs): the environment holds what it offers.
  `MSR_ASSUME(m_desc_hold, desc_valid_i && !desc_ready_o |=> desc_valid_i && $stable(desc_i),
      clk_i, !rst_ni || clear_i)
  `MSR_ASSUME(m_desc_legal, desc_valid_i |-> desc_i.w inside {[1 : MAX_TILE]} &&
      desc_i.h inside {[1 : MAX_TILE]} && desc_i.levels inside {[1 : MAX_LEVELS]})
  // Internal invariants.
  `MSR_ASSERT(a_one_writer, !(out_write && r2_write && out_side.ctx == rsp_wctx))
  `MSR_ASSERT(a_issue_onehot, $onehot0(ctx_issue))
  `MSR_ASSERT(a_out_buf_room, pv_valid |-> ob_ready)
  `MSR_ASSERT(a_credits, 32'(credit_q) + 32'(ob_count) <= OUT_DEPTH)
  // the line before is 1..8 away (rows of G_y(k-1), columns of G_x(k))
  `MSR_ASSERT(a_retro_delta, pv_valid && pv_side.lin && !pv_side.fline |->
      pv_side.o.ldelta inside {[1 : 8]})
  `MSR_COVER(c_retro, retro_phase && alloc_tag)
  `MSR_COVER(c_all_ctx_busy, ctx_free == '0)
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_tile_engine
