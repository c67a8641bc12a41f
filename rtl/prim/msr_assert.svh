// Assertion macros of the accelerator, in the manner of OpenTitan's prim_assert.sv: the label,
// the clock, the reset and the message are written once here, not at every use.
//
//   `MSR_ASSERT(name, prop)            concurrent assertion, clocked by clk_i, off in reset
//   `MSR_ASSERT(name, prop, clk, rst)  the same with another clock / disable condition
//   `MSR_ASSUME(...)                   the same as an assumption (formal environments)
//   `MSR_COVER(name, prop)             cover property (coverage and formal non-vacuity)
//   `MSR_CHK_OFF                       the disable condition of the protocol checkers' own
//                                      assertions (rtl/checkers), which stay on under FORMAL
//
// Nothing is checked at time 0: with a random initial state (+verilator+rand+reset+2) the
// simulator may see a first clock edge while rst_ni, random too, is still high, before any
// bench can drive the reset; that edge would check random state.
// Every macro expands to nothing when SYNTHESIS is defined, so synthesis drops them. A failing
// assertion prints its label and its property text. Files that use them wrap the block in
// `/* verilator lint_off SYNCASYNCNET */` (disable iff reads the asynchronous reset).
// Formal (make formal, formal/): the jobs read the RTL with yosys's slang front end and define
// FORMAL. That front end takes concurrent assertions only in their boolean form (no |->, |=>
// or sequences), so under FORMAL the inline macros expand to nothing and each formal harness
// (formal/<unit>/*_fv.sv) states the properties of its unit again, in that form, next to the
// stronger ones it proves.
`ifndef MSR_ASSERT_SVH
`define MSR_ASSERT_SVH

`ifdef FORMAL

// The protocol checkers write `disable iff (`MSR_CHK_OFF)` by hand (their rules are plain
// boolean properties, which the formal front end takes): the same rule as the macros below,
// nothing checked in reset nor at time 0, but under FORMAL the plain reset condition.
`define MSR_CHK_OFF (!rst_ni)

`define MSR_ASSERT(__name, __prop, __clk = clk_i, __rst = !rst_ni)
`define MSR_ASSUME(__name, __prop, __clk = clk_i, __rst = !rst_ni)
`define MSR_COVER(__name, __prop, __clk = clk_i, __rst = !rst_ni)

`else

`define MSR_CHK_OFF (!rst_ni || $time == 0)

`define MSR_ASSERT(__name, __prop, __clk = clk_i, __rst = !rst_ni) \
`ifndef SYNTHESIS \
  __name : assert property (@(posedge __clk) disable iff ((__rst) || $time == 0) (__prop)) \
    else $error("%m: assertion %s failed: %s", `"__name`", `"__prop`"); \
`endif

`define MSR_ASSUME(__name, __prop, __clk = clk_i, __rst = !rst_ni) \
`ifndef SYNTHESIS \
  __name : assume property (@(posedge __clk) disable iff ((__rst) || $time == 0) (__prop)) \
    else $error("%m: assumption %s failed: %s", `"__name`", `"__prop`"); \
`endif

`define MSR_COVER(__name, __prop, __clk = clk_i, __rst = !rst_ni) \
`ifndef SYNTHESIS \
  __name : cover property (@(posedge __clk) disable iff ((__rst) || $time == 0) (__prop)); \
`endif

`endif // FORMAL

`endif // MSR_ASSERT_SVH
