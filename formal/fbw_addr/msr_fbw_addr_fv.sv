// Formal harness of msr_fbw_addr, the frame-buffer writer's address pipeline: two inputs, a
// 32-bit bus. The frame-buffer settings and the rows' metadata are constants the solver picks
// (strides below 64 KiB, any y, x0 and length); each input's buffer to pick is constant and its
// row request held until taken (msr_fbw_rowbuf's registered row_ready). Checks, on every row
// out: both plane addresses, base + y*stride + x0 term (4*x0 for pixels), and the burst shape
// (first / last byte, AWLEN, the split at 4 KiB and the second burst's buffer beat) against
// arithmetic written plainly here; the row's buffer is its input's; a take only of a requesting
// input, one at a time; the credit bound (rows taken and not yet out at most the queue's 8);
// idle only with none in flight. Bounded.
`include "msr_fbw_types.svh"

module msr_fbw_addr_fv import msr_pkg::*; import msr_fbw_pkg::*; #(
  localparam int unsigned DW   = 32,
  localparam int unsigned PB   = pix_beats(DW / 32),
  localparam int unsigned SB   = code_beats(DW / 32),
  localparam int unsigned MA_W = $clog2(NBUF * PB),
  localparam int unsigned BB_W = $clog2(DW / 8)
) (
  input logic        clk_i, rst_ni,
  input logic [1:0]  req_i,
  input buf_t [1:0]  pick_i,
  input fb_cfg_t     fb_i,
  input row_meta_t   meta_i,
  input logic        row_ready_i
);
  typedef `MSR_FBW_ROW_T(1, MA_W, BB_W) row_t;
  logic [1:0] take;
  logic       meta_in, row_valid, idle;
  buf_t       meta_buf;
  row_t       row;

  msr_fbw_addr #(.NUM_IN(2), .AXI_DATA_W(DW), .row_t(row_t)) dut (
    .clk_i, .rst_ni, .clear_i (1'b0), .fb_i, .req_i, .pick_i, .take_o (take),
    .meta_in_o (meta_in), .meta_buf_o (meta_buf), .meta_i, .row_valid_o (row_valid),
    .row_ready_i, .row_o (row), .idle_o (idle)
  );

  logic init_q;
  msr_fv_init #(.ONCE(1'b1)) u_init (.clk_i, .rst_ni, .init_o(init_q));

  // Constants of the run; requests held until taken; none in the first clocks (the stride
  // multiples settle four clocks after the strides: the configuration is latched at START).
  fb_cfg_t    fb_q;
  row_meta_t  meta_q;
  buf_t [1:0] pick_q;
  logic [1:0] req_q, take_q;
  logic [2:0] age_q;
  always_ff @(posedge clk_i) begin
    fb_q <= fb_i; meta_q <= meta_i; pick_q <= pick_i; req_q <= req_i; take_q <= take;
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) age_q <= '0;
    else if (age_q != 3'd7) age_q <= age_q + 1'b1;
  end
  always_comb begin
    if (!init_q) assume (fb_i == fb_q && meta_i == meta_q && pick_i == pick_q);
    assume (fb_i.fb_stride[31:16] == '0 && fb_i.src_stride[31:16] == '0);
    assume ((meta_i.x0 & 12'd7) == '0 && pick_i[0] != 2'd3 && pick_i[1] != 2'd3);
    if (age_q < 3'd5) assume (req_i == '0);
    if (!init_q) assume ((req_q & ~take_q & ~req_i) == '0);
  end

  // Rows taken and not yet out.
  logic [4:0] fly_q;
  wire        pop = row_valid && row_ready_i;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) fly_q <= '0;
    else         fly_q <= fly_q + 5'(take != '0) - 5'(pop);
  end

  // The row's planes, plainly.
  logic [31:0] a_want [2];
  logic [12:0] end_lo [2];     // address [11:0] + bytes - 1
  logic [7:0]  nbm1 [2];       // bytes - 1
  always_comb begin
    a_want[0] = fb_q.fb_base + 32'(meta_q.y) * fb_q.fb_stride + 32'(meta_q.x0) * 4;
    a_want[1] = fb_q.src_base + 32'(meta_q.y) * fb_q.src_stride + 32'(meta_q.x0);
    nbm1[0]   = 8'(meta_q.l) * 4 + 8'd3;
    nbm1[1]   = 8'(meta_q.l);
    for (int p = 0; p < 2; p++) end_lo[p] = 13'(a_want[p][11:0]) + 13'(nbm1[p]);
  end

  logic [1:0] plane_ok;
  always_comb begin
    for (int p = 0; p < 2; p++) begin
      logic two;
      two = end_lo[p][12];
      plane_ok[p] = row.a[p] == a_want[p] && row.shape[p].two == two &&
                    row.shape[p].lo == a_want[p][1:0] && row.shape[p].hi == end_lo[p][1:0] &&
                    (two ? row.shape[p].len0 == 8'(10'h3FF - a_want[p][11:2]) &&
                           row.shape[p].len1 == 8'(end_lo[p][11:2]) &&
                           row.mb1[p] == MA_W'(32'(row.bufi) * ((p != 0) ? SB : PB) + 32'(row.shape[p].len0) + 1)
                         : row.shape[p].len0 == 8'((10'(a_want[p][1:0]) + 10'(nbm1[p])) >> 2));
    end
  end

  a_planes:  assert property (@(posedge clk_i) disable iff (!rst_ni) !row_valid || plane_ok == 2'b11);
  a_buf:     assert property (@(posedge clk_i) disable iff (!rst_ni) !row_valid || row.bufi == pick_q[row.in]);
  a_take:    assert property (@(posedge clk_i) disable iff (!rst_ni) $onehot0(take) && (take & ~req_i) == '0);
  a_credit:  assert property (@(posedge clk_i) disable iff (!rst_ni) fly_q <= 5'd8);
  a_idle:    assert property (@(posedge clk_i) disable iff (!rst_ni) !idle || fly_q == '0);

  c_row:     cover property (@(posedge clk_i) disable iff (!rst_ni) pop && row.shape[0].two);
  c_two:     cover property (@(posedge clk_i) disable iff (!rst_ni) pop && fly_q == 5'd2 && row.in);
endmodule
