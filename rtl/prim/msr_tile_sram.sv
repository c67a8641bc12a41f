// Tile buffer: behavioural 2R1W SRAM, one word per pixel of a MAX_TILE x MAX_TILE tile.
// Read data is registered (one cycle) and holds its value while the port is not enabled, as
// compiled SRAM macros do (the engine does not need the hold: it registers the data once more
// beside the memory and uses it exactly two clocks after the address).
// Why two read ports: a decision reads both neighbours, A and B, of the position at the head
// of its context's queue, one per port, so one position can be issued every clock. A
// hand-off maps this onto two 1R1W macros written in parallel (or one 2R1W register file).
// A port may read a word in the cycle it is written; the engine never uses such a read's
// data. No reset on the array.
module msr_tile_sram #(
  parameter int unsigned DEPTH  = 1024,
  parameter int unsigned DATA_W = 32,
  parameter int unsigned ADDR_W = $clog2(DEPTH)
) (
  input  logic              clk_i,
  input  logic              re0_i,     // read port 0 enable
  input  logic [ADDR_W-1:0] raddr0_i,
  output logic [DATA_W-1:0] rdata0_o,  // valid the cycle after re0_i
  input  logic              re1_i,     // read port 1 enable
  input  logic [ADDR_W-1:0] raddr1_i,
  output logic [DATA_W-1:0] rdata1_o,
  input  logic              we_i,      // write port
  input  logic [ADDR_W-1:0] waddr_i,
  input  logic [DATA_W-1:0] wdata_i
);

  if (DEPTH < 2 || DEPTH > (1 << ADDR_W)) begin : g_check_depth
    $fatal(1, "msr_tile_sram: DEPTH %0d does not fit ADDR_W %0d", DEPTH, ADDR_W);
  end

  // no_rw_check: a read of the word written in the same cycle is don't-care (see above), so a
  // synthesis tool maps the ports straight onto the block RAM. Without it Yosys emulates a
  // defined collision result: ~100 flip-flops and a multiplexer behind the RAM's output per
  // buffer, in the path the block RAM's slow clock-to-output already dominates.
  (* no_rw_check *)
  logic [DATA_W-1:0] mem_q [DEPTH];

  always_ff @(posedge clk_i) begin
    if (we_i) begin
      mem_q[waddr_i] <= wdata_i;
    end
  end

  always_ff @(posedge clk_i) begin
    if (re0_i) begin
      rdata0_o <= mem_q[raddr0_i];
    end
  end

  always_ff @(posedge clk_i) begin
    if (re1_i) begin
      rdata1_o <= mem_q[raddr1_i];
    end
  end

`ifndef SYNTHESIS
  a_waddr : assert property (@(posedge clk_i) we_i |-> 32'(waddr_i) < DEPTH)
    else $error("msr_tile_sram: write address %0d out of range", waddr_i);
  a_raddr0 : assert property (@(posedge clk_i) re0_i |-> 32'(raddr0_i) < DEPTH)
    else $error("msr_tile_sram: read address %0d out of range", raddr0_i);
  a_raddr1 : assert property (@(posedge clk_i) re1_i |-> 32'(raddr1_i) < DEPTH)
    else $error("msr_tile_sram: read address %0d out of range", raddr1_i);
`endif

endmodule : msr_tile_sram
