# Constraints of the standard-cell timing runs (make asic, scripts/asic.py; OpenSTA at the
# library's typical corner). The caller sets CLK_PERIOD_NS before sourcing this file; every
# other number is an assumption written here with its reason.

# One clock for everything (the AXI4-Lite register port, the AXI4 frame-buffer master and the
# render port are synchronous to it). 5.0 ns is the 200 MHz target; scripts/asic.py reports
# the slack against it and Fmax = 1 / (period - WNS).
# A purely combinational unit (no clk_i port) is timed against a virtual clock of the same
# period: its input-to-output paths get what the two registers around it leave.
set clk_port [get_ports -quiet clk_i]
if {[llength $clk_port]} {
  create_clock -name clk_i -period $CLK_PERIOD_NS $clk_port
  # Pre-layout: no clock tree yet; the clock edge gets the transition of a clock buffer.
  set_clock_transition 0.15 [get_clocks clk_i]
} else {
  create_clock -name clk_i -period $CLK_PERIOD_NS
}
# 0.25 ns covers the skew and jitter of a clock tree at 180 nm.
set_clock_uncertainty 0.25 [get_clocks clk_i]

# rst_ni: asynchronous assert, de-asserted by a reset synchroniser outside the block; the
# flip-flops' recovery/removal checks are signed off after the reset tree is built.
set rst_port [get_ports -quiet rst_ni]
if {[llength $rst_port]} {
  set_false_path -from $rst_port
}

# I/O: every port of a unit is a register (or a short path to one) on the other side, in the
# same clock domain. The outside gets 20 % of the cycle on each side, and a port is driven by
# a 2x buffer and loads the net with four inputs' worth of capacitance (4 x ~10 fF).
set IO_DELAY_NS [expr {0.2 * $CLK_PERIOD_NS}]
set data_inputs [delete_from_list [all_inputs] $clk_port]
set_input_delay  $IO_DELAY_NS -clock clk_i $data_inputs
set_output_delay $IO_DELAY_NS -clock clk_i [all_outputs]
set_driving_cell -lib_cell BUFX2 -pin Y $data_inputs
set_load 0.04 [all_outputs]
