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
// An input slice per input (here: the writer's end of the wire from the engines, with the
// row-end test), then four units, wired here:
//   msr_fbw_rowbuf  per input a ring of three row buffers: pixels and codes in, lane by lane;
//   msr_fbw_addr    the address pipeline, one row per clock: pick (round robin over the inputs
//                   with a complete row) -> y, x0, length -> each plane's row address, base +
//                   y*stride + x0 term (no multiplier) -> the burst shapes, into a short queue;
//   msr_fbw_aw      the row's bursts (up to two per plane: a 4 KiB split) from a register list
//                   onto AW within the budget of MAX_OUT outstanding bursts; the B responses;
//   msr_fbw_w       the beats of each burst, in order: W1 registers the next beat's buffer
//                   address, strobes and WLAST, W2 reads the buffer into the W output register;
//                   a row's buffer is free once W2 reads its last beat.
// Three buffers per input hide the pipeline's latency (about 14 clocks from a row's last pixel
// to its buffer being free) at the smallest tile (a row of 8 pixels every 8 clocks per input).
//
// Throughput: a 16-pixel row with its codes takes 2 + 1 beats of 256 bits when the frame
// buffer is 32-byte aligned, so four engines at one pixel per clock each fit with room (5.3
// pixels per clock); 128 bits would cap the writer at 3.2 pixels per clock.
`include "msr_assert.svh"
`include "msr_flops.svh"
`include "msr_fbw_types.svh"
`include "msr_axi_ports.svh"

module msr_fb_writer import msr_pkg::*; import msr_fbw_pkg::*; #(
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
  // Status.
  output logic              idle_o,          // no complete row waiting, no burst open/outstanding
  output logic [NUM_IN-1:0] tile_done_o,     // pulse per input: the last pixel of a tile taken
  output logic              bresp_err_o,     // pulse: a write response was SLVERR or DECERR
  output logic [31:0]       bresp_addr_o,    // with bresp_err_o: the address of that burst
  output logic              b_unexpected_o,  // pulse: a write response with no burst outstanding
  // AXI4 write master (no read channels).
  `MSR_AXI_WR_MASTER_PORTS(ID_W, AXI_DATA_W)
);
  localparam int unsigned IN_W    = (NUM_IN > 1) ? $clog2(NUM_IN) : 1;
  localparam int unsigned WPB     = AXI_DATA_W / 32;                 // 32-bit lanes per beat
  localparam int unsigned MA_W    = $clog2(NBUF * pix_beats(WPB));   // row-buffer beat address
  localparam int unsigned BB_W    = $clog2(STRB_W);                  // byte offset in a beat

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

  typedef logic [IN_W-1:0] in_t;
  typedef `MSR_FBW_ROW_T(IN_W, MA_W, BB_W) row_t;
  typedef `MSR_FBW_WBURST_T(IN_W, MA_W, BB_W) wburst_t;

  // The ports' bundles.
  fb_cfg_t                fb;
  pix_word_t [NUM_IN-1:0] pix;
  assign fb = '{fb_base: fb_base_i, fb_stride: fb_stride_i, src_en: src_en_i,
                src_base: src_base_i, src_stride: src_stride_i};
  for (genvar i = 0; i < NUM_IN; i++) begin : g_pix
    assign pix[i] = '{x: pix_x_i[i], y: pix_y_i[i], rgb: pix_rgb_i[i], src: pix_src_i[i],
                      last: pix_last_i[i]};
  end

  // ---- The frame's settings, a registered copy at the writer ------------------------------
  // The settings come from the configuration controller's latch across the die; the stride
  // multiples' adders and the input slices' row-end test read this copy instead (that wire
  // set the default top's clock on ECP5). The settings are
  // constant during a frame and reach the copy a clock after START, long before the frame's
  // first pixel (a_frame_settled).
  fb_cfg_t    fb_q;
  tile_size_e tile_q;
  dim_t       last_x_q;
  `MSR_CLR_REG(u_frame_q, $bits(fb_cfg_t) + $bits(tile_size_e) + $bits(dim_t), 1'b0, 1'b1,
               {fb, tile_i, width_i - 1'b1}, {fb_q, tile_q, last_x_q})

  // ---- Input slices: the writer's end of the wire from the engines -------------------------
  // A pixel's row-end test (x mod T == T-1 or x == W-1) is taken on the way in and travels with
  // it as a registered bit: the row buffers' flags then see a register, not a comparator behind
  // the wire (that decode set the default top's clock on ECP5).
  lcoord_t                tmask;
  logic      [NUM_IN-1:0] sl_valid, sl_ready, sl_end;
  pix_word_t [NUM_IN-1:0] sl_pix;
  assign tmask = tile_mask(tile_q);

  for (genvar i = 0; i < NUM_IN; i++) begin : g_in_slice
    logic in_end;
    assign in_end = ((pix[i].x[LCOORD_W-1:0] & tmask) == tmask)
                 || (dim_t'(pix[i].x) == last_x_q);
    msr_spill_reg #(.WIDTH($bits(pix_word_t) + 1)) u_in_slice (
      .clk_i   (clk_i),
      .rst_ni  (rst_ni),
      .clear_i (clear_i),
      .valid_i (pix_valid_i[i]),
      .ready_o (pix_ready_o[i]),
      .data_i  ({in_end, pix[i]}),
      .valid_o (sl_valid[i]),
      .ready_i (sl_ready[i]),
      .data_o  ({sl_end[i], sl_pix[i]})
    );
  end

  // Row buffers <-> address pipeline: complete rows, their take, their metadata.
  logic [NUM_IN-1:0] row_pend, take;
  buf_t [NUM_IN-1:0] pick;
  in_t               meta_in;
  buf_t              meta_buf;
  row_meta_t         meta;
  // Address pipeline -> AW side: addressed rows.
  logic              row_valid, row_ready_aw;
  row_t              row;
  // AW side -> W side: bursts whose address went out.
  logic              wb_push, wb_room;
  wburst_t           wb;
  // W side <-> row buffers: beat reads, buffer release.
  logic [NUM_IN-1:0][MA_W-1:0]     raddr;
  in_t                             rd_in;
  logic [WPB-1:0][23:0]            rd_pix;
  logic [WPB-1:0][4*CODE_W-1:0]    rd_code;
  logic              free_valid;
  in_t               free_in;
  buf_t              free_buf;
  logic              idle_rb, idle_addr, idle_aw, idle_w;

  msr_fbw_rowbuf #(.NUM_IN(NUM_IN), .AXI_DATA_W(AXI_DATA_W)) u_rowbuf (
    .clk_i        (clk_i),
    .rst_ni       (rst_ni),
    .clear_i      (clear_i),
    .tile_i       (tile_q),
    .fb_i         (fb_q),
    .pix_valid_i  (sl_valid),
    .pix_ready_o  (sl_ready),
    .pix_i        (sl_pix),
    .pix_row_end_i (sl_end),
    .tile_done_o  (tile_done_o),
    .row_ready_o  (row_pend),
    .pick_o       (pick),
    .take_i       (take),
    .meta_in_i    (meta_in),
    .meta_buf_i   (meta_buf),
    .meta_o       (meta),
    .raddr_i      (raddr),
    .rd_in_i      (rd_in),
    .rd_pix_o     (rd_pix),
    .rd_code_o    (rd_code),
    .free_valid_i (free_valid),
    .free_in_i    (free_in),
    .free_buf_i   (free_buf),
    .idle_o       (idle_rb)
  );

  msr_fbw_addr #(.NUM_IN(NUM_IN), .AXI_DATA_W(AXI_DATA_W), .row_t(row_t)) u_addr (
    .clk_i        (clk_i),
    .rst_ni       (rst_ni),
    .clear_i      (clear_i),
    .fb_i         (fb_q),
    .req_i        (row_pend),
    .pick_i       (pick),
    .take_o       (take),
    .meta_in_o    (meta_in),
    .meta_buf_o   (meta_buf),
    .meta_i       (meta),
    .row_valid_o  (row_valid),
    .row_ready_i  (row_ready_aw),
    .row_o        (row),
    .idle_o       (idle_addr)
  );

  // verilog_lint: waive-start module-port (the bus ports connect by name, macro last)
  msr_fbw_aw #(
    .NUM_IN     (NUM_IN),
    .AXI_DATA_W (AXI_DATA_W),
    .ID_W       (ID_W),
    .MAX_OUT    (MAX_OUT),
    .row_t      (row_t),
    .wburst_t   (wburst_t)
  ) u_aw (
    .clk_i          (clk_i),
    .rst_ni         (rst_ni),
    .clear_i        (clear_i),
    .src_en_i       (fb_q.src_en),
    .row_valid_i    (row_valid),
    .row_ready_o    (row_ready_aw),
    .row_i          (row),
    .wb_push_o      (wb_push),
    .wb_room_i      (wb_room),
    .wb_o           (wb),
    .idle_o         (idle_aw),
    .bresp_err_o    (bresp_err_o),
    .bresp_addr_o   (bresp_addr_o),
    .b_unexpected_o (b_unexpected_o),
    `MSR_AXI_AWB_CONNECT
  );
  // verilog_lint: waive-stop module-port

  // verilog_lint: waive-start module-port (the bus ports connect by name, macro last)
  msr_fbw_w #(.NUM_IN(NUM_IN), .AXI_DATA_W(AXI_DATA_W), .wburst_t(wburst_t)) u_w (
    .clk_i        (clk_i),
    .rst_ni       (rst_ni),
    .clear_i      (clear_i),
    .wb_push_i    (wb_push),
    .wb_room_o    (wb_room),
    .wb_i         (wb),
    .raddr_o      (raddr),
    .rd_in_o      (rd_in),
    .rd_pix_i     (rd_pix),
    .rd_code_i    (rd_code),
    .free_valid_o (free_valid),
    .free_in_o    (free_in),
    .free_buf_o   (free_buf),
    .idle_o       (idle_w),
    `MSR_AXI_W_CONNECT
  );
  // verilog_lint: waive-stop module-port

  assign idle_o = (sl_valid == '0) && idle_rb && idle_addr && idle_aw && idle_w;

  /* verilator lint_off SYNCASYNCNET */
  `MSR_ASSERT_IMP(a_frame_settled, pix_valid_i != '0, fb_q == fb && tile_q == tile_i &&
                               last_x_q == width_i - 1'b1)
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_fb_writer
