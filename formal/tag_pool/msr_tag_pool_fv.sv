// Formal harness of msr_tag_pool (N tags): the engine side is free within the pool's
// contract (alloc_i only while avail_o, release_i only of a tag in flight (release_tag_i), outside the
// initialisation walk), reset assumed in the first cycle.
// Proves: a reference set of tags in flight (updated by alloc_i / release_i) equals the pool's
// own view (query_inflight_o, inflight_o); no tag is handed out while in flight; after the
// walk, free + in flight = N, and every tag is either in flight or exactly once in the free
// list; the walk ends within N cycles of reset or clear_i.
module msr_tag_pool_fv #(
  parameter int unsigned N       = 4,
  parameter int unsigned ENTRY_W = 2
) (
  input logic                 clk_i,
  input logic                 rst_ni,
  input logic                 clear_i,
  input logic                 alloc_i,
  input logic [ENTRY_W-1:0]   entry_i,
  input logic [$clog2(N)-1:0] query_tag_i,
  input logic [$clog2(N)-1:0] release_tag_i,
  input logic                 release_i
);
  localparam int unsigned TAG_W = $clog2(N);
  typedef logic [TAG_W:0] cnt_t;

  logic               avail_o, query_inflight_o, init_o, out_q_o;
  logic [TAG_W-1:0]   tag_o;
  logic [ENTRY_W-1:0] query_entry_o;
  logic [TAG_W:0]     inflight_o;

  msr_tag_pool #(.N(N), .ENTRY_W(ENTRY_W)) dut (
    .clk_i, .rst_ni, .clear_i, .avail_o, .tag_o, .alloc_i, .entry_i, .query_tag_i,
    .query_entry_o, .query_inflight_o, .release_tag_i, .release_i, .inflight_o, .out_q_o, .init_o
  );

  logic init_q = 1'b1;
  always_ff @(posedge clk_i) init_q <= 1'b0;
  always_comb if (init_q) assume (!rst_ni);

  // Reference set of tags in flight and the entry remembered for each.
  logic [N-1:0]       ref_q;
  logic [N-1:0][ENTRY_W-1:0] ref_entry_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni)      ref_q <= '0;
    else if (clear_i) ref_q <= '0;
    else begin
      if (alloc_i)   ref_q[tag_o]       <= 1'b1;
      if (release_i) ref_q[release_tag_i] <= 1'b0;
    end
  end
  always_ff @(posedge clk_i) if (alloc_i) ref_entry_q[tag_o] <= entry_i;

  // The engine's side of the contract.
  always_comb begin
    if (rst_ni && alloc_i)   assume (avail_o);
    if (rst_ni && release_i) assume (ref_q[release_tag_i] && !init_o);
  end

  cnt_t ref_cnt, walk_q;
  always_comb begin
    ref_cnt = '0;
    for (int i = 0; i < N; i++) ref_cnt += cnt_t'(ref_q[i]);
  end
  // Cycles since reset or clear_i, saturating (bounds the walk).
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni)                walk_q <= '0;
    else if (clear_i)           walk_q <= '0;
    else if (walk_q != cnt_t'(N)) walk_q <= walk_q + 1'b1;
  end

  a_no_double:  assert property (@(posedge clk_i) disable iff (!rst_ni) !avail_o || !ref_q[tag_o]);
  a_query:      assert property (@(posedge clk_i) disable iff (!rst_ni) query_inflight_o == ref_q[query_tag_i]);
  a_inflight:   assert property (@(posedge clk_i) disable iff (!rst_ni) inflight_o == ref_cnt);
  // The registered "a tag may be out" flag never says none while the reference has one.
  a_out_q:      assert property (@(posedge clk_i) disable iff (!rst_ni) out_q_o || ref_q == '0);
  a_conserved:  assert property (@(posedge clk_i) disable iff (!rst_ni)
                                 init_o || 32'(dut.fifo_count) + 32'(ref_cnt) == N);
  a_entry:      assert property (@(posedge clk_i) disable iff (!rst_ni)
                                 !ref_q[query_tag_i] || query_entry_o == ref_entry_q[query_tag_i]);
  a_walk_ends:  assert property (@(posedge clk_i) disable iff (!rst_ni) !init_o || walk_q < cnt_t'(N));
  a_walk_quiet: assert property (@(posedge clk_i) disable iff (!rst_ni) !init_o || (ref_q == '0 && !avail_o));
  // msr_tag_pool.sv's own assertions (a_alloc_free, a_no_overflow, ...) hold under FORMAL
  // too; a_alloc_avail and the release condition are the engine's side of the contract,
  // assumed above.

  // Induction strengtheners: the free list (the FIFO's occupied slots) holds exactly the tags
  // not in flight (with free + in flight = N, each of them once); during the walk it holds
  // 0..walk-1 in order.
  localparam int unsigned PTR_W = TAG_W;
  logic [TAG_W-1:0] slot [N];
  logic [N-1:0]     occ, in_list;
  for (genvar s = 0; s < N; s++) begin : g_slot
    assign slot[s] = dut.u_free_list.mem_q[s];
    assign occ[s]  = cnt_t'(PTR_W'(s - dut.u_free_list.rptr_q)) < dut.fifo_count;
  end
  always_comb begin
    in_list = '0;
    for (int s = 0; s < N; s++) if (occ[s]) in_list[slot[s]] = 1'b1;
  end
  a_list: assert property (@(posedge clk_i) disable iff (!rst_ni) init_o || in_list == ~ref_q);
  for (genvar t = 0; t < N; t++) begin : g_tag
    a_table: assert property (@(posedge clk_i) disable iff (!rst_ni)
                              !ref_q[t] || dut.table_q[t] == ref_entry_q[t]);
    a_walk: assert property (@(posedge clk_i) disable iff (!rst_ni)
                             !init_o || cnt_t'(t) >= dut.init_cnt_q || (occ[t] && slot[t] == TAG_W'(t)));
  end
  a_walk_fifo: assert property (@(posedge clk_i) disable iff (!rst_ni)
                                !init_o || (dut.u_free_list.rptr_q == '0 && dut.fifo_count == dut.init_cnt_q
                                            && dut.init_cnt_q == walk_q));
  a_fifo_ptrs: assert property (@(posedge clk_i) disable iff (!rst_ni)
                                PTR_W'(dut.u_free_list.wptr_q - dut.u_free_list.rptr_q)
                                == PTR_W'(dut.fifo_count) && dut.fifo_count <= cnt_t'(N));
  // The free list's flag and head registers agree with its count and array.
  a_fifo_regs: assert property (@(posedge clk_i) disable iff (!rst_ni)
                                dut.u_free_list.nonempty_q == (dut.fifo_count != '0)
                                && dut.u_free_list.notfull_q == (dut.fifo_count != cnt_t'(N))
                                && dut.u_free_list.g_out_reg.many_q == (dut.fifo_count > cnt_t'(1))
                                && dut.u_free_list.g_out_reg.rnext_q == PTR_W'(dut.u_free_list.rptr_q + 1)
                                && (!dut.u_free_list.nonempty_q || dut.u_free_list.g_out_reg.head_q
                                    == dut.u_free_list.mem_q[dut.u_free_list.rptr_q]));
  a_bitmap:    assert property (@(posedge clk_i) disable iff (!rst_ni)
                                dut.inflight_q == ref_q);

  // Non-vacuity: every tag in flight; alloc and release in the same cycle; the tag released
  // when all were out handed out again next; a clear with tags in flight; the walk's end.
  c_all_out:  cover property (@(posedge clk_i) disable iff (!rst_ni) ref_cnt == cnt_t'(N));
  c_both:     cover property (@(posedge clk_i) disable iff (!rst_ni) alloc_i && release_i);
  c_reuse:    cover property (@(posedge clk_i) disable iff (!rst_ni)
                              alloc_i && $past(release_i) && tag_o == $past(release_tag_i)
                              && $past(ref_cnt) == cnt_t'(N));
  c_clear:    cover property (@(posedge clk_i) disable iff (!rst_ni) clear_i && ref_cnt == cnt_t'(2));
  c_walk_end: cover property (@(posedge clk_i) disable iff (!rst_ni) $past(init_o) && avail_o);
endmodule
