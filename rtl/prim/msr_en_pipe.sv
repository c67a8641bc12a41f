// Datapath flip-flops without a reset, DEPTH registers in a row, register k loading on en_i[k]:
// the words a stalling pipeline carries past stages that do not change them (its valid bits,
// in an msr_clr_reg, say which words mean something). DEPTH 1 is a plain register with a load.
module msr_en_pipe #(
  parameter int unsigned WIDTH = 1,     // bits
  parameter int unsigned DEPTH = 1      // registers in a row
) (
  input  logic             clk_i,       // clock
  input  logic [DEPTH-1:0] en_i,        // register k loads the one before it (0: d_i)
  input  logic [WIDTH-1:0] d_i,         // into the first register
  output logic [WIDTH-1:0] q_o          // the last register
);

  logic [DEPTH-1:0][WIDTH-1:0] q_q;
  logic [DEPTH-1:0][WIDTH-1:0] d;       // register k's input

  // {q_q, d_i} less its top word: d_i, then each register's output
  assign d = (DEPTH * WIDTH)'({q_q, d_i});

  always_ff @(posedge clk_i) begin
    for (int k = 0; k < DEPTH; k++) begin
      if (en_i[k]) begin
        q_q[k] <= d[k];
      end
    end
  end

  assign q_o = q_q[DEPTH-1];

endmodule : msr_en_pipe
