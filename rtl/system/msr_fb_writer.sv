// Frame-buffer writer: an AXI4 write master that stores the engines' finished pixels.
//
// Inputs: NUM_IN pixel streams, one per engine, taken in parallel (one pixel per stream per
// clock). Each stream is row-contiguous by itself (an engine emits whole tiles row-major);
// a row ends at the tile's right edge or the frame's, which this unit derives from x.
// Per input, two row buffers (ping-pong): one collects the next row while the other waits
// for / is being written. A row is written only once it is complete, so a burst never waits
// for data and an abandoned row (soft reset) never leaves a burst open.
// Output per row: the 32-bit pixels 0x00RRGGBB at FB_BASE + y*FB_STRIDE + 4*x0 and, when the
// source map is enabled, the 8-bit codes at SRC_BASE + y*SRC_STRIDE + x0, each as INCR
// bursts of AXI_DATA_W-bit beats from the bus-aligned address below the row's start, with
// byte strobes on the partial first / last beats (bases and strides are 4-byte aligned, so
// both planes start on a 32-bit lane). A burst that would cross a 4 KiB boundary (AXI rule)
// is split there. Rows of different inputs are written round robin.
//
// Width: a 16-pixel row with its codes takes 2 + 1 beats of 256 bits when the frame buffer is
// 32-byte aligned, so four engines at one pixel per clock each (4 pixels per clock) fit with
// room (5.3 pixels per clock); 128 bits would cap the writer at 3.2 pixels per clock.
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
  input  dim_t              width_i,         // W
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
  output logic              bresp_err_o      // pulse: a write response was SLVERR or DECERR
);
  localparam int unsigned WPB     = AXI_DATA_W / 32;         // 32-bit lanes per beat
  localparam int unsigned LANE_W  = (WPB > 1) ? $clog2(WPB) : 1;
  localparam int unsigned BB_W    = $clog2(STRB_W);          // byte offset inside a beat
  localparam int unsigned BEATS_W = LDIM_W + 1;              // beats of a plane, 1..33
  localparam int unsigned OUT_W   = $clog2(MAX_OUT + 1);
  localparam int unsigned IN_W    = (NUM_IN > 1) ? $clog2(NUM_IN) : 1;
  localparam int unsigned SRCW_N  = MAX_TILE / 4;            // 32-bit words of codes per row

  if (AXI_DATA_W != 32 && AXI_DATA_W != 64 && AXI_DATA_W != 128 && AXI_DATA_W != 256)
  begin : gen_bad_width
    $fatal(1, "msr_fb_writer: AXI_DATA_W must be 32, 64, 128 or 256, got %0d", AXI_DATA_W);
  end
  if (MAX_OUT < 1 || MAX_OUT > 255) begin : gen_bad_out
    $fatal(1, "msr_fb_writer: MAX_OUT must be 1..255, got %0d", MAX_OUT);
  end
  if (NUM_IN < 1 || NUM_IN > 16) begin : gen_bad_in
    $fatal(1, "msr_fb_writer: NUM_IN must be 1..16, got %0d", NUM_IN);
  end

  typedef logic [IN_W-1:0] in_t;

  // ---- Row buffers: two per input ---------------------------------------------------------------
  logic [LCOORD_W-1:0] tmask;      // T - 1
  always_comb begin
    unique case (tile_i)
      TILE_8:  tmask = LCOORD_W'(7);
      TILE_16: tmask = LCOORD_W'(15);
      TILE_32: tmask = LCOORD_W'(31);
      default: tmask = LCOORD_W'(15);
    endcase
  end

  logic [NUM_IN-1:0][1:0][MAX_TILE-1:0][31:0] buf_px_q;   // pixels 0x00RRGGBB
  logic [NUM_IN-1:0][1:0][MAX_TILE-1:0][7:0]  buf_src_q;  // source codes
  coord_t [NUM_IN-1:0][1:0]  buf_y_q, buf_x0_q;
  ldim_t  [NUM_IN-1:0][1:0]  buf_n_q;                      // pixels of the row
  logic   [NUM_IN-1:0][1:0]  buf_full_q;                   // complete, not yet written
  logic   [NUM_IN-1:0][1:0]  buf_aw_q;                     // ... and its bursts are addressed
  logic   [NUM_IN-1:0]       col_sel_q;                    // buffer that collects
  logic   [NUM_IN-1:0]       aw_sel_q;                     // buffer the address side takes next
  logic   [NUM_IN-1:0]       pix_hs, row_end;
  logic   [NUM_IN-1:0][LCOORD_W-1:0] lane;

  for (genvar i = 0; i < NUM_IN; i++) begin : gen_in
    assign lane[i]        = pix_x_i[i][LCOORD_W-1:0] & tmask;
    assign row_end[i]     = (lane[i] == tmask) || (dim_t'(pix_x_i[i]) + 1'b1 == width_i);
    assign pix_ready_o[i] = !buf_full_q[i][col_sel_q[i]];
    assign pix_hs[i]      = pix_valid_i[i] && pix_ready_o[i];
    assign tile_done_o[i] = pix_hs[i] && pix_last_i[i];

    always_ff @(posedge clk_i) begin
      if (pix_hs[i]) begin
        buf_px_q[i][col_sel_q[i]][lane[i]]  <= {8'h00, pix_rgb_i[i]};
        buf_src_q[i][col_sel_q[i]][lane[i]] <= pix_src_i[i];
        buf_y_q[i][col_sel_q[i]]            <= pix_y_i[i];
        buf_x0_q[i][col_sel_q[i]]           <= pix_x_i[i] & ~coord_t'(tmask);
        buf_n_q[i][col_sel_q[i]]            <= ldim_t'(lane[i]) + 1'b1;
      end
    end
  end

  // ---- Address side: one burst per clock when the bus takes it ----------------------------------
  // The generator holds one row (input, buffer) and its current plane; awaddr / awlen are
  // formed from registers, and the handshake moves to the next burst, plane or row.
  typedef struct packed {
    in_t                in;         // input of the row
    logic               bsel;       // its buffer
    logic               src;        // 1: source plane, 0: pixels
    logic [BEATS_W-1:0] k0;         // first beat of the burst within the plane
    logic [BEATS_W-1:0] beats;      // beats of the burst
    logic [LANE_W-1:0]  ow;         // lane of the plane's first word in its first beat
    logic               row_last;   // the row's last burst: its buffer is free after it
  } burst_t;

  logic               gen_valid_q;   // a row is loaded
  in_t                gen_in_q;
  logic               gen_bsel_q, gen_src_q;
  logic [31:0]        gen_base_q;    // bus-aligned address of the plane's first beat
  logic [31:0]        gen_src_addr_q;// the source plane's row address (for after the pixels)
  logic [LANE_W-1:0]  gen_ow_q;
  logic [BEATS_W-1:0] gen_k_q, gen_nbeat_q;
  ldim_t              gen_n_q;
  logic [OUT_W-1:0]   outst_q;
  logic               wq_push_ready, wq_pop_valid, wq_pop;
  burst_t             wq_push_data, wq_pop_data;
  logic               aw_hs, b_hs, w_hs;

  assign aw_hs = m_axi_awvalid && m_axi_awready;
  assign b_hs  = m_axi_bvalid && m_axi_bready;

  // The current burst: from beat k of the plane up to its end or the next 4 KiB boundary.
  logic [31:0]        burst_addr;
  logic [12:0]        to_4k;         // beats left before the 4 KiB boundary
  logic [BEATS_W-1:0] burst_beats, left;
  logic               plane_last, row_last;

  always_comb begin
    burst_addr  = gen_base_q + (32'(gen_k_q) << BB_W);
    to_4k       = (13'h1000 - {1'b0, burst_addr[11:0]}) >> BB_W;
    left        = gen_nbeat_q - gen_k_q;
    burst_beats = (13'(left) > to_4k) ? BEATS_W'(to_4k) : left;
    plane_last  = (burst_beats == left);
    row_last    = plane_last && (gen_src_q || !src_en_i);
  end

  // Plane set-up: the aligned base, the first lane and the number of beats.
  function automatic logic [LANE_W-1:0] first_lane(logic [31:0] addr);
    return LANE_W'((addr & (STRB_W - 1)) >> 2);
  endfunction
  function automatic logic [BEATS_W-1:0] plane_beats(logic [LANE_W-1:0] ow, ldim_t words);
    return BEATS_W'((32'(ow) + 32'(words) + WPB - 1) / WPB);
  endfunction
  function automatic ldim_t src_words(ldim_t n);
    return ldim_t'((32'(n) + 3) / 4);
  endfunction

  // Next row for the address side: round robin over inputs with a complete row not addressed.
  logic [NUM_IN-1:0] row_ready;
  in_t               rr_q, pick;
  logic              pick_valid, load;
  for (genvar i = 0; i < NUM_IN; i++) begin : gen_row_ready
    assign row_ready[i] = buf_full_q[i][aw_sel_q[i]] && !buf_aw_q[i][aw_sel_q[i]];
  end
  always_comb begin
    pick       = rr_q;
    pick_valid = 1'b0;
    for (int unsigned j = NUM_IN; j > 0; j--) begin
      int unsigned c;
      c = 32'(rr_q) + j - 1;
      if (c >= NUM_IN) c -= NUM_IN;
      if (row_ready[c]) begin
        pick       = in_t'(c);
        pick_valid = 1'b1;
      end
    end
  end
  // A row is loaded when the generator is empty or its last burst is being taken.
  assign load = pick_valid && (!gen_valid_q || (aw_hs && row_last));

  logic [31:0] ld_fb_addr, ld_src_addr;
  coord_t      ld_y, ld_x0;
  ldim_t       ld_n;
  assign ld_y  = buf_y_q[pick][aw_sel_q[pick]];
  assign ld_x0 = buf_x0_q[pick][aw_sel_q[pick]];
  assign ld_n  = buf_n_q[pick][aw_sel_q[pick]];
  // 32 x 12 bit products, one per row (rows take >= 8 clocks per input); a hand-off may
  // pipeline them.
  assign ld_fb_addr  = fb_base_i + 32'(ld_y) * fb_stride_i + {18'b0, ld_x0, 2'b0};
  assign ld_src_addr = src_base_i + 32'(ld_y) * src_stride_i + {20'b0, ld_x0};

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      gen_valid_q    <= 1'b0;
      gen_in_q       <= '0;
      gen_bsel_q     <= 1'b0;
      gen_src_q      <= 1'b0;
      gen_base_q     <= '0;
      gen_src_addr_q <= '0;
      gen_ow_q       <= '0;
      gen_k_q        <= '0;
      gen_nbeat_q    <= '0;
      gen_n_q        <= '0;
      rr_q           <= '0;
      outst_q        <= '0;
    end else if (clear_i) begin
      gen_valid_q    <= 1'b0;
      gen_src_q      <= 1'b0;
      gen_k_q        <= '0;
      rr_q           <= '0;
      outst_q        <= '0;
    end else begin
      outst_q <= outst_q + OUT_W'(aw_hs) - OUT_W'(b_hs);
      if (load) begin
        gen_valid_q    <= 1'b1;
        gen_in_q       <= pick;
        gen_bsel_q     <= aw_sel_q[pick];
        gen_src_q      <= 1'b0;
        gen_base_q     <= ld_fb_addr & ~(STRB_W - 1);
        gen_src_addr_q <= ld_src_addr;
        gen_ow_q       <= first_lane(ld_fb_addr);
        gen_k_q        <= '0;
        gen_nbeat_q    <= plane_beats(first_lane(ld_fb_addr), ld_n);
        gen_n_q        <= ld_n;
        rr_q           <= (32'(pick) == NUM_IN - 1) ? '0 : pick + 1'b1;
      end else if (aw_hs) begin
        if (!plane_last) begin
          gen_k_q <= gen_k_q + burst_beats;
        end else if (!row_last) begin
          // pixels done: the source plane of the same row
          gen_src_q   <= 1'b1;
          gen_base_q  <= gen_src_addr_q & ~(STRB_W - 1);
          gen_ow_q    <= first_lane(gen_src_addr_q);
          gen_k_q     <= '0;
          gen_nbeat_q <= plane_beats(first_lane(gen_src_addr_q), src_words(gen_n_q));
        end else begin
          gen_valid_q <= 1'b0;
        end
      end
    end
  end

  assign m_axi_awid    = '0;
  assign m_axi_awaddr  = burst_addr;
  assign m_axi_awlen   = 8'(burst_beats - 1'b1);
  assign m_axi_awsize  = 3'(BB_W);   // a full beat
  assign m_axi_awburst = 2'b01;      // INCR
  assign m_axi_awlock  = 1'b0;
  assign m_axi_awcache = 4'b0011;    // normal, non-cacheable, bufferable
  assign m_axi_awprot  = 3'b000;
  // A burst goes out only when its W bookkeeping has room and the B budget allows.
  assign m_axi_awvalid = gen_valid_q && wq_push_ready && (outst_q < OUT_W'(MAX_OUT));

  assign wq_push_data = '{in: gen_in_q, bsel: gen_bsel_q, src: gen_src_q, k0: gen_k_q,
                          beats: burst_beats, ow: gen_ow_q, row_last: row_last};

  msr_fifo #(.WIDTH($bits(burst_t)), .DEPTH(4)) u_burst_fifo (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .flush_i (clear_i),
    .valid_i (aw_hs),
    .ready_o (wq_push_ready),
    .data_i  (wq_push_data),
    .valid_o (wq_pop_valid),
    .ready_i (wq_pop),
    .data_o  (wq_pop_data),
      .count_o ()
  );

  // ---- W: the beats of each addressed burst, in order ---------------------------------------------
  logic [BEATS_W-1:0] wcnt_q;
  logic [BEATS_W-1:0] wbeat;                       // beat index within the plane
  logic [MAX_TILE-1:0][31:0] w_px;
  logic [SRCW_N-1:0][31:0]   w_srcw;
  ldim_t                     w_n;

  assign w_px  = buf_px_q[wq_pop_data.in][wq_pop_data.bsel];
  assign w_srcw = buf_src_q[wq_pop_data.in][wq_pop_data.bsel];   // 4 codes per word, x0 first
  assign w_n   = buf_n_q[wq_pop_data.in][wq_pop_data.bsel];
  assign wbeat = wq_pop_data.k0 + wcnt_q;

  always_comb begin
    m_axi_wdata = '0;
    m_axi_wstrb = '0;
    for (int unsigned j = 0; j < WPB; j++) begin
      // Word of the plane in lane j: idx = beat * WPB + j - ow.
      int signed idx;
      int unsigned nbytes;
      idx    = int'(32'(wbeat) * WPB + j) - int'(32'(wq_pop_data.ow));
      nbytes = wq_pop_data.src ? 32'(w_n) : 4 * 32'(w_n);
      if (idx >= 0 && idx < MAX_TILE && (!wq_pop_data.src || idx < int'(SRCW_N))) begin
        m_axi_wdata[32*j +: 32] = wq_pop_data.src ? w_srcw[idx[$clog2(SRCW_N)-1:0]]
                                                  : w_px[idx[LCOORD_W-1:0]];
        for (int unsigned b = 0; b < 4; b++) begin
          m_axi_wstrb[4*j + b] = (unsigned'(idx) * 4 + b < nbytes);
        end
      end
    end
  end

  assign m_axi_wvalid = wq_pop_valid;
  assign m_axi_wlast  = (wcnt_q + 1'b1 == wq_pop_data.beats);
  assign w_hs         = m_axi_wvalid && m_axi_wready;
  assign wq_pop       = w_hs && m_axi_wlast;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      wcnt_q <= '0;
    end else if (clear_i) begin
      wcnt_q <= '0;
    end else if (w_hs) begin
      wcnt_q <= m_axi_wlast ? '0 : wcnt_q + 1'b1;
    end
  end

  // ---- Buffer state ---------------------------------------------------------------------------------
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      buf_full_q <= '0;
      buf_aw_q   <= '0;
      col_sel_q  <= '0;
      aw_sel_q   <= '0;
    end else if (clear_i) begin
      buf_full_q <= '0;
      buf_aw_q   <= '0;
      col_sel_q  <= '0;
      aw_sel_q   <= '0;
    end else begin
      for (int unsigned i = 0; i < NUM_IN; i++) begin
        if (pix_hs[i] && row_end[i]) begin
          buf_full_q[i][col_sel_q[i]] <= 1'b1;
          col_sel_q[i]                <= !col_sel_q[i];
        end
        if (load && pick == in_t'(i)) begin
          buf_aw_q[i][aw_sel_q[i]] <= 1'b1;
          aw_sel_q[i]              <= !aw_sel_q[i];
        end
      end
      // The row's last beat is taken: its buffer collects again.
      if (wq_pop && wq_pop_data.row_last) begin
        buf_full_q[wq_pop_data.in][wq_pop_data.bsel] <= 1'b0;
        buf_aw_q[wq_pop_data.in][wq_pop_data.bsel]   <= 1'b0;
      end
    end
  end

  // ---- B ----------------------------------------------------------------------------------------
  assign m_axi_bready = 1'b1;
  assign bresp_err_o  = b_hs && m_axi_bresp[1];
  assign idle_o       = (buf_full_q == '0) && !gen_valid_q && !wq_pop_valid && (outst_q == '0);

  logic unused_b;
  assign unused_b = ^{m_axi_bid, m_axi_bresp[0]};   // single ID (in-order B); EXOKAY cannot occur

`ifndef SYNTHESIS
  // Lint: disable iff (!rst_ni) looks like a synchronous use of the asynchronous reset.
  /* verilator lint_off SYNCASYNCNET */
  // AXI: an offered address / beat stays until taken.
  assert property (@(posedge clk_i) disable iff (!rst_ni || clear_i)
                   m_axi_awvalid && !m_axi_awready |=>
                   m_axi_awvalid && $stable({m_axi_awaddr, m_axi_awlen}));
  assert property (@(posedge clk_i) disable iff (!rst_ni || clear_i)
                   m_axi_wvalid && !m_axi_wready |=>
                   m_axi_wvalid && $stable({m_axi_wdata, m_axi_wstrb, m_axi_wlast}));
  assert property (@(posedge clk_i) disable iff (!rst_ni || clear_i)
                   b_hs |-> outst_q != '0);
  // No burst crosses a 4 KiB boundary.
  assert property (@(posedge clk_i) disable iff (!rst_ni || clear_i)
                   m_axi_awvalid |-> (32'(m_axi_awaddr[11:0]) +
                                      (32'(m_axi_awlen) + 1) * STRB_W) <= 32'h1000);
  /* verilator lint_on SYNCASYNCNET */
`endif
endmodule
