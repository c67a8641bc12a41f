// Frame-buffer writer, W side: the beats of each burst whose address went out on AW, in order,
// read from the row buffers onto the AXI4 W channel.
//
// W1 registers the next beat's buffer address (to the copy of the input it reads), strobes
// and WLAST; W2 reads the buffer at that address (LUT RAM, asynchronous) into the W output
// register. A row's buffer is free once W2 reads its last beat (free_*_o, registered).
`include "msr_assert.svh"
`include "msr_flops.svh"
`include "msr_fbw_types.svh"
`include "msr_axi_ports.svh"

module msr_fbw_w import msr_fbw_pkg::*; #(
  parameter int unsigned NUM_IN     = 4,     // pixel streams (engines)
  parameter int unsigned AXI_DATA_W = 256,   // AXI data width: 32, 64, 128 or 256
  localparam int unsigned WPB       = AXI_DATA_W / 32,               // 32-bit lanes per beat
  localparam int unsigned STRB_W    = AXI_DATA_W / 8,
  localparam int unsigned IN_W      = (NUM_IN > 1) ? $clog2(NUM_IN) : 1,
  localparam int unsigned MA_W      = $clog2(NBUF * pix_beats(WPB)),
  localparam int unsigned BB_W      = $clog2(STRB_W),                // byte offset in a beat
  parameter  type         wburst_t  = `MSR_FBW_WBURST_T(IN_W, MA_W, BB_W) // the writer's
) (
  input  logic              clk_i,           // clock
  input  logic              rst_ni,          // asynchronous reset, active low
  input  logic              clear_i,         // synchronous clear
  // Bursts from the AW side.
  input  logic              wb_push_i,       // a burst's address was taken on AW
  output logic              wb_room_o,       // room for another burst
  input  wburst_t           wb_i,            // with wb_push_i: that burst
  // Row-buffer reads.
  output logic [NUM_IN-1:0][MA_W-1:0] raddr_o,   // per input: the beat read
  output logic [IN_W-1:0]   rd_in_o,         // the input whose beat is read
  input  logic [WPB-1:0][23:0]         rd_pix_i,   // its pixel lanes
  input  logic [WPB-1:0][4*CODE_W-1:0] rd_code_i,  // its code lanes (four codes a lane)
  output logic              free_valid_o,    // a buffer's last beat was read:
  output logic [IN_W-1:0]   free_in_o,       //   its input
  output buf_t              free_buf_o,      //   and buffer
  // Status.
  output logic              idle_o,          // no burst queued, no beat on its way out
  // AXI4 write data channel.
  `MSR_AXI_W_MASTER_PORTS(AXI_DATA_W)
);
  typedef logic [IN_W-1:0] in_t;
  typedef logic [MA_W-1:0] maddr_t;

  wburst_t         wq_data;
  logic            wq_valid, wq_pop, w_issue, wlast_d;
  logic [7:0]      wcnt_q;
  logic            wv_q;
  logic [AXI_DATA_W-1:0] wdata_q, wdata_d;
  logic [STRB_W-1:0]     wstrb_q, wstrb_d;
  logic                  wlast_q;
  logic [2:0]            wq_count;
  maddr_t [NUM_IN-1:0]   raddr_q;   // per input: only that input's memories hang on its copy

  msr_fifo #(.WIDTH($bits(wburst_t)), .DEPTH(4)) u_burst_fifo (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .flush_i (clear_i),
    .valid_i (wb_push_i),
    .ready_o (wb_room_o),
    .data_i  (wb_i),
    .valid_o (wq_valid),
    .ready_i (wq_pop),
    .data_o  (wq_data),
    .count_o (wq_count)
  );

  logic                  w1_v_q, w1_last_q, w1_src_q, w1_row_last_q, w2_load;
  in_t                   w1_in_q;
  buf_t                  w1_buf_q;
  logic [STRB_W-1:0]     w1_strb_q;
  logic                  row_free_q;
  in_t                   row_free_in_q;
  buf_t                  row_free_buf_q;

  assign w2_load = w1_v_q && (!wv_q || m_axi_wready);
  assign w_issue = wq_valid && (!w1_v_q || w2_load);
  assign wlast_d = (wcnt_q == wq_data.len);
  assign wq_pop  = w_issue && wlast_d;

  // Registered: the buffers' flags sit with their inputs, spread over the die, and the W side
  // is in one place; a buffer is free a clock after its last beat is read.
  `MSR_CLR_REG(u_row_free, 1, clear_i, 1'b1, w2_load && w1_last_q && w1_row_last_q, row_free_q)
  always_ff @(posedge clk_i) begin
    row_free_in_q  <= w1_in_q;
    row_free_buf_q <= w1_buf_q;
  end
  assign free_valid_o = row_free_q;
  assign free_in_o    = row_free_in_q;
  assign free_buf_o   = row_free_buf_q;

  assign rd_in_o = w1_in_q;
  always_comb begin
    for (int unsigned j = 0; j < WPB; j++) begin
      logic [4*CODE_W-1:0] c;
      c = rd_code_i[j];
      if (w1_src_q) begin
        wdata_d[32*j +: 32] = {3'b0, c[3*CODE_W +: CODE_W], 3'b0, c[2*CODE_W +: CODE_W],
                               3'b0, c[CODE_W +: CODE_W], 3'b0, c[0 +: CODE_W]};
      end else begin
        wdata_d[32*j +: 32] = {8'h00, rd_pix_i[j]};
      end
    end
    for (int unsigned b = 0; b < STRB_W; b++) begin
      wstrb_d[b] = (wcnt_q != '0 || b >= 32'(wq_data.lo)) && (!wlast_d || b <= 32'(wq_data.hi));
    end
  end

  // W1 fills on an issue and empties into W2; W2 fills from W1 and empties on WREADY.
  `MSR_CLR_REG(u_w_v, 2, clear_i, 1'b1,
               {w_issue || (w1_v_q && !w2_load), w2_load || (wv_q && !m_axi_wready)},
               {w1_v_q, wv_q})
  // The beat of the burst at the queue's head.
  `MSR_CLR_REG(u_wcnt, 8, clear_i, w_issue, wlast_d ? '0 : wcnt_q + 1'b1, wcnt_q)
  // The beat's buffer address goes only to the copy of the input it reads (the others keep
  // theirs: their read data is not selected), so each copy drives a quarter of the memories.
  for (genvar i = 0; i < NUM_IN; i++) begin : g_raddr
    always_ff @(posedge clk_i) begin
      if (w_issue && wq_data.in == in_t'(i)) begin
        raddr_q[i] <= maddr_t'(32'(wq_data.mbase) + 32'(wcnt_q));
      end
    end
  end
  assign raddr_o = raddr_q;

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

  assign idle_o = !wq_valid && !w1_v_q && !wv_q;

  logic unused;
  assign unused = ^wq_count;

  /* verilator lint_off SYNCASYNCNET */
  `MSR_ASSERT_NXT(a_w_stable, m_axi_wvalid && !m_axi_wready,
              m_axi_wvalid && $stable({m_axi_wdata, m_axi_wstrb, m_axi_wlast}), clk_i,
              !rst_ni || clear_i)
  `MSR_ASSERT_IMP(a_wb_room, wb_push_i, wb_room_o)
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_fbw_w
