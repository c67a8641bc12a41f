// AXI4-Lite protocol checker (both directions: AW, W, B and AR, R), passive: every port an
// input, for instantiation or `bind` to a module's ports (docs/verification.md, "Protocol
// checkers"). Checks, each a labelled assertion that prints its rule:
//   a_aw_stable  AWVALID held until AWREADY, AWADDR/AWPROT stable meanwhile
//   a_w_stable   WVALID held until WREADY, WDATA/WSTRB stable meanwhile
//   a_b_stable   BVALID held until BREADY, BRESP stable meanwhile
//   a_ar_stable  ARVALID held until ARREADY, ARADDR/ARPROT stable meanwhile
//   a_r_stable   RVALID held until RREADY, RDATA/RRESP stable meanwhile
//   a_b_orphan   no BVALID unless a write (its AW and its W both accepted earlier) is unanswered
//   a_r_orphan   no RVALID unless a read (its AR accepted earlier) is unanswered
//   a_capacity   the checker's own limit: at most MAX_OUT requests per channel unanswered
// Plain boolean properties over a few registers: the same file runs in Verilator (--assert) and
// in yosys's slang front end (make formal). viol_o: bit i = the i-th check above, this cycle.
// Assertions are off in reset and at time 0, plain reset under FORMAL (`MSR_CHK_OFF of
// rtl/prim/msr_assert.svh, the rule of its MSR_ASSERT macros). The handshake rules (valid held,
// payload stable) come from msr_chk_stable.sv, one instance a channel.
`include "msr_assert.svh"
`include "msr_chk_axi.svh"
// Verification IP, not design: no coverage points (make coverage reports the design's lines).
/* verilator coverage_off */
module msr_axil_checker #(
  parameter int unsigned ADDR_W  = 32,
  parameter int unsigned DATA_W  = 32,
  parameter int unsigned MAX_OUT = 15    // requests per channel the checker can count
) (
  input logic       clk_i,
  input logic       rst_ni,
  `MSR_AXIL_PORTS(input, input, ADDR_W, DATA_W),   // every AXI4-Lite signal, passive
  output logic [7:0] viol_o
);
  localparam int unsigned CNT_W = $clog2(MAX_OUT + 1);
  typedef logic [CNT_W-1:0] cnt_t;
  localparam cnt_t CNT_MAX = cnt_t'(MAX_OUT);

  wire aw_hs = awvalid && awready;
  wire w_hs  = wvalid && wready;
  wire b_hs  = bvalid && bready;
  wire ar_hs = arvalid && arready;
  wire r_hs  = rvalid && rready;
  logic [7:0] viol;

  // Valid held / payload stable (rules 0-4).
  msr_chk_stable #(.W(ADDR_W + 3)) u_aw_stable (
    .clk_i, .rst_ni, .valid_i(awvalid), .ready_i(awready), .payload_i({awaddr, awprot}),
    .viol_o(viol[0])
  );
  msr_chk_stable #(.W(DATA_W + DATA_W / 8)) u_w_stable (
    .clk_i, .rst_ni, .valid_i(wvalid), .ready_i(wready), .payload_i({wdata, wstrb}),
    .viol_o(viol[1])
  );
  msr_chk_stable #(.W(2)) u_b_stable (
    .clk_i, .rst_ni, .valid_i(bvalid), .ready_i(bready), .payload_i(bresp), .viol_o(viol[2])
  );
  msr_chk_stable #(.W(ADDR_W + 3)) u_ar_stable (
    .clk_i, .rst_ni, .valid_i(arvalid), .ready_i(arready), .payload_i({araddr, arprot}),
    .viol_o(viol[3])
  );
  msr_chk_stable #(.W(DATA_W + 2)) u_r_stable (
    .clk_i, .rst_ni, .valid_i(rvalid), .ready_i(rready), .payload_i({rdata, rresp}),
    .viol_o(viol[4])
  );

  cnt_t aw_out_q, w_out_q, ar_out_q;   // accepted, not yet answered
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      aw_out_q <= '0; w_out_q <= '0; ar_out_q <= '0;
    end else begin
      // saturating: a_capacity reports the overflow, a_*_orphan the underflow
      if (aw_hs && !b_hs && aw_out_q != CNT_MAX) aw_out_q <= aw_out_q + 1'b1;
      else if (!aw_hs && b_hs && aw_out_q != '0) aw_out_q <= aw_out_q - 1'b1;
      if (w_hs && !b_hs && w_out_q != CNT_MAX) w_out_q <= w_out_q + 1'b1;
      else if (!w_hs && b_hs && w_out_q != '0) w_out_q <= w_out_q - 1'b1;
      if (ar_hs && !r_hs && ar_out_q != CNT_MAX) ar_out_q <= ar_out_q + 1'b1;
      else if (!ar_hs && r_hs && ar_out_q != '0) ar_out_q <= ar_out_q - 1'b1;
    end
  end

  assign viol[5] = bvalid && (aw_out_q == '0 || w_out_q == '0);
  assign viol[6] = rvalid && ar_out_q == '0;
  assign viol[7] = (aw_hs && !b_hs && aw_out_q == CNT_MAX) || (w_hs && !b_hs && w_out_q == CNT_MAX)
                || (ar_hs && !r_hs && ar_out_q == CNT_MAX);
  assign viol_o  = viol;
  // Rules a fault-injection bench turns off while it breaks the protocol on purpose (bit i =
  // check i; tb/msr_top writes it through VPI around a spurious B response); 0 otherwise.
  // viol_o is not masked, so the bench can see the checker flag what it injected.
`ifdef FORMAL
  localparam logic [7:0] mask = '0;
`else
  logic [7:0] mask /* verilator public_flat_rw */ = '0;
`endif
  wire [7:0] chk = viol & ~mask;

`ifndef SYNTHESIS
  /* verilator lint_off SYNCASYNCNET */
  `MSR_CHK_RULE(a_aw_stable, 0,
      ("%m: AXI4-Lite AW: AWVALID dropped or AWADDR/AWPROT changed before AWREADY"))
  `MSR_CHK_RULE(a_w_stable, 1,
      ("%m: AXI4-Lite W: WVALID dropped or WDATA/WSTRB changed before WREADY"))
  `MSR_CHK_RULE(a_b_stable, 2, ("%m: AXI4-Lite B: BVALID dropped or BRESP changed before BREADY"))
  `MSR_CHK_RULE(a_ar_stable, 3,
      ("%m: AXI4-Lite AR: ARVALID dropped or ARADDR/ARPROT changed before ARREADY"))
  `MSR_CHK_RULE(a_r_stable, 4,
      ("%m: AXI4-Lite R: RVALID dropped or RDATA/RRESP changed before RREADY"))
  `MSR_CHK_RULE(a_b_orphan, 5,
      ("%m: AXI4-Lite B: BVALID with no write (AW and W accepted) unanswered"))
  `MSR_CHK_RULE(a_r_orphan, 6, ("%m: AXI4-Lite R: RVALID with no read unanswered"))
  `MSR_CHK_RULE(a_capacity, 7,
      ("%m: AXI4-Lite checker: more than MAX_OUT=%0d requests unanswered", MAX_OUT))
  /* verilator lint_on SYNCASYNCNET */
`endif

endmodule : msr_axil_checker
/* verilator coverage_on */
