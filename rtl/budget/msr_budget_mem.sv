// Ray budget: the activity memory (docs/budget.md section 6), one word per tile row, one
// synchronous read and one write port at a shared address, no reset (two ECP5 EBRs at 512 x 39).
// The read word is registered twice: rdata_q is the block RAM's own read register, word_o a
// second register, so no consumer sees the RAM's clock-to-output (into the controller's 45-bit
// sum and the seed pass's compare it was the unit's worst path in the top).
module msr_budget_mem #(
  parameter int unsigned  W     = 39,                 // word bits
  parameter int unsigned  DEPTH = 512,                // tile rows
  localparam int unsigned A_W   = $clog2(DEPTH)
) (
  input  logic           clk_i,      // clock
  input  logic           re_i,       // read the word at addr_i ...
  input  logic           we_i,       // write wdata_i at addr_i
  input  logic [A_W-1:0] addr_i,
  input  logic [W-1:0]   wdata_i,
  output logic [W-1:0]   word_o      // ... two clocks after re_i (held until the next read)
);
  (* no_rw_check *)
  logic [W-1:0] mem_q [DEPTH];
  logic [W-1:0] rdata_q;

  always_ff @(posedge clk_i) begin
    if (we_i) mem_q[addr_i] <= wdata_i;
  end
  always_ff @(posedge clk_i) begin
    if (re_i) rdata_q <= mem_q[addr_i];
  end
  always_ff @(posedge clk_i) begin
    word_o <= rdata_q;
  end

endmodule : msr_budget_mem
