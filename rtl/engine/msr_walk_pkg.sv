// The level controller's lists and walks (msr_level_ctrl): a tile axis's positions of one
// pass as a list (its regular part, then its border offsets), a walk along it, and what a list
// is built from. Types and pure functions only; the controller registers every step of them.
package msr_walk_pkg;
  import msr_pkg::*;
  import msr_border_pkg::*;

  // ---- An ordered list of positions on one axis, and a walk along it ---------------------
  // The list is its regular part (first, first + st, ... up to p; `nreg` entries) followed by
  // p + o for every border offset o in the bq. A walk state is the current entry, how
  // many regular entries follow it, the border offsets still to come and how many entries
  // are left in all; stepping is an add (regular) or a bq shift (border), no search.
  typedef struct packed {
    lcoord_t p;
    lcoord_t st;
    lcoord_t first;
    logic [LCOORD_W:0] nreg;       // regular entries (0..32)
    logic [LCOORD_W:0] total;      // all entries
    bqueue_t bq;                   // border offsets
    gqueue_t gq;                   // their gaps (new positions only)
    gap_t    nk;                   // the gap of a regular new position
  } list_t;

  typedef struct packed {
    logic              ok;         // the list is not empty (cur is an entry)
    lcoord_t           cur;
    logic              border;     // cur is in the border region
    logic [LCOORD_W:0] reg_left;   // regular entries after cur
    logic [LCOORD_W:0] left;       // entries after cur
    bqueue_t           bq;      // border offsets after cur
    gap_t              gap;        // gap of cur (new positions only)
    gqueue_t           gq;         // gaps of the border offsets after cur
  } walk_t;

  // The start state needs every field of the list but its step.
  /* verilator lint_off UNUSEDSIGNAL */
  function automatic walk_t walk_start(list_t l);
    walk_t   w;
    bqueue_t q;
    q      = l.bq;
    w.ok   = (l.total != '0);
    w.left = l.total - 1'b1;
    if (l.nreg != '0) begin
      w.cur      = l.first;
      w.border   = 1'b0;
      w.reg_left = l.nreg - 1'b1;
      w.bq       = q;
      w.gap      = l.nk;
      w.gq       = l.gq;
    end else begin
      w.cur      = l.p + lcoord_t'(q[0]);
      w.border   = 1'b1;
      w.reg_left = '0;
      w.bq       = q >> 3;
      w.gap      = l.gq[0];
      w.gq       = l.gq >> 4;
    end
    return w;
  endfunction
  /* verilator lint_on UNUSEDSIGNAL */

  function automatic walk_t walk_step(walk_t w, lcoord_t p, lcoord_t st);
    walk_t n;
    n      = w;
    n.left = w.left - 1'b1;
    if (w.reg_left != '0) begin
      n.cur      = w.cur + st;
      n.reg_left = w.reg_left - 1'b1;
    end else begin
      n.cur    = p + lcoord_t'(w.bq[0]);
      n.border = 1'b1;
      n.bq     = w.bq >> 3;
      n.gap    = w.gq[0];
      n.gq     = w.gq >> 4;
    end
    return n;
  endfunction

  // A list from its parameters: the regular part's count from p and the step, the border
  // offsets, their count and gaps from the tables.
  function automatic list_t make_list(lcoord_t p, lcoord_t st, logic [1:0] lst, lcoord_t first,
                                      logic grid, bqueue_t bq, logic [2:0] nb, gqueue_t gq);
    list_t l;
    l.gq    = gq;
    l.nk    = gap_t'(st);
    l.p     = p;
    l.st    = st;
    l.first = first;
    // regular entries: multiples of st up to p (grid), odd multiples of st / 2 below p (new)
    l.nreg  = (LCOORD_W+1)'(p >> lst) + (LCOORD_W+1)'(grid);
    l.total = (LCOORD_W+1)'(p >> lst) + (LCOORD_W+1)'(grid) + (LCOORD_W+1)'(nb);
    l.bq    = bq;
    return l;
  endfunction

  // What a list is made of, chosen per pass (set-up 0) and registered, so that the table
  // look-ups and counts of set-up 1 start from registers.
  typedef struct packed {
    lcoord_t    p;
    logic [2:0] r;
    level_t     kt;       // level index of the border table
    logic       is_new;   // new positions of level kt (else G(kt))
    lcoord_t    st;
    logic [1:0] lst;      // log2(st)
    lcoord_t    first;
    logic       grid;     // the regular part includes p
  } lparam_t;

  function automatic lparam_t lparam(lcoord_t p, logic [2:0] r, level_t kt, logic is_new,
                                     lcoord_t st, logic [1:0] lst, lcoord_t first, logic grid);
    return '{p: p, r: r, kt: kt, is_new: is_new, st: st, lst: lst, first: first, grid: grid};
  endfunction

  function automatic list_t build_list(lparam_t l);
    bqueue_t    bq;
    logic [2:0] nb;
    bq = l.is_new ? BQ_NEW[l.r][l.kt] : BQ_SET[l.r][l.kt];
    nb = l.is_new ? BN_NEW[l.r][l.kt] : BN_SET[l.r][l.kt];
    return make_list(l.p, l.st, l.lst, l.first, l.grid, bq, nb,
                     l.is_new ? BGQ_NEW[l.r][l.kt] : '0);
  endfunction

endpackage : msr_walk_pkg
