// The tile generator as the top uses it: alone (BUDGET_EN 0), or with the ray budget's stage
// between it and the engines (BUDGET_EN 1), the controller's answer (row_ok_i, row_m_i) driven
// by the bench.
module msr_tile_gen_tb import msr_pkg::*; #(
  parameter int unsigned NUM_ENGINES = 4,
  parameter bit          BUDGET_EN   = 1'b0
) (
  input  logic                   clk_i,
  input  logic                   rst_ni,
  input  logic                   clear_i,
  input  logic                   start_i,
  input  dim_t                   width_i,
  input  dim_t                   height_i,
  input  tile_size_e             tile_i,
  input  level_t                 levels_i,
  input  metric_e                metric_i,
  input  rule_e                  rule_i,
  input  thr_t [MAX_LEVELS-1:0]  thr_i,
  input  logic [7:0]             fov_gain_i,
  input  logic                   gaze_en_i,
  input  logic [COORD_W-2:0]     gaze_cx_i,
  input  logic [COORD_W-2:0]     gaze_cy_i,
  input  logic                   bud_en_i,
  output logic [COORD_W-3:0]     row_idx_o,
  input  logic                   row_ok_i,
  input  logic [12:0]            row_m_i,
  output logic [NUM_ENGINES-1:0] desc_valid_o,
  input  logic [NUM_ENGINES-1:0] desc_ready_i,
  output tile_desc_t             desc_o,
  output logic                   busy_o,
  output logic                   done_o
);
  logic [COORD_W-2:0] ntx, nty;
  logic [COORD_W-3:0] tx, ty, row_next;
  logic               row_step, row_last, row_go, adv;
  tile_desc_t         pipe_desc, tail_desc;

  msr_tile_gen #(
    .NUM_ENGINES (NUM_ENGINES),
    .EXT_ORDER   (BUDGET_EN),
    .TAIL_STAGES (BUDGET_EN ? msr_budget_pkg::BUD_TAIL : 0)
  ) u_tile_gen (
    .clk_i, .rst_ni, .clear_i, .start_i, .width_i, .height_i, .tile_i, .levels_i, .metric_i,
    .rule_i, .thr_i, .fov_gain_i, .gaze_en_i, .gaze_cx_i, .gaze_cy_i,
    .ntx_o (ntx), .nty_o (nty), .tx_o (tx), .ty_o (ty), .row_step_o (row_step),
    .row_next_i (row_next), .row_last_i (row_last), .row_go_i (row_go), .adv_o (adv),
    .pipe_desc_o (pipe_desc), .tail_desc_i (tail_desc),
    .desc_valid_o, .desc_ready_i, .desc_o, .busy_o, .done_o
  );

  if (BUDGET_EN) begin : g_budget
    logic [COORD_W-3:0] smask;
    logic [COORD_W-2:0] nty_s;
    msr_budget_stage u_stage (
      .clk_i, .rst_ni, .clear_i, .start_i, .height_i, .tile_i, .bud_en_i,
      .row_idx_o, .row_ok_i, .row_m_i, .smask_o (smask), .nty_s_o (nty_s),
      .nty_i (nty), .tx_i (tx[7:0]), .ty_i (ty), .row_step_i (row_step),
      .row_next_o (row_next), .row_last_o (row_last), .row_go_o (row_go),
      .adv_i (adv), .desc_i (pipe_desc), .desc_o (tail_desc)
    );
  end else begin : g_no_budget
    assign row_next  = '0;
    assign row_last  = 1'b0;
    assign row_go    = 1'b1;
    assign tail_desc = '0;
    assign row_idx_o = ty;
  end

endmodule : msr_tile_gen_tb
