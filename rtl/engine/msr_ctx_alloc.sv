// Tile start: the lowest free context, chosen a clock ahead, takes the next descriptor.
//
// The choice is registered: the lowest context that is free and neither starting nor being
// handed a descriptor this cycle. The hand-off itself is registered too: a handshake loads
// desc_o and one bit of start_o, and the context starts from those flip-flops a clock later.
// So the descriptor handshake (which crosses the die from the generator) ends in a few
// registers, and the level controllers load from registers beside the contexts.
// desc_ready_o is a function of flip-flops only (and hold_i, a register of the tag pool); the
// soft reset is kept out of it (it is one net to every flip-flop of the engine): a descriptor
// taken during a clear is dropped by the clear of start_o, as everything else in flight is.
`include "msr_flops.svh"
module msr_ctx_alloc import msr_pkg::*; #(
  parameter int unsigned NUM_CTX = 8, parameter int unsigned CTX_W = $clog2(NUM_CTX)
) (
  input  logic               clk_i, rst_ni, clear_i,  // clear: drops a start in flight
  input  logic [NUM_CTX-1:0] ctx_free_i,    // contexts without a tile
  input  logic               hold_i,        // take no descriptor (the tags are being reset)
  input  logic               desc_valid_i,  // tile descriptor from the generator
  output logic               desc_ready_o,
  input  tile_desc_t         desc_i,
  output logic [NUM_CTX-1:0] start_o,       // one-hot: this context takes desc_o now
  output tile_desc_t         desc_o         // the descriptor taken a clock before
);

  typedef logic [CTX_W-1:0] ctx_t;

  logic [CTX_W-1:0]   alloc, alloc_q;
  logic               none_avail, any_free_q, desc_hs;
  logic [NUM_CTX-1:0] hs_onehot;

  assign desc_ready_o = any_free_q && !hold_i;
  assign desc_hs      = desc_valid_i && desc_ready_o;
  for (genvar c = 0; c < NUM_CTX; c++) begin : g_start
    assign hs_onehot[c] = desc_hs && (alloc_q == ctx_t'(c));
  end

  msr_lzc #(.WIDTH(NUM_CTX), .CNT_W(CTX_W)) u_alloc (
    .in_i    (ctx_free_i & ~start_o & ~hs_onehot),
    .cnt_o   (alloc),
    .empty_o (none_avail)
  );

  // the choice is remade every clock, so a clear need not reset it
  `MSR_CLR_REG(u_alloc_q, CTX_W, 1'b0, 1'b1, alloc, alloc_q)
  `MSR_CLR_REG(u_start_q, 1 + NUM_CTX, clear_i, 1'b1, {!none_avail, hs_onehot},
               {any_free_q, start_o})

  // data: used only with a start bit
  tile_desc_t desc_q;
  always_ff @(posedge clk_i) begin
    if (desc_hs) desc_q <= desc_i;
  end
  assign desc_o = desc_q;

endmodule : msr_ctx_alloc
