// Frame-buffer writer, row buffers: per input a ring of NBUF = 3 row buffers that collect the
// input's pixels and codes, lane by lane, for the W side to read a whole bus beat per clock.
//
// Each input's stream is row-contiguous by itself; a row ends at the tile's right edge or the
// frame's (x mod T == T-1 or x == W-1): the writer's input slice tests that and hands the bit
// in with the pixel (pix_row_end_i), so the flags here see no comparator. The lane of a pixel
// in its bus beat depends only on the low bits of its row address, and those follow from y's
// low bits (x0 is a multiple of 8, so 4*x0 is a multiple of the 32-byte beat):
//   pixel word w = ow + l, ow = (FB_BASE/4 + y*FB_STRIDE/4) mod WPB, l = x mod T,
// so every pixel is written straight into lane (w mod WPB), beat (w / WPB) of its row buffer:
// one memory per lane, one lane written per clock, a whole beat read per clock, and no
// rotation network on the read side. Source codes are gathered four to a 32-bit word (the
// source plane starts on a 32-bit lane too) and written one word per four pixels. Codes keep
// their low CODE_W bits (the codes of algorithm.md section 4 are 0..19).
//
// A pixel is taken into a write stage (W1 of the memories), then its lane enables, address and
// data are registered (stage 2) and written. A complete row's buffer is `full` until the W
// side has read its last beat (free_*_i); it is offered to the address side (row_ready_o)
// until taken (take_i), and `picked` from then on.
`include "msr_assert.svh"
`include "msr_flops.svh"

module msr_fbw_rowbuf import msr_pkg::*; import msr_fbw_pkg::*; #(
  parameter int unsigned NUM_IN     = 4,     // pixel streams (engines)
  parameter int unsigned AXI_DATA_W = 256,   // AXI data width: 32, 64, 128 or 256
  localparam int unsigned WPB       = AXI_DATA_W / 32,           // 32-bit lanes per beat
  localparam int unsigned IN_W      = (NUM_IN > 1) ? $clog2(NUM_IN) : 1,
  localparam int unsigned MA_W      = $clog2(NBUF * pix_beats(WPB))   // pixel buffer address
) (
  input  logic              clk_i,           // clock
  input  logic              rst_ni,          // asynchronous reset, active low
  input  logic              clear_i,         // synchronous clear
  // Frame configuration, stable during a frame.
  input  tile_size_e        tile_i,          // T
  input  fb_cfg_t           fb_i,            // frame-buffer settings (bases and strides)
  // Pixel streams in.
  input  logic      [NUM_IN-1:0] pix_valid_i,  // a finished pixel
  output logic      [NUM_IN-1:0] pix_ready_o,  // room for it
  input  pix_word_t [NUM_IN-1:0] pix_i,        // the pixel
  input  logic      [NUM_IN-1:0] pix_row_end_i,  // it ends its row (x mod T == T-1 or x == W-1)
  output logic      [NUM_IN-1:0] tile_done_o,  // pulse: the last pixel of a tile taken
  // Complete rows to the address side.
  output logic      [NUM_IN-1:0] row_ready_o,  // the input's next row is complete (registered)
  output buf_t      [NUM_IN-1:0] pick_o,       // per input: the buffer of that row
  input  logic      [NUM_IN-1:0] take_i,       // that row is taken (one-hot)
  input  logic [IN_W-1:0]   meta_in_i,       // metadata read port: input
  input  buf_t              meta_buf_i,      // and buffer
  output row_meta_t         meta_o,          // the row there: y, x0, pixels - 1
  // Beat reads and buffer release from the W side.
  input  logic [NUM_IN-1:0][MA_W-1:0] raddr_i,  // per input: the beat read
  input  logic [IN_W-1:0]   rd_in_i,         // the input whose beat is returned
  output logic [WPB-1:0][23:0]         rd_pix_o,   // its pixel lanes
  output logic [WPB-1:0][4*CODE_W-1:0] rd_code_o,  // its code lanes (four codes a lane)
  input  logic              free_valid_i,    // a buffer's last beat was read:
  input  logic [IN_W-1:0]   free_in_i,       //   its input
  input  buf_t              free_buf_i,      //   and buffer
  // Status.
  output logic              idle_o           // no row held, no pixel on its way in
);
  localparam int unsigned LANE_W  = (WPB > 1) ? $clog2(WPB) : 1;
  localparam int unsigned LANE_SH = (WPB > 1) ? $clog2(WPB) : 0;
  localparam int unsigned PB      = pix_beats(WPB);                  // pixel beats per row, max
  localparam int unsigned SB      = code_beats(WPB);                 // code beats per row, max
  localparam int unsigned PDEPTH  = NBUF * PB;
  localparam int unsigned SDEPTH  = NBUF * SB;
  localparam int unsigned SA_W    = $clog2(SDEPTH);                  // code buffer address

  typedef logic [IN_W-1:0] in_t;
  typedef logic [MA_W-1:0] maddr_t;

  // (y * s) mod 2^LANE_W without a multiplier (a few gates: LANE_W <= 3).
  function automatic logic [LANE_W-1:0] mul_lane(coord_t y, logic [LANE_W-1:0] s);
    logic [LANE_W-1:0] r;
    r = '0;
    for (int unsigned j = 0; j < LANE_W; j++) begin
      if (y[j]) r = r + (s << j);
    end
    return r;
  endfunction

  lcoord_t tmask;      // T - 1
  assign tmask = tile_mask(tile_i);

  // Lane offsets of a row's first pixel word / first code word in its first beat.
  logic [LANE_W-1:0] lane_mask;
  assign lane_mask = LANE_W'(WPB - 1);

  // ---- Row buffer state: per input a ring of NBUF buffers ----------------------------------
  // full: the row is complete (until its last beat is read); picked: its bursts are addressed.
  logic [NUM_IN-1:0][NBUF-1:0] full_q, picked_q;
  buf_t [NUM_IN-1:0]           col_q;     // the buffer that collects
  buf_t [NUM_IN-1:0]           pick_q;    // the buffer the address side takes next
  coord_t [NUM_IN-1:0][NBUF-1:0] meta_y_q, meta_x0_q;
  lcoord_t [NUM_IN-1:0][NBUF-1:0] meta_l_q;   // pixels of the row - 1

  logic [NUM_IN-1:0] pix_hs, row_end, row_ready, row_ready_q;
  logic [NUM_IN-1:0][LCOORD_W-1:0] lpos;

  // Write stage: the pixel taken last clock goes into the memories.
  logic   [NUM_IN-1:0]               wr_v_q, wr_end_q;
  buf_t   [NUM_IN-1:0]               wr_buf_q;
  logic   [NUM_IN-1:0][LCOORD_W-1:0] wr_l_q;
  coord_t [NUM_IN-1:0]               wr_y_q, wr_x0_q;
  rgb_t   [NUM_IN-1:0]               wr_rgb_q;
  logic   [NUM_IN-1:0][CODE_W-1:0]   wr_code_q;
  logic   [NUM_IN-1:0][2:0][CODE_W-1:0] asm_q;   // codes 0..2 of the current word

  // Per input and lane the read data.
  logic [NUM_IN-1:0][WPB-1:0][23:0]         prd;
  logic [NUM_IN-1:0][WPB-1:0][4*CODE_W-1:0] srd;
  logic [NUM_IN-1:0] wr2_busy;       // a memory write is pending in stage 2

  for (genvar i = 0; i < NUM_IN; i++) begin : g_in
    logic [NBUF-1:0] full_d, picked_d;
    buf_t            col_d, pick_d;

    assign lpos[i]        = pix_i[i].x[LCOORD_W-1:0] & tmask;
    assign row_end[i]     = pix_row_end_i[i];
    assign pix_ready_o[i] = !full_q[i][col_q[i]];
    assign pix_hs[i]      = pix_valid_i[i] && pix_ready_o[i];
    assign tile_done_o[i] = pix_hs[i] && pix_i[i].last;
    assign row_ready[i]   = full_q[i][pick_q[i]] && !picked_q[i][pick_q[i]];

    always_comb begin
      full_d   = full_q[i];
      picked_d = picked_q[i];
      col_d    = col_q[i];
      pick_d   = pick_q[i];
      if (pix_hs[i] && row_end[i]) begin
        full_d[col_q[i]] = 1'b1;
        col_d            = buf_next(col_q[i]);
      end
      if (take_i[i]) begin
        picked_d[pick_q[i]] = 1'b1;
        pick_d              = buf_next(pick_q[i]);
      end
      if (free_valid_i && free_in_i == in_t'(i)) begin
        full_d[free_buf_i]   = 1'b0;
        picked_d[free_buf_i] = 1'b0;
      end
    end

    // The address side sees a registered "row ready": a ready row stays ready until it is
    // taken (its flags change only by the take), so last clock's flag minus this clock's take
    // is never ready early; a new row shows a clock later. That cut the buffer-flag muxes off
    // the arbiter's carry chain and the pick that follows it.
    `MSR_CLR_REG(u_state, 2 * NBUF + 2 * BUF_W + 2, clear_i, 1'b1,
                 {full_d, picked_d, col_d, pick_d, pix_hs[i], row_ready[i] && !take_i[i]},
                 {full_q[i], picked_q[i], col_q[i], pick_q[i], wr_v_q[i], row_ready_q[i]})

    // Data registers: written on a handshake only, read only under their valid / full flag.
    always_ff @(posedge clk_i) begin
      if (pix_hs[i]) begin
        wr_buf_q[i]  <= col_q[i];
        wr_l_q[i]    <= lpos[i];
        wr_y_q[i]    <= pix_i[i].y;
        wr_x0_q[i]   <= pix_i[i].x & ~coord_t'(tmask);
        wr_rgb_q[i]  <= pix_i[i].rgb;
        wr_code_q[i] <= pix_i[i].src[CODE_W-1:0];
        wr_end_q[i]  <= row_end[i];
      end
      if (pix_hs[i] && row_end[i]) begin
        meta_y_q[i][col_q[i]]  <= pix_i[i].y;
        meta_x0_q[i][col_q[i]] <= pix_i[i].x & ~coord_t'(tmask);
        meta_l_q[i][col_q[i]]  <= lpos[i];
      end
    end

    // Where the registered pixel and its code go (stage 1), registered into stage 2 (memory
    // write: lane enables, address and data straight from registers).
    logic [LANE_W-1:0]   ow, sow;
    logic [LCOORD_W:0]   pw;          // pixel word of the row from the beat start
    logic [LCOORD_W-2:0] sw;          // code word of the row from the beat start
    // Beat of the pixel / code word in its row; the upper bits are 0 when the bus is wide.
    /* verilator lint_off UNUSEDSIGNAL */
    logic [LCOORD_W:0]   pbeat;
    logic [LCOORD_W-2:0] sbeat;
    /* verilator lint_on UNUSEDSIGNAL */
    logic [1:0]          slot;
    maddr_t              paddr;
    logic [SA_W-1:0]     saddr;
    logic                sword_we;
    logic [4*CODE_W-1:0] sword;
    logic [WPB-1:0]      pwe_q, swe_q;      // stage 2: lane write enables
    logic [WPB-1:0]      pwe_d, swe_d;
    maddr_t              paddr_q;
    logic [SA_W-1:0]     saddr_q;
    rgb_t                prgb_q;
    logic [4*CODE_W-1:0] sword_q;

    always_comb begin
      ow    = (LANE_W'(fb_i.fb_base >> 2) + mul_lane(wr_y_q[i], LANE_W'(fb_i.fb_stride >> 2)))
              & lane_mask;
      sow   = (LANE_W'(fb_i.src_base >> 2) + mul_lane(wr_y_q[i], LANE_W'(fb_i.src_stride >> 2)) +
               LANE_W'(wr_x0_q[i] >> 2)) & lane_mask;
      pw    = (LCOORD_W+1)'(ow) + (LCOORD_W+1)'(wr_l_q[i]);
      sw    = (LCOORD_W-1)'(sow) + (LCOORD_W-1)'(wr_l_q[i] >> 2);
      slot  = wr_l_q[i][1:0];
      pbeat = pw >> LANE_SH;
      sbeat = sw >> LANE_SH;
      paddr = maddr_t'(buf_base(wr_buf_q[i], PB)) + maddr_t'(pbeat);
      saddr = SA_W'(buf_base(wr_buf_q[i], SB)) + SA_W'(sbeat);
      sword_we = wr_v_q[i] && (slot == 2'd3 || wr_end_q[i]);
      sword = {wr_code_q[i], asm_q[i][2], asm_q[i][1], asm_q[i][0]};
      for (int unsigned s = 0; s < 3; s++) begin
        if (32'(slot) == s) sword[CODE_W*s +: CODE_W] = wr_code_q[i];
      end
    end

    for (genvar j = 0; j < WPB; j++) begin : g_we
      assign pwe_d[j] = wr_v_q[i] && (32'(pw) % WPB == j);
      assign swe_d[j] = sword_we && (32'(sw) % WPB == j);
    end
    `MSR_CLR_REG(u_we, 2 * WPB, clear_i, 1'b1, {pwe_d, swe_d}, {pwe_q, swe_q})

    always_ff @(posedge clk_i) begin
      if (wr_v_q[i] && slot != 2'd3) asm_q[i][slot] <= wr_code_q[i];
      paddr_q <= paddr;
      saddr_q <= saddr;
      prgb_q  <= wr_rgb_q[i];
      sword_q <= sword;
    end
    assign wr2_busy[i] = (pwe_q != '0) || (swe_q != '0);

    for (genvar j = 0; j < WPB; j++) begin : g_lane
      logic [23:0]         pmem_q [PDEPTH];
      logic [4*CODE_W-1:0] smem_q [SDEPTH];
      always_ff @(posedge clk_i) begin
        if (pwe_q[j]) pmem_q[paddr_q] <= prgb_q;
        if (swe_q[j]) smem_q[saddr_q] <= sword_q;
      end
      assign prd[i][j] = pmem_q[raddr_i[i]];
      assign srd[i][j] = smem_q[raddr_i[i][SA_W-1:0]];
    end
  end

  assign row_ready_o = row_ready_q;
  assign pick_o      = pick_q;
  assign meta_o      = '{y: meta_y_q[meta_in_i][meta_buf_i], x0: meta_x0_q[meta_in_i][meta_buf_i],
                         l: meta_l_q[meta_in_i][meta_buf_i]};
  assign rd_pix_o    = prd[rd_in_i];
  assign rd_code_o   = srd[rd_in_i];
  assign idle_o      = (full_q == '0) && (wr_v_q == '0) && (wr2_busy == '0);

  // Codes keep CODE_W bits in the buffers; the upper bits of every code are 0.
  logic [NUM_IN-1:0] code_big;
  for (genvar i = 0; i < NUM_IN; i++) begin : g_code_big
    assign code_big[i] = pix_hs[i] && (pix_i[i].src[SRC_W-1:CODE_W] != '0);
  end

  // The code plane's lanes are written whether or not the plane goes out (src_en).
  logic unused;
  assign unused = fb_i.src_en;

  /* verilator lint_off SYNCASYNCNET */
  `MSR_ASSERT(a_code_fits, code_big == '0)
  `MSR_ASSERT(a_row_ready_late, (row_ready_q & ~row_ready) == '0)
  `MSR_ASSERT(a_take_ready, (take_i & ~row_ready_q) == '0)
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_fbw_rowbuf
