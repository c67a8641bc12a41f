// Constant tables of a tile axis's border region, for the level controller (msr_level_ctrl).
// An axis of extent n with stride S = 2^L has a regular part (multiples of S up to
// p = (n-1) & ~(S-1)) and a border region [p, n-1] of r = (n-1) & (S-1) < 8 pixels; which of
// its offsets belong to G(k), which are new at level k and their gaps b - a depend only on
// (r, k), so they are tables indexed by r, computed at elaboration (border_set is in msr_pkg:
// the engine's outer-sample flags use it too).
package msr_border_pkg;
  import msr_pkg::*;

  typedef logic [7:0] bmask_t;

  // The helpers below take whole values or structs and use a part of them.
  /* verilator lint_off UNUSEDSIGNAL */
  // Every function here runs at elaboration only (the localparam tables at the end): no
  // simulation code, so coverage is off for them (the tables' users are covered).
  /* verilator coverage_off */

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

  // Offsets o >= 1 of a border mask in ascending order (a bq, 3 bits each, the first at
  // bits [2:0]) and how many there are.
  typedef logic [6:0][2:0] bqueue_t;

  function automatic bqueue_t border_queue(bmask_t bm);
    bqueue_t q;
    int unsigned n;
    q = '0;
    n = 0;
    for (int unsigned o = 1; o < 8; o++) begin
      if (bm[o]) begin
        q[n] = 3'(o);
        n++;
      end
    end
    return q;
  endfunction

  function automatic logic [2:0] border_count(bmask_t bm);
    logic [2:0] n;
    n = '0;
    for (int unsigned o = 1; o < 8; o++) n += 3'(bm[o]);
    return n;
  endfunction

  // The same tables as queues: G(k)'s border offsets >= 1 (BQ_SET) and level k's new border
  // offsets (BQ_NEW, with their gaps BG_NEW), each with its length: constants, so a pass's
  // set-up is table look-ups and no search.
  typedef bqueue_t     [MAX_LEVELS:0] bq_row_t;
  typedef logic [MAX_LEVELS:0][2:0] bn_row_t;

  function automatic bmask_t new_mask(int unsigned r, int unsigned k);
    return (k == 0) ? '0 : (border_set(r, k) & ~border_set(r, k - 1));
  endfunction
  // The offsets of G(k) (is_new = 0) or of level k's new positions (is_new = 1).
  function automatic bmask_t list_mask(int unsigned r, int unsigned k, bit is_new);
    return is_new ? new_mask(r, k) : border_set(r, k);
  endfunction
  function automatic bq_row_t bq_row(int unsigned r, bit is_new);
    bq_row_t t;
    for (int unsigned k = 0; k <= MAX_LEVELS; k++) t[k] = border_queue(list_mask(r, k, is_new));
    return t;
  endfunction
  function automatic bn_row_t bn_row(int unsigned r, bit is_new);
    bn_row_t t;
    for (int unsigned k = 0; k <= MAX_LEVELS; k++) t[k] = border_count(list_mask(r, k, is_new));
    return t;
  endfunction

  typedef logic [6:0][3:0]      gqueue_t;    // gaps of the new border offsets, in order
  typedef gqueue_t [MAX_LEVELS:0] gq_row_t;
  function automatic gq_row_t gq_new_row(int unsigned r);
    gq_row_t t;
    int unsigned n;
    t = '0;
    for (int unsigned k = 1; k <= MAX_LEVELS; k++) begin
      n = 0;
      for (int unsigned o = 1; o < 8; o++) begin
        if (new_mask(r, k)[o]) begin
          t[k][n] = 4'(border_gap(r, k, o));
          n++;
        end
      end
    end
    return t;
  endfunction
  /* verilator coverage_on */
  // Per r: level k's new border offsets' gaps (BGQ_NEW), G(k)'s offsets >= 1 and their count
  // (BQ_SET, BN_SET), level k's new offsets and their count (BQ_NEW, BN_NEW).
  localparam gq_row_t BGQ_NEW [8] = '{gq_new_row(0), gq_new_row(1), gq_new_row(2), gq_new_row(3),
                                      gq_new_row(4), gq_new_row(5), gq_new_row(6), gq_new_row(7)};

  localparam bq_row_t BQ_SET [8] = '{bq_row(0, 0), bq_row(1, 0), bq_row(2, 0), bq_row(3, 0),
                                     bq_row(4, 0), bq_row(5, 0), bq_row(6, 0), bq_row(7, 0)};
  localparam bn_row_t BN_SET [8] = '{bn_row(0, 0), bn_row(1, 0), bn_row(2, 0), bn_row(3, 0),
                                     bn_row(4, 0), bn_row(5, 0), bn_row(6, 0), bn_row(7, 0)};
  localparam bq_row_t BQ_NEW [8] = '{bq_row(0, 1), bq_row(1, 1), bq_row(2, 1), bq_row(3, 1),
                                     bq_row(4, 1), bq_row(5, 1), bq_row(6, 1), bq_row(7, 1)};
  localparam bn_row_t BN_NEW [8] = '{bn_row(0, 1), bn_row(1, 1), bn_row(2, 1), bn_row(3, 1),
                                     bn_row(4, 1), bn_row(5, 1), bn_row(6, 1), bn_row(7, 1)};

  /* verilator lint_on UNUSEDSIGNAL */

endpackage : msr_border_pkg
