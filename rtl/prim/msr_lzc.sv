// Lowest-set-bit finder (trailing-zero count), in the manner of common_cells' lzc: the index
// of the lowest set bit of in_i and whether there is none. A balanced tree of 2:1 choices, so
// the depth is log2(WIDTH) levels of small multiplexers, not a WIDTH-long priority chain.
`include "msr_assert.svh"

module msr_lzc #(
  parameter int unsigned WIDTH = 32,                        // bits searched, >= 1
  parameter int unsigned CNT_W = (WIDTH > 1) ? $clog2(WIDTH) : 1
) (
  input  logic [WIDTH-1:0] in_i,     // bit vector
  output logic [CNT_W-1:0] cnt_o,    // index of the lowest set bit (0 when empty)
  output logic             empty_o   // no bit set
);

  if (WIDTH < 1) begin : g_check_width
    $fatal(1, "msr_lzc: WIDTH must be >= 1, got %0d", WIDTH);
  end

  localparam int unsigned LEVELS = (WIDTH > 1) ? $clog2(WIDTH) : 1;
  localparam int unsigned LEAVES = 1 << LEVELS;

  // Node n of the tree (heap order, 1 = root) covers a power-of-two slice of the padded input;
  // it holds whether the slice has a set bit and the slice-local index of the lowest one.
  logic [2*LEAVES-1:1]             node_any;
  logic [2*LEAVES-1:1][CNT_W-1:0]  node_idx;

  for (genvar i = 0; i < LEAVES; i++) begin : g_leaf
    if (i < WIDTH) begin : g_bit
      assign node_any[LEAVES+i] = in_i[i];
    end else begin : g_pad
      assign node_any[LEAVES+i] = 1'b0;
    end
    assign node_idx[LEAVES+i] = '0;
  end

  for (genvar n = LEAVES - 1; n >= 1; n--) begin : g_node
    // depth of node n below the root: its children cover 2^(LEVELS-1-depth) leaves each
    localparam int unsigned DEPTH_N = $clog2(n + 1) - 1;
    localparam int unsigned HALF    = LEAVES >> (DEPTH_N + 1);
    assign node_any[n] = node_any[2*n] | node_any[2*n+1];
    assign node_idx[n] = node_any[2*n] ? node_idx[2*n]
                                       : (node_idx[2*n+1] | CNT_W'(HALF));
  end

  assign cnt_o   = node_idx[1];
  assign empty_o = !node_any[1];

endmodule : msr_lzc
