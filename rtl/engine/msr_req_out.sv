// The tile engine's output: each result from the output buffer's register becomes a write of
// its context's tile buffer (interpolated) or a render request (traced); a lindilate result
// with a retro trace first sends the retro request (msr_lin_dilate forms it), then goes on as
// any other result. A request takes a tag from the tag pool as it enters a spill register,
// so the render port is driven by flip-flops and its ready reaches no further than here.
//
// Handshakes: the result (out_valid_i / out_ready_o) leaves when its write is done (at once
// where the write port is the pipeline's first; when wr_ok_i where a macro's cycle makes it
// wait, msr_ctx_write) or its request is taken; the request port is valid / ready, valid never
// waits for ready.
module msr_req_out
  import msr_pkg::*;
#(
  parameter int unsigned TAG_W = 4                 // render tag bits
) (
  input  logic             clk_i,                  // clock
  input  logic             rst_ni,                 // asynchronous reset, active low
  input  logic             clear_i,                // synchronous soft reset: drops the request held
  // the result
  input  logic             out_valid_i,            // a result is offered
  output logic             out_ready_o,            // it leaves this cycle
  input  logic             out_trace_i,            // traced (else interpolated: written)
  input  logic             retro_phase_i,          // its retro request goes first
  input  logic             wr_ok_i,                // its context's port may be written now
  output logic             out_write_o,            // write its pixel now
  input  coord_t           req_x_i,                // the request's frame coordinates
  input  coord_t           req_y_i,
  // tags
  input  logic             tag_avail_i,            // a tag is free ...
  input  logic [TAG_W-1:0] free_tag_i,             // ... this one
  output logic             alloc_tag_o,            // take it (the request enters the spill reg.)
  // render request, global frame coordinates
  output logic             req_valid_o,
  input  logic             req_ready_i,
  output coord_t           req_x_o,
  output coord_t           req_y_o,
  output logic [TAG_W-1:0] req_tag_o
);

  typedef struct packed {
    coord_t           x;
    coord_t           y;
    logic [TAG_W-1:0] tag;
  } req_t;

  logic req_in_ready, req_in_valid;
  req_t req_in, req_out;

  assign req_in       = '{x: req_x_i, y: req_y_i, tag: free_tag_i};
  assign out_write_o  = out_valid_i && !out_trace_i && !retro_phase_i && wr_ok_i;
  assign out_ready_o  = !retro_phase_i && (out_trace_i ? (tag_avail_i && req_in_ready) : wr_ok_i);
  assign req_in_valid = out_valid_i && (out_trace_i || retro_phase_i) && tag_avail_i;
  assign alloc_tag_o  = req_in_valid && req_in_ready;

  msr_spill_reg #(.WIDTH($bits(req_t))) u_req_spill (
    .clk_i, .rst_ni, .clear_i,
    .valid_i (req_in_valid), .ready_o (req_in_ready), .data_i (req_in),
    .valid_o (req_valid_o),  .ready_i (req_ready_i),  .data_o (req_out)
  );

  // By field name, not position: a reordered req_t cannot swap them silently.
  assign req_x_o   = req_out.x;
  assign req_y_o   = req_out.y;
  assign req_tag_o = req_out.tag;

endmodule : msr_req_out
