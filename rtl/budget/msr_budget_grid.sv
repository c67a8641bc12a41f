// Ray budget: the frame's configuration and its grid constants, registered for the controller
// (msr_budget_ctrl; docs/budget.md "Terms", closed forms without a multiplier).
//
// The constants load the controller's multiplier at a check or a start; computed straight from
// the configuration (behind msr_budget's check/frame mux and the tile-size decode) they were
// the budget unit's worst path. So the configuration is registered,
// the constants from it registered again, and the pulses come out six clocks late with them
// (check_o, start_o): the configuration must hold from the input pulse on. A clear drops a
// pulse in flight.
`include "msr_flops.svh"

module msr_budget_grid import msr_pkg::*; import msr_budget_pkg::*; #(
  localparam int unsigned ROW_W = BUD_ROW_W             // tile row index (as the walker's)
) (
  input  logic             clk_i,              // clock
  input  logic             rst_ni,             // asynchronous reset, active low
  input  logic             clear_i,            // synchronous clear: drop pulses in flight
  // The configuration, from the pulse on.
  input  dim_t             width_i,            // W, 1..4096
  input  dim_t             height_i,           // H, 1..4096
  input  logic [2:0]       tile_log2_i,        // log2 T: 3, 4 or 5
  input  level_t           levels_i,           // L, 1..3 (S = 2^L)
  input  logic [23:0]      budget_i,           // B
  input  logic [10:0]      scale_init_i,       // u0 (0 reads as 256)
  input  logic [2:0]       prior_shift_i,      // PRIOR_SHIFT
  input  logic             seeded_i,           // the seeded law
  input  logic             check_i,            // pulse
  input  logic             start_i,            // pulse
  // Six clocks later: the pulses, with the configuration and the constants.
  output logic             check_o,
  output logic             start_o,
  output budget_grid_t     grid_o              // the configuration and the constants
);
  // Stage 1: the configuration.
  dim_t        width_q, height_q;
  logic [2:0]  tile_log2_q, prior_shift_q;
  level_t      levels_q;
  logic [23:0] budget_q;
  logic [10:0] scale_init_q;
  logic        seeded_q;
  always_ff @(posedge clk_i) begin
    width_q       <= width_i;
    height_q      <= height_i;
    tile_log2_q   <= tile_log2_i;
    levels_q      <= levels_i;
    budget_q      <= budget_i;
    scale_init_q  <= scale_init_i;
    prior_shift_q <= prior_shift_i;
    seeded_q      <= seeded_i;
  end

  // Stages 2 to 6: the constants, a few adds per clock (in one clock they were 49 generic
  // logic levels). The configuration goes out from stage 1 and the
  // constants that need no more from stage 2: it holds from the input pulse on, so they hold
  // when the pulse comes out.
  // Stage 2: each axis split at the tile size, the shift T / S, and what needs no more.
  logic [5:0]       tile_sz, h_rest, h_last, h_last_q;
  logic [12:0]      full_w, full_h, full_w_q, full_h_q;
  logic [5:0]       rest_w, rest_h, rest_w_q, rest_h_q;
  logic [2:0]       sh, sh_q;                        // log2 (T / S)
  level_t           lv_q;
  logic [ROW_W-1:0] nty, nty_q;
  logic [17:0]      p_full, p_full_q;
  logic [10:0]      u0, u0_q;
  // T is 8, 16 or 32 (msr_budget's decode): three-way choices, not shifters for every log2 T.
  assign {full_w, rest_w} = split_tile(width_q, tile_log2_q);
  assign {full_h, rest_h} = split_tile(height_q, tile_log2_q);
  always_comb begin
    unique case (tile_log2_q)
      3'd3:    begin tile_sz = 6'd8;  p_full = 18'(width_q) << 3; end
      3'd5:    begin tile_sz = 6'd32; p_full = 18'(width_q) << 5; end
      default: begin tile_sz = 6'd16; p_full = 18'(width_q) << 4; end
    endcase
  end
  assign h_rest  = rest_h;
  assign h_last  = (h_rest == '0) ? tile_sz : h_rest;
  assign sh      = tile_log2_q - {1'b0, levels_q};
  assign nty     = ROW_W'(full_h) + ROW_W'(rest_h != '0);
  assign u0      = clamp_u((scale_init_q == '0) ? 11'd256 : scale_init_q, U_MIN);
  // Stages 3 and 4: line(N) = floor(N / T) * n0(T) + n0(N mod T), n0(T) = T / S + 1 as
  // T >= 8 >= S: the full tiles' part and the rest's n0 side by side, then their sum (in one
  // clock, the rest's n0 and the two adds were the budget unit's worst path). One path
  // for both axes, W and H on alternate clocks (ax_q): each line is ready two clocks after
  // stage 2, the other one clock later.
  logic             ax_q, ax2_q;                     // the axis in stage 3, 4: 0 = W, 1 = H
  logic [12:0]      full_a, fl, fl_q;
  logic [5:0]       rest_a, ga, ga_q;
  assign full_a = ax_q ? full_h_q : full_w_q;
  assign rest_a = ax_q ? rest_h_q : rest_w_q;
  assign fl     = (full_a << sh_q) + full_a;
  assign ga     = grid_axis(rest_a, lv_q);
  logic [12:0]      line, line_w_q, line_h_q;
  assign line = fl_q + 13'(ga_q);
  // Stage 5: g of a full tile row = line(W) * n0(T).
  logic [17:0]      g_full, g_full_q;
  assign g_full = 18'((19'(line_w_q) << sh_q) + 19'(line_w_q));
  always_ff @(posedge clk_i) begin
    {h_last_q, full_w_q, full_h_q, rest_w_q, rest_h_q, sh_q, lv_q, nty_q, p_full_q, u0_q} <=
        {h_last, full_w, full_h, rest_w, rest_h, sh, levels_q, nty, p_full, u0};
    {fl_q, ga_q, ax2_q} <= {fl, ga, ax_q};
    if (ax2_q) line_h_q <= line;
    else       line_w_q <= line;
    g_full_q <= g_full;
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) ax_q <= 1'b0;
    else         ax_q <= !ax_q;
  end
  // In budget_grid_t's field order.
  assign grid_o = {width_q, height_q, levels_q, budget_q, prior_shift_q, seeded_q, h_last_q,
                   line_w_q, line_h_q, nty_q, g_full_q, p_full_q, u0_q};

  localparam int unsigned DLY = 6;                   // the stages above
  logic [DLY-1:0] check_q, start_q;
  `MSR_CLR_REG(u_dly_q, 2 * DLY, clear_i, 1'b1,
               {check_q[DLY-2:0], check_i, start_q[DLY-2:0], start_i}, {check_q, start_q})
  assign check_o = check_q[DLY-1];
  assign start_o = start_q[DLY-1];

endmodule : msr_budget_grid
