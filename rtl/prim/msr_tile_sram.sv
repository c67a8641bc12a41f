// Tile buffer: behavioural 2R1W SRAM, one word per pixel of a MAX_TILE x MAX_TILE tile.
// Read data is there RD_LAT clocks after the clock edge that takes the address (1: a
// synchronous read, as an FPGA block RAM or a fast compiled SRAM; 2 to 4: a macro that needs
// more than a clock, pipelined here as RD_LAT - 1 registers behind the array) and holds its
// value while the port is not enabled, as compiled SRAM macros do (the engine does not need
// the hold: it registers the data once more beside the memory and uses it exactly RD_LAT + 1
// clocks after the address).
// Why two read ports: a decision reads both neighbours, A and B, of the position at the head
// of its context's queue, one per port, so one position can be issued every clock. A
// hand-off maps this onto two 1R1W macros written in parallel (or one 2R1W register file).
// A port may read a word in the cycle it is written; the engine never uses such a read's
// data. No reset on the array.
module msr_tile_sram #(
  parameter int unsigned DEPTH  = 1024,
  parameter int unsigned DATA_W = 32,
  parameter int unsigned RD_LAT = 1,      // read latency in clocks (1..4)
  parameter int unsigned ADDR_W = $clog2(DEPTH)
) (
  input  logic              clk_i,
  input  logic              re0_i,     // read port 0 enable
  input  logic [ADDR_W-1:0] raddr0_i,
  output logic [DATA_W-1:0] rdata0_o,  // valid RD_LAT cycles after re0_i
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
  if (RD_LAT < 1 || RD_LAT > 4) begin : g_check_rd_lat
    $fatal(1, "msr_tile_sram: RD_LAT %0d must be in 1..4", RD_LAT);
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

  // The array's read registers, then (RD_LAT > 1) RD_LAT - 1 more per port, each loaded when
  // the read reaches it, so the output holds between reads as above.
  logic [DATA_W-1:0] rd0_q, rd1_q;

  always_ff @(posedge clk_i) begin
    if (re0_i) begin
      rd0_q <= mem_q[raddr0_i];
    end
  end

  always_ff @(posedge clk_i) begin
    if (re1_i) begin
      rd1_q <= mem_q[raddr1_i];
    end
  end

  if (RD_LAT > 1) begin : g_rd_pipe
    logic [RD_LAT-2:0]             re0_q, re1_q;      // [k]: the port read k + 1 clocks ago
    logic [RD_LAT-2:0][DATA_W-1:0] pipe0_q, pipe1_q;

    always_ff @(posedge clk_i) begin
      re0_q <= (RD_LAT - 1)'({re0_q, re0_i});
      re1_q <= (RD_LAT - 1)'({re1_q, re1_i});
      if (re0_q[0]) pipe0_q[0] <= rd0_q;
      if (re1_q[0]) pipe1_q[0] <= rd1_q;
      for (int unsigned k = 1; k < RD_LAT - 1; k++) begin
        if (re0_q[k]) pipe0_q[k] <= pipe0_q[k-1];
        if (re1_q[k]) pipe1_q[k] <= pipe1_q[k-1];
      end
    end

    assign rdata0_o = pipe0_q[RD_LAT-2];
    assign rdata1_o = pipe1_q[RD_LAT-2];
  end else begin : g_rd_now
    assign rdata0_o = rd0_q;
    assign rdata1_o = rd1_q;
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
