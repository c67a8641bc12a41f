// Issue: round robin over the contexts whose next position may go, the grant registered.
//
// No stage between the issue and the output buffer ever stalls: a position is granted only
// with a free slot in that buffer reserved for it (a credit, can_issue_i), so the pipeline
// registers need no enable and the issue does not wait on the output's handshake.
//
// The grant is registered (GR): the arbiter's output goes into flip-flops beside it, and the
// contexts, spread over the die with their tile buffers, see a register one clock later
// (gr_gnt_o: the head leaves, the buffer reads it). The contexts' candidate bits know about
// the grant in flight, so a context can still win every clock.
//
// CYCLE > 1 (a tile buffer whose macro takes an address on a port only once per CYCLE clocks,
// docs/asic.md): a context granted now is masked for the next CYCLE - 1 clocks, so its buffer's
// read ports see one address per CYCLE clocks; the other contexts fill the clocks between.
`include "msr_assert.svh"
`include "msr_flops.svh"

module msr_ctx_issue import msr_pkg::*; #(
  parameter int unsigned NUM_CTX = 8, parameter int unsigned CTX_W = $clog2(NUM_CTX),
  parameter int unsigned CYCLE   = 1   // clocks between two grants of one context (1..8)
) (
  input  logic                     clk_i, rst_ni, clear_i,  // clear: synchronous soft reset
  // each context's candidate alternatives (registers): the tail may go while its head leaves
  // (the grant in flight, gr_gnt_o), the head otherwise
  input  logic     [NUM_CTX-1:0]   cand_tail_i,
  input  logic     [NUM_CTX-1:0]   cand_head_i,
  input  eng_pos_t [NUM_CTX-1:0]   pos_i,        // each context's head position
  input  logic                     can_issue_i,  // an output-buffer slot is free (a credit)
  output logic                     issue_o,      // a grant this cycle (takes the credit)
  output logic                     gr_valid_o,   // GR: a grant registered ...
  output logic     [NUM_CTX-1:0]   gr_gnt_o,     // ... one-hot (the contexts' issue_i) ...
  output logic     [CTX_W-1:0]     gr_ctx_o,     // ... its index ...
  output eng_pos_t                 gr_pos_o      // ... and the granted head's position
);

  logic               arb_valid;
  logic [CTX_W-1:0]   gnt_idx;
  logic [NUM_CTX-1:0] gnt, cand;

  // The contexts whose position may go: one LUT per context, here beside the grant register
  // and the arbiter, so that the path can cross from a context once, from its flip-flops (the
  // placer decides where the LUT goes: msr_tile_ctx).
  logic [NUM_CTX-1:0] may_go;          // the context's buffer takes an address next clock
  assign cand = ((gr_gnt_o & cand_tail_i) | (~gr_gnt_o & cand_head_i)) & may_go;

  msr_rr_arb #(.N(NUM_CTX), .IDX_W(CTX_W)) u_issue_arb (
    .clk_i, .rst_ni, .clear_i,
    .req_i (cand), .gnt_o (gnt), .idx_o (gnt_idx), .valid_o (arb_valid), .ready_i (can_issue_i)
  );

  assign issue_o = arb_valid && can_issue_i;

  // The buffers' cycle: CYCLE - 1 clocks of rest after a grant, the "may go" bit a register
  // per context (the arbiter's path starts at flip-flops, as above).
  msr_rest_timer #(.N(NUM_CTX), .CYCLE(CYCLE)) u_rest (
    .clk_i, .rst_ni, .clear_i, .use_i (gnt & {NUM_CTX{can_issue_i}}), .free_o (may_go)
  );
  if (CYCLE < 1 || CYCLE > 8) begin : g_check_cycle
    $fatal(1, "msr_ctx_issue: CYCLE %0d must be in 1..8", CYCLE);
  end

  `MSR_CLR_REG(u_gr_q, 1 + NUM_CTX, clear_i, 1'b1, {issue_o, gnt & {NUM_CTX{can_issue_i}}},
               {gr_valid_o, gr_gnt_o})

  // The granted context's index, encoded from the registered one-hot grant (one LUT level in
  // the short GR -> IS path) rather than registered from the arbiter's index output (two LUT
  // levels more behind its carry chain, the engine's longest path).
  msr_onehot_to_bin #(.N(NUM_CTX), .IDX_W(CTX_W)) u_gr_ctx (
    .onehot_i (gr_gnt_o), .bin_o (gr_ctx_o)
  );
  logic unused_gnt_idx;
  assign unused_gnt_idx = ^gnt_idx;

  // The granted position, picked with the one-hot grant (an AND-OR, not an index multiplexer).
  always_comb begin
    gr_pos_o = '0;
    for (int unsigned c = 0; c < NUM_CTX; c++) begin
      gr_pos_o |= pos_i[c] & {$bits(eng_pos_t){gr_gnt_o[c]}};
    end
  end

  /* verilator lint_off SYNCASYNCNET */
  `MSR_ASSERT(a_gnt_onehot, $onehot0(gr_gnt_o))
  `MSR_ASSERT(a_gr_valid, gr_valid_o == (gr_gnt_o != '0))
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_ctx_issue
