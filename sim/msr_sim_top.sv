// Top of the Verilator C++ harness: the accelerator (msr_top) with the DPI rendering unit on
// its render port. The harness drives the AXI4-Lite register port and models the memory
// behind the AXI4 write port. The dbg_* outputs tell the harness when a tile is handed out
// and when its last pixel is written, for the FST tile window.
module msr_sim_top import msr_pkg::*; #(
  parameter int unsigned NUM_ENGINES     = 4,
  parameter int unsigned MAX_OUTSTANDING = 64,
  parameter int unsigned NUM_CTX         = 7,    // msr_top's default
  parameter bit          BUDGET_EN       = 1'b0, // the ray-budget controller (make sim BUDGET=)
  parameter bit          DEPTH_EN        = 1'b0, // the engines' depth channel (make sim DEPTH=1)
  parameter int unsigned RD_LAT          = 1,    // the tile buffers' read latency (make bench: _rl<L>)
  parameter int unsigned TILE_LIMIT      = 32,   // the largest tile the buffers hold (make bench: _t<T>)
  parameter int unsigned BUF_CYCLE       = 1,    // the tile buffers' cycle (make bench: _cy<N>)
  localparam int unsigned EID_W  = (NUM_ENGINES > 1) ? $clog2(NUM_ENGINES) : 1,
  localparam int unsigned RTAG_W = EID_W + $clog2(MAX_OUTSTANDING)
) (
  input  logic        clk_i,
  input  logic        rst_ni,
  // AXI4-Lite register port, driven by the harness (AWPROT/ARPROT 0 and WSTRB all ones here).
  input  logic        s_axil_awvalid, s_axil_wvalid, s_axil_bready, s_axil_arvalid, s_axil_rready,
  input  logic [6:0]  s_axil_awaddr, s_axil_araddr,
  input  logic [31:0] s_axil_wdata,
  output logic        s_axil_awready, s_axil_wready, s_axil_bvalid, s_axil_arready, s_axil_rvalid,
  output logic [1:0]  s_axil_bresp, s_axil_rresp,
  output logic [31:0] s_axil_rdata,
  // AXI4 frame-buffer write port, answered by the harness's memory model (one ID, the BID
  // echoes the AWID; AWSIZE, AWBURST, AWLOCK, AWCACHE and AWPROT stay inside).
  output logic        m_axi_awvalid, m_axi_wvalid, m_axi_wlast, m_axi_bready,
  output logic [31:0] m_axi_awaddr,
  output logic [7:0]  m_axi_awlen,
  output logic [255:0] m_axi_wdata,   // msr_top's default AXI_DATA_W (the harness expects 256)
  output logic [31:0] m_axi_wstrb,
  input  logic        m_axi_awready, m_axi_wready, m_axi_bvalid,
  input  logic [1:0]  m_axi_bresp,
  output logic        irq_o,
  output logic        dbg_desc_fire_o,   // a tile was handed to an engine
  output coord_t      dbg_desc_x0_o,     // its origin
  output coord_t      dbg_desc_y0_o,
  input  coord_t      dbg_watch_tx_i,    // a tile column / row the harness watches
  input  coord_t      dbg_watch_ty_i,
  input  logic [5:0]  dbg_watch_t_i,     // the frame's tile size
  output logic        dbg_watch_done_o   // the last pixel of the watched tile went to the writer
);
  logic              req_valid, req_ready, rsp_valid, rsp_ready;
  coord_t            req_x, req_y;
  logic [RTAG_W-1:0] req_tag, rsp_tag;
  rgb_t              rsp_rgb;
  logic [15:0]       rsp_invz;
  logic   [NUM_ENGINES-1:0] dbg_tile_done;
  coord_t [NUM_ENGINES-1:0] dbg_pix_x, dbg_pix_y;
  logic [3:0]        awid;
  logic [2:0]        awsize, awprot;
  logic [1:0]        awburst;
  logic              awlock;
  logic [3:0]        awcache;

  msr_top #(
    .NUM_ENGINES     (NUM_ENGINES),
    .MAX_OUTSTANDING (MAX_OUTSTANDING),
    .NUM_CTX         (NUM_CTX),
    .BUDGET_EN       (BUDGET_EN),
    .DEPTH_EN        (DEPTH_EN),
    .RD_LAT          (RD_LAT),
    .TILE_LIMIT      (TILE_LIMIT),
    .BUF_CYCLE       (BUF_CYCLE)
  ) u_top (
    .clk_i, .rst_ni,
    .s_axil_awvalid, .s_axil_awready, .s_axil_awaddr, .s_axil_awprot (3'b000),
    .s_axil_wvalid, .s_axil_wready, .s_axil_wdata, .s_axil_wstrb (4'hF),
    .s_axil_bvalid, .s_axil_bready, .s_axil_bresp,
    .s_axil_arvalid, .s_axil_arready, .s_axil_araddr, .s_axil_arprot (3'b000),
    .s_axil_rvalid, .s_axil_rready, .s_axil_rdata, .s_axil_rresp,
    .rnd_req_valid_o (req_valid),
    .rnd_req_ready_i (req_ready),
    .rnd_req_x_o     (req_x),
    .rnd_req_y_o     (req_y),
    .rnd_req_tag_o   (req_tag),
    .rnd_rsp_valid_i (rsp_valid),
    .rnd_rsp_ready_o (rsp_ready),
    .rnd_rsp_tag_i   (rsp_tag),
    .rnd_rsp_rgb_i   (rsp_rgb),
    .rnd_rsp_invz_i  (rsp_invz),
    .m_axi_awid (awid), .m_axi_awaddr, .m_axi_awlen, .m_axi_awsize (awsize),
    .m_axi_awburst (awburst), .m_axi_awlock (awlock), .m_axi_awcache (awcache),
    .m_axi_awprot (awprot), .m_axi_awvalid, .m_axi_awready,
    .m_axi_wdata, .m_axi_wstrb, .m_axi_wlast, .m_axi_wvalid, .m_axi_wready,
    .m_axi_bid (awid), .m_axi_bresp, .m_axi_bvalid, .m_axi_bready,
    .irq_o, .dbg_desc_fire_o, .dbg_desc_x0_o, .dbg_desc_y0_o,
    .dbg_tile_done_o (dbg_tile_done),
    .dbg_pix_x_o     (dbg_pix_x),
    .dbg_pix_y_o     (dbg_pix_y)
  );

  render_dpi #(.TAG_W(RTAG_W), .DEPTH(NUM_ENGINES * MAX_OUTSTANDING), .DEPTH_EN(DEPTH_EN)) u_render (
    .clk_i       (clk_i),
    .rst_ni      (rst_ni),
    .req_valid_i (req_valid),
    .req_ready_o (req_ready),
    .req_x_i     (req_x),
    .req_y_i     (req_y),
    .req_tag_i   (req_tag),
    .rsp_valid_o (rsp_valid),
    .rsp_ready_i (rsp_ready),
    .rsp_tag_o   (rsp_tag),
    .rsp_rgb_o   (rsp_rgb),
    .rsp_invz_o  (rsp_invz)
  );

  // The depth channel's monitor: no writer stores the engines' inverse depth yet, so the harness
  // takes every pixel's as it leaves its engine (its --depth plane).
  import "DPI-C" function void msr_dpi_depth_pixel(input int x, input int y, input int invz);
  if (DEPTH_EN) begin : g_depth_monitor
    always @(posedge clk_i) begin
      for (int unsigned i = 0; i < NUM_ENGINES; i++) begin
        if (rst_ni && u_top.eng_pix_valid[i] && u_top.eng_pix_ready[i]) begin
          msr_dpi_depth_pixel(int'(u_top.eng_pix_x[i]), int'(u_top.eng_pix_y[i]),
                              int'(u_top.eng_pix_invz[i]));
        end
      end
    end
  end

  // Tile life markers for the harness, from msr_top's debug ports. Engines finish tiles in
  // parallel: look for the watched one among them.
  always_comb begin
    dbg_watch_done_o = 1'b0;
    for (int unsigned i = 0; i < NUM_ENGINES; i++) begin
      if (dbg_tile_done[i] &&
          32'(dbg_pix_x[i]) / 32'(dbg_watch_t_i) == 32'(dbg_watch_tx_i) &&
          32'(dbg_pix_y[i]) / 32'(dbg_watch_t_i) == 32'(dbg_watch_ty_i)) begin
        dbg_watch_done_o = 1'b1;
      end
    end
  end

  logic unused_sim;
  assign unused_sim = ^{awsize, awprot, awburst, awlock, awcache};
endmodule
