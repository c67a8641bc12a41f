// Tile engine: tiles in, their final pixels out (spec docs/spec/algorithm.md).
//
//   desc  : msr_ctx_alloc: the lowest free context c takes it (msr_tile_ctx: descriptor,
//           level controller, pass barrier, tile buffer)
//   issue : msr_ctx_issue: round robin over the contexts whose next position may go, the grant
//           registered (GR); the context's head leaves, its tile buffer reads B, A (and B')
//   IS, RD, AB : msr_operand_fetch: the position, its descriptor fields, its read data
//   msr_decision_pipe (6 stages): decide and interpolate; never stalls: a position is issued
//           only with a slot of the 16-entry output buffer reserved (msr_out_buf's credits)
//   out   : msr_req_out: interpolate -> write {16+k, C}; trace -> tag -> render request
//   rsp   : msr_rsp_check: the tag pool; each response checked -> write {k, rgb} to its context
//   writes: msr_ctx_write: each context's one write port, registered
//   drain : msr_ctx_drain (rtl/drain): full contexts, round robin --> msr_tile_stream --> pix
//           stream; with BUF_CYCLE > 1 several streamers, their rows merged (msr_row_merge)
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
// (in msr_operand_fetch: line tracking, the outer samples A', B' and their existence),
// msr_base_decision (beside the decision pipeline: Q) and msr_lin_dilate (the dilation's line
// store as decisions leave the pipeline, the retro request at the output).
//
// Registers: control flip-flops (valid bits, flags, counts) are msr_clr_reg instances (reset
// and clear_i); data registers that a valid bit qualifies are plain flip-flops without reset.
`include "msr_assert.svh"
`include "msr_flops.svh"

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
  // 1: the depth channel (docs/spec/reuse.md): every traced pixel's inverse depth comes with its
  // colour (rsp_invz_i), an interpolated one's is interpolated from the same neighbours
  // (msr_depth_interp), 16 more bits in each tile buffer's word, pix_invz_o with each pixel;
  // 0: none of it is built and pix_invz_o is 0.
  parameter int unsigned DEPTH_EN        = 0,
  // The tile buffers' read latency in clocks (1..4): 1, a block RAM or a fast SRAM; more, a
  // compiled macro that needs several clocks (docs/asic.md). The operand fetch waits as many
  // clocks for the data, so a context still issues one position a clock.
  parameter int unsigned RD_LAT          = 1,
  // The largest tile edge the tile buffers hold (8, 16 or 32): TILE_LIMIT^2 words a context.
  // A standard-cell build whose tiles stay at 16 keeps a quarter of the bits (docs/asic.md);
  // a larger tile is refused by the top's configuration check.
  parameter int unsigned TILE_LIMIT      = MAX_TILE,
  // The tile buffers' cycle in clocks (1..8): a macro that takes an address on a port only once
  // per BUF_CYCLE clocks (the cited 180 nm macro: 5 at 200 MHz, docs/asic.md). Each context's
  // decisions are then granted at most once per BUF_CYCLE clocks (the other contexts fill the
  // clocks between) and its writes likewise (an answer first, the output's write waits); the
  // streamer reads a finished tile from the buffer's two copies in turn, two pixels per
  // BUF_CYCLE clocks.
  parameter int unsigned BUF_CYCLE       = 1,
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
  input  logic [15:0]      rsp_invz_i,     // DEPTH_EN: the traced pixel's inverse depth (0: sky)
  output logic             pix_valid_o,    // finished pixels of the tile, row-major, global coords
  input  logic             pix_ready_i,
  output coord_t           pix_x_o,
  output coord_t           pix_y_o,
  output rgb_t             pix_rgb_o,
  output src_t             pix_src_o,
  output logic [15:0]      pix_invz_o,     // DEPTH_EN: the pixel's inverse depth (else 0)
  output logic             pix_last_o,     // last pixel of the tile
  output logic             busy_o,         // tile accepted and not yet fully emitted, or tags being reset
  output logic             rsp_drop_o,     // pulse: a response whose tag was not in flight was dropped
  output logic [$clog2(MAX_OUTSTANDING):0] inflight_o, // render requests in flight (tests, waves)
  output logic             tags_out_o      // registered: a request may be in flight (0: none is)
  // verilog_lint: waive-stop line-length
);

  localparam int unsigned CTX_W  = (NUM_CTX > 1) ? $clog2(NUM_CTX) : 1;
  // The output buffer's slots: the credits of the positions between the grant and the buffer's
  // output (msr_out_buf), about 12 clocks; twice as many for reads of more than a clock.
  localparam int unsigned OUT_DEPTH_RD1 = 16;
  localparam int unsigned OUT_DEPTH     = (RD_LAT > 1) ? 2 * OUT_DEPTH_RD1 : OUT_DEPTH_RD1;
  // Positions of one context issued and not yet written: at most the pipeline plus its tags.
  localparam int unsigned PEND_W = $clog2(MAX_OUTSTANDING + OUT_DEPTH) + 1;
  // A pixel's data on its way into a context: the colour, with DEPTH_EN {inverse depth, colour}.
  localparam int unsigned PIX_W  = $bits(rgb_t) + ((DEPTH_EN != 0) ? 16 : 0);

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
  if (DEPTH_EN > 1) begin : g_check_depth
    $fatal(1, "msr_tile_engine: DEPTH_EN %0d must be 0 or 1", DEPTH_EN);
  end
  if (RD_LAT < 1 || RD_LAT > 4) begin : g_check_rd_lat
    $fatal(1, "msr_tile_engine: RD_LAT %0d must be in 1..4", RD_LAT);
  end
  if (!(TILE_LIMIT inside {8, 16, 32})) begin : g_check_tile_limit
    $fatal(1, "msr_tile_engine: TILE_LIMIT %0d must be 8, 16 or 32", TILE_LIMIT);
  end
  if (BUF_CYCLE < 1 || BUF_CYCLE > 8) begin : g_check_buf_cycle
    $fatal(1, "msr_tile_engine: BUF_CYCLE %0d must be in 1..8", BUF_CYCLE);
  end

  // ---- Contexts ---------------------------------------------------------------------------------
  logic       [NUM_CTX-1:0] ctx_free, ctx_full, ctx_cand_tail, ctx_cand_head, ctx_start;
  // the head is the first position of its pass (waveforms, scripts/bench_engine.py)
  /* verilator lint_off UNUSEDSIGNAL */
  logic       [NUM_CTX-1:0] ctx_first;
  /* verilator lint_on UNUSEDSIGNAL */
  tile_desc_t [NUM_CTX-1:0] ctx_desc;
  eng_pos_t   [NUM_CTX-1:0] ctx_pos;
  rgb_t       [NUM_CTX-1:0] ctx_rd_a, ctx_rd_b, ctx_rd_o2, ctx_str_rgb;
  src_t       [NUM_CTX-1:0] ctx_str_src;
  logic       [NUM_CTX-1:0] ctx_str_own, ctx_str_done;
  logic       [NUM_CTX-1:0] ctx_we, ctx_retro;
  logic       [NUM_CTX-1:0][TADDR_W-1:0] ctx_waddr;
  src_t       [NUM_CTX-1:0] ctx_wsrc;
  logic       [NUM_CTX-1:0][PIX_W-1:0] ctx_wpix;
  logic       [NUM_CTX-1:0][15:0] ctx_rd_wa, ctx_rd_wb, ctx_str_invz, ctx_winvz;

  // ---- Tile start (msr_ctx_alloc) and issue (msr_ctx_issue) ---------------------------------
  logic               tags_init, issue, can_issue, gr_valid;
  logic [NUM_CTX-1:0] gr_gnt;
  tile_desc_t         alloc_desc;
  ctx_t               gr_ctx;
  eng_pos_t           iss_pos;

  msr_ctx_alloc #(.NUM_CTX(NUM_CTX), .CTX_W(CTX_W)) u_ctx_alloc (
    .clk_i, .rst_ni, .clear_i,
    .ctx_free_i (ctx_free), .hold_i (tags_init),
    .desc_valid_i, .desc_ready_o, .desc_i,
    .start_o (ctx_start), .desc_o (alloc_desc)
  );

  msr_ctx_issue #(.NUM_CTX(NUM_CTX), .CTX_W(CTX_W), .CYCLE(BUF_CYCLE)) u_ctx_issue (
    .clk_i, .rst_ni, .clear_i,
    .cand_tail_i (ctx_cand_tail), .cand_head_i (ctx_cand_head), .pos_i (ctx_pos),
    .can_issue_i (can_issue), .issue_o (issue),
    .gr_valid_o (gr_valid), .gr_gnt_o (gr_gnt), .gr_ctx_o (gr_ctx), .gr_pos_o (iss_pos)
  );

  // ---- The grant as the operand fetch sees it: RD_LAT - 1 clocks later -----------------------
  // The tile buffers take the address on the grant (GR); their data is there RD_LAT clocks
  // later, then registered beside the memory. The operand fetch's stages stay as they are,
  // behind a delay of the grant: with RD_LAT 1 none.
  logic               of_valid;
  logic [NUM_CTX-1:0] of_gnt;
  ctx_t               of_ctx;
  eng_pos_t           of_pos;

  if (RD_LAT > 1) begin : g_gr_delay
    logic [RD_LAT-2:0]                         dv_q;
    logic [RD_LAT-2:0][NUM_CTX-1:0]            dgnt_q;
    logic [RD_LAT-2:0][CTX_W-1:0]              dctx_q;
    logic [RD_LAT-2:0][$bits(eng_pos_t)-1:0]   dpos_q;
    `MSR_CLR_REG(u_dv_q, RD_LAT - 1, clear_i, 1'b1, (RD_LAT - 1)'({dv_q, gr_valid}), dv_q)
    always_ff @(posedge clk_i) begin
      dgnt_q <= ((RD_LAT - 1) * NUM_CTX)'({dgnt_q, gr_gnt});
      dctx_q <= ((RD_LAT - 1) * CTX_W)'({dctx_q, gr_ctx});
      dpos_q <= ((RD_LAT - 1) * $bits(eng_pos_t))'({dpos_q, iss_pos});
    end
    assign of_valid = dv_q[RD_LAT-2];
    assign of_gnt   = dgnt_q[RD_LAT-2];   // read under of_valid only
    assign of_ctx   = dctx_q[RD_LAT-2];
    assign of_pos   = eng_pos_t'(dpos_q[RD_LAT-2]);
  end else begin : g_gr_now
    assign of_valid = gr_valid;
    assign of_gnt   = gr_gnt;
    assign of_ctx   = gr_ctx;
    assign of_pos   = iss_pos;
  end

  // ---- Operands: GR -> IS -> RD -> AB (msr_operand_fetch) -----------------------------------
  logic                ab_valid, ab_lin, ab_fline, ab_oka, ab_okb, rd_valid;
  ctx_t                ab_ctx, rd_ctx;
  /* verilator lint_off UNUSEDSIGNAL */
  eng_pos_t            ab_pos;      // o2a and first are used before AB
  /* verilator lint_on UNUSEDSIGNAL */
  coord_t              ab_gx, ab_gy;
  metric_e             ab_metric;
  thr_t                ab_thr;
  rgb_t                ab_a, ab_b, ab_oa, ab_ob;
  logic [LCOORD_W-2:0] ab_mh;
  logic [3:0]          ab_ldelta;

  msr_operand_fetch #(.NUM_CTX(NUM_CTX), .CTX_W(CTX_W), .LINDILATE(LINDILATE)) u_operand_fetch (
    .clk_i, .rst_ni, .clear_i,
    .gr_valid_i (of_valid), .gr_gnt_i (of_gnt), .gr_ctx_i (of_ctx), .gr_pos_i (of_pos),
    .desc_i (ctx_desc), .rd_a_i (ctx_rd_a), .rd_b_i (ctx_rd_b), .rd_o2_i (ctx_rd_o2),
    .rd_valid_o (rd_valid), .rd_ctx_o (rd_ctx),
    .valid_o (ab_valid), .ctx_o (ab_ctx), .pos_o (ab_pos), .gx_o (ab_gx), .gy_o (ab_gy),
    .metric_o (ab_metric), .thr_o (ab_thr), .a_o (ab_a), .b_o (ab_b),
    .lin_o (ab_lin), .mh_o (ab_mh), .fline_o (ab_fline), .ldelta_o (ab_ldelta),
    .oa_o (ab_oa), .oka_o (ab_oka), .ob_o (ab_ob), .okb_o (ab_okb)
  );

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

  side_t ab_side;
  assign ab_side = '{o: '{ctx: ab_ctx, x: ab_pos.x, y: ab_pos.y, gx: ab_gx, gy: ab_gy,
                          level: ab_pos.level, vert: ab_pos.dir == DIR_V, ldelta: ab_ldelta},
                     init: ab_pos.init, lin: ab_lin, mh: ab_mh, fline: ab_fline};

  // ---- Decision pipeline and output buffer (msr_out_buf: the credits) -----------------------

  // trace is formed before the output buffer, so the tag allocation starts at a register.
  typedef struct packed {
    logic   trace;
    logic   retro;      // lindilate: first a trace of the previous line's pixel
    rgb_t   rgb;
    oside_t side;
  } result_t;

  logic    pv_valid, pv_interp, out_valid, out_ready;
  side_t   pv_side;
  oside_t  out_side;
  rgb_t    pv_rgb, out_rgb;
  result_t pv_result, out_result;
  // d is carried for waveforms only, and the pipeline never waits (ready_i is 1).
  /* verilator lint_off UNUSEDSIGNAL */
  diff_t   pv_diff;
  logic    pv_ready;
  /* verilator lint_on UNUSEDSIGNAL */

  msr_decision_pipe #(
    .USER_W ($bits(side_t))
  ) u_decision_pipe (
    .clk_i, .rst_ni, .clear_i,
    .valid_i  (ab_valid), .ready_o (pv_ready),
    .a_i      (ab_a), .b_i (ab_b), .metric_i (ab_metric), .thr_i (ab_thr),
    .gap_i    (ab_pos.init ? gap_t'(2) : ab_pos.gap),
    .off_i    (ab_pos.init ? gap_t'(1) : ab_pos.off),
    .nshift_i (ab_pos.nshift), .user_i (ab_side),
    .valid_o  (pv_valid), .ready_i (1'b1),
    .interp_o (pv_interp), .diff_o (pv_diff), .rgb_o (pv_rgb), .user_o (pv_side)
  );

  // lindilate: msr_base_decision takes the same AB registers plus A' and B' and answers four
  // clocks later with Q; msr_lin_dilate aligns it with the pipeline and forms D = P or Q with
  // the pipeline's own P (the unit's P and D outputs are left open: synthesis drops them).
  logic base_q, pv_lin_interp, pv_retro;
  /* verilator lint_off UNUSEDSIGNAL */
  logic base_p, base_d;
  /* verilator lint_on UNUSEDSIGNAL */

  msr_base_decision u_base_decision (
    .clk_i, .en_i (1'b1),
    .outer_a_i (ab_oa), .outer_a_ok_i (ab_oka), .a_i (ab_a),
    .b_i       (ab_b),  .outer_b_i    (ab_ob),  .outer_b_ok_i (ab_okb),
    .metric_i (ab_metric), .thr_i (ab_thr), .gap_i (ab_pos.gap), .nshift_i (ab_pos.nshift),
    .base_o (base_d), .patent_o (base_p), .second_o (base_q)
  );

  assign pv_result = '{trace: pv_side.init || !(pv_side.lin ? pv_lin_interp : pv_interp),
                       retro: pv_retro, rgb: pv_rgb,
                       side: pv_side.o};

  // With DEPTH_EN the output buffer's word carries the interpolated inverse depth above the result.
  localparam int unsigned OUT_W = $bits(result_t) + ((DEPTH_EN != 0) ? 16 : 0);
  logic [OUT_W-1:0] pv_word, out_word;

  msr_out_buf #(.WIDTH(OUT_W), .DEPTH(OUT_DEPTH)) u_out_buf (
    .clk_i, .rst_ni, .clear_i,
    .issue_i (issue), .can_issue_o (can_issue),
    .valid_i (pv_valid), .data_i (pv_word),
    .valid_o (out_valid), .ready_i (out_ready), .data_o (out_word)
  );

  assign out_result = result_t'(out_word[$bits(result_t)-1:0]);
  assign out_rgb    = out_result.rgb;
  assign out_side   = out_result.side;

  // ---- Depth channel (DEPTH_EN): A's and B's inverse depth registered into AB beside the
  // colours, interpolated beside the decision pipeline (the same advance and stages), and
  // carried to the output in the output buffer's word, above the result.
  logic [PIX_W-1:0] out_pix, rsp_pix;

  if (DEPTH_EN != 0) begin : g_depth
    logic [15:0] ab_wa_q, ab_wb_q, pv_invz, out_invz;
    logic        pv_invz_valid;

    always_ff @(posedge clk_i) begin
      if (rd_valid) begin
        ab_wa_q <= ctx_rd_wa[rd_ctx];
        ab_wb_q <= ctx_rd_wb[rd_ctx];
      end
    end

    msr_depth_interp u_depth_interp (
      .clk_i, .rst_ni, .clear_i,
      .advance_i (pv_ready), .valid_i (ab_valid),
      .wa_i (ab_wa_q), .wb_i (ab_wb_q),
      .gap_i (ab_pos.init ? gap_t'(2) : ab_pos.gap),
      .off_i (ab_pos.init ? gap_t'(1) : ab_pos.off),
      .valid_o (pv_invz_valid), .invz_o (pv_invz)
    );

    assign pv_word  = {pv_invz, pv_result};
    assign out_invz = out_word[OUT_W-1 -: 16];
    assign out_pix  = {out_invz, out_rgb};
    assign rsp_pix  = {rsp_invz_i, rsp_rgb_i};
    for (genvar c = 0; c < NUM_CTX; c++) begin : g_winvz
      assign ctx_winvz[c] = ctx_wpix[c][PIX_W-1 -: 16];
    end

    // the depth moves in step with the decision
    /* verilator lint_off SYNCASYNCNET */
    `MSR_ASSERT(a_depth_in_step, pv_invz_valid == pv_valid)
    /* verilator lint_on SYNCASYNCNET */
  end else begin : g_no_depth
    /* verilator lint_off UNUSEDSIGNAL */
    logic             rd_unused;
    logic [15:0]      rsp_invz_unused;
    logic [NUM_CTX-1:0][15:0] ctx_rd_w_unused;
    /* verilator lint_on UNUSEDSIGNAL */
    assign rd_unused       = rd_valid ^ (^rd_ctx);
    assign rsp_invz_unused = rsp_invz_i;
    assign ctx_rd_w_unused = ctx_rd_wa ^ ctx_rd_wb;
    assign pv_word         = pv_result;
    assign out_pix         = out_rgb;
    assign rsp_pix         = rsp_rgb_i;
    assign ctx_winvz       = '0;
  end

  // ---- Output: interpolate -> write, trace -> tag and render request -----------------------------
  logic               out_write, retro_phase, alloc_tag, tag_avail, out_wr_ok;
  logic [TAG_W-1:0]   free_tag;
  coord_t             req_x, req_y;
  logic [TADDR_W-1:0] req_addr;

  msr_lin_dilate #(.NUM_CTX(NUM_CTX), .CTX_W(CTX_W)) u_lin_dilate (
    .clk_i, .rst_ni, .clear_i,
    .base_q_i (base_q),
    .pv_valid_i (pv_valid), .pv_interp_i (pv_interp), .pv_lin_i (pv_side.lin),
    .pv_fline_i (pv_side.fline), .pv_ctx_i (pv_side.o.ctx), .pv_mh_i (pv_side.mh),
    .pv_lin_interp_o (pv_lin_interp), .pv_retro_o (pv_retro),
    .out_valid_i (out_valid), .out_retro_i (out_result.retro),
    .out_done_i (out_valid && out_ready), .alloc_i (alloc_tag),
    .out_vert_i (out_side.vert), .out_x_i (out_side.x), .out_y_i (out_side.y),
    .out_gx_i (out_side.gx), .out_gy_i (out_side.gy), .out_ldelta_i (out_side.ldelta),
    .retro_phase_o (retro_phase), .req_x_o (req_x), .req_y_o (req_y), .req_addr_o (req_addr)
  );

  msr_req_out #(.TAG_W(TAG_W)) u_req_out (
    .clk_i, .rst_ni, .clear_i,
    .out_valid_i (out_valid), .out_ready_o (out_ready), .out_trace_i (out_result.trace),
    .retro_phase_i (retro_phase), .wr_ok_i (out_wr_ok), .out_write_o (out_write),
    .req_x_i (req_x), .req_y_i (req_y),
    .tag_avail_i (tag_avail), .free_tag_i (free_tag), .alloc_tag_o (alloc_tag),
    .req_valid_o, .req_ready_i, .req_x_o, .req_y_o, .req_tag_o
  );

  // ---- Responses and tags -----------------------------------------------------------------------
  logic               r2_write;
  ctx_t               rsp_wctx;
  logic [TADDR_W-1:0] rsp_waddr;
  level_t             rsp_wlevel;
  logic [PIX_W-1:0]   rsp_wpix;
  logic [NUM_CTX-1:0] ctx_wfree;           // msr_ctx_write: each context's port may be written
  logic               rsp_port_ok, rsp_pipe_we;

  // Who writes a context first when both would: with one-clock ports the output (it never waits,
  // the answer waits a clock); with a macro's cycle the answer (msr_ctx_write), and the output's
  // write waits for its port, as a traced result waits for a tag.
  if (BUF_CYCLE > 1) begin : g_port_cycle
    assign rsp_port_ok = ctx_wfree[rsp_wctx];
    assign rsp_pipe_we = 1'b0;
    assign out_wr_ok   = ctx_wfree[out_side.ctx] && !(r2_write && rsp_wctx == out_side.ctx);
  end else begin : g_port_every_clock
    // every port is free every clock (msr_ctx_write's free_o is all ones)
    /* verilator lint_off UNUSEDSIGNAL */
    logic [NUM_CTX-1:0] wfree_unused;
    /* verilator lint_on UNUSEDSIGNAL */
    assign wfree_unused = ctx_wfree;
    assign rsp_port_ok = 1'b1;
    assign rsp_pipe_we = out_write;
    assign out_wr_ok   = 1'b1;
  end

  msr_rsp_check #(
    .MAX_OUTSTANDING (MAX_OUTSTANDING),
    .TAG_W           (TAG_W),
    .CTX_W           (CTX_W),
    .DATA_W          (PIX_W)
  ) u_rsp_check (
    .clk_i, .rst_ni, .clear_i,
    .rsp_valid_i, .rsp_ready_o, .rsp_tag_i, .rsp_rgb_i (rsp_pix),
    .tag_avail_o (tag_avail), .free_tag_o (free_tag),
    .alloc_i (alloc_tag), .alloc_ctx_i (out_side.ctx), .alloc_addr_i (req_addr),
    .alloc_level_i (out_side.level), .pipe_we_i (rsp_pipe_we), .pipe_ctx_i (out_side.ctx),
    .port_ok_i (rsp_port_ok),
    .we_o (r2_write), .wctx_o (rsp_wctx), .waddr_o (rsp_waddr), .wlevel_o (rsp_wlevel),
    .wrgb_o (rsp_wpix),
    .drop_o (rsp_drop_o), .inflight_o, .tags_out_o, .init_o (tags_init)
  );

  // ---- Writes: each context's one port, registered (msr_ctx_write) ---------------------------
  msr_ctx_write #(.NUM_CTX(NUM_CTX), .CTX_W(CTX_W), .DATA_W(PIX_W), .CYCLE(BUF_CYCLE)) u_ctx_write (
    .clk_i, .rst_ni, .clear_i,
    .out_write_i (out_write), .out_retro_i (retro_phase && alloc_tag), .out_ctx_i (out_side.ctx),
    .out_x_i (out_side.x), .out_y_i (out_side.y), .out_level_i (out_side.level),
    .out_rgb_i (out_pix),
    .rsp_write_i (r2_write), .rsp_ctx_i (rsp_wctx), .rsp_addr_i (rsp_waddr),
    .rsp_level_i (rsp_wlevel), .rsp_rgb_i (rsp_wpix),
    .we_o (ctx_we), .retro_o (ctx_retro), .waddr_o (ctx_waddr), .wsrc_o (ctx_wsrc),
    .wrgb_o (ctx_wpix), .free_o (ctx_wfree)
  );

  // ---- Finished tiles out (msr_ctx_drain) -----------------------------------------------------
  logic [NUM_CTX-1:0]              str_re;
  logic [NUM_CTX-1:0][TADDR_W-1:0] str_raddr;
  pix_word_t          pix_word;            // the engine's ports stay flat for the benches
  assign {pix_x_o, pix_y_o, pix_rgb_o, pix_src_o, pix_last_o} = pix_word;

  msr_ctx_drain #(
    .NUM_CTX(NUM_CTX), .CTX_W(CTX_W), .DEPTH_EN(DEPTH_EN), .RD_LAT(RD_LAT), .CYCLE(BUF_CYCLE),
    .TILE_LIMIT(TILE_LIMIT)
  ) u_ctx_drain (
    .clk_i, .rst_ni, .clear_i,
    .full_i (ctx_full), .desc_i (ctx_desc), .own_o (ctx_str_own),
    .re_o (str_re), .raddr_o (str_raddr), .rgb_i (ctx_str_rgb), .src_i (ctx_str_src),
    .invz_i (ctx_str_invz),
    .done_o (ctx_str_done),
    .pix_valid_o, .pix_ready_i, .pix_o (pix_word), .pix_invz_o
  );

  // ---- The contexts themselves ----------------------------------------------------------------
  for (genvar c = 0; c < NUM_CTX; c++) begin : g_ctx
    msr_tile_ctx #(
      .PEND_W    (PEND_W),
      .LINDILATE (LINDILATE),
      .DEPTH_EN  (DEPTH_EN),
      .RD_LAT    (RD_LAT),
      .TILE_LIMIT (TILE_LIMIT),
      .BUF_CYCLE  (BUF_CYCLE)
    ) u_ctx (
      .clk_i, .rst_ni, .clear_i,
      .start_i (ctx_start[c]), .desc_i (alloc_desc), .free_o (ctx_free[c]),
      .desc_o (ctx_desc[c]), .cand_tail_o (ctx_cand_tail[c]), .cand_head_o (ctx_cand_head[c]),
      .step_o (ctx_pos[c]), .issue_i (gr_gnt[c]),
      .rd_a_o (ctx_rd_a[c]), .rd_b_o (ctx_rd_b[c]), .rd_o2_o (ctx_rd_o2[c]),
      .rd_wa_o (ctx_rd_wa[c]), .rd_wb_o (ctx_rd_wb[c]),
      .retro_i (ctx_retro[c]), .we_i (ctx_we[c]), .waddr_i (ctx_waddr[c]),
      .wsrc_i (ctx_wsrc[c]), .wrgb_i (rgb_t'(ctx_wpix[c][$bits(rgb_t)-1:0])),
      .winvz_i (ctx_winvz[c]), .full_o (ctx_full[c]),
      .str_own_i (ctx_str_own[c]), .str_re_i (str_re[c]), .str_raddr_i (str_raddr[c]),
      .str_rgb_o (ctx_str_rgb[c]), .str_src_o (ctx_str_src[c]), .str_invz_o (ctx_str_invz[c]),
      .str_done_i (ctx_str_done[c])
    );
    assign ctx_first[c] = ctx_pos[c].first;
  end

  assign busy_o = !(&ctx_free) || (|ctx_start) || tags_init;

  // ---- Checks -------------------------------------------------------------------------------------
  /* verilator lint_off SYNCASYNCNET */
  // Handshakes (outputs): valid held until ready, data stable.
  `MSR_ASSERT_NXT(a_req_hold, req_valid_o && !req_ready_i, req_valid_o &&
      $stable({req_x_o, req_y_o, req_tag_o}), clk_i, !rst_ni || clear_i)
  `MSR_ASSERT_NXT(a_pix_hold, pix_valid_o && !pix_ready_i, pix_valid_o &&
      $stable(pix_word), clk_i, !rst_ni || clear_i)
  // Handshakes (inputs): the environment holds what it offers.
  `MSR_ASSUME_NXT(m_desc_hold, desc_valid_i && !desc_ready_o, desc_valid_i && $stable(desc_i),
      clk_i, !rst_ni || clear_i)
  `MSR_ASSUME_IMP(m_desc_legal, desc_valid_i, desc_i.w inside {[1 : MAX_TILE]} &&
      desc_i.h inside {[1 : MAX_TILE]} && desc_i.levels inside {[1 : MAX_LEVELS]})
  // Internal invariants.
  `MSR_ASSERT(a_issue_onehot, $onehot0(gr_gnt))
  // the line before is 1..8 away (rows of G_y(k-1), columns of G_x(k))
  `MSR_ASSERT_IMP(a_retro_delta, pv_valid && pv_side.lin && !pv_side.fline,
      pv_side.o.ldelta inside {[1 : 8]})
  `MSR_COVER(c_retro, retro_phase && alloc_tag)
  `MSR_COVER(c_all_ctx_busy, ctx_free == '0)
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_tile_engine
