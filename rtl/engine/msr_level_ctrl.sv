// Level processing controller (spec sections 2-3, claims 4-9): walks every position of one
// tile in the binding order of sw_model/msr_model/tile_model.tile_schedule, one per clock:
//   initial pass : corners (0,0) (w-1,0) (0,h-1) (w-1,h-1) without duplicates, then the
//                  rest of G0(w) x G0(h) row-major;
//   level k, H   : rows y of Gy(k-1) top to bottom, new x of the level left to right;
//   level k, V   : columns x of Gx(k) left to right, new y of the level top to bottom.
//
// No bit masks and no priority encoders over the tile: an axis of extent n with stride
// S = 2^L splits into a regular part, the multiples of S up to p = (n-1) & ~(S-1), and a
// border region [p, n-1] of r = (n-1) & (S-1) < 8 pixels. In the regular part G(k) is the
// multiples of S >> k and the new positions of level k are the odd multiples of n_k / 2 with
// neighbours m -+ n_k / 2; the border region's positions and gaps depend only on (r, k) and
// come from small constant tables (msr_border_pkg, computed at elaboration).
// So the next position is an add, a compare and an 8-bit lowest-set-bit search.
//
// Pipeline: the walk state (which pass, line, position) runs one position ahead of the
// output register, which holds the position on offer with its neighbours; both are computed
// from registers only. Each pass starts with three set-up cycles (WS_SETUP0..2: the pass's
// list parameters, the lists, the walks' start states); an invalid corner, an empty row of the initial grid and an empty pass cost one
// idle cycle each. Inside a pass a position is offered every clock.
`include "msr_assert.svh"
`include "msr_flops.svh"

module msr_level_ctrl
  import msr_pkg::*;
  import msr_border_pkg::*;
  import msr_walk_pkg::*;
(
  input  logic    clk_i,
  input  logic    rst_ni,
  input  logic    clear_i,        // synchronous soft reset
  input  logic    start_valid_i,  // new tile
  output logic    start_ready_o,
  input  ldim_t   w_i,            // tile width 1..MAX_TILE
  input  ldim_t   h_i,            // tile height 1..MAX_TILE
  input  level_t  levels_i,       // L, 1..MAX_LEVELS
  output logic    step_valid_o,   // one position of one pass (registered)
  input  logic    step_ready_i,
  // The position, its neighbours, gap, level and pass (step_t). For the `lindilate` rule
  // (docs/rules.md; H and V passes) also the third read port's address, o2: it reads
  // B' = b + g, or A' = a - g where B' is outside the tile. Where B' is inside, A' (if it
  // exists) is the A of the line's previous position, which the context keeps; where A' is
  // not that (four cases over every n and L), B' is outside (tb/level_ctrl).
  output step_t   step_o,
  output logic    busy_o          // a tile is accepted and not all positions are out
);

  // The border region's constant tables: rtl/engine/msr_border_pkg.sv; the lists and walks
  // along an axis: rtl/engine/msr_walk_pkg.sv.

  // ---- Output register: the step on offer (its first flag is out_first_q) --------------------
  lcoord_t    step_x_q, step_y_q, step_ax_q, step_ay_q, step_bx_q, step_by_q, step_o2_q;
  gap_t       step_gap_q, step_off_q;
  level_t     step_level_q;
  logic [1:0] step_nshift_q;
  dir_e       step_dir_q;
  logic       step_o2a_q;

  // ---- Tile registers (set at start) -----------------------------------------------------
  level_t  levels_q;
  lcoord_t wm1_q, hm1_q;             // w - 1, h - 1
  lcoord_t px_q, py_q;               // p of each axis
  logic [2:0] rx_q, ry_q;            // border length of each axis

  // ---- Walk state: the candidate after the one in the output register ---------------------
  typedef enum logic [2:0] {
    WS_IDLE   = 3'd0,
    WS_CORNER = 3'd1,
    WS_SETUP0 = 3'd6,    // the pass's list parameters from the tile registers
    WS_SETUP1 = 3'd2,    // the lists (table look-ups, counts)
    WS_SETUP2 = 3'd3,    // the walks' start states from the lists
    WS_WALK   = 3'd4,
    WS_DONE   = 3'd5     // every position has left the walk state
  } wstate_e;

  wstate_e    ws_q, ws_d;
  dir_e       dir_q, dir_d;          // pass of the walk (DIR_INIT = initial grid)
  level_t     k_q, k_d;
  logic [1:0] corner_q, corner_d;
  logic       first_q, first_d;      // no position of this pass has been offered yet
  logic       skip_q, skip_d;        // the candidate is the x = 0 of an edge row: not offered
  list_t      lines_q, poss_q;       // the pass's lists (set-up 1)
  walk_t      pstart_q;              // walk state at the start of a line (set-up 2)
  walk_t      lw_q, lw_d, pw_q, pw_d;  // line walk, position walk
  // Compares of the walk state kept as flags beside it, set with it from the value it gets:
  // the next-candidate decision (line end, edge row) then starts from flip-flops, not from
  // compares of lw_q / pw_q (that was the engine's worst path, lw_q -> line end -> lw_next).
  logic       pw_left0_q, pw_left0_d;  // pw_q.left == 0
  logic       pw_left1_q, pw_left1_d;  // pw_q.left == 1
  logic       lw_edge_q, lw_edge_d;    // lw_q.cur == 0 || lw_q.left == 0
  lcoord_t    gp_nm1_q;               // n - 1 of the pass's position axis

  // Set-up 1: the lists of the pass (dir_q, k_q).
  lcoord_t s_full, nk, nk_half;
  logic [1:0] lst_new;               // log2 of the new positions' step n_k
  list_t   set_lines, set_poss;
  // What each list is made of, chosen per pass (set-up 0) and registered, so that the table
  // look-ups and counts of set-up 1 start from registers (msr_walk_pkg).
  lparam_t sel_lines, sel_poss, pl_q, pp_q;

  always_comb begin
    s_full  = lcoord_t'(1) << levels_q;
    nk      = (dir_q == DIR_INIT) ? s_full : (s_full >> (k_q - 1'b1));
    nk_half = nk >> 1;
    lst_new = 2'(levels_q - k_q + 1'b1);
    unique case (dir_q)
      DIR_H: begin   // rows of Gy(k-1), new x of level k
        sel_lines = lparam(py_q, ry_q, k_q - 1'b1, 1'b0, nk, lst_new, '0, 1'b1);
        sel_poss  = lparam(px_q, rx_q, k_q, 1'b1, nk, lst_new, nk_half, 1'b0);
      end
      DIR_V: begin   // columns of Gx(k), new y of level k
        sel_lines = lparam(px_q, rx_q, k_q, 1'b0, nk_half, lst_new - 1'b1, '0, 1'b1);
        sel_poss  = lparam(py_q, ry_q, k_q, 1'b1, nk, lst_new, nk_half, 1'b0);
      end
      default: begin // initial grid: rows of Gy(0), x of Gx(0)
        sel_lines = lparam(py_q, ry_q, '0, 1'b0, s_full, 2'(levels_q), '0, 1'b1);
        sel_poss  = lparam(px_q, rx_q, '0, 1'b0, s_full, 2'(levels_q), '0, 1'b1);
      end
    endcase
  end

  assign set_lines = build_list(pl_q);
  assign set_poss  = build_list(pp_q);

  // ---- Walk: next candidate ------------------------------------------------------------------
  logic    cand_valid;       // the candidate (set below, from the walk state)
  lcoord_t cand_x, cand_y, cand_a, cand_b;
  gap_t    cand_gap, cand_off;
  logic  advance, out_valid_q;
  logic  edge_row;         // the candidate's row is the first or the last of the initial grid
  logic  line_end;         // the candidate is the last position of its line
  walk_t pw_next, lw_next;

  assign advance  = !out_valid_q || step_ready_i;
  assign pw_next  = walk_step(pw_q, poss_q.p, poss_q.st);
  assign lw_next  = walk_step(lw_q, lines_q.p, lines_q.st);
  assign edge_row = (dir_q == DIR_INIT) && lw_edge_q;
  // an edge row leaves out its last position (a corner): it ends one early
  assign line_end = !pw_q.ok || pw_left0_q || (edge_row && pw_left1_q);

  always_comb begin
    ws_d     = ws_q;
    dir_d    = dir_q;
    k_d      = k_q;
    corner_d = corner_q;
    first_d  = first_q;
    skip_d   = skip_q;
    lw_d     = lw_q;
    pw_d     = pw_q;
    pw_left0_d = pw_left0_q;
    pw_left1_d = pw_left1_q;
    lw_edge_d  = lw_edge_q;
    if (advance) begin
      unique case (ws_q)
        WS_CORNER: begin
          first_d = 1'b0;
          if (corner_q == 2'd3) begin
            ws_d  = WS_SETUP0;
            dir_d = DIR_INIT;
          end
          corner_d = corner_q + 1'b1;
        end
        WS_SETUP0: ws_d = WS_SETUP1;
        WS_SETUP1: ws_d = WS_SETUP2;
        WS_SETUP2: begin
          lw_d    = walk_start(lines_q);
          pw_d    = walk_start(poss_q);
          // left = total - 1 (the first entry is cur)
          pw_left0_d = (poss_q.total == (LCOORD_W+1)'(1));
          pw_left1_d = (poss_q.total == (LCOORD_W+1)'(2));
          lw_edge_d  = (lines_q.total == (LCOORD_W+1)'(1)) || (walk_start(lines_q).cur == '0);
          // row 0 of the initial grid is an edge row: its x = 0 is a corner
          skip_d  = (dir_q == DIR_INIT);
          first_d = (dir_q != DIR_INIT);
          ws_d    = WS_WALK;
        end
        WS_WALK: begin
          if (pw_q.ok && !skip_q) first_d = 1'b0;
          skip_d = 1'b0;
          if (!line_end) begin
            pw_d = pw_next;                              // next position of the line
            pw_left0_d = pw_left1_q;
            pw_left1_d = (pw_q.left == (LCOORD_W+1)'(2));
          end else if ((pw_q.ok || dir_q == DIR_INIT) && lw_q.left != '0) begin
            lw_d   = lw_next;                            // first position of the next line
            pw_d   = pstart_q;
            pw_left0_d = (pstart_q.left == '0);
            pw_left1_d = (pstart_q.left == (LCOORD_W+1)'(1));
            // a step never comes back to 0 (the next regular line or a border line beyond p:
            // a_edge_flag checks it)
            lw_edge_d  = (lw_q.left == (LCOORD_W+1)'(1));
            skip_d = (dir_q == DIR_INIT) && (lw_q.left == 1);   // the last row is an edge row
          end else begin                                 // end of the pass (or an empty pass)
            pw_d.ok = 1'b0;
            if (dir_q == DIR_INIT) begin
              dir_d = DIR_H;
              k_d   = level_t'(1);
              ws_d  = WS_SETUP0;
            end else if (dir_q == DIR_H) begin
              dir_d = DIR_V;
              ws_d  = WS_SETUP0;
            end else if (k_q == levels_q) begin
              ws_d  = WS_DONE;
            end else begin
              dir_d = DIR_H;
              k_d   = k_q + 1'b1;
              ws_d  = WS_SETUP0;
            end
          end
        end
        WS_DONE: ws_d = WS_IDLE;
        default: ;
      endcase
    end
    if (ws_q == WS_IDLE && start_valid_i) begin
      ws_d     = WS_CORNER;
      dir_d    = DIR_INIT;
      k_d      = '0;
      corner_d = '0;
      first_d  = 1'b1;
      pw_d.ok  = 1'b0;
    end
  end

  // ---- Candidate -> output register ------------------------------------------------------

  always_comb begin
    cand_valid = 1'b0;
    cand_x     = '0;
    cand_y     = '0;
    cand_gap   = pw_q.gap;
    cand_off   = cand_gap >> 1;
    cand_a     = pw_q.cur - lcoord_t'(cand_off);
    cand_b     = pw_q.cur + lcoord_t'(cand_gap - cand_off);
    unique case (ws_q)
      WS_CORNER: begin
        cand_x = corner_q[0] ? wm1_q : '0;
        cand_y = corner_q[1] ? hm1_q : '0;
        unique case (corner_q)
          2'd0:    cand_valid = 1'b1;
          2'd1:    cand_valid = (wm1_q != '0);
          2'd2:    cand_valid = (hm1_q != '0);
          default: cand_valid = (wm1_q != '0) && (hm1_q != '0);
        endcase
      end
      WS_WALK: begin
        cand_valid = pw_q.ok && !skip_q;
        cand_x     = (dir_q == DIR_V) ? lw_q.cur : pw_q.cur;
        cand_y     = (dir_q == DIR_V) ? pw_q.cur : lw_q.cur;
      end
      default: ;
    endcase
  end

  // ---- The third port's read (lindilate) ----------------------------------------------------
  // A' = a - g = m - (o + g) and B' = b + g = m + (2g - o), o = g >> 1, from the walk state
  // (one small table and one add each). Whether they exist is worked out after the issue,
  // once per engine (msr_tile_engine), not here.
  logic [LCOORD_W:0] bp;
  logic [GAP_W:0]    back, fwd;         // g + o and 2g - o, o = g >> 1
  lcoord_t           ap, o2pos;         // A' only matters where it is in the tile
  logic              o2a;

  // back and fwd as tables of the gap (one LUT per bit) rather than two adders in series with
  // the add to cur and the compare: that chain of carries was the top's critical path.
  always_comb begin
    back = '0;
    fwd  = '0;
    for (int unsigned v = 0; v < 2**GAP_W; v++) begin
      if (pw_q.gap == gap_t'(v)) begin
        back = (GAP_W+1)'(v + v / 2);
        fwd  = (GAP_W+1)'(2 * v - v / 2);
      end
    end
    ap    = pw_q.cur - lcoord_t'(back);
    bp    = {1'b0, pw_q.cur} + (LCOORD_W+1)'(fwd);
    o2a   = bp[LCOORD_W] || (bp[LCOORD_W-1:0] > gp_nm1_q);
    o2pos = o2a ? ap : bp[LCOORD_W-1:0];
  end

  logic       out_first_q;

  // The clear stops the walk: its state, the position walk's "ok" and the offered position
  // go back to their reset values; the rest of the walk state holds through a clear (it is
  // set up again before it is used).
  logic [$bits(wstate_e)-1:0] ws_raw;
  logic  pw_ok_q, out_valid_d, out_first_d;
  // its ok bit is pw_ok_q's
  /* verilator lint_off UNUSEDSIGNAL */
  walk_t pw_rest_q;
  /* verilator lint_on UNUSEDSIGNAL */
  assign out_valid_d = advance ? cand_valid : out_valid_q;
  assign out_first_d = advance ? cand_valid && first_q : out_first_q;

  `MSR_CLR_REG_RST(u_walk_q, $bits(wstate_e) + 3, {WS_IDLE, 3'b000}, clear_i, 1'b1,
                   {ws_d, pw_d.ok, out_valid_d, out_first_d},
                   {ws_raw, pw_ok_q, out_valid_q, out_first_q})
  assign ws_q = wstate_e'(ws_raw);

  always_comb begin
    pw_q    = pw_rest_q;
    pw_q.ok = pw_ok_q;
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      dir_q      <= DIR_INIT;
      k_q        <= '0;
      corner_q   <= '0;
      first_q    <= 1'b0;
      skip_q     <= 1'b0;
      pw_rest_q  <= '0;
      pw_left0_q <= 1'b1;
      pw_left1_q <= 1'b0;
    end else if (!clear_i) begin
      dir_q      <= dir_d;
      k_q        <= k_d;
      corner_q   <= corner_d;
      first_q    <= first_d;
      skip_q     <= skip_d;
      pw_rest_q  <= pw_d;
      pw_left0_q <= pw_left0_d;
      pw_left1_q <= pw_left1_d;
    end
  end

  // Data registers: gated by the state and valid bits above, no reset needed.
  always_ff @(posedge clk_i) begin
    lw_q      <= lw_d;
    lw_edge_q <= lw_edge_d;
    if (ws_q == WS_SETUP0) begin
      pl_q    <= sel_lines;
      pp_q    <= sel_poss;
    end
    if (ws_q == WS_SETUP1) begin
      lines_q <= set_lines;
      poss_q  <= set_poss;
    end
    if (ws_q == WS_SETUP2) begin
      pstart_q  <= walk_start(poss_q);
      gp_nm1_q  <= (dir_q == DIR_V) ? hm1_q : wm1_q;
    end
    if (ws_q == WS_IDLE && start_valid_i) begin
      levels_q <= levels_i;
      wm1_q    <= lcoord_t'(w_i - 1'b1);
      hm1_q    <= lcoord_t'(h_i - 1'b1);
      px_q     <= lcoord_t'(w_i - 1'b1) & ~((lcoord_t'(1) << levels_i) - 1'b1);
      py_q     <= lcoord_t'(h_i - 1'b1) & ~((lcoord_t'(1) << levels_i) - 1'b1);
      rx_q     <= 3'(lcoord_t'(w_i - 1'b1) & ((lcoord_t'(1) << levels_i) - 1'b1));
      ry_q     <= 3'(lcoord_t'(h_i - 1'b1) & ((lcoord_t'(1) << levels_i) - 1'b1));
    end
    if (advance) begin
      step_x_q      <= cand_x;
      step_y_q      <= cand_y;
      step_ax_q     <= (dir_q == DIR_V) ? lw_q.cur : cand_a;
      step_ay_q     <= (dir_q == DIR_V) ? cand_a : lw_q.cur;
      step_bx_q     <= (dir_q == DIR_V) ? lw_q.cur : cand_b;
      step_by_q     <= (dir_q == DIR_V) ? cand_b : lw_q.cur;
      step_gap_q    <= (ws_q == WS_WALK && dir_q != DIR_INIT) ? cand_gap : '0;
      step_off_q    <= (ws_q == WS_WALK && dir_q != DIR_INIT) ? cand_off : '0;
      step_level_q  <= (ws_q == WS_WALK) ? k_q : '0;
      step_nshift_q <= 2'(levels_q - k_q + 1'b1);
      step_dir_q    <= (ws_q == WS_WALK) ? dir_q : DIR_INIT;
      step_o2a_q    <= o2a;
      step_o2_q     <= o2pos;
    end
  end

  assign step_valid_o  = out_valid_q;
  always_comb begin
    step_o = '{x: step_x_q, y: step_y_q, ax: step_ax_q, ay: step_ay_q, bx: step_bx_q,
               by: step_by_q, gap: step_gap_q, off: step_off_q, level: step_level_q,
               nshift: step_nshift_q, dir: step_dir_q, first: out_first_q, o2a: step_o2a_q,
               o2: step_o2_q};
  end
  assign start_ready_o = (ws_q == WS_IDLE);
  assign busy_o        = (ws_q != WS_IDLE) || out_valid_q;

  /* verilator lint_off SYNCASYNCNET */
  `MSR_ASSERT_IMP(a_start_args, start_valid_i && start_ready_o,
      w_i inside {[1 : MAX_TILE]} && h_i inside {[1 : MAX_TILE]} &&
      levels_i inside {[1 : MAX_LEVELS]})
  `MSR_ASSERT_NXT(a_step_hold, step_valid_o && !step_ready_i, step_valid_o &&
      $stable({step_x_q, step_y_q, step_ax_q, step_ay_q, step_bx_q, step_by_q, step_gap_q,
               step_dir_q, out_first_q}), clk_i, !rst_ni || clear_i)
  `MSR_ASSERT_IMP(a_gap, step_valid_o && step_dir_q != DIR_INIT,
      step_gap_q inside {[2 : 8]} && step_off_q == (step_gap_q >> 1))
  // The flags beside the walk state equal the compares they stand for, while they are used.
  `MSR_ASSERT_IMP(a_walk_flags, ws_q == WS_WALK,
      pw_left0_q == (pw_q.left == '0) && pw_left1_q == (pw_q.left == (LCOORD_W+1)'(1)) &&
      lw_edge_q == (lw_q.cur == '0 || lw_q.left == '0))
  `MSR_COVER(c_outer_a, step_valid_o && step_dir_q != DIR_INIT && step_o2a_q)
  `MSR_COVER(c_border_gap3, step_valid_o && step_gap_q == 4'd3)
  `MSR_COVER(c_level3, step_valid_o && step_level_q == 2'd3)
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_level_ctrl
