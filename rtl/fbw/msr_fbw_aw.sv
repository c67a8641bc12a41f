// Frame-buffer writer, AW side: the addressed rows' bursts onto the AXI4 AW channel within a
// budget of MAX_OUT outstanding bursts, and the B responses.
//
// A row's bursts (up to two per plane: a 4 KiB split) go into a short list, issued from
// registers one per clock through the AW register (msr_spill_reg); each burst whose address is
// taken on AW goes on to the W side (wb_push_o, with its descriptor). Bursts count against the
// budget from the AW register on; B responses are expected only for bursts whose address went
// out on the bus. One ID: B comes in order, and the addresses of the bursts on the bus wait in
// order for theirs (so a failing response names its burst).
`include "msr_assert.svh"
`include "msr_flops.svh"
`include "msr_fbw_types.svh"
`include "msr_axi_ports.svh"

module msr_fbw_aw import msr_fbw_pkg::*; #(
  parameter int unsigned NUM_IN     = 4,     // pixel streams (engines)
  parameter int unsigned AXI_DATA_W = 256,   // AXI data width: 32, 64, 128 or 256
  parameter int unsigned ID_W       = 4,     // AXI ID width (a single ID is used: in-order B)
  parameter int unsigned MAX_OUT    = 8,     // outstanding write bursts
  localparam int unsigned IN_W      = (NUM_IN > 1) ? $clog2(NUM_IN) : 1,
  localparam int unsigned MA_W      = $clog2(NBUF * pix_beats(AXI_DATA_W / 32)),
  localparam int unsigned BB_W      = $clog2(AXI_DATA_W / 8),        // byte offset in a beat
  parameter  type         row_t     = `MSR_FBW_ROW_T(IN_W, MA_W, BB_W),    // the writer's
  parameter  type         wburst_t  = `MSR_FBW_WBURST_T(IN_W, MA_W, BB_W) // the writer's
) (
  input  logic              clk_i,           // clock
  input  logic              rst_ni,          // asynchronous reset, active low
  input  logic              clear_i,         // synchronous clear
  input  logic              src_en_i,        // the code plane is written too
  // Addressed rows from the address pipeline.
  input  logic              row_valid_i,     // an addressed row
  output logic              row_ready_o,     // taken: the list is empty or empties this clock
  input  row_t              row_i,           // the row
  // Bursts to the W side.
  output logic              wb_push_o,       // a burst's address was taken on AW
  input  logic              wb_room_i,       // the W side has room for another burst
  output wburst_t           wb_o,            // with wb_push_o: that burst
  // Status.
  output logic              idle_o,          // no burst listed, in the AW register or outstanding
  output logic              bresp_err_o,     // pulse: a write response was SLVERR or DECERR
  output logic [31:0]       bresp_addr_o,    // with bresp_err_o: the address of that burst
  output logic              b_unexpected_o,  // pulse: a write response with no burst outstanding
  // AXI4 write address and response channels.
  `MSR_AXI_AWB_MASTER_PORTS(ID_W)
);
  localparam int unsigned STRB_W = AXI_DATA_W / 8;
  localparam int unsigned PB     = pix_beats(AXI_DATA_W / 32);
  localparam int unsigned SB     = code_beats(AXI_DATA_W / 32);
  localparam int unsigned OUT_W  = $clog2(MAX_OUT + 1);
  localparam int unsigned AQ_D   = (MAX_OUT < 2) ? 2 : (1 << $clog2(MAX_OUT));

  typedef logic [IN_W-1:0] in_t;
  typedef logic [MA_W-1:0] maddr_t;

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

  burst_t [3:0] bl_q, bl_d;       // the list; entry 0 goes to the AW register next
  logic   [3:0] blv_q, blv_d;
  burst_t [1:0] b0, b1;           // per plane: first and second burst
  logic         aw_hs, aw_push, b_hs, s5_take;
  // AW register (msr_spill_reg): the list's head moves into it on aw_push, a decision made from
  // flip-flops only (list valid, budget, the register's registered ready). So the list's shift
  // and reload (an enable on some 280 flip-flops) never wait on AWREADY or on a count compare.
  logic         aw_sp_ready, aw_sp_valid;
  burst_t       aw_sp;
  logic         out_ok_q;         // another burst fits the budget (registered compare)

  always_comb begin
    for (int unsigned p = 0; p < 2; p++) begin
      logic [31:0] al;
      al = row_i.a[p] & ~(STRB_W - 1);
      b0[p] = '{addr: al, len: row_i.shape[p].len0, in: row_i.in, bufi: row_i.bufi, src: p[0],
                mbase: maddr_t'(buf_base(row_i.bufi, (p != 0) ? SB : PB)), lo: row_i.shape[p].lo,
                hi: row_i.shape[p].two ? BB_W'(STRB_W - 1) : row_i.shape[p].hi, row_last: 1'b0};
      b1[p] = '{addr: {al[31:12] + 1'b1, 12'h000}, len: row_i.shape[p].len1, in: row_i.in,
                bufi: row_i.bufi, src: p[0], mbase: row_i.mb1[p], lo: '0, hi: row_i.shape[p].hi,
                row_last: 1'b0};
    end
  end

  assign aw_push     = blv_q[0] && out_ok_q && aw_sp_ready;
  // A new row enters when the list is empty or its last burst goes this clock.
  assign row_ready_o = (blv_q == '0 || (aw_push && blv_q[3:1] == '0));
  assign s5_take     = row_valid_i && row_ready_o;

  always_comb begin
    logic ptwo, stwo;
    ptwo  = row_i.shape[0].two;
    stwo  = row_i.shape[1].two;
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

  `MSR_CLR_REG(u_blv, 4, clear_i, 1'b1, blv_d, blv_q)
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
    .ready_i (wb_room_i && m_axi_awready),
    .data_o  (aw_sp)
  );

  // Bursts against the budget of MAX_OUT: counted from the AW register on (budget_q), so the
  // check that lets the next one in is a register; B responses are expected only for bursts
  // whose address went out on the bus (onbus_q).
  logic [OUT_W-1:0] budget_q, budget_d, onbus_q;
  logic             b_pop, onbus_nz_q, onbus_nz_d, out_ok_d;
  logic             b_expected, aq_valid, aq_ready;
  logic [31:0]      aq_addr;
  logic [$clog2(AQ_D):0] aq_count;

  // AWVALID waits for room in the W side's burst queue; that room only grows while AWVALID
  // waits (the queue takes a burst only on the AW handshake), so AWVALID is never withdrawn.
  assign m_axi_awvalid = aw_sp_valid && wb_room_i;
  assign aw_hs         = m_axi_awvalid && m_axi_awready;
  assign m_axi_awid    = '0;
  assign m_axi_awaddr  = aw_sp.addr;
  assign m_axi_awlen   = aw_sp.len;
  assign m_axi_awsize  = 3'(BB_W);   // a full beat
  assign m_axi_awburst = 2'b01;      // INCR
  assign m_axi_awlock  = 1'b0;
  assign m_axi_awcache = 4'b0011;    // normal, non-cacheable, bufferable
  assign m_axi_awprot  = 3'b000;

  assign wb_push_o = aw_hs;
  assign wb_o      = '{len: aw_sp.len, in: aw_sp.in, bufi: aw_sp.bufi, src: aw_sp.src,
                       mbase: aw_sp.mbase, lo: aw_sp.lo, hi: aw_sp.hi, row_last: aw_sp.row_last};

  assign m_axi_bready   = 1'b1;
  assign b_hs           = m_axi_bvalid && m_axi_bready;
  assign b_expected     = onbus_nz_q;
  assign bresp_err_o    = b_hs && b_expected && m_axi_bresp[1];
  assign bresp_addr_o   = aq_addr;
  assign b_unexpected_o = b_hs && !b_expected;
  assign budget_d       = budget_q + OUT_W'(aw_push) - OUT_W'(b_pop);

  // The two flags' next values without the counts' adders behind them (a long placed path:
  // onbus_q -> "a B is expected" -> budget adder -> budget compare): compares of
  // the count registers, and the late AW push / B pop through one gate. aw_push needs out_ok_q,
  // so a full budget only shrinks. a_budget_flags checks both against the compares.
  assign b_pop      = b_hs && b_expected;
  // (compared at 32 bits: with MAX_OUT 1 the counts are one bit wide)
  assign onbus_nz_d = aw_hs || (32'(onbus_q) >= 2) || (32'(onbus_q) == 1 && !b_pop);
  assign out_ok_d   = (32'(budget_q) < MAX_OUT - 1) ||
                      (32'(budget_q) == MAX_OUT - 1 && !(aw_push && !b_pop)) ||
                      (32'(budget_q) == MAX_OUT && b_pop);

  // out_ok_q is 1 after reset and clear: the budget is then empty.
  `MSR_CLR_REG_RST(u_budget, 2 * OUT_W + 2, {(2 * OUT_W)'(0), 2'b10}, clear_i, 1'b1,
                   {budget_d, onbus_q + OUT_W'(aw_hs) - OUT_W'(b_pop), out_ok_d, onbus_nz_d},
                   {budget_q, onbus_q, out_ok_q, onbus_nz_q})

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

  assign idle_o = (blv_q == '0) && !aw_sp_valid && (budget_q == '0);

  logic unused;
  assign unused = ^{m_axi_bid, m_axi_bresp[0], aq_valid, aq_ready, aq_count};

  /* verilator lint_off SYNCASYNCNET */
  `MSR_ASSERT_NXT(a_aw_stable, m_axi_awvalid && !m_axi_awready,
              m_axi_awvalid && $stable({m_axi_awaddr, m_axi_awlen}), clk_i, !rst_ni || clear_i)
  `MSR_ASSERT_IMP(a_no_4k_cross, m_axi_awvalid, (32'(m_axi_awaddr[11:0]) +
              (32'(m_axi_awlen) + 1) * STRB_W) <= 32'h1000)
  `MSR_ASSERT_IMP(a_addr_fifo_room, aw_hs, aq_ready)
  `MSR_ASSERT(a_onbus_in_budget, onbus_q <= budget_q)
  `MSR_ASSERT(a_budget_flags, out_ok_q == (budget_q != OUT_W'(MAX_OUT)) &&
              onbus_nz_q == (onbus_q != '0))
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_fbw_aw
