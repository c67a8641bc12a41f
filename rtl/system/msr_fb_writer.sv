// Frame-buffer writer: an AXI4 write master that stores the engines' finished pixels.
//
// Inputs: NUM_IN pixel streams, one per engine, taken in parallel (one pixel per stream per
// clock). Each stream is row-contiguous by itself (an engine emits whole tiles row-major); a
// row ends at the tile's right edge or the frame's, which this unit derives from x.
// Output per row: the 32-bit pixels 0x00RRGGBB at FB_BASE + y*FB_STRIDE + 4*x0 and, when the
// source map is enabled, the 8-bit codes at SRC_BASE + y*SRC_STRIDE + x0, each as INCR bursts
// of AXI_DATA_W-bit beats from the bus-aligned address below the row's start, with byte
// strobes on the partial first / last beats. A burst that would cross 4 KiB is split there.
//
// Buffering (why it is small): per input NBUF = 3 row buffers in a ring, held in small
// memories (LUT RAM on an FPGA, a register file on an ASIC), not flip-flops. The lane of a
// pixel in its bus beat depends only on the low bits of its row address, and those follow
// from y's low bits (x0 is a multiple of 8, so 4*x0 is a multiple of the 32-byte beat):
//   pixel word w = ow + l, ow = (FB_BASE/4 + y*FB_STRIDE/4) mod WPB, l = x mod T,
// so every pixel is written straight into lane (w mod WPB), beat (w / WPB) of its row buffer:
// one memory per lane, one lane written per clock, a whole beat read per clock, and no
// rotation network on the read side. Source codes are gathered four to a 32-bit word (the
// source plane starts on a 32-bit lane too) and written one word per four pixels. Codes keep
// their low 5 bits in the buffer (the codes of algorithm.md section 4 are 0..19).
//
// Address side, a pipeline with one row per clock: pick (round robin over the inputs with a
// complete row, msr_rr_arb; registered) -> the row's y, x0 and length -> the row address of
// each plane, base + y*stride + x0 term, with y*stride a radix-8 sum of stride multiples (no
// multiplier: 3x, 5x and 7x are registers), the six addends compressed to a carry-save pair
// and added in 12/10/10-bit segments over three clocks -> the row's bursts (up to two per
// plane: a 4 KiB split) into a short list, issued from registers one per clock. The W side
// registers the next beat's buffer address, strobes and WLAST (W1), then reads the buffer
// into the W output register (W2); a row's buffer is free once W2 reads its last beat. Three
// buffers per input hide the pipeline's latency (about 14 clocks from a row's last pixel to
// its buffer being free) at the smallest tile (a row of 8 pixels every 8 clocks per input).
//
// Throughput: a 16-pixel row with its codes takes 2 + 1 beats of 256 bits when the frame
// buffer is 32-byte aligned, so four engines at one pixel per clock each fit with room (5.3
// pixels per clock); 128 bits would cap the writer at 3.2 pixels per clock.
`include "msr_assert.svh"

module msr_fb_writer import msr_pkg::*; #(
  parameter int unsigned NUM_IN     = 4,     // pixel streams (engines)
  parameter int unsigned AXI_DATA_W = 256,   // AXI data width: 32, 64, 128 or 256
  parameter int unsigned ID_W       = 4,     // AXI ID width (a single ID is used: in-order B)
  parameter int unsigned MAX_OUT    = 8,     // outstanding write bursts
  localparam int unsigned STRB_W    = AXI_DATA_W / 8
) (
  input  logic              clk_i,           // clock
  input  logic              rst_ni,          // asynchronous reset, active low
  input  logic              clear_i,         // synchronous clear (only when idle_o or abandoned)
  // Frame configuration, stable during a frame.
  input  dim_t              width_i,         // W (stable a clock before a pixel comes)
  input  tile_size_e        tile_i,          // T
  input  logic [31:0]       fb_base_i,       // frame-buffer byte address of pixel (0, 0)
  input  logic [31:0]       fb_stride_i,     // frame-buffer bytes per row
  input  logic              src_en_i,        // also write the source-code plane
  input  logic [31:0]       src_base_i,      // source-plane byte address of pixel (0, 0)
  input  logic [31:0]       src_stride_i,    // source-plane bytes per row
  // Pixel streams in.
  input  logic   [NUM_IN-1:0] pix_valid_i,   // a finished pixel
  output logic   [NUM_IN-1:0] pix_ready_o,   // room for it
  input  coord_t [NUM_IN-1:0] pix_x_i,       // global x
  input  coord_t [NUM_IN-1:0] pix_y_i,       // global y
  input  rgb_t   [NUM_IN-1:0] pix_rgb_i,     // colour
  input  src_t   [NUM_IN-1:0] pix_src_i,     // source code
  input  logic   [NUM_IN-1:0] pix_last_i,    // last pixel of its tile
  // AXI4 write master (no read channels).
  output logic [ID_W-1:0]       m_axi_awid,
  output logic [31:0]           m_axi_awaddr,
  output logic [7:0]            m_axi_awlen,
  output logic [2:0]            m_axi_awsize,
  output logic [1:0]            m_axi_awburst,
  output logic                  m_axi_awlock,
  output logic [3:0]            m_axi_awcache,
  output logic [2:0]            m_axi_awprot,
  output logic                  m_axi_awvalid,
  input  logic                  m_axi_awready,
  output logic [AXI_DATA_W-1:0] m_axi_wdata,
  output logic [STRB_W-1:0]     m_axi_wstrb,
  output logic                  m_axi_wlast,
  output logic                  m_axi_wvalid,
  input  logic                  m_axi_wready,
  input  logic [ID_W-1:0]       m_axi_bid,
  input  logic [1:0]            m_axi_bresp,
  input  logic                  m_axi_bvalid,
  output logic                  m_axi_bready,
  // Status.
  output logic              idle_o,          // no complete row waiting, no burst open/outstanding
  output logic [NUM_IN-1:0] tile_done_o,     // pulse per input: the last pixel of a tile taken
  output logic              bresp_err_o,     // pulse: a write response was SLVERR or DECERR
  output logic [31:0]       bresp_addr_o,    // with bresp_err_o: the address of that burst
  output logic              b_unexpected_o   // pulse: a write response with no burst outstanding
);
  localparam int unsigned WPB     = AXI_DATA_W / 32;                 // 32-bit lanes per beat
  localparam int unsigned LANE_W  = (WPB > 1) ? $clog2(WPB) : 1;
  localparam int unsigned BB_W    = $clog2(STRB_W);                  // byte offset in a beat
  localparam int unsigned NBUF    = 3;                               // row buffers per input
  localparam int unsigned BUF_W   = 2;
  localparam int unsigned SWORDS  = MAX_TILE / 4;                    // code words of a row
  localparam int unsigned PB      = (MAX_TILE + 2 * WPB - 2) / WPB;  // pixel beats per row, max
  localparam int unsigned SB      = (SWORDS + 2 * WPB - 2) / WPB;    // code beats per row, max
  localparam int unsigned PDEPTH  = NBUF * PB;
  localparam int unsigned SDEPTH  = NBUF * SB;
  localparam int unsigned MA_W    = $clog2(PDEPTH);                  // pixel buffer address
  localparam int unsigned SA_W    = $clog2(SDEPTH);                  // code buffer address
  localparam int unsigned OUT_W   = $clog2(MAX_OUT + 1);
  localparam int unsigned IN_W    = (NUM_IN > 1) ? $clog2(NUM_IN) : 1;
  localparam int unsigned CODE_W  = 5;                               // code bits kept
  localparam int unsigned AQ_D    = (MAX_OUT < 2) ? 2 : (1 << $clog2(MAX_OUT));
  localparam int unsigned B4K_W   = 12 - BB_W;                       // beat index in a 4 KiB page

  if (AXI_DATA_W != 32 && AXI_DATA_W != 64 && AXI_DATA_W != 128 && AXI_DATA_W != 256)
  begin : g_check_width
    $fatal(1, "msr_fb_writer: AXI_DATA_W must be 32, 64, 128 or 256, got %0d", AXI_DATA_W);
  end
  if (MAX_OUT < 1 || MAX_OUT > 255) begin : g_check_out
    $fatal(1, "msr_fb_writer: MAX_OUT must be 1..255, got %0d", MAX_OUT);
  end
  if (NUM_IN < 1 || NUM_IN > 16) begin : g_check_in
    $fatal(1, "msr_fb_writer: NUM_IN must be 1..16, got %0d", NUM_IN);
  end

  typedef logic [IN_W-1:0]  in_t;
  typedef logic [BUF_W-1:0] buf_t;
  typedef logic [MA_W-1:0]  maddr_t;

  function automatic buf_t buf_next(buf_t b);
    return (b == buf_t'(NBUF - 1)) ? '0 : b + 1'b1;
  endfunction

  localparam int unsigned LANE_SH = (WPB > 1) ? $clog2(WPB) : 0;

  // (y * s) mod 2^LANE_W without a multiplier (a few gates: LANE_W <= 3).
  function automatic logic [LANE_W-1:0] mul_lane(coord_t y, logic [LANE_W-1:0] s);
    logic [LANE_W-1:0] r;
    r = '0;
    for (int unsigned j = 0; j < LANE_W; j++) begin
      if (y[j]) r = r + (s << j);
    end
    return r;
  endfunction
  // First beat of buffer b (0..2) in a memory of n beats per buffer: b * n, for the pixel
  // memory (n = PB) and the code memory (n = SB); n is a constant, so this is a 3-way mux.
  function automatic maddr_t buf_base(logic [1:0] b, int unsigned n);
    unique case (b)
      2'd1:    return maddr_t'(n);
      2'd2:    return maddr_t'(2 * n);
      default: return '0;
    endcase
  endfunction

  logic [LCOORD_W-1:0] tmask;      // T - 1
  always_comb begin
    unique case (tile_i)
      TILE_8:  tmask = LCOORD_W'(7);
      TILE_16: tmask = LCOORD_W'(15);
      TILE_32: tmask = LCOORD_W'(31);
      default: tmask = LCOORD_W'(15);
    endcase
  end

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

  // Row free (from the W side): input, buffer.
  // Registered: the buffers' flags sit with their inputs, spread over the die, and the W side
  // is in one place; a buffer is free a clock after its last beat is read.
  logic row_free_q;
  in_t  row_free_in_q;
  buf_t row_free_buf_q;
  // Row picked (address side).
  logic arb_valid, arb_ready, arb_take;
  in_t  arb_idx;
  logic [NUM_IN-1:0] arb_gnt;

  // Read side, shared by the inputs: beat address; per input and lane the read data.
  maddr_t [NUM_IN-1:0] raddr_q;     // per input: only that input's memories hang on its copy
  logic [NUM_IN-1:0][WPB-1:0][23:0]         prd;
  logic [NUM_IN-1:0][WPB-1:0][4*CODE_W-1:0] srd;
  logic [NUM_IN-1:0] wr2_busy;       // a memory write is pending in stage 2

  // The frame's last column, registered: the row-end test is an equality on the incoming x,
  // with no adder between the input slice and the buffer flags (width_i is the frame's
  // configuration: it settles long before the frame's first pixel, a_width_stable).
  dim_t last_x_q;
  always_ff @(posedge clk_i) last_x_q <= width_i - 1'b1;

  for (genvar i = 0; i < NUM_IN; i++) begin : g_in
    assign lpos[i]        = pix_x_i[i][LCOORD_W-1:0] & tmask;
    assign row_end[i]     = (lpos[i] == tmask) || (dim_t'(pix_x_i[i]) == last_x_q);
    assign pix_ready_o[i] = !full_q[i][col_q[i]];
    assign pix_hs[i]      = pix_valid_i[i] && pix_ready_o[i];
    assign tile_done_o[i] = pix_hs[i] && pix_last_i[i];
    assign row_ready[i]   = full_q[i][pick_q[i]] && !picked_q[i][pick_q[i]];

    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        full_q[i]   <= '0;
        picked_q[i] <= '0;
        col_q[i]    <= '0;
        pick_q[i]   <= '0;
        wr_v_q[i]   <= 1'b0;
        row_ready_q[i] <= 1'b0;
      end else if (clear_i) begin
        full_q[i]   <= '0;
        picked_q[i] <= '0;
        col_q[i]    <= '0;
        pick_q[i]   <= '0;
        wr_v_q[i]   <= 1'b0;
        row_ready_q[i] <= 1'b0;
      end else begin
        wr_v_q[i] <= pix_hs[i];
        // The arbiter sees a registered "row ready": a ready row stays ready until it is taken
        // (its flags change only by the take), so last clock's flag minus this clock's take is
        // never ready early; a new row shows a clock later. That cut the buffer-flag muxes off
        // the arbiter's carry chain and the pick that follows it.
        row_ready_q[i] <= row_ready[i] && !(arb_take && arb_gnt[i]);
        if (pix_hs[i] && row_end[i]) begin
          full_q[i][col_q[i]] <= 1'b1;
          col_q[i]            <= buf_next(col_q[i]);
        end
        if (arb_take && arb_gnt[i]) begin
          picked_q[i][pick_q[i]] <= 1'b1;
          pick_q[i]              <= buf_next(pick_q[i]);
        end
        if (row_free_q && row_free_in_q == in_t'(i)) begin
          full_q[i][row_free_buf_q]   <= 1'b0;
          picked_q[i][row_free_buf_q] <= 1'b0;
        end
      end
    end

    // Data registers: written on a handshake only, read only under their valid / full flag.
    always_ff @(posedge clk_i) begin
      if (pix_hs[i]) begin
        wr_buf_q[i]  <= col_q[i];
        wr_l_q[i]    <= lpos[i];
        wr_y_q[i]    <= pix_y_i[i];
        wr_x0_q[i]   <= pix_x_i[i] & ~coord_t'(tmask);
        wr_rgb_q[i]  <= pix_rgb_i[i];
        wr_code_q[i] <= pix_src_i[i][CODE_W-1:0];
        wr_end_q[i]  <= row_end[i];
      end
      if (pix_hs[i] && row_end[i]) begin
        meta_y_q[i][col_q[i]]  <= pix_y_i[i];
        meta_x0_q[i][col_q[i]] <= pix_x_i[i] & ~coord_t'(tmask);
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
      ow    = (LANE_W'(fb_base_i >> 2) + mul_lane(wr_y_q[i], LANE_W'(fb_stride_i >> 2)))
              & lane_mask;
      sow   = (LANE_W'(src_base_i >> 2) + mul_lane(wr_y_q[i], LANE_W'(src_stride_i >> 2)) +
               LANE_W'(wr_x0_q[i] >> 2)) & lane_mask;
      pw    = (LCOORD_W+1)'(ow) + (LCOORD_W+1)'(wr_l_q[i]);
      sw    = (LCOORD_W-1)'(sow) + (LCOORD_W-1)'(wr_l_q[i] >> 2);
      slot  = wr_l_q[i][1:0];
      pbeat = pw >> LANE_SH;
      sbeat = sw >> LANE_SH;
      paddr = buf_base(wr_buf_q[i], PB) + maddr_t'(pbeat);
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
    msr_clr_reg #(.WIDTH(2 * WPB)) u_we (
      .clk_i,
      .rst_ni,
      .clear_i,
      .en_i    (1'b1),
      .d_i     ({pwe_d, swe_d}),
      .q_o     ({pwe_q, swe_q})
    );

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
      assign prd[i][j] = pmem_q[raddr_q[i]];
      assign srd[i][j] = smem_q[raddr_q[i][SA_W-1:0]];
    end
  end

  // ---- Address side --------------------------------------------------------------------------
  msr_rr_arb #(.N(NUM_IN), .LOCK(1'b0), .IDX_W(IN_W)) u_row_arb (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .clear_i (clear_i),
    .req_i   (row_ready_q),
    .gnt_o   (arb_gnt),
    .idx_o   (arb_idx),
    .valid_o (arb_valid),
    .ready_i (arb_ready)
  );
  assign arb_take = arb_valid && arb_ready;

  // Stride multiples 3s, 5s, 7s for y * stride (radix 8: y*s = sum_k digit_k(y) * s << 3k).
  // The strides are constant during a frame, so these adders are segmented with a registered
  // carry between 8-bit segments: the products settle four clocks after a stride changes
  // (the configuration is latched at START; the first row completes much later).
  localparam int unsigned NMUL = 6;   // fb 3s, 5s, 7s, src 3s, 5s, 7s
  logic [NMUL-1:0][31:0] mul_a, mul_b;
  logic [NMUL-1:0]       mul_ci;
  logic [NMUL-1:0][31:0] mul_q;
  logic [NMUL-1:0][4:0]  mul_c_q;     // carry into segment k (k = 1..3)

  always_comb begin
    for (int unsigned p = 0; p < 2; p++) begin
      logic [31:0] st;
      st = (p != 0) ? src_stride_i : fb_stride_i;
      mul_a[3*p]     = st;
      mul_b[3*p]     = st << 1;
      mul_ci[3*p]    = 1'b0;
      mul_a[3*p+1]   = st;
      mul_b[3*p+1]   = st << 2;
      mul_ci[3*p+1]  = 1'b0;
      mul_a[3*p+2]   = st << 3;       // 8s - s = 8s + ~s + 1
      mul_b[3*p+2]   = ~st;
      mul_ci[3*p+2]  = 1'b1;
    end
  end

  logic [NMUL-1:0][31:0] mul_d;
  logic [NMUL-1:0][4:0]  mul_c_d;
  for (genvar v = 0; v < NMUL; v++) begin : g_mul
    logic [3:0] co;
    msr_seg_add #(.WIDTH(32), .SEG_W(8)) u_add (
      .a_i (mul_a[v]),
      .b_i (mul_b[v]),
      .c_i ({mul_c_q[v][3:1], mul_ci[v]}),
      .s_o (mul_d[v]),
      .c_o (co)
    );
    assign mul_c_d[v] = {co, 1'b0};
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      mul_q   <= '0;
      mul_c_q <= '0;
    end else begin
      mul_q   <= mul_d;
      mul_c_q <= mul_c_d;
    end
  end

  function automatic logic [31:0] mult8(logic [2:0] d, logic [31:0] s, logic [31:0] s3,
                                        logic [31:0] s5, logic [31:0] s7);
    unique case (d)
      3'd0:    return '0;
      3'd1:    return s;
      3'd2:    return s << 1;
      3'd3:    return s3;
      3'd4:    return s << 2;
      3'd5:    return s5;
      3'd6:    return s3 << 1;
      default: return s7;
    endcase
  endfunction

  // Carry-save 3:2 compression of three addends.
  typedef struct packed {
    logic [31:0] s;
    logic [31:0] c;
  } cs_t;
  function automatic cs_t csa(logic [31:0] a, logic [31:0] b, logic [31:0] c);
    cs_t r;
    r.s = a ^ b ^ c;
    r.c = ((a & b) | (a & c) | (b & c)) << 1;
    return r;
  endfunction

  // Row address of plane p (0 pixels, 1 codes):
  //   S0 the arbiter's pick; S1 the picked row; S1m the four stride multiples; S1.5 / S2 six
  //   addends (the multiples, base, x0 term) compressed to a carry-save pair in three 3:2 levels; S3, S4, S5 the carry-propagate add in segments [11:0], [21:12], [31:22]
  //   with the carry registered between them; beside S4 / S5 the plane's burst shape from the
  //   low 12 bits (first-beat offset, beats, the 4 KiB split), with no add wider than 12 bits.
  typedef struct packed {
    logic             two;       // the plane crosses 4 KiB: two bursts
    logic [7:0]       len0;      // AWLEN of the first burst
    logic [7:0]       len1;      // AWLEN of the second
    logic [BB_W-1:0]  lo;        // first byte in the first beat
    logic [BB_W-1:0]  hi;        // last byte in the last beat
  } shape_t;

  logic   s0_v_q;                               // S0: the arbiter's pick, registered
  in_t    s0_in_q;
  buf_t   s0_buf_q;
  logic   s1_v_q, s1m_v_q, s15_v_q, s2_v_q, s3_v_q, s4_v_q, s5_v_q;
  in_t    s1m_in_q, s15_in_q;
  buf_t   s1m_buf_q, s15_buf_q;
  lcoord_t s1m_l_q, s15_l_q;
  coord_t s1m_x0_q;
  logic   [1:0][3:0][31:0] s1m_m_q, s1m_m_d;     // per plane: the four stride multiples
  cs_t    [1:0][1:0] s15_cs_q, s15_cs_d;         // per plane: two carry-save pairs
  logic   s5_take;
  in_t    s1_in_q, s2_in_q, s3_in_q, s4_in_q, s5_in_q;
  buf_t   s1_buf_q, s2_buf_q, s3_buf_q, s4_buf_q, s5_buf_q;
  lcoord_t s1_l_q, s2_l_q, s3_l_q;             // pixels of the row - 1
  coord_t s1_y_q, s1_x0_q;
  cs_t    [1:0] s2_cs_q, s3_cs_q, s4_cs_q;
  logic   [1:0][11:0] s3_lo_q, s4_lo_q;         // address bits [11:0]
  logic   [1:0][9:0]  s4_mid_q;                 // address bits [21:12]
  logic   [1:0]       s3_cy_q, s4_cy_q;
  logic   [1:0][8:0]  s4_em1_q;                 // first-beat offset + bytes - 1
  logic   [1:0][12:0] s4_pe_q;                  // address [11:0] + bytes - 1
  // S0..S4 never stall: a row enters S0 only with a place reserved for it in the S5 queue
  // (a credit), so the stage registers load every clock, without an enable. (A ready chain
  // back through the stages was an enable on some 600 flip-flops: its fan-out net alone was
  // 6.9 ns after placement.) S5 is a short FIFO; AWREADY's way back ends at its pop.
  typedef struct packed {
    in_t                    in;
    buf_t                   bufi;
    logic   [1:0][31:0]     a;                  // plane start address
    shape_t [1:0]           shape;
    logic   [1:0][MA_W-1:0] mb1;                // buffer beat of the second burst
  } s5_t;
  s5_t                s5_q, s5_d;
  logic   [1:0][31:0] s5_a_q;
  shape_t [1:0]       s5_shape_q;
  logic   [1:0][MA_W-1:0] s5_mb1_q;
  cs_t    [1:0]       s2_cs_d;
  logic   [1:0][11:0] s3_lo_d;
  logic   [1:0][9:0]  s4_mid_d;
  logic   [1:0]       s3_cy_d, s4_cy_d;
  logic   [1:0][8:0]  s4_em1_d;
  logic   [1:0][12:0] s4_pe_d;
  logic   [1:0][31:0] s5_a_d;
  shape_t [1:0]       s5_shape_d;
  logic   [1:0][MA_W-1:0] s5_mb1_d;
  // Beats before the 4 KiB boundary - 1; when a plane is split it is < 32, so on narrow buses
  // its upper bits are not needed.
  /* verilator lint_off UNUSEDSIGNAL */
  logic   [1:0][B4K_W-1:0] to4k_m1;
  /* verilator lint_on UNUSEDSIGNAL */

  // Rows between the arbiter and the end of the S5 queue, at most S5_D: a row is taken only
  // while that count is below S5_D (a compare of a register), so the queue always has room.
  localparam int unsigned S5_D = 8;   // >= the 7 stages S0..S4 + 1 for a row per clock
  logic [$clog2(S5_D):0] s5_credit_q;
  assign arb_ready = (s5_credit_q != ($clog2(S5_D) + 1)'(S5_D));

  msr_clr_reg #(.WIDTH($clog2(S5_D) + 1)) u_s5_credit (
    .clk_i,
    .rst_ni,
    .clear_i,
    .en_i    (1'b1),
    .d_i     (s5_credit_q + ($clog2(S5_D) + 1)'(arb_take) - ($clog2(S5_D) + 1)'(s5_take)),
    .q_o     (s5_credit_q)
  );

  // The stages' valid bits, one shift register.
  msr_clr_reg #(.WIDTH(7)) u_stage_v (
    .clk_i,
    .rst_ni,
    .clear_i,
    .en_i    (1'b1),
    .d_i     ({s3_v_q, s2_v_q, s15_v_q, s1m_v_q, s1_v_q, s0_v_q, arb_take}),
    .q_o     ({s4_v_q, s3_v_q, s2_v_q, s15_v_q, s1m_v_q, s1_v_q, s0_v_q})
  );

  // No enables: each stage's valid bit says whether its registers hold a row.
  always_ff @(posedge clk_i) begin
    s0_in_q   <= arb_idx;
    s0_buf_q  <= pick_q[arb_idx];
    s1_in_q   <= s0_in_q;
    s1_buf_q  <= s0_buf_q;
    s1_y_q    <= meta_y_q[s0_in_q][s0_buf_q];
    s1_x0_q   <= meta_x0_q[s0_in_q][s0_buf_q];
    s1_l_q    <= meta_l_q[s0_in_q][s0_buf_q];
    s1m_in_q  <= s1_in_q;
    s1m_buf_q <= s1_buf_q;
    s1m_l_q   <= s1_l_q;
    s1m_x0_q  <= s1_x0_q;
    s1m_m_q   <= s1m_m_d;
    s15_in_q  <= s1m_in_q;
    s15_buf_q <= s1m_buf_q;
    s15_l_q   <= s1m_l_q;
    s15_cs_q  <= s15_cs_d;
    s2_in_q   <= s15_in_q;
    s2_buf_q  <= s15_buf_q;
    s2_l_q    <= s15_l_q;
    s2_cs_q   <= s2_cs_d;
    s3_in_q   <= s2_in_q;
    s3_buf_q  <= s2_buf_q;
    s3_l_q    <= s2_l_q;
    s3_cs_q   <= s2_cs_q;
    s3_lo_q   <= s3_lo_d;
    s3_cy_q   <= s3_cy_d;
    s4_in_q   <= s3_in_q;
    s4_buf_q  <= s3_buf_q;
    s4_cs_q   <= s3_cs_q;
    s4_lo_q   <= s3_lo_q;
    s4_mid_q  <= s4_mid_d;
    s4_cy_q   <= s4_cy_d;
    s4_em1_q  <= s4_em1_d;
    s4_pe_q   <= s4_pe_d;
  end

  // The stages' arithmetic, per plane.
  always_comb begin
    for (int unsigned p = 0; p < 2; p++) begin
      logic [31:0] st, base, xt;
      cs_t         c1, c2, c3;
      logic [12:0] lo_sum;
      logic [10:0] mid_sum;
      logic [9:0]  hi_sum;
      logic [7:0]  nbm1;    // bytes of the plane - 1
      logic [MA_W-1:0] mb;
      // S2: six addends to a carry-save pair
      st   = (p != 0) ? src_stride_i : fb_stride_i;
      // S1m: the stride multiples, registered: each y bit selects in 64 multiplexers, and
      // that fan-out alone was most of the glue's worst placed path (10.4 ns) when the
      // carry-save level sat behind it in the same clock.
      // Radix-8 digit k of y selects its multiple, shifted to its weight 8^k.
      for (int unsigned k = 0; k < 4; k++) begin
        s1m_m_d[p][k] = mult8(s1_y_q[3*k +: 3], st, mul_q[3*p], mul_q[3*p+1], mul_q[3*p+2])
                        << (3 * k);
      end
      base = (p != 0) ? src_base_i : fb_base_i;
      xt   = (p != 0) ? {20'b0, s1m_x0_q} : {18'b0, s1m_x0_q, 2'b0};
      s15_cs_d[p][0] = csa(s1m_m_q[p][0], s1m_m_q[p][1], s1m_m_q[p][2]);
      s15_cs_d[p][1] = csa(s1m_m_q[p][3], base, xt);
      c1   = s15_cs_q[p][0];
      c2   = s15_cs_q[p][1];
      c3   = csa(c1.s, c1.c, c2.s);
      s2_cs_d[p] = csa(c3.s, c3.c, c2.c);
      // S3: bits [11:0]
      lo_sum     = {1'b0, s2_cs_q[p].s[11:0]} + {1'b0, s2_cs_q[p].c[11:0]};
      s3_lo_d[p] = lo_sum[11:0];
      s3_cy_d[p] = lo_sum[12];
      // S4: bits [21:12]; the plane's end from the low bits
      mid_sum     = {1'b0, s3_cs_q[p].s[21:12]} + {1'b0, s3_cs_q[p].c[21:12]} + 11'(s3_cy_q[p]);
      nbm1        = (p != 0) ? 8'(s3_l_q) : {1'b0, s3_l_q, 2'b11};
      s4_mid_d[p] = mid_sum[9:0];
      s4_cy_d[p]  = mid_sum[10];
      s4_em1_d[p] = 9'(s3_lo_q[p][BB_W-1:0]) + 9'(nbm1);
      s4_pe_d[p]  = {1'b0, s3_lo_q[p]} + 13'(nbm1);
      // S5: bits [31:22]; the burst shape
      hi_sum     = s4_cs_q[p].s[31:22] + s4_cs_q[p].c[31:22] + 10'(s4_cy_q[p]);
      to4k_m1[p] = ~s4_lo_q[p][11:BB_W];
      mb         = buf_base(s4_buf_q, (p != 0) ? SB : PB);
      s5_a_d[p]          = {hi_sum, s4_mid_q[p], s4_lo_q[p]};
      s5_shape_d[p].two  = s4_pe_q[p][12];
      s5_shape_d[p].len0 = s4_pe_q[p][12] ? 8'(to4k_m1[p]) : 8'(s4_em1_q[p] >> BB_W);
      s5_shape_d[p].len1 = 8'(s4_pe_q[p][11:0] >> BB_W);
      s5_shape_d[p].lo   = s4_lo_q[p][BB_W-1:0];
      s5_shape_d[p].hi   = s4_em1_q[p][BB_W-1:0];
      s5_mb1_d[p]        = mb + maddr_t'(to4k_m1[p]) + 1'b1;
    end
  end

  assign s5_d = '{in: s4_in_q, bufi: s4_buf_q, a: s5_a_d, shape: s5_shape_d, mb1: s5_mb1_d};

  logic                  s5_room;   // always 1 (credits): checked below
  logic [$clog2(S5_D):0] s5_count;
  msr_fifo #(.WIDTH($bits(s5_t)), .DEPTH(S5_D)) u_s5_queue (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .flush_i (clear_i),
    .valid_i (s4_v_q),
    .ready_o (s5_room),
    .data_i  (s5_d),
    .valid_o (s5_v_q),
    .ready_i (s5_take),
    .data_o  (s5_q),
    .count_o (s5_count)
  );
  assign s5_in_q    = s5_q.in;
  assign s5_buf_q   = s5_q.bufi;
  assign s5_a_q     = s5_q.a;
  assign s5_shape_q = s5_q.shape;
  assign s5_mb1_q   = s5_q.mb1;

  // The row's bursts, up to two per plane, issued from a register list one per clock.
  typedef struct packed {
    logic [31:0]      addr;      // bus-aligned burst address
    logic [7:0]       len;       // AWLEN (beats - 1)
    in_t              in;        // input of the row
    buf_t             bufi;      // its buffer
    logic             src;       // 1: code plane, 0: pixels
    maddr_t           mbase;     // buffer memory address of the burst's first beat
    logic [BB_W-1:0]  lo;        // first byte written in the burst's first beat
    logic [BB_W-1:0]  hi;        // last byte written in the burst's last beat
    logic             row_last;  // the row's last burst: its buffer is free after it
  } burst_t;

  // What the W side needs of a burst.
  typedef struct packed {
    logic [7:0]       len;
    in_t              in;
    buf_t             bufi;
    logic             src;
    maddr_t           mbase;
    logic [BB_W-1:0]  lo;
    logic [BB_W-1:0]  hi;
    logic             row_last;
  } wburst_t;

  burst_t [3:0] bl_q, bl_d;       // the list; entry 0 goes to the AW register next
  logic   [3:0] blv_q, blv_d;
  burst_t [1:0] b0, b1;           // per plane: first and second burst
  logic         aw_hs, aw_push, w_push_ready, b_hs;
  // AW register (msr_spill_reg): the list's head moves into it on aw_push, a decision made from
  // flip-flops only (list valid, budget, the register's registered ready). So the list's shift
  // and reload (an enable on some 280 flip-flops) never wait on AWREADY or on a count compare.
  logic         aw_sp_ready, aw_sp_valid;
  burst_t       aw_sp;
  logic         out_ok_q;         // another burst fits the budget (registered compare)

  always_comb begin
    for (int unsigned p = 0; p < 2; p++) begin
      logic [31:0] al;
      al = s5_a_q[p] & ~(STRB_W - 1);
      b0[p] = '{addr: al, len: s5_shape_q[p].len0, in: s5_in_q, bufi: s5_buf_q, src: p[0],
                mbase: buf_base(s5_buf_q, (p != 0) ? SB : PB), lo: s5_shape_q[p].lo,
                hi: s5_shape_q[p].two ? BB_W'(STRB_W - 1) : s5_shape_q[p].hi, row_last: 1'b0};
      b1[p] = '{addr: {al[31:12] + 1'b1, 12'h000}, len: s5_shape_q[p].len1, in: s5_in_q,
                bufi: s5_buf_q, src: p[0], mbase: s5_mb1_q[p], lo: '0, hi: s5_shape_q[p].hi,
                row_last: 1'b0};
    end
  end

  assign aw_push = blv_q[0] && out_ok_q && aw_sp_ready;
  // A new row enters when the list is empty or its last burst goes this clock.
  assign s5_take = s5_v_q && (blv_q == '0 || (aw_push && blv_q[3:1] == '0));

  always_comb begin
    logic ptwo, stwo;
    ptwo  = s5_shape_q[0].two;
    stwo  = s5_shape_q[1].two;
    bl_d  = bl_q;
    blv_d = blv_q;
    if (aw_push) begin
      bl_d  = {bl_q[3], bl_q[3:1]};
      blv_d = {1'b0, blv_q[3:1]};
    end
    if (s5_take) begin
      bl_d[0] = b0[0];
      bl_d[1] = ptwo ? b1[0] : b0[1];
      bl_d[2] = ptwo ? b0[1] : b1[1];
      bl_d[3] = b1[1];
      if (!src_en_i) blv_d = ptwo ? 4'b0011 : 4'b0001;
      else           blv_d = ptwo ? (stwo ? 4'b1111 : 4'b0111) : (stwo ? 4'b0111 : 4'b0011);
      // the row's last burst
      unique case (blv_d)
        4'b0001: bl_d[0].row_last = 1'b1;
        4'b0011: bl_d[1].row_last = 1'b1;
        4'b0111: bl_d[2].row_last = 1'b1;
        default: bl_d[3].row_last = 1'b1;
      endcase
    end
  end

  msr_clr_reg #(.WIDTH(4)) u_blv (
    .clk_i,
    .rst_ni,
    .clear_i,
    .en_i    (1'b1),
    .d_i     (blv_d),
    .q_o     (blv_q)
  );
  always_ff @(posedge clk_i) begin
    bl_q <= bl_d;
  end

  msr_spill_reg #(.WIDTH($bits(burst_t))) u_aw_reg (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .clear_i (clear_i),
    .valid_i (aw_push),
    .ready_o (aw_sp_ready),
    .data_i  (bl_q[0]),
    .valid_o (aw_sp_valid),
    .ready_i (w_push_ready && m_axi_awready),
    .data_o  (aw_sp)
  );

  // Bursts against the budget of MAX_OUT: counted from the AW register on (budget_q), so the
  // check that lets the next one in is a register; B responses are expected only for bursts
  // whose address went out on the bus (onbus_q). One ID: B comes in order, and the addresses
  // of the bursts on the bus wait in order for theirs.
  logic [OUT_W-1:0] budget_q, budget_d, onbus_q;
  logic             b_pop, onbus_nz_q, onbus_nz_d, out_ok_d;
  logic             b_expected, aq_valid, aq_ready;
  logic [31:0]      aq_addr;
  logic [$clog2(AQ_D):0] aq_count;

  // AWVALID waits for room in the W side's burst queue; that room only grows while AWVALID
  // waits (the queue takes a burst only on the AW handshake), so AWVALID is never withdrawn.
  assign m_axi_awvalid = aw_sp_valid && w_push_ready;
  assign aw_hs         = m_axi_awvalid && m_axi_awready;
  assign m_axi_awid    = '0;
  assign m_axi_awaddr  = aw_sp.addr;
  assign m_axi_awlen   = aw_sp.len;
  assign m_axi_awsize  = 3'(BB_W);   // a full beat
  assign m_axi_awburst = 2'b01;      // INCR
  assign m_axi_awlock  = 1'b0;
  assign m_axi_awcache = 4'b0011;    // normal, non-cacheable, bufferable
  assign m_axi_awprot  = 3'b000;

  assign m_axi_bready   = 1'b1;
  assign b_hs           = m_axi_bvalid && m_axi_bready;
  assign b_expected     = onbus_nz_q;
  assign bresp_err_o    = b_hs && b_expected && m_axi_bresp[1];
  assign bresp_addr_o   = aq_addr;
  assign b_unexpected_o = b_hs && !b_expected;
  assign budget_d       = budget_q + OUT_W'(aw_push) - OUT_W'(b_pop);

  // The two flags' next values without the counts' adders behind them (the placed top's path
  // at fef40d6: onbus_q -> "a B is expected" -> budget adder -> budget compare): compares of
  // the count registers, and the late AW push / B pop through one gate. aw_push needs out_ok_q,
  // so a full budget only shrinks. a_budget_flags checks both against the compares.
  assign b_pop      = b_hs && b_expected;
  // (compared at 32 bits: with MAX_OUT 1 the counts are one bit wide)
  assign onbus_nz_d = aw_hs || (32'(onbus_q) >= 2) || (32'(onbus_q) == 1 && !b_pop);
  assign out_ok_d   = (32'(budget_q) < MAX_OUT - 1) ||
                      (32'(budget_q) == MAX_OUT - 1 && !(aw_push && !b_pop)) ||
                      (32'(budget_q) == MAX_OUT && b_pop);

  // out_ok_q is 1 after reset and clear: the budget is then empty.
  msr_clr_reg #(.WIDTH(2 * OUT_W + 2), .RESET({(2 * OUT_W)'(0), 2'b10})) u_budget (
    .clk_i,
    .rst_ni,
    .clear_i,
    .en_i    (1'b1),
    .d_i     ({budget_d, onbus_q + OUT_W'(aw_hs) - OUT_W'(b_pop), out_ok_d, onbus_nz_d}),
    .q_o     ({budget_q, onbus_q, out_ok_q, onbus_nz_q})
  );

  msr_fifo #(.WIDTH(32), .DEPTH(AQ_D)) u_addr_fifo (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .flush_i (clear_i),
    .valid_i (aw_hs),
    .ready_o (aq_ready),
    .data_i  (m_axi_awaddr),
    .valid_o (aq_valid),
    .ready_i (b_pop),
    .data_o  (aq_addr),
    .count_o (aq_count)
  );

  // ---- W: the beats of each addressed burst, in order ------------------------------------------
  wburst_t         wq_data, wq_push;
  logic            wq_valid, wq_pop, w_issue, wlast_d;
  logic [7:0]      wcnt_q;
  logic            wv_q;
  logic [AXI_DATA_W-1:0] wdata_q, wdata_d;
  logic [STRB_W-1:0]     wstrb_q, wstrb_d;
  logic                  wlast_q;

  assign wq_push = '{len: aw_sp.len, in: aw_sp.in, bufi: aw_sp.bufi, src: aw_sp.src,
                     mbase: aw_sp.mbase, lo: aw_sp.lo, hi: aw_sp.hi, row_last: aw_sp.row_last};
  logic [2:0] wq_count;

  msr_fifo #(.WIDTH($bits(wburst_t)), .DEPTH(4)) u_burst_fifo (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .flush_i (clear_i),
    .valid_i (aw_hs),
    .ready_o (w_push_ready),
    .data_i  (wq_push),
    .valid_o (wq_valid),
    .ready_i (wq_pop),
    .data_o  (wq_data),
    .count_o (wq_count)
  );

  // W1: the next beat's buffer address, strobes and WLAST, registered; W2: the buffer read at
  // that address (LUT RAM, asynchronous) into the W output register. A row's buffer is free
  // when W2 reads its last beat.
  logic                  w1_v_q, w1_last_q, w1_src_q, w1_row_last_q, w2_load;
  in_t                   w1_in_q;
  buf_t                  w1_buf_q;
  logic [STRB_W-1:0]     w1_strb_q;

  assign w2_load = w1_v_q && (!wv_q || m_axi_wready);
  assign w_issue = wq_valid && (!w1_v_q || w2_load);
  assign wlast_d = (wcnt_q == wq_data.len);
  assign wq_pop  = w_issue && wlast_d;

  msr_clr_reg #(.WIDTH(1)) u_row_free (
    .clk_i,
    .rst_ni,
    .clear_i,
    .en_i    (1'b1),
    .d_i     (w2_load && w1_last_q && w1_row_last_q),
    .q_o     (row_free_q)
  );
  always_ff @(posedge clk_i) begin
    row_free_in_q  <= w1_in_q;
    row_free_buf_q <= w1_buf_q;
  end

  always_comb begin
    for (int unsigned j = 0; j < WPB; j++) begin
      logic [4*CODE_W-1:0] c;
      c = srd[w1_in_q][j];
      if (w1_src_q) begin
        wdata_d[32*j +: 32] = {3'b0, c[3*CODE_W +: CODE_W], 3'b0, c[2*CODE_W +: CODE_W],
                               3'b0, c[CODE_W +: CODE_W], 3'b0, c[0 +: CODE_W]};
      end else begin
        wdata_d[32*j +: 32] = {8'h00, prd[w1_in_q][j]};
      end
    end
    for (int unsigned b = 0; b < STRB_W; b++) begin
      wstrb_d[b] = (wcnt_q != '0 || b >= 32'(wq_data.lo)) && (!wlast_d || b <= 32'(wq_data.hi));
    end
  end

  // W1 fills on an issue and empties into W2; W2 fills from W1 and empties on WREADY.
  msr_clr_reg #(.WIDTH(2)) u_w_v (
    .clk_i,
    .rst_ni,
    .clear_i,
    .en_i    (1'b1),
    .d_i     ({w_issue || (w1_v_q && !w2_load), w2_load || (wv_q && !m_axi_wready)}),
    .q_o     ({w1_v_q, wv_q})
  );
  // The beat of the burst at the queue's head.
  msr_clr_reg #(.WIDTH(8)) u_wcnt (
    .clk_i,
    .rst_ni,
    .clear_i,
    .en_i    (w_issue),
    .d_i     (wlast_d ? '0 : wcnt_q + 1'b1),
    .q_o     (wcnt_q)
  );
  // The beat's buffer address goes only to the copy of the input it reads (the others keep
  // theirs: their read data is not selected), so each copy drives a quarter of the memories.
  for (genvar i = 0; i < NUM_IN; i++) begin : g_raddr
    always_ff @(posedge clk_i) begin
      if (w_issue && wq_data.in == in_t'(i)) begin
        raddr_q[i] <= maddr_t'(32'(wq_data.mbase) + 32'(wcnt_q));
      end
    end
  end

  always_ff @(posedge clk_i) begin
    if (w_issue) begin
      w1_in_q       <= wq_data.in;
      w1_buf_q      <= wq_data.bufi;
      w1_src_q      <= wq_data.src;
      w1_strb_q     <= wstrb_d;
      w1_last_q     <= wlast_d;
      w1_row_last_q <= wq_data.row_last;
    end
    if (w2_load) begin
      wdata_q <= wdata_d;
      wstrb_q <= w1_strb_q;
      wlast_q <= w1_last_q;
    end
  end

  assign m_axi_wvalid = wv_q;
  assign m_axi_wdata  = wdata_q;
  assign m_axi_wstrb  = wstrb_q;
  assign m_axi_wlast  = wlast_q;

  assign idle_o = (full_q == '0) && (wr_v_q == '0) && (wr2_busy == '0) &&
                  !s0_v_q && !s1_v_q && !s1m_v_q && !s15_v_q && !s2_v_q && !s3_v_q && !s4_v_q &&
                  !s5_v_q &&
                  (blv_q == '0) && !aw_sp_valid && !wq_valid && !w1_v_q && !wv_q &&
                  (budget_q == '0);

  // Codes keep CODE_W bits in the buffers; the upper bits of every code are 0.
  logic [NUM_IN-1:0] code_big;
  for (genvar i = 0; i < NUM_IN; i++) begin : g_code_big
    assign code_big[i] = pix_hs[i] && (pix_src_i[i][SRC_W-1:CODE_W] != '0);
  end

  logic unused_b;
  assign unused_b = ^{m_axi_bid, m_axi_bresp[0], aq_valid, aq_ready, aq_count, wq_count, code_big,
                      s5_count};

  /* verilator lint_off SYNCASYNCNET */
  `MSR_ASSERT(a_aw_stable, m_axi_awvalid && !m_axi_awready |=>
              m_axi_awvalid && $stable({m_axi_awaddr, m_axi_awlen}), clk_i, !rst_ni || clear_i)
  `MSR_ASSERT(a_w_stable, m_axi_wvalid && !m_axi_wready |=>
              m_axi_wvalid && $stable({m_axi_wdata, m_axi_wstrb, m_axi_wlast}), clk_i,
              !rst_ni || clear_i)
  `MSR_ASSERT(a_no_4k_cross, m_axi_awvalid |-> (32'(m_axi_awaddr[11:0]) +
              (32'(m_axi_awlen) + 1) * STRB_W) <= 32'h1000)
  `MSR_ASSERT(a_addr_fifo_room, aw_hs |-> aq_ready)
  `MSR_ASSERT(a_s5_room, s4_v_q |-> s5_room)
  `MSR_ASSERT(a_onbus_in_budget, onbus_q <= budget_q)
  `MSR_ASSERT(a_budget_flags, out_ok_q == (budget_q != OUT_W'(MAX_OUT)) &&
              onbus_nz_q == (onbus_q != '0))
  `MSR_ASSERT(a_s5_credit, s5_credit_q <= ($clog2(S5_D) + 1)'(S5_D))
  `MSR_ASSERT(a_code_fits, code_big == '0)
  `MSR_ASSERT(a_row_ready_late, (row_ready_q & ~row_ready) == '0)
  `MSR_ASSERT(a_width_stable, pix_valid_i != '0 |-> $stable(width_i))
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_fb_writer
