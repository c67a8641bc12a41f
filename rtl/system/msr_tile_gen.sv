// Tile generation unit (spec section 1, claims 1, 3 and 12): walks the tiles of a frame
// row-major from the top-left, computes each tile's extent and foveated per-level
// thresholds, and hands the descriptor to the first engine that can take it.
//
// Timing: one cycle computes a descriptor into a register (the 8x10 multiplier of the
// foveation term stays off the engines' input paths), the next offers it; a tile costs at
// least two cycles, far below an engine's time per tile.
module msr_tile_gen import msr_pkg::*; #(
  parameter int unsigned NUM_ENGINES = 4
) (
  input  logic                   clk_i,         // clock
  input  logic                   rst_ni,        // asynchronous reset, active low
  input  logic                   clear_i,       // synchronous clear: forget the frame
  input  logic                   start_i,       // pulse: begin a frame with the cfg below
  // Frame configuration, checked by the caller and stable from start_i to done_o.
  input  dim_t                   width_i,       // W, 1..4096
  input  dim_t                   height_i,      // H, 1..4096
  input  tile_size_e             tile_i,        // T
  input  level_t                 levels_i,      // L, 1..3
  input  metric_e                metric_i,      // colour difference metric
  input  thr_t [MAX_LEVELS-1:0]  thr_i,         // base thresholds, thr_i[k-1] for level k
  input  logic [7:0]             fov_gain_i,    // foveation gain, 0 = uniform
  // Descriptor to the engines: valid goes to exactly one engine that is ready.
  output logic [NUM_ENGINES-1:0] desc_valid_o,  // offer to engine i
  input  logic [NUM_ENGINES-1:0] desc_ready_i,  // engine i can take a tile
  output tile_desc_t             desc_o,        // the tile (shared by all engines)
  output logic                   busy_o,        // tiles left to hand out
  output logic                   done_o         // every tile of the frame handed out
);
  if (NUM_ENGINES < 1 || NUM_ENGINES > 16) begin : gen_bad_engines
    $fatal(1, "msr_tile_gen: NUM_ENGINES must be 1..16, got %0d", NUM_ENGINES);
  end

  typedef enum logic [1:0] {
    TG_IDLE  = 2'd0,   // no frame
    TG_CALC  = 2'd1,   // compute the descriptor of tile (tx, ty)
    TG_OFFER = 2'd2,   // offer it until an engine takes it
    TG_DONE  = 2'd3    // every tile handed out
  } tg_state_e;

  localparam int unsigned TIDX_W = COORD_W - 2;     // tile index, up to 4096/8 = 512 tiles
  localparam int unsigned R2_W   = TIDX_W + 1;      // |2t - (n-1)| < 1024

  tg_state_e             state_q, state_d;
  logic [TIDX_W-1:0]     tx_q, tx_d, ty_q, ty_d;    // tile indices
  logic [TIDX_W:0]       ntx_q, ntx_d, nty_q, nty_d;  // tile counts, 1..512
  tile_desc_t            desc_q, desc_d;

  // ---- Tile size and counts ----------------------------------------------------------------
  logic [2:0]   tile_log2;
  logic [LDIM_W-1:0] tile_edge;
  always_comb begin
    unique case (tile_i)
      TILE_8:  tile_log2 = 3'd3;
      TILE_16: tile_log2 = 3'd4;
      TILE_32: tile_log2 = 3'd5;
      default: tile_log2 = 3'd4;
    endcase
    tile_edge = LDIM_W'(1) << tile_log2;
  end

  // ceil(n / T) for n = 1..4096: at most 512 tiles per axis.
  function automatic logic [TIDX_W:0] tile_count(dim_t n, logic [2:0] lg);
    logic [DIM_W:0] sum;
    sum = {1'b0, n} + ((DIM_W+1)'(1) << lg) - (DIM_W+1)'(1);
    return (TIDX_W+1)'(sum >> lg);
  endfunction

  // r2 = |2t - (n-1)|: distance of tile t from the frame centre in half-tiles.
  function automatic logic [R2_W-1:0] half_dist(logic [TIDX_W-1:0] t, logic [TIDX_W:0] n);
    logic signed [R2_W+1:0] v;
    v = $signed({2'b0, t, 1'b0}) - $signed({2'b0, n}) + (R2_W+2)'(1);
    return (v < 0) ? R2_W'(-v) : R2_W'(v);
  endfunction

  // ---- Descriptor of tile (tx_q, ty_q) -------------------------------------------------------
  logic [R2_W-1:0]       r2, r2x, r2y;
  logic [R2_W+7:0]       fov_prod;                   // gain * r2 < 2^18
  logic [R2_W+3:0]       fov_add;                    // (gain * r2) >> 4
  coord_t                x0, y0;
  dim_t                  rest_w, rest_h;

  always_comb begin
    r2x      = half_dist(tx_q, ntx_q);
    r2y      = half_dist(ty_q, nty_q);
    r2       = (r2x > r2y) ? r2x : r2y;
    fov_prod = (R2_W+8)'(fov_gain_i) * (R2_W+8)'(r2);
    fov_add  = (R2_W+4)'(fov_prod >> 4);
    x0       = coord_t'(tx_q) << tile_log2;
    y0       = coord_t'(ty_q) << tile_log2;
    rest_w   = width_i  - dim_t'(x0);
    rest_h   = height_i - dim_t'(y0);

    desc_d        = desc_q;
    desc_d.x0     = x0;
    desc_d.y0     = y0;
    desc_d.w      = (rest_w > dim_t'(tile_edge)) ? tile_edge : ldim_t'(rest_w);
    desc_d.h      = (rest_h > dim_t'(tile_edge)) ? tile_edge : ldim_t'(rest_h);
    desc_d.levels = levels_i;
    desc_d.metric = metric_i;
    for (int k = 0; k < MAX_LEVELS; k++) begin
      logic [R2_W+4:0] t;
      t = (R2_W+5)'(thr_i[k]) + (R2_W+5)'(fov_add);
      desc_d.thr[k] = (t > (R2_W+5)'(255)) ? thr_t'(255) : thr_t'(t);
    end
  end

  // ---- Dispatch: the lowest-numbered ready engine takes the offered tile --------------------
  logic [NUM_ENGINES-1:0] pick;
  logic                   taken;
  always_comb begin
    pick = '0;
    for (int i = NUM_ENGINES - 1; i >= 0; i--) begin
      if (desc_ready_i[i]) pick = '0 | (NUM_ENGINES'(1) << i);
    end
    desc_valid_o = (state_q == TG_OFFER) ? pick : '0;
    taken        = |desc_valid_o;   // the picked engine is ready: transfer this cycle
  end

  assign desc_o = desc_q;
  assign busy_o = (state_q == TG_CALC) || (state_q == TG_OFFER);
  assign done_o = (state_q == TG_DONE);

  // ---- Walk ----------------------------------------------------------------------------------
  always_comb begin
    state_d = state_q;
    tx_d    = tx_q;
    ty_d    = ty_q;
    ntx_d   = ntx_q;
    nty_d   = nty_q;
    unique case (state_q)
      TG_IDLE, TG_DONE: begin
        if (start_i) begin
          tx_d    = '0;
          ty_d    = '0;
          ntx_d   = tile_count(width_i, tile_log2);
          nty_d   = tile_count(height_i, tile_log2);
          state_d = TG_CALC;
        end
      end
      TG_CALC: state_d = TG_OFFER;
      TG_OFFER: begin
        if (taken) begin
          state_d = TG_CALC;
          if ({1'b0, tx_q} + 1'b1 == ntx_q) begin
            tx_d = '0;
            ty_d = ty_q + 1'b1;
            if ({1'b0, ty_q} + 1'b1 == nty_q) state_d = TG_DONE;
          end else begin
            tx_d = tx_q + 1'b1;
          end
        end
      end
      default: state_d = TG_IDLE;
    endcase
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      state_q <= TG_IDLE;
      tx_q    <= '0;
      ty_q    <= '0;
      ntx_q   <= '0;
      nty_q   <= '0;
      desc_q  <= '0;
    end else if (clear_i) begin
      state_q <= TG_IDLE;
      tx_q    <= '0;
      ty_q    <= '0;
      ntx_q   <= '0;
      nty_q   <= '0;
      desc_q  <= '0;
    end else begin
      state_q <= state_d;
      tx_q    <= tx_d;
      ty_q    <= ty_d;
      ntx_q   <= ntx_d;
      nty_q   <= nty_d;
      if (state_q == TG_CALC) desc_q <= desc_d;
    end
  end

`ifndef SYNTHESIS
  // Lint: disable iff (!rst_ni) looks like a synchronous use of the asynchronous reset.
  /* verilator lint_off SYNCASYNCNET */
  // At most one engine is offered a tile, and only one that is ready.
  assert property (@(posedge clk_i) disable iff (!rst_ni) $onehot0(desc_valid_o));
  assert property (@(posedge clk_i) disable iff (!rst_ni) (desc_valid_o & ~desc_ready_i) == '0);
`endif
endmodule
