// The contexts' write ports: the output's write (an interpolated pixel) or a checked render
// response (a traced one) to its context's tile buffer, registered per context.
//
// The write reaches its context a clock after the output or the response check decided it:
// the contexts sit across the engine's area, and the decision -> context path (its pending
// count's adder behind) was the placed top's worst path. Nothing waits on a write
// but the context itself (its pending count and pass barrier see the write when it lands), so
// the register only delays a barrier by one clock. A clear drops a write on its way. A retro
// request is one more pending write of its context (registered like the write). The response
// check never writes the context that the output writes in the same cycle.
//
// CYCLE > 1 (a macro that takes an address on its write port once per CYCLE clocks): after a
// write to a context its port rests CYCLE - 1 clocks; free_o tells the two writers which ports
// may be written now (a register per context). The response check goes first, the output's
// write waits (msr_req_out), so an answer never waits behind a context that keeps interpolating.
`include "msr_assert.svh"
`include "msr_flops.svh"

module msr_ctx_write import msr_pkg::*; #(
  parameter int unsigned NUM_CTX = 8, parameter int unsigned CTX_W = $clog2(NUM_CTX),
  // a pixel's data: the colour, or with the engine's depth channel {inverse depth, colour}
  parameter int unsigned DATA_W = $bits(rgb_t),
  parameter int unsigned CYCLE  = 1     // clocks between two writes of one context (1..8)
) (
  input  logic                              clk_i, rst_ni, clear_i,  // clear: soft reset
  // the output: an interpolated pixel, or a retro request of its context
  input  logic                              out_write_i,
  input  logic                              out_retro_i,
  input  logic     [CTX_W-1:0]              out_ctx_i,
  input  lcoord_t                           out_x_i,
  input  lcoord_t                           out_y_i,
  input  level_t                            out_level_i,
  input  logic     [DATA_W-1:0]             out_rgb_i,
  // the response check: a traced pixel
  input  logic                              rsp_write_i,
  input  logic     [CTX_W-1:0]              rsp_ctx_i,
  input  logic     [TADDR_W-1:0]            rsp_addr_i,
  input  level_t                            rsp_level_i,
  input  logic     [DATA_W-1:0]             rsp_rgb_i,
  // each context's port, registered
  output logic     [NUM_CTX-1:0]              we_o,
  output logic     [NUM_CTX-1:0]              retro_o,
  output logic     [NUM_CTX-1:0][TADDR_W-1:0] waddr_o,
  output src_t     [NUM_CTX-1:0]              wsrc_o,
  output logic     [NUM_CTX-1:0][DATA_W-1:0] wrgb_o,
  output logic     [NUM_CTX-1:0]              free_o    // the context's port may be written now
);

  logic [NUM_CTX-1:0]              we_d, retro_d;
  logic [NUM_CTX-1:0][TADDR_W-1:0] waddr_q;
  src_t [NUM_CTX-1:0]              wsrc_q;
  logic [NUM_CTX-1:0][DATA_W-1:0] wrgb_q;

  for (genvar c = 0; c < NUM_CTX; c++) begin : g_write
    logic pipe_we, rsp_we;
    assign pipe_we    = out_write_i && (out_ctx_i == CTX_W'(c));
    assign rsp_we     = rsp_write_i && (rsp_ctx_i == CTX_W'(c));
    assign we_d[c]    = pipe_we || rsp_we;
    assign retro_d[c] = out_retro_i && (out_ctx_i == CTX_W'(c));

    // Data without an enable: it is used only with we_o.
    always_ff @(posedge clk_i) begin
      waddr_q[c] <= pipe_we ? {out_y_i, out_x_i} : rsp_addr_i;
      wsrc_q[c]  <= pipe_we ? src_interp(out_level_i) : src_traced(rsp_level_i);
      wrgb_q[c]  <= pipe_we ? out_rgb_i : rsp_rgb_i;
    end
  end

  assign waddr_o = waddr_q;
  assign wsrc_o  = wsrc_q;
  assign wrgb_o  = wrgb_q;

  `MSR_CLR_REG(u_write_q, 2 * NUM_CTX, clear_i, 1'b1, {we_d, retro_d}, {we_o, retro_o})

  msr_rest_timer #(.N(NUM_CTX), .CYCLE(CYCLE)) u_rest (
    .clk_i, .rst_ni, .clear_i, .use_i (we_d), .free_o
  );
  if (CYCLE < 1 || CYCLE > 8) begin : g_check_cycle
    $fatal(1, "msr_ctx_write: CYCLE %0d must be in 1..8", CYCLE);
  end

  /* verilator lint_off SYNCASYNCNET */
  `MSR_ASSERT(a_one_writer, !(out_write_i && rsp_write_i && out_ctx_i == rsp_ctx_i))
  `MSR_ASSERT(a_port_rested, (we_d & ~free_o) == '0)
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_ctx_write
