// Formal harness of msr_rr_arb: requests and ready free, reset assumed in the first cycle.
// Proves: the grant is one-hot (or zero without requests), only to a requester, idx_o names
// it; fairness: while requester K (chosen by the solver, fixed after reset) holds its request,
// at most N-1 grants to others are taken before its own; with LOCK, an offered grant that is
// not taken stays while its request stays.
module msr_rr_arb_fv #(
  parameter int unsigned N      = 4,
  parameter bit          LOCK   = 1'b0,
  parameter bit          PREFIX = 1'b0,    // the LUT prefix choice instead of the carry chain
  parameter bit          MASKS  = 1'b0     // each grant from registered masks
) (
  input logic                 clk_i,
  input logic                 rst_ni,
  input logic                 clear_i,
  input logic [N-1:0]         req_i,
  input logic                 ready_i,
  input logic [$clog2(N)-1:0] k_i        // the watched requester
);
  localparam int unsigned IDX_W = $clog2(N);

  logic [N-1:0]     gnt_o;
  logic [IDX_W-1:0] idx_o;
  logic             valid_o;

  msr_rr_arb #(.N(N), .LOCK(LOCK), .PREFIX(PREFIX), .MASKS(MASKS)) dut (
    .clk_i, .rst_ni, .clear_i, .req_i, .gnt_o, .idx_o, .valid_o, .ready_i
  );

  logic init_q;
  msr_fv_init u_init (.clk_i, .rst_ni, .init_o(init_q));
  // K is fixed for the whole run.
  logic [IDX_W-1:0] k_q;
  always_ff @(posedge clk_i) k_q <= k_i;
  always_comb if (!init_q) assume (k_i == k_q);

  wire taken = valid_o && ready_i;

  // Grants taken by others while K waits (its request held and not yet served).
  logic [IDX_W:0] wait_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni)                                      wait_q <= '0;
    else if (clear_i || !req_i[k_i] || (taken && gnt_o[k_i])) wait_q <= '0;
    else if (taken)                                   wait_q <= wait_q + 1'b1;
  end

  // Round-robin distance from the last winner to K (requesters strictly between them);
  // the last winner is the bit below the lowest set bit of the mask (N-1 when it is empty).
  typedef logic [IDX_W:0] cnt_t;
  typedef logic [N-1:0]   vec_t;
  cnt_t last_w, k_dist;
  always_comb begin
    last_w = cnt_t'(N - 1);
    for (int i = N - 1; i >= 1; i--) if (dut.above_q[i]) last_w = cnt_t'(i - 1);
    k_dist = ({1'b0, k_i} > last_w) ? cnt_t'({1'b0, k_i} - last_w - 1)
                                  : cnt_t'(N - 1 - last_w + {1'b0, k_i});
  end

  wire [N-1:0] above_low = dut.above_q & (~dut.above_q + 1'b1);

  a_onehot:    assert property (@(posedge clk_i) disable iff (!rst_ni) (gnt_o & (gnt_o - 1'b1)) == '0);
  a_requested: assert property (@(posedge clk_i) disable iff (!rst_ni) (gnt_o & ~req_i) == '0);
  a_when_req:  assert property (@(posedge clk_i) disable iff (!rst_ni) (req_i != '0) == (gnt_o != '0));
  a_valid:     assert property (@(posedge clk_i) disable iff (!rst_ni) valid_o == (req_i != '0));
  a_idx:       assert property (@(posedge clk_i) disable iff (!rst_ni) !valid_o || gnt_o[idx_o]);
  a_fair:      assert property (@(posedge clk_i) disable iff (!rst_ni) wait_q <= N - 1);
  // Induction strengtheners: the mask is "every requester above one position" (or empty),
  // and K's wait plus its distance from the last winner never exceeds N-1.
  a_mask:      assert property (@(posedge clk_i) disable iff (!rst_ni) vec_t'(dut.above_q + above_low) == '0 && !dut.above_q[0]);
  a_fair_dist: assert property (@(posedge clk_i) disable iff (!rst_ni) wait_q + k_dist <= N - 1);

  if (MASKS) begin : g_masks
    // The registered masks give the chain's grant (so every property above holds for them),
    // and follow the pointer: "i outranks j" restated from above_q, the induction's invariant.
    logic [N-1:0][N-1:0] outrank_ref;
    always_comb begin
      for (int i = 0; i < N; i++) begin
        for (int j = 0; j < N; j++) begin
          // j outranks i: both above the last winner or both not, and j lower; or j above, i not
          outrank_ref[i][j] = (dut.above_q[j] == dut.above_q[i]) ? (j < i)
                                                                 : dut.above_q[j];
        end
      end
    end
    a_masks_chain: assert property (@(posedge clk_i) disable iff (!rst_ni)
                                    dut.gnt == dut.gnt_chain);
    a_masks_ptr:   assert property (@(posedge clk_i) disable iff (!rst_ni)
                                    dut.g_masks.outrank_q == outrank_ref);
  end

  if (LOCK) begin : g_lock
    // The grant offered and not taken last cycle (a clear counts as taken), registered by
    // the handshake rule of the protocol checkers (rtl/checkers/msr_chk_stable.sv).
    msr_chk_stable #(.W(N)) u_offered (
      .clk_i, .rst_ni, .valid_i(valid_o), .ready_i(ready_i || clear_i), .payload_i(gnt_o),
      .viol_o()
    );
    wire         offered_q     = u_offered.wait_q;
    wire [N-1:0] offered_gnt_q = u_offered.payload_q;
    a_lock_hold: assert property (@(posedge clk_i) disable iff (!rst_ni)
                                  !(offered_q && (req_i & offered_gnt_q) != '0) || gnt_o == offered_gnt_q);
    a_lock_state: assert property (@(posedge clk_i) disable iff (!rst_ni)
                                   dut.g_lock.lock_q == offered_q && (!offered_q || dut.g_lock.locked_q == offered_gnt_q));
    // A lock formed while K waits (after a grant taken past it) points between the last
    // winner and K, so taking it still moves the round-robin position towards K.
    cnt_t j_dist, j_idx;
    always_comb begin
      j_idx = '0;
      for (int i = 0; i < N; i++) if (dut.g_lock.locked_q[i]) j_idx = cnt_t'(i);
      j_dist = (j_idx > last_w) ? cnt_t'(j_idx - last_w - 1) : cnt_t'(N - 1 - last_w + j_idx);
    end
    a_lock_onehot: assert property (@(posedge clk_i) disable iff (!rst_ni)
                                    !dut.g_lock.lock_q || (dut.g_lock.locked_q != '0 &&
                                    (dut.g_lock.locked_q & (dut.g_lock.locked_q - 1'b1)) == '0));
    a_lock_fair:   assert property (@(posedge clk_i) disable iff (!rst_ni)
                                    !(dut.g_lock.lock_q && wait_q != '0) || j_dist <= k_dist);
    c_lock_held: cover property (@(posedge clk_i) disable iff (!rst_ni)
                                 offered_q && (req_i & offered_gnt_q) != '0 && (req_i & ~offered_gnt_q) != '0 && taken);
  end

  // Non-vacuity: K served after waiting N-1 grants (the fairness bound is reached); all
  // requesting at once; a grant taken while others wait.
  c_wait_max: cover property (@(posedge clk_i) disable iff (!rst_ni) wait_q == N - 1 && taken && gnt_o[k_i]);
  c_all_req:  cover property (@(posedge clk_i) disable iff (!rst_ni) req_i == '1 && taken);
endmodule
