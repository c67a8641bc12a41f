// Formal harness of msr_spill_reg: every input free, reset assumed in the first cycle.
// Proves: no word lost or duplicated (the words held equal a reference count of the
// handshakes, at most two), words leave in order (a word chosen by the solver with track_i
// leaves intact after exactly the words pushed before it), and the output is held while the
// consumer stalls.
module msr_spill_reg_fv #(
  parameter int unsigned WIDTH = 4
) (
  input logic             clk_i, rst_ni, clear_i,
  input logic             valid_i, ready_i,    // the producer's valid, the consumer's ready
  input logic [WIDTH-1:0] data_i,
  input logic             track_i              // the solver picks the tracked word with this
);
  logic             ready_o, valid_o;
  logic [WIDTH-1:0] data_o;

  msr_spill_reg #(.WIDTH(WIDTH)) dut (
    .clk_i, .rst_ni, .clear_i, .valid_i, .ready_o, .data_i, .valid_o, .ready_i, .data_o
  );

  msr_fv_init u_init (.clk_i, .rst_ni, .init_o());

  wire push = valid_i && ready_o;
  wire pop  = valid_o && ready_i;

  // Words held, by the handshakes, and one tracked word: its value and the words ahead of it
  // (formal/common/msr_fv_queue_ref.sv; the spill register is an in-order queue of two).
  logic [2:0]       ref_q;
  logic             trk_q;
  logic [WIDTH-1:0] trk_data_q;
  logic [1:0]       trk_pos_q;
  msr_fv_queue_ref #(.WIDTH(WIDTH), .DEPTH(2)) u_ref (
    .clk_i, .rst_ni, .clear_i, .push_i(push), .pop_i(pop), .track_i, .data_i,
    .ref_o(ref_q), .trk_o(trk_q), .trk_data_o(trk_data_q), .trk_pos_o(trk_pos_q)
  );

  // Output held while stalled is msr_spill_reg.sv's own a_out_hold (the RTL's assertions hold
  // under FORMAL); the stability checker of the protocol checkers gives the covers their
  // stall (a clear counts as taking the word).
  logic hold_viol;
  msr_chk_stable #(.W(WIDTH)) u_hold (
    .clk_i, .rst_ni, .valid_i(valid_o), .ready_i(ready_i || clear_i), .payload_i(data_o),
    .viol_o(hold_viol)
  );
  wire stall_q = u_hold.wait_q;   // offered and not taken last cycle

  a_count:     assert property (@(posedge clk_i) disable iff (!rst_ni) ref_q <= 2);
  a_valid:     assert property (@(posedge clk_i) disable iff (!rst_ni) valid_o == (ref_q != 0));
  a_ready:     assert property (@(posedge clk_i) disable iff (!rst_ni) ready_o == (ref_q != 2));
  a_trk_order: assert property (@(posedge clk_i) disable iff (!rst_ni)
                                !(trk_q && trk_pos_q == 0) || (valid_o && data_o == trk_data_q));
  a_trk_inside: assert property (@(posedge clk_i) disable iff (!rst_ni) !trk_q || trk_pos_q < ref_q);

  // Induction strengtheners on the two entries.
  a_entries: assert property (@(posedge clk_i) disable iff (!rst_ni)
                              ref_q == 3'(dut.a_full_q) + 3'(dut.b_full_q) && (dut.a_full_q || !dut.b_full_q));
  a_trk_b:   assert property (@(posedge clk_i) disable iff (!rst_ni)
                              !(trk_q && trk_pos_q == 1) || dut.b_data_q == trk_data_q);

  // Non-vacuity: both entries full; a push into B while A stalls; full throughput (push and
  // pop in the same cycle); the tracked word leaving from B's position; stall then release.
  c_full:       cover property (@(posedge clk_i) disable iff (!rst_ni) ref_q == 2);
  c_through:    cover property (@(posedge clk_i) disable iff (!rst_ni) push && pop && ref_q == 1);
  c_trk_second: cover property (@(posedge clk_i) disable iff (!rst_ni)
                                trk_q && trk_pos_q == 0 && pop && $past(trk_pos_q) == 1);
  c_stall_go:   cover property (@(posedge clk_i) disable iff (!rst_ni) stall_q && pop);
endmodule
