// Ray budget controller, the arithmetic (docs/budget.md sections 1-4 and 6; golden model
// sw_model/msr_model/budget.py, class Controller, bit for bit).
//
// Why sequential: a tile row lasts thousands of clocks and the law runs once per row, so one
// shift-add multiplier (up to 36 x 25 bits, one multiplier bit per clock, stopping when the
// multiplier's remaining bits are zero) and one restoring divider (11 quotient bits, one per
// clock, the quotient saturated at U_MAX + 1 by a first test num >= den << 11) do every
// product and quotient of the frame; the only fast path is the read-back of a row's m.
//
// Sequences (one state machine, clear_i > start_i > check_i > row_done_i):
//   check_i: the grid constants line(W), line(H) from shifts and adds, G = line(W) * line(H)
//     on the multiplier (<= 13 clocks), the two checks: check_done_o at most 18 clocks after
//     the pulse (four of them register the configuration and the constants). check_done_o and the flags hold until the next check_i or clear_i.
//   start_i: G again, W * H, g of the last row, p of the last row, N0 = ((B' - G) * u0) >>
//     PRIOR_SHIFT (B' = min(B, W * H)), m0 = (u0 * u0 + 128) >> 8: <= 69 clocks, then rows
//     0 and 1 are known (row_ok_o) and row_ready_o rises. Atot is the N the last finished
//     frame ended with (the sum of the words it wrote into the activity memory).
//   row_done_i: a_j = (c_j - g_j) * u_j, the sums, the memory word, then the law of section 4
//     (first frame: two products and a quotient; seeded: a quotient), the slew limit and the
//     clamp, and m of row j + 2, row_ready_o low: at most 1 + 12 (a_j) + 2 + 26 + 26 (the two
//     products, multipliers of 25 bits) + 12 (division) + 2 + 12 (m) = 93 clocks.
//
// Scales: three slots (u, m) for the rows j, j + 1, j + 2 around rows_done (slot of row
// rows_done = base_q, the next ones follow modulo 3). row_ok_o answers row_idx_i: its scale is
// known and held, i.e. rows_done <= row_idx_i <= rows_done + 1 < nty + 1 (row r >= 2 becomes
// ok when the update of row r - 2 ends; the walker never asks a row below rows_done: a row is
// counted only after every one of its tiles left). row_ok_o and row_m_o are registered: they
// answer the row_idx_i of the clock before; a start or clear drops row_ok_o at once.
//
// Activity memory: 512 x 28 bits, one synchronous read and one write port (one ECP5 EBR), no
// reset; row j's word is read when its row result arrives and written a few clocks later. It
// is valid, with the row count of the frame that wrote it, once a budget frame has finished
// every row; a start invalidates it (it is being rewritten); a clear keeps a finished frame's
// memory.
//
// Widths (W, H <= 4096, so W * H <= 2^24; u <= 1448 < 2^10.5):
//   p_r <= 32 * 4096 = 2^17, c_j - g_j < 2^18; a_j <= 2^17 * 1448 < 2^27.5   (28 bits)
//   N, Atot, Ad <= (W * H - G) * 1448 < 2^34.5; N0 <= 2^24 * 1448 < 2^34.5;
//   N + N0 < 2^35.5                                                          (36 bits)
//   C, P, Gd, G, W * H, B' <= 2^24 (25 bits); P + P0 <= 2^25 (26 bits);
//   X = B' + Gd - C - G in (-2^25, 2^25) (27 bits signed; used only when > 0: 25 bits)
//   numerator (N + N0) * (W * H - P) < 2^35.5 * 2^24 = 2^59.5; the multiplier's 61-bit
//   accumulator (36 + 25 bits) holds any product of its operands.
//   denominator (P + P0) * X < 2^26 * 2^25 = 2^51 (51 bits); den << 11 < 2^62 (62-bit compare)
`include "msr_assert.svh"

module msr_budget_ctrl import msr_pkg::*; import msr_budget_pkg::*; #(
  localparam int unsigned ROW_W = COORD_W - 2           // tile row index (as the walker's)
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
  output logic             row_ready_o,        // a row result can be taken
  input  logic [ROW_W-1:0] row_idx_i,          // the row the tile generator asks about
  output logic             row_ok_o,           // its scale is known (registered)
  output logic [12:0]      row_m_o,            // its m = (u * u + 128) >> 8 (registered)
  output logic [10:0]      scale_out_o,        // SCALE_OUT
  output logic             scale_out_valid_o,  // SCALE_OUT is from a finished budget frame
  output logic             frame_done_o        // pulse: the last row's update is done
);


  localparam int unsigned WH_W   = 25;           // W * H and every pixel count of the frame
  localparam int unsigned ACT_W  = 36;           // N, N0, Atot, Ad
  localparam int unsigned MEM_W  = 28;           // a_j
  localparam int unsigned MC_W   = 36;           // multiplicand
  localparam int unsigned MP_W   = 25;           // multiplier
  localparam int unsigned PROD_W = MC_W + MP_W;  // 61
  localparam int unsigned REM_W  = PROD_W + 1;   // 62: holds den << 11
  localparam int unsigned MEM_DEPTH = 512;

  // ---- The configuration and the grid constants, four clocks after the pulses -------------
  // The check's flags and the row read-back drop at the input pulse itself (below).
  logic             check_p, start_p;
  dim_t             width_r, height_r;
  level_t           levels_r;
  logic [23:0]      budget_r;
  logic [2:0]       prior_shift_r;
  logic             seeded_r;
  logic [5:0]       h_last;
  logic [12:0]      line_w, line_h;
  logic [ROW_W-1:0] nty;
  logic [17:0]      g_full, p_full;
  logic [10:0]      u0;
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
    .width_o       (width_r),
    .height_o      (height_r),
    .levels_o      (levels_r),
    .budget_o      (budget_r),
    .prior_shift_o (prior_shift_r),
    .seeded_o      (seeded_r),
    .h_last_o      (h_last),
    .line_w_o      (line_w),
    .line_h_o      (line_h),
    .nty_o         (nty),
    .g_full_o      (g_full),
    .p_full_o      (p_full),
    .u0_o          (u0)
  );

  function automatic logic [1:0] inc3(logic [1:0] s);
    return (s == 2'd2) ? 2'd0 : s + 2'd1;
  endfunction

  // ---- State ---------------------------------------------------------------------------------
  typedef enum logic [4:0] {
    ST_IDLE,
    ST_G,        // G = line(W) * line(H) (check and start)
    ST_WH,       // W * H
    ST_GL,       // g of the last row = line(W) * n0(h_last)
    ST_PL,       // p of the last row = W * h_last
    ST_N0,       // (B' - G) * u0
    ST_M0,       // u0 * u0
    ST_ACT,      // a_j = (c_j - g_j) * u_j
    ST_ACC,      // the sums and the memory word
    ST_LAW,      // which law
    ST_NUM,      // (N + N0) * (W * H - P)
    ST_DEN,      // (P + P0) * X
    ST_DIV,      // the saturation test, then 11 quotient bits
    ST_SLEW,     // u_{j+2}
    ST_SQ0,      // u_{j+2} * u_{j+2} loaded
    ST_SQ,       // m_{j+2}
    ST_FIN       // SCALE_OUT, the memory's tag
  } state_e;

  state_e            state_q, state_d;
  logic              checking_q;           // the G sequence answers a check (not a start)
  logic              act_q;                // a budget frame is on and rows 0, 1 are known
  logic              seeded_q;
  logic [12:0]       line_w_q;
  logic [ROW_W-1:0]  nty_q, rows_done_q;
  logic [5:0]        h_last_q;
  logic [17:0]       g_full_q, p_full_q, g_last_q, p_last_q;
  logic [WH_W-1:0]   grid_q, wh_q, bud_q, spare_q, p0_q;
  logic [WH_W-1:0]   p_sum_q;
  logic signed [26:0] x_rem_q;             // X = (B' - G) + Gd - C, kept as a running sum
  logic              row_last_q, row_new_q; // row rows_done is the last; it sets a new scale
  logic [ACT_W-1:0]  n_q, n0_q, atot_q, ad_q, mem_sum_q;
  logic [10:0]       u0_q;
  logic [17:0]       c_q, g_row_q, p_row_q;
  logic [10:0]       u_q [3];
  logic [12:0]       m_q [3];
  logic [1:0]        base_q;               // slot of row rows_done_q
  logic              mem_valid_q;
  logic [ROW_W-1:0]  mem_rows_q;
  logic              check_done_q, err_budget_q, err_profile_q;
  logic [10:0]       scale_out_q;
  logic              scale_out_valid_q, frame_done_q;
  logic              row_ok_q;
  logic [12:0]       row_m_q;

  // ---- Multiplier (msr_shift_add_mul): one multiplier bit per clock -------------------------
  logic              mul_load;
  logic [MC_W-1:0]   mul_a;
  logic [MP_W-1:0]   mul_b;
  logic [PROD_W-1:0] mul_prod;
  logic              mul_done;

  // The multiplier's first operands of a check or a start: G = line(W) * line(H). Loaded
  // here, not in the state machine, as the pulse may come in any state.
  logic              seq_load;
  logic [MC_W-1:0]   seq_a;
  logic [MP_W-1:0]   seq_b;
  assign seq_load = !clear_i && (start_p || check_p);
  assign seq_a    = MC_W'(line_w);
  assign seq_b    = MP_W'(line_h);

  // mul_load of the state machine is overridden by a new sequence (one driver per flop).
  logic              mload;
  logic [MC_W-1:0]   ma;
  logic [MP_W-1:0]   mb;
  assign mload = seq_load || (mul_load && !start_p && !check_p);
  assign ma    = seq_load ? seq_a : mul_a;
  assign mb    = seq_load ? seq_b : mul_b;

  msr_shift_add_mul #(.A_W(MC_W), .B_W(MP_W)) u_mul (
    .clk_i,
    .rst_ni,
    .clear_i,
    .load_i (mload),
    .a_i    (ma),
    .b_i    (mb),
    .done_o (mul_done),
    .prod_o (mul_prod)
  );

  // ---- Divider: restoring, quotient bits 10..0 -------------------------------------------------
  logic [REM_W-1:0] div_rem_q, div_den_q;   // remainder; the divisor shifted to the next bit
  logic [10:0]      div_quo_q;
  logic [3:0]       div_cnt_q;
  logic             div_sat_q;              // the quotient is >= 2^11
  logic [REM_W-1:0] div_num_in, div_den_in;
  logic [REM_W:0]   div_diff;               // remainder - divisor: its borrow is the compare
  logic             div_ge;
  assign div_diff = {1'b0, div_rem_q} - {1'b0, div_den_q};
  assign div_ge   = !div_diff[REM_W];

  // ---- Activity memory ---------------------------------------------------------------------
  (* no_rw_check *)
  logic [MEM_W-1:0] mem_q [MEM_DEPTH];
  logic [MEM_W-1:0] mem_rdata_q;
  logic             mem_re, mem_we;
  logic [8:0]       mem_addr;
  assign mem_addr = rows_done_q[8:0];

  always_ff @(posedge clk_i) begin
    if (mem_we) mem_q[mem_addr] <= MEM_W'(mul_prod);
  end
  always_ff @(posedge clk_i) begin
    if (mem_re) mem_rdata_q <= mem_q[mem_addr];
  end

  // ---- Row quantities ------------------------------------------------------------------------
  logic             row_last, row_new, x_pos;
  logic [1:0]       slot1, slot2;
  logic [17:0]      g_sel, p_sel, c_minus_g;
  logic [18:0]      c_diff;                // c - g and its borrow (one carry chain)
  logic [ACT_W:0]   a_diff;                // Atot - Ad and its borrow
  logic [WH_W:0]    pp0;                  // P + P0 <= 2^25: 26 bits
  logic [ACT_W-1:0] nn0, a_left;
  logic [10:0]      u_new;
  logic [10:0]      slew_q, u_mx_q;        // u_{j+1} >> 1; max(q, u_{j+1} >> 1)
  assign row_last  = row_last_q;
  assign row_new   = row_new_q;
  assign x_pos     = !x_rem_q[26] && x_rem_q != '0;
  assign slot1     = inc3(base_q);
  assign slot2     = inc3(slot1);
  assign g_sel     = row_last ? g_last_q : g_full_q;
  assign p_sel     = row_last ? p_last_q : p_full_q;
  assign c_diff    = {1'b0, row_traced_i} - {1'b0, g_sel};
  assign c_minus_g = c_diff[18] ? '0 : c_diff[17:0];
  assign pp0       = (WH_W + 1)'(p_sum_q) + (WH_W + 1)'(p0_q);
  assign nn0       = n_q + n0_q;
  assign a_diff    = {1'b0, atot_q} - {1'b0, ad_q};
  assign a_left    = a_diff[ACT_W] ? '0 : a_diff[ACT_W-1:0];
  assign u_new     = clamp_u(u_mx_q);

  always_comb begin
    state_d    = state_q;
    mul_load   = 1'b0;
    mul_a      = '0;
    mul_b      = '0;
    mem_re     = 1'b0;
    mem_we     = 1'b0;
    div_num_in = '0;
    div_den_in = '0;
    unique case (state_q)
      ST_IDLE: begin
        if (act_q && row_done_i) begin
          mem_re   = 1'b1;
          mul_load = 1'b1;
          mul_a    = MC_W'(c_minus_g);
          mul_b    = MP_W'(u_q[base_q]);
          state_d  = ST_ACT;
        end
      end
      ST_G: if (mul_done) begin
        if (checking_q) begin
          state_d = ST_IDLE;
        end else begin
          mul_load = 1'b1;
          mul_a    = MC_W'(width_r);
          mul_b    = MP_W'(height_r);
          state_d  = ST_WH;
        end
      end
      ST_WH: if (mul_done) begin
        mul_load = 1'b1;
        mul_a    = MC_W'(line_w_q);
        mul_b    = MP_W'(grid_axis(h_last_q, levels_r));
        state_d  = ST_GL;
      end
      ST_GL: if (mul_done) begin
        mul_load = 1'b1;
        mul_a    = MC_W'(width_r);
        mul_b    = MP_W'(h_last_q);
        state_d  = ST_PL;
      end
      ST_PL: if (mul_done) begin
        mul_load = 1'b1;
        mul_a    = MC_W'(spare_q);
        mul_b    = MP_W'(u0_q);
        state_d  = ST_N0;
      end
      ST_N0: if (mul_done) begin
        mul_load = 1'b1;
        mul_a    = MC_W'(u0_q);
        mul_b    = MP_W'(u0_q);
        state_d  = ST_M0;
      end
      ST_M0: if (mul_done) state_d = ST_IDLE;
      ST_ACT: if (mul_done) begin
        mem_we  = 1'b1;
        state_d = ST_ACC;
      end
      ST_ACC: state_d = ST_LAW;
      ST_LAW: begin
        if (row_last) begin
          div_num_in = REM_W'(n_q);
          div_den_in = REM_W'(spare_q) << 11;
          state_d    = (spare_q == '0) ? ST_FIN : ST_DIV;
        end else if (!row_new) begin
          state_d = ST_SQ;                       // no new scale: just the row count
        end else if (!x_pos) begin
          state_d = ST_SLEW;                     // q = U_MAX + 1 (set below)
        end else if (seeded_q) begin
          div_num_in = REM_W'(a_left);
          div_den_in = REM_W'(x_rem_q[MP_W-1:0]) << 11;
          state_d    = ST_DIV;
        end else begin
          mul_load = 1'b1;
          mul_a    = nn0;
          mul_b    = wh_q - p_sum_q;
          state_d  = ST_NUM;
        end
      end
      ST_NUM: if (mul_done) begin
        mul_load = 1'b1;
        mul_a    = MC_W'(pp0);
        mul_b    = x_rem_q[MP_W-1:0];
        state_d  = ST_DEN;
      end
      ST_DEN: if (mul_done) state_d = ST_DIV;
      ST_DIV: if (div_cnt_q == 4'd1) state_d = row_last ? ST_FIN : ST_SLEW;
      ST_SLEW: state_d = ST_SQ0;
      ST_SQ0: begin
        mul_load = 1'b1;
        mul_a    = MC_W'(u_new);
        mul_b    = MP_W'(u_new);
        state_d  = ST_SQ;
      end
      ST_SQ: if (mul_done) state_d = ST_IDLE;
      ST_FIN: state_d = ST_IDLE;
      default: state_d = ST_IDLE;
    endcase
  end

  // ---- Registers ---------------------------------------------------------------------------
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      state_q           <= ST_IDLE;
      checking_q        <= 1'b0;
      act_q             <= 1'b0;
      seeded_q          <= 1'b0;
      line_w_q          <= '0;
      nty_q             <= '0;
      rows_done_q       <= '0;
      h_last_q          <= '0;
      g_full_q          <= '0;
      p_full_q          <= '0;
      g_last_q          <= '0;
      p_last_q          <= '0;
      grid_q            <= '0;
      wh_q              <= '0;
      bud_q             <= '0;
      spare_q           <= '0;
      p0_q              <= '0;
      p_sum_q           <= '0;
      x_rem_q           <= '0;
      row_last_q        <= 1'b0;
      row_new_q         <= 1'b0;
      n_q               <= '0;
      n0_q              <= '0;
      atot_q            <= '0;
      ad_q              <= '0;
      mem_sum_q         <= '0;
      u0_q              <= '0;
      c_q               <= '0;
      g_row_q           <= '0;
      p_row_q           <= '0;
      u_q               <= '{default: '0};
      m_q               <= '{default: '0};
      base_q            <= '0;
      mem_valid_q       <= 1'b0;
      mem_rows_q        <= '0;
      check_done_q      <= 1'b0;
      err_budget_q      <= 1'b0;
      err_profile_q     <= 1'b0;
      scale_out_q       <= '0;
      scale_out_valid_q <= 1'b0;
      frame_done_q      <= 1'b0;
      div_rem_q         <= '0;
      div_den_q         <= '0;
      div_quo_q         <= '0;
      div_cnt_q         <= '0;
      div_sat_q         <= 1'b0;
      slew_q            <= '0;
      u_mx_q            <= '0;
      row_ok_q          <= 1'b0;
      row_m_q           <= '0;
    end else if (clear_i) begin
      state_q      <= ST_IDLE;
      act_q        <= 1'b0;
      check_done_q <= 1'b0;
      err_budget_q <= 1'b0;
      err_profile_q <= 1'b0;
      frame_done_q <= 1'b0;
      row_ok_q     <= 1'b0;
    end else begin
      frame_done_q <= 1'b0;
      // Read-back of the row the walker asks about: known rows are rows_done and the next.
      row_ok_q <= act_q && row_idx_i >= rows_done_q && row_idx_i <= rows_done_q + ROW_W'(1)
                  && row_idx_i < nty_q;
      row_m_q  <= m_q[(row_idx_i == rows_done_q) ? base_q : slot1];

      // The input pulses drop the old answers at once (the sequence starts four clocks later).
      if (check_i) check_done_q <= 1'b0;
      if (start_i) begin
        act_q    <= 1'b0;
        row_ok_q <= 1'b0;
      end
      if (start_p || check_p) begin
        // Both begin with the grid constants and G (the multiplier is loaded below).
        state_q     <= ST_G;
        checking_q  <= !start_p;
        act_q       <= 1'b0;
        row_ok_q    <= 1'b0;
        line_w_q    <= line_w;
        nty_q       <= nty;
        h_last_q    <= h_last;
        g_full_q    <= g_full;
        p_full_q    <= p_full;
        u0_q        <= u0;
        seeded_q    <= seeded_r;
        if (check_p && !start_p) check_done_q <= 1'b0;
        if (start_p) begin
          n_q               <= '0;
          p_sum_q           <= '0;
          ad_q              <= '0;
          rows_done_q       <= '0;
          base_q            <= '0;
          atot_q            <= mem_sum_q;
          mem_valid_q       <= 1'b0;
          scale_out_valid_q <= 1'b0;
          u_q[0]            <= u0;
          u_q[1]            <= u0;
        end
      end else begin
        state_q <= state_d;
        unique case (state_q)
          ST_G: if (mul_done) begin
            grid_q <= WH_W'(mul_prod);
            if (checking_q) begin
              check_done_q  <= 1'b1;
              err_budget_q  <= budget_r != '0 && WH_W'(budget_r) < WH_W'(mul_prod);
              err_profile_q <= seeded_r && !(mem_valid_q && mem_rows_q == nty_q);
            end
          end
          ST_WH: if (mul_done) begin
            wh_q  <= WH_W'(mul_prod);
            bud_q <= (WH_W'(budget_r) < WH_W'(mul_prod)) ? WH_W'(budget_r) : WH_W'(mul_prod);
            p0_q  <= WH_W'(mul_prod) >> prior_shift_r;
          end
          ST_GL: if (mul_done) begin
            g_last_q <= 18'(mul_prod);
            spare_q  <= (bud_q > grid_q) ? bud_q - grid_q : '0;
          end
          ST_PL: if (mul_done) begin
            p_last_q <= 18'(mul_prod);
            x_rem_q  <= $signed({2'b00, spare_q});
          end
          ST_N0: if (mul_done) n0_q <= ACT_W'(mul_prod >> prior_shift_r);
          ST_M0: if (mul_done) begin
            m_q[0] <= 13'((mul_prod + PROD_W'(128)) >> 8);
            m_q[1] <= 13'((mul_prod + PROD_W'(128)) >> 8);
            act_q      <= 1'b1;
            row_last_q <= nty_q == ROW_W'(1);
            row_new_q  <= nty_q > ROW_W'(2);
          end
          ST_IDLE: if (act_q && row_done_i) begin
            c_q     <= row_traced_i;
            g_row_q <= g_sel;
            p_row_q <= p_sel;
          end
          ST_ACT: ;
          ST_ACC: begin
            n_q     <= n_q + ACT_W'(mul_prod);
            p_sum_q <= p_sum_q + WH_W'(p_row_q);
            x_rem_q <= x_rem_q - $signed({9'd0, c_q}) + $signed({9'd0, g_row_q});
            if (seeded_q) ad_q <= ad_q + ACT_W'(mem_rdata_q);
          end
          ST_LAW: begin
            // q = U_MAX + 1 without a division: X <= 0, or the last row with B' = G
            div_quo_q <= (row_last ? spare_q == '0 : row_new && !x_pos) ? Q_SAT : 11'd0;
            div_sat_q <= 1'b0;
            div_cnt_q <= 4'd12;
            slew_q    <= u_q[slot1] >> 1;
            div_rem_q <= div_num_in;
            div_den_q <= div_den_in;
          end
          ST_NUM: if (mul_done) div_rem_q <= REM_W'(mul_prod);
          ST_DEN: if (mul_done) div_den_q <= REM_W'(mul_prod) << 11;
          // Step 12 compares with den << 11: a quotient >= 2^11 saturates at U_MAX + 1 (it
          // clamps to U_MAX either way; the steps still run, so the step count does not
          // depend on the compare). Steps 11..1 give the quotient bits 10..0.
          ST_DIV: begin
            div_cnt_q <= div_cnt_q - 4'd1;
            div_den_q <= div_den_q >> 1;
            if (div_cnt_q == 4'd12) begin
              div_sat_q <= div_ge;
            end else begin
              if (div_ge) div_rem_q <= div_diff[REM_W-1:0];
              div_quo_q <= (div_cnt_q == 4'd1 && div_sat_q) ? Q_SAT : {div_quo_q[9:0], div_ge};
            end
          end
          ST_SLEW: u_mx_q <= (div_quo_q > slew_q) ? div_quo_q : slew_q;
          ST_SQ0: u_q[slot2] <= u_new;
          ST_SQ: if (mul_done) begin
            if (row_new) m_q[slot2] <= 13'((mul_prod + PROD_W'(128)) >> 8);
            rows_done_q <= rows_done_q + ROW_W'(1);
            row_last_q  <= rows_done_q + ROW_W'(2) == nty_q;
            row_new_q   <= rows_done_q + ROW_W'(3) < nty_q;
            base_q      <= slot1;
          end
          ST_FIN: begin
            scale_out_q       <= clamp_u(div_quo_q);
            rows_done_q       <= rows_done_q + ROW_W'(1);
            base_q            <= slot1;
            act_q             <= 1'b0;
            scale_out_valid_q <= 1'b1;
            frame_done_q      <= 1'b1;
            mem_valid_q       <= 1'b1;
            mem_rows_q        <= nty_q;
            mem_sum_q         <= n_q;
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
  `MSR_ASSERT(a_row_when_ready, row_done_i |-> row_ready_o || start_p || check_p || clear_i)
  `MSR_ASSERT(a_start_budget_on, start_p |-> budget_r != '0)
  `MSR_ASSERT(a_row_traced_range, state_q == ST_ACC |-> c_q >= g_row_q && c_q <= p_row_q)
  `MSR_ASSERT(a_div_den_nonzero, state_q == ST_DIV && div_cnt_q == 4'd12 |-> div_den_q != '0)
  `MSR_ASSERT(a_scale_range, act_q |-> u_q[base_q] >= U_MIN && u_q[base_q] <= U_MAX)
  `MSR_ASSERT(a_rows_in_frame, act_q |-> rows_done_q < nty_q)
  `MSR_ASSERT(a_num_fits, state_q == ST_NUM && mul_done |-> mul_prod[PROD_W-1] == 1'b0)
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_budget_ctrl
