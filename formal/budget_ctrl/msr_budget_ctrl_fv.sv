// Formal harness of msr_budget_ctrl (docs/budget.md section 6): any legal configuration (held,
// as msr_cfg_ctrl holds it), check and start pulses, clears and row results at any moment the
// controller takes them, any traced count in the row's range [g_j, p_j]. Proves by k-induction
// from any reachable state:
// - scale bounds: every scale slot holds 0 (never written since reset) or a u in
//   [U_MIN_FIRST, U_MAX]; the rows' slot (base) is in range while a frame runs, and in
//   [U_MIN, U_MAX] while a seeded frame runs; SCALE_OUT too; u0 in [U_MIN, U_MAX];
// - the read-back window: row_ok_o only for a row the controller has a scale for
//   (rows_done <= row <= rows_done + 1 < nty), and rows_done < nty while a frame runs;
// - no deadlock: no state but idle lasts more than MAX_STAY clocks (a product waits at most its
//   multiplier width, 25, the division 12 steps; every other state moves on at once), so each
//   sequence (check, start, a row's update) ends; with the multiplier's and the divider's step
//   counts bounded (the harness's helper invariants).
// The products' and quotients' values are proven in formal/shift_add_mul and formal/seq_div.
`include "msr_assert.svh"

module msr_budget_ctrl_fv import msr_pkg::*; import msr_budget_pkg::*; #(
  localparam int unsigned ROW_W    = BUD_ROW_W,
  localparam int unsigned MAX_STAY = 26
) (
  input logic             clk_i, rst_ni, clear_i,
  input dim_t             width_i, height_i,
  input logic [2:0]       tile_log2_i,
  input level_t           levels_i,
  input logic [23:0]      budget_i,
  input logic [10:0]      scale_init_i,
  input logic [2:0]       prior_shift_i,
  input logic             seeded_i,
  input logic             check_i, start_i, row_done_i,
  input logic [17:0]      row_traced_i,
  input logic             row_bottom_i,     // any: the row's height (either) bounds its count
  input logic [ROW_W-1:0] row_idx_i
);
  logic             init, check_done, err_budget, err_profile, row_ready, row_ok;
  logic             scale_out_valid, frame_done;
  logic [12:0]      row_m;
  logic [10:0]      scale_out;

  msr_fv_init #(.ONCE(1'b1)) u_init (.clk_i, .rst_ni, .init_o(init));

  msr_budget_ctrl dut (
    .clk_i, .rst_ni, .clear_i, .width_i, .height_i, .tile_log2_i, .levels_i, .budget_i,
    .scale_init_i, .prior_shift_i, .seeded_i, .check_i, .check_done_o(check_done),
    .err_budget_o(err_budget), .err_profile_o(err_profile), .start_i, .row_done_i,
    .row_traced_i, .row_bottom_i, .row_ready_o(row_ready), .row_idx_i, .row_ok_o(row_ok), .row_m_o(row_m),
    .scale_out_o(scale_out), .scale_out_valid_o(scale_out_valid), .frame_done_o(frame_done)
  );

  // ---- The environment (msr_cfg_ctrl, msr_budget_rows, the tile generator) -----------------
  // A legal configuration, held (the configuration registers hold it through a frame).
  logic [54:0] cfg_q;
  wire  [54:0] cfg = {width_i, height_i, tile_log2_i, levels_i, budget_i, scale_init_i,
                      prior_shift_i, seeded_i};
  always_ff @(posedge clk_i) cfg_q <= cfg;
  always_comb begin
    if (!init) assume (cfg == cfg_q);
    assume (width_i >= dim_t'(1) && width_i <= dim_t'(4096));
    assume (height_i >= dim_t'(1) && height_i <= dim_t'(4096));
    assume (tile_log2_i >= 3'd3 && tile_log2_i <= 3'd5);
    assume (levels_i >= level_t'(1));
    // A frame starts with a budget (0 is off: no start reaches the unit), never with a check.
    if (start_i) assume (budget_i != '0 && !check_i);
    // A row result only when taken, with a count in the row's range (every grid pixel traced).
    if (row_done_i) assume (row_ready && row_traced_i >= dut.g_sel && row_traced_i <= dut.p_sel);
  end

  // ---- Properties ----------------------------------------------------------------------------
  function automatic logic ok_u(logic [10:0] u);    // a scale in [U_MIN_FIRST, U_MAX]
    return u >= U_MIN_FIRST && u <= U_MAX;
  endfunction
  function automatic logic ok_u0(logic [10:0] u);   // u0 and a seeded frame's: [U_MIN, U_MAX]
    return u >= U_MIN && u <= U_MAX;
  endfunction

  a_slots:     assert property (@(posedge clk_i) disable iff (!rst_ni)
                                (dut.u_q[0] == '0 || ok_u(dut.u_q[0])) &&
                                (dut.u_q[1] == '0 || ok_u(dut.u_q[1])) &&
                                (dut.u_q[2] == '0 || ok_u(dut.u_q[2])));
  a_base:      assert property (@(posedge clk_i) disable iff (!rst_ni)
                                !dut.act_q || ok_u(dut.u_q[dut.base_q]));
  a_base_sd:   assert property (@(posedge clk_i) disable iff (!rst_ni)
                                !(dut.act_q && dut.frm_q.seeded) || ok_u0(dut.u_q[dut.base_q]));
  a_base_slot: assert property (@(posedge clk_i) disable iff (!rst_ni) dut.base_q != 2'd3);
  a_scale_out: assert property (@(posedge clk_i) disable iff (!rst_ni)
                                !scale_out_valid || ok_u(scale_out));
  a_rows:      assert property (@(posedge clk_i) disable iff (!rst_ni)
                                !dut.act_q || dut.rows_done_q < dut.frm_q.nty);

  // The read-back answers the row asked the clock before, from the window of that clock (the
  // registered answer stays right when the row count moves on under it: the old row's slot is
  // rewritten only by a later update's ST_SQ0).
  logic [ROW_W-1:0] asked_q, rows_q, nty_q;
  logic             act_q;
  always_ff @(posedge clk_i) begin
    asked_q <= row_idx_i;
    rows_q  <= dut.rows_done_q;
    nty_q   <= dut.frm_q.nty;
    act_q   <= dut.act_q && !(start_i || clear_i);
  end
  a_window:    assert property (@(posedge clk_i) disable iff (!rst_ni)
                                !row_ok || (act_q && asked_q >= rows_q &&
                                            asked_q <= rows_q + ROW_W'(1) && asked_q < nty_q));

  // No deadlock: clocks in the same non-idle state, since it was entered or restarted (a check
  // or start pulse restarts the sequence, a clear ends it: both the environment's).
  logic [5:0] stay_q;
  logic [4:0] state_q;
  logic       restart_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      stay_q    <= '0;
      state_q   <= '0;
      restart_q <= 1'b0;
    end else begin
      state_q   <= dut.state_q;
      restart_q <= dut.start_p || dut.check_p || clear_i;
      stay_q    <= (dut.state_q != state_q || dut.state_q == ST_IDLE || restart_q) ? '0
                 : (stay_q == 6'd63) ? stay_q : stay_q + 6'd1;
    end
  end
  wire same = dut.state_q == state_q && dut.state_q != ST_IDLE && !restart_q;
  a_stay:      assert property (@(posedge clk_i) disable iff (!rst_ni) !same || stay_q <= 6'(MAX_STAY));

  // Helpers (induction): the step counts are bounded, and a state that waits for a product
  // entered with it loaded (or done), so the wait plus the steps left never exceeds 25; the
  // divider counts its 12 steps from the law on.
  wire mul_wait = dut.state_q inside {ST_G, ST_WH, ST_GL, ST_PL, ST_N0,
                                      ST_M0, ST_ACT, ST_NUM, ST_DEN, ST_SQ, ST_PB};
  a_mul_cnt:   assert property (@(posedge clk_i) disable iff (!rst_ni) dut.u_mul.cnt_q <= 5'd25);
  a_mul_done:  assert property (@(posedge clk_i) disable iff (!rst_ni)
                                dut.u_mul.done_q == (dut.u_mul.cnt_q == '0));
  a_mul_wait:  assert property (@(posedge clk_i) disable iff (!rst_ni)
                                !(mul_wait && same) || 6'(dut.u_mul.cnt_q) + stay_q <= 6'd25);
  a_div_wait:  assert property (@(posedge clk_i) disable iff (!rst_ni)
                                !(dut.state_q inside {ST_NUM, ST_DEN}) ||
                                dut.u_div.cnt_q == 4'd12);
  a_div_run:   assert property (@(posedge clk_i) disable iff (!rst_ni)
                                dut.state_q != ST_DIV ||
                                (dut.u_div.cnt_q >= 4'd1 && (!same || 6'(dut.u_div.cnt_q) + stay_q <= 6'd12)));

  // Helpers (induction) for the scale bounds and the row count: the grid unit's pipeline carries
  // a clamped seed and at least one tile row; a start sequence runs from row 0, slot 0, with
  // rows 0 and 1 at the seed; while a frame runs the last-row and new-scale flags follow the
  // row count, the next row's scale is known, and a new scale is written (ST_SQ0) before ST_SQ.
  wire       start_seq = dut.state_q inside {ST_WH, ST_GL, ST_PL, ST_N0, ST_M0} ||
                         (dut.state_q == ST_G && !dut.checking_q);
  // (the grid unit's registers have no reset: stage n holds a value n clocks after reset)
  logic [2:0] age_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni)             age_q <= '0;
    else if (age_q != 3'd7)  age_q <= age_q + 3'd1;
  end
  a_grid_u0:   assert property (@(posedge clk_i) disable iff (!rst_ni)
                                age_q < 3'd2 || ok_u0(dut.u_grid.u0_q));
  a_grid_nty:  assert property (@(posedge clk_i) disable iff (!rst_ni)
                                age_q < 3'd2 || dut.u_grid.nty_q != '0);
  // (and a pulse leaves the grid unit only six clocks after reset: its delay line resets, and
  // its stage i holds a pulse of i + 1 clocks ago)
  for (genvar i = 0; i < 6; i++) begin : g_age
    a_pulse_age: assert property (@(posedge clk_i) disable iff (!rst_ni)
                                  age_q > 3'(i) || !(dut.u_grid.start_q[i] || dut.u_grid.check_q[i]));
  end
  a_start_seq: assert property (@(posedge clk_i) disable iff (!rst_ni)
                                !start_seq || (!dut.act_q && dut.rows_done_q == '0 &&
                                dut.base_q == 2'd0 && ok_u0(dut.u_q[0]) && ok_u0(dut.u_q[1]) &&
                                dut.frm_q.nty != '0));
  // (the seed pass's flag, registered from the next state, is the state's decode)
  a_in_pass:   assert property (@(posedge clk_i) disable iff (!rst_ni)
                                dut.u_pass.in_pass_q == (dut.state_q inside {ST_PRD, ST_PWT, ST_PW, ST_PMUL, ST_PB}));
  // (the row count's companions: the next row and the rows left, kept beside it)
  a_rows_next: assert property (@(posedge clk_i) disable iff (!rst_ni)
                                dut.rows_next_q == dut.rows_done_q + ROW_W'(1));
  a_rows_left: assert property (@(posedge clk_i) disable iff (!rst_ni)
                                !dut.act_q || dut.rows_left_q == dut.frm_q.nty - dut.rows_done_q);
  a_last:      assert property (@(posedge clk_i) disable iff (!rst_ni)
                                !dut.act_q || (dut.row_last_q == (dut.rows_done_q + ROW_W'(1) == dut.frm_q.nty) &&
                                dut.row_new_q == ((ROW_W+1)'(dut.rows_done_q) + (ROW_W+1)'(2) <
                                                  (ROW_W+1)'(dut.frm_q.nty))));
  // A row's update runs in a frame (or finishes in the six clocks a new start takes through the
  // grid unit: the start drops act_q at once, its sequence restarts the state machine), and only
  // the last row's ends in ST_FIN (no new scale).
  a_row_seq:   assert property (@(posedge clk_i) disable iff (!rst_ni)
                                !(dut.state_q inside {ST_FLR, ST_ACT, ST_ACC, ST_LAW, ST_NUM, ST_DEN,
                                                      ST_DIV, ST_SLEW, ST_SQ0, ST_SQ, ST_FIN}) ||
                                dut.act_q || dut.u_grid.start_q != '0);
  a_not_last:  assert property (@(posedge clk_i) disable iff (!rst_ni)
                                !(dut.state_q inside {ST_NUM, ST_DEN, ST_SQ0, ST_SQ}) ||
                                !dut.row_last_q);
  a_fin_last:  assert property (@(posedge clk_i) disable iff (!rst_ni)
                                dut.state_q != ST_FIN || dut.row_last_q);
  a_next:      assert property (@(posedge clk_i) disable iff (!rst_ni)
                                !dut.act_q || dut.row_last_q || ok_u(dut.u_q[dut.slot1]));
  a_next_sd:   assert property (@(posedge clk_i) disable iff (!rst_ni)
                                !(dut.act_q && dut.frm_q.seeded) || dut.row_last_q ||
                                ok_u0(dut.u_q[dut.slot1]));
  a_new:       assert property (@(posedge clk_i) disable iff (!rst_ni)
                                !(dut.act_q && dut.state_q == ST_SQ && dut.row_new_q) ||
                                ok_u(dut.u_q[dut.slot2]));
  a_new_sd:    assert property (@(posedge clk_i) disable iff (!rst_ni)
                                !(dut.act_q && dut.frm_q.seeded && dut.state_q == ST_SQ &&
                                  dut.row_new_q) || ok_u0(dut.u_q[dut.slot2]));

  // Non-vacuity (cover, from reset): a check answered, a frame's first row update.
  c_check: cover property (@(posedge clk_i) disable iff (!rst_ni) check_done && !err_budget);
  c_row:   cover property (@(posedge clk_i) disable iff (!rst_ni) dut.state_q == ST_SQ);
endmodule
