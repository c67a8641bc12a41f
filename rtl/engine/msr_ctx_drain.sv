// Drain: finished tiles leave their contexts as the engine's pixel stream. A full context is
// picked round robin (one cycle), the streamer starts on it (the next cycle) and reads its
// tile buffer's port 0 row-major; the context is freed when its last pixel has left.
`include "msr_flops.svh"
module msr_ctx_drain import msr_pkg::*; #(
  parameter int unsigned NUM_CTX = 8, parameter int unsigned CTX_W = $clog2(NUM_CTX),
  parameter int unsigned DEPTH_EN = 0,  // 1: each pixel's inverse depth beside it (else 0)
  parameter int unsigned RD_LAT   = 1,  // the tile buffers' read latency (1..4)
  parameter int unsigned CYCLE    = 1   // clocks between two reads of one tile-buffer copy
) (
  input  logic                       clk_i, rst_ni, clear_i,  // clear: synchronous soft reset
  // the contexts
  input  logic       [NUM_CTX-1:0]   full_i,     // the tile is finished
  input  tile_desc_t [NUM_CTX-1:0]   desc_i,     // the tile's origin and size
  output logic       [NUM_CTX-1:0]   own_o,      // the streamer reads this context now
  output logic                       re_o,       // the read, to every context (own_o selects)
  output logic       [TADDR_W-1:0]   raddr_o,
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

  logic             arb_valid, streaming_q, start_q, start_ready;
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
    .re_o, .raddr_o, .rdata_rgb_i (rgb_i[cur_q]), .rdata_src_i (src_i[cur_q]),
    .rdata_invz_i (invz_i[cur_q]),
    .pix_valid_o, .pix_ready_i, .pix_o, .pix_invz_o, .done_o (done)
  );

  for (genvar c = 0; c < NUM_CTX; c++) begin : g_own
    assign own_o[c]  = streaming_q && (cur_q == CTX_W'(c));
    assign done_o[c] = done && (cur_q == CTX_W'(c));
  end

endmodule : msr_ctx_drain
