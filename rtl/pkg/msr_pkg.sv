// Shared types and constants of the multi-level selective rendering accelerator.
// The arithmetic they carry is defined in docs/spec/algorithm.md.
//
// Naming: parameters and constants ALL_CAPS, types *_t, enums *_e (lowRISC style).
package msr_pkg;

  // Not every module uses every constant of the package; Verilator lints each module on
  // its own with the package, so its unused-parameter warning is waived for this file only.
  /* verilator lint_off UNUSEDPARAM */

  // ---- Limits ---------------------------------------------------------------------------
  localparam int unsigned MAX_TILE   = 32;                   // largest tile edge T
  localparam int unsigned MAX_LEVELS = 3;                    // largest L
  localparam int unsigned MAX_FRAME  = 4096;                 // largest frame edge
  localparam int unsigned MAX_STRIDE = 1 << MAX_LEVELS;      // initial stride S = 2^L <= 8

  localparam int unsigned COORD_W   = 12;                    // frame coordinate 0..4095
  localparam int unsigned DIM_W     = 13;                    // frame extent 1..4096
  localparam int unsigned LCOORD_W  = $clog2(MAX_TILE);      // tile-local coordinate 0..31
  localparam int unsigned LDIM_W    = LCOORD_W + 1;          // tile extent 1..32
  localparam int unsigned GAP_W     = 4;                     // gap b - a, 1..8
  localparam int unsigned THR_W     = 8;
  localparam int unsigned DIFF_W    = 10;                    // colour difference, sum metric <= 765
  localparam int unsigned SRC_W     = 8;                     // source code (spec section 4)

  // ---- Pixels and coordinates -------------------------------------------------------------
  typedef logic [7:0]          chan_t;
  typedef struct packed {
    chan_t r;
    chan_t g;
    chan_t b;
  } rgb_t;

  typedef logic [COORD_W-1:0]  coord_t;    // global frame coordinate
  typedef logic [DIM_W-1:0]    dim_t;      // frame width / height
  typedef logic [LCOORD_W-1:0] lcoord_t;   // tile-local coordinate
  typedef logic [LDIM_W-1:0]   ldim_t;     // tile width / height
  typedef logic [GAP_W-1:0]    gap_t;
  typedef logic [THR_W-1:0]    thr_t;
  typedef logic [DIFF_W-1:0]   diff_t;
  typedef logic [SRC_W-1:0]    src_t;

  // ---- Run-time configuration encodings -----------------------------------------------------
  typedef enum logic [1:0] {
    TILE_8  = 2'd0,
    TILE_16 = 2'd1,
    TILE_32 = 2'd2
  } tile_size_e;

  // log2 T of a tile size (the encoding's shift); an unused encoding reads as 16.
  function automatic logic [2:0] tile_log2(tile_size_e t);
    unique case (t)
      TILE_8:  return 3'd3;
      TILE_32: return 3'd5;
      default: return 3'd4;
    endcase
  endfunction

  // ceil(n / T) for n = 1..4096, T = 2^lg: at most 512 tiles per axis; (n >> lg) + (any bit
  // below lg), a 10-bit increment instead of a 14-bit add.
  function automatic logic [COORD_W-2:0] tile_count(dim_t n, logic [2:0] lg);
    logic [COORD_W-2:0] q;
    logic               rem;
    q   = (COORD_W-1)'(n >> lg);
    rem = (n & ((dim_t'(1) << lg) - 1'b1)) != '0;
    return q + (COORD_W-1)'(rem);
  endfunction

  // The tile generator's stages from its walker to its descriptor register (S1..S5): a unit
  // that carries a tile's own data beside them (msr_budget_stage) shifts it as deep.
  localparam int unsigned TILE_GEN_DEPTH = 5;

  typedef enum logic {
    METRIC_MAX = 1'b0,   // max(|dR|, |dG|, |dB|)
    METRIC_SUM = 1'b1    // |dR| + |dG| + |dB|
  } metric_e;

  // Decision rule (docs/rules.md): the patent's test, or `lindilate` (second differences on
  // A', A, B, B', dilated across the lines of the pass).
  typedef enum logic {
    RULE_PATENT    = 1'b0,
    RULE_LINDILATE = 1'b1
  } rule_e;

  typedef logic [1:0] level_t;            // L = 1..3, level index k = 0..3

  // ---- Source codes (spec section 4) ------------------------------------------------------
  localparam src_t SRC_INITIAL     = 8'd0;    // initial sample, traced
  localparam src_t SRC_INTERP_BASE = 8'd16;   // interpolated at level k: 16 + k
                                              // traced at level k: k

  function automatic src_t src_traced(level_t k);
    return src_t'(k);
  endfunction

  function automatic src_t src_interp(level_t k);
    return SRC_INTERP_BASE | src_t'(k);
  endfunction

  // ---- Tile descriptor: everything one engine needs for one tile ---------------------------
  // `rule` is the most significant field, so a descriptor packed without it is a patent one.
  typedef struct packed {
    rule_e                   rule;        // decision rule of the frame
    coord_t                  x0;          // tile origin in the frame
    coord_t                  y0;
    ldim_t                   w;           // tile extent, 1..T
    ldim_t                   h;
    level_t                  levels;      // L, 1..3
    metric_e                 metric;
    thr_t [MAX_LEVELS-1:0]   thr;         // foveated thresholds, thr[k-1] for level k
  } tile_desc_t;

  // ---- A finished pixel, as an engine emits it to the frame-buffer writer -----------------
  typedef struct packed {
    coord_t x;                            // global frame coordinates
    coord_t y;
    rgb_t   rgb;
    src_t   src;                          // source code (algorithm.md section 4)
    logic   last;                         // last pixel of its tile
  } pix_word_t;

  // ---- Level processing controller: one position of one pass -------------------------------
  typedef enum logic [1:0] {
    DIR_INIT = 2'd0,     // initial sample: traced, no neighbours
    DIR_H    = 2'd1,     // horizontal pass: neighbours left / right
    DIR_V    = 2'd2      // vertical pass: neighbours above / below
  } dir_e;

  // One position of one pass, as the level controller hands it on (its step_o).
  typedef struct packed {
    lcoord_t    x;        // the position
    lcoord_t    y;
    lcoord_t    ax;       // neighbour A (left / top), H and V passes only
    lcoord_t    ay;
    lcoord_t    bx;       // neighbour B (right / bottom)
    lcoord_t    by;
    gap_t       gap;      // g = b - a (0 in the initial pass)
    gap_t       off;      // m - a
    level_t     level;    // k (0 in the initial pass)
    logic [1:0] nshift;   // log2(n_k), n_k = S >> (k-1)
    dir_e       dir;
    logic       first;    // first position of a pass (the engine's pass barrier)
    logic       o2a;      // lindilate: the third port reads A' (B' = b + g is outside the tile)
    lcoord_t    o2;       // lindilate: the third port's read on the line: A' if o2a, else B'
  } step_t;

  localparam int unsigned TADDR_W = 2 * LCOORD_W;            // tile buffer address {y, x}

  // ---- Tile engine: one issued position (a context's head, carried from the issue to AB) ---
  // init stays the last field (scripts/bench_engine.py reads it as bit 0).
  typedef struct packed {
    dir_e       dir;
    logic       o2a;       // lindilate: A' comes from port 2 (else the context's last A)
    logic       first;     // the first position of its pass
    lcoord_t    x;         // tile-local coordinates
    lcoord_t    y;
    gap_t       gap;       // b - a
    gap_t       off;       // position - a
    level_t     level;
    logic [1:0] nshift;
    logic       init;      // initial-grid position: traced, no reads
  } eng_pos_t;

  // ---- Decision arithmetic shared by the decision units ------------------------------------
  // |x - y| of one colour channel.
  function automatic chan_t chan_absdiff(chan_t x, chan_t y);
    return (x > y) ? x - y : y - x;
  endfunction

  // The per-channel |x - y| of two colours, [2] red .. [0] blue.
  function automatic logic [2:0][7:0] rgb_absdiff(rgb_t x, rgb_t y);
    return {chan_absdiff(x.r, y.r), chan_absdiff(x.g, y.g), chan_absdiff(x.b, y.b)};
  endfunction

  // The spec's colour difference d from the per-channel differences: their maximum or sum.
  function automatic diff_t metric_diff(logic [2:0][7:0] d, metric_e metric);
    diff_t m;
    m = diff_t'(d[2]);
    if (diff_t'(d[1]) > m) m = diff_t'(d[1]);
    if (diff_t'(d[0]) > m) m = diff_t'(d[0]);
    return (metric == METRIC_SUM) ? diff_t'(d[2]) + diff_t'(d[1]) + diff_t'(d[0]) : m;
  endfunction

  // x * m for a 4-bit m, as two levels of adds of shifted copies of x (x up to MUL4_X_W bits):
  // every product of the decision and interpolation units has a 4-bit factor, and written this
  // way it stays in the logic beside its registers, out of the FPGA's multiplier blocks, whose
  // fixed rows cost the placed top most of a clock in wire (docs/handoff.md section 6).
  localparam int unsigned MUL4_X_W = 19;
  function automatic logic [MUL4_X_W+3:0] mul4(logic [3:0] m, logic [MUL4_X_W-1:0] x);
    logic [MUL4_X_W+3:0] t0, t1, t2, t3;
    t0 = m[0] ? (MUL4_X_W+4)'(x)      : '0;
    t1 = m[1] ? (MUL4_X_W+4)'(x) << 1 : '0;
    t2 = m[2] ? (MUL4_X_W+4)'(x) << 2 : '0;
    t3 = m[3] ? (MUL4_X_W+4)'(x) << 3 : '0;
    return (t0 + t1) + (t2 + t3);
  endfunction

  // thr * g: the right-hand side of every threshold test (<= 2040).
  function automatic logic [THR_W+GAP_W-1:0] thr_times_gap(thr_t thr, gap_t g);
    return (THR_W+GAP_W)'(mul4(g, MUL4_X_W'(thr)));
  endfunction

  /* verilator lint_on UNUSEDPARAM */

  // ---- Grid of an axis: border_set(r, k) = offsets of G(k) inside a border region of r + 1
  // pixels (offsets from p, 0..7; msr_level_ctrl's tables, the engine's outer-sample flags).
  // r and k are indices 0..7 and 0..3; their high bits are zero.
  // Called only in constant expressions (tables built at elaboration): no simulation code, so
  // no line of it can be covered; its tables are checked through their users' benches.
  /* verilator lint_off UNUSEDSIGNAL */
  /* verilator coverage_off */
  function automatic logic [7:0] border_set(int unsigned r, int unsigned k);
    logic [7:0] s, n;
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
  /* verilator coverage_on */
  /* verilator lint_on UNUSEDSIGNAL */

endpackage : msr_pkg
