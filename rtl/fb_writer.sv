// Frame-buffer writer: an AXI4 write master that stores the engines' finished pixels.
//
// Input: one pixel stream, row-contiguous (the caller locks its arbiter on a tile row; the
// row ends at the tile's right edge or the frame's, which this unit derives from x, so it
// needs no per-tile state). A row is buffered completely before its address goes out, so a
// burst never waits for data and an abandoned row (soft reset) never leaves a burst open.
// Output per row: one INCR burst of 32-bit pixels 0x00RRGGBB at
//   FB_BASE + y*FB_STRIDE + 4*x0, and, when the source map is enabled, one burst of packed
// 8-bit codes at SRC_BASE + y*SRC_STRIDE + x0 (byte strobes on the last word; x0 is a
// multiple of 8 and the bases/strides are 4-byte aligned, so the first byte is lane 0).
// A burst that would cross a 4 KiB boundary (AXI rule) is split there.
module fb_writer import msr_pkg::*; #(
  parameter int unsigned ID_W    = 4,    // AXI ID width (a single ID is used: in-order B)
  parameter int unsigned MAX_OUT = 8     // outstanding write bursts
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
  // Pixel stream in.
  input  logic              pix_valid_i,     // a finished pixel
  output logic              pix_ready_o,     // room for it
  input  coord_t            pix_x_i,         // global x
  input  coord_t            pix_y_i,         // global y
  input  rgb_t              pix_rgb_i,       // colour
  input  src_t              pix_src_i,       // source code
  input  logic              pix_last_i,      // last pixel of its tile
  output logic              pix_row_end_o,   // the offered pixel ends its tile row
  // AXI4 write master (no read channels).
  output logic [ID_W-1:0]   m_axi_awid,
  output logic [31:0]       m_axi_awaddr,
  output logic [7:0]        m_axi_awlen,
  output logic [2:0]        m_axi_awsize,
  output logic [1:0]        m_axi_awburst,
  output logic              m_axi_awlock,
  output logic [3:0]        m_axi_awcache,
  output logic [2:0]        m_axi_awprot,
  output logic              m_axi_awvalid,
  input  logic              m_axi_awready,
  output logic [31:0]       m_axi_wdata,
  output logic [3:0]        m_axi_wstrb,
  output logic              m_axi_wlast,
  output logic              m_axi_wvalid,
  input  logic              m_axi_wready,
  input  logic [ID_W-1:0]   m_axi_bid,
  input  logic [1:0]        m_axi_bresp,
  input  logic              m_axi_bvalid,
  output logic              m_axi_bready,
  // Status.
  output logic              idle_o,          // no complete row waiting, no burst open/outstanding
  output logic              tile_done_o,     // pulse: the last pixel of a tile was taken
  output logic              bresp_err_o      // pulse: a write response was SLVERR or DECERR
);
  localparam int unsigned BEATS_W = LDIM_W + 1;   // beats of one burst, 1..32 (+ headroom)
  localparam int unsigned OUT_W   = $clog2(MAX_OUT + 1);

  if (MAX_OUT < 1 || MAX_OUT > 255) begin : gen_bad_out
    $fatal(1, "fb_writer: MAX_OUT must be 1..255, got %0d", MAX_OUT);
  end

  // ---- Row geometry from x alone ---------------------------------------------------------------
  logic [LCOORD_W-1:0] tmask;      // T - 1
  coord_t              row_x0;
  logic                row_end;
  always_comb begin
    unique case (tile_i)
      TILE_8:  tmask = LCOORD_W'(7);
      TILE_16: tmask = LCOORD_W'(15);
      TILE_32: tmask = LCOORD_W'(31);
      default: tmask = LCOORD_W'(15);
    endcase
    row_x0  = pix_x_i & ~coord_t'(tmask);
    row_end = ((pix_x_i[LCOORD_W-1:0] & tmask) == tmask) || (dim_t'(pix_x_i) + 1'b1 == width_i);
  end
  assign pix_row_end_o = row_end;

  // ---- Input: pixel FIFO, source-word packing, row commands -----------------------------------
  typedef struct packed {
    logic [31:0]        fb_addr;
    logic [31:0]        src_addr;
    logic [BEATS_W-1:0] beats;      // pixels of the row
  } row_cmd_t;

  typedef struct packed {
    logic [31:0] data;
    logic [3:0]  strb;
  } src_word_t;

  logic        pf_push_ready, pf_pop_valid, pf_pop;
  logic [31:0] pf_pop_data;
  logic        sf_push, sf_push_ready, sf_pop_valid, sf_pop;
  src_word_t   sf_push_data, sf_pop_data;
  logic        cf_push, cf_push_ready, cf_pop_valid, cf_pop;
  row_cmd_t    cf_push_data, cf_pop_data;
  logic        pix_hs;
  logic [31:0] srcw_q, srcw_d;
  logic [3:0]  srcs_q, srcs_d;

  assign pix_ready_o = pf_push_ready && cf_push_ready && (!src_en_i || sf_push_ready);
  assign pix_hs      = pix_valid_i && pix_ready_o;
  assign tile_done_o = pix_hs && pix_last_i;

  always_comb begin
    // Byte lane of x inside its source word: x0 is a multiple of 8, so lane = x mod 4.
    srcw_d = srcw_q;
    srcs_d = srcs_q;
    srcw_d[8*pix_x_i[1:0] +: 8] = pix_src_i;
    srcs_d[pix_x_i[1:0]]        = 1'b1;
    sf_push      = pix_hs && src_en_i && ((pix_x_i[1:0] == 2'd3) || row_end);
    sf_push_data = '{data: srcw_d, strb: srcs_d};
    if (pix_hs && ((pix_x_i[1:0] == 2'd3) || row_end)) begin   // word complete, stored or not
      srcw_d = '0;
      srcs_d = '0;
    end
    cf_push = pix_hs && row_end;
    // 32 x 13 bit product: one per row; a hand-off may pipeline it (rows take >= 8 cycles).
    cf_push_data.fb_addr  = fb_base_i + 32'(pix_y_i) * fb_stride_i + {18'b0, row_x0, 2'b0};
    cf_push_data.src_addr = src_base_i + 32'(pix_y_i) * src_stride_i + {20'b0, row_x0};
    cf_push_data.beats    = BEATS_W'(pix_x_i - row_x0) + 1'b1;
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      srcw_q <= '0;
      srcs_q <= '0;
    end else if (clear_i) begin
      srcw_q <= '0;
      srcs_q <= '0;
    end else if (pix_hs) begin
      srcw_q <= srcw_d;
      srcs_q <= srcs_d;
    end
  end

  sys_fifo #(.WIDTH(32), .DEPTH(2 * MAX_TILE)) u_pix_fifo (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .flush_i (clear_i),
    .valid_i (pix_hs),
    .ready_o (pf_push_ready),
    .data_i  ({8'h00, pix_rgb_i}),
    .valid_o (pf_pop_valid),
    .ready_i (pf_pop),
    .data_o  (pf_pop_data)
  );

  sys_fifo #(.WIDTH($bits(src_word_t)), .DEPTH(2 * MAX_TILE / 4)) u_src_fifo (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .flush_i (clear_i),
    .valid_i (sf_push),
    .ready_o (sf_push_ready),
    .data_i  (sf_push_data),
    .valid_o (sf_pop_valid),
    .ready_i (sf_pop),
    .data_o  (sf_pop_data)
  );

  sys_fifo #(.WIDTH($bits(row_cmd_t)), .DEPTH(4)) u_cmd_fifo (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .flush_i (clear_i),
    .valid_i (cf_push),
    .ready_o (cf_push_ready),
    .data_i  (cf_push_data),
    .valid_o (cf_pop_valid),
    .ready_i (cf_pop),
    .data_o  (cf_pop_data)
  );

  // ---- AW: rows into bursts (split at 4 KiB) ----------------------------------------------------
  typedef enum logic [1:0] {
    AW_IDLE  = 2'd0,   // wait for a complete row
    AW_ISSUE = 2'd1,   // form the next burst
    AW_WAIT  = 2'd2    // burst address offered
  } aw_state_e;

  typedef struct packed {
    logic               src;        // 1: source-plane burst, 0: pixel burst
    logic [BEATS_W-1:0] beats;      // 1..32
  } burst_t;

  aw_state_e          aw_state_q, aw_state_d;
  logic [31:0]        cur_addr_q, cur_addr_d;      // next byte address of the current plane
  logic [BEATS_W-1:0] left_q, left_d;              // beats of the current plane still to issue
  logic               cur_src_q, cur_src_d;        // current plane is the source plane
  logic [31:0]        nxt_addr_q, nxt_addr_d;      // the source plane's row address
  logic [BEATS_W-1:0] nxt_beats_q, nxt_beats_d;    // and its words
  logic [31:0]        aw_addr_q, aw_addr_d;
  burst_t             aw_burst_q, aw_burst_d;
  logic [OUT_W-1:0]   outst_q, outst_d;            // bursts whose B has not arrived
  logic               wq_push_ready, wq_pop_valid, wq_pop;
  burst_t             wq_pop_data;
  logic               aw_hs, b_hs;
  logic [10:0]        to_4k;                       // beats left before the 4 KiB boundary
  logic [BEATS_W-1:0] burst_beats;

  assign aw_hs = m_axi_awvalid && m_axi_awready;
  assign b_hs  = m_axi_bvalid && m_axi_bready;

  always_comb begin
    aw_state_d  = aw_state_q;
    cur_addr_d  = cur_addr_q;
    left_d      = left_q;
    cur_src_d   = cur_src_q;
    nxt_addr_d  = nxt_addr_q;
    nxt_beats_d = nxt_beats_q;
    aw_addr_d   = aw_addr_q;
    aw_burst_d  = aw_burst_q;
    cf_pop      = 1'b0;
    to_4k       = 11'((13'h1000 - {1'b0, cur_addr_q[11:0]}) >> 2);
    burst_beats = ({{(11-BEATS_W){1'b0}}, left_q} > to_4k) ? BEATS_W'(to_4k) : left_q;
    unique case (aw_state_q)
      AW_IDLE: begin
        if (cf_pop_valid) begin
          cf_pop      = 1'b1;
          cur_addr_d  = cf_pop_data.fb_addr;
          left_d      = cf_pop_data.beats;
          cur_src_d   = 1'b0;
          nxt_addr_d  = cf_pop_data.src_addr;
          nxt_beats_d = (cf_pop_data.beats + BEATS_W'(3)) >> 2;
          aw_state_d  = AW_ISSUE;
        end
      end
      AW_ISSUE: begin
        // A burst goes out only when its W bookkeeping has room and the B budget allows.
        if (wq_push_ready && (outst_q < OUT_W'(MAX_OUT))) begin
          aw_addr_d  = cur_addr_q;
          aw_burst_d = '{src: cur_src_q, beats: burst_beats};
          cur_addr_d = cur_addr_q + {23'b0, burst_beats, 2'b0};
          left_d     = left_q - burst_beats;
          aw_state_d = AW_WAIT;
        end
      end
      AW_WAIT: begin
        if (m_axi_awready) begin
          if (left_q != '0) begin
            aw_state_d = AW_ISSUE;
          end else if (!cur_src_q && src_en_i) begin
            cur_src_d  = 1'b1;
            cur_addr_d = nxt_addr_q;
            left_d     = nxt_beats_q;
            aw_state_d = AW_ISSUE;
          end else begin
            aw_state_d = AW_IDLE;
          end
        end
      end
      default: aw_state_d = AW_IDLE;
    endcase

    outst_d = outst_q + OUT_W'(aw_hs) - OUT_W'(b_hs);
  end

  assign m_axi_awid    = '0;
  assign m_axi_awaddr  = aw_addr_q;
  assign m_axi_awlen   = 8'(aw_burst_q.beats - 1'b1);
  assign m_axi_awsize  = 3'b010;     // 4 bytes per beat
  assign m_axi_awburst = 2'b01;      // INCR
  assign m_axi_awlock  = 1'b0;
  assign m_axi_awcache = 4'b0011;    // normal, non-cacheable, bufferable
  assign m_axi_awprot  = 3'b000;
  assign m_axi_awvalid = (aw_state_q == AW_WAIT);

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      aw_state_q  <= AW_IDLE;
      cur_addr_q  <= '0;
      left_q      <= '0;
      cur_src_q   <= 1'b0;
      nxt_addr_q  <= '0;
      nxt_beats_q <= '0;
      aw_addr_q   <= '0;
      aw_burst_q  <= '0;
      outst_q     <= '0;
    end else if (clear_i) begin
      aw_state_q  <= AW_IDLE;
      cur_addr_q  <= '0;
      left_q      <= '0;
      cur_src_q   <= 1'b0;
      nxt_addr_q  <= '0;
      nxt_beats_q <= '0;
      aw_addr_q   <= '0;
      aw_burst_q  <= '0;
      outst_q     <= '0;
    end else begin
      aw_state_q  <= aw_state_d;
      cur_addr_q  <= cur_addr_d;
      left_q      <= left_d;
      cur_src_q   <= cur_src_d;
      nxt_addr_q  <= nxt_addr_d;
      nxt_beats_q <= nxt_beats_d;
      aw_addr_q   <= aw_addr_d;
      aw_burst_q  <= aw_burst_d;
      outst_q     <= outst_d;
    end
  end

  // ---- W: the beats of each accepted burst, in order --------------------------------------------
  logic [BEATS_W-1:0] wcnt_q, wcnt_d;
  logic               w_hs;

  sys_fifo #(.WIDTH($bits(burst_t)), .DEPTH(4)) u_burst_fifo (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .flush_i (clear_i),
    .valid_i (aw_hs),
    .ready_o (wq_push_ready),
    .data_i  (aw_burst_q),
    .valid_o (wq_pop_valid),
    .ready_i (wq_pop),
    .data_o  (wq_pop_data)
  );

  always_comb begin
    m_axi_wvalid = wq_pop_valid && (wq_pop_data.src ? sf_pop_valid : pf_pop_valid);
    m_axi_wdata  = wq_pop_data.src ? sf_pop_data.data : pf_pop_data;
    m_axi_wstrb  = wq_pop_data.src ? sf_pop_data.strb : 4'hF;
    m_axi_wlast  = (wcnt_q + 1'b1 == wq_pop_data.beats);
    w_hs         = m_axi_wvalid && m_axi_wready;
    pf_pop       = w_hs && !wq_pop_data.src;
    sf_pop       = w_hs && wq_pop_data.src;
    wq_pop       = w_hs && m_axi_wlast;
    wcnt_d       = wcnt_q;
    if (w_hs) wcnt_d = m_axi_wlast ? '0 : wcnt_q + 1'b1;
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      wcnt_q <= '0;
    end else if (clear_i) begin
      wcnt_q <= '0;
    end else begin
      wcnt_q <= wcnt_d;
    end
  end

  // ---- B ----------------------------------------------------------------------------------------
  assign m_axi_bready = 1'b1;
  assign bresp_err_o  = b_hs && m_axi_bresp[1];
  assign idle_o       = (aw_state_q == AW_IDLE) && !cf_pop_valid && !wq_pop_valid &&
                        (outst_q == '0);

  logic unused_b;
  assign unused_b = ^{m_axi_bid, m_axi_bresp[0]};   // single ID (in-order B); EXOKAY cannot occur

`ifndef SYNTHESIS
  // Lint: disable iff (!rst_ni) looks like a synchronous use of the asynchronous reset.
  /* verilator lint_off SYNCASYNCNET */
  // AXI: an offered address stays until taken; a row never has more than 32 pixels.
  assert property (@(posedge clk_i) disable iff (!rst_ni || clear_i)
                   m_axi_awvalid && !m_axi_awready |=> m_axi_awvalid && $stable(m_axi_awaddr));
  assert property (@(posedge clk_i) disable iff (!rst_ni || clear_i)
                   m_axi_wvalid && !m_axi_wready |=> m_axi_wvalid && $stable(m_axi_wdata));
  assert property (@(posedge clk_i) disable iff (!rst_ni || clear_i)
                   b_hs |-> outst_q != '0);
`endif
endmodule
