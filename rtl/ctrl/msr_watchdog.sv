// Watchdog of the configuration controller: counts the clocks in a row without progress while
// a frame runs or a soft reset drains, and fires when the count reaches the limit (WATCHDOG, or
// DRAIN_TIMEOUT in a drain when WATCHDOG is 0; docs/system.md "Watchdog").
//
// The compare is registered: the clock before the count reaches the limit, hit_q is loaded
// from "count == limit - 1, and the count is not cleared", so the fire is one flip-flop and the
// controller's next-state logic sees no 32-bit compare (the count-to-state path set the
// default top's clock on ECP5). The limit - 1 is a
// register too; a limit written while counting takes effect two clocks later, which moves a
// fire by at most two clocks and never fires below the smaller of the two limits minus two.
`include "msr_assert.svh"
`include "msr_flops.svh"

module msr_watchdog #(
  parameter int unsigned DRAIN_TIMEOUT = 16384   // bound of a drain when the limit is 0
) (
  input  logic        clk_i,        // clock
  input  logic        rst_ni,       // asynchronous reset, active low
  input  logic        run_i,        // a frame runs
  input  logic        drain_i,      // a soft reset drains
  input  logic        restart_i,    // count from 0 (a soft reset written): no fire this clock
  input  logic        progress_i,   // progress this clock (registered by the caller)
  input  logic [31:0] limit_i,      // WATCHDOG: clocks without progress, 0 = off
  output logic        fire_o        // the count reached the limit: end the frame or the drain
);
  logic        on, clr;
  logic [31:0] limit;
  logic [31:0] cnt_q;          // clocks in a row without progress
  logic        lo_ones_q;      // cnt_q[15:0] is all ones
  logic [31:0] lim_m1_q;       // limit - 1
  logic        lim_on_q;       // limit != 0
  logic        hit_q;          // cnt_q == limit (registered compare)

  assign on     = run_i || drain_i;
  assign limit  = (drain_i && limit_i == '0) ? DRAIN_TIMEOUT : limit_i;
  assign fire_o = on && !restart_i && hit_q;
  assign clr    = !on || progress_i || fire_o || restart_i;

  `MSR_CLR_REG(u_limit_q, 33, 1'b0, 1'b1, {limit != '0, limit - 1'b1}, {lim_on_q, lim_m1_q})

  // The 32-bit count is two 16-bit halves; the upper half steps on a registered "lower half is
  // all ones" flag (set the clock before the lower half reaches it), so no path holds a 32-bit
  // carry: the count is exact, the logic depth that of a 16-bit counter.
  logic [31:0] cnt_d;
  logic        lo_ones_d, hit_d;
  always_comb begin
    cnt_d     = '0;
    lo_ones_d = 1'b0;
    hit_d     = 1'b0;
    if (!clr) begin
      cnt_d[15:0]  = cnt_q[15:0] + 1'b1;
      cnt_d[31:16] = lo_ones_q ? cnt_q[31:16] + 1'b1 : cnt_q[31:16];
      lo_ones_d    = (cnt_q[15:0] == 16'hFFFE);
      hit_d        = lim_on_q && (cnt_q == lim_m1_q);
    end
  end
  `MSR_CLR_REG(u_cnt_q, 34, 1'b0, 1'b1, {cnt_d, lo_ones_d, hit_d}, {cnt_q, lo_ones_q, hit_q})

  /* verilator lint_off SYNCASYNCNET */
  `MSR_ASSERT(a_lo_ones, lo_ones_q == (cnt_q[15:0] == 16'hFFFF))
  // With the limit held, the registered compare is the compare: it fires exactly at the limit.
  `MSR_ASSERT_IMP(a_hit_exact, on && $stable(limit) && $past($stable(limit)) && $past(on),
                           hit_q == (lim_on_q && cnt_q == limit && cnt_q != '0))
  /* verilator lint_on SYNCASYNCNET */
endmodule : msr_watchdog
