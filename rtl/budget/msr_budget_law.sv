// Ray budget controller, the datapath registers (docs/budget.md sections 4 and 6c; golden model
// sw_model/msr_model/budget.py, class Controller): the frame's constants, loaded from the grid
// unit and the start's products, and the law's running sums and operands, updated once per
// finished row. msr_budget_ctrl's state machine says when (state_i, run_i, the pulses); this
// unit says what, with the adds, compares and clamps that only these registers need.
//
// Plain flip-flops (the state machine and act_q say when they hold a value): a start's clear
// is the flip-flops' synchronous reset, not a multiplexer in front.
`include "msr_assert.svh"

module msr_budget_law import msr_pkg::*; import msr_budget_pkg::*; #(
  parameter int unsigned PROD_W = 61,                   // the multiplier's product
  parameter int unsigned MEM_W  = 39                    // an activity memory word
) (
  input  logic              clk_i,           // clock
  input  budget_state_e     state_i,         // the controller's state
  input  logic              run_i,           // no pulse or clear overrides the state machine
  input  logic              seq_load_i,      // a check's or a start's sequence begins
  input  logic              start_i,         // ... and it is a start's
  input  budget_grid_t      cfg_i,           // the configuration and the grid constants
  input  logic              mul_done_i,      // the product below is done
  input  logic [PROD_W-1:0] mul_prod_i,
  input  logic              row_take_i,      // a row result is taken (in ST_IDLE) ...
  input  logic [17:0]       row_traced_i,    // ... with this many traced pixels (c_j)
  input  logic              row_last_i,      // the row being updated is the frame's last
  input  logic              row_bottom_i,    // the row taken is the frame's bottom tile row
  input  logic              pass_i,          // the seed pass (its product is b_k)
  input  logic [MEM_W-1:0]  mem_word_i,      // the activity word of the row being updated
  input  logic [10:0]       u_next_i,        // u_{j+1}
  input  logic [10:0]       div_quo_i,       // the divider's quotient q
  output budget_frame_t     frm_o,           // the frame's constants
  output budget_law_t       law_o,           // the running sums and operands
  output logic [17:0]       g_sel_o,         // g_j and p_j of the row being updated
  output logic [17:0]       p_sel_o,
  output logic [17:0]       floor_ex_o,      // max(c_j - g_j, p_j >> FLOOR_SHIFT)
  output logic [BUD_ACT_W-1:0] nn0_o,        // N + N0
  output logic              x_pos_o,         // X > 0
  output logic [10:0]       u_new_o          // clamp(min(max(q, fall(u_{j+1})), 2 u_{j+1}))
);
  localparam int unsigned WH_W   = BUD_WH_W;
  localparam int unsigned ACT_W  = BUD_ACT_W;
  localparam int unsigned SEED_W = BUD_SEED_W;

  budget_frame_t frm_q;
  budget_law_t   law_q;

  // ---- Row quantities ------------------------------------------------------------------------
  logic [17:0]      c_minus_g;
  logic [18:0]      c_diff;                // c - g and its borrow (one carry chain)
  logic [SEED_W:0]  b_diff;                // b_rest -+ the word and its borrow
  logic [WH_W:0]    spare_d;               // B' - G and its borrow (one carry chain)
  logic [17:0]      floor_px;              // p_j >> FLOOR_SHIFT
  assign x_pos_o    = !law_q.x_rem[26] && law_q.x_rem != '0;
  assign g_sel_o    = row_bottom_i ? frm_q.g_last : frm_q.g_full;
  assign p_sel_o    = row_bottom_i ? frm_q.p_last : frm_q.p_full;
  assign c_diff     = {1'b0, row_traced_i} - {1'b0, g_sel_o};
  assign c_minus_g  = c_diff[18] ? '0 : c_diff[17:0];
  assign floor_px   = law_q.p_row >> FLOOR_SHIFT;
  assign floor_ex_o = (law_q.ex > floor_px) ? law_q.ex : floor_px;
  assign nn0_o      = law_q.n + law_q.n0;
  assign spare_d    = {1'b0, frm_q.bud} - {1'b0, frm_q.grid};
  // (a first frame's row goes below U_MIN only from a row at U_MIN or below; docs/budget.md)
  assign u_new_o    = clamp_u(law_q.u_mx, (law_q.deep && !frm_q.seeded) ? U_MIN_FIRST : U_MIN);
  // max(Btot - Bd, 0) kept as one running register: the divider loads it without a subtract in
  // front. One adder for both: + b_k in the seed pass (ST_PB), - b_j at a row's update (ST_ACC).
  // Row j's update subtracts the very word the seed pass added for row j (the memory holds it
  // until that update), so Btot - Bd never goes below 0 and the max is not built: a saturation
  // on the subtract's borrow was the top's worst path (a 46-bit carry into the registers'
  // reset). a_b_rest_no_borrow checks it in every bench.
  logic             b_sub;
  logic [MEM_W-1:0] b_opd;
  assign b_sub  = !pass_i;
  assign b_opd  = pass_i ? MEM_W'(mul_prod_i) : mem_word_i;
  assign b_diff = {1'b0, law_q.b_rest} + ((SEED_W + 1)'(b_opd) ^ {(SEED_W + 1){b_sub}})
                  + (SEED_W + 1)'(b_sub);
  // P0 = W * H >> PRIOR_SHIFT (ST_WH) and N0 = (B' - G) * u0 >> PRIOR_SHIFT (ST_N0) through one
  // shifter: both products are below 2^36 (W * H <= 2^24, B' - G < 2^24, u0 < 2^11).
  logic [ACT_W-1:0] prod_shr;
  assign prod_shr = mul_prod_i[ACT_W-1:0] >> cfg_i.prior_shift;

  // ---- Registers -----------------------------------------------------------------------------
  logic st_done, b_upd, acc;
  assign st_done = run_i && mul_done_i;
  assign acc     = run_i && state_i == ST_ACC;
  assign b_upd   = (acc && frm_q.seeded) || (st_done && state_i == ST_PB);
  always_ff @(posedge clk_i) begin
    if (seq_load_i) begin
      frm_q.nty    <= cfg_i.nty;
      frm_q.h_last <= cfg_i.h_last;
      frm_q.g_full <= cfg_i.g_full;
      frm_q.p_full <= cfg_i.p_full;
      frm_q.u0     <= cfg_i.u0;
      frm_q.seeded <= cfg_i.seeded;
    end
    if (st_done && state_i == ST_G) frm_q.grid <= WH_W'(mul_prod_i);
    if (st_done && state_i == ST_WH) begin
      frm_q.bud <= (WH_W'(cfg_i.budget) < WH_W'(mul_prod_i)) ? WH_W'(cfg_i.budget)
                                                              : WH_W'(mul_prod_i);
    end
    if (st_done && state_i == ST_GL) begin
      frm_q.g_last <= 18'(mul_prod_i);
      frm_q.spare  <= spare_d[WH_W] ? '0 : spare_d[WH_W-1:0];
    end
    if (st_done && state_i == ST_PL) frm_q.p_last <= 18'(mul_prod_i);
    // P + P0 and W * H - P start at ST_WH (P = 0) and move by p_j at each row's update
    if (st_done && state_i == ST_WH) begin
      law_q.pp0    <= (WH_W + 1)'(prod_shr);
      law_q.p_left <= WH_W'(mul_prod_i);
    end else if (acc) begin
      law_q.pp0    <= law_q.pp0 + (WH_W + 1)'(law_q.p_row);
      law_q.p_left <= law_q.p_left - WH_W'(law_q.p_row);
    end
    if (st_done && state_i == ST_PL) law_q.x_rem <= $signed({2'b00, frm_q.spare});
    else if (acc) law_q.x_rem <= law_q.x_rem - $signed({9'd0, law_q.ex});   // - c_j + g_j
    if (st_done && state_i == ST_N0) law_q.n0 <= prod_shr;
    if (seq_load_i && start_i) law_q.n <= '0;
    else if (acc) law_q.n <= law_q.n + ACT_W'(mul_prod_i);
    if (seq_load_i && start_i) law_q.b_rest <= '0;
    else if (b_upd) law_q.b_rest <= b_diff[SEED_W-1:0];
    if (run_i && state_i == ST_IDLE && row_take_i) begin
      law_q.p_row <= p_sel_o;
      law_q.ex    <= c_minus_g;
    end
    // (the last row has no next scale to slew from: SCALE_OUT = clamp(q) through the same step,
    // in [U_MIN, U_MAX] like u0, since it seeds the next frame)
    // The scale rises at most to twice a row's and falls at most to half (first frame) or by a
    // quarter (seeded): min(max(q, fall(u)), 2 u) as two compares of q beside each other
    // (fall(u) < 2 u), not one after the other.
    if (run_i && state_i == ST_LAW) begin
      law_q.slew <= row_last_i   ? '0 :
                    frm_q.seeded ? u_next_i - (u_next_i >> 2) : u_next_i >> 1;
      law_q.rise <= (row_last_i || u_next_i[10]) ? '1 : {u_next_i[9:0], 1'b0};
      law_q.deep <= !row_last_i && u_next_i <= U_MIN;
    end
    if (run_i && state_i == ST_SLEW) begin
      law_q.u_mx <= (div_quo_i > law_q.rise) ? law_q.rise :
                    (div_quo_i > law_q.slew) ? div_quo_i : law_q.slew;
    end
  end

  // (the geometry goes to the multiplier's operands in the controller; no product here is wider
  // than a memory word)
  logic unused;
  assign unused = ^{cfg_i.width, cfg_i.height, cfg_i.levels, cfg_i.line_w, cfg_i.line_h,
                    mul_prod_i[PROD_W-1:MEM_W], b_diff[SEED_W]};   // (the borrow: asserted 0)

  // The seed pass's add stays below 2^SEED_W and a row's subtract never borrows (above). No
  // reset here: state_i comes from the controller's reset state, so b_upd is low after reset.
  `MSR_ASSERT_IMP(a_b_rest_no_borrow, b_upd, !b_diff[SEED_W], clk_i, 1'b0)

  assign frm_o = frm_q;
  assign law_o = law_q;

endmodule : msr_budget_law
