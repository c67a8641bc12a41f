// Flip-flop macros (in the manner of common_cells' registers.svh): one line a register, so a
// unit's control flops read as what they hold, not as eight lines of port list each.
// Included as "msr_flops.svh" through the include folder rtl/prim.
`ifndef MSR_FLOPS_SVH
`define MSR_FLOPS_SVH

// A control register (msr_clr_reg, instance __name): __w bits, asynchronous reset rst_ni and the
// synchronous clear __clr of the enclosing unit both to zero, loading __d into __q on __en.
`define MSR_CLR_REG(__name, __w, __clr, __en, __d, __q) \
  msr_clr_reg #(.WIDTH(__w)) __name ( \
    .clk_i, .rst_ni, .clear_i(__clr), .en_i(__en), .d_i(__d), .q_o(__q));

// The same, to __reset (not zero) after the reset and the clear.
`define MSR_CLR_REG_RST(__name, __w, __reset, __clr, __en, __d, __q) \
  msr_clr_reg #(.WIDTH(__w), .RESET(__reset)) __name ( \
    .clk_i, .rst_ni, .clear_i(__clr), .en_i(__en), .d_i(__d), .q_o(__q));

`endif // MSR_FLOPS_SVH
