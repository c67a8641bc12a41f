// Ray budget stage (docs/budget.md sections 1 and 2): the unit between the tile generator and
// the engines in a top with the budget. It orders the generator's walk, paces it by the
// controller's scales and scales every tile's thresholds by its row's multiplier.
//
// Order: a budget frame's walker takes the tile rows interleaved (rows 0, S, 2S, .., then 1,
// 1 + S, ..; msr_budget_pkg::next_row), so the rows the controller has seen are spread over the
// frame; S is set the clock after the start (from the tile row count) and the walker waits for
// it; a frame without a budget has S = 1, row-major. The walker starts a row only when the
// controller knows its scale (row_ok_i for row_idx_o, the row's position in that order).
//
// Scale: every tile carries its row's threshold multiplier m and its dither d beside the
// generator's pipeline (taken as it enters S1), and two stages after the generator's descriptor
// register scale its thresholds, thr'' = min(255, (thr' * m + d) >> 8), d the tile's dither
// (bit-reversed (tx + ty) mod 256, whose mean is the rounding's 128: a row's mean threshold then
// moves smoothly with m instead of in integer steps): S6 the products (multiplier blocks on an
// FPGA), registered straight out of them, and d, S7 the add and the saturation (in one clock,
// the block and its wires in and out made the top's worst path). With bud_en_i low m = 256
// (every thr'' = thr' whatever d), so its descriptors are those of a top without the budget.
module msr_budget_stage import msr_pkg::*; import msr_budget_pkg::*; #(
  localparam int unsigned TROW_W = COORD_W - 2      // tile row index (as the walker's)
) (
  input  logic              clk_i,          // clock
  input  logic              rst_ni,         // asynchronous reset, active low
  input  logic              clear_i,        // synchronous clear (the generator's)
  input  logic              start_i,        // pulse: a frame starts (the generator's)
  input  dim_t              height_i,       // H of the starting frame
  input  tile_size_e        tile_i,         // T of the starting frame
  input  logic              bud_en_i,       // this frame holds a budget
  // The budget controller (msr_budget): the scale of the walker's row.
  output logic [TROW_W-1:0] row_idx_o,      // the walker's row: its position in the order
  input  logic              row_ok_i,       // its scale is known (this clock)
  input  logic [12:0]       row_m_i,        // its threshold multiplier m (1.0 = 256)
  // The row order, to the budget's row counters (from the second clock after start_i).
  output logic [TROW_W-1:0] smask_o,        // the order's stride S, less one
  output logic [TROW_W:0]   nty_s_o,        // nty - S
  // The tile generator (msr_tile_gen, EXT_ORDER, BUD_TAIL tail stages).
  input  logic [TROW_W:0]   nty_i,          // tile rows
  input  logic [7:0]        tx_i,           // the walker's next tile (its column mod 256)
  input  logic [TROW_W-1:0] ty_i,
  input  logic              row_step_i,     // the walker leaves its row
  output logic [TROW_W-1:0] row_next_o,     // the row after ty_i in the order
  output logic              row_last_o,     // ty_i is the order's last row
  output logic              row_go_o,       // the walker may hand out a tile of its row
  input  logic              adv_i,          // the generator's pipeline moves
  input  tile_desc_t        desc_i,         // its descriptor register (S5)
  output tile_desc_t        desc_o          // S7: the descriptor for the engines
);
  localparam int unsigned TIDX_W = TROW_W;
  localparam int unsigned D      = TILE_GEN_DEPTH;

  // ---- Order -----------------------------------------------------------------------------------
  // S = smask_q + 1: rows r, r + S, .. of phase r mod S, then the next phase; the last row in
  // that order is the last of phase S - 1. The stride is set the clock after the start (from
  // nty_i): row-major until then, and a budget frame's walker waits for it (in the top it waits
  // far longer, for the first scale).
  logic              set_q;
  logic [2:0]        lgs_d;                         // log2 S
  logic [TIDX_W-1:0] smask_q;                       // S - 1
  logic [TIDX_W:0]   nty_s_q;                       // nty - S: ty < nty_s_q is ty + S < nty
  logic [TIDX_W-1:0] pos_q;                         // the walker's row position in the order
  assign lgs_d = (set_q && bud_en_i) ? row_stride_log2(TIDX_W'(nty_i)) : 3'd0;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      set_q   <= 1'b0;
      smask_q <= '0;
      nty_s_q <= '0;
      pos_q   <= '0;
    end else begin
      set_q <= start_i && !clear_i;
      if ((start_i && !clear_i) || set_q) begin
        smask_q <= TIDX_W'((TIDX_W+1)'(1) << lgs_d) - 1'b1;
        nty_s_q <= (start_i ? tile_count(height_i, tile_log2(tile_i)) : nty_i) -
                   ((TIDX_W+1)'(1) << lgs_d);
      end
      if (start_i) pos_q <= '0;
      else if (row_step_i) pos_q <= pos_q + 1'b1;
    end
  end
  assign row_next_o = ({1'b0, ty_i} < nty_s_q) ? ty_i + (smask_q + 1'b1) : (ty_i & smask_q) + 1'b1;
  assign row_last_o = (ty_i & smask_q) == smask_q && !({1'b0, ty_i} < nty_s_q);
  assign row_go_o   = !bud_en_i || (row_ok_i && !set_q);
  assign row_idx_o  = pos_q;
  assign smask_o    = smask_q;
  assign nty_s_o    = nty_s_q;

  // ---- Scale: m and d beside S1..S5, then S6, S7 ----------------------------------------------
  localparam int unsigned P_W = THR_W + 13;         // thr' * m
  logic [D-1:0][12:0]              m_q;             // m of the tile in S1..S5
  logic [D-1:0][7:0]               dith_q;          // its dither d in S1..S5
  logic [MAX_LEVELS-1:0][P_W-1:0] prod6_q;         // S6: thr' * m per level
  logic [7:0]                      dith6_q;         // S6: the tile's dither d
  tile_desc_t                      desc6_q, desc7_q, desc7_d;
  // d = bit-reversed (tx + ty) mod 256: neighbouring tiles far apart in [0, 255]. Formed from
  // the walker's tile indices as the tile enters S1 and carried with it, not from the
  // descriptor's origin (x0 >> lg, y0 >> lg: two shifts by the tile size in front of the add).
  logic [7:0] txy, txy_rev;
  assign txy     = tx_i + 8'(ty_i);
  assign txy_rev = {<<{txy}};
  always_comb begin
    desc7_d = desc6_q;
    for (int k = 0; k < MAX_LEVELS; k++) begin
      /* verilator lint_off UNUSEDSIGNAL */
      logic [P_W-1:0] p;                            // its bits [7:0] are shifted out
      /* verilator lint_on UNUSEDSIGNAL */
      p = prod6_q[k] + P_W'(dith6_q);
      desc7_d.thr[k] = (p[P_W-1:THR_W+8] != '0) ? thr_t'(255) : thr_t'(p[THR_W+8-1:8]);
    end
  end
  // Data registers: read only under the generator's valid flags.
  always_ff @(posedge clk_i) begin
    if (adv_i) begin
      m_q     <= {m_q[D-2:0], bud_en_i ? row_m_i : 13'd256};
      dith_q  <= {dith_q[D-2:0], txy_rev};
      desc6_q <= desc_i;
      dith6_q <= dith_q[D-1];
      for (int k = 0; k < MAX_LEVELS; k++) prod6_q[k] <= P_W'(desc_i.thr[k]) * P_W'(m_q[D-1]);
      desc7_q <= desc7_d;
    end
  end
  assign desc_o = desc7_q;

endmodule : msr_budget_stage
