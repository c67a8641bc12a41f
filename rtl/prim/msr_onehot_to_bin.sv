// One-hot to binary, in the manner of common_cells' onehot_to_bin: the index of the set bit of
// a one-hot vector, each index bit the OR of the input bits whose index has it set (one small
// OR per output bit, no priority chain). 0 when no bit is set; with more than one bit set, the
// OR of their indices.
module msr_onehot_to_bin #(
  parameter int unsigned N     = 4,                      // input bits, >= 1
  parameter int unsigned IDX_W = (N > 1) ? $clog2(N) : 1
) (
  input  logic [N-1:0]     onehot_i,   // at most one bit set
  output logic [IDX_W-1:0] bin_o       // index of the set bit
);

  if (N < 1) begin : g_check_n
    $fatal(1, "msr_onehot_to_bin: N must be >= 1, got %0d", N);
  end

  always_comb begin
    bin_o = '0;
    for (int unsigned i = 0; i < N; i++) begin
      if (onehot_i[i]) bin_o |= IDX_W'(i);
    end
  end

endmodule : msr_onehot_to_bin
