// The decision pipeline's output buffer, with the credits that keep the pipeline from ever
// stalling: a position is issued only with a slot of the buffer reserved for it (issue_i
// takes a credit, a result leaving the buffer returns one), so the buffer always has room
// for what the pipeline delivers and the pipeline registers need no enable.
//
// Credits in flight per position: grant -> GR -> IS -> RD -> AB -> S0..S5 -> buffer -> out,
// ~12 clocks; DEPTH 16 (the next power of two) keeps one grant per clock. The output logic
// works on a register (a spill register after the buffer), not on the buffer's read
// multiplexer.
`include "msr_assert.svh"
`include "msr_flops.svh"

module msr_out_buf #(
  parameter int unsigned WIDTH = 8,
  parameter int unsigned DEPTH = 16
) (
  input  logic             clk_i,
  input  logic             rst_ni,
  input  logic             clear_i,      // synchronous soft reset: empties it, every credit back
  input  logic             issue_i,      // a position issued: takes a credit
  output logic             can_issue_o,  // a credit is left
  input  logic             valid_i,      // a result from the pipeline (never refused)
  input  logic [WIDTH-1:0] data_i,
  output logic             valid_o,      // the oldest result, from a register
  input  logic             ready_i,
  output logic [WIDTH-1:0] data_o
);

  localparam int unsigned CRED_W = $clog2(DEPTH) + 1;

  logic              buf_ready, buf_valid, spill_ready;
  logic [WIDTH-1:0]  buf_data;
  logic [CRED_W-1:0] credit_q, buf_count;

  msr_fifo #(
    .WIDTH (WIDTH),
    .DEPTH (DEPTH)
  ) u_fifo (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .flush_i (clear_i),
    .valid_i (valid_i),
    .ready_o (buf_ready),
    .data_i  (data_i),
    .valid_o (buf_valid),
    .ready_i (spill_ready),
    .data_o  (buf_data),
    .count_o (buf_count)
  );

  msr_spill_reg #(
    .WIDTH (WIDTH)
  ) u_spill (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .clear_i (clear_i),
    .valid_i (buf_valid),
    .ready_o (spill_ready),
    .data_i  (buf_data),
    .valid_o (valid_o),
    .ready_i (ready_i),
    .data_o  (data_o)
  );

  // Credits: buffer slots not yet reserved by an issued position.
  `MSR_CLR_REG_RST(u_credit_q, CRED_W, CRED_W'(DEPTH), clear_i, 1'b1,
                   credit_q - CRED_W'(issue_i) + CRED_W'(buf_valid && spill_ready), credit_q)

  assign can_issue_o = (credit_q != '0);

  /* verilator lint_off SYNCASYNCNET */
  `MSR_ASSERT_IMP(a_room, valid_i, buf_ready)
  `MSR_ASSERT(a_credits, 32'(credit_q) + 32'(buf_count) <= DEPTH)
  `MSR_ASSERT_IMP(a_no_issue_without_credit, issue_i, can_issue_o)
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_out_buf
