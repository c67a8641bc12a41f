// lindilate, the tile engine's IS -> RD -> AB side of the rule (docs/rules.md): per context the
// line tracking, the outer samples' existence tests and the outer sample A'.
//
// Line tracking: per context, the line of its last issued position and the line before it (a
// pass walks its lines in order), read at IS for the issued position and updated at IS. The
// first-line flag and the distance to the line before (1..8) are formed in RD, for the engine
// to register at AB.
//
// Existence: A' = a - g and B' = b + g on the position axis exist iff inside the tile and in
// G(k-1): a multiple of n_k up to p, else border offset (r, k - 1) (`border_set` in msr_pkg).
// IS -> RD: the two positions and the axis's p, r, n - 1; RD: the membership tests.
//
// A': per context the A of its last issued position (A' of the next position on the line, fact 1
// of the lindilate section in docs/architecture.md), written as the engine takes the read
// data (RD), read the same clock for the position in RD (the old value: the previous issue);
// where the level controller says o2a, A' is the third read port's word instead. A small
// memory: distributed RAM on an FPGA.
//
// The trackers' update has issue registers of its own, taken from the grant (GR): per context
// "its first position of a pass" and "another position of a pass" (one-hot, so the update
// needs no decode of the IS context) and the position's line. The engine's shared IS registers
// fan out to the descriptor choice and the RD stage across the engine, and the path from them
// through the tracker choice and the line compare into the trackers set the flat top's clock
// (most of it wire). The values are those of IS.
//
// Reset: only those two update flags (under the engine's clear, like IS's valid bit). Every
// other register here is loaded under its stage's valid bit, the trackers of a context by the
// first position of each pass, and the previous A is read only on a line whose earlier
// position wrote it.
`include "msr_flops.svh"
module msr_lin_track import msr_pkg::*; #(
  parameter int unsigned NUM_CTX = 8, parameter int unsigned CTX_W = $clog2(NUM_CTX)  // contexts
) (
  input  logic                clk_i, rst_ni, clear_i,  // clear: synchronous soft reset
  // GR: the granted position (the trackers' own issue registers)
  input  logic                gr_valid_i,   // a position is granted
  input  logic [NUM_CTX-1:0]  gr_gnt_i,     // its context, one-hot
  /* verilator lint_off UNUSEDSIGNAL */
  input  eng_pos_t            gr_pos_i,     // the position (its line, init and first flags)
  /* verilator lint_on UNUSEDSIGNAL */
  // IS: the issued position
  input  logic                is_valid_i,   // a position is in IS
  input  logic [CTX_W-1:0]    is_ctx_i,     // its context
  // the position and its tile (of the tile, only size and levels are read here)
  /* verilator lint_off UNUSEDSIGNAL */
  input  eng_pos_t            is_pos_i,
  input  tile_desc_t          is_desc_i,
  /* verilator lint_on UNUSEDSIGNAL */
  output logic [LCOORD_W-2:0] is_mh_o,      // its index on its line, m >> 1 (the line store's)
  // RD: the same position a clock later, with its read data
  input  logic                rd_valid_i,   // a position is in RD
  input  logic [CTX_W-1:0]    rd_ctx_i,     // its context
  input  logic                rd_o2a_i,     // A' is the third port's word
  input  rgb_t                rd_a_i,       // A (port 1)
  input  rgb_t                rd_o2_i,      // the third port's word
  output logic                rd_fline_o,   // first line of its pass
  output logic [3:0]          rd_ldelta_o,  // distance to the line before (1..8)
  output logic                rd_oka_o,     // A' exists
  output logic                rd_okb_o,     // B' exists
  output rgb_t                rd_oa_o       // A'
);

  // ---- Line trackers ---------------------------------------------------------------------------
  lcoord_t [NUM_CTX-1:0] ln_cur_q, ln_prev_q;
  logic    [NUM_CTX-1:0] ln_has_q;
  lcoord_t is_line, is_m;
  logic    is_newline;

  assign is_line    = (is_pos_i.dir == DIR_V) ? is_pos_i.x : is_pos_i.y;
  assign is_m       = (is_pos_i.dir == DIR_V) ? is_pos_i.y : is_pos_i.x;
  assign is_newline = is_line != ln_cur_q[is_ctx_i];
  // new positions of a level are at least 2 apart on their line
  assign is_mh_o    = is_m[LCOORD_W-1:1];

  logic [NUM_CTX-1:0] ln_first_q, ln_next_q, ln_moved;
  lcoord_t            ln_line_q;
  `MSR_CLR_REG(u_ln_upd_q, 2 * NUM_CTX, clear_i, 1'b1,
               {gr_gnt_i & {NUM_CTX{gr_valid_i && !gr_pos_i.init && gr_pos_i.first}},
                gr_gnt_i & {NUM_CTX{gr_valid_i && !gr_pos_i.init && !gr_pos_i.first}}},
               {ln_first_q, ln_next_q})
  always_ff @(posedge clk_i) begin
    ln_line_q <= (gr_pos_i.dir == DIR_V) ? gr_pos_i.x : gr_pos_i.y;
  end
  // "The granted position is on a new line", compared per context: ln_next_q is one-hot, so
  // this is the granted context's compare. Through the choice of the granted tracker first
  // (an AND-OR over the contexts), then one compare, the trackers' load enable was 7 LUT
  // levels deep (a worst path of the BUDGET_EN = 1 top); per context it is 3.
  for (genvar c = 0; c < NUM_CTX; c++) begin : g_moved
    assign ln_moved[c] = ln_line_q != ln_cur_q[c];
  end

  always_ff @(posedge clk_i) begin
    for (int unsigned c = 0; c < NUM_CTX; c++) begin
      if (ln_first_q[c]) begin
        ln_cur_q[c] <= ln_line_q;
        ln_has_q[c] <= 1'b0;
      end else if (ln_next_q[c] && ln_moved[c]) begin
        ln_prev_q[c] <= ln_cur_q[c];
        ln_cur_q[c]  <= ln_line_q;
        ln_has_q[c]  <= 1'b1;
      end
    end
  end

  // ---- Outer samples' existence ----------------------------------------------------------------
  typedef logic [MAX_LEVELS-1:0][7:0] bm_row_t;       // [k - 1] for the levels 1..3
  /* verilator coverage_off */        // elaboration only (the table below)
  function automatic bm_row_t bm_row(int unsigned r);
    bm_row_t t;
    for (int unsigned k = 0; k < MAX_LEVELS; k++) t[k] = border_set(r, k);
    return t;
  endfunction
  /* verilator coverage_on */
  localparam bm_row_t BM_SET [8] = '{bm_row(0), bm_row(1), bm_row(2), bm_row(3),
                                     bm_row(4), bm_row(5), bm_row(6), bm_row(7)};

  function automatic logic in_grid(lcoord_t v, lcoord_t p, lcoord_t mask, logic [7:0] bm);
    logic [2:0] o;            // v - p < 8 wherever it is used
    o = 3'(v - p);
    return (v <= p) ? ((v & mask) == '0) : bm[o];
  endfunction

  logic [LCOORD_W:0] is_ap, is_bp, is_a;
  lcoord_t           is_nm1, is_smask;

  always_comb begin
    is_a     = (LCOORD_W+1)'(is_m) - (LCOORD_W+1)'(is_pos_i.off);
    is_ap    = is_a - (LCOORD_W+1)'(is_pos_i.gap);
    is_bp    = is_a + (LCOORD_W+1)'({is_pos_i.gap, 1'b0});
    is_nm1   = lcoord_t'(((is_pos_i.dir == DIR_V) ? is_desc_i.h : is_desc_i.w) - 1'b1);
    is_smask = (lcoord_t'(1) << is_desc_i.levels) - 1'b1;              // S - 1
  end

  logic              rd_first_q, rd_newline_q, rd_has_q;
  lcoord_t           rd_line_q, rd_cur_q, rd_prev_q, rd_nm1_q, rd_p_q, rd_nkmask_q;
  logic [2:0]        rd_r_q;
  level_t            rd_km1_q;
  logic [LCOORD_W:0] rd_ap_q, rd_bp_q;

  always_ff @(posedge clk_i) begin
    if (is_valid_i) begin
      rd_first_q   <= is_pos_i.first;
      rd_newline_q <= is_newline;
      rd_has_q     <= ln_has_q[is_ctx_i];
      rd_line_q    <= is_line;
      rd_cur_q     <= ln_cur_q[is_ctx_i];
      rd_prev_q    <= ln_prev_q[is_ctx_i];
      rd_ap_q      <= is_ap;
      rd_bp_q      <= is_bp;
      rd_nm1_q     <= is_nm1;
      rd_p_q       <= is_nm1 & ~is_smask;
      rd_r_q       <= 3'(is_nm1 & is_smask);
      rd_km1_q     <= is_pos_i.level - 1'b1;
      // n_k - 1 = (S >> (k - 1)) - 1
      rd_nkmask_q  <= is_smask >> (is_pos_i.level - 1'b1);
    end
  end

  lcoord_t    rd_lprev;
  logic [7:0] rd_bm;

  always_comb begin
    rd_fline_o  = rd_first_q || (!rd_newline_q && !rd_has_q);
    rd_lprev    = rd_newline_q ? rd_cur_q : rd_prev_q;
    rd_ldelta_o = 4'(rd_line_q - rd_lprev);
    rd_bm       = BM_SET[rd_r_q][rd_km1_q];
    rd_oka_o    = !rd_ap_q[LCOORD_W] && in_grid(rd_ap_q[LCOORD_W-1:0], rd_p_q, rd_nkmask_q, rd_bm);
    rd_okb_o    = !rd_bp_q[LCOORD_W] && (rd_bp_q[LCOORD_W-1:0] <= rd_nm1_q) &&
                  in_grid(rd_bp_q[LCOORD_W-1:0], rd_p_q, rd_nkmask_q, rd_bm);
  end

  // ---- A': the context's previous A, or the third port ------------------------------------------
  rgb_t last_a_mem [NUM_CTX];

  always_ff @(posedge clk_i) begin
    if (rd_valid_i) last_a_mem[rd_ctx_i] <= rd_a_i;
  end

  assign rd_oa_o = rd_o2a_i ? rd_o2_i : last_a_mem[rd_ctx_i];

endmodule : msr_lin_track
