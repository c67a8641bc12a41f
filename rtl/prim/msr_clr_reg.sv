// Control register with an asynchronous reset and a synchronous clear to the same value (the
// valid bits, flags and counts of the units: clear_i is every unit's soft reset), loading d_i
// on en_i. Data registers that their valid bits gate need neither and stay plain flip-flops.
module msr_clr_reg #(
  parameter int unsigned      WIDTH = 1,    // bits
  parameter logic [WIDTH-1:0] RESET = '0    // value after reset and after a clear
) (
  input  logic             clk_i,           // clock
  input  logic             rst_ni,          // asynchronous reset, active low
  input  logic             clear_i,         // synchronous: back to RESET (before en_i)
  input  logic             en_i,            // load d_i
  input  logic [WIDTH-1:0] d_i,             // next value
  output logic [WIDTH-1:0] q_o              // value
);

  logic [WIDTH-1:0] q_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      q_q <= RESET;
    end else if (clear_i) begin
      q_q <= RESET;
    end else if (en_i) begin
      q_q <= d_i;
    end
  end

  assign q_o = q_q;

endmodule : msr_clr_reg
