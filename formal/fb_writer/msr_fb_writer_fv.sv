// Formal harness of msr_fb_writer, the AXI4 write master, with msr_axi4_w_checker on its
// write port: one pixel stream, a 32-bit bus, two bursts outstanding. The obligations are the
// checker's master-side rules (AW and W held and stable until taken, WLAST on beat AWLEN+1, AW
// no later than its first W beat, no 4 KiB crossing, AWSIZE within the bus, at most MAX_OUT
// bursts open). (Strobes inside the frame are checked by the tb/fb_writer bench, not here.)
// Environment: the configuration is free but legal (msr_cfg_ctrl refuses the rest) and stable;
// the slave is free within AXI4 (B only for a completed burst, held until taken); the engine is
// a legal one: whole tiles, row-major, T-aligned origins inside the frame, the last flag on a
// tile's last pixel, valid held until taken, codes below 32.
`include "msr_chk_axi.svh"

module msr_fb_writer_fv import msr_pkg::*; (
  input logic        clk_i,
  input logic        rst_ni,
  input logic [5:0]  width_i,       // frame width 1..63 (small: a short proof)
  input tile_size_e  tile_i,
  input logic [31:0] fb_base_i, fb_stride_i, src_base_i, src_stride_i,
  input logic        src_en_i,
  input logic        pix_valid_i,
  input rgb_t        pix_rgb_i,
  input logic [4:0]  pix_src_i,
  // the next tile's origin (T-aligned, inside the frame) and its height, 1..T
  input logic [5:0]  next_tx_i, next_ty_i, next_th_i,
  // the write port: the slave's signals free (BID tied to 0 below), the master's watched
  `MSR_AXI4_W_PORTS(output, input, 32, 32, 4)
);
  localparam int unsigned DW = 32;
  logic        pix_ready, idle, bresp_err, b_unexp;
  logic [0:0]  tile_done;
  logic [31:0] bresp_addr;
  coord_t      pix_x, pix_y;
  logic        pix_last;

  msr_fb_writer #(.NUM_IN(1), .AXI_DATA_W(DW), .ID_W(4), .MAX_OUT(2)) dut (
    .clk_i, .rst_ni, .clear_i (1'b0),
    .width_i (dim_t'(width_i)), .tile_i, .fb_base_i, .fb_stride_i, .src_en_i, .src_base_i,
    .src_stride_i,
    .pix_valid_i (pix_valid_i), .pix_ready_o (pix_ready), .pix_x_i (pix_x), .pix_y_i (pix_y),
    .pix_rgb_i (pix_rgb_i), .pix_src_i (src_t'(pix_src_i)), .pix_last_i (pix_last),
    `MSR_AXI4_W_CONN(m_axi_, ), .idle_o (idle), .tile_done_o (tile_done), .bresp_err_o (bresp_err),
    .bresp_addr_o (bresp_addr), .b_unexpected_o (b_unexp)
  );

  logic [8:0] viol;
  msr_axi4_w_checker #(.ADDR_W(32), .DATA_W(DW), .ID_W(4), .MAX_OUT(4)) u_chk (
    .clk_i, .rst_ni, `MSR_AXI4_W_CONN(, ), .viol_o (viol)
  );

  logic init_q;
  msr_fv_init #(.ONCE(1'b1)) u_init (.clk_i, .rst_ni, .init_o(init_q));

  // Configuration: legal (as msr_cfg_ctrl accepts it) and constant.
  logic [5:0] tsz;
  assign tsz = (tile_i == TILE_8) ? 6'd8 : (tile_i == TILE_16) ? 6'd16 : 6'd32;
  logic [31:0] cfg_q [5];
  logic [5:0]  w_q;
  logic [1:0]  t_q;
  logic        s_q;
  always_ff @(posedge clk_i) begin
    cfg_q[0] <= fb_base_i; cfg_q[1] <= fb_stride_i; cfg_q[2] <= src_base_i;
    cfg_q[3] <= src_stride_i; w_q <= width_i; t_q <= tile_i; s_q <= src_en_i;
  end

  // The engine: tiles row-major; (x, y) of the next pixel; the tile's x origin and last row.
  logic [5:0] x_q, y_q, tx_q, ty_q, th_q;
  logic       started_q;
  wire        row_end  = (x_q == tx_q + tsz - 1) || (x_q == w_q - 1);
  wire        tile_end = row_end && (y_q == ty_q + th_q - 1);
  wire        pix_hs   = pix_valid_i && pix_ready;
  assign pix_x    = coord_t'(x_q);
  assign pix_y    = coord_t'(y_q);
  assign pix_last = tile_end;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      started_q <= 1'b0; x_q <= '0; y_q <= '0; tx_q <= '0; ty_q <= '0; th_q <= 6'd1;
    end else if (!started_q || (pix_hs && tile_end)) begin
      started_q <= 1'b1;
      tx_q <= next_tx_i; ty_q <= next_ty_i; th_q <= next_th_i;
      x_q <= next_tx_i; y_q <= next_ty_i;
    end else if (pix_hs) begin
      x_q <= row_end ? tx_q : x_q + 1'b1;
      y_q <= row_end ? y_q + 1'b1 : y_q;
    end
  end
  // The pixel stream's handshake rule (valid held with its pixel until taken), assumed below.
  logic pix_viol;
  msr_chk_stable #(.W(29)) u_pix_stable (
    .clk_i, .rst_ni, .valid_i(pix_valid_i), .ready_i(pix_ready),
    .payload_i({pix_rgb_i, pix_src_i}), .viol_o(pix_viol)
  );

  always_comb begin
    if (!init_q)
      assume (fb_base_i == cfg_q[0] && fb_stride_i == cfg_q[1] && src_base_i == cfg_q[2]
              && src_stride_i == cfg_q[3] && width_i == w_q && tile_i == t_q && src_en_i == s_q);
    assume (tile_i != 2'd3 && width_i != '0);
    assume (fb_base_i[1:0] == '0 && fb_stride_i[1:0] == '0 && src_base_i[1:0] == '0
            && src_stride_i[1:0] == '0);
    assume (fb_stride_i >= 32'(width_i) * 4 && src_stride_i >= 32'(width_i) * 4);
    // the planes do not wrap past 4 GiB (64 rows at most here)
    assume (33'(fb_base_i) + 33'(fb_stride_i) * 64 < 33'h1_0000_0000);
    assume (33'(src_base_i) + 33'(src_stride_i) * 64 < 33'h1_0000_0000);
    // the next tile: T-aligned, inside the frame, 1..T rows
    assume ((next_tx_i & (tsz - 1)) == '0 && next_tx_i < width_i);
    assume ((next_ty_i & (tsz - 1)) == '0 && next_th_i != '0 && next_th_i <= tsz);
    assume (7'(next_ty_i) + 7'(next_th_i) <= 7'd63);
    // valid held with its pixel until taken
    assume (!pix_viol);
    // the slave: B held until taken, none without a completed burst (checker rules 2 and 7);
    // one ID (the writer ignores BID)
    assume (!viol[2] && !viol[7] && bid == '0);
  end

  wire aw_hs = awvalid && awready;
  wire w_hs  = wvalid && wready;

  // Non-vacuity: a tile taken, a burst accepted on AW (at step 11: the first W beats come
  // after the bounds that make formal can afford; tb/fb_writer covers whole bursts).
  c_tile:  cover property (@(posedge clk_i) disable iff (!rst_ni) tile_done[0]);
  c_aw:    cover property (@(posedge clk_i) disable iff (!rst_ni) aw_hs);
endmodule
