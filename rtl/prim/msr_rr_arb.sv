// Round-robin arbiter, in the manner of common_cells' rr_arb_tree: a request vector in, a
// one-hot grant and its index out. The requester after the last one served has priority, so
// every requester is served within N grants. The pointer moves only when the grant is taken
// (valid_o && ready_i); with LOCK set, a grant that was offered and not taken is held while
// its request stays up, so a valid/ready consumer sees stable data.
//
// Timing: the "requests above the last winner" mask is a register (a thermometer code), and
// the grant and the next mask both come from the lowest set bit of {requests, requests above
// the last winner}: one 2N-bit carry chain (or, with PREFIX, a prefix OR in LUTs), so the
// grant is a handful of LUT levels for any N. With MASKS the grant comes instead from
// registered per-requester masks (below); the chain then only gives the next pointer.
`include "msr_assert.svh"
`include "msr_flops.svh"

module msr_rr_arb #(
  parameter int unsigned N     = 4,                      // requesters, >= 1
  parameter bit          LOCK  = 1'b0,                   // hold an offered, untaken grant
  parameter bit          PREFIX = 1'b0,                  // the choice in LUTs, not a carry chain
  parameter bit          MASKS = 1'b0,                   // each grant from registered masks
  parameter int unsigned IDX_W = (N > 1) ? $clog2(N) : 1
) (
  input  logic             clk_i,     // clock
  input  logic             rst_ni,    // asynchronous reset, active low
  input  logic             clear_i,   // synchronous: pointer back to requester 0
  input  logic [N-1:0]     req_i,     // requests
  output logic [N-1:0]     gnt_o,     // one-hot grant (0 when no request)
  output logic [IDX_W-1:0] idx_o,     // index of the granted requester
  output logic             valid_o,   // some request is granted
  input  logic             ready_i    // the grant is taken this cycle
);

  if (N < 1) begin : g_check_n
    $fatal(1, "msr_rr_arb: N must be >= 1, got %0d", N);
  end

  logic [N-1:0]   above_q, above_d;   // requesters strictly after the last winner
  logic [2*N-1:0] both, below_incl, lowest;
  logic [N-1:0]   gnt, above_pick;

  // One 2N-bit vector for the whole choice: the requests above the last winner in the low half,
  // all requests in the high half; its lowest set bit is the winner (in the high half only
  // when nobody above the last winner asks). below_incl marks the bits up to and including
  // the lowest set one (x ^ (x - 1)); the pointer for the next round comes from the same
  // vector, not from a second chain behind the grant.
  assign both = {req_i, req_i & above_q};
  if (PREFIX) begin : g_prefix_or
    // A prefix OR in LUTs, for an arbiter whose requesters are spread over the die: a carry
    // chain sits in one column, and the placer pulled the render mux's four queue heads across
    // to it and back (most of that path was wire in the default top); LUTs can sit beside the
    // queues. Where the requesters are close, the carry chain is the faster (the writer's
    // input arbiter made the top slower with this). Same function: bit i is set while
    // no request is set below it.
    always_comb begin
      logic seen;
      seen = 1'b0;
      for (int unsigned i = 0; i < 2*N; i++) begin
        below_incl[i] = !seen;
        seen          = seen | both[i];
      end
    end
  end else begin : g_carry_chain
    assign below_incl = both ^ (both - 1'b1);
  end
  logic [N-1:0] gnt_chain;
  assign lowest     = both & below_incl;
  assign gnt_chain  = lowest[N-1:0] | lowest[2*N-1:N];
  assign above_pick = below_incl[N] ? ~below_incl[2*N-1:N] : ~below_incl[N-1:0];

  // The masks' register of MASKS (below), at module level: its reset value is a constant call.
  typedef logic [N-1:0][N-1:0] outrank_t;
  function automatic outrank_t outrank_of(logic [N-1:0] above);
    outrank_t m;
    for (int unsigned i = 0; i < N; i++) begin
      for (int unsigned j = 0; j < N; j++) begin
        if (j < i)      m[i][j] = !above[i] || above[j];
        else if (j > i) m[i][j] = !above[i] && above[j];
        else            m[i][j] = 1'b0;
      end
    end
    return m;
  endfunction

  if (MASKS) begin : g_masks
    // Each grant from a registered mask: outrank_q[i] holds the requesters that outrank i this
    // round (below i: all of them unless i is above the last winner, then those above it too;
    // above i: those above the last winner, unless i is), so grant i is request i and none of
    // the masked requests, one AND-OR of the requests and flip-flops (two LUT levels at N = 4)
    // beside requester i. For the render mux: its queue heads' pops went through the prefix
    // chain at the port and back, a path mostly of wire in the BUDGET_EN = 1 top. The
    // pointer's next value (above_d) still comes from the chain, off that path.
    outrank_t outrank_q;
    for (genvar i = 0; i < N; i++) begin : g_gnt
      assign gnt[i] = req_i[i] && (req_i & outrank_q[i]) == '0;
    end
    localparam outrank_t OUTRANK_0 = outrank_of('0);
    `MSR_CLR_REG_RST(u_outrank_q, $bits(outrank_t), OUTRANK_0, clear_i, valid_o && ready_i,
                     outrank_of(above_d), outrank_q)
    /* verilator lint_off SYNCASYNCNET */
    `MSR_ASSERT(a_masks_of_pointer, outrank_q == outrank_of(above_q))
    `MSR_ASSERT(a_masks_match_chain, gnt == gnt_chain)
    /* verilator lint_on SYNCASYNCNET */
  end else begin : g_chain
    assign gnt = gnt_chain;
  end

  if (LOCK) begin : g_lock
    logic [N-1:0] locked_q;   // the grant offered last cycle
    logic         lock_q;     // ... and not taken
    logic         hold;
    assign hold    = lock_q && (req_i & locked_q) != '0;
    assign gnt_o   = hold ? locked_q : gnt;
    // after a held winner w: every requester above w (thermometer ~(w | (w - 1)))
    assign above_d = hold ? ~(locked_q | (locked_q - 1'b1)) : above_pick;
    `MSR_CLR_REG(u_lock_q, 1 + N, clear_i, 1'b1, {valid_o && !ready_i, gnt_o}, {lock_q, locked_q})
  end else begin : g_no_lock
    assign gnt_o   = gnt;
    assign above_d = above_pick;
  end

  assign valid_o = (req_i != '0);

  msr_onehot_to_bin #(.N(N), .IDX_W(IDX_W)) u_idx (.onehot_i (gnt_o), .bin_o (idx_o));

  `MSR_CLR_REG(u_above_q, N, clear_i, valid_o && ready_i, above_d, above_q)

  /* verilator lint_off SYNCASYNCNET */
  `MSR_ASSERT(a_gnt_onehot, $onehot0(gnt_o))
  `MSR_ASSERT(a_gnt_requested, (gnt_o & ~req_i) == '0)
  `MSR_ASSERT(a_gnt_when_req, (req_i != '0) == (gnt_o != '0))
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_rr_arb
