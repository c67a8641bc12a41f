// Level processing controller (spec sections 2-3, claims 4-9): walks every position of one
// tile in the binding order of sw_model/msr_model/tile_model.tile_schedule, one per clock:
//   initial pass : corners (0,0) (w-1,0) (0,h-1) (w-1,h-1) without duplicates, then the
//                  rest of G0(w) x G0(h) row-major;
//   level k, H   : rows y of Gy(k-1) top to bottom, new x of the level left to right;
//   level k, V   : columns x of Gx(k) left to right, new y of the level top to bottom.
// Each axis is kept as bit masks G(0..L) (bit i set = position i sampled), computed when the
// tile is accepted: G0 from the stride, G(k) = G(k-1) plus the midpoints of its gaps >= 2.
// Neighbours are the nearest set bits of G(k-1) on either side of the new position.
// A position whose row mask is empty (a hole, only in the initial pass) or an empty pass
// costs one idle cycle; otherwise a position is offered every clock.
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
  output logic    step_valid_o,   // one position of one pass
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
  output logic    step_first_o,   // first position of a pass (the engine's barrier)
  output logic    step_reuse_o,   // A is the B of the position before (same row / column)
  output logic    busy_o          // a tile is accepted and not all positions are out
);

  localparam int unsigned N = MAX_TILE;
  typedef logic [N-1:0] mask_t;

  typedef enum logic [2:0] {
    PH_IDLE   = 3'd0,
    PH_CORNER = 3'd1,
    PH_GRID   = 3'd2,
    PH_H      = 3'd3,
    PH_V      = 3'd4
  } phase_e;

  // ---- Mask helpers (small priority encoders) -----------------------------------------------
  function automatic mask_t initial_grid(ldim_t n, level_t levels);
    mask_t m;
    for (int unsigned bi = 0; bi < N; bi++) begin
      m[bi] = (bi < 32'(n)) && (((bi & ((32'd1 << levels) - 1)) == 0) || (bi == 32'(n) - 1));
    end
    return m;
  endfunction

  // Midpoints of every gap >= 2 of g: m = a + floor((b - a) / 2). Gaps are at most 8, so
  // m - a is 1..4 and only a window of 9 positions matters.
  function automatic mask_t split(mask_t g);
    mask_t s;
    logic  clear_lo, clear_hi;
    s = '0;
    for (int unsigned m = 1; m < N; m++) begin
      for (int unsigned d = 1; d <= 4; d++) begin
        if (m >= d && !g[m]) begin
          // a = m - d must be the nearest sampled position below m ...
          clear_lo = g[m-d];
          for (int unsigned j = 1; j < d; j++) clear_lo &= !g[m-j];
          // ... and b = a + 2d or a + 2d + 1 the nearest above it
          for (int unsigned e = 0; e <= 1; e++) begin
            if (m - d + 2 * d + e < N) begin
              clear_hi = g[m-d+2*d+e];
              for (int unsigned j = m + 1; j < m - d + 2 * d + e; j++) clear_hi &= !g[j];
              if (clear_lo && clear_hi) s[m] = 1'b1;
            end
          end
        end
      end
    end
    return s;
  endfunction

  function automatic lcoord_t first_set(mask_t g);
    lcoord_t r = '0;
    for (int bi = N - 1; bi >= 0; bi--) if (g[bi]) r = lcoord_t'(bi);
    return r;
  endfunction

  // Lowest set bit above p; found = 0 if none.
  function automatic logic [LCOORD_W:0] next_set(mask_t g, lcoord_t p);
    logic [LCOORD_W:0] r = '0;
    for (int bi = N - 1; bi >= 0; bi--) if (g[bi] && bi > int'(p)) r = {1'b1, lcoord_t'(bi)};
    return r;
  endfunction

  // Highest set bit below p (0 if none; the callers only ask where one exists).
  function automatic lcoord_t prev_set(mask_t g, lcoord_t p);
    lcoord_t r = '0;
    for (int bi = 0; bi < N; bi++) if (g[bi] && bi < int'(p)) r = lcoord_t'(bi);
    return r;
  endfunction

  // ---- State --------------------------------------------------------------------------------
  mask_t [MAX_LEVELS:0] gx_q, gy_q, gx_d, gy_d;
  ldim_t   w_q, h_q;
  level_t  levels_q;
  phase_e  phase_q, phase_d;
  level_t  k_q, k_d;            // level of the H / V pass
  logic [1:0] corner_q, corner_d;
  lcoord_t line_q, line_d;      // row y (grid, H) or column x (V)
  lcoord_t pos_q, pos_d;        // x (grid, H) or y (V)
  logic    first_q, first_d;
  lcoord_t last_b_q, last_line_q;

  // ---- Masks of the current pass --------------------------------------------------------------
  mask_t lineset, newmask, oldmask, linemask;
  logic  pass_empty;
  lcoord_t wm1, hm1;

  always_comb begin
    wm1 = lcoord_t'(w_q - 1'b1);
    hm1 = lcoord_t'(h_q - 1'b1);
    lineset = '0;
    newmask = '0;
    oldmask = '0;
    unique case (phase_q)
      PH_GRID: begin
        lineset = gy_q[0];
        newmask = gx_q[0];
      end
      PH_H: begin
        lineset = gy_q[k_q-1];
        newmask = gx_q[k_q] & ~gx_q[k_q-1];
        oldmask = gx_q[k_q-1];
      end
      PH_V: begin
        lineset = gx_q[k_q];
        newmask = gy_q[k_q] & ~gy_q[k_q-1];
        oldmask = gy_q[k_q-1];
      end
      default: ;
    endcase
    pass_empty = (newmask == '0);
  end

  // Positions of one line; the corners are left out of the grid phase's edge rows.
  function automatic mask_t line_mask(phase_e ph, mask_t nm, lcoord_t line, lcoord_t lw,
                                      lcoord_t lh);
    mask_t m = nm;
    if (ph == PH_GRID && (line == '0 || line == lh)) begin
      m[0]  = 1'b0;
      m[lw] = 1'b0;
    end
    return m;
  endfunction

  assign linemask = line_mask(phase_q, newmask, line_q, wm1, hm1);

  // ---- The position on offer ---------------------------------------------------------------
  logic    cur_valid;
  lcoord_t cur_x, cur_y, cur_a, cur_b;

  always_comb begin
    cur_valid = 1'b0;
    cur_x     = '0;
    cur_y     = '0;
    cur_a     = prev_set(oldmask, pos_q);
    cur_b     = lcoord_t'(next_set(oldmask, pos_q));
    unique case (phase_q)
      PH_CORNER: begin
        cur_x     = corner_q[0] ? wm1 : '0;
        cur_y     = corner_q[1] ? hm1 : '0;
        unique case (corner_q)
          2'd0:    cur_valid = 1'b1;
          2'd1:    cur_valid = (w_q > 1);
          2'd2:    cur_valid = (h_q > 1);
          default: cur_valid = (w_q > 1) && (h_q > 1);
        endcase
      end
      PH_GRID, PH_H: begin
        cur_x     = pos_q;
        cur_y     = line_q;
        cur_valid = linemask[pos_q];
      end
      PH_V: begin
        cur_x     = line_q;
        cur_y     = pos_q;
        cur_valid = linemask[pos_q];
      end
      default: ;
    endcase
  end

  assign step_valid_o  = cur_valid;
  assign step_x_o      = cur_x;
  assign step_y_o      = cur_y;
  assign step_ax_o     = (phase_q == PH_V) ? line_q : cur_a;
  assign step_ay_o     = (phase_q == PH_V) ? cur_a : line_q;
  assign step_bx_o     = (phase_q == PH_V) ? line_q : cur_b;
  assign step_by_o     = (phase_q == PH_V) ? cur_b : line_q;
  assign step_dir_o    = (phase_q == PH_H) ? DIR_H : (phase_q == PH_V) ? DIR_V : DIR_INIT;
  assign step_level_o  = (phase_q == PH_H || phase_q == PH_V) ? k_q : '0;
  assign step_gap_o    = (phase_q == PH_H || phase_q == PH_V) ? gap_t'(cur_b - cur_a) : '0;
  assign step_off_o    = (phase_q == PH_H || phase_q == PH_V) ? gap_t'(pos_q - cur_a) : '0;
  assign step_nshift_o = 2'(levels_q - k_q + 1'b1);
  assign step_first_o  = first_q;
  assign step_reuse_o  = !first_q && (phase_q == PH_H || phase_q == PH_V) &&
                         (line_q == last_line_q) && (cur_a == last_b_q);
  assign start_ready_o = (phase_q == PH_IDLE);
  assign busy_o        = (phase_q != PH_IDLE);

  // ---- Next position -------------------------------------------------------------------------
  logic              advance;
  logic [LCOORD_W:0] nx, nl;

  assign advance = !cur_valid || step_ready_i;
  assign nx      = next_set(linemask, pos_q);
  assign nl      = next_set(lineset, line_q);

  // The pass after this one: H(1) after the initial pass, V(k) after H(k), H(k+1) after V(k).
  phase_e  np_phase;
  level_t  np_k;
  logic    np_done;
  mask_t   np_lineset, np_newmask;

  always_comb begin
    np_done  = 1'b0;
    np_phase = PH_H;
    np_k     = k_q;
    unique case (phase_q)
      PH_GRID: np_k = level_t'(1);
      PH_H:    np_phase = PH_V;
      default: begin
        np_k    = k_q + 1'b1;
        np_done = (k_q == levels_q);
      end
    endcase
    np_lineset = (np_phase == PH_H) ? gy_q[np_k-1] : gx_q[np_k];
    np_newmask = (np_phase == PH_H) ? (gx_q[np_k] & ~gx_q[np_k-1])
                                    : (gy_q[np_k] & ~gy_q[np_k-1]);
  end

  always_comb begin
    phase_d  = phase_q;
    k_d      = k_q;
    corner_d = corner_q;
    line_d   = line_q;
    pos_d    = pos_q;
    first_d  = first_q;
    gx_d     = gx_q;
    gy_d     = gy_q;
    if (cur_valid && step_ready_i) first_d = 1'b0;
    unique case (phase_q)
      PH_IDLE: begin
        if (start_valid_i) begin
          gx_d[0] = initial_grid(w_i, levels_i);
          gy_d[0] = initial_grid(h_i, levels_i);
          for (int unsigned k = 1; k <= MAX_LEVELS; k++) begin
            gx_d[k] = gx_d[k-1] | split(gx_d[k-1]);
            gy_d[k] = gy_d[k-1] | split(gy_d[k-1]);
          end
          phase_d  = PH_CORNER;
          corner_d = '0;
          first_d  = 1'b1;
        end
      end
      PH_CORNER: begin
        if (advance) begin
          if (corner_q == 2'd3) begin
            phase_d = PH_GRID;
            line_d  = '0;
            pos_d   = first_set(line_mask(PH_GRID, gx_q[0], '0, wm1, hm1));
          end else begin
            corner_d = corner_q + 1'b1;
          end
        end
      end
      PH_GRID, PH_H, PH_V: begin
        if (advance) begin
          if (pass_empty || (!nx[LCOORD_W] && !nl[LCOORD_W])) begin
            // end of this pass: on to the next one (it may be empty), or done
            if (np_done) begin
              phase_d = PH_IDLE;
            end else begin
              phase_d = np_phase;
              k_d     = np_k;
              line_d  = first_set(np_lineset);
              pos_d   = first_set(np_newmask);
              first_d = 1'b1;
            end
          end else if (nx[LCOORD_W]) begin
            pos_d = lcoord_t'(nx);
          end else begin
            line_d = lcoord_t'(nl);
            pos_d  = first_set(line_mask(phase_q, newmask, lcoord_t'(nl), wm1, hm1));
          end
        end
      end
      default: phase_d = PH_IDLE;
    endcase
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      phase_q     <= PH_IDLE;
      k_q         <= '0;
      corner_q    <= '0;
      line_q      <= '0;
      pos_q       <= '0;
      first_q     <= 1'b0;
      gx_q        <= '0;
      gy_q        <= '0;
      w_q         <= '0;
      h_q         <= '0;
      levels_q    <= '0;
      last_b_q    <= '0;
      last_line_q <= '0;
    end else if (clear_i) begin
      phase_q     <= PH_IDLE;
      first_q     <= 1'b0;
    end else begin
      phase_q  <= phase_d;
      k_q      <= k_d;
      corner_q <= corner_d;
      line_q   <= line_d;
      pos_q    <= pos_d;
      first_q  <= first_d;
      gx_q     <= gx_d;
      gy_q     <= gy_d;
      if (start_valid_i && start_ready_o) begin
        w_q      <= w_i;
        h_q      <= h_i;
        levels_q <= levels_i;
      end
      if (cur_valid && step_ready_i) begin
        last_b_q    <= cur_b;
        last_line_q <= line_q;
      end
    end
  end

`ifndef SYNTHESIS
  // Lint: disable iff (!rst_ni) looks like a synchronous use of the asynchronous reset.
  /* verilator lint_off SYNCASYNCNET */
  a_start_args : assert property (@(posedge clk_i) disable iff (!rst_ni)
      start_valid_i && start_ready_o |->
        w_i inside {[1 : MAX_TILE]} && h_i inside {[1 : MAX_TILE]} &&
        levels_i inside {[1 : MAX_LEVELS]})
    else $error("msr_level_ctrl: tile %0dx%0d L=%0d out of range", w_i, h_i, levels_i);
  a_step_hold : assert property (@(posedge clk_i) disable iff (!rst_ni || clear_i)
      step_valid_o && !step_ready_i |=>
        step_valid_o && $stable({step_x_o, step_y_o, step_ax_o, step_ay_o, step_bx_o,
                                 step_by_o, step_gap_o, step_dir_o, step_first_o}))
    else $error("msr_level_ctrl: step changed while stalled");
  a_gap : assert property (@(posedge clk_i) disable iff (!rst_ni)
      step_valid_o && step_dir_o != DIR_INIT |-> step_gap_o inside {[2 : 8]} &&
        step_off_o == (step_gap_o >> 1))
    else $error("msr_level_ctrl: gap %0d offset %0d", step_gap_o, step_off_o);
  /* verilator lint_on SYNCASYNCNET */
`endif

endmodule : msr_level_ctrl
