// Ray budget: the controller's constants and the closed forms of the grid (docs/budget.md
// "Terms"), shared by the grid-constant unit (msr_budget_grid) and the controller
// (msr_budget_ctrl). Golden model: sw_model/msr_model/budget.py.
package msr_budget_pkg;
  import msr_pkg::*;

  // Not every unit uses every constant (each is linted on its own with the package).
  /* verilator lint_off UNUSEDPARAM */
  // Scale u in 1/256: the clamp [U_MIN, U_MAX] = [45, 1448] (0.18 .. 5.66).
  localparam logic [10:0] U_MIN = 11'd45;
  localparam logic [10:0] U_MAX = 11'd1448;
  localparam logic [10:0] Q_SAT = 11'd1449;      // U_MAX + 1: "no budget left" / saturated
  /* verilator lint_on UNUSEDPARAM */

  // n0(n) = ceil(n / S) + ((n - 1) mod S != 0), for n in 0..32 (0 for n = 0), S = 2^l.
  function automatic logic [5:0] grid_axis(logic [5:0] n, level_t l);
    logic [5:0] s1;
    s1 = 6'((7'd1 << l) - 7'd1);
    if (n == '0) return '0;
    return ((n + s1) >> l) + 6'(((n - 6'd1) & s1) != '0);
  endfunction

  function automatic logic [10:0] clamp_u(logic [10:0] v);
    return (v > U_MAX) ? U_MAX : (v < U_MIN) ? U_MIN : v;
  endfunction

endpackage : msr_budget_pkg
