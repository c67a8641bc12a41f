// Drain: finished tiles leave their contexts as the engine's pixel stream. A full context is
// picked round robin (one cycle), the streamer starts on it (the next cycle) and reads its
// tile buffer's port 0 row-major; the context is freed when its last pixel has left.
//
// CYCLE > 1 (a macro whose port takes an address once per CYCLE clocks): a streamer reads two
// pixels per CYCLE clocks, so NSTR = (CYCLE + 1) / 2 streamers drain as many full contexts at
// once, each from its own context's two copies, and msr_row_merge passes their rows one whole
// row at a time (rows of different tiles interleave in the stream; each tile's stay in order).
`include "msr_flops.svh"
module msr_ctx_drain import msr_pkg::*; #(
  parameter int unsigned NUM_CTX = 8, parameter int unsigned CTX_W = $clog2(NUM_CTX),
  parameter int unsigned DEPTH_EN = 0,  // 1: each pixel's inverse depth beside it (else 0)
  parameter int unsigned RD_LAT   = 1,  // the tile buffers' read latency (1..4)
  parameter int unsigned CYCLE    = 1,  // clocks between two reads of one tile-buffer copy
  parameter int unsigned TILE_LIMIT = MAX_TILE  // the longest row (CYCLE > 1: a FIFO holds one)
) (
  input  logic                       clk_i, rst_ni, clear_i,  // clear: synchronous soft reset
  // the contexts
  input  logic       [NUM_CTX-1:0]   full_i,     // the tile is finished
  input  tile_desc_t [NUM_CTX-1:0]   desc_i,     // the tile's origin and size
  output logic       [NUM_CTX-1:0]   own_o,      // a streamer reads this context now
  output logic       [NUM_CTX-1:0]   re_o,       // each context's read (own_o selects)
  output logic       [NUM_CTX-1:0][TADDR_W-1:0] raddr_o,
  input  rgb_t       [NUM_CTX-1:0]   rgb_i,      // RD_LAT + 1 cycles after re_o
  input  src_t       [NUM_CTX-1:0]   src_i,
  input  logic       [NUM_CTX-1:0][15:0] invz_i,  // DEPTH_EN: with rgb_i
  output logic       [NUM_CTX-1:0]   done_o,     // pulse: the whole tile has left
  // the pixel stream, row-major, global coordinates
  output logic                       pix_valid_o,
  input  logic                       pix_ready_i,
  output pix_word_t                  pix_o,      // the pixel (msr_pkg::pix_word_t)
  output logic       [15:0]          pix_invz_o  // DEPTH_EN: its inverse depth
);

  if (CYCLE <= 1) begin : g_one_streamer
    logic             arb_valid, streaming_q, start_q, start_ready;
    logic             re;
    logic [TADDR_W-1:0] raddr;
    // one streamer: nothing merges rows, its row flags go unused
    /* verilator lint_off UNUSEDSIGNAL */
    logic             row_ready_unused, row_end_unused;
    /* verilator lint_on UNUSEDSIGNAL */
    logic             streaming_d, start_d, pick, done;
    logic [CTX_W-1:0] sel, cur_q, cur_d;
    // The streamer needs the winner's index and the tile's origin and size only.
    /* verilator lint_off UNUSEDSIGNAL */
    tile_desc_t         cur_desc;
    logic [NUM_CTX-1:0] gnt;
    /* verilator lint_on UNUSEDSIGNAL */

    msr_rr_arb #(.N(NUM_CTX), .IDX_W(CTX_W)) u_stream_arb (
      .clk_i, .rst_ni, .clear_i,
      .req_i (full_i), .gnt_o (gnt), .idx_o (sel), .valid_o (arb_valid), .ready_i (!streaming_q)
    );

    always_comb begin
      pick        = !streaming_q && arb_valid;
      streaming_d = !done && (pick || streaming_q);
      start_d     = !(start_q && start_ready) && (pick || start_q);
      cur_d       = pick ? sel : cur_q;
    end

    `MSR_CLR_REG(u_stream_q, 2 + CTX_W, clear_i, 1'b1, {streaming_d, start_d, cur_d},
                 {streaming_q, start_q, cur_q})

    assign cur_desc = desc_i[cur_q];

    msr_tile_stream #(.RD_LAT(RD_LAT), .DEPTH_EN(DEPTH_EN), .CYCLE(CYCLE)) u_stream (
      .clk_i, .rst_ni, .clear_i,
      .start_valid_i (start_q), .start_ready_o (start_ready),
      .x0_i (cur_desc.x0), .y0_i (cur_desc.y0), .w_i (cur_desc.w), .h_i (cur_desc.h),
      .re_o (re), .raddr_o (raddr), .rdata_rgb_i (rgb_i[cur_q]), .rdata_src_i (src_i[cur_q]),
      .rdata_invz_i (invz_i[cur_q]),
      .pix_valid_o, .pix_ready_i, .pix_o, .pix_invz_o, .done_o (done),
      .row_ready_o (row_ready_unused), .row_end_o (row_end_unused)
    );

    for (genvar c = 0; c < NUM_CTX; c++) begin : g_own
      assign own_o[c]  = streaming_q && (cur_q == CTX_W'(c));
      assign re_o[c]    = re;          // every context sees the one read
      assign raddr_o[c] = raddr;
      assign done_o[c] = done && (cur_q == CTX_W'(c));
    end

  end else begin : g_streamers
    localparam int unsigned NSTR  = (CYCLE + 1) / 2;
    localparam int unsigned S_W   = (NSTR > 1) ? $clog2(NSTR) : 1;
    // every read in flight and a whole row (msr_tile_stream's row merge condition)
    localparam int unsigned FIFO_NEED = TILE_LIMIT + RD_LAT + 2;
    localparam int unsigned FIFO_D    = 1 << $clog2(FIFO_NEED);

    logic       [NSTR-1:0]              busy_q, busy_d, start_q, start_d, start_ready, done;
    logic       [NSTR-1:0][CTX_W-1:0]   cur_q, cur_d;
    logic       [NSTR-1:0]              s_re, s_valid, s_ready, s_row_ready, s_row_end;
    logic       [NSTR-1:0][TADDR_W-1:0] s_raddr;
    pix_word_t  [NSTR-1:0]              s_pix;
    logic       [NSTR-1:0][15:0]        s_invz;
    logic       [NUM_CTX-1:0]           owned, gnt;
    logic                               arb_valid, pick;
    logic       [CTX_W-1:0]             sel;
    logic       [S_W-1:0]               free_s;      // the lowest idle streamer
    logic                               any_free;

    // A full context that no streamer holds goes to the lowest idle streamer.
    always_comb begin
      owned = '0;
      for (int unsigned s = 0; s < NSTR; s++) begin
        if (busy_q[s]) owned[cur_q[s]] = 1'b1;
      end
      any_free = 1'b0;
      free_s   = '0;
      for (int unsigned s = NSTR; s > 0; s--) begin
        if (!busy_q[s-1]) begin
          any_free = 1'b1;
          free_s   = S_W'(s - 1);
        end
      end
    end

    msr_rr_arb #(.N(NUM_CTX), .IDX_W(CTX_W)) u_stream_arb (
      .clk_i, .rst_ni, .clear_i,
      .req_i (full_i & ~owned), .gnt_o (gnt), .idx_o (sel), .valid_o (arb_valid),
      .ready_i (any_free)
    );
    assign pick = any_free && arb_valid;

    always_comb begin
      for (int unsigned s = 0; s < NSTR; s++) begin
        busy_d[s]  = !done[s] && (busy_q[s] || (pick && free_s == S_W'(s)));
        start_d[s] = !(start_q[s] && start_ready[s]) && (start_q[s] || (pick && free_s == S_W'(s)));
        cur_d[s]   = (pick && free_s == S_W'(s)) ? sel : cur_q[s];
      end
    end

    `MSR_CLR_REG(u_stream_q, NSTR * (2 + CTX_W), clear_i, 1'b1, {busy_d, start_d, cur_d},
                 {busy_q, start_q, cur_q})

    for (genvar s = 0; s < NSTR; s++) begin : g_stream
      // The streamer needs the tile's origin and size only.
      /* verilator lint_off UNUSEDSIGNAL */
      tile_desc_t cur_desc;
      /* verilator lint_on UNUSEDSIGNAL */
      assign cur_desc = desc_i[cur_q[s]];
      msr_tile_stream #(
        .RD_LAT (RD_LAT), .DEPTH_EN (DEPTH_EN), .CYCLE (CYCLE), .FIFO_DEPTH (FIFO_D)
      ) u_stream (
        .clk_i, .rst_ni, .clear_i,
        .start_valid_i (start_q[s]), .start_ready_o (start_ready[s]),
        .x0_i (cur_desc.x0), .y0_i (cur_desc.y0), .w_i (cur_desc.w), .h_i (cur_desc.h),
        .re_o (s_re[s]), .raddr_o (s_raddr[s]), .rdata_rgb_i (rgb_i[cur_q[s]]),
        .rdata_src_i (src_i[cur_q[s]]), .rdata_invz_i (invz_i[cur_q[s]]),
        .pix_valid_o (s_valid[s]), .pix_ready_i (s_ready[s]), .pix_o (s_pix[s]),
        .pix_invz_o (s_invz[s]), .done_o (done[s]),
        .row_ready_o (s_row_ready[s]), .row_end_o (s_row_end[s])
      );
    end

    msr_row_merge #(.N(NSTR)) u_row_merge (
      .clk_i, .rst_ni, .clear_i,
      .row_ready_i (s_row_ready), .valid_i (s_valid), .ready_o (s_ready), .pix_i (s_pix),
      .invz_i (s_invz), .row_end_i (s_row_end),
      .valid_o (pix_valid_o), .ready_i (pix_ready_i), .pix_o, .invz_o (pix_invz_o)
    );

    // Each context's read and its done pulse come from the streamer that holds it.
    always_comb begin
      own_o   = '0;
      re_o    = '0;
      raddr_o = '0;
      done_o  = '0;
      for (int unsigned s = 0; s < NSTR; s++) begin
        if (busy_q[s]) begin
          own_o[cur_q[s]]   = 1'b1;
          re_o[cur_q[s]]    = s_re[s];
          raddr_o[cur_q[s]] = s_raddr[s];
          done_o[cur_q[s]]  = done[s];
        end
      end
    end

    logic unused_gnt;
    assign unused_gnt = ^gnt;
  end

endmodule : msr_ctx_drain
