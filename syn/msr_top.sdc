# SDC template for msr_top: the assumptions a synthesis run starts from. Edit the numbers
# for your library and system; every line says what it assumes.

# One clock for the whole design (the AXI4-Lite register port, the AXI4 frame-buffer master
# and the render port are all synchronous to it). 100 MHz is the planning target.
set CLK_PERIOD_NS 10.0
create_clock -name clk_i -period $CLK_PERIOD_NS [get_ports clk_i]
set_clock_uncertainty 0.2 [get_clocks clk_i]
set_clock_transition 0.1 [get_clocks clk_i]

# rst_ni is asynchronous assert, synchronous de-assert by a reset synchroniser outside the
# block: no timing through it inside the design.
set_false_path -from [get_ports rst_ni]

# I/O: every port is registered on the other side within the same clock domain; give the
# outside 40 % of the cycle on each side.
set IO_DELAY_NS [expr {0.4 * $CLK_PERIOD_NS}]
set non_clock_inputs [remove_from_collection [all_inputs] [get_ports {clk_i rst_ni}]]
set_input_delay  $IO_DELAY_NS -clock clk_i $non_clock_inputs
set_output_delay $IO_DELAY_NS -clock clk_i [all_outputs]
set_load 0.01 [all_outputs]
set_driving_cell -lib_cell BUF_X2 $non_clock_inputs    ;# replace with your library's buffer
