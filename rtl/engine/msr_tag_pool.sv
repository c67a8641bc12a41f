// Render-request tags of one engine: a free list, the table that says where each answer goes,
// and the set of tags in flight.
//
// The free list is a FIFO of tag numbers, filled with 0..N-1 by an initialisation walk of N
// cycles after reset or clear_i (so a soft reset ends within N cycles whatever the
// neighbours do). A tag leaves the list when a request takes it (alloc_i) and returns when
// its answer is written (release_i). The in-flight bitmap lets the engine refuse an answer
// whose tag is not in flight (stale, duplicate or made up): such an answer is dropped, never
// frees a tag twice and never writes a pixel.
`include "msr_assert.svh"
`include "msr_flops.svh"

module msr_tag_pool #(
  parameter int unsigned N       = 16,                 // tags (power of two, 2..64)
  parameter int unsigned ENTRY_W = 8,                  // what is kept per tag
  parameter int unsigned TAG_W   = $clog2(N)
) (
  input  logic               clk_i,
  input  logic               rst_ni,
  input  logic               clear_i,     // synchronous soft reset: every tag free again
  // allocation
  output logic               avail_o,     // a tag is free (tag_o is the one to take)
  output logic [TAG_W-1:0]   tag_o,
  input  logic               alloc_i,     // take tag_o and remember entry_i for it
  input  logic [ENTRY_W-1:0] entry_i,
  // answers
  input  logic [TAG_W-1:0]   query_tag_i, // look a tag up
  output logic [ENTRY_W-1:0] query_entry_o,
  output logic               query_inflight_o,
  input  logic [TAG_W-1:0]   release_tag_i, // a tag that is answered ...
  input  logic               release_i,     // ... free it
  // status
  output logic [TAG_W:0]     inflight_o,  // tags handed out and not yet answered
  output logic               out_q_o,     // registered: some tag may be out (0: none is)
  output logic               init_o       // the free list is being filled
);

  if (N < 2 || N > 64 || (N & (N - 1)) != 0) begin : g_check_n
    $fatal(1, "msr_tag_pool: N %0d must be a power of two in 2..64", N);
  end

  logic               init_q;
  logic [TAG_W:0]     init_cnt_q;
  logic [N-1:0]       inflight_q;
  logic               out_q;
  logic [ENTRY_W-1:0] table_q [N];
  logic               fifo_valid, fifo_ready;
  logic [TAG_W:0]     fifo_count;

  msr_fifo #(
    .WIDTH (TAG_W),
    .DEPTH (N),
    .OUT_REG (1'b1)   // tag_o from a flip-flop: it addresses the tag table's write
  ) u_free_list (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .flush_i (clear_i),
    .valid_i (init_q || release_i),
    .ready_o (fifo_ready),
    .data_i  (init_q ? TAG_W'(init_cnt_q) : release_tag_i),
    .valid_o (fifo_valid),
    .ready_i (alloc_i),
    .data_o  (tag_o),
    .count_o (fifo_count)
  );

  assign avail_o          = fifo_valid && !init_q;
  assign query_entry_o    = table_q[query_tag_i];
  assign query_inflight_o = inflight_q[query_tag_i];
  // Every tag is either on the free list or in flight, so the count in flight is what the list
  // lacks: a subtract of the list's count register, with no adder behind the allocation
  // (formal/tag_pool checks it against a reference count).
  assign inflight_o       = init_q ? '0 : (TAG_W+1)'(N) - fifo_count;
  assign init_o           = init_q;
  // A register the controller's drain check can read across the die: set while a tag is in
  // flight or was taken last clock, so a clear out_q_o proves no tag is out now (a tag only
  // leaves the list by alloc_i; a_out_covers checks it).
  assign out_q_o          = out_q;

  // Next state of the control registers; the reset and the clear both restart the
  // initialisation with every tag free.
  logic           init_d, out_d;
  logic [TAG_W:0] init_cnt_d;
  logic [N-1:0]   inflight_d;
  always_comb begin
    init_d     = init_q;
    init_cnt_d = init_cnt_q;
    inflight_d = inflight_q;
    out_d      = (inflight_q != '0) || alloc_i;
    if (init_q) begin
      init_cnt_d = init_cnt_q + 1'b1;
      if (32'(init_cnt_q) == N - 1) init_d = 1'b0;
    end
    if (alloc_i)   inflight_d[tag_o]         = 1'b1;
    if (release_i) inflight_d[release_tag_i] = 1'b0;
  end

  `MSR_CLR_REG_RST(u_ctl_q, 2 + TAG_W + 1 + N, {1'b1, (TAG_W+1)'(0), N'(0), 1'b0}, clear_i, 1'b1,
                   {init_d, init_cnt_d, inflight_d, out_d}, {init_q, init_cnt_q, inflight_q, out_q})

  always_ff @(posedge clk_i) begin
    if (alloc_i) table_q[tag_o] <= entry_i;
  end

  /* verilator lint_off SYNCASYNCNET */
  `MSR_ASSERT_IMP(a_alloc_avail, alloc_i, avail_o)
  `MSR_ASSERT_IMP(a_alloc_free, alloc_i, !inflight_q[tag_o])
  `MSR_ASSERT_IMP(a_release_inflight, release_i, inflight_q[release_tag_i] && !init_q)
  `MSR_ASSERT_IMP(a_no_overflow, (init_q || release_i), fifo_ready)
  `MSR_ASSERT_IMP(a_conserved, !init_q, $countones(inflight_q) == 32'(inflight_o))
  `MSR_ASSERT_IMP(a_out_covers, !out_q, inflight_q == '0)
  `MSR_COVER(c_all_inflight, inflight_o == (TAG_W+1)'(N))
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_tag_pool
