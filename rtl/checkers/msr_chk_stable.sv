// One valid/ready channel's handshake rule, shared by the protocol checkers of rtl/checkers:
// VALID, once offered and not taken (READY low), stays high the next cycle with the same
// payload. viol_o flags a break in the current cycle; the checker that instantiates this owns
// the rule's assertion (its label, its message, its mask bit). Passive, every port an input
// but viol_o; a plain register and a comparison, so it runs in Verilator and in make formal.
// Verification IP, not design: no coverage points (make coverage reports the design's lines).
/* verilator coverage_off */
module msr_chk_stable #(
  parameter int unsigned W = 1   // payload bits
) (
  input  logic         clk_i,
  input  logic         rst_ni,
  input  logic         valid_i,
  input  logic         ready_i,
  input  logic [W-1:0] payload_i,
  output logic         viol_o
);
  // What was offered and not taken last cycle.
  logic         wait_q;
  logic [W-1:0] payload_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) {wait_q, payload_q} <= '0;
    else         {wait_q, payload_q} <= {valid_i && !ready_i, payload_i};
  end
  assign viol_o = wait_q && !(valid_i && payload_i == payload_q);
endmodule : msr_chk_stable
/* verilator coverage_on */
