// Bench wrapper of msr_level_ctrl: its step_o struct as one port per field, so the cocotb
// test reads the fields by name (a packed struct reaches cocotb as one flat vector).
module msr_level_ctrl_tb
  import msr_pkg::*;
(
  input  logic       clk_i,
  input  logic       rst_ni,
  input  logic       clear_i,
  input  logic       start_valid_i,
  output logic       start_ready_o,
  input  ldim_t      w_i,
  input  ldim_t      h_i,
  input  level_t     levels_i,
  output logic       step_valid_o,
  input  logic       step_ready_i,
  output lcoord_t    step_x_o,
  output lcoord_t    step_y_o,
  output lcoord_t    step_ax_o,
  output lcoord_t    step_ay_o,
  output lcoord_t    step_bx_o,
  output lcoord_t    step_by_o,
  output gap_t       step_gap_o,
  output gap_t       step_off_o,
  output level_t     step_level_o,
  output logic [1:0] step_nshift_o,
  output dir_e       step_dir_o,
  output logic       step_first_o,
  output logic       step_o2a_o,
  output lcoord_t    step_o2_o,
  output logic       busy_o
);

  step_t step;

  msr_level_ctrl u_dut (
    .clk_i         (clk_i),
    .rst_ni        (rst_ni),
    .clear_i       (clear_i),
    .start_valid_i (start_valid_i),
    .start_ready_o (start_ready_o),
    .w_i           (w_i),
    .h_i           (h_i),
    .levels_i      (levels_i),
    .step_valid_o  (step_valid_o),
    .step_ready_i  (step_ready_i),
    .step_o        (step),
    .busy_o        (busy_o)
  );

  // step_t's fields, in their declared order
  assign {step_x_o, step_y_o, step_ax_o, step_ay_o, step_bx_o, step_by_o, step_gap_o, step_off_o,
          step_level_o, step_nshift_o, step_dir_o, step_first_o, step_o2a_o, step_o2_o} = step;

endmodule : msr_level_ctrl_tb
