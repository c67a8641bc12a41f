// Formal harness of msr_req_out (the tile engine's output): results, tags and the render
// port's ready free, within the engine's contract: a result, once offered, stays (same trace
// flag) until it leaves; the retro phase (msr_lin_dilate) is high only with a result, and ends
// for good once its request has taken a tag. Reset assumed in the first cycle.
// Proves: a tag is taken only while one is free; an interpolated result is written and leaves
// exactly when its context's port is free (wr_ok_i, free here: a macro's cycle makes it wait);
// a result never leaves in its retro phase; a traced result leaves exactly when
// its request takes a tag; every result takes exactly trace + retro tags (no request lost or
// doubled); the render request is held, unchanged, until taken.
module msr_req_out_fv
  import msr_pkg::*;
#(
  parameter int unsigned TAG_W = 2
) (
  input logic             clk_i, rst_ni, clear_i,
  input logic             out_valid_i, out_trace_i, retro_phase_i, wr_ok_i,
  input coord_t           req_x_i, req_y_i,
  input logic             tag_avail_i,
  input logic [TAG_W-1:0] free_tag_i,
  input logic             req_ready_i
);
  logic             out_ready_o, out_write_o, alloc_tag_o, req_valid_o;
  coord_t           req_x_o, req_y_o;
  logic [TAG_W-1:0] req_tag_o;

  msr_req_out #(.TAG_W(TAG_W)) dut (
    .clk_i, .rst_ni, .clear_i, .out_valid_i, .out_ready_o, .out_trace_i, .retro_phase_i, .wr_ok_i,
    .out_write_o, .req_x_i, .req_y_i, .tag_avail_i, .free_tag_i, .alloc_tag_o, .req_valid_o,
    .req_ready_i, .req_x_o, .req_y_o, .req_tag_o
  );

  msr_fv_init u_init (.clk_i, .rst_ni, .init_o());

  wire done = out_valid_i && out_ready_o;

  // The environment: the result held until it leaves, the retro phase once per result.
  logic held_q, trace_q, rsent_q;
  logic [1:0] n_q;                    // tags the result on offer has taken so far
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      held_q <= 1'b0; rsent_q <= 1'b0; n_q <= '0;
    end else if (clear_i) begin
      held_q <= 1'b0; rsent_q <= 1'b0; n_q <= '0;
    end else begin
      held_q  <= out_valid_i && !out_ready_o;
      rsent_q <= !done && (rsent_q || (retro_phase_i && alloc_tag_o));
      n_q     <= done ? '0 : n_q + 2'(alloc_tag_o);
    end
  end
  always_ff @(posedge clk_i) trace_q <= out_trace_i;
  always_comb begin
    if (rst_ni && !clear_i && held_q) assume (out_valid_i && out_trace_i == trace_q);
    if (rst_ni && retro_phase_i)      assume (out_valid_i && !rsent_q);
  end

  // The request port: valid held until taken, the word unchanged (a clear drops it).
  logic stall_q;
  logic [2*$bits(coord_t)+TAG_W-1:0] word_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) stall_q <= 1'b0;
    else         stall_q <= req_valid_o && !req_ready_i && !clear_i;
  end
  always_ff @(posedge clk_i) word_q <= {req_x_o, req_y_o, req_tag_o};

  a_alloc_avail: assert property (@(posedge clk_i) disable iff (!rst_ni) !alloc_tag_o || tag_avail_i);
  a_write:       assert property (@(posedge clk_i) disable iff (!rst_ni)
                                  out_write_o == (out_valid_i && !out_trace_i && !retro_phase_i && wr_ok_i));
  a_write_waits: assert property (@(posedge clk_i) disable iff (!rst_ni)
                                  !(out_valid_i && !out_trace_i && !wr_ok_i) || !out_ready_o);
  a_write_done:  assert property (@(posedge clk_i) disable iff (!rst_ni) !out_write_o || out_ready_o);
  a_retro_stays: assert property (@(posedge clk_i) disable iff (!rst_ni) !retro_phase_i || !out_ready_o);
  a_trace_req:   assert property (@(posedge clk_i) disable iff (!rst_ni)
                                  !(done && out_trace_i) || alloc_tag_o);
  a_tags:        assert property (@(posedge clk_i) disable iff (!rst_ni || clear_i)
                                  !done || 32'(n_q) + 32'(alloc_tag_o) == 32'(out_trace_i) + 32'(rsent_q));
  // induction strengthener: before it leaves, a result has taken only its retro request's tag
  a_taken:       assert property (@(posedge clk_i) disable iff (!rst_ni) n_q == 2'(rsent_q));
  a_req_hold:    assert property (@(posedge clk_i) disable iff (!rst_ni)
                                  !stall_q || (req_valid_o && {req_x_o, req_y_o, req_tag_o} == word_q));

  c_retro_trace: cover property (@(posedge clk_i) disable iff (!rst_ni) done && rsent_q && out_trace_i);
  c_retro_write: cover property (@(posedge clk_i) disable iff (!rst_ni) done && rsent_q && out_write_o);
  c_port_wait:   cover property (@(posedge clk_i) disable iff (!rst_ni)
                                  held_q && !out_trace_i && out_write_o);
  c_stall:       cover property (@(posedge clk_i) disable iff (!rst_ni) stall_q && out_valid_i && out_trace_i);
endmodule
