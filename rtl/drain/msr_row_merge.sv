// Row merge: several tile streamers into the engine's one pixel stream, a whole row at a time.
//
// With a tile buffer whose macro takes an address once per BUF_CYCLE clocks a streamer reads
// two pixels per BUF_CYCLE clocks (msr_tile_stream), so the engine drains several finished
// tiles at once (msr_ctx_drain). The frame-buffer writer needs each row of a tile contiguous in
// an engine's stream (msr_fb_writer), not each tile: this unit passes one streamer's row, then
// picks the next streamer that holds a whole row in its FIFO (round robin), so a row leaves at
// one pixel a clock however slowly it was read. Each tile's pixels stay in order; rows of
// different tiles interleave.
//
// The pick is combinational while no row is open (the row's first pixel leaves in the clock it
// is picked); the open row's streamer is a register until its last pixel leaves.
`include "msr_assert.svh"
`include "msr_flops.svh"

module msr_row_merge
  import msr_pkg::*;
#(
  parameter int unsigned N     = 3,                      // streamers
  parameter int unsigned IDX_W = (N > 1) ? $clog2(N) : 1
) (
  input  logic                    clk_i,
  input  logic                    rst_ni,
  input  logic                    clear_i,      // synchronous soft reset: no row open
  // the streamers
  input  logic      [N-1:0]       row_ready_i,  // a whole row waits in streamer s's FIFO
  input  logic      [N-1:0]       valid_i,
  output logic      [N-1:0]       ready_o,
  input  pix_word_t [N-1:0]       pix_i,
  input  logic      [N-1:0][15:0] invz_i,
  input  logic      [N-1:0]       row_end_i,    // pix_i is the last pixel of its row
  // the engine's stream
  output logic                    valid_o,
  input  logic                    ready_i,
  output pix_word_t               pix_o,
  output logic      [15:0]        invz_o
);

  logic             open_q, open_d, arb_valid, pick, row_done;
  logic [IDX_W-1:0] cur_q, cur_d, arb_idx, sel;
  logic [N-1:0]     arb_gnt;

  // A streamer's request is its whole row; the pointer moves when a row is picked.
  msr_rr_arb #(.N(N), .IDX_W(IDX_W)) u_row_arb (
    .clk_i, .rst_ni, .clear_i,
    .req_i (row_ready_i), .gnt_o (arb_gnt), .idx_o (arb_idx), .valid_o (arb_valid),
    .ready_i (pick)
  );

  assign pick     = !open_q && arb_valid;
  assign sel      = open_q ? cur_q : arb_idx;
  assign valid_o  = (open_q || arb_valid) && valid_i[sel];
  assign pix_o    = pix_i[sel];
  assign invz_o   = invz_i[sel];
  assign row_done = valid_o && ready_i && row_end_i[sel];
  assign open_d   = (open_q || pick) && !row_done;
  assign cur_d    = pick ? arb_idx : cur_q;

  for (genvar s = 0; s < N; s++) begin : g_ready
    assign ready_o[s] = ready_i && (open_q || arb_valid) && (sel == IDX_W'(s));
  end

  `MSR_CLR_REG(u_open_q, 1 + IDX_W, clear_i, 1'b1, {open_d, cur_d}, {open_q, cur_q})

  logic unused_gnt;
  assign unused_gnt = ^arb_gnt;

  /* verilator lint_off SYNCASYNCNET */
  // a picked row is whole in its FIFO: its pixels are there every clock until its end
  `MSR_ASSERT_IMP(a_row_whole, open_q, valid_i[cur_q])
  `MSR_ASSERT_IMP(a_pick_whole, pick, valid_i[arb_idx])
  `MSR_COVER(c_rows_wait, pick && $countones(row_ready_i) > 1)
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_row_merge
