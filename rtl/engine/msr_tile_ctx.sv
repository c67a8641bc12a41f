// One tile context of the engine: the tile's descriptor, its level processing controller,
// the pass barrier and its tile buffer. The engine instantiates NUM_CTX of these in one
// generate loop and shares one decision pipeline between them.
//
// Pass barrier (spec section 3: a pass reads only pixels that were final before it began):
// `pend_q` counts the context's positions that were issued and whose pixel is not yet
// written (interpolated, or traced and answered). The first position of a pass is offered
// only when that count is zero; the other positions of the pass read only pixels of earlier
// passes, so they go as soon as the engine picks them. The waits of one context (a render
// latency per pass with traced positions) are filled with the other contexts' decisions.
//
// Life of a context: FREE -> (start_i) COMPUTE -> (controller idle, nothing pending) FULL
// -> (stream_done_i) FREE. Its tile buffer is read for decisions while computing (port 0
// B, port 1 A, addresses straight from the controller's output register) and by the
// streamer while full (port 0; with BUF_CYCLE > 1 ports 0 and 1 in turn). Every pixel of the
// tile is written exactly once before the tile is streamed (lindilate's dilation may write a
// pixel once more), so the buffer needs no clearing.
`include "msr_assert.svh"
`include "msr_flops.svh"

module msr_tile_ctx
  import msr_pkg::*;
#(
  parameter int unsigned PEND_W    = 8,  // width of the pending-position count
  parameter int unsigned LINDILATE = 1,  // 0: no third port (patent-only engine; rd_o2_o is 0)
  parameter int unsigned DEPTH_EN  = 0,  // 1: the tile buffer's word holds the inverse depth
                                         //    too (else the inverse-depth outputs are 0)
  parameter int unsigned RD_LAT    = 1,  // the tile buffers' read latency in clocks (1..4)
  parameter int unsigned TILE_LIMIT = MAX_TILE, // the largest tile edge the buffer holds (8, 16,
                                                // 32): TILE_LIMIT^2 words
  parameter int unsigned BUF_CYCLE = 1   // clocks between two addresses on a port of a copy:
                                         // > 1, the streamer's reads go to the two copies in
                                         // turn (the engine spaces the rest; checked here)
) (
  input  logic               clk_i,
  input  logic               rst_ni,
  input  logic               clear_i,       // synchronous soft reset
  // tile start
  input  logic               start_i,       // take desc_i (only when free_o)
  input  tile_desc_t         desc_i,
  output logic               free_o,        // no tile: may start one
  output tile_desc_t         desc_o,        // the tile held
  // the position on offer
  // the position on offer: the candidate bit is issue_i ? cand_tail_o : cand_head_o, formed
  // at the arbiter (msr_ctx_issue), which holds the grant register issue_i comes from
  output logic               cand_tail_o,   // the tail may go once the head leaves
  output logic               cand_head_o,   // the head may go
  // its position (init: traced, no reads; o2a: lindilate's A' is rd_o2_o, else the last A)
  output eng_pos_t           step_o,
  input  logic               issue_i,       // the head leaves this cycle (granted the cycle before)
  // decision reads: the neighbours of the position issued RD_LAT + 1 cycles before
  output rgb_t               rd_a_o,
  output rgb_t               rd_b_o,
  output rgb_t               rd_o2_o,       // the third port: B' (or A' where o2a)
  output logic [15:0]        rd_wa_o,       // DEPTH_EN: A's and B's inverse depth (with rd_a_o,
  output logic [15:0]        rd_wb_o,       // rd_b_o)
  // a render request for a pixel of this context that was already written (lindilate's
  // dilation traces an interpolated pixel of the line before): one more pending write
  input  logic               retro_i,
  // the one write port: an interpolated value or a render response, one per cycle
  input  logic               we_i,
  input  logic [TADDR_W-1:0] waddr_i,
  input  src_t               wsrc_i,
  input  rgb_t               wrgb_i,
  input  logic [15:0]        winvz_i,       // DEPTH_EN: the written pixel's inverse depth
  // hand-over to the streamer
  output logic               full_o,        // the tile is finished, waiting for / in the streamer
  input  logic               str_own_i,     // the streamer reads port 0 now
  input  logic               str_re_i,
  input  logic [TADDR_W-1:0] str_raddr_i,
  output rgb_t               str_rgb_o,     // RD_LAT + 1 cycles after str_re_i
  output src_t               str_src_o,
  output logic [15:0]        str_invz_o,    // DEPTH_EN: with str_rgb_o
  input  logic               str_done_i     // the streamer has emitted the whole tile
);

  // A tile-buffer word: {source code, colour}, with DEPTH_EN the inverse depth above them.
  localparam int unsigned WORD_W = $bits(src_t) + $bits(rgb_t) + ((DEPTH_EN != 0) ? 16 : 0);

  // The buffer's address: the low log2(TILE_LIMIT) bits of the tile-local y and x. The engine
  // forms {y, x} addresses for the largest tile (MAX_TILE); a top built for smaller tiles
  // (msr_top TILE_LIMIT, which CONFIG.TILE may not exceed) keeps the words it can use: a
  // standard-cell build's macros are most of its area (docs/asic.md).
  localparam int unsigned BUF_LG = $clog2(TILE_LIMIT);
  localparam int unsigned BUF_AW = 2 * BUF_LG;
  if (!(TILE_LIMIT inside {8, 16, 32}) || TILE_LIMIT > MAX_TILE) begin : g_check_limit
    $fatal(1, "msr_tile_ctx: TILE_LIMIT %0d must be 8, 16 or 32", TILE_LIMIT);
  end
  // (a smaller TILE_LIMIT leaves the high bits of y and x unused: they are 0 in a tile that fits)
  /* verilator lint_off UNUSEDSIGNAL */
  function automatic logic [BUF_AW-1:0] buf_addr(logic [TADDR_W-1:0] a);
    return {a[LCOORD_W +: BUF_LG], a[0 +: BUF_LG]};
  endfunction
  /* verilator lint_on UNUSEDSIGNAL */

  typedef enum logic [1:0] {
    CTX_FREE    = 2'd0,
    CTX_COMPUTE = 2'd1,
    CTX_FULL    = 2'd2
  } ctx_state_e;

  ctx_state_e        state_q, state_d;
  tile_desc_t        desc_q;
  logic [PEND_W-1:0] pend_q, pend_d;

  // ---- Level processing controller and its position queue ------------------------------------
  // The controller fills a spill register, the spill register a two-entry queue; the
  // engine's arbiter takes positions from the queue's head. So the walk state (a few hundred
  // flip-flops spread over the context) advances on the spill register's "has room", a
  // flip-flop of this context, and the engine's grant (issue_i, a register beside the
  // arbiter) reaches only the queue's and the spill register's control. Two queue entries
  // keep one position per clock for a context that wins every cycle; the spill register
  // passes one per clock as well.
  //
  // The queue is a head register and a tail register (not a FIFO with pointers): the head's
  // fields, hence the candidate bit and the tile buffer's read addresses, come straight from
  // flip-flops, so the engine's issue path starts at a register and one LUT.

  logic    ctrl_valid, ctrl_room, step_valid, ctrl_busy, q_room, q_push;
  step_t   ctrl_step, step;
  logic    head_valid_q, tail_valid_q;
  step_t   head_q, tail_q;
  // The controller is idle whenever the context is free; its own start handshake is not needed.
  /* verilator lint_off UNUSEDSIGNAL */
  logic    ctrl_start_ready;
  /* verilator lint_on UNUSEDSIGNAL */

  msr_level_ctrl u_level_ctrl (
    .clk_i, .rst_ni, .clear_i,
    .start_valid_i (start_i), .start_ready_o (ctrl_start_ready),
    .w_i (desc_i.w), .h_i (desc_i.h), .levels_i (desc_i.levels),
    .step_valid_o (ctrl_valid), .step_ready_i (ctrl_room),
    .step_o (ctrl_step),
    .busy_o (ctrl_busy)
  );

  // ctrl_room is the spill register's "second entry empty", a flip-flop: the controller's
  // advance (the clock enable of its walk state) does not wait for the engine's grant.
  msr_spill_reg #(.WIDTH($bits(step_t))) u_step_slice (
    .clk_i, .rst_ni, .clear_i,
    .valid_i (ctrl_valid), .ready_o (ctrl_room), .data_i (ctrl_step),
    .valid_o (step_valid), .ready_i (q_room),    .data_o (step)
  );

  // The engine's grant is registered: issue_i is a flip-flop, and the position granted the
  // clock before is still the head while issue_i is high (it leaves at the end of that
  // clock). So the queue has room while its tail is empty or the head is leaving: both are
  // registers, and a context that wins every clock gets a new position every clock.
  assign q_room = !tail_valid_q || issue_i;
  assign q_push = step_valid && q_room;

  // Next state of the queue, written out so that the candidate bits below can be registered
  // from it.
  logic head_valid_d, tail_valid_d, head_first_d, tail_first_d;
  always_comb begin
    head_valid_d = head_valid_q;
    tail_valid_d = tail_valid_q;
    if (issue_i) begin
      // the head leaves: the tail (if any) moves up and a push goes behind it
      head_valid_d = tail_valid_q || q_push;
      tail_valid_d = tail_valid_q && q_push;
    end else if (q_push) begin
      head_valid_d = 1'b1;
      tail_valid_d = head_valid_q;
    end
    head_first_d = head_q.first;
    if (issue_i)                        head_first_d = tail_valid_q ? tail_q.first : step.first;
    else if (q_push && !head_valid_q)   head_first_d = step.first;
    tail_first_d = (q_push && head_valid_q && (tail_valid_q || !issue_i)) ? step.first
                                                                          : tail_q.first;
  end

  // The queue's valid bits (the entries below are plain data registers).
  `MSR_CLR_REG(u_q_valid, 2, clear_i, 1'b1, {head_valid_d, tail_valid_d},
               {head_valid_q, tail_valid_q})

  // Entries have no reset: each is written with its valid bit.
  always_ff @(posedge clk_i) begin
    if (issue_i) begin
      head_q <= tail_valid_q ? tail_q : step;
    end else if (q_push && !head_valid_q) begin
      head_q <= step;
    end
    if (q_push && head_valid_q && (tail_valid_q || !issue_i)) begin
      tail_q <= step;
    end
  end

  // pend_zero_q is "pend_q == 0", kept as a register: it changes only when an issue and a
  // write do not cancel, and then depends on "pend_q == 1" (a compare of a register).
  //
  // The candidate: the position that is head once the one leaving now (issue_i) has left.
  // While a head leaves, that is the tail, and only if it is not the first of a pass (the
  // leaving position is not yet written, so the barrier holds anyway). Otherwise the head,
  // the first of a pass only when nothing issued is pending. Both alternatives are registered
  // from the next state (cand_tail_q, cand_head_q), so the candidate is one 3-input mux of
  // flip-flops: the arbiter's path (the engine's longest) starts right there. The mux sits in
  // the arbiter (msr_ctx_issue), beside the grant register, so that the path may cross the
  // engine once (from these flip-flops) rather than twice (grant -> context -> arbiter). The
  // placer is still free to put its LUT beside the context (and does on the default top); with
  // the mux in the context instead the top was no faster, its worst paths elsewhere.
  // A retro request (retro_i) adds one pending write like an issue; it comes only while the
  // position that caused it is pending, so it never meets a zero count.
  logic pend_zero_q, pend_zero_d, pend_one, cand_tail_q, cand_head_q, pend_up;
  assign pend_up     = issue_i || retro_i;
  assign pend_one    = (pend_q == PEND_W'(1));
  assign pend_zero_d = (issue_i && retro_i) ? 1'b0 :
                       (pend_up != we_i)    ? (we_i && pend_one) : pend_zero_q;
  assign cand_tail_o = cand_tail_q;
  assign cand_head_o = cand_head_q;

  `MSR_CLR_REG(u_cand, 2, clear_i, 1'b1,
               {tail_valid_d && !tail_first_d, head_valid_d && (!head_first_d || pend_zero_d)},
               {cand_tail_q, cand_head_q})

  assign step_o = '{dir: head_q.dir, o2a: head_q.o2a, first: head_q.first, x: head_q.x, y: head_q.y,
                   gap: head_q.gap, off: head_q.off, level: head_q.level, nshift: head_q.nshift,
                   init: head_q.dir == DIR_INIT};

  // ---- State ----------------------------------------------------------------------------------
  always_comb begin
    state_d = state_q;
    pend_d  = pend_q + PEND_W'(issue_i) + PEND_W'(retro_i) - PEND_W'(we_i);
    unique case (state_q)
      CTX_FREE:    if (start_i) state_d = CTX_COMPUTE;
      CTX_COMPUTE: if (!ctrl_busy && !step_valid && !head_valid_q && pend_zero_q) begin
        state_d = CTX_FULL;
      end
      CTX_FULL:    if (str_done_i) state_d = CTX_FREE;
      default:     state_d = CTX_FREE;
    endcase
  end

  `MSR_CLR_REG_RST(u_pend_q, PEND_W + 1, {PEND_W'(0), 1'b1}, clear_i, 1'b1,
                   {pend_d, pend_zero_d}, {pend_q, pend_zero_q})

  logic [1:0] state_raw;
  `MSR_CLR_REG_RST(u_state_q, 2, CTX_FREE, clear_i, 1'b1, state_d, state_raw)
  assign state_q = ctx_state_e'(state_raw);

  always_ff @(posedge clk_i) begin
    if (start_i) desc_q <= desc_i;
  end

  assign free_o = (state_q == CTX_FREE);
  assign full_o = (state_q == CTX_FULL);
  assign desc_o = desc_q;

  // ---- Tile buffer ----------------------------------------------------------------------------
  // Port 0: B of the queue's head, or the streamer once the tile is full; port 1: A. The ports
  // read the head's neighbours only in the clock the head leaves (issue_i, the registered
  // grant: a flip-flop, so the read enable adds no logic to the arbiter's path), and the data
  // of the issued position is there RD_LAT clocks after. A buffer is read once per decision of its
  // context, not every clock its context computes: most of the buffers' energy was reads whose
  // data nobody used. The pass barrier keeps a position from being issued until its neighbours
  // are written, and a write is visible to the read of the next clock. A read that takes
  // several clocks (RD_LAT) changes none of this: the memory takes the address on the issue.
  logic computing, rd_issue;
  assign computing = (state_q == CTX_COMPUTE);
  assign rd_issue  = computing && issue_i;

  logic [WORD_W-1:0] rdata0, rdata0_q;
  // A decision needs the colour of A, not its source code (the streamer reads it with BUF_CYCLE).
  /* verilator lint_off UNUSEDSIGNAL */
  logic [WORD_W-1:0] rdata1, rdata1_q;
  /* verilator lint_on UNUSEDSIGNAL */
  logic [WORD_W-1:0] str_word;         // the streamer's word, RD_LAT + 1 clocks after its read

  // The streamer's reads: port 0 (one a clock); with BUF_CYCLE > 1 ports 0 and 1 in turn (the
  // buffer is two macros holding the same words), each port read once per BUF_CYCLE clocks
  // (msr_tile_stream spaces every other read), the word taken from the port the read went to.
  logic str_re0, str_re1;
  if (BUF_CYCLE > 1) begin : g_str_two_ports
    logic              turn_q;         // the next streamer read goes to port 1
    logic [RD_LAT:0]   port_q;         // the port of each read in flight
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        turn_q <= 1'b0;
      end else begin
        turn_q <= str_own_i && (turn_q ^ str_re_i);
      end
    end
    always_ff @(posedge clk_i) begin
      port_q <= (RD_LAT + 1)'({port_q, turn_q});
    end
    assign str_re0  = str_own_i && str_re_i && !turn_q;
    assign str_re1  = str_own_i && str_re_i && turn_q;
    assign str_word = port_q[RD_LAT] ? rdata1_q : rdata0_q;
  end else begin : g_str_port0
    assign str_re0  = str_own_i && str_re_i;
    assign str_re1  = 1'b0;
    assign str_word = rdata0_q;
  end

  msr_tile_sram #(
    .DEPTH  (TILE_LIMIT * TILE_LIMIT),
    .DATA_W (WORD_W),
    .RD_LAT (RD_LAT)
  ) u_tile_sram (
    .clk_i,
    .re0_i (str_own_i ? str_re0 : rd_issue),
    .raddr0_i (buf_addr(str_own_i ? str_raddr_i : {head_q.by, head_q.bx})), .rdata0_o (rdata0),
    .re1_i ((BUF_CYCLE > 1 && str_own_i) ? str_re1 : rd_issue),
    .raddr1_i (buf_addr((BUF_CYCLE > 1 && str_own_i) ? str_raddr_i : {head_q.ay, head_q.ax})),
    .rdata1_o (rdata1),
    .we_i, .waddr_i (buf_addr(waddr_i)), .wdata_i (WORD_W'({winvz_i, wsrc_i, wrgb_i}))
  );

  // Port 2 (lindilate): a colour-only copy written with the buffer, reading the head's
  // third-port address (B', or A' where o2a) on the issue like ports 0 and 1. Elsewhere A' is
  // the A of the line's previous position, this context's previous issue: the engine keeps
  // it, so one more port gives all four samples of a position every clock.
  rgb_t rdata2, rdata2_q;
  // Port 1 of the copy is not used.
  /* verilator lint_off UNUSEDSIGNAL */
  rgb_t rdata2_unused;
  /* verilator lint_on UNUSEDSIGNAL */

  msr_tile_sram #(
    .DEPTH  (TILE_LIMIT * TILE_LIMIT),
    .DATA_W ($bits(rgb_t)),
    .RD_LAT (RD_LAT)
  ) u_tile_sram_outer (
    .clk_i,
    .re0_i (rd_issue && LINDILATE != 0),
    .raddr0_i (buf_addr((head_q.dir == DIR_V) ? {head_q.o2, head_q.x} : {head_q.y, head_q.o2})),
    .rdata0_o (rdata2),
    .re1_i (1'b0), .raddr1_i ('0), .rdata1_o (rdata2_unused),
    .we_i (we_i && LINDILATE != 0), .waddr_i (buf_addr(waddr_i)), .wdata_i (wrgb_i)
  );

  always_ff @(posedge clk_i) begin
    rdata2_q <= rdata2;
  end

  // Without the rule the copy is never written or read and nothing reads rd_o2_o: synthesis
  // drops the copy (two DP16KD per context) with everything behind it.
  assign rd_o2_o = (LINDILATE != 0) ? rdata2_q : '0;

  // The read data is registered once more, beside the memory, before anything selects between
  // contexts: a block RAM's clock-to-output (5.8 ns on an ECP5 DP16KD) leaves no room for the
  // 8:1 choice behind it. Read data reaches the engine RD_LAT + 1 clocks after the address.
  always_ff @(posedge clk_i) begin
    rdata0_q <= rdata0;
    rdata1_q <= rdata1;
  end

  // After an initial-grid position the read data is stale: the engine forces a trace there.
  assign rd_a_o    = rgb_t'(rdata1_q[$bits(rgb_t)-1:0]);
  assign rd_b_o    = rgb_t'(rdata0_q[$bits(rgb_t)-1:0]);
  assign str_rgb_o = rgb_t'(str_word[$bits(rgb_t)-1:0]);
  assign str_src_o = src_t'(str_word[$bits(rgb_t) +: $bits(src_t)]);

  // The inverse depth: the top 16 bits of the tile buffer's word (DEPTH_EN).
  if (DEPTH_EN != 0) begin : g_depth
    assign rd_wa_o    = rdata1_q[WORD_W-1 -: 16];
    assign rd_wb_o    = rdata0_q[WORD_W-1 -: 16];
    assign str_invz_o = str_word[WORD_W-1 -: 16];
  end else begin : g_no_depth
    /* verilator lint_off UNUSEDSIGNAL */
    logic [15:0] winvz_unused;
    /* verilator lint_on UNUSEDSIGNAL */
    assign winvz_unused = winvz_i;
    assign rd_wa_o    = '0;
    assign rd_wb_o    = '0;
    assign str_invz_o = '0;
  end

  // ---- Checks ---------------------------------------------------------------------------------
`ifndef SYNTHESIS
  // Every pixel of a tile is written exactly once, inside the tile, while computing.
  logic [MAX_TILE*MAX_TILE-1:0] written_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      written_q <= '0;
    end else if (start_i || clear_i) begin
      written_q <= '0;
    end else if (we_i) begin
      written_q[waddr_i] <= 1'b1;
    end
  end

  function automatic logic all_written(logic [MAX_TILE*MAX_TILE-1:0] wr, ldim_t w, ldim_t h);
    logic ok = 1'b1;
    for (int unsigned y = 0; y < MAX_TILE; y++) begin
      for (int unsigned x = 0; x < MAX_TILE; x++) begin
        if (x < 32'(w) && y < 32'(h)) ok &= wr[y*MAX_TILE+x];
      end
    end
    return ok;
  endfunction
`endif

  /* verilator lint_off SYNCASYNCNET */
  `MSR_ASSERT_IMP(a_start_free, start_i, free_o)
  // the tile fits the buffer (the configuration check refuses larger T)
  `MSR_ASSERT_IMP(a_start_fits, start_i, 32'(desc_i.w) <= TILE_LIMIT && 32'(desc_i.h) <= TILE_LIMIT)
  `MSR_ASSERT_IMP(a_issue_head, issue_i, head_valid_q && state_q == CTX_COMPUTE &&
      (!head_q.first || pend_zero_q))
  `MSR_ASSERT(a_pend_no_wrap, !(pend_q == '0 && we_i && !pend_up) &&
      !(pend_q >= PEND_W'('1 - 1) && pend_up && !we_i))
  `MSR_ASSERT_IMP(a_retro_pending, retro_i, !pend_zero_q && desc_q.rule == RULE_LINDILATE)
  // lindilate's dilation may trace a pixel it interpolated (the render answer overwrites it)
  `MSR_ASSERT_IMP(a_write_once, we_i, state_q == CTX_COMPUTE &&
      (!written_q[waddr_i] || (desc_q.rule == RULE_LINDILATE && wsrc_i < SRC_INTERP_BASE)) &&
      32'(waddr_i[LCOORD_W-1:0]) < 32'(desc_q.w) &&
      32'(waddr_i[TADDR_W-1:LCOORD_W]) < 32'(desc_q.h))
  `MSR_ASSERT_IMP(a_all_written, state_q == CTX_COMPUTE && state_d == CTX_FULL,
      all_written(written_q, desc_q.w, desc_q.h))
  `MSR_ASSERT_IMP(a_stream_full, str_own_i, full_o)
`ifndef SYNTHESIS
  // The macro's cycle: every port of the buffer and its copy (decision reads, the streamer's,
  // writes) takes an address at most once per BUF_CYCLE clocks.
  logic rd0, rd1;
  int unsigned since_rd0_q, since_rd1_q, since_wr_q;
  assign rd0 = str_own_i ? str_re0 : rd_issue;
  assign rd1 = str_own_i ? str_re1 : rd_issue;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      since_rd0_q <= BUF_CYCLE;
      since_rd1_q <= BUF_CYCLE;
      since_wr_q  <= BUF_CYCLE;
    end else begin
      since_rd0_q <= rd0  ? 1 : (since_rd0_q < BUF_CYCLE) ? since_rd0_q + 1 : since_rd0_q;
      since_rd1_q <= rd1  ? 1 : (since_rd1_q < BUF_CYCLE) ? since_rd1_q + 1 : since_rd1_q;
      since_wr_q  <= we_i ? 1 : (since_wr_q < BUF_CYCLE)  ? since_wr_q + 1  : since_wr_q;
    end
  end
  `MSR_ASSERT_IMP(a_read0_cycle, rd0, since_rd0_q >= BUF_CYCLE)
  `MSR_ASSERT_IMP(a_read1_cycle, rd1, since_rd1_q >= BUF_CYCLE)
  `MSR_ASSERT_IMP(a_write_cycle, we_i, since_wr_q >= BUF_CYCLE)
`endif
  `MSR_ASSERT(a_pend_zero, pend_zero_q == (pend_q == '0))
  `MSR_ASSERT_IMP(a_tail_has_head, tail_valid_q, head_valid_q)
  `MSR_ASSERT(a_cand_regs, cand_tail_q == (tail_valid_q && !tail_q.first) &&
      cand_head_q == (head_valid_q && (!head_q.first || pend_zero_q)))
  `MSR_COVER(c_barrier_wait, head_valid_q && head_q.first && !pend_zero_q)
  `MSR_COVER(c_queue_full, tail_valid_q)
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_tile_ctx
