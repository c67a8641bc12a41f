// Formal harness of msr_fbw_aw, the frame-buffer writer's AW side: one input, a 32-bit bus,
// two bursts outstanding. Every input free but two environment rules: the W side's room only
// shrinks by a push (as msr_fbw_w's burst queue does), and the frame's src_en is constant.
// Checks (bounded): AW held and stable until taken; the bursts outstanding (AW taken, B
// not yet) counted from the handshakes never pass MAX_OUT, and a B with none outstanding is
// flagged, one with a burst outstanding is not; an error response names the address of the
// oldest outstanding burst; every row taken yields its bursts (one per plane, two when the
// plane crosses 4 KiB; the code plane only with src_en), none lost or duplicated, and exactly
// one of them is marked as the row's last.
`include "msr_fbw_types.svh"

module msr_fbw_aw_fv import msr_fbw_pkg::*; #(
  localparam int unsigned DW      = 32,
  localparam int unsigned MAX_OUT = 2,
  localparam int unsigned MA_W    = $clog2(NBUF * pix_beats(DW / 32)),
  localparam int unsigned BB_W    = $clog2(DW / 8)
) (
  input logic        clk_i, rst_ni, clear_i,
  input logic        src_en_i,
  input logic        row_valid_i,
  input logic [$bits(`MSR_FBW_ROW_T(1, MA_W, BB_W))-1:0] row_bits_i,
  input logic        wb_room_i,
  input logic        awready_i,
  input logic        bvalid_i,
  input logic [1:0]  bresp_i,
  input logic        track_i               // the solver picks the tracked burst with this
);
  typedef `MSR_FBW_ROW_T(1, MA_W, BB_W) row_t;
  typedef `MSR_FBW_WBURST_T(1, MA_W, BB_W) wburst_t;
  row_t        row;
  wburst_t     wb;
  logic        row_ready, wb_push, awvalid, bready, idle, bresp_err, b_unexp;
  logic [31:0] awaddr, bresp_addr;
  logic [7:0]  awlen;
  logic [2:0]  awsize, awprot;
  logic [1:0]  awburst;
  logic [3:0]  awcache;
  logic        awlock;
  logic [0:0]  awid;
  assign row = row_t'(row_bits_i);

  msr_fbw_aw #(.NUM_IN(1), .AXI_DATA_W(DW), .ID_W(1), .MAX_OUT(MAX_OUT), .row_t(row_t),
               .wburst_t(wburst_t)) dut (
    .clk_i, .rst_ni, .clear_i, .src_en_i,
    .row_valid_i, .row_ready_o (row_ready), .row_i (row),
    .wb_push_o (wb_push), .wb_room_i, .wb_o (wb),
    .m_axi_awid (awid), .m_axi_awaddr (awaddr), .m_axi_awlen (awlen), .m_axi_awsize (awsize),
    .m_axi_awburst (awburst), .m_axi_awlock (awlock), .m_axi_awcache (awcache),
    .m_axi_awprot (awprot), .m_axi_awvalid (awvalid), .m_axi_awready (awready_i),
    .m_axi_bid (1'b0), .m_axi_bresp (bresp_i), .m_axi_bvalid (bvalid_i), .m_axi_bready (bready),
    .idle_o (idle), .bresp_err_o (bresp_err), .bresp_addr_o (bresp_addr),
    .b_unexpected_o (b_unexp)
  );

  logic init_q;
  msr_fv_init #(.ONCE(1'b1)) u_init (.clk_i, .rst_ni, .init_o(init_q));

  wire aw_hs   = awvalid && awready_i;
  wire b_hs    = bvalid_i && bready;
  wire take    = row_valid_i && row_ready;

  // Environment: the W side's room only shrinks by a push; src_en constant.
  logic room_q, push_q, src_en_q;
  always_ff @(posedge clk_i) begin
    room_q <= wb_room_i; push_q <= wb_push; src_en_q <= src_en_i;
  end
  always_comb begin
    if (!init_q) begin
      assume (!(room_q && !push_q) || wb_room_i);
      assume (src_en_i == src_en_q);
    end
  end

  // Bursts outstanding by the handshakes, and one tracked burst address (its place among them).
  logic [2:0]  out_q;
  logic        trk_q;
  logic [31:0] trk_addr_q;
  logic [1:0]  trk_pos_q;
  msr_fv_queue_ref #(.WIDTH(32), .DEPTH(MAX_OUT)) u_ref (
    .clk_i, .rst_ni, .clear_i, .push_i(aw_hs), .pop_i(b_hs && out_q != '0), .track_i,
    .data_i(awaddr), .ref_o(out_q), .trk_o(trk_q), .trk_data_o(trk_addr_q), .trk_pos_o(trk_pos_q)
  );

  // Bursts a taken row owes (by its shape), less the bursts pushed to the W side; rows taken
  // less row-last bursts pushed.
  function automatic logic [2:0] nbursts(row_t r, logic src_en);
    return 3'(1) + 3'(r.shape[0].two) + (src_en ? 3'(1) + 3'(r.shape[1].two) : 3'(0));
  endfunction
  logic [3:0] owed_q, rows_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      owed_q <= '0; rows_q <= '0;
    end else if (clear_i) begin
      owed_q <= '0; rows_q <= '0;
    end else begin
      owed_q <= owed_q + (take ? 4'(nbursts(row, src_en_i)) : 4'(0)) - 4'(wb_push);
      rows_q <= rows_q + 4'(take) - 4'(wb_push && wb.row_last);
    end
  end

  // AW held, unchanged, until taken (a clear drops it).
  logic aw_viol;
  msr_chk_stable #(.W(40)) u_aw_hold (
    .clk_i, .rst_ni, .valid_i(awvalid), .ready_i(awready_i || clear_i),
    .payload_i({awaddr, awlen}), .viol_o(aw_viol)
  );

  a_aw_hold:    assert property (@(posedge clk_i) disable iff (!rst_ni || clear_i) !aw_viol);
  a_out_budget: assert property (@(posedge clk_i) disable iff (!rst_ni) out_q <= MAX_OUT);
  a_b_flags:    assert property (@(posedge clk_i) disable iff (!rst_ni)
                                 b_unexp == (b_hs && out_q == '0) && bready);
  a_err_addr:   assert property (@(posedge clk_i) disable iff (!rst_ni)
                                 !(trk_q && trk_pos_q == '0 && bresp_err) || bresp_addr == trk_addr_q);
  a_err:        assert property (@(posedge clk_i) disable iff (!rst_ni)
                                 bresp_err == (b_hs && out_q != '0 && bresp_i[1]));
  a_bursts:     assert property (@(posedge clk_i) disable iff (!rst_ni)
                                 owed_q == 4'($countones(dut.blv_q)) + 4'(dut.aw_sp_valid) +
                                           4'(dut.u_aw_reg.b_full_q));
  a_row_last:   assert property (@(posedge clk_i) disable iff (!rst_ni)
                                 rows_q == 4'(dut.blv_q != '0) + 4'(dut.aw_sp_valid && dut.aw_sp.row_last) +
                                           4'(dut.u_aw_reg.b_full_q && dut.u_aw_reg.b_data_q[0]));
  a_idle:       assert property (@(posedge clk_i) disable iff (!rst_ni) !idle || (owed_q == '0 && out_q == '0));

  // The budget counts the AW register and the bus (the inline a_budget_flags and
  // a_onbus_in_budget of msr_fbw_aw.sv, restated and made exact).
  a_onbus:   assert property (@(posedge clk_i) disable iff (!rst_ni) dut.onbus_q == 2'(out_q));
  a_budget:  assert property (@(posedge clk_i) disable iff (!rst_ni)
                              dut.budget_q == dut.onbus_q + 2'(dut.aw_sp_valid) + 2'(dut.u_aw_reg.b_full_q)
                              && dut.budget_q <= MAX_OUT);
  a_flags:   assert property (@(posedge clk_i) disable iff (!rst_ni)
                              dut.out_ok_q == (dut.budget_q != MAX_OUT) && dut.onbus_nz_q == (dut.onbus_q != '0));
  a_aq:      assert property (@(posedge clk_i) disable iff (!rst_ni) dut.u_addr_fifo.count_q == out_q);
  a_list:    assert property (@(posedge clk_i) disable iff (!rst_ni)
                              dut.blv_q inside {4'b0000, 4'b0001, 4'b0011, 4'b0111, 4'b1111});

  // Non-vacuity: a row with four bursts; a burst waiting on a full budget; an error response
  // with its address.
  c_four:    cover property (@(posedge clk_i) disable iff (!rst_ni) take && nbursts(row, src_en_i) == 3'd4);
  c_full:    cover property (@(posedge clk_i) disable iff (!rst_ni) out_q == MAX_OUT && dut.blv_q[0]);
  c_err:     cover property (@(posedge clk_i) disable iff (!rst_ni) bresp_err && trk_q && trk_pos_q == '0);
endmodule
