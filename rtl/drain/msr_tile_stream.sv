// Output streamer: reads a finished tile from the tile buffer row-major and emits it as a
// valid/ready pixel stream in global coordinates (claim 10's hand-over to the frame
// buffer). Read data arrives RD_LAT + 1 cycles after the address (the tile buffer's read and
// the register behind it). Reads are issued only when the skid FIFO has room for every
// read in flight, so a stalled consumer never loses data and a ready consumer gets one pixel
// per clock.
//
// CYCLE > 1 (a macro whose port takes an address once per CYCLE clocks): the context sends the
// reads to its two copies in turn (msr_tile_ctx), so a read may go when the read two before it
// went CYCLE clocks ago or more: two pixels per CYCLE clocks.
`include "msr_flops.svh"

module msr_tile_stream
  import msr_pkg::*;
#(
  parameter int unsigned RD_LAT     = 1,  // the tile buffer's read latency (1..4)
  // the skid FIFO: the reads in flight, one pixel in the FIFO and one more keep a pixel a clock
  parameter int unsigned FIFO_DEPTH = (RD_LAT + 3 <= 4) ? 4 : 8,
  parameter int unsigned DEPTH_EN   = 0,  // 1: each pixel's inverse depth beside it (else 0)
  parameter int unsigned CYCLE      = 1   // clocks between two reads of one copy (1..8)
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  input  logic                 clear_i,      // synchronous soft reset
  input  logic                 start_valid_i, // a finished tile to stream
  output logic                 start_ready_o,
  input  coord_t               x0_i,         // tile origin and size
  input  coord_t               y0_i,
  input  ldim_t                w_i,
  input  ldim_t                h_i,
  output logic                 re_o,         // tile buffer read port
  output logic [TADDR_W-1:0]   raddr_o,
  input  rgb_t                 rdata_rgb_i,  // RD_LAT + 1 cycles after re_o
  input  src_t                 rdata_src_i,
  input  logic [15:0]          rdata_invz_i, // DEPTH_EN: with rdata_rgb_i
  output logic                 pix_valid_o,  // pixel stream
  input  logic                 pix_ready_i,
  output pix_word_t            pix_o,        // global x, y, colour, source code, last of tile
  output logic [15:0]          pix_invz_o,   // DEPTH_EN: the pixel's inverse depth
  output logic                 done_o,       // pulse: last pixel taken
  // whole rows waiting (for msr_row_merge, which passes one streamer's row at a time)
  output logic                 row_ready_o,  // the FIFO holds a whole row of the tile (registered)
  output logic                 row_end_o     // pix_o is the last pixel of its row
);

  localparam int unsigned CNT_W = $clog2(FIFO_DEPTH + 1);

  if (FIFO_DEPTH < 2 || (FIFO_DEPTH & (FIFO_DEPTH - 1)) != 0) begin : g_check_depth
    $fatal(1, "msr_tile_stream: FIFO_DEPTH %0d must be a power of two >= 2", FIFO_DEPTH);
  end
  if (RD_LAT < 1 || RD_LAT > 4 || FIFO_DEPTH < RD_LAT + 2) begin : g_check_rd_lat
    $fatal(1, "msr_tile_stream: RD_LAT %0d must be in 1..4 and below FIFO_DEPTH - 1", RD_LAT);
  end

  logic    active_q;
  coord_t  x0_q, y0_q;
  lcoord_t wm1_q, hm1_q;
  lcoord_t rx_q, ry_q;          // next pixel to read
  logic    rd_done_q;           // all reads issued

  // Reads in flight (data arrives RD_LAT + 1 cycles after the read) and their coordinates.
  localparam int unsigned NPEND = RD_LAT + 1;
  logic    [NPEND-1:0] rd_pend_q;
  lcoord_t [NPEND-1:0] pend_x_q, pend_y_q;
  logic    [NPEND-1:0] pend_last_q;

  // Skid FIFO: a push always finds room (issue counts the reads in flight), so its ready is
  // not needed.
  pix_word_t        push_word, pop_word;
  logic [CNT_W-1:0] cnt;
  /* verilator lint_off UNUSEDSIGNAL */
  logic             fifo_ready;
  /* verilator lint_on UNUSEDSIGNAL */

  logic push, pop, issue, last_rd;

  assign start_ready_o = !active_q;
  assign last_rd  = (rx_q == wm1_q) && (ry_q == hm1_q);
  // room for the reads in flight plus this one, without looking at this cycle's pop
  logic port_rested;                   // the copy this read goes to has rested CYCLE clocks
  assign issue    = active_q && !rd_done_q && port_rested &&
                    (32'(cnt) + $countones(rd_pend_q) < FIFO_DEPTH);

  // Ages of the last two reads (saturating at CYCLE): the next read goes to the copy of the
  // one before the last.
  if (CYCLE > 1) begin : g_cycle
    localparam int unsigned AW = $clog2(CYCLE + 1);
    logic [AW-1:0] age1_q, age2_q, age1_d, age2_d;
    always_comb begin
      age1_d = (age1_q < AW'(CYCLE)) ? age1_q + AW'(1) : age1_q;
      age2_d = (age2_q < AW'(CYCLE)) ? age2_q + AW'(1) : age2_q;
      if (issue) begin
        age2_d = age1_d;
        age1_d = AW'(1);
      end
    end
    `MSR_CLR_REG_RST(u_age_q, 2 * AW, {AW'(CYCLE), AW'(CYCLE)}, clear_i, 1'b1,
                     {age1_d, age2_d}, {age1_q, age2_q})
    assign port_rested = (age2_q >= AW'(CYCLE));
  end else begin : g_every_clock
    assign port_rested = 1'b1;
  end
  assign push     = rd_pend_q[NPEND-1];
  assign pop      = pix_valid_o && pix_ready_i;
  assign re_o     = issue;
  assign raddr_o  = {ry_q, rx_q};

  assign pix_o       = pop_word;
  assign done_o      = pop && pop_word.last;

  // Rows whose last pixel is in the FIFO: a pushed row end counts one up, a popped one down.
  // A FIFO that holds every read in flight and a whole row (FIFO_DEPTH >= MAX_TILE + RD_LAT + 2
  // where the rows are merged) always completes a row, so a merge that waits for one cannot
  // wait forever.
  logic             push_row_end;
  logic [CNT_W-1:0] rows_q, rows_d;
  assign push_row_end = push && (pend_x_q[NPEND-1] == wm1_q);
  assign row_end_o    = (pop_word.x == x0_q + coord_t'(wm1_q));
  assign rows_d       = rows_q + CNT_W'(push_row_end) - CNT_W'(pop && row_end_o);
  `MSR_CLR_REG(u_rows_q, CNT_W + 1, clear_i, 1'b1, {rows_d, rows_d != '0}, {rows_q, row_ready_o})

  // The read state: the clear stops a stream (active, all reads issued, reads in flight); the
  // tile's origin, size and read position hold through it and are loaded at the next start.
  logic       active_d, rd_done_d;
  always_comb begin
    active_d  = active_q;
    rd_done_d = rd_done_q;
    if (start_valid_i && start_ready_o) begin
      active_d  = 1'b1;
      rd_done_d = 1'b0;
    end
    if (issue && last_rd) rd_done_d = 1'b1;
    if (done_o) active_d = 1'b0;
  end

  `MSR_CLR_REG(u_ctl_q, 2 + NPEND, clear_i, 1'b1,
               {active_d, rd_done_d, NPEND'({rd_pend_q, issue})}, {active_q, rd_done_q, rd_pend_q})

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      x0_q        <= '0;
      y0_q        <= '0;
      wm1_q       <= '0;
      hm1_q       <= '0;
      rx_q        <= '0;
      ry_q        <= '0;
      pend_x_q    <= '0;
      pend_y_q    <= '0;
      pend_last_q <= '0;
    end else if (!clear_i) begin           // held through a clear, loaded again at the start
      if (start_valid_i && start_ready_o) begin
        x0_q      <= x0_i;
        y0_q      <= y0_i;
        wm1_q     <= lcoord_t'(w_i - 1'b1);
        hm1_q     <= lcoord_t'(h_i - 1'b1);
        rx_q      <= '0;
        ry_q      <= '0;
      end
      pend_x_q    <= (NPEND * LCOORD_W)'({pend_x_q, rx_q});
      pend_y_q    <= (NPEND * LCOORD_W)'({pend_y_q, ry_q});
      pend_last_q <= NPEND'({pend_last_q, last_rd && issue});
      if (issue && !last_rd) begin
        if (rx_q == wm1_q) begin
          rx_q <= '0;
          ry_q <= ry_q + 1'b1;
        end else begin
          rx_q <= rx_q + 1'b1;
        end
      end
    end
  end

  assign push_word = '{x: x0_q + coord_t'(pend_x_q[NPEND-1]), y: y0_q + coord_t'(pend_y_q[NPEND-1]),
                      rgb: rdata_rgb_i, src: rdata_src_i, last: pend_last_q[NPEND-1]};

  msr_fifo #(.WIDTH($bits(pix_word_t)), .DEPTH(FIFO_DEPTH)) u_fifo (
    .clk_i,
    .rst_ni,
    .flush_i (clear_i),
    .valid_i (push),
    .ready_o (fifo_ready),
    .data_i  (push_word),
    .valid_o (pix_valid_o),
    .ready_i (pix_ready_i),
    .data_o  (pop_word),
    .count_o (cnt)
  );

  // The inverse depth in a FIFO of its own, pushed and popped with the pixel's.
  if (DEPTH_EN != 0) begin : g_depth
    /* verilator lint_off UNUSEDSIGNAL */
    logic             invz_ready, invz_valid;
    logic [CNT_W-1:0] invz_cnt;
    /* verilator lint_on UNUSEDSIGNAL */
    msr_fifo #(.WIDTH(16), .DEPTH(FIFO_DEPTH)) u_invz_fifo (
      .clk_i,
      .rst_ni,
      .flush_i (clear_i),
      .valid_i (push),
      .ready_o (invz_ready),
      .data_i  (rdata_invz_i),
      .valid_o (invz_valid),
      .ready_i (pix_ready_i),
      .data_o  (pix_invz_o),
      .count_o (invz_cnt)
    );
  end else begin : g_no_depth
    /* verilator lint_off UNUSEDSIGNAL */
    logic [15:0] invz_unused;
    /* verilator lint_on UNUSEDSIGNAL */
    assign invz_unused = rdata_invz_i;
    assign pix_invz_o  = '0;
  end

`ifndef SYNTHESIS
  // Lint: disable iff (!rst_ni) looks like a synchronous use of the asynchronous reset.
  /* verilator lint_off SYNCASYNCNET */
  a_pix_hold : assert property (@(posedge clk_i) disable iff (!rst_ni || clear_i || $time == 0)
      pix_valid_o && !pix_ready_i |=> pix_valid_o &&
        $stable(pix_o))
    else $error("msr_tile_stream: pixel changed while stalled");
  a_no_overflow : assert property (@(posedge clk_i) disable iff (!rst_ni || $time == 0)
      push |-> 32'(cnt) < FIFO_DEPTH)
    else $error("msr_tile_stream: FIFO overflow");
  a_no_wrap : assert property (@(posedge clk_i) disable iff (!rst_ni || clear_i || $time == 0)
      32'(cnt) + $countones(rd_pend_q) <= FIFO_DEPTH)
    else $error("msr_tile_stream: reads in flight beyond the FIFO");
  /* verilator lint_on SYNCASYNCNET */
`endif

endmodule : msr_tile_stream
