// AXI4-Lite slave in front of the register block's CPU interface (PeakRDL-regblock's
// `passthrough` cpuif). Why not the generator's own AXI4-Lite cpuif: it decodes the request
// combinationally from its channel registers (in-flight limit, read/write pick, stall mask,
// address multiplexer) and the register block's write decode follows in the same clock: six
// LUT levels to every control field, the placed top's critical path (docs/handoff.md, section
// 6). Here every signal towards the register block leaves a flip-flop, so a write reaches a
// field through the address compare and the field's own enable only.
//
// Each channel (AW, W, AR) has a one-entry holding register, ready while it is empty. A read
// and a write that are both waiting alternate (read first, unless the last request was a
// read). A request stage holds the picked request until the block takes it (a write waits
// while the block's stall_wr is up, after a read). Responses queue in a FIFO of RSP_DEPTH
// entries; a request is only issued while fewer than RSP_DEPTH are issued and unanswered, so
// the block's acknowledgements, which cannot wait, always find room. A read is answered five
// clocks after its AR handshake at the earliest, a write four after its last of AW / W.
`include "msr_assert.svh"
`include "msr_axi_ports.svh"

module msr_axil_cpuif #(
  parameter int unsigned ADDR_W    = 7,   // byte address bits
  parameter int unsigned DATA_W    = 32,  // data bits
  parameter int unsigned RSP_DEPTH = 4    // responses held (a power of two >= 2)
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,
  // register block, PeakRDL passthrough cpuif (the block's s_cpuif_* ports)
  output logic                  cpuif_req_o,
  output logic                  cpuif_req_is_wr_o,
  output logic [ADDR_W-1:0]     cpuif_addr_o,     // word aligned
  output logic [DATA_W-1:0]     cpuif_wr_data_o,
  output logic [DATA_W-1:0]     cpuif_wr_biten_o,
  input  logic                  cpuif_req_stall_wr_i,
  input  logic                  cpuif_req_stall_rd_i,
  input  logic                  cpuif_rd_ack_i,
  input  logic                  cpuif_rd_err_i,
  input  logic [DATA_W-1:0]     cpuif_rd_data_i,
  input  logic                  cpuif_wr_ack_i,
  input  logic                  cpuif_wr_err_i,
  // AXI4-Lite slave
  `MSR_AXIL_SLAVE_PORTS(ADDR_W, DATA_W)
);
  localparam int unsigned CNT_W = $clog2(RSP_DEPTH) + 1;
  localparam int unsigned RSP_W = 2 + DATA_W;  // {is_wr, err, rdata}

  if (DATA_W % 8 != 0 || ADDR_W < 3) begin : gen_bad_params
    $fatal(1, "msr_axil_cpuif: DATA_W must be a multiple of 8 and ADDR_W >= 3");
  end

  // ---- channel holding registers ------------------------------------------------------------
  logic                aw_full_q, w_full_q, ar_full_q;
  logic [ADDR_W-1:2]   aw_addr_q, ar_addr_q;   // word addresses
  logic [DATA_W-1:0]   w_data_q;
  logic [DATA_W/8-1:0] w_strb_q;

  assign s_axil_awready = !aw_full_q;
  assign s_axil_wready  = !w_full_q;
  assign s_axil_arready = !ar_full_q;

  // ---- request stage --------------------------------------------------------------------------
  logic                req_q, req_is_wr_q;
  logic [ADDR_W-1:0]   req_addr_q;
  logic [DATA_W-1:0]   req_data_q, req_biten_q;
  logic                prev_was_rd_q;
  logic [CNT_W-1:0]    open_q;        // issued and not yet popped as a response

  logic req_taken, stage_free, room, pick_rd, pick_wr, issue, rsp_pop;
  logic [DATA_W-1:0] strb_bits;

  // The block takes the staged request unless it stalls that kind (a write after a read).
  assign req_taken  = req_q && !(req_is_wr_q ? cpuif_req_stall_wr_i : cpuif_req_stall_rd_i);
  assign stage_free = !req_q || req_taken;
  assign room       = open_q < CNT_W'(RSP_DEPTH);
  assign pick_rd    = ar_full_q && (!prev_was_rd_q || !(aw_full_q && w_full_q));
  assign pick_wr    = !pick_rd && aw_full_q && w_full_q;
  assign issue      = stage_free && room && (pick_rd || pick_wr);

  for (genvar b = 0; b < DATA_W / 8; b++) begin : g_biten
    assign strb_bits[b*8 +: 8] = {8{w_strb_q[b]}};
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      aw_full_q     <= 1'b0;
      w_full_q      <= 1'b0;
      ar_full_q     <= 1'b0;
      req_q         <= 1'b0;
      req_is_wr_q   <= 1'b0;
      prev_was_rd_q <= 1'b0;
    end else begin
      if (s_axil_awvalid && s_axil_awready) aw_full_q <= 1'b1;
      else if (issue && pick_wr)            aw_full_q <= 1'b0;
      if (s_axil_wvalid && s_axil_wready)   w_full_q  <= 1'b1;
      else if (issue && pick_wr)            w_full_q  <= 1'b0;
      if (s_axil_arvalid && s_axil_arready) ar_full_q <= 1'b1;
      else if (issue && pick_rd)            ar_full_q <= 1'b0;
      if (issue) begin
        req_q         <= 1'b1;
        req_is_wr_q   <= pick_wr;
        prev_was_rd_q <= pick_rd;
      end else if (req_taken) begin
        req_q <= 1'b0;
      end
    end
  end

  // Payload registers: no reset (loaded before the flag that marks them valid).
  always_ff @(posedge clk_i) begin
    if (s_axil_awvalid && s_axil_awready) aw_addr_q <= s_axil_awaddr[ADDR_W-1:2];
    if (s_axil_arvalid && s_axil_arready) ar_addr_q <= s_axil_araddr[ADDR_W-1:2];
    if (s_axil_wvalid && s_axil_wready) begin
      w_data_q <= s_axil_wdata;
      w_strb_q <= s_axil_wstrb;
    end
    if (issue) begin
      req_addr_q  <= {(pick_wr ? aw_addr_q : ar_addr_q), 2'b00};
      req_data_q  <= w_data_q;
      req_biten_q <= pick_wr ? strb_bits : '0;
    end
  end

  assign cpuif_req_o       = req_q;
  assign cpuif_req_is_wr_o = req_is_wr_q;
  assign cpuif_addr_o      = req_addr_q;
  assign cpuif_wr_data_o   = req_data_q;
  assign cpuif_wr_biten_o  = req_biten_q;

  // ---- responses ------------------------------------------------------------------------------
  logic             rsp_valid;
  logic [RSP_W-1:0] rsp_head;
  logic             rsp_push, rsp_room;
  logic [CNT_W-1:0] rsp_count;
  logic [RSP_W-1:0] rsp_in;

  assign rsp_push = cpuif_rd_ack_i || cpuif_wr_ack_i;
  assign rsp_in   = cpuif_wr_ack_i ? {1'b1, cpuif_wr_err_i, {DATA_W{1'b0}}}
                                   : {1'b0, cpuif_rd_err_i, cpuif_rd_data_i};

  msr_fifo #(.WIDTH(RSP_W), .DEPTH(RSP_DEPTH), .OUT_REG(1'b1)) u_rsp_fifo (
    .clk_i, .rst_ni, .flush_i(1'b0),
    .valid_i(rsp_push), .ready_o(rsp_room),  // never full: open_q bounds what is issued
    .data_i(rsp_in),
    .valid_o(rsp_valid), .ready_i(rsp_pop), .data_o(rsp_head), .count_o(rsp_count)
  );

  assign s_axil_bvalid = rsp_valid && rsp_head[RSP_W-1];
  assign s_axil_rvalid = rsp_valid && !rsp_head[RSP_W-1];
  assign s_axil_bresp  = rsp_head[RSP_W-2] ? 2'b10 : 2'b00;   // SLVERR or OKAY
  assign s_axil_rresp  = rsp_head[RSP_W-2] ? 2'b10 : 2'b00;
  assign s_axil_rdata  = rsp_head[DATA_W-1:0];
  assign rsp_pop       = (s_axil_bvalid && s_axil_bready) || (s_axil_rvalid && s_axil_rready);

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni)                 open_q <= '0;
    else if (issue && !rsp_pop)  open_q <= open_q + 1'b1;
    else if (!issue && rsp_pop)  open_q <= open_q - 1'b1;
  end

  logic unused;
  assign unused = ^{s_axil_awprot, s_axil_arprot, s_axil_awaddr[1:0], s_axil_araddr[1:0],
                   rsp_room, rsp_count};

  // The block answers a read two clocks after taking it and a write in the same clock, and
  // stalls a write for two clocks after a read, so the two acknowledgements never coincide.
  /* verilator lint_off SYNCASYNCNET */
  `MSR_ASSERT(a_acks_apart, !(cpuif_rd_ack_i && cpuif_wr_ack_i))
  `MSR_ASSERT(a_rsp_room, !rsp_push || rsp_room)
  `MSR_ASSERT(a_open_bound, open_q <= CNT_W'(RSP_DEPTH))
  /* verilator lint_on SYNCASYNCNET */
endmodule : msr_axil_cpuif
