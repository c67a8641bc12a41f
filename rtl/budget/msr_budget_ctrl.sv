// Ray budget controller, the arithmetic (docs/budget.md sections 1-4 and 6; golden model
// sw_model/msr_model/budget.py, class Controller, bit for bit). This module is the state
// machine, the scale slots and the shared multiplier and divider; the frame's constants and the
// law's running sums are msr_budget_law's registers, the multiplier's operands by state
// msr_budget_mul_ops's choice, the activity memory's address, data and the seed pass's row
// counter msr_budget_pass's.
//
// Why sequential: a tile row lasts thousands of clocks and the law runs once per row, so one
// bit-serial multiplier (msr_shift_add_mul, up to 36 x 25 bits, as many clocks as the multiplier
// operand's width) and one restoring divider
// (msr_seq_div, 11 quotient bits saturated at U_MAX + 1) do every product and quotient of the
// frame; the only fast path is the read-back of a row's m.
//
// Sequences (check, start, row; clock counts) and the widths of every quantity: docs/budget.md
// section 6c.
//
// Scales: three slots (u, m) for the rows j, j + 1, j + 2 around rows_done (slot of row
// rows_done = base_q, the next ones follow modulo 3). row_ok_o answers row_idx_i: its scale is
// known and held, i.e. rows_done <= row_idx_i <= rows_done + 1 < nty + 1 (row r >= 2 becomes
// ok when the update of row r - 2 ends; the walker never asks a row below rows_done: a row is
// counted only after every one of its tiles left). row_ok_o and row_m_o are registered: they
// answer the row_idx_i of the clock before; a start or clear drops row_ok_o at once.
//
// Activity memory (msr_budget_mem, behind msr_budget_pass): row j's update writes {u_j, a_j}; a
// seeded start's seed pass first rewrites every word as b_k = a_k * w(u_k, u0), and row j's
// update reads b_j before it writes. Valid, with its row count, once a budget frame finished
// every row; a start invalidates it (it is being rewritten); a clear keeps a finished frame's
// memory. This state machine steps the pass; msr_budget_pass holds its row counter, the
// memory's address and data selection and the weight.
//
`include "msr_assert.svh"
`include "msr_flops.svh"

module msr_budget_ctrl import msr_pkg::*; import msr_budget_pkg::*; #(
  localparam int unsigned ROW_W = BUD_ROW_W             // tile row index (as the walker's)
) (
  input  logic             clk_i,              // clock
  input  logic             rst_ni,             // asynchronous reset, active low
  input  logic             clear_i,            // synchronous clear: forget the frame
  // Frame configuration, stable from check_i to the end of the frame.
  input  dim_t             width_i,            // W, 1..4096
  input  dim_t             height_i,           // H, 1..4096
  input  logic [2:0]       tile_log2_i,        // log2 T: 3, 4 or 5
  input  level_t           levels_i,           // L, 1..3 (S = 2^L)
  input  logic [23:0]      budget_i,           // B, 0 = off
  input  logic [10:0]      scale_init_i,       // u0 (0 reads as 256; clamped to [45, 1448])
  input  logic [2:0]       prior_shift_i,      // PRIOR_SHIFT
  input  logic             seeded_i,           // the seeded law
  // The configuration check.
  input  logic             check_i,            // pulse
  output logic             check_done_o,       // the flags below are valid (held)
  output logic             err_budget_o,       // 0 < B < G
  output logic             err_profile_o,      // seeded without a matching memory
  // The frame.
  input  logic             start_i,            // pulse: an accepted budget frame starts
  input  logic             row_done_i,         // pulse: the next row in order is finished ...
  input  logic [17:0]      row_traced_i,       // ... with this many traced pixels (c_j)
  input  logic             row_bottom_i,       // ... and it is the frame's bottom tile row
  output logic             row_ready_o,        // a row result can be taken
  input  logic [ROW_W-1:0] row_idx_i,          // the row the tile generator asks about
  output logic             row_ok_o,           // its scale is known (registered)
  output logic [12:0]      row_m_o,            // its m = (u * u + 128) >> 8 (registered)
  output logic [10:0]      scale_out_o,        // SCALE_OUT
  output logic             scale_out_valid_o,  // SCALE_OUT is from a finished budget frame
  output logic             frame_done_o        // pulse: the last row's update is done
);

  localparam int unsigned WH_W   = BUD_WH_W;     // W * H and every pixel count of the frame
  localparam int unsigned ACT_W  = BUD_ACT_W;    // N, N0
  localparam int unsigned MEM_W  = 39;           // {u_j, a_j} (11 + 28 bits) or b_k < 2^38
  localparam int unsigned MC_W   = BUD_MC_W;     // multiplicand (36)
  localparam int unsigned MP_W   = BUD_MP_W;     // multiplier (25)
  localparam int unsigned PROD_W = MC_W + MP_W;  // 61
  localparam int unsigned REM_W  = PROD_W + 1;   // 62: holds den << 11

  // ---- The configuration and the grid constants, six clocks after the pulses --------------
  // The check's flags and the row read-back drop at the input pulse itself (below).
  logic             check_p, start_p;
  budget_grid_t     cfg;                  // the configuration and the constants
  msr_budget_grid u_grid (
    .clk_i,
    .rst_ni,
    .clear_i,
    .width_i,
    .height_i,
    .tile_log2_i,
    .levels_i,
    .budget_i,
    .scale_init_i,
    .prior_shift_i,
    .seeded_i,
    .check_i,
    .start_i,
    .check_o       (check_p),
    .start_o       (start_p),
    .grid_o        (cfg)
  );

  // ---- State ---------------------------------------------------------------------------------
  budget_state_e     state_q, state_d;
  logic              checking_q;           // the G sequence answers a check (not a start)
  logic              act_q;                // a budget frame is on and rows 0, 1 are known
  budget_frame_t     frm_q;                // the frame's constants (check and start)
  budget_law_t       law_q;                // the running sums and the law's operands
  logic [ROW_W-1:0]  rows_done_q;
  logic [ROW_W-1:0]  rows_next_q;           // rows_done + 1
  logic [ROW_W-1:0]  rows_left_q;           // nty - rows_done (from the first scales on)
  logic              row_last_q, row_new_q; // row rows_done is the last; it sets a new scale
  logic [10:0]       u_q [3];
  logic [12:0]       m_q [3];
  logic [1:0]        base_q;               // slot of row rows_done_q
  logic              mem_valid_q;
  logic [ROW_W-1:0]  mem_rows_q;
  logic              check_done_q, err_budget_q, err_profile_q, frame_done_q;
  logic [10:0]       scale_out_q;
  logic              scale_out_valid_q;
  logic              row_ok_q;
  logic [12:0]       row_m_q;

  // ---- Multiplier (msr_shift_add_mul): one multiplier bit per clock -------------------------
  // Its operands by the loading state: msr_budget_mul_ops, below.
  logic              mul_load;
  budget_mul_op_t    mop;
  logic [PROD_W-1:0] mul_prod;
  logic              mul_done;

  // A check or a start loads G = line(W) * line(H) at its pulse, whatever the state (below);
  // otherwise the state machine loads the product its state starts (mul_load). A new sequence
  // overrides the state machine (one driver per flop).
  logic              seq_load, mload;
  assign seq_load = !clear_i && (start_p || check_p);
  assign mload    = seq_load || (mul_load && !start_p && !check_p);

  msr_shift_add_mul #(.A_W(MC_W), .B_W(MP_W)) u_mul (
    .clk_i,
    .rst_ni,
    .clear_i,
    .load_i  (mload),
    .a_i     (mop.a),
    .b_i     (mop.b),
    .steps_i (mop.n),
    .done_o  (mul_done),
    .prod_o  (mul_prod)
  );

  // ---- Activity memory and the seed pass (msr_budget_pass): the word two clocks after its read
  logic [MEM_W-1:0] mem_word_q;
  logic             mem_re, mem_we;
  logic             pass, pass_last;       // the seed pass; its row is the last
  logic [27:0]      pass_a;                // a'_k of the pass's word
  logic [10:0]      pass_w_q;              // w(u'_k, u0), registered

  msr_budget_pass #(.MEM_W(MEM_W), .ROW_W(ROW_W)) u_pass (
    .clk_i,
    .rst_ni,
    .restart_i   (clear_i || start_p || check_p),
    .state_i     (state_q),
    .state_d_i   (state_d),
    .mul_done_i  (mul_done),
    .mul_prod_i  (mul_prod[MEM_W-1:0]),
    .mem_re_i    (mem_re),
    .mem_we_i    (mem_we),
    .rows_done_i (rows_done_q),
    .u_row_i     (u_q[base_q]),
    .u0_i        (frm_q.u0),
    .nty_i       (frm_q.nty),
    .pass_o      (pass),
    .pass_last_o (pass_last),
    .mem_word_o  (mem_word_q),
    .pass_a_o    (pass_a),
    .pass_w_o    (pass_w_q)
  );

  // ---- The frame's constants and the law's registers (msr_budget_law) ----------------------
  logic             x_pos;
  logic [1:0]       slot1, slot2;
  logic [17:0]      g_sel, p_sel, floor_ex;
  logic [ACT_W-1:0] nn0;
  logic [10:0]      u_new;
  logic [10:0]      div_quo;
  logic             run;                    // no pulse or clear overrides the state machine
  assign slot1 = inc3(base_q);
  assign slot2 = inc3(slot1);
  assign run   = !clear_i && !start_p && !check_p;

  msr_budget_law #(.PROD_W(PROD_W), .MEM_W(MEM_W)) u_law (
    .clk_i,
    .state_i      (state_q),
    .run_i        (run),
    .seq_load_i   (seq_load),
    .start_i      (start_p),
    .cfg_i        (cfg),
    .mul_done_i   (mul_done),
    .mul_prod_i   (mul_prod),
    .row_take_i   (act_q && row_done_i),
    .row_traced_i,
    .row_last_i   (row_last_q),
    .row_bottom_i (row_bottom_i),
    .pass_i       (pass),
    .mem_word_i   (mem_word_q),
    .u_next_i     (u_q[slot1]),
    .div_quo_i    (div_quo),
    .frm_o        (frm_q),
    .law_o        (law_q),
    .g_sel_o      (g_sel),
    .p_sel_o      (p_sel),
    .floor_ex_o   (floor_ex),
    .nn0_o        (nn0),
    .x_pos_o      (x_pos),
    .u_new_o      (u_new)
  );

  // (the fields the law unit keeps to itself)
  logic unused_law;
  assign unused_law = ^{frm_q.g_full, frm_q.g_last, frm_q.grid,
                        frm_q.bud, law_q.n0, law_q.p_row, law_q.ex, law_q.slew, law_q.rise,
                        law_q.u_mx, law_q.deep};

  // ---- Divider (msr_seq_div): the saturation test, then quotient bits 10..0 ---------------
  // Loaded by the law (ST_LAW) or by the two products (ST_NUM, ST_DEN); steps in ST_DIV.
  logic             div_init, div_load_num, div_load_den, div_last;
  logic [REM_W-1:0] div_num_in, div_den_in;
  // The divider's operands, one flat choice each: in ST_LAW N and B' - G (the last row) or
  // max(Btot - Bd, 0) (the others: only the seeded law divides it; the first-frame law's
  // ST_NUM and ST_DEN reload both, and the other branches do not divide), else the product
  // (ST_NUM, ST_DEN).
  logic law_last, law_rest;
  assign law_last   = state_q == ST_LAW && row_last_q;
  assign law_rest   = state_q == ST_LAW && !row_last_q;
  assign div_num_in = (REM_W'(law_q.n)      & {REM_W{law_last}})
                    | (REM_W'(law_q.b_rest) & {REM_W{law_rest}})
                    | (REM_W'(mul_prod)     & {REM_W{state_q != ST_LAW}});
  assign div_den_in = (REM_W'(frm_q.spare)  & {REM_W{law_last}})
                    | (REM_W'(mul_prod)     & {REM_W{state_q != ST_LAW}});
  assign div_init     = run && state_q == ST_LAW;
  assign div_load_num = div_init || (run && state_q == ST_NUM && mul_done);
  assign div_load_den = div_init || (run && state_q == ST_DEN && mul_done);

  msr_seq_div #(.R_W(REM_W), .Q_W(11), .Q_SAT(Q_SAT)) u_div (
    .clk_i,
    .rst_ni,
    .init_i     (div_init),
    .quo_init_i ((row_last_q ? frm_q.spare == '0 : row_new_q && !x_pos) ? Q_SAT : 11'd0),
    .load_num_i (div_load_num),
    .num_i      (div_num_in),
    .load_den_i (div_load_den),
    .den_i      (div_den_in),
    .step_i     (run && state_q == ST_DIV),
    .last_o     (div_last),
    .quo_o      (div_quo)
  );

  // n0 of the last row, registered: h_last loads at the pulse and ST_WH, which uses it, begins
  // after the G product (at least one clock); from the pulse's registers through grid_axis
  // into the multiplier's load it was the unit's worst path.
  logic [5:0]      n0_last_q;
  always_ff @(posedge clk_i) begin
    n0_last_q <= grid_axis(frm_q.h_last, cfg.levels);
  end

  // The operands of the product that loads this clock, by the state that loads it.
  msr_budget_mul_ops u_mul_ops (
    .state_i      (state_q),
    .seq_load_i   (seq_load),
    .cfg_i        (cfg),
    .frm_i        (frm_q),
    .law_i        (law_q),
    .n0_last_i    (n0_last_q),
    .nn0_i        (nn0),
    .floor_ex_i   (floor_ex),
    .u_row_i      (u_q[base_q]),
    .u_new_i      (u_new),
    .pass_a_i     (pass_a),
    .pass_w_i     (pass_w_q),
    .op_o         (mop)
  );

  always_comb begin
    state_d    = state_q;
    mul_load   = 1'b0;
    mem_re     = 1'b0;
    mem_we     = 1'b0;
    unique case (state_q)
      ST_IDLE: begin
        if (act_q && row_done_i) begin
          mem_re   = 1'b1;
          state_d  = ST_FLR;
        end
      end
      // The floor from registers (c_j - g_j and p_j, latched with the row result): the
      // subtract and the compare are not one carry chain after the other in one clock.
      ST_FLR: begin
        mul_load = 1'b1;
        state_d  = ST_ACT;
      end
      // The chains of products: a product done starts the next (the table above).
      ST_G, ST_WH, ST_GL, ST_PL, ST_N0, ST_NUM: if (mul_done) begin
        mul_load = !(state_q == ST_G && checking_q);   // a check ends with G
        state_d  = mul_load ? budget_state_e'(state_q + 5'd1) : ST_IDLE;
      end
      ST_M0: if (mul_done) state_d = frm_q.seeded ? ST_PRD : ST_IDLE;
      // The seed pass: every row's word of the previous frame into b_k (docs/budget.md 6c).
      ST_PRD: begin
        mem_re  = 1'b1;
        state_d = ST_PWT;
      end
      ST_PWT: state_d = ST_PW;
      ST_PW:  state_d = ST_PMUL;
      ST_PMUL: begin
        mul_load = 1'b1;
        state_d  = ST_PB;
      end
      ST_PB: if (mul_done) begin
        mem_we  = 1'b1;
        state_d = pass_last ? ST_IDLE : ST_PRD;
      end
      ST_ACT: if (mul_done) begin
        mem_we  = 1'b1;
        state_d = ST_ACC;
      end
      ST_ACC: state_d = ST_LAW;
      ST_LAW: begin
        if (row_last_q) begin
          // SCALE_OUT = clamp(q) through ST_SLEW's max with a zero slew: one clamp for both
          state_d    = (frm_q.spare == '0) ? ST_SLEW : ST_DIV;
        end else if (!row_new_q) begin
          state_d = ST_SQ;                       // no new scale: just the row count
        end else if (!x_pos) begin
          state_d = ST_SLEW;                     // q = U_MAX + 1 (set below)
        end else if (frm_q.seeded) begin
          // (the divider's numerator: max(Btot - Bd, 0); its divisor u0 * X from ST_DEN)
          mul_load   = 1'b1;
          state_d    = ST_DEN;
        end else begin
          mul_load = 1'b1;
          state_d  = ST_NUM;
        end
      end
      ST_DEN: if (mul_done) state_d = ST_DIV;
      ST_DIV: if (div_last) state_d = ST_SLEW;
      ST_SLEW: state_d = row_last_q ? ST_FIN : ST_SQ0;
      ST_SQ0: begin
        mul_load = 1'b1;
        state_d  = ST_SQ;
      end
      ST_SQ: if (mul_done) state_d = ST_IDLE;
      ST_FIN: state_d = ST_IDLE;
      default: state_d = ST_IDLE;
    endcase
  end

  // ---- Registers ---------------------------------------------------------------------------
  // The ones the clear resets. The read-back of the row the walker asks about: known rows are
  // rows_done and the next (rows_done < nty while act_q; row rows_done + 1 is in the frame
  // unless rows_done is the last: equalities, not three magnitude compares). The input pulses
  // drop the old answers at once (the sequence starts six clocks later).
  budget_state_e state_n;
  logic          act_n, check_done_n, err_budget_n, err_profile_n, frame_done_n, row_ok_n;
  always_comb begin
    state_n       = (start_p || check_p) ? ST_G : state_d;
    act_n         = act_q && !start_i;
    check_done_n  = check_done_q && !check_i;
    {err_budget_n, err_profile_n} = {err_budget_q, err_profile_q};
    frame_done_n  = 1'b0;
    row_ok_n      = act_q && (row_idx_i == rows_done_q || (row_idx_i == rows_next_q && !row_last_q))
                    && !start_i && !start_p && !check_p;
    if (start_p || check_p) begin
      act_n = 1'b0;
      if (check_p && !start_p) check_done_n = 1'b0;
    end else if (state_q == ST_G && mul_done && checking_q) begin
      check_done_n  = 1'b1;
      err_budget_n  = cfg.budget != '0 && WH_W'(cfg.budget) < WH_W'(mul_prod);
      err_profile_n = cfg.seeded && !(mem_valid_q && mem_rows_q == frm_q.nty);
    end else if (state_q == ST_M0 && mul_done) begin
      act_n = 1'b1;
    end else if (state_q == ST_FIN) begin
      {act_n, frame_done_n} = 2'b01;
    end
  end
  `MSR_CLR_REG(u_ctl_q, $bits(budget_state_e) + 6, clear_i, 1'b1,
               {state_n, act_n, check_done_n, err_budget_n, err_profile_n, frame_done_n, row_ok_n},
               {state_q, act_q, check_done_q, err_budget_q, err_profile_q, frame_done_q, row_ok_q})

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      checking_q        <= 1'b0;
      rows_done_q       <= '0;
      rows_next_q       <= ROW_W'(1);
      rows_left_q       <= '0;
      row_last_q        <= 1'b0;
      row_new_q         <= 1'b0;
      u_q               <= '{default: '0};
      m_q               <= '{default: '0};
      base_q            <= '0;
      mem_valid_q       <= 1'b0;
      mem_rows_q        <= '0;
      scale_out_q       <= '0;
      scale_out_valid_q <= 1'b0;
      row_m_q           <= '0;
    end else if (!clear_i) begin                    // (a clear leaves them)
      row_m_q  <= m_q[(row_idx_i == rows_done_q) ? base_q : slot1];
      if (start_p || check_p) begin
        // Both begin with the grid constants and G (the multiplier is loaded below).
        checking_q  <= !start_p;
        if (start_p) begin
          rows_done_q       <= '0;
          rows_next_q       <= ROW_W'(1);
          base_q            <= '0;
          mem_valid_q       <= 1'b0;
          scale_out_valid_q <= 1'b0;
          u_q[0]            <= cfg.u0;
          u_q[1]            <= cfg.u0;
        end
      end else begin
        unique case (state_q)
          ST_M0: if (mul_done) begin
            m_q[0] <= 13'((mul_prod + PROD_W'(128)) >> 8);
            m_q[1] <= 13'((mul_prod + PROD_W'(128)) >> 8);
            rows_left_q <= frm_q.nty;
            row_last_q <= frm_q.nty == ROW_W'(1);
            row_new_q  <= frm_q.nty[ROW_W-1:2] != '0 || frm_q.nty[1:0] == 2'd3;   // nty > 2
          end
          ST_FLR, ST_ACT: ;
          ST_SQ0: u_q[slot2] <= u_new;
          ST_SQ: if (mul_done) begin
            if (row_new_q) m_q[slot2] <= 13'((mul_prod + PROD_W'(128)) >> 8);
            // (the next row's flags from the rows left: equalities and bits, one decrement)
            rows_done_q <= rows_next_q;
            rows_next_q <= rows_next_q + ROW_W'(1);
            rows_left_q <= rows_left_q - ROW_W'(1);
            row_last_q  <= rows_left_q == ROW_W'(2);               // rows_done + 2 == nty
            row_new_q   <= rows_left_q[ROW_W-1:2] != '0;          // rows_done + 3 < nty
            base_q      <= slot1;
          end
          ST_FIN: begin
            scale_out_q       <= u_new;                // clamp(q) (ST_SLEW)
            rows_done_q       <= rows_next_q;
            rows_next_q       <= rows_next_q + ROW_W'(1);
            base_q            <= slot1;
            scale_out_valid_q <= 1'b1;
            mem_valid_q       <= 1'b1;
            mem_rows_q        <= frm_q.nty;
          end
          default: ;
        endcase
      end
    end
  end

  assign check_done_o      = check_done_q;
  assign err_budget_o      = err_budget_q;
  assign err_profile_o     = err_profile_q;
  assign row_ready_o       = act_q && state_q == ST_IDLE;
  assign row_ok_o          = row_ok_q;
  assign row_m_o           = row_m_q;
  assign scale_out_o       = scale_out_q;
  assign scale_out_valid_o = scale_out_valid_q;
  assign frame_done_o      = frame_done_q;

  // ---- Invariants ----------------------------------------------------------------------------
  /* verilator lint_off SYNCASYNCNET */
  `MSR_ASSERT_IMP(a_row_when_ready, row_done_i, row_ready_o || start_p || check_p || clear_i)
  `MSR_ASSERT_IMP(a_start_budget_on, start_p, cfg.budget != '0)
  `MSR_ASSERT_IMP(a_row_traced_range,
              act_q && row_done_i && state_q == ST_IDLE, row_traced_i >= g_sel &&
              row_traced_i <= p_sel)
  `MSR_ASSERT_IMP(a_scale_range, act_q, u_q[base_q] >= (frm_q.seeded ? U_MIN : U_MIN_FIRST) &&
                             u_q[base_q] <= U_MAX)
  `MSR_ASSERT_IMP(a_rows_in_frame, act_q, rows_done_q < frm_q.nty)
  `MSR_ASSERT_IMP(a_rows_count, act_q, rows_next_q == rows_done_q + ROW_W'(1) &&
                                      rows_left_q == frm_q.nty - rows_done_q)
  `MSR_ASSERT_IMP(a_shift_fits, state_q inside {ST_WH, ST_N0} && mul_done,
              mul_prod[PROD_W-1:ACT_W] == '0)
  `MSR_ASSERT_IMP(a_num_fits, state_q == ST_NUM && mul_done, mul_prod[PROD_W-1] == 1'b0)
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_budget_ctrl
