// Rest timers: N resources that may each be used at most once per CYCLE clocks (a memory
// macro's port whose minimum cycle spans several clocks). A use loads the resource's counter
// with CYCLE - 1; free_o says, from a register, that a use this clock is CYCLE clocks or more
// after the last one. CYCLE 1: every resource is free every clock and nothing is built.
`include "msr_flops.svh"

module msr_rest_timer #(
  parameter int unsigned N     = 1,   // resources
  parameter int unsigned CYCLE = 1    // clocks from one use of a resource to the next (1..255)
) (
  input  logic         clk_i,
  input  logic         rst_ni,
  input  logic         clear_i,       // synchronous: every resource free
  input  logic [N-1:0] use_i,         // resource i is used this clock (only while free_o[i])
  output logic [N-1:0] free_o         // resource i may be used this clock
);

  if (CYCLE < 1 || CYCLE > 255) begin : g_check_cycle
    $fatal(1, "msr_rest_timer: CYCLE %0d must be in 1..255", CYCLE);
  end

  if (CYCLE > 1) begin : g_rest
    localparam int unsigned CW = $clog2(CYCLE);
    logic [N-1:0][CW-1:0] rest_q, rest_d;
    logic [N-1:0]         free_d;
    always_comb begin
      for (int unsigned i = 0; i < N; i++) begin
        rest_d[i] = use_i[i] ? CW'(CYCLE - 1) : (rest_q[i] != '0) ? rest_q[i] - CW'(1) : '0;
        free_d[i] = (rest_d[i] == '0);
      end
    end
    // reset and clear: no rest, every resource free
    `MSR_CLR_REG_RST(u_rest_q, N * (CW + 1), (N * (CW + 1))'({N{1'b1}}), clear_i, 1'b1,
                     {rest_d, free_d}, {rest_q, free_o})
  end else begin : g_every_clock
    assign free_o = '1;
    /* verilator lint_off UNUSEDSIGNAL */
    logic unused;
    /* verilator lint_on UNUSEDSIGNAL */
    assign unused = ^{clk_i, rst_ni, clear_i, use_i};
  end

endmodule : msr_rest_timer
