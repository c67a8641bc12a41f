// Formal harness of msr_fifo: every input free, reset assumed in the first cycle.
// Proves: count_o equals a reference count of the handshakes (so no overflow, no underflow),
// ready_o / valid_o follow it, the pointers agree with it, and one word chosen by the solver
// (track_i on its push) leaves the FIFO intact, after exactly the words pushed before it.
module msr_fifo_fv #(
  parameter int unsigned WIDTH = 4,
  parameter int unsigned DEPTH = 4,
  parameter bit          OUT_REG = 1'b0
) (
  input logic             clk_i, rst_ni, flush_i,
  input logic             valid_i, ready_i,    // the producer's valid, the consumer's ready
  input logic [WIDTH-1:0] data_i,
  input logic             track_i              // the solver picks the tracked word with this
);
  localparam int unsigned PTR_W = $clog2(DEPTH);

  logic             ready_o, valid_o;
  logic [WIDTH-1:0] data_o;
  logic [PTR_W:0]   count_o;

  msr_fifo #(.WIDTH(WIDTH), .DEPTH(DEPTH), .OUT_REG(OUT_REG)) dut (
    .clk_i, .rst_ni, .flush_i, .valid_i, .ready_o, .data_i, .valid_o, .ready_i, .data_o, .count_o
  );

  // Reset in the first cycle; afterwards reset may come at any time.
  msr_fv_init u_init (.clk_i, .rst_ni, .init_o());

  wire push = valid_i && ready_o;
  wire pop  = valid_o && ready_i;

  // Reference count of the words held and one tracked word: its value and how many words are
  // ahead of it (formal/common/msr_fv_queue_ref.sv).
  logic [PTR_W+1:0] ref_q;
  logic             trk_q;
  logic [WIDTH-1:0] trk_data_q;
  logic [PTR_W:0]   trk_pos_q;
  msr_fv_queue_ref #(.WIDTH(WIDTH), .DEPTH(DEPTH)) u_ref (
    .clk_i, .rst_ni, .clear_i(flush_i), .push_i(push), .pop_i(pop), .track_i, .data_i,
    .ref_o(ref_q), .trk_o(trk_q), .trk_data_o(trk_data_q), .trk_pos_o(trk_pos_q)
  );

  // The contract.
  a_count:      assert property (@(posedge clk_i) disable iff (!rst_ni) count_o == ref_q);
  a_range:      assert property (@(posedge clk_i) disable iff (!rst_ni) ref_q <= DEPTH);
  a_ready:      assert property (@(posedge clk_i) disable iff (!rst_ni) ready_o == (ref_q != DEPTH));
  a_valid:      assert property (@(posedge clk_i) disable iff (!rst_ni) valid_o == (ref_q != 0));
  a_trk_inside: assert property (@(posedge clk_i) disable iff (!rst_ni) !trk_q || trk_pos_q < ref_q);
  a_trk_order:  assert property (@(posedge clk_i) disable iff (!rst_ni)
                                 !(trk_q && trk_pos_q == 0) || (valid_o && data_o == trk_data_q));

  // Induction strengtheners on the internal state (pointers agree with the count; the
  // tracked word sits trk_pos_q entries after the read pointer).
  wire [PTR_W-1:0] trk_slot = dut.rptr_q + trk_pos_q[PTR_W-1:0];
  a_ptrs:     assert property (@(posedge clk_i) disable iff (!rst_ni)
                               PTR_W'(dut.wptr_q - dut.rptr_q) == ref_q[PTR_W-1:0]);
  a_trk_slot: assert property (@(posedge clk_i) disable iff (!rst_ni)
                               !trk_q || dut.mem_q[trk_slot] == trk_data_q);

  // With the output register: it holds the head, and its helpers agree with the count.
  if (OUT_REG) begin : g_out_reg_inv
    a_head_reg: assert property (@(posedge clk_i) disable iff (!rst_ni)
                                 !dut.nonempty_q || dut.g_out_reg.head_q == dut.mem_q[dut.rptr_q]);
    a_many_reg: assert property (@(posedge clk_i) disable iff (!rst_ni)
                                 dut.g_out_reg.many_q == (ref_q > 1) &&
                                 dut.g_out_reg.rnext_q == PTR_W'(dut.rptr_q + 1));
  end

  // Non-vacuity: full, emptied again, the tracked word out after others, push and pop at once
  // when full is refused (ready_o low), a flush with words inside.
  c_full:       cover property (@(posedge clk_i) disable iff (!rst_ni) ref_q == DEPTH);
  c_trk_out:    cover property (@(posedge clk_i) disable iff (!rst_ni)
                                trk_q && trk_pos_q == 0 && pop && $past(trk_pos_q) == DEPTH - 1);
  c_full_pop:   cover property (@(posedge clk_i) disable iff (!rst_ni) ref_q == DEPTH && pop && valid_i);
  c_flush_full: cover property (@(posedge clk_i) disable iff (!rst_ni) ref_q == DEPTH && flush_i);
endmodule
