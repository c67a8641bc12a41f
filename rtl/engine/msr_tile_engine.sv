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
//   out  : interpolate -> write {16+k, C} into the context's buffer (a registered port);
//          trace -> tag (msr_tag_pool) -> render request {x0+x, y0+y, tag} (spill register)
//   rsp  : spill register -> R1 (tag looked up, checked in flight) -> write {k, rgb} into
//          the tag's context, unless the pipeline writes that context in the same cycle
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
  // The pass-start flags: the lindilate line trackers (the barrier itself lives in each
  // context).
  logic       [NUM_CTX-1:0] ctx_first;
  tile_desc_t [NUM_CTX-1:0] ctx_desc;
  lcoord_t    [NUM_CTX-1:0] ctx_x, ctx_y;
  gap_t       [NUM_CTX-1:0] ctx_gap, ctx_off;
  level_t     [NUM_CTX-1:0] ctx_level;
  logic       [NUM_CTX-1:0][1:0] ctx_nshift;
  logic       [NUM_CTX-1:0] ctx_init;
  dir_e       [NUM_CTX-1:0] ctx_dir;
  logic       [NUM_CTX-1:0] ctx_o2a, ctx_retro;
  rgb_t       [NUM_CTX-1:0] ctx_rd_a, ctx_rd_b, ctx_rd_o2, ctx_str_rgb;
  src_t       [NUM_CTX-1:0] ctx_str_src;
  logic       [NUM_CTX-1:0] ctx_we, ctx_str_own, ctx_str_done;
  logic       [NUM_CTX-1:0][TADDR_W-1:0] ctx_waddr;
  src_t       [NUM_CTX-1:0] ctx_wsrc;
  rgb_t       [NUM_CTX-1:0] ctx_wrgb;

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

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      alloc_q    <= '0;
      any_free_q <= 1'b0;
      start_q    <= '0;
    end else if (clear_i) begin
      alloc_q    <= alloc;
      any_free_q <= 1'b0;
      start_q    <= '0;
    end else begin
      alloc_q    <= alloc;
      any_free_q <= !none_avail;
      start_q    <= hs_onehot;
    end
  end

  always_ff @(posedge clk_i) begin
    if (desc_hs) desc_q <= desc_i;
  end

  assign ctx_start = start_q;

  // ---- Issue ----------------------------------------------------------------------------------
  logic             arb_valid, can_issue, issue;
  logic [CTX_W-1:0] gnt_idx;
  logic [NUM_CTX-1:0] gnt;

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

  // No stage between the issue and the output buffer ever stalls: a position is granted only
  // with a free slot in that buffer reserved for it (a credit), so the pipeline registers need
  // no enable and the issue does not wait on the output's handshake.
  //
  // The grant is registered (GR): the arbiter's output goes into flip-flops beside it, and the
  // contexts, spread over the die with their tile buffers, see a register one clock later
  // (their issue_i: the head leaves, the buffer reads it). The contexts' candidate bits know
  // about the grant in flight, so a context can still win every clock.
  assign issue = arb_valid && can_issue;

  logic               gr_valid_q;
  logic [NUM_CTX-1:0] gr_gnt_q;
  ctx_t               gr_ctx;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      gr_valid_q <= 1'b0;
      gr_gnt_q   <= '0;
    end else if (clear_i) begin
      gr_valid_q <= 1'b0;
      gr_gnt_q   <= '0;
    end else begin
      gr_valid_q <= issue;
      gr_gnt_q   <= gnt & {NUM_CTX{can_issue}};
    end
  end

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
  // init stays the last field (scripts/bench_engine.py reads it as bit 0).
  typedef struct packed {
    dir_e       dir;
    logic       o2a;       // lindilate: A' comes from port 2 (else the context's last A)
    logic       first;     // the first position of its pass
    lcoord_t    x;
    lcoord_t    y;
    gap_t       gap;
    gap_t       off;
    level_t     level;
    logic [1:0] nshift;
    logic       init;
  } pos_t;

  pos_t iss_pos;
  pos_t [NUM_CTX-1:0] ctx_pos;
  for (genvar c = 0; c < NUM_CTX; c++) begin : g_pos
    assign ctx_pos[c] = '{dir: ctx_dir[c], o2a: ctx_o2a[c], first: ctx_first[c],
                          x: ctx_x[c], y: ctx_y[c], gap: ctx_gap[c], off: ctx_off[c],
                          level: ctx_level[c], nshift: ctx_nshift[c], init: ctx_init[c]};
  end
  always_comb begin
    iss_pos = '0;
    for (int unsigned c = 0; c < NUM_CTX; c++) begin
      iss_pos |= ctx_pos[c] & {$bits(pos_t){gr_gnt_q[c]}};
    end
  end

  // ---- IS: the issue registers (the buffer reads happen in the GR cycle) ----------------------
  logic is_valid_q;
  ctx_t is_ctx_q;
  pos_t is_pos_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      is_valid_q <= 1'b0;
    end else if (clear_i) begin
      is_valid_q <= 1'b0;
    end else begin
      is_valid_q <= gr_valid_q;
    end
  end

  // No enable: is_valid_q says whether they hold an issue (an enable would hang the grant's
  // fan-out on every one of these flip-flops).
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
  logic       rd_valid_q;
  ctx_t       rd_ctx_q;
  side_t      rd_side_q;
  metric_e    rd_metric_q;
  thr_t       rd_thr_q;
  // Each of these is read in part: the position's x / y and the tile's size go elsewhere.
  /* verilator lint_off UNUSEDSIGNAL */
  pos_t       rd_pos_q;
  tile_desc_t is_desc;
  /* verilator lint_on UNUSEDSIGNAL */

  assign is_desc = ctx_desc[is_ctx_q];

  // ---- lindilate: the line trackers and the outer samples' existence, once per engine --------
  // Per context, the line of its last issued position and the line before it (a pass walks
  // its lines in order): read at IS for the issued position, updated at IS. fline / ldelta
  // (first line of the pass / distance to the line before) are formed RD -> AB.
  lcoord_t [NUM_CTX-1:0] ln_cur_q, ln_prev_q;
  logic    [NUM_CTX-1:0] ln_has_q;
  lcoord_t is_line, is_m;
  logic    is_newline;

  assign is_line    = (is_pos_q.dir == DIR_V) ? is_pos_q.x : is_pos_q.y;
  assign is_m       = (is_pos_q.dir == DIR_V) ? is_pos_q.y : is_pos_q.x;
  assign is_newline = is_line != ln_cur_q[is_ctx_q];

  // The trackers' update has issue registers of its own, taken from the grant: per context
  // "its first position of a pass" and "another position of a pass" (one-hot, so the update
  // needs no decode of is_ctx_q) and the position's line. The shared IS registers fan out to
  // the descriptor choice and the RD stage across the engine, and the path from them through
  // the tracker choice and the line compare into the trackers set the flat top's clock
  // (10.1 ns, 7.6 of them wire, seed 3, issue 31). The values are those of IS.
  logic [NUM_CTX-1:0] ln_first_q, ln_next_q;
  lcoord_t            ln_line_q, ln_cur_sel;
  msr_clr_reg #(.WIDTH(2 * NUM_CTX)) u_ln_upd_q (
    .clk_i, .rst_ni, .clear_i, .en_i (1'b1),
    .d_i ({gr_gnt_q & {NUM_CTX{gr_valid_q && !iss_pos.init && iss_pos.first}},
           gr_gnt_q & {NUM_CTX{gr_valid_q && !iss_pos.init && !iss_pos.first}}}),
    .q_o ({ln_first_q, ln_next_q})
  );
  always_ff @(posedge clk_i) begin
    ln_line_q <= (iss_pos.dir == DIR_V) ? iss_pos.x : iss_pos.y;
  end
  always_comb begin
    ln_cur_sel = '0;
    for (int unsigned c = 0; c < NUM_CTX; c++) ln_cur_sel |= ln_cur_q[c] & {LCOORD_W{ln_next_q[c]}};
  end

  always_ff @(posedge clk_i) begin
    for (int unsigned c = 0; c < NUM_CTX; c++) begin
      if (ln_first_q[c]) begin
        ln_cur_q[c] <= ln_line_q;
        ln_has_q[c] <= 1'b0;
      end else if (ln_next_q[c] && ln_line_q != ln_cur_sel) begin
        ln_prev_q[c] <= ln_cur_q[c];
        ln_cur_q[c]  <= ln_line_q;
        ln_has_q[c]  <= 1'b1;
      end
    end
  end

  // A' = a - g and B' = b + g on the position axis exist iff inside the tile and in G(k-1):
  // a multiple of n_k up to p, else border offset (r, k - 1) (docs/rules.md). IS -> RD: the
  // two positions and the axis's p, r, n - 1; RD -> AB: the membership tests.
  typedef logic [MAX_LEVELS-1:0][7:0] bm_row_t;       // [k - 1] for the levels 1..3
  function automatic bm_row_t bm_row(int unsigned r);
    bm_row_t t;
    for (int unsigned k = 0; k < MAX_LEVELS; k++) t[k] = border_set(r, k);
    return t;
  endfunction
  localparam bm_row_t BM_SET [8] = '{bm_row(0), bm_row(1), bm_row(2), bm_row(3),
                                     bm_row(4), bm_row(5), bm_row(6), bm_row(7)};

  function automatic logic in_grid(lcoord_t v, lcoord_t p, lcoord_t mask, logic [7:0] bm);
    logic [2:0] o;            // v - p < 8 wherever it is used
    o = 3'(v - p);
    return (v <= p) ? ((v & mask) == '0) : bm[o];
  endfunction

  logic [LCOORD_W:0] is_ap, is_bp, is_a;
  lcoord_t           is_nm1, is_smask;

  always_comb begin
    is_a     = (LCOORD_W+1)'(is_m) - (LCOORD_W+1)'(is_pos_q.off);
    is_ap    = is_a - (LCOORD_W+1)'(is_pos_q.gap);
    is_bp    = is_a + (LCOORD_W+1)'({is_pos_q.gap, 1'b0});
    is_nm1   = lcoord_t'(((is_pos_q.dir == DIR_V) ? is_desc.h : is_desc.w) - 1'b1);
    is_smask = (lcoord_t'(1) << is_desc.levels) - 1'b1;              // S - 1
  end

  logic              rd_first, rd_newline, rd_has;
  lcoord_t           rd_line, rd_cur, rd_prev, rd_nm1, rd_p, rd_nkmask;
  logic [2:0]        rd_r;
  level_t            rd_km1;
  logic [LCOORD_W:0] rd_ap, rd_bp;

  always_ff @(posedge clk_i) begin
    if (is_valid_q) begin
      rd_first   <= is_pos_q.first;
      rd_newline <= is_newline;
      rd_has     <= ln_has_q[is_ctx_q];
      rd_line    <= is_line;
      rd_cur     <= ln_cur_q[is_ctx_q];
      rd_prev    <= ln_prev_q[is_ctx_q];
      rd_ap      <= is_ap;
      rd_bp      <= is_bp;
      rd_nm1     <= is_nm1;
      rd_p       <= is_nm1 & ~is_smask;
      rd_r       <= 3'(is_nm1 & is_smask);
      rd_km1     <= is_pos_q.level - 1'b1;
      // n_k - 1 = (S >> (k - 1)) - 1
      rd_nkmask  <= is_smask >> (is_pos_q.level - 1'b1);
    end
  end

  logic       rd_fline, rd_oka, rd_okb;
  lcoord_t    rd_lprev;
  logic [7:0] rd_bm;

  always_comb begin
    rd_fline = rd_first || (!rd_newline && !rd_has);
    rd_lprev = rd_newline ? rd_cur : rd_prev;
    rd_bm    = BM_SET[rd_r][rd_km1];
    rd_oka   = !rd_ap[LCOORD_W] && in_grid(rd_ap[LCOORD_W-1:0], rd_p, rd_nkmask, rd_bm);
    rd_okb   = !rd_bp[LCOORD_W] && (rd_bp[LCOORD_W-1:0] <= rd_nm1) &&
               in_grid(rd_bp[LCOORD_W-1:0], rd_p, rd_nkmask, rd_bm);
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      rd_valid_q <= 1'b0;
    end else if (clear_i) begin
      rd_valid_q <= 1'b0;
    end else begin
      rd_valid_q <= is_valid_q;
    end
  end

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
                       mh: is_m[LCOORD_W-1:1], fline: 1'b0};
      rd_metric_q <= is_desc.metric;
      // threshold of the position's level; an initial-grid position gets 0 (always trace)
      rd_thr_q    <= is_pos_q.init ? '0 : is_desc.thr[is_pos_q.level - 1'b1];
    end
  end

  // ---- AB: the issued context's read data, registered -----------------------------------------
  logic       ab_valid_q, ab_oka_q, ab_okb_q;
  rgb_t       ab_a_q, ab_b_q, ab_oa_q, ab_ob_q;
  side_t      ab_side_q;
  metric_e    ab_metric_q;
  thr_t       ab_thr_q;
  // Each of these is read in part: the position's x / y go elsewhere.
  /* verilator lint_off UNUSEDSIGNAL */
  pos_t       ab_pos_q;
  /* verilator lint_on UNUSEDSIGNAL */

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      ab_valid_q <= 1'b0;
    end else if (clear_i) begin
      ab_valid_q <= 1'b0;
    end else begin
      ab_valid_q <= rd_valid_q;
    end
  end

  // Per context, the A of its last issued position (A' of the next position on the line,
  // fact 1 of the lindilate section in docs/architecture.md): written as AB takes the read
  // data, read the same clock for the position in RD (the old value: the previous issue).
  // A small memory: distributed RAM on an FPGA.
  rgb_t rd_a, last_a_mem [NUM_CTX];
  assign rd_a = ctx_rd_a[rd_ctx_q];

  always_ff @(posedge clk_i) begin
    if (rd_valid_q) last_a_mem[rd_ctx_q] <= rd_a;
  end

  always_ff @(posedge clk_i) begin
    if (rd_valid_q) begin
      ab_a_q      <= rd_a;
      ab_b_q      <= ctx_rd_b[rd_ctx_q];
      // A': port 2 where o2a, else the context's previous A; B': port 2
      ab_oa_q     <= rd_pos_q.o2a ? ctx_rd_o2[rd_ctx_q] : last_a_mem[rd_ctx_q];
      ab_ob_q     <= ctx_rd_o2[rd_ctx_q];
      ab_oka_q    <= rd_oka;
      ab_okb_q    <= rd_okb;
      ab_pos_q    <= rd_pos_q;
      ab_side_q   <= rd_side_q;
      ab_side_q.fline  <= rd_fline;
      ab_side_q.o.ldelta <= 4'(rd_line - rd_lprev);
      ab_metric_q <= rd_metric_q;
      ab_thr_q    <= rd_thr_q;
    end
  end

  // ---- Decision pipeline and output buffer ----------------------------------------------------
  // Credits in flight per position: grant -> GR -> IS -> RD -> AB -> S0..S5 -> buffer -> out,
  // ~12 clocks; 16 (the next power of two) keeps one grant per clock.
  localparam int unsigned OUT_DEPTH = 16;


  // trace is formed before the output buffer, so the tag allocation below starts at a register.
  typedef struct packed {
    logic   trace;
    logic   retro;      // lindilate: first a trace of the previous line's pixel (see below)
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

  // ---- lindilate: base decision D = P or Q beside the decision pipeline, and the dilation ----
  // msr_base_decision takes the same AB registers plus A' and B' and answers four clocks
  // later; two registers align its Q with the decision pipeline's six stages (neither
  // stalls). D = P or Q with the pipeline's own P: the unit's P and D outputs are left
  // open, so synthesis drops their logic.
  logic base_q, base_q1_q, base_q2_q, pv_base;
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

  always_ff @(posedge clk_i) begin
    base_q1_q <= base_q;
    base_q2_q <= base_q1_q;
  end
  assign pv_base = pv_interp || base_q2_q;

  // Dilation (docs/rules.md step 4) in decision order. A position's D is known when it
  // leaves the pipeline, the next line's only when the same position of the next line does.
  // So the position is interpolated (for now) iff D(l-) and D(l); when D(l+) fails later, a
  // retro trace of (l-, m) follows, and its render answer overwrites the interpolated pixel
  // (same final pixel and code as the rule, one request per traced pixel). Per context and
  // position index the line store keeps D of the last line and whether that line's pixel
  // was interpolated. The passes of a context leave the pipeline in order, so no clearing:
  // the first line of a pass reads nothing.
  // The store is a small memory (read and written at one address a clock, the read of the
  // old value): distributed RAM on an FPGA.
  localparam int unsigned DL_AW = CTX_W + LCOORD_W - 1;
  logic [1:0] dl_mem [NUM_CTX * 16];               // {D(l-), "(l-) was interpolated"}
  logic [1:0] dl_rd;
  logic [DL_AW-1:0] dl_addr;
  logic pv_dprev, pv_tprev, pv_lin_interp, pv_retro;

  assign dl_addr       = {pv_side.o.ctx, pv_side.mh};
  assign dl_rd         = dl_mem[dl_addr];
  assign pv_dprev      = pv_side.fline || dl_rd[1];
  assign pv_tprev      = !pv_side.fline && dl_rd[0];
  assign pv_lin_interp = pv_dprev && pv_base;
  assign pv_retro      = pv_side.lin && pv_tprev && !pv_base;

  always_ff @(posedge clk_i) begin
    if (pv_valid && pv_side.lin) begin
      dl_mem[dl_addr] <= {pv_base, pv_lin_interp};
    end
  end

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

  assign out_rgb    = out_result.rgb;
  assign out_side   = out_result.side;

  // Credits: output-buffer slots not yet reserved by an issued position.
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      credit_q <= ($clog2(OUT_DEPTH)+1)'(OUT_DEPTH);
    end else if (clear_i) begin
      credit_q <= ($clog2(OUT_DEPTH)+1)'(OUT_DEPTH);
    end else begin
      credit_q <= credit_q - ($clog2(OUT_DEPTH)+1)'(issue)
                           + ($clog2(OUT_DEPTH)+1)'(ob_valid && os_ready);
    end
  end

  assign can_issue = (credit_q != '0);

  // ---- Output: interpolate -> write, trace -> tag and render request -----------------------------
  typedef struct packed {
    ctx_t               ctx;
    logic [TADDR_W-1:0] addr;
    level_t             level;
  } tag_entry_t;

  typedef struct packed {
    coord_t           x;
    coord_t           y;
    logic [TAG_W-1:0] tag;
  } req_t;

  logic             out_trace, out_write, tag_avail, req_in_ready, alloc_tag, req_in_valid;
  logic             retro_phase, retro_sent_q;
  logic [TAG_W-1:0] free_tag;
  req_t             req_in, req_out;
  coord_t           rt_gx, rt_gy, rt_line_g;
  lcoord_t          rt_line;

  // A result with a retro trace takes two clocks: the retro request (the previous line's
  // pixel at the same position), then the result's own write or request.
  assign rt_line     = (out_side.vert ? out_side.x : out_side.y) - lcoord_t'(out_side.ldelta);
  assign rt_line_g   = (out_side.vert ? out_side.gx : out_side.gy) - coord_t'(out_side.ldelta);
  assign rt_gx       = out_side.vert ? rt_line_g : out_side.gx;
  assign rt_gy       = out_side.vert ? out_side.gy : rt_line_g;
  assign retro_phase = out_valid && out_result.retro && !retro_sent_q;
  assign req_in      = retro_phase ? '{x: rt_gx, y: rt_gy, tag: free_tag}
                                   : '{x: out_side.gx, y: out_side.gy, tag: free_tag};

  assign out_trace    = out_result.trace;
  assign out_write    = out_valid && !out_trace && !retro_phase;
  assign out_ready    = !retro_phase && (!out_trace || (tag_avail && req_in_ready));
  assign req_in_valid = out_valid && (out_trace || retro_phase) && tag_avail;
  assign alloc_tag    = req_in_valid && req_in_ready;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      retro_sent_q <= 1'b0;
    end else if (clear_i) begin
      retro_sent_q <= 1'b0;
    end else if (out_valid && out_ready) begin
      retro_sent_q <= 1'b0;
    end else if (retro_phase && alloc_tag) begin
      retro_sent_q <= 1'b1;
    end
  end

  msr_spill_reg #(
    .WIDTH ($bits(req_t))
  ) u_req_spill (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .clear_i (clear_i),
    .valid_i (req_in_valid),
    .ready_o (req_in_ready),
    .data_i  (req_in),
    .valid_o (req_valid_o),
    .ready_i (req_ready_i),
    .data_o  (req_out)
  );

  assign req_x_o   = req_out.x;
  assign req_y_o   = req_out.y;
  assign req_tag_o = req_out.tag;

  // ---- Responses --------------------------------------------------------------------------------
  typedef struct packed {
    logic [TAG_W-1:0] tag;
    rgb_t             rgb;
  } rsp_t;

  logic             rs_valid, rs_ready;
  rsp_t             rs_data, rsp_in;
  logic             r1_valid_q, r1_ready;
  rsp_t             r1_q;
  tag_entry_t       r1_entry;
  logic             r1_inflight;
  logic             r2_valid_q, r2_ok_q, r2_write, r2_drop, r2_done;
  rsp_t             r2_q;
  tag_entry_t       r2_entry_q;

  msr_spill_reg #(
    .WIDTH ($bits(rsp_t))
  ) u_rsp_spill (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .clear_i (clear_i),
    .valid_i (rsp_valid_i),
    .ready_o (rsp_ready_o),
    .data_i  (rsp_in),
    .valid_o (rs_valid),
    .ready_i (rs_ready),
    .data_o  (rs_data)
  );

  assign rsp_in = '{tag: rsp_tag_i, rgb: rsp_rgb_i};

  // R1 looks the tag up (where the answer goes, and whether the tag is in flight, minus the
  // tag R2 releases this cycle, so a duplicate right behind its original is caught). R2 writes
  // the colour when its context's port is free this cycle (the pipeline's interpolated write
  // goes first), or drops an answer whose tag was not in flight.
  assign r2_drop  = r2_valid_q && !r2_ok_q;
  assign r2_write = r2_valid_q && r2_ok_q && !(out_write && out_side.ctx == r2_entry_q.ctx);
  assign r2_done  = r2_drop || r2_write;
  assign r1_ready = !r2_valid_q || r2_done;
  assign rs_ready = !r1_valid_q || r1_ready;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      r1_valid_q <= 1'b0;
      r2_valid_q <= 1'b0;
    end else if (clear_i) begin
      r1_valid_q <= 1'b0;
      r2_valid_q <= 1'b0;
    end else begin
      if (rs_ready) r1_valid_q <= rs_valid;
      if (r1_ready) r2_valid_q <= r1_valid_q;
    end
  end

  always_ff @(posedge clk_i) begin
    if (rs_ready && rs_valid) r1_q <= rs_data;
    if (r1_ready && r1_valid_q) begin
      r2_q       <= r1_q;
      r2_entry_q <= r1_entry;
      r2_ok_q    <= r1_inflight && !(r2_write && r2_q.tag == r1_q.tag);
    end
  end

  assign rsp_drop_o = r2_drop;

  // ---- Tags -------------------------------------------------------------------------------------
  logic [TAG_W:0] tags_inflight;
  tag_entry_t     alloc_entry;

  assign alloc_entry = '{ctx: out_side.ctx, level: out_side.level,
                         addr: !retro_phase  ? {out_side.y, out_side.x} :
                               out_side.vert ? {out_side.y, rt_line}
                                             : {rt_line, out_side.x}};

  msr_tag_pool #(
    .N       (MAX_OUTSTANDING),
    .ENTRY_W ($bits(tag_entry_t)),
    .TAG_W   (TAG_W)
  ) u_tag_pool (
    .clk_i            (clk_i),
    .rst_ni           (rst_ni),
    .clear_i          (clear_i),
    .avail_o          (tag_avail),
    .tag_o            (free_tag),
    .alloc_i          (alloc_tag),
    .entry_i          (alloc_entry),
    .query_tag_i      (r1_q.tag),
    .query_entry_o    (r1_entry),
    .query_inflight_o (r1_inflight),
    .release_tag_i    (r2_q.tag),
    .release_i        (r2_write),
    .inflight_o       (tags_inflight),
    .out_q_o          (tags_out_o),
    .init_o           (tags_init)
  );

  assign inflight_o = tags_inflight;

  // ---- Writes: each context's one port, registered -----------------------------------------
  // The write reaches its context a clock after the output or R2 decided it: the contexts sit
  // across the engine's area, and the decision -> context path (its pending count's adder
  // behind) was the placed top's worst path at 10.9 ns. Nothing waits on a write but the
  // context itself (its pending count and pass barrier see the write when it lands), so the
  // register only delays a barrier by one clock. A clear drops a write on its way.
  for (genvar c = 0; c < NUM_CTX; c++) begin : g_write
    logic pipe_we, rsp_we;
    assign pipe_we = out_write && (out_side.ctx == ctx_t'(c));
    assign rsp_we  = r2_write && (r2_entry_q.ctx == ctx_t'(c));

    // a retro request is one more pending write of its context (registered like the write)
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        ctx_retro[c] <= 1'b0;
      end else if (clear_i) begin
        ctx_retro[c] <= 1'b0;
      end else begin
        ctx_retro[c] <= retro_phase && alloc_tag && (out_side.ctx == ctx_t'(c));
      end
    end

    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        ctx_we[c] <= 1'b0;
      end else if (clear_i) begin
        ctx_we[c] <= 1'b0;
      end else begin
        ctx_we[c] <= pipe_we || rsp_we;
      end
    end

    // Data without an enable: it is used only with ctx_we.
    always_ff @(posedge clk_i) begin
      ctx_waddr[c] <= pipe_we ? {out_side.y, out_side.x} : r2_entry_q.addr;
      ctx_wsrc[c]  <= pipe_we ? src_interp(out_side.level) : src_traced(r2_entry_q.level);
      ctx_wrgb[c]  <= pipe_we ? out_rgb : r2_q.rgb;
    end
  end

  // ---- Output streamer ----------------------------------------------------------------------
  logic             str_arb_valid, streaming_q, str_start_q, str_start_ready;
  logic             str_re, str_done;
  logic [CTX_W-1:0] str_sel, str_q;
  logic [TADDR_W-1:0] str_raddr;
  // The streamer needs the winner's index and the tile's origin and size only.
  /* verilator lint_off UNUSEDSIGNAL */
  tile_desc_t       str_desc;
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

  // Pick a full context (one cycle), start the streamer on it (next cycle), free it when its
  // last pixel has left.
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      streaming_q <= 1'b0;
      str_start_q <= 1'b0;
      str_q       <= '0;
    end else if (clear_i) begin
      streaming_q <= 1'b0;
      str_start_q <= 1'b0;
      str_q       <= '0;
    end else begin
      if (!streaming_q && str_arb_valid) begin
        streaming_q <= 1'b1;
        str_start_q <= 1'b1;
        str_q       <= str_sel;
      end
      if (str_start_q && str_start_ready) str_start_q <= 1'b0;
      if (str_done) streaming_q <= 1'b0;
    end
  end

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
      .step_first_o  (ctx_first[c]),
      .step_x_o      (ctx_x[c]),
      .step_y_o      (ctx_y[c]),
      .step_gap_o    (ctx_gap[c]),
      .step_off_o    (ctx_off[c]),
      .step_level_o  (ctx_level[c]),
      .step_nshift_o (ctx_nshift[c]),
      .step_init_o   (ctx_init[c]),
      .step_dir_o    (ctx_dir[c]),
      .step_o2a_o    (ctx_o2a[c]),
      .issue_i       (ctx_issue[c]),
      .rd_a_o        (ctx_rd_a[c]),
      .rd_b_o        (ctx_rd_b[c]),
      .rd_o2_o       (ctx_rd_o2[c]),
      .retro_i       (ctx_retro[c]),
      .we_i          (ctx_we[c]),
      .waddr_i       (ctx_waddr[c]),
      .wsrc_i        (ctx_wsrc[c]),
      .wrgb_i        (ctx_wrgb[c]),
      .full_o        (ctx_full[c]),
      .str_own_i     (ctx_str_own[c]),
      .str_re_i      (str_re),
      .str_raddr_i   (str_raddr),
      .str_rgb_o     (ctx_str_rgb[c]),
      .str_src_o     (ctx_str_src[c]),
      .str_done_i    (ctx_str_done[c])
    );
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
  `MSR_ASSERT(a_one_writer, !(out_write && r2_write && out_side.ctx == r2_entry_q.ctx))
  `MSR_ASSERT(a_issue_onehot, $onehot0(ctx_issue))
  `MSR_ASSERT(a_out_buf_room, pv_valid |-> ob_ready)
  `MSR_ASSERT(a_credits, 32'(credit_q) + 32'(ob_count) <= OUT_DEPTH)
  // the line before is 1..8 away (rows of G_y(k-1), columns of G_x(k))
  `MSR_ASSERT(a_retro_delta, pv_valid && pv_side.lin && !pv_side.fline |->
      pv_side.o.ldelta inside {[1 : 8]})
  `MSR_COVER(c_retro, retro_phase && alloc_tag)
  `MSR_COVER(c_rsp_dropped, rsp_drop_o)
  `MSR_COVER(c_all_ctx_busy, ctx_free == '0)
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_tile_engine
