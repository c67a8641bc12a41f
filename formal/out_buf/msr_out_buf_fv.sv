// Formal harness of msr_out_buf (the tile engine's output buffer and its credits). The
// decision pipeline is modelled as the engine's is: a fixed delay line from an issue to its
// result (LAT clocks, never stalling, emptied by the soft reset); the issue is free but, as in
// the engine, only with a credit left; the output's ready is free. Each result carries the
// issue's sequence number. Reset assumed in the first cycle.
// Proves: the buffer always takes what the pipeline delivers (the credits are never wrong);
// credits plus results in the pipeline and the buffer are always the depth; every issue is
// accounted for until it leaves (none lost or doubled); the output holds its word while
// stalled. Task bmc: results leave in issue order (12 clocks).
module msr_out_buf_fv #(
  parameter int unsigned DEPTH = 4,
  parameter int unsigned LAT   = 3,
  parameter int unsigned SEQ_W = 4
) (
  input logic clk_i, rst_ni, clear_i,
  input logic issue_i,
  input logic ready_i
);
  logic             can_issue_o, valid_o;
  logic [SEQ_W-1:0] data_o;

  // The pipeline: LAT stages of {valid, seq}, cleared with the buffer.
  logic [LAT-1:0]            pv_q;
  logic [LAT-1:0][SEQ_W-1:0] ps_q;
  logic [SEQ_W-1:0]          next_q;   // sequence number of the next issue
  logic [SEQ_W-1:0]          exp_q;    // sequence number of the next result out

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      pv_q <= '0; next_q <= '0; exp_q <= '0;
    end else if (clear_i) begin
      pv_q <= '0; next_q <= '0; exp_q <= '0;
    end else begin
      pv_q   <= {pv_q[LAT-2:0], issue_i};
      next_q <= next_q + SEQ_W'(issue_i);
      exp_q  <= exp_q + SEQ_W'(valid_o && ready_i);
    end
  end
  always_ff @(posedge clk_i) ps_q <= {ps_q[LAT-2:0], next_q};

  msr_out_buf #(.WIDTH(SEQ_W), .DEPTH(DEPTH)) dut (
    .clk_i, .rst_ni, .clear_i, .issue_i, .can_issue_o, .valid_i (pv_q[LAT-1]),
    .data_i (ps_q[LAT-1]), .valid_o, .ready_i, .data_o
  );

  msr_fv_init u_init (.clk_i, .rst_ni, .init_o());

  always_comb if (rst_ni) assume (!issue_i || can_issue_o);

  // Results in the pipeline and the buffer (the engine's credit invariant, counted here).
  logic [$clog2(LAT+1)-1:0] in_pipe;
  always_comb begin
    in_pipe = '0;
    for (int i = 0; i < LAT; i++) in_pipe += pv_q[i];
  end

  logic [SEQ_W-1:0] outstanding;     // issued and not yet out (modulo 2^SEQ_W)
  assign outstanding = next_q - exp_q;

  // The output held while stalled.
  logic             stall_q;
  logic [SEQ_W-1:0] word_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) stall_q <= 1'b0;
    else         stall_q <= valid_o && !ready_i && !clear_i;
  end
  always_ff @(posedge clk_i) word_q <= data_o;

  always_comb begin
    if (rst_ni && !clear_i) begin
      a_room:     assert (!pv_q[LAT-1] || dut.buf_ready);
      // a credit is back when its result moves on into the spill register
      a_credits:  assert (32'(dut.credit_q) + 32'(dut.buf_count) + 32'(in_pipe) == DEPTH);
`ifdef CHECK_ORDER
      // bounded (task bmc): the order is msr_fifo's and msr_spill_reg's own, proved unbounded
      // by their jobs (formal/fifo, formal/spill_reg); this checks that the two are chained in
      // order
      a_order:    assert (!valid_o || data_o == exp_q);
`endif
      // the parts' own invariants (their jobs prove them), stated for the induction
      a_fifo_range: assert (dut.buf_count <= ($clog2(DEPTH) + 1)'(DEPTH));
      a_fifo_flags: assert (dut.u_fifo.notfull_q == (dut.buf_count != ($clog2(DEPTH) + 1)'(DEPTH))
                            && dut.u_fifo.nonempty_q == (dut.buf_count != '0));
      a_fifo_ptrs:  assert ($clog2(DEPTH)'(dut.u_fifo.wptr_q - dut.u_fifo.rptr_q)
                            == $clog2(DEPTH)'(dut.buf_count));
      a_spill:      assert (!dut.u_spill.b_full_q || dut.u_spill.a_full_q);
      a_held:     assert (!stall_q || (valid_o && data_o == word_q));
      // (the spill register holds up to two: its output word and its skid entry)
      a_outstanding: assert (32'(outstanding) == 32'(in_pipe) + 32'(dut.buf_count)
                             + 32'(dut.u_spill.a_full_q) + 32'(dut.u_spill.b_full_q));
    end
  end

  always_comb begin
    if (rst_ni) begin
      c_no_credit: cover (!can_issue_o && valid_o && ready_i);
      c_full:      cover (dut.buf_count == ($clog2(DEPTH) + 1)'(DEPTH));
    end
  end
endmodule
