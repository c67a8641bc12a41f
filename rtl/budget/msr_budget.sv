// Ray budget (docs/budget.md): the row counters at the writer's inputs (msr_budget_rows) and
// the controller that turns each finished row into the scale of the row two below it
// (msr_budget_ctrl), with what ties them to the tile generator and the configuration check.
//
// Configuration: the sampled registers (msr_cfg_ctrl's raw_o), taken at START and held until
// the next START, which only an idle controller takes: so they hold from the check through the
// frame's last row, and a started frame's are the checked ones (the check passed). One source,
// no check/frame multiplexer in front of the controller.
//
// The tile generator asks for the scale of the row its walker is in (row_idx_i) and starts
// the row only on row_ok_o. The answer is taken a clock after the question (the controller's
// read-back is registered) and only while it answers the same row, and not in the first
// clocks of a frame, when the controller is still setting rows 0 and 1 to the seed: so a row
// never starts on another row's or another frame's scale.
`include "msr_flops.svh"

module msr_budget import msr_pkg::*; import msr_sys_pkg::*; #(
  parameter int unsigned NUM_IN = 4,                       // pixel streams (engines)
  localparam int unsigned TROW_W = COORD_W - 2
) (
  input  logic                     clk_i,            // clock
  input  logic                     rst_ni,           // asynchronous reset, active low
  input  logic                     clear_i,          // synchronous clear
  // The sampled registers (msr_cfg_ctrl), held from check_i through the frame.
  input  cfg_raw_t                 raw_i,
  // The configuration check.
  input  logic                     check_i,          // pulse: check raw_i
  output logic                     check_done_o,     // the check below is valid
  output logic                     err_budget_o,     // 0 < BUDGET < the initial grid
  output logic                     err_profile_o,    // SEEDED without a matching memory
  // The frame.
  input  logic                     start_i,          // pulse: an accepted frame starts (raw_i)
  output logic                     busy_o,           // a budget frame's rows are not all accounted
  // Tile generator.
  input  logic [TROW_W-1:0]        row_idx_i,        // the row the walker is in
  output logic                     row_ok_o,         // its scale is known
  output logic [12:0]              row_m_o,          // its threshold multiplier
  // ... and its tile grid and row order (held through the frame from the second clock on).
  input  logic [TROW_W:0]          ntx_i,            // tiles per row
  input  logic [TROW_W:0]          nty_i,            // tile rows
  input  logic [TROW_W-1:0]        smask_i,          // the order's stride S, less one
  input  logic [TROW_W:0]          nty_s_i,          // nty - S
  // Finished pixels at the writer's inputs.
  input  logic [NUM_IN-1:0]        pix_fire_i,
  input  coord_t [NUM_IN-1:0]      pix_y_i,
  input  src_t [NUM_IN-1:0]        pix_src_i,
  input  logic [NUM_IN-1:0]        pix_last_i,
  // Read-back (BUDGET_CTRL.SCALE_OUT, SCALE_OUT_VALID).
  output logic [10:0]              scale_out_o,
  output logic                     scale_out_valid_o
);
  logic bud_start, on_q;
  assign bud_start = start_i && raw_i.bud.pixels != '0;   // 0 = off

  // ---- Rows ----------------------------------------------------------------------------------
  logic                 row_valid, row_ready, rows_busy;
  logic [TROW_W-1:0]    row_idx;
  logic [17:0]          row_traced;
  logic                 row_bottom;
  logic [NUM_IN-1:0]    traced;
  logic [2:0]           lg;                // log2 T (the check passed: T is 8, 16 or 32)
  assign lg = (raw_i.tile == 6'd8) ? 3'd3 : (raw_i.tile == 6'd32) ? 3'd5 : 3'd4;
  for (genvar i = 0; i < NUM_IN; i++) begin : g_traced
    assign traced[i] = pix_src_i[i] < src_t'(16);
  end

  msr_budget_rows #(.NUM_IN(NUM_IN)) u_rows (
    .clk_i        (clk_i),
    .rst_ni       (rst_ni),
    .clear_i      (clear_i),
    .start_i      (bud_start),
    .tile_log2_i  (lg),
    .ntx_i        (ntx_i),
    .nty_i        (nty_i),
    .smask_i      (smask_i),
    .nty_s_i      (nty_s_i),
    .pix_fire_i   (pix_fire_i),
    .pix_y_i      (pix_y_i),
    .pix_traced_i (traced),
    .pix_last_i   (pix_last_i),
    .row_valid_o  (row_valid),
    .row_ready_i  (row_ready),
    .row_idx_o    (row_idx),
    .row_bottom_o (row_bottom),
    .row_traced_o (row_traced),
    .busy_o       (rows_busy)
  );

  // ---- Controller ------------------------------------------------------------------------------
  logic        ctl_row_ready, ctl_row_ok, ctl_frame_done;
  logic [12:0] ctl_row_m;

  msr_budget_ctrl u_ctrl (
    .clk_i             (clk_i),
    .rst_ni            (rst_ni),
    .clear_i           (clear_i),
    .width_i           (raw_i.width),
    .height_i          (raw_i.height),
    .tile_log2_i       (lg),
    .levels_i          (raw_i.levels),
    .budget_i          (raw_i.bud.pixels),
    .scale_init_i      (raw_i.bud.scale_init),
    .prior_shift_i     (raw_i.bud.prior_shift),
    .seeded_i          (raw_i.bud.seeded),
    .check_i           (check_i),
    .check_done_o      (check_done_o),
    .err_budget_o      (err_budget_o),
    .err_profile_o     (err_profile_o),
    .start_i           (bud_start),
    .row_done_i        (row_valid && ctl_row_ready),
    .row_traced_i      (row_traced),
    .row_bottom_i      (row_bottom),
    .row_ready_o       (ctl_row_ready),
    .row_idx_i         (row_idx_i),
    .row_ok_o          (ctl_row_ok),
    .row_m_o           (ctl_row_m),
    .scale_out_o       (scale_out_o),
    .scale_out_valid_o (scale_out_valid_o),
    .frame_done_o      (ctl_frame_done)
  );
  assign row_ready = ctl_row_ready;

  // ---- The tile generator's answer ---------------------------------------------------------------
  logic [TROW_W-1:0] asked_q;
  logic [2:0]        settle_q, settle_d;  // clocks since the frame started, saturating at 4
  logic              on_d;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      asked_q <= '0;
    end else if (!clear_i) begin
      asked_q <= row_idx_i;
    end
  end
  always_comb begin
    settle_d = settle_q;
    on_d     = on_q;
    if (bud_start)              settle_d = '0;
    else if (settle_q != 3'd4)  settle_d = settle_q + 1'b1;
    if (bud_start)              on_d = 1'b1;
    else if (ctl_frame_done)    on_d = 1'b0;
  end
  `MSR_CLR_REG(u_on_q, 4, clear_i, 1'b1, {settle_d, on_d}, {settle_q, on_q})
  assign row_ok_o = ctl_row_ok && asked_q == row_idx_i && settle_q == 3'd4 && on_q;
  assign row_m_o  = ctl_row_m;
  assign busy_o   = on_q || rows_busy;

  // only the frame's geometry and budget fields are read (the rest is the writer's and engines')
  logic unused;
  assign unused = ^{row_idx, raw_i.rule, raw_i.metric, raw_i.thr, raw_i.fov_gain, raw_i.gaze,
                    raw_i.fb};

endmodule : msr_budget
