// Ray budget, the counting side (docs/budget.md section 3): per tile row, the traced pixels
// (source code < 16) of the finished pixels at the frame-buffer writer's inputs, and the row's
// results handed to the budget controller in dispatch order (rows interleaved at the stride
// S of msr_budget_pkg::row_stride_log2, as the tile generator walks a budget frame).
//
// A row is finished when the last pixel of each of its ntx tiles has arrived: an engine emits
// a tile's pixels in order and ends with the one flagged last, so by then every pixel of the
// row has been counted (the same moment as "its pixel count reaches W * h", without a product).
// At most three rows are open (the controller's position j - 2 gates the tile generator's
// position j), so three counter pairs indexed by position mod 3 suffice; a slot is cleared when
// the controller takes its row, and its next row (three on) cannot have a pixel before then.
// The rows of the three open positions are registers (hrow_q), moved on by next_row at each
// take, so a pixel's slot is which of them its tile row is. The frame's tile grid and the
// order's stride are the tile generator's (its walker's registers, set by the second clock
// after the start): one copy of the tile counts in the top, not one per unit.
//
// Timing: S1 registers each input's slot (position mod 3: the open row its tile row equals,
// two masked equalities of its pixel row with registers), traced and last flags; S2 adds the
// per-slot counts (0..NUM_IN each) into the counters.
`include "msr_assert.svh"
`include "msr_flops.svh"

module msr_budget_rows import msr_pkg::*; import msr_budget_pkg::*; #(
  parameter int unsigned NUM_IN = 4,                       // pixel streams (engines)
  localparam int unsigned TROW_W = COORD_W - 2,           // tile row / column count width
  localparam int unsigned CNT_W  = 18                     // traced in a row: <= 4096 * 32
) (
  input  logic                     clk_i,         // clock
  input  logic                     rst_ni,        // asynchronous reset, active low
  input  logic                     clear_i,       // synchronous clear
  input  logic                     start_i,       // pulse: a budget frame begins (cfg below)
  input  logic [2:0]               tile_log2_i,   // log2 T: 3, 4 or 5, at start_i
  // The tile generator's grid and order, from the second clock after start_i to the frame's end.
  input  logic [TROW_W:0]          ntx_i,         // tiles per row
  input  logic [TROW_W:0]          nty_i,         // tile rows
  input  logic [TROW_W-1:0]        smask_i,       // the order's stride S, less one
  input  logic [TROW_W:0]          nty_s_i,       // nty - S
  // Finished pixels, as the writer takes them.
  input  logic [NUM_IN-1:0]        pix_fire_i,    // input i's pixel is taken this clock
  input  coord_t [NUM_IN-1:0]      pix_y_i,       // its row
  input  logic [NUM_IN-1:0]        pix_traced_i,  // its source code is < 16
  input  logic [NUM_IN-1:0]        pix_last_i,    // the last pixel of its tile
  // The next row's result, in row order, to the controller.
  output logic                     row_valid_o,   // row row_idx_o is finished
  input  logic                     row_ready_i,   // the controller takes it
  output logic [TROW_W-1:0]        row_idx_o,     // the oldest open row's position
  output logic                     row_bottom_o,  // ... it is the frame's bottom tile row
  output logic [CNT_W-1:0]         row_traced_o,  // its traced pixels
  output logic                     busy_o         // a budget frame's rows are not all handed on
);
  typedef logic [1:0] slot_t;                            // row mod 3
  localparam int unsigned INC_W = $clog2(NUM_IN + 1);    // pixels of one slot in a clock

  logic [2:0]              lg_q;                          // log2 T
  logic                    act_q;                         // rows left to hand on
  logic [TROW_W-1:0]       head_q;                        // the oldest open row's position
  slot_t                   hslot_q;                       // its slot
  logic [2:0][TROW_W-1:0]  hrow_q;                        // the rows of positions head .. head + 2
  logic [1:0][COORD_W-1:3] hy_q;                          // the first pixel rows of head, head + 1
  logic                    ign3_q, ign4_q;                // y bits 3, 4 are below the tile row (lg)
  logic                    bottom_q;                      // hrow_q[0] is row nty - 1
  logic [1:0]              set_q;                         // the two clocks after a start
  logic [2:0][CNT_W-1:0]   traced_q;
  logic [2:0][TROW_W-1:0]  tiles_q;                       // tiles of the row whose last pixel came
  // S1
  logic [NUM_IN-1:0]       s1_v_q, s1_tr_q, s1_last_q;
  slot_t [NUM_IN-1:0]      s1_slot_q;

  // The tile row of pixel row y: y >> lg.
  function automatic logic [TROW_W-1:0] tile_row(coord_t y, logic [2:0] lg);
    unique case (lg)
      3'd3:    return TROW_W'(y >> 3);
      3'd5:    return TROW_W'(y >> 5);
      default: return TROW_W'(y >> 4);
    endcase
  endfunction

  // (s + d) mod 3 for s in 0..2, d in 0..3, as a table (no carry chain for two bits)
  function automatic slot_t slot_add(slot_t s, logic [1:0] d);
    unique case ({s, d})
      4'b00_00, 4'b01_10, 4'b10_01, 4'b00_11: return 2'd0;
      4'b00_01, 4'b01_00, 4'b10_10, 4'b01_11: return 2'd1;
      4'b00_10, 4'b01_01, 4'b10_00, 4'b10_11: return 2'd2;
      default:                                return 2'd0;  // s = 3 never happens
    endcase
  endfunction

  // The number of set bits as boolean logic: a thermometer code (at least k + 1 set) built
  // one input at a time, then its length. A loop of additions made a chain of small carry
  // chains per slot (two per input), more than the counters themselves.
  function automatic logic [INC_W-1:0] ones(logic [NUM_IN-1:0] b);
    logic [NUM_IN-1:0] t;
    logic [INC_W-1:0]  n;
    t = '0;
    for (int unsigned i = 0; i < NUM_IN; i++) begin
      for (int k = NUM_IN - 1; k > 0; k--) t[k] = t[k] | (b[i] & t[k-1]);
      t[0] = t[0] | b[i];
    end
    n = '0;
    for (int unsigned k = 0; k < NUM_IN; k++) if (t[k]) n = INC_W'(k + 1);
    return n;
  endfunction

  logic take;
  assign row_valid_o  = act_q && ({1'b0, tiles_q[hslot_q]} == ntx_i);
  assign take         = row_valid_o && row_ready_i;
  assign row_idx_o    = head_q;
  assign row_bottom_o = bottom_q;
  assign row_traced_o = traced_q[hslot_q];
  assign busy_o       = act_q;

  // S2: each slot's counts plus this clock's pixels of its row; the taken row's slot restarts a
  // clock after the take (take_q: the take itself is the controller's ready and this unit's
  // row compare, too late to also steer three counters). No pixel of the slot's next row (three
  // rows on) can come in that clock: the tile generator waits for the controller's update.
  logic                   take_q;
  slot_t                  tslot_q;                       // the slot taken
  `MSR_CLR_REG(u_take_q, 3, clear_i || start_i, 1'b1, {take, hslot_q}, {take_q, tslot_q})
  // Per slot the clock's counts first (a small popcount of the inputs), then one add: not a
  // chain of NUM_IN wide adders (that chain was 36 logic levels).
  logic [2:0][INC_W-1:0] inc_tr, inc_la;
  always_comb begin
    for (int unsigned s = 0; s < 3; s++) begin
      logic [NUM_IN-1:0] in_s;                           // the inputs with a pixel of slot s
      for (int unsigned i = 0; i < NUM_IN; i++) in_s[i] = s1_v_q[i] && s1_slot_q[i] == slot_t'(s);
      inc_tr[s] = ones(in_s & s1_tr_q);
      inc_la[s] = ones(in_s & s1_last_q);
    end
  end

  // The counters are data registers (act_q gates them): a start, a clear or the slot's restart
  // loads zero, which synthesis makes the flip-flops' synchronous reset, not a multiplexer in
  // front of each adder (the slot has no pixel in the clock it restarts, a_restart_idle).
  logic [2:0] restart;
  for (genvar s = 0; s < 3; s++) begin : g_restart
    assign restart[s] = clear_i || start_i || (take_q && slot_t'(s) == tslot_q);
  end
  always_ff @(posedge clk_i) begin
    for (int unsigned s = 0; s < 3; s++) begin
      if (restart[s]) begin
        traced_q[s] <= '0;
        tiles_q[s]  <= '0;
      end else begin
        traced_q[s] <= traced_q[s] + CNT_W'(inc_tr[s]);
        tiles_q[s]  <= tiles_q[s] + TROW_W'(inc_la[s]);
      end
    end
  end

  logic                act_d;
  logic [NUM_IN-1:0]   s1_v_d;
  always_comb begin
    act_d  = act_q;
    s1_v_d = '0;
    if (!start_i) begin
      s1_v_d = pix_fire_i & {NUM_IN{act_q}};
      if (take && {1'b0, head_q} + 1'b1 == nty_i) act_d = 1'b0;
    end else begin
      act_d  = 1'b1;
    end
  end
  `MSR_CLR_REG(u_act_q, 1 + NUM_IN, clear_i, 1'b1, {act_d, s1_v_d}, {act_q, s1_v_q})
  // (a clear leaves the head: only a start reads it)
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      head_q   <= '0;
      hslot_q  <= '0;
    end else if (!clear_i) begin
      if (start_i) begin
        head_q  <= '0;
        hslot_q <= '0;
      end else if (take) begin
        head_q  <= head_q + 1'b1;
        hslot_q <= slot_add(hslot_q, 2'd1);
      end
    end
  end

  // The open rows: two clocks after a start (once the tile generator's grid and stride are
  // set) rows 0, S and 2S (S <= nty / 4, or S = 1); each take moves them on by one position.
  // Pixels come only once the controller has the first scales, many clocks later (a_rows_set).
  logic [TROW_W-1:0] s_row;                               // S = 2^k from S - 1 = 2^k - 1
  assign s_row = {smask_i[TROW_W-2:0], 1'b1} & ~smask_i;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) set_q <= '0;
    else         set_q <= {set_q[0], start_i && !clear_i};
  end
  // hy_q: the first pixel rows of the open rows at positions head and head + 1 (row << lg), so
  // that a pixel's slot is two masked equalities on its pixel row (in_row, below), not a shift
  // by lg per input and two compares after it: those were over half of this unit's LUTs on
  // ECP5 at four inputs. An open row is a row of the frame, so row << lg
  // < H fits a pixel row (a_slot_exact checks the equalities against the tile rows).
  // (bits 3 and up: a tile row starts at a multiple of 8; a row of the frame is below 512)
  function automatic logic [COORD_W-1:3] row_y(logic [COORD_W-4:0] r, logic [2:0] lg);
    unique case (lg)
      3'd3:    return r;
      3'd5:    return r << 2;
      default: return r << 1;
    endcase
  endfunction
  always_ff @(posedge clk_i) begin
    if (set_q[1]) begin
      hrow_q   <= {s_row << 1, s_row, TROW_W'(0)};
      hy_q     <= {row_y(s_row[COORD_W-4:0], lg_q), (COORD_W - 3)'(0)};
      bottom_q <= nty_i == (TROW_W + 1)'(1);
    end else if (take) begin
      hrow_q   <= {next_row(hrow_q[2], s_row, smask_i, nty_s_i), hrow_q[2], hrow_q[1]};
      hy_q     <= {row_y(hrow_q[2][COORD_W-4:0], lg_q), hy_q[1]};
      bottom_q <= {1'b0, hrow_q[1]} + 1'b1 == nty_i;
    end
  end

  // S1: the row's slot from which open position its tile row is (0..2; 2 if neither of the
  // first two). hrow_q and hslot_q move together, so the slot is the same whether S1 saw the
  // old or the new head.
  // (pixel row y is in tile row r iff y's bits from lg up equal those of r << lg)
  function automatic logic in_row(logic [COORD_W-1:3] y, logic [COORD_W-1:3] hy, logic ign3,
                                  logic ign4);
    return y[COORD_W-1:5] == hy[COORD_W-1:5] && (ign4 || y[4] == hy[4]) && (ign3 || y[3] == hy[3]);
  endfunction
  slot_t [NUM_IN-1:0] s1_slot_d;
  always_comb begin
    for (int unsigned i = 0; i < NUM_IN; i++) begin
      logic [COORD_W-1:3] y;
      y = pix_y_i[i][COORD_W-1:3];
      s1_slot_d[i] = slot_add(hslot_q, in_row(y, hy_q[0], ign3_q, ign4_q) ? 2'd0 :
                                       in_row(y, hy_q[1], ign3_q, ign4_q) ? 2'd1 : 2'd2);
    end
  end

  always_ff @(posedge clk_i) begin
    s1_slot_q <= s1_slot_d;
    s1_tr_q   <= pix_traced_i;
    s1_last_q <= pix_last_i;
    if (start_i) begin
      lg_q   <= tile_log2_i;
      ign3_q <= tile_log2_i != 3'd3;
      ign4_q <= tile_log2_i == 3'd5;
    end
  end

  /* verilator lint_off SYNCASYNCNET */
  // Every pixel belongs to one of the three open rows (and none comes before they are set).
  for (genvar i = 0; i < NUM_IN; i++) begin : g_chk
    `MSR_ASSERT_IMP(a_row_open, pix_fire_i[i] && act_q,
                (tile_row(pix_y_i[i], lg_q) == hrow_q[0] ||
                 tile_row(pix_y_i[i], lg_q) == hrow_q[1] ||
                 tile_row(pix_y_i[i], lg_q) == hrow_q[2]),
                clk_i, !rst_ni || clear_i)
    for (genvar k = 0; k < 2; k++) begin : g_exact
      `MSR_ASSERT_IMP(a_slot_exact, pix_fire_i[i] && act_q && set_q == '0,
                  in_row(pix_y_i[i][COORD_W-1:3], hy_q[k], ign3_q, ign4_q) ==
                  (tile_row(pix_y_i[i], lg_q) == hrow_q[k]), clk_i, !rst_ni || clear_i)
    end
    `MSR_ASSERT_IMP(a_rows_set, pix_fire_i[i] && act_q, set_q == '0, clk_i, !rst_ni || clear_i)
  end
  `MSR_ASSERT_IMP(a_restart_idle, take_q, inc_tr[tslot_q] == '0 && inc_la[tslot_q] == '0,
              clk_i, !rst_ni || clear_i)
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_budget_rows
