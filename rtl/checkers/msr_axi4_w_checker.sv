// AXI4 write-channel protocol checker (AW, W, B), passive: every port an input, so it can be
// instantiated next to an interface or bound to a module's ports (see docs/verification.md,
// "Protocol checkers"). Checks, each a labelled assertion that prints its rule:
//   a_aw_stable   AWVALID held until AWREADY, AW payload stable meanwhile
//   a_w_stable    WVALID held until WREADY, WDATA/WSTRB/WLAST stable meanwhile
//   a_b_stable    BVALID held until BREADY, BID/BRESP stable meanwhile
//   a_wlast       WLAST exactly on beat AWLEN+1 of each burst (bursts in AW order)
//   a_w_early     a W beat before its burst's AW was accepted (this checker needs the AW no
//                 later than the first W beat: stricter than AXI4, true of this project's master)
//   a_4k          an INCR burst does not cross a 4 KiB boundary
//   a_awsize      AWSIZE not wider than the data bus
//   a_b_orphan    no BVALID without a write whose AW and last W beat were both accepted earlier
//   a_capacity    the checker's own limit: at most MAX_OUT bursts between AW and last W, or
//                 between last W and B (raise MAX_OUT when it fires on a legal master)
// The rules are written as plain boolean properties over a few registers (no |-> or |=>), so
// the same file runs in Verilator (--assert) and in yosys's slang front end (make formal).
// viol_o shows each check's violation in the current cycle (for negative tests and waves),
// bit i = the i-th check above.
// Assertions are off in reset and at time 0, plain reset under FORMAL (`MSR_CHK_OFF of
// rtl/prim/msr_assert.svh, the rule of its MSR_ASSERT macros). The handshake rules (valid held,
// payload stable) come from msr_chk_stable.sv, one instance a channel.
`include "msr_assert.svh"
`include "msr_chk_axi.svh"
// Verification IP, not design: no coverage points (make coverage reports the design's lines).
/* verilator coverage_off */
module msr_axi4_w_checker #(
  parameter int unsigned ADDR_W  = 32,
  parameter int unsigned DATA_W  = 64,
  parameter int unsigned ID_W    = 4,
  parameter int unsigned MAX_OUT = 16    // bursts the checker can track (power of two)
) (
  input logic       clk_i,
  input logic       rst_ni,
  `MSR_AXI4_W_PORTS(input, input, ADDR_W, DATA_W, ID_W),   // AW, W, B: passive
  output logic [8:0] viol_o
);
  localparam int unsigned PTR_W  = (MAX_OUT > 1) ? $clog2(MAX_OUT) : 1;
  localparam int unsigned SIZE_MAX = $clog2(DATA_W / 8);
  localparam int unsigned AW_W   = ID_W + ADDR_W + 8 + 3 + 2 + 1 + 4 + 3;
  localparam int unsigned WB_W   = DATA_W + DATA_W / 8 + 1;
  typedef logic [PTR_W:0] cnt_t;

  if (MAX_OUT < 2 || (MAX_OUT & (MAX_OUT - 1)) != 0) begin : g_check_max_out
    $fatal(1, "msr_axi4_w_checker: MAX_OUT %0d must be a power of two >= 2", MAX_OUT);
  end

  wire aw_hs = awvalid && awready;
  wire w_hs  = wvalid && wready;
  wire b_hs  = bvalid && bready;
  logic [8:0] viol;

  // Valid held / payload stable (rules 0-2).
  msr_chk_stable #(.W(AW_W)) u_aw_stable (
    .clk_i, .rst_ni, .valid_i(awvalid), .ready_i(awready),
    .payload_i({awid, awaddr, awlen, awsize, awburst, awlock, awcache, awprot}), .viol_o(viol[0])
  );
  msr_chk_stable #(.W(WB_W)) u_w_stable (
    .clk_i, .rst_ni, .valid_i(wvalid), .ready_i(wready), .payload_i({wdata, wstrb, wlast}),
    .viol_o(viol[1])
  );
  msr_chk_stable #(.W(ID_W + 2)) u_b_stable (
    .clk_i, .rst_ni, .valid_i(bvalid), .ready_i(bready), .payload_i({bid, bresp}),
    .viol_o(viol[2])
  );

  // Bursts whose AW is accepted and whose last W beat is not yet: their AWLEN, in order.
  logic [7:0]       len_q [MAX_OUT];
  logic [PTR_W-1:0] len_wr_q, len_rd_q;
  cnt_t             len_cnt_q;    // entries in len_q
  logic [8:0]       wbeat_q;      // W beats of the current burst so far
  cnt_t             done_q;       // writes complete (AW and last W), waiting for B
  logic             head_valid, w_end, push, pop, done_inc;
  logic [7:0]       head_len;

  assign head_valid = (len_cnt_q != '0) || aw_hs;
  assign head_len   = (len_cnt_q != '0) ? len_q[len_rd_q] : awlen;
  assign w_end      = w_hs && head_valid && (wbeat_q == {1'b0, head_len});
  assign pop        = w_end && (len_cnt_q != '0);
  assign push       = aw_hs && !(w_end && len_cnt_q == '0);
  assign done_inc   = w_end;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      len_wr_q <= '0; len_rd_q <= '0; len_cnt_q <= '0; wbeat_q <= '0; done_q <= '0;
    end else begin
      if (push && len_cnt_q != cnt_t'(MAX_OUT)) len_wr_q <= len_wr_q + 1'b1;
      if (pop) len_rd_q <= len_rd_q + 1'b1;
      if (push && !pop && len_cnt_q != cnt_t'(MAX_OUT)) len_cnt_q <= len_cnt_q + 1'b1;
      else if (pop && !push) len_cnt_q <= len_cnt_q - 1'b1;
      if (w_hs) wbeat_q <= (w_end || wlast) ? '0 : wbeat_q + 1'b1;
      if (done_inc && !b_hs && done_q != cnt_t'(MAX_OUT)) done_q <= done_q + 1'b1;
      else if (b_hs && !done_inc && done_q != '0) done_q <= done_q - 1'b1;
    end
  end
  always_ff @(posedge clk_i) begin
    if (push && len_cnt_q != cnt_t'(MAX_OUT)) len_q[len_wr_q] <= awlen;
  end

  // Bytes of the burst offered on AW, and where it ends inside its 4 KiB page.
  logic [13:0] aw_bytes;
  logic [13:0] aw_end;
  assign aw_bytes = 14'({1'b0, awlen} + 9'd1) << awsize;
  assign aw_end   = 14'(awaddr[11:0]) + aw_bytes;

  assign viol[3] = w_hs && head_valid && (wlast != (wbeat_q == {1'b0, head_len}));
  assign viol[4] = w_hs && !head_valid;
  assign viol[5] = awvalid && awburst == 2'b01 && aw_end > 14'd4096;
  assign viol[6] = awvalid && 32'(awsize) > SIZE_MAX;
  assign viol[7] = bvalid && done_q == '0;
  assign viol[8] = (push && len_cnt_q == cnt_t'(MAX_OUT)) || (done_inc && done_q == cnt_t'(MAX_OUT));
  assign viol_o  = viol;
  // Rules a fault-injection bench turns off while it breaks the protocol on purpose (bit i =
  // check i; tb/msr_top writes it through VPI around a spurious B response); 0 otherwise.
  // viol_o is not masked, so the bench can see the checker flag what it injected.
`ifdef FORMAL
  localparam logic [8:0] mask = '0;
`else
  logic [8:0] mask /* verilator public_flat_rw */ = '0;
`endif
  wire [8:0] chk = viol & ~mask;

`ifndef SYNTHESIS
  /* verilator lint_off SYNCASYNCNET */
  `MSR_CHK_RULE(a_aw_stable, 0,
      ("%m: AXI4 AW: AWVALID dropped or AW payload changed before AWREADY"))
  `MSR_CHK_RULE(a_w_stable, 1,
      ("%m: AXI4 W: WVALID dropped or WDATA/WSTRB/WLAST changed before WREADY"))
  `MSR_CHK_RULE(a_b_stable, 2, ("%m: AXI4 B: BVALID dropped or BID/BRESP changed before BREADY"))
  `MSR_CHK_RULE(a_wlast, 3,
      ("%m: AXI4 W: WLAST=%0d on beat %0d of a burst of AWLEN+1=%0d",
       wlast, wbeat_q + 1, head_len + 1))
  `MSR_CHK_RULE(a_w_early, 4, ("%m: AXI4 W: a beat before its AW (this checker wants AW first)"))
  `MSR_CHK_RULE(a_4k, 5,
      ("%m: AXI4 AW: burst at 0x%0h of %0d bytes crosses 4 KiB", awaddr, aw_bytes))
  `MSR_CHK_RULE(a_awsize, 6, ("%m: AXI4 AW: AWSIZE %0d wider than the %0d-bit bus", awsize, DATA_W))
  `MSR_CHK_RULE(a_b_orphan, 7, ("%m: AXI4 B: BVALID with no completed write outstanding"))
  `MSR_CHK_RULE(a_capacity, 8,
      ("%m: AXI4 checker: more than MAX_OUT=%0d bursts in flight", MAX_OUT))
  /* verilator lint_on SYNCASYNCNET */
`endif

endmodule : msr_axi4_w_checker
/* verilator coverage_on */
