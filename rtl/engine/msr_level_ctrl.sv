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
// come from small constant tables (border_set, border_gap below, computed at elaboration).
// So the next position is an add, a compare and an 8-bit lowest-set-bit search.
//
// Pipeline: the walk state (which pass, line, position) runs one position ahead of the
// output register, which holds the position on offer with its neighbours; both are computed
// from registers only. Each pass starts with one set-up cycle that loads the pass's list
// parameters; an invalid corner, an empty row of the initial grid and an empty pass cost one
// idle cycle each. Inside a pass a position is offered every clock.
`include "msr_assert.svh"

module msr_level_ctrl
  import msr_pkg::*;
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
  output lcoord_t step_x_o,       // the position
  output lcoord_t step_y_o,
  output lcoord_t step_ax_o,      // neighbour A (left / top), H and V passes only
  output lcoord_t step_ay_o,
  output lcoord_t step_bx_o,      // neighbour B (right / bottom)
  output lcoord_t step_by_o,
  output gap_t    step_gap_o,     // g = b - a (0 in the initial pass)
  output gap_t    step_off_o,     // m - a
  output level_t  step_level_o,   // k (0 in the initial pass)
  output logic [1:0] step_nshift_o, // log2(n_k), n_k = S >> (k-1)
  output dir_e    step_dir_o,
  output logic    step_first_o,   // first position of a pass (the engine's pass barrier)
  output logic    busy_o          // a tile is accepted and not all positions are out
);

  // ---- Border-region tables (offsets from p, 0..7) ---------------------------------------
  typedef logic [7:0] bmask_t;

  // The helpers below take whole values or structs and use a part of them.
  /* verilator lint_off UNUSEDSIGNAL */

  // border_set(r, k): offsets of G(k) inside a border region of r + 1 pixels.
  function automatic bmask_t border_set(int unsigned r, int unsigned k);
    bmask_t s, n;
    s = '0;
    s[0] = 1'b1;
    s[r] = 1'b1;
    for (int unsigned lv = 1; lv <= k; lv++) begin
      n = s;
      for (int unsigned a = 0; a < 8; a++) begin
        if (s[a]) begin
          for (int unsigned b = a + 1; b < 8; b++) begin
            if (s[b]) begin
              if (b - a >= 2) n[a + (b - a) / 2] = 1'b1;
              break;
            end
          end
        end
      end
      s = n;
    end
    return s;
  endfunction

  // border_gap(r, k, o): gap b - a of the new position o of level k (0 if o is not new).
  function automatic gap_t border_gap(int unsigned r, int unsigned k, int unsigned o);
    bmask_t prev, cur;
    int unsigned a, b;
    prev = border_set(r, k - 1);
    cur  = border_set(r, k);
    if (!cur[o] || prev[o]) return '0;
    a = 0;
    b = 0;
    for (int unsigned i = 0; i < o; i++) if (prev[i]) a = i;
    for (int unsigned i = 7; i > o; i--) if (prev[i]) b = i;
    return gap_t'(b - a);
  endfunction

  typedef bmask_t [MAX_LEVELS:0] bset_row_t;
  typedef gap_t   [7:0]          gap_row_t;

  function automatic bset_row_t bset_row(int unsigned r);
    bset_row_t t;
    for (int unsigned k = 0; k <= MAX_LEVELS; k++) t[k] = border_set(r, k);
    return t;
  endfunction

  function automatic gap_row_t gap_row(int unsigned r, int unsigned k);
    gap_row_t t;
    for (int unsigned o = 0; o < 8; o++) t[o] = (k == 0) ? '0 : border_gap(r, k, o);
    return t;
  endfunction

  localparam bset_row_t BSET [8] = '{bset_row(0), bset_row(1), bset_row(2), bset_row(3),
                                     bset_row(4), bset_row(5), bset_row(6), bset_row(7)};
  localparam gap_row_t BGAP [8][MAX_LEVELS+1] = '{
    '{gap_row(0, 0), gap_row(0, 1), gap_row(0, 2), gap_row(0, 3)},
    '{gap_row(1, 0), gap_row(1, 1), gap_row(1, 2), gap_row(1, 3)},
    '{gap_row(2, 0), gap_row(2, 1), gap_row(2, 2), gap_row(2, 3)},
    '{gap_row(3, 0), gap_row(3, 1), gap_row(3, 2), gap_row(3, 3)},
    '{gap_row(4, 0), gap_row(4, 1), gap_row(4, 2), gap_row(4, 3)},
    '{gap_row(5, 0), gap_row(5, 1), gap_row(5, 2), gap_row(5, 3)},
    '{gap_row(6, 0), gap_row(6, 1), gap_row(6, 2), gap_row(6, 3)},
    '{gap_row(7, 0), gap_row(7, 1), gap_row(7, 2), gap_row(7, 3)}};

  // ---- One ordered list of positions on an axis ------------------------------------------
  // Regular part first .. p in steps of st (from first), then p + o for each set bit o >= 1
  // of the border mask bm.
  typedef struct packed {
    lcoord_t first;   // first regular value (0 for grids, n_k / 2 for new positions)
    logic    reg_ok;  // first <= p (the regular part is not empty)
    lcoord_t st;      // regular step
    lcoord_t p;       // last multiple of S on the axis
    bmask_t  bm;      // border offsets (bit 0 never set)
  } list_t;

  typedef struct packed {
    logic    ok;
    lcoord_t v;
  } opt_t;

  // Lowest set bit of a border mask above offset `after` (all bits when `all`).
  function automatic opt_t border_next(lcoord_t p, bmask_t bm, logic [2:0] after, logic all);
    bmask_t above;
    opt_t   r;
    above = all ? bm : (bm & ~((bmask_t'(2) << after) - 1'b1));
    r = '{ok: 1'b0, v: '0};
    for (int i = 7; i >= 1; i--) begin
      if (above[i]) r = '{ok: 1'b1, v: p + lcoord_t'(i)};
    end
    return r;
  endfunction

  function automatic opt_t list_first(list_t l);
    return l.reg_ok ? '{ok: 1'b1, v: l.first} : border_next(l.p, l.bm, '0, 1'b1);
  endfunction

  function automatic opt_t list_next(list_t l, lcoord_t v);
    logic [LCOORD_W:0] nv;
    nv = {1'b0, v} + {1'b0, l.st};
    if (v <= l.p && nv <= {1'b0, l.p}) return '{ok: 1'b1, v: lcoord_t'(nv)};
    if (v <= l.p) return border_next(l.p, l.bm, '0, 1'b1);
    return border_next(l.p, l.bm, 3'(v - l.p), 1'b0);
  endfunction

  /* verilator lint_on UNUSEDSIGNAL */

  // ---- Tile registers (set at start) -----------------------------------------------------
  level_t  levels_q;
  lcoord_t wm1_q, hm1_q;             // w - 1, h - 1
  lcoord_t px_q, py_q;               // p of each axis
  logic [2:0] rx_q, ry_q;            // border length of each axis

  // ---- Walk state: the candidate after the one in the output register ---------------------
  typedef enum logic [2:0] {
    WS_IDLE   = 3'd0,
    WS_CORNER = 3'd1,
    WS_SETUP  = 3'd2,    // load the pass's lists (one idle cycle)
    WS_WALK   = 3'd3,
    WS_DONE   = 3'd4     // every position has left the walk state
  } wstate_e;

  wstate_e    ws_q, ws_d;
  dir_e       dir_q, dir_d;          // pass of the walk (DIR_INIT = initial grid)
  level_t     k_q, k_d;
  logic [1:0] corner_q, corner_d;
  lcoord_t    line_q, line_d, pos_q, pos_d;
  logic       pos_ok_q, pos_ok_d;    // (line, pos) is a real position
  logic       first_q, first_d;      // no position of this pass has been offered yet
  list_t      lines_q, lines_d, poss_q, poss_d;
  gap_row_t   gaps_q, gaps_d;        // border gaps of the pass's new positions
  opt_t       pfirst_q, pfirst_d;    // first position of a line
  opt_t       pedge_q, pedge_d;      // first position of an edge row of the initial grid

  // Lists of a pass (set-up cycle).
  function automatic list_t grid_list(lcoord_t p, lcoord_t st, lcoord_t first, bmask_t bm);
    list_t l;
    l.first  = first;
    l.reg_ok = (first <= p);
    l.st     = st;
    l.p      = p;
    l.bm     = bm & 8'hFE;
    return l;
  endfunction

  lcoord_t s_full, nk, nk_half;        // S, n_k, n_k / 2 of the pass being set up
  list_t   set_lines, set_poss;
  gap_row_t set_gaps;
  logic    edge_row;                   // the candidate row is the first or last of the grid

  always_comb begin
    s_full  = lcoord_t'(1) << levels_q;
    nk      = (dir_q == DIR_INIT) ? s_full : (s_full >> (k_q - 1'b1));
    nk_half = nk >> 1;
    unique case (dir_q)
      DIR_H: begin   // rows of Gy(k-1), new x of level k
        set_lines = grid_list(py_q, nk, '0, BSET[ry_q][k_q - 1'b1]);
        set_poss  = grid_list(px_q, nk, nk_half, BSET[rx_q][k_q] & ~BSET[rx_q][k_q - 1'b1]);
        set_gaps  = BGAP[rx_q][k_q];
      end
      DIR_V: begin   // columns of Gx(k), new y of level k
        set_lines = grid_list(px_q, nk_half, '0, BSET[rx_q][k_q]);
        set_poss  = grid_list(py_q, nk, nk_half, BSET[ry_q][k_q] & ~BSET[ry_q][k_q - 1'b1]);
        set_gaps  = BGAP[ry_q][k_q];
      end
      default: begin // initial grid: rows of Gy(0), x of Gx(0)
        set_lines = grid_list(py_q, s_full, '0, BSET[ry_q][0]);
        set_poss  = grid_list(px_q, s_full, '0, BSET[rx_q][0]);
        set_gaps  = '0;
      end
    endcase
  end

  // ---- Walk: next candidate ------------------------------------------------------------------
  logic advance;                       // the output register takes the candidate
  opt_t nx, nl, ex;
  logic out_valid_q;

  assign nx       = list_next(poss_q, pos_q);
  assign nl       = list_next(lines_q, line_q);
  assign ex       = list_next(set_poss, '0);     // after x = 0 in an edge row (set-up only)
  assign edge_row = (dir_q == DIR_INIT) && (line_q == '0 || line_q == hm1_q);
  assign advance  = !out_valid_q || step_ready_i;

  // The pass after (dir_q, k_q): H(1) after the initial grid, V(k) after H(k), H(k+1) after V(k).
  always_comb begin
    ws_d     = ws_q;
    dir_d    = dir_q;
    k_d      = k_q;
    corner_d = corner_q;
    line_d   = line_q;
    pos_d    = pos_q;
    pos_ok_d = pos_ok_q;
    first_d  = first_q;
    lines_d  = lines_q;
    poss_d   = poss_q;
    gaps_d   = gaps_q;
    pfirst_d = pfirst_q;
    pedge_d  = pedge_q;
    if (advance) begin
      unique case (ws_q)
        WS_CORNER: begin
          first_d = 1'b0;
          if (corner_q == 2'd3) begin
            ws_d  = WS_SETUP;
            dir_d = DIR_INIT;
          end
          corner_d = corner_q + 1'b1;
        end
        WS_SETUP: begin
          lines_d  = set_lines;
          poss_d   = set_poss;
          gaps_d   = set_gaps;
          pfirst_d = list_first(set_poss);
          pedge_d  = '{ok: ex.ok && ex.v != wm1_q, v: ex.v};
          line_d   = '0;                                 // every line list starts at 0
          if (dir_q == DIR_INIT) begin                   // row 0 is an edge row
            pos_d    = ex.v;
            pos_ok_d = ex.ok && ex.v != wm1_q;
          end else begin
            pos_d    = list_first(set_poss).v;
            pos_ok_d = list_first(set_poss).ok;
          end
          first_d = (dir_q != DIR_INIT);
          ws_d    = WS_WALK;
        end
        WS_WALK: begin
          if (pos_ok_q) first_d = 1'b0;
          if (pos_ok_q && nx.ok && !(edge_row && nx.v == wm1_q)) begin
            pos_d = nx.v;                                // next position of the line
          end else if ((pos_ok_q || dir_q == DIR_INIT) && nl.ok) begin
            line_d = nl.v;                               // first position of the next line
            if (dir_q == DIR_INIT && nl.v == hm1_q) begin
              pos_d    = pedge_q.v;
              pos_ok_d = pedge_q.ok;
            end else begin
              pos_d    = pfirst_q.v;
              pos_ok_d = pfirst_q.ok;
            end
          end else begin                                 // end of the pass (or an empty pass)
            pos_ok_d = 1'b0;
            if (dir_q == DIR_INIT) begin
              dir_d = DIR_H;
              k_d   = level_t'(1);
              ws_d  = WS_SETUP;
            end else if (dir_q == DIR_H) begin
              dir_d = DIR_V;
              ws_d  = WS_SETUP;
            end else if (k_q == levels_q) begin
              ws_d  = WS_DONE;
            end else begin
              dir_d = DIR_H;
              k_d   = k_q + 1'b1;
              ws_d  = WS_SETUP;
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
      pos_ok_d = 1'b0;
    end
  end

  // ---- Candidate -> output register ------------------------------------------------------
  logic    cand_valid;
  lcoord_t cand_x, cand_y, cand_a, cand_b, cand_m;
  gap_t    cand_gap, cand_off;
  logic [2:0] cand_o;

  always_comb begin
    cand_valid = 1'b0;
    cand_x     = '0;
    cand_y     = '0;
    cand_m     = pos_q;
    cand_o     = 3'(pos_q - poss_q.p);
    cand_gap   = (pos_q > poss_q.p) ? gaps_q[cand_o] : gap_t'(poss_q.st);
    cand_off   = cand_gap >> 1;
    cand_a     = cand_m - lcoord_t'(cand_off);
    cand_b     = cand_m + lcoord_t'(cand_gap - cand_off);
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
        cand_valid = pos_ok_q;
        cand_x     = (dir_q == DIR_V) ? line_q : pos_q;
        cand_y     = (dir_q == DIR_V) ? pos_q : line_q;
      end
      default: ;
    endcase
  end

  logic       out_first_q;
  lcoord_t    out_x_q, out_y_q, out_ax_q, out_ay_q, out_bx_q, out_by_q;
  gap_t       out_gap_q, out_off_q;
  level_t     out_level_q;
  logic [1:0] out_nshift_q;
  dir_e       out_dir_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      ws_q        <= WS_IDLE;
      dir_q       <= DIR_INIT;
      k_q         <= '0;
      corner_q    <= '0;
      line_q      <= '0;
      pos_q       <= '0;
      pos_ok_q    <= 1'b0;
      first_q     <= 1'b0;
      out_valid_q <= 1'b0;
      out_first_q <= 1'b0;
    end else if (clear_i) begin
      ws_q        <= WS_IDLE;
      pos_ok_q    <= 1'b0;
      out_valid_q <= 1'b0;
      out_first_q <= 1'b0;
    end else begin
      ws_q     <= ws_d;
      dir_q    <= dir_d;
      k_q      <= k_d;
      corner_q <= corner_d;
      line_q   <= line_d;
      pos_q    <= pos_d;
      pos_ok_q <= pos_ok_d;
      first_q  <= first_d;
      if (advance) begin
        out_valid_q <= cand_valid;
        out_first_q <= cand_valid && first_q;
      end
    end
  end

  // Data registers: gated by the valid bits above, no reset needed.
  always_ff @(posedge clk_i) begin
    lines_q  <= lines_d;
    poss_q   <= poss_d;
    gaps_q   <= gaps_d;
    pfirst_q <= pfirst_d;
    pedge_q  <= pedge_d;
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
      out_x_q      <= cand_x;
      out_y_q      <= cand_y;
      out_ax_q     <= (dir_q == DIR_V) ? line_q : cand_a;
      out_ay_q     <= (dir_q == DIR_V) ? cand_a : line_q;
      out_bx_q     <= (dir_q == DIR_V) ? line_q : cand_b;
      out_by_q     <= (dir_q == DIR_V) ? cand_b : line_q;
      out_gap_q    <= (ws_q == WS_WALK && dir_q != DIR_INIT) ? cand_gap : '0;
      out_off_q    <= (ws_q == WS_WALK && dir_q != DIR_INIT) ? cand_off : '0;
      out_level_q  <= (ws_q == WS_WALK) ? k_q : '0;
      out_nshift_q <= 2'(levels_q - k_q + 1'b1);
      out_dir_q    <= (ws_q == WS_WALK) ? dir_q : DIR_INIT;
    end
  end

  assign step_valid_o  = out_valid_q;
  assign step_x_o      = out_x_q;
  assign step_y_o      = out_y_q;
  assign step_ax_o     = out_ax_q;
  assign step_ay_o     = out_ay_q;
  assign step_bx_o     = out_bx_q;
  assign step_by_o     = out_by_q;
  assign step_gap_o    = out_gap_q;
  assign step_off_o    = out_off_q;
  assign step_level_o  = out_level_q;
  assign step_nshift_o = out_nshift_q;
  assign step_dir_o    = out_dir_q;
  assign step_first_o  = out_first_q;
  assign start_ready_o = (ws_q == WS_IDLE);
  assign busy_o        = (ws_q != WS_IDLE) || out_valid_q;

  /* verilator lint_off SYNCASYNCNET */
  `MSR_ASSERT(a_start_args, start_valid_i && start_ready_o |->
      w_i inside {[1 : MAX_TILE]} && h_i inside {[1 : MAX_TILE]} &&
      levels_i inside {[1 : MAX_LEVELS]})
  `MSR_ASSERT(a_step_hold, step_valid_o && !step_ready_i |=> step_valid_o &&
      $stable({step_x_o, step_y_o, step_ax_o, step_ay_o, step_bx_o, step_by_o, step_gap_o,
               step_dir_o, step_first_o}), clk_i, !rst_ni || clear_i)
  `MSR_ASSERT(a_gap, step_valid_o && step_dir_o != DIR_INIT |->
      step_gap_o inside {[2 : 8]} && step_off_o == (step_gap_o >> 1))
  `MSR_COVER(c_border_gap3, step_valid_o && step_gap_o == 4'd3)
  `MSR_COVER(c_level3, step_valid_o && step_level_o == 2'd3)
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_level_ctrl
