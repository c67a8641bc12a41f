// Control of a global-stall pipeline of STAGES register stages, one item a clock: every stage
// moves when the last (the output register) is empty or taken, ready_o = !valid_o || ready_i.
// vld_o[k]: stage k holds an item; en_o[k]: stage k loads (the pipeline moves and the stage
// before it, or valid_i for stage 0, holds one). The datapath flops load on en_o and need no
// reset; clear_i empties every stage.
`include "msr_flops.svh"

module msr_stall_ctrl #(
  parameter int unsigned STAGES = 2             // register stages, at least 2
) (
  input  logic              clk_i,              // clock
  input  logic              rst_ni,             // asynchronous reset, active low
  input  logic              clear_i,            // synchronous flush
  input  logic              valid_i,            // an item at the input
  output logic              ready_o,            // the pipeline moves
  output logic              valid_o,            // an item in the output register
  input  logic              ready_i,            // the output register is taken
  output logic [STAGES-1:0] vld_o,              // stage k holds an item
  output logic [STAGES-1:0] en_o                // stage k loads
);

  logic [STAGES-1:0] vld_q;
  logic              advance;

  assign advance = !vld_q[STAGES-1] || ready_i;
  assign ready_o = advance;
  assign valid_o = vld_q[STAGES-1];
  assign vld_o   = vld_q;
  assign en_o    = {STAGES{advance}} & {vld_q[STAGES-2:0], valid_i};

  `MSR_CLR_REG(u_valid, STAGES, clear_i, advance, {vld_q[STAGES-2:0], valid_i}, vld_q)

endmodule : msr_stall_ctrl
