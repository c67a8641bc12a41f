// COPIES flip-flops of one control bit, each kept by synthesis: a register duplicated for
// placement (a copy beside each group of far loads). Written as one register, the copies have
// the same inputs and the optimiser merges them back into one flip-flop (Yosys opt_merge did
// exactly that to the controller's per-engine clear and drain registers, so their one output
// ran across the die); `keep` on each copy's process stops the merge.
module msr_dup_reg #(
  parameter int unsigned COPIES = 2,      // flip-flops
  parameter logic        RESET  = 1'b0    // value after reset
) (
  input  logic              clk_i,        // clock
  input  logic              rst_ni,       // asynchronous reset, active low
  input  logic              d_i,          // next value, the same for every copy
  output logic [COPIES-1:0] q_o           // the copies
);

  for (genvar i = 0; i < COPIES; i++) begin : g_copy
    logic q_q;
    (* keep *)
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        q_q <= RESET;
      end else begin
        q_q <= d_i;
      end
    end
    assign q_o[i] = q_q;
  end

endmodule : msr_dup_reg
