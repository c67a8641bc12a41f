// Spill register, in the manner of common_cells' spill_register: a two-entry elastic buffer
// that cuts every combinational path of a valid/ready channel (data, valid and ready are all
// registered), at full throughput. Entry A is the output register; entry B catches the word
// that arrives in the cycle the consumer stops.
`include "msr_assert.svh"
`include "msr_flops.svh"

module msr_spill_reg #(
  parameter int unsigned WIDTH = 8     // bits per word
) (
  input  logic             clk_i,      // clock
  input  logic             rst_ni,     // asynchronous reset, active low
  input  logic             clear_i,    // synchronous: drop both entries
  input  logic             valid_i,    // upstream word
  output logic             ready_o,
  input  logic [WIDTH-1:0] data_i,
  output logic             valid_o,    // downstream word
  input  logic             ready_i,
  output logic [WIDTH-1:0] data_o
);

  logic             a_full_q, b_full_q;
  logic [WIDTH-1:0] a_data_q, b_data_q;
  logic             a_fill, a_drain, b_fill, b_drain;

  // A drains to the consumer; it is refilled from B first, else from the input.
  assign a_drain = a_full_q && ready_i;
  assign b_drain = b_full_q && (!a_full_q || a_drain);
  assign a_fill  = (valid_i && ready_o && !b_full_q && (!a_full_q || a_drain)) || b_drain;
  // The input goes to B when A stays full (or A takes B's word this cycle).
  assign b_fill  = valid_i && ready_o && ((a_full_q && !a_drain) || b_full_q);
  assign ready_o = !b_full_q;
  assign valid_o = a_full_q;
  assign data_o  = a_data_q;

  logic a_full_d, b_full_d;
  assign a_full_d = a_fill || (a_full_q && !a_drain);
  assign b_full_d = b_fill || (b_full_q && !b_drain);
  `MSR_CLR_REG(u_full_q, 2, clear_i, 1'b1, {a_full_d, b_full_d}, {a_full_q, b_full_q})

  // Data registers carry no reset: the full flags gate them.
  always_ff @(posedge clk_i) begin
    if (a_fill) a_data_q <= b_drain ? b_data_q : data_i;
    if (b_fill) b_data_q <= data_i;
  end

  /* verilator lint_off SYNCASYNCNET */
  `MSR_ASSERT_NXT(a_out_hold, valid_o && !ready_i, valid_o && $stable(data_o), clk_i,
              !rst_ni || clear_i)
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_spill_reg
