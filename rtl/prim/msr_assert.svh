// Assertion macros of the accelerator, in the manner of OpenTitan's prim_assert.sv: the label,
// the clock, the reset and the message are written once here, not at every use. One family
// for simulation and formal alike: every property is a boolean condition, an implication in
// the same clock, or an implication into the next clock, and each form has a macro.
//
//   `MSR_ASSERT(name, cond)              cond holds every clock (clocked by clk_i, off in reset)
//   `MSR_ASSERT_IMP(name, ante, cons)    ante |-> cons: cons holds in every clock ante does
//   `MSR_ASSERT_NXT(name, ante, cons)    ante |=> cons: cons holds the clock after ante
//   `MSR_ASSUME, `MSR_ASSUME_IMP, `MSR_ASSUME_NXT   the same as assumptions (environments)
//   `MSR_COVER(name, cond)               cover (simulation coverage; see below)
//   ... , clk, rst)                      any of them with another clock / disable condition
//   `MSR_CHK_OFF                         the disable condition of the protocol checkers' own
//                                        assertions (rtl/checkers)
//
// Simulation: concurrent assertions, nothing checked in reset nor at time 0 (with a random
// initial state, +verilator+rand+reset+2, the simulator may see a first clock edge while
// rst_ni, random too, is still high, before any bench can drive the reset). A failing
// assertion prints its label and its property text. Files that use them wrap the block in
// `/* verilator lint_off SYNCASYNCNET */` (disable iff reads the asynchronous reset).
// Formal (FORMAL defined; the jobs of formal/ read the RTL with yosys's slang front end, which
// takes concurrent assertions only in their boolean form): the same properties, a boolean
// form for the first two, and for the next-clock form an immediate assertion in a clocked
// process on $past of the antecedent. So a formal job of a unit proves the unit's own
// assertions too, and its harness states only what the unit's RTL does not. Covers stay
// simulation only: a formal cover job reaches the goals its harness names.
// Synthesis (SYNTHESIS defined), and a formal job that defines MSR_FORMAL_NO_INLINE: every
// macro expands to nothing.
`ifndef MSR_ASSERT_SVH
`define MSR_ASSERT_SVH

`ifdef SYNTHESIS
`define MSR_ASSERT_NONE
`elsif MSR_FORMAL_NO_INLINE
// A formal job that cuts datapath registers into free values (formal/budget_ctrl) cannot hold
// the units' own datapath assertions; it defines MSR_FORMAL_NO_INLINE and states its own.
`define MSR_ASSERT_NONE
`endif

`ifdef MSR_ASSERT_NONE

`define MSR_CHK_OFF (!rst_ni)
`define MSR_ASSERT(__name, __prop, __clk = clk_i, __rst = !rst_ni)
`define MSR_ASSERT_IMP(__name, __ante, __cons, __clk = clk_i, __rst = !rst_ni)
`define MSR_ASSERT_NXT(__name, __ante, __cons, __clk = clk_i, __rst = !rst_ni)
`define MSR_ASSUME(__name, __prop, __clk = clk_i, __rst = !rst_ni)
`define MSR_ASSUME_IMP(__name, __ante, __cons, __clk = clk_i, __rst = !rst_ni)
`define MSR_ASSUME_NXT(__name, __ante, __cons, __clk = clk_i, __rst = !rst_ni)
`define MSR_COVER(__name, __prop, __clk = clk_i, __rst = !rst_ni)

`elsif FORMAL

// The protocol checkers write `disable iff (`MSR_CHK_OFF)` by hand: under FORMAL the plain
// reset condition (the jobs start in reset).
`define MSR_CHK_OFF (!rst_ni)

`define MSR_ASSERT(__name, __prop, __clk = clk_i, __rst = !rst_ni) \
  __name : assert property (@(posedge __clk) disable iff (__rst) (__prop));
`define MSR_ASSERT_IMP(__name, __ante, __cons, __clk = clk_i, __rst = !rst_ni) \
  __name : assert property (@(posedge __clk) disable iff (__rst) (!(__ante) || (__cons)));
`define MSR_ASSERT_NXT(__name, __ante, __cons, __clk = clk_i, __rst = !rst_ni) \
  always_ff @(posedge __clk) \
    if (!(__rst) && !$past(__rst) && $past(__ante)) __name : assert (__cons);
`define MSR_ASSUME(__name, __prop, __clk = clk_i, __rst = !rst_ni) \
  __name : assume property (@(posedge __clk) disable iff (__rst) (__prop));
`define MSR_ASSUME_IMP(__name, __ante, __cons, __clk = clk_i, __rst = !rst_ni) \
  __name : assume property (@(posedge __clk) disable iff (__rst) (!(__ante) || (__cons)));
`define MSR_ASSUME_NXT(__name, __ante, __cons, __clk = clk_i, __rst = !rst_ni) \
  always_ff @(posedge __clk) \
    if (!(__rst) && !$past(__rst) && $past(__ante)) __name : assume (__cons);
`define MSR_COVER(__name, __prop, __clk = clk_i, __rst = !rst_ni)

`else

`define MSR_CHK_OFF (!rst_ni || $time == 0)

`define MSR_ASSERT(__name, __prop, __clk = clk_i, __rst = !rst_ni) \
  __name : assert property (@(posedge __clk) disable iff ((__rst) || $time == 0) (__prop)) \
    else $error("%m: assertion %s failed: %s", `"__name`", `"__prop`");
`define MSR_ASSERT_IMP(__name, __ante, __cons, __clk = clk_i, __rst = !rst_ni) \
  __name : assert property (@(posedge __clk) disable iff ((__rst) || $time == 0) \
      (__ante) |-> (__cons)) \
    else $error("%m: assertion %s failed: %s |-> %s", `"__name`", `"__ante`", `"__cons`");
`define MSR_ASSERT_NXT(__name, __ante, __cons, __clk = clk_i, __rst = !rst_ni) \
  __name : assert property (@(posedge __clk) disable iff ((__rst) || $time == 0) \
      (__ante) |=> (__cons)) \
    else $error("%m: assertion %s failed: %s |=> %s", `"__name`", `"__ante`", `"__cons`");
`define MSR_ASSUME(__name, __prop, __clk = clk_i, __rst = !rst_ni) \
  __name : assume property (@(posedge __clk) disable iff ((__rst) || $time == 0) (__prop)) \
    else $error("%m: assumption %s failed: %s", `"__name`", `"__prop`");
`define MSR_ASSUME_IMP(__name, __ante, __cons, __clk = clk_i, __rst = !rst_ni) \
  __name : assume property (@(posedge __clk) disable iff ((__rst) || $time == 0) \
      (__ante) |-> (__cons)) \
    else $error("%m: assumption %s failed: %s |-> %s", `"__name`", `"__ante`", `"__cons`");
`define MSR_ASSUME_NXT(__name, __ante, __cons, __clk = clk_i, __rst = !rst_ni) \
  __name : assume property (@(posedge __clk) disable iff ((__rst) || $time == 0) \
      (__ante) |=> (__cons)) \
    else $error("%m: assumption %s failed: %s |=> %s", `"__name`", `"__ante`", `"__cons`");
`define MSR_COVER(__name, __prop, __clk = clk_i, __rst = !rst_ni) \
  __name : cover property (@(posedge __clk) disable iff ((__rst) || $time == 0) (__prop));

`endif

`endif // MSR_ASSERT_SVH
