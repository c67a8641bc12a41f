// Ray budget: the controller's constants and the closed forms of the grid (docs/budget.md
// "Terms"), shared by the grid-constant unit (msr_budget_grid) and the controller
// (msr_budget_ctrl). Golden model: sw_model/msr_model/budget.py.
package msr_budget_pkg;
  import msr_pkg::*;

  // Not every unit uses every constant (each is linted on its own with the package).
  /* verilator lint_off UNUSEDPARAM */
  // Scale u in 1/256: the clamp [U_MIN, U_MAX] = [45, 1448] (0.18 .. 5.66); a first frame's
  // rows go down to U_MIN_FIRST = 32 (0.125: thresholds x 1/64) from a row at U_MIN or below
  // (docs/budget.md, "The first frame's range").
  localparam logic [10:0] U_MIN = 11'd45;
  localparam logic [10:0] U_MIN_FIRST = 11'd32;
  // A row's activity is at least its pixels >> FLOOR_SHIFT times its scale (docs/budget.md).
  localparam int unsigned FLOOR_SHIFT = 7;
  localparam logic [10:0] U_MAX = 11'd1448;
  localparam logic [10:0] Q_SAT = 11'd1449;      // U_MAX + 1: "no budget left" / saturated
  // msr_budget_stage's stages after the tile generator's descriptor register (S6, S7).
  localparam int unsigned BUD_TAIL = 2;
  /* verilator lint_on UNUSEDPARAM */

  // The controller's quantities (docs/budget.md section 6c gives the bounds).
  localparam int unsigned BUD_ROW_W = COORD_W - 2;   // tile row index (as the walker's)
  localparam int unsigned BUD_WH_W  = 25;            // W * H and every pixel count of a frame
  localparam int unsigned BUD_ACT_W = 36;            // N, N0
  localparam int unsigned BUD_SEED_W = 45;           // Btot, Bd: sums of a' * w(u', u0)
  // The shared multiplier (msr_shift_add_mul): multiplicand, multiplier, multiplier bits.
  localparam int unsigned BUD_MC_W = 36;
  localparam int unsigned BUD_MP_W = 25;
  localparam int unsigned BUD_ST_W = $clog2(BUD_MP_W + 1);

  // The configuration and the grid constants, as msr_budget_grid hands them on.
  typedef struct packed {
    dim_t                 width;      // W
    dim_t                 height;     // H
    level_t               levels;     // L
    logic [23:0]          budget;     // B
    logic [2:0]           prior_shift;
    logic                 seeded;     // the seeded law
    logic [5:0]           h_last;     // h of the last tile row (1..T)
    logic [12:0]          line_w;     // line(W): grid pixels of a tile row's row
    logic [12:0]          line_h;     // line(H)
    logic [BUD_ROW_W-1:0] nty;        // tile rows
    logic [17:0]          g_full;     // grid pixels of a full tile row
    logic [17:0]          p_full;     // pixels of a full tile row, W * T
    logic [10:0]          u0;         // u0, clamped
  } budget_grid_t;

  // The frame's constants: registered at a check or a start, then by the start's products.
  typedef struct packed {
    logic                 seeded;     // the seeded law
    logic [BUD_ROW_W-1:0] nty;        // tile rows
    logic [5:0]           h_last;     // height of the last tile row
    logic [17:0]          g_full;     // grid pixels of a full row, of the last row
    logic [17:0]          g_last;
    logic [17:0]          p_full;     // pixels of a full row, of the last row
    logic [17:0]          p_last;
    logic [BUD_WH_W-1:0]  grid;       // G
    logic [BUD_WH_W-1:0]  bud;        // B' = min(B, W * H)
    logic [BUD_WH_W-1:0]  spare;      // max(B' - G, 0)
    logic [10:0]          u0;         // the first rows' scale
  } budget_frame_t;

  // The law's running sums and operands, updated once per finished row.
  typedef struct packed {
    logic [BUD_ACT_W-1:0] n;          // N
    logic [BUD_ACT_W-1:0] n0;         // N0
    logic [BUD_SEED_W-1:0] b_rest;    // max(Btot - Bd, 0): seed-pass words of the rows to come
    logic [BUD_WH_W:0]    pp0;        // P + P0 (P0 = W * H >> PRIOR_SHIFT), as a running sum
    logic [BUD_WH_W-1:0]  p_left;     // W * H - P, as a running difference
    logic signed [26:0]   x_rem;      // X = (B' - G) + Gd - C, kept as a running sum
    logic [17:0]          p_row;      // the finished row's p_j
    logic [17:0]          ex;         // c_j - g_j >= 0 (the floor is applied from it a clock later)
    logic [10:0]          slew;       // fall(u_{j+1}): u >> 1, seeded u - (u >> 2)
    logic [10:0]          rise;       // 2 u_{j+1}, saturated at 2047 (2047 for the last row)
    logic                 deep;       // u_{j+1} <= U_MIN (a first frame's lo is U_MIN_FIRST)
    logic [10:0]          u_mx;       // min(max(q, fall(u_{j+1})), 2 u_{j+1})
  } budget_law_t;

  // A product's operands (msr_budget_mul_ops): b's low n bits are the multiplier, handed over
  // left-aligned (a fixed n per product, so the alignment is wiring).
  typedef struct packed {
    logic [BUD_MC_W-1:0] a;
    logic [BUD_MP_W-1:0] b;
    logic [BUD_ST_W-1:0] n;
  } budget_mul_op_t;

  // The controller's states (msr_budget_ctrl; here so its formal harness names them too).
  typedef enum logic [4:0] {
    ST_IDLE,
    ST_G,        // G = line(W) * line(H) (check and start)
    ST_WH,       // W * H
    ST_GL,       // g of the last row = line(W) * n0(h_last)
    ST_PL,       // p of the last row = W * h_last
    ST_N0,       // (B' - G) * u0
    ST_M0,       // u0 * u0
    ST_FLR,      // the activity floor: max(c_j - g_j, p_j >> FLOOR_SHIFT) loaded
    ST_ACT,      // a_j = max(c_j - g_j, p_j >> FLOOR_SHIFT) * u_j
    ST_ACC,      // the sums and the memory word
    ST_LAW,      // which law
    ST_NUM,      // (N + N0) * (W * H - P)
    ST_DEN,      // (P + P0) * X
    ST_DIV,      // the saturation test, then 11 quotient bits
    ST_SLEW,     // u_{j+2}
    ST_SQ0,      // u_{j+2} * u_{j+2} loaded
    ST_SQ,       // m_{j+2}
    ST_FIN,      // SCALE_OUT, the memory's tag
    ST_PRD,      // seed pass (a seeded start): read row k's word {u'_k, a'_k}
    ST_PWT,      // the word in the RAM's output register, then registered once more
    ST_PW,       // w = min(u'_k, u0) registered
    ST_PMUL,     // a'_k * w(u'_k, u0) loaded
    ST_PB        // b_k written back in its place, Btot += b_k
  } budget_state_e;

  // n0(n) = ceil(n / S) + ((n - 1) mod S != 0), for n in 0..32 (0 for n = 0), S = 2^l.
  function automatic logic [5:0] grid_axis(logic [5:0] n, level_t l);
    logic [5:0] s1;
    s1 = 6'((7'd1 << l) - 7'd1);
    if (n == '0) return '0;
    return ((n + s1) >> l) + 6'(((n - 6'd1) & s1) != '0);
  endfunction

  // n split at the tile size T = 2^lg, lg in 3..5: {n >> lg, n mod T}, a three-way choice (a
  // shift by a 3-bit amount would be a shifter for all eight).
  function automatic logic [18:0] split_tile(dim_t n, logic [2:0] lg);
    unique case (lg)
      3'd3:    return {13'(n >> 3), 6'(n[2:0])};
      3'd5:    return {13'(n >> 5), 6'(n[4:0])};
      default: return {13'(n >> 4), 6'(n[3:0])};
    endcase
  endfunction

  // The slot after s of the three scale slots.
  function automatic logic [1:0] inc3(logic [1:0] s);
    return (s == 2'd2) ? 2'd0 : s + 2'd1;
  endfunction

  // The dispatch order of a budget frame (docs/budget.md section 2): tile rows interleaved at a
  // stride S = 2^lgs, rows 0, S, 2S, .. then 1, 1 + S, .. up to phase S - 1, so the rows the law
  // has seen are spread over the frame. lgs = msb(nty) - 2, at least 0: the largest S with
  // 4 S <= nty (every phase holds four rows or more; raster order below 8 rows).
  function automatic logic [2:0] row_stride_log2(logic [BUD_ROW_W-1:0] nty);
    for (int b = BUD_ROW_W - 1; b >= 3; b--) if (nty[b]) return 3'(b - 2);
    return 3'd0;
  endfunction

  // The row dispatched after row r: r + S within its phase, else the next phase's first row,
  // (r mod S) + 1. s = S, smask = S - 1, nty_s = nty - S (registers of the frame): r < nty_s is
  // r + S < nty.
  function automatic logic [BUD_ROW_W-1:0] next_row(logic [BUD_ROW_W-1:0] r,
                                                     logic [BUD_ROW_W-1:0] s,
                                                     logic [BUD_ROW_W-1:0] smask,
                                                     logic [BUD_ROW_W:0] nty_s);
    return ({1'b0, r} < nty_s) ? r + s : (r & smask) + 1'b1;
  endfunction

  // The law's clamp [lo, U_MAX]: lo = U_MIN, or U_MIN_FIRST for a first frame's row whose
  // predecessor runs at U_MIN or below.
  function automatic logic [10:0] clamp_u(logic [10:0] v, logic [10:0] lo);
    return less_u(U_MAX, v) ? U_MAX : less_u(v, lo) ? lo : v;
  endfunction

  // a < b on scales, as plain logic from the top bit down: the clamp's bounds are constants (or
  // one of two), where a carry chain (and the packer's two extra carry cells around each
  // chain, on ECP5) cost several times the few LUTs the logic folds to.
  function automatic logic less_u(logic [10:0] a, logic [10:0] b);
    logic lt;
    lt = 1'b0;
    for (int i = 0; i < 11; i++) lt = (!a[i] && b[i]) || (!(a[i] ^ b[i]) && lt);
    return lt;
  endfunction

endpackage : msr_budget_pkg
