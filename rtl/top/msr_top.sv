// The accelerator: registers (AXI4-Lite), configuration check and control, tile generation,
// NUM_ENGINES tile engines sharing one render request/response port through the render mux,
// one frame-buffer writer (AXI4 write master) and the performance counters. This module only
// wires the units together (docs/system.md).
//
// Render port: requests carry tag {engine id, engine tag}; responses may come back in any
// order and are routed to the engine named in their tag. Soft reset: new requests are held,
// responses are still taken until no engine has one outstanding, finished pixels are
// dropped, open bursts complete; then every unit is cleared. Watchdog (WATCHDOG register): no
// progress on the ports for that many cycles ends the frame, or a soft reset's wait, by force.
`include "msr_assert.svh"
`include "msr_axi_ports.svh"

module msr_top import msr_pkg::*; import msr_sys_pkg::*; #(
  parameter int unsigned NUM_ENGINES     = 4,    // parallel tile engines (claim 11)
  parameter int unsigned MAX_OUTSTANDING = 64,   // render requests in flight per engine (tags)
  parameter int unsigned NUM_CTX         = 7,    // tile contexts per engine (2..16)
  parameter int unsigned AXI_ID_W        = 4,    // frame-buffer AXI ID width
  parameter int unsigned AXI_DATA_W      = 256,  // frame-buffer AXI data width (32..256)
  // The rules built in (beside CONFIG.RULE, the run-time choice): 1 both (the default top);
  // 0 patent only (no third tile-buffer port: 2 DP16KD fewer per context; CONFIG.RULE 1 is
  // refused at START with STATUS.ERROR 13).
  parameter int unsigned LINDILATE       = 1,
  // The ray-budget controller (docs/budget.md; BUDGET and BUDGET_CTRL): 1 built in; 0 not (a
  // non-zero BUDGET is refused at START with STATUS.ERROR 14).
  parameter bit          BUDGET_EN       = 1'b0,
  // The engines' depth channel (docs/architecture.md "The depth channel"): 1 every traced
  // pixel's inverse depth comes with its colour (rnd_rsp_invz_i) and the engines interpolate
  // and emit each pixel's (not yet written to memory); 0 not built, rnd_rsp_invz_i unused.
  parameter bit          DEPTH_EN        = 1'b0,
  // The tile buffers' read latency in clocks (1..4): 1 for block RAM (the FPGA build); a
  // standard-cell build takes what its SRAM macro needs (docs/asic.md).
  parameter int unsigned RD_LAT          = 1,
  // The largest tile edge the tile buffers hold: 32 (the default; CONFIG.TILE 8, 16, 32), or 16
  // or 8 for a build that keeps a quarter or a sixteenth of the tile-buffer bits (docs/asic.md);
  // a larger CONFIG.TILE is refused at START with STATUS.ERROR 2.
  parameter int unsigned TILE_LIMIT      = 32,
  // The tile buffers' cycle in clocks (1..8): 1 for block RAM; a standard-cell build whose macro
  // takes an address on a port once per N clocks takes N (msr_tile_engine, docs/asic.md).
  parameter int unsigned BUF_CYCLE       = 1,
  localparam int unsigned EID_W  = (NUM_ENGINES > 1) ? $clog2(NUM_ENGINES) : 1,
  localparam int unsigned ETAG_W = $clog2(MAX_OUTSTANDING),
  localparam int unsigned RTAG_W = EID_W + ETAG_W
) (
  input  logic              clk_i,              // clock
  input  logic              rst_ni,             // asynchronous reset, active low
  // Render request port: trace pixel (x, y).
  output logic              rnd_req_valid_o,    // a request
  input  logic              rnd_req_ready_i,    // the rendering unit takes it
  output coord_t            rnd_req_x_o,        // global x
  output coord_t            rnd_req_y_o,        // global y
  output logic [RTAG_W-1:0] rnd_req_tag_o,      // {engine, engine tag}: echo it in the response
  // Render response port: any order.
  input  logic              rnd_rsp_valid_i,    // a traced colour
  output logic              rnd_rsp_ready_o,    // taken
  input  logic [RTAG_W-1:0] rnd_rsp_tag_i,      // tag of the request
  input  rgb_t              rnd_rsp_rgb_i,      // colour
  input  logic [15:0]       rnd_rsp_invz_i,     // DEPTH_EN: its inverse depth (0: sky)
  // Interrupt: (STATUS.DONE, CFG_ERR or WDOG) while CTRL.IRQ_EN; registered, a clock after them.
  output logic              irq_o,
  // Debug (simulation and bring-up; no function): tile hand-out and tile completion.
  output logic              dbg_desc_fire_o,    // a tile goes to an engine this clock
  output coord_t            dbg_desc_x0_o,      // its origin
  output coord_t            dbg_desc_y0_o,
  output logic [NUM_ENGINES-1:0] dbg_tile_done_o, // engine i's last pixel of a tile is written
  output coord_t [NUM_ENGINES-1:0] dbg_pix_x_o,   // engine i's pixel (with dbg_tile_done_o)
  output coord_t [NUM_ENGINES-1:0] dbg_pix_y_o,
  // The buses (rtl/top/msr_axi_ports.svh): the AXI4-Lite register port s_axil_* (7-bit byte
  // address) and the AXI4 frame-buffer write master m_axi_*.
  `MSR_TOP_BUS_PORTS(AXI_ID_W, AXI_DATA_W)
);
  if (AXI_ID_W < 1 || AXI_ID_W > 8) begin : g_check_id_w
    $fatal(1, "msr_top: AXI_ID_W must be 1..8, got %0d", AXI_ID_W);
  end

  // ---- Registers --------------------------------------------------------------------------------
  cfg_raw_t    raw;
  reg_ctrl_t   reg_ctrl;
  reg_status_t reg_status;
  readback_t   readback;
  logic [10:0] scale_out;
  logic        scale_out_valid;

  // verilog_lint: waive-start module-port (the bus ports connect by name, macro last)
  msr_reg_if u_reg_if (
    .clk_i, .rst_ni,
    .raw_o             (raw),
    .ctrl_o            (reg_ctrl),
    .status_i          (reg_status),
    .readback_i        (readback),
    .scale_out_i       (scale_out),
    .scale_out_valid_i (scale_out_valid),
    `MSR_AXIL_SLAVE_CONNECT
  );
  // verilog_lint: waive-stop module-port

  // ---- Configuration check and control ----------------------------------------------------------
  cfg_t        cfg;
  err_e        err;
  err_counts_t err_counts;
  logic  busy, done_set, done_clr, cfg_err_set, wdog_set, start, run, drain, clear, moved;
  logic  tg_done, tg_busy, rnd_idle, wr_idle, bresp_err, b_unexpected, rmux_busy, bad_eid;
  logic  [31:0] bresp_addr;
  logic  [NUM_ENGINES-1:0] eng_rsp_drop, eng_clear, eng_drain;
  logic  [NUM_ENGINES-1:0] eng_desc_valid, eng_desc_ready, eng_busy, wr_tile_done;

  cfg_raw_t raw_q;                 // the registers as the check samples them
  logic     bud_check, bud_done, bud_err_budget, bud_err_profile, bud_busy;

  msr_cfg_ctrl #(
    .NUM_ENGINES (NUM_ENGINES), .LINDILATE (LINDILATE), .TILE_LIMIT (TILE_LIMIT),
    .BUDGET_EN   (BUDGET_EN)
  ) u_ctrl (
    .clk_i, .rst_ni,
    .start_i (reg_ctrl.start), .soft_reset_i (reg_ctrl.soft_reset),
    .wdog_limit_i (reg_ctrl.wdog_limit),
    .raw_i (raw), .cfg_o (cfg),
    .busy_o (busy), .err_o (err), .done_set_o (done_set), .done_clr_o (done_clr),
    .cfg_err_set_o (cfg_err_set), .wdog_set_o (wdog_set), .err_counts_o (err_counts),
    .irq_en_i (reg_ctrl.irq_en), .irq_flags_i (reg_ctrl.irq_flags), .irq_o,
    .start_o (start), .run_o (run), .drain_o (drain), .eng_drain_o (eng_drain),
    .clear_o (clear), .eng_clear_o (eng_clear),
    .desc_fire_i (|eng_desc_valid), .tile_done_i (wr_tile_done), .tg_done_i (tg_done),
    .rnd_idle_i (rnd_idle), .wr_idle_i (wr_idle),
    .bresp_err_i (bresp_err), .bresp_addr_i (bresp_addr), .b_unexp_i (b_unexpected),
    .rsp_drop_i (eng_rsp_drop), .bad_eid_i (bad_eid), .moved_i (moved),
    .rsp_taken_i (rnd_rsp_valid_i && rnd_rsp_ready_o),
    .raw_o (raw_q),
    .bud_check_o (bud_check), .bud_done_i (bud_done), .bud_err_budget_i (bud_err_budget),
    .bud_err_profile_i (bud_err_profile), .bud_busy_i (bud_busy)
  );

  assign reg_status = '{busy: busy, err: err, done_set: done_set, done_clr: done_clr,
                        cfg_err_set: cfg_err_set, wdog_set: wdog_set};
  // ---- Tile generation -------------------------------------------------------------------------
  tile_desc_t desc;
  logic [NUM_ENGINES-1:0] desc_sp_ready;

  logic [COORD_W-2:0] tg_ntx, tg_nty;             // the walker's grid
  logic [COORD_W-3:0] tg_tx, tg_ty, tg_row_next;  // its next tile, its row after ty
  logic               tg_row_step, tg_row_last, tg_row_go, tg_adv;
  tile_desc_t         tg_pipe_desc, tg_tail_desc; // the generator's S5, the stage's last

  // The ray budget's stage sits between the generator and the engines (g_budget below): it
  // orders and paces the walk and adds its stages after the descriptor register.
  msr_tile_gen #(
    .NUM_ENGINES (NUM_ENGINES),
    .EXT_ORDER   (BUDGET_EN),
    .TAIL_STAGES (BUDGET_EN ? msr_budget_pkg::BUD_TAIL : 0)
  ) u_tile_gen (
    .clk_i, .rst_ni, .clear_i (drain), .start_i (start),
    .width_i (cfg.width), .height_i (cfg.height), .tile_i (cfg.tile), .levels_i (cfg.levels),
    .metric_i (cfg.metric), .rule_i (cfg.rule), .thr_i (cfg.thr), .fov_gain_i (cfg.fov_gain),
    .gaze_en_i (cfg.gaze.en), .gaze_cx_i (cfg.gaze.cx), .gaze_cy_i (cfg.gaze.cy),
    .ntx_o (tg_ntx), .nty_o (tg_nty), .tx_o (tg_tx), .ty_o (tg_ty),
    .row_step_o (tg_row_step), .row_next_i (tg_row_next), .row_last_i (tg_row_last),
    .row_go_i (tg_row_go), .adv_o (tg_adv), .pipe_desc_o (tg_pipe_desc),
    .tail_desc_i (tg_tail_desc),
    .desc_valid_o (eng_desc_valid), .desc_ready_i (desc_sp_ready & {NUM_ENGINES{run}}),
    .desc_o (desc),
    .busy_o (tg_busy), .done_o (tg_done)
  );

  // ---- Engines ----------------------------------------------------------------------------------
  logic   [NUM_ENGINES-1:0] eng_req_valid, eng_req_ready, mux_req_valid, mux_req_ready;
  coord_t [NUM_ENGINES-1:0] eng_req_x, eng_req_y, mux_req_x, mux_req_y;
  logic   [NUM_ENGINES-1:0][ETAG_W-1:0] eng_req_tag, mux_req_tag;
  logic   [NUM_ENGINES-1:0] eng_rsp_valid, eng_rsp_ready;
  logic   [ETAG_W-1:0]      eng_rsp_tag;
  // a response's data on its way to the engines: the colour, with DEPTH_EN {inverse depth, colour}
  localparam int unsigned RSP_W = $bits(rgb_t) + (DEPTH_EN ? 16 : 0);
  logic   [RSP_W-1:0]       eng_rsp_data, rnd_rsp_data;
  rgb_t                     eng_rsp_rgb;
  logic   [15:0]            eng_rsp_invz;
  // each engine's pixels' inverse depth (DEPTH_EN; the harness reads it, no writer takes it yet)
  /* verilator lint_off UNUSEDSIGNAL */
  logic   [NUM_ENGINES-1:0][15:0] eng_pix_invz;
  /* verilator lint_on UNUSEDSIGNAL */

  if (DEPTH_EN) begin : g_depth
    assign rnd_rsp_data = {rnd_rsp_invz_i, rnd_rsp_rgb_i};
    assign eng_rsp_invz = eng_rsp_data[RSP_W-1 -: 16];
  end else begin : g_no_depth
    /* verilator lint_off UNUSEDSIGNAL */
    logic [15:0] rnd_rsp_invz_unused;
    /* verilator lint_on UNUSEDSIGNAL */
    assign rnd_rsp_invz_unused = rnd_rsp_invz_i;
    assign rnd_rsp_data        = rnd_rsp_rgb_i;
    assign eng_rsp_invz        = '0;
  end
  assign eng_rsp_rgb = rgb_t'(eng_rsp_data[$bits(rgb_t)-1:0]);
  logic   [NUM_ENGINES-1:0] eng_pix_valid, eng_pix_ready, eng_pix_last;
  coord_t [NUM_ENGINES-1:0] eng_pix_x, eng_pix_y;
  rgb_t   [NUM_ENGINES-1:0] eng_pix_rgb;
  src_t   [NUM_ENGINES-1:0] eng_pix_src;
  logic   [NUM_ENGINES-1:0] eng_tags_out;
  /* verilator lint_off UNUSEDSIGNAL */
  logic   [NUM_ENGINES-1:0][ETAG_W:0] eng_inflight;   // for waves; the drain reads eng_tags_out
  /* verilator lint_on UNUSEDSIGNAL */

  for (genvar i = 0; i < NUM_ENGINES; i++) begin : g_engine
    // Two register slices per engine on the tile hand-off, one at each end of the wire: the
    // generator picks among the engines' ready bits, and each engine starts a context on its
    // valid (a load of some hundred flip-flops); without a slice that was one combinational
    // path across the die, from one engine through the generator into another, and with one
    // the wire still shared a clock with one end's logic. A tile in the slices is already
    // counted in flight (cfg_ctrl counts the generator's hand-off).
    logic       gs_desc_valid, gs_desc_ready, sp_desc_valid;
    tile_desc_t gs_desc, sp_desc;
    msr_spill_reg #(.WIDTH($bits(tile_desc_t))) u_desc_slice_gen (
      .clk_i, .rst_ni, .clear_i (clear),
      .valid_i (eng_desc_valid[i]), .ready_o (desc_sp_ready[i]), .data_i (desc),
      .valid_o (gs_desc_valid),     .ready_i (gs_desc_ready),    .data_o (gs_desc)
    );
    msr_spill_reg #(.WIDTH($bits(tile_desc_t))) u_desc_slice_eng (
      .clk_i, .rst_ni, .clear_i (eng_clear[i]),
      .valid_i (gs_desc_valid), .ready_o (gs_desc_ready),     .data_i (gs_desc),
      .valid_o (sp_desc_valid), .ready_i (eng_desc_ready[i]), .data_o (sp_desc)
    );

    msr_tile_engine #(
      .NUM_CTX         (NUM_CTX),
      .MAX_OUTSTANDING (MAX_OUTSTANDING),
      .LINDILATE       (LINDILATE),
      .DEPTH_EN        (32'(DEPTH_EN)),
      .RD_LAT          (RD_LAT),
      .TILE_LIMIT      (TILE_LIMIT),
      .BUF_CYCLE       (BUF_CYCLE)
    ) u_engine (
      .clk_i, .rst_ni, .clear_i (eng_clear[i]),
      .desc_valid_i (sp_desc_valid), .desc_ready_o (eng_desc_ready[i]), .desc_i (sp_desc),
      .req_valid_o (eng_req_valid[i]), .req_ready_i (eng_req_ready[i]),
      .req_x_o (eng_req_x[i]), .req_y_o (eng_req_y[i]), .req_tag_o (eng_req_tag[i]),
      .rsp_valid_i (eng_rsp_valid[i]), .rsp_ready_o (eng_rsp_ready[i]),
      .rsp_tag_i (eng_rsp_tag), .rsp_rgb_i (eng_rsp_rgb), .rsp_invz_i (eng_rsp_invz),
      .pix_valid_o (eng_pix_valid[i]), .pix_ready_i (eng_pix_ready[i]),
      .pix_x_o (eng_pix_x[i]), .pix_y_o (eng_pix_y[i]), .pix_rgb_o (eng_pix_rgb[i]),
      .pix_src_o (eng_pix_src[i]), .pix_last_o (eng_pix_last[i]), .pix_invz_o (eng_pix_invz[i]),
      .busy_o (eng_busy[i]), .rsp_drop_o (eng_rsp_drop[i]),
      .inflight_o (eng_inflight[i]), .tags_out_o (eng_tags_out[i])
    );

    // A register slice on the request wire to the render mux: without it the engine's output
    // stage (a free tag, the trace bit, the request register's load) and the mux's queue
    // were one path across the die, most of it wire (flat top).
    msr_spill_reg #(.WIDTH(2 * $bits(coord_t) + ETAG_W)) u_req_slice (
      .clk_i, .rst_ni, .clear_i (eng_clear[i]),
      .valid_i (eng_req_valid[i]), .ready_o (eng_req_ready[i]),
      .data_i  ({eng_req_x[i], eng_req_y[i], eng_req_tag[i]}),
      .valid_o (mux_req_valid[i]), .ready_i (mux_req_ready[i]),
      .data_o  ({mux_req_x[i], mux_req_y[i], mux_req_tag[i]})
    );
  end

  // ---- Render mux ---------------------------------------------------------------------------------

  msr_render_mux #(.NUM_ENGINES(NUM_ENGINES), .ETAG_W(ETAG_W), .DATA_W(RSP_W)) u_render_mux (
    .clk_i, .rst_ni, .clear_i (clear),
    // Requests are not held during a soft reset: an engine counts a request it offers as in
    // flight, so a held request would never come home and the drain would not end. The
    // engines finish the tiles they hold (no new tile is handed out, their pixels are
    // dropped) and every request goes out and is answered.
    .hold_i          (1'b0),
    .eng_req_valid_i (mux_req_valid), .eng_req_ready_o (mux_req_ready),
    .eng_req_x_i (mux_req_x), .eng_req_y_i (mux_req_y), .eng_req_tag_i (mux_req_tag),
    .eng_rsp_valid_o (eng_rsp_valid), .eng_rsp_ready_i (eng_rsp_ready),
    .eng_rsp_tag_o (eng_rsp_tag), .eng_rsp_rgb_o (eng_rsp_data),
    .rnd_req_valid_o, .rnd_req_ready_i, .rnd_req_x_o, .rnd_req_y_o, .rnd_req_tag_o,
    .rnd_rsp_valid_i, .rnd_rsp_ready_o, .rnd_rsp_tag_i, .rnd_rsp_rgb_i (rnd_rsp_data),
    .busy_o (rmux_busy), .bad_eid_o (bad_eid)
  );

  // Every engine's tags are home (queued and offered requests count as in flight). Each
  // engine's flag is a register (a clock late in clearing, never early), so the drain check
  // starts at flip-flops and not at the tag pools' counters across the die.
  assign rnd_idle = (eng_tags_out == '0);

  // ---- Pixel path: every engine has its own writer input (no arbitration) -----------------
  // Two register slices per engine, one at each end of the wire: the engines sit across the
  // die from the writer. This one, by its engine, is cleared with the engine; the writer's
  // input slice (msr_fbw_rowbuf, cleared with the writer) is the other end, and takes the
  // pixel's row-end test on the way in so that its buffer flags see a register, not a
  // comparator behind the wire. Soft reset: finished pixels are dropped between the two.
  logic      [NUM_ENGINES-1:0] ep_pix_valid, ep_pix_ready, wr_pix_valid, wr_pix_ready;
  pix_word_t [NUM_ENGINES-1:0] ep_pix;
  coord_t    [NUM_ENGINES-1:0] wr_pix_x, wr_pix_y;
  rgb_t      [NUM_ENGINES-1:0] wr_pix_rgb;
  src_t      [NUM_ENGINES-1:0] wr_pix_src;
  logic      [NUM_ENGINES-1:0] wr_pix_last;

  for (genvar i = 0; i < NUM_ENGINES; i++) begin : g_pix_slice
    msr_spill_reg #(.WIDTH($bits(pix_word_t))) u_pix_slice_eng (
      .clk_i, .rst_ni, .clear_i (eng_clear[i]),
      .valid_i (eng_pix_valid[i]), .ready_o (eng_pix_ready[i]),
      .data_i  (pix_word_t'{x: eng_pix_x[i], y: eng_pix_y[i], rgb: eng_pix_rgb[i],
                            src: eng_pix_src[i], last: eng_pix_last[i]}),
      .valid_o (ep_pix_valid[i]), .ready_i (ep_pix_ready[i]), .data_o (ep_pix[i])
    );
    assign {wr_pix_x[i], wr_pix_y[i], wr_pix_rgb[i], wr_pix_src[i], wr_pix_last[i]} = ep_pix[i];
  end

  assign wr_pix_valid = ep_pix_valid & ~eng_drain;
  assign ep_pix_ready = wr_pix_ready | eng_drain;

  // ---- Frame-buffer writer ----------------------------------------------------------------------
  // verilog_lint: waive-start module-port (the bus ports connect by name, macro last)
  msr_fb_writer #(
    .NUM_IN     (NUM_ENGINES),
    .AXI_DATA_W (AXI_DATA_W),
    .ID_W       (AXI_ID_W)
  ) u_fb_writer (
    .clk_i, .rst_ni, .clear_i (clear),
    .width_i (cfg.width), .tile_i (cfg.tile),
    .fb_base_i (cfg.fb.fb_base), .fb_stride_i (cfg.fb.fb_stride),
    .src_en_i (cfg.fb.src_en), .src_base_i (cfg.fb.src_base), .src_stride_i (cfg.fb.src_stride),
    .pix_valid_i (wr_pix_valid), .pix_ready_o (wr_pix_ready),
    .pix_x_i (wr_pix_x), .pix_y_i (wr_pix_y), .pix_rgb_i (wr_pix_rgb), .pix_src_i (wr_pix_src),
    .pix_last_i (wr_pix_last),
    .idle_o (wr_idle), .tile_done_o (wr_tile_done),
    .bresp_err_o (bresp_err), .bresp_addr_o (bresp_addr), .b_unexpected_o (b_unexpected),
    `MSR_AXI_WR_CONNECT
  );
  // verilog_lint: waive-stop module-port

  // ---- Ray budget: built in here or not at all ------------------------------------------------
  if (BUDGET_EN) begin : g_budget
    logic [COORD_W-3:0] bud_row, bud_smask;       // the walker's row position, the order's S - 1
    logic [COORD_W-2:0] bud_nty_s;                // nty - S
    logic               bud_row_ok;
    logic [12:0]        bud_row_m;
    msr_budget_stage u_stage (
      .clk_i, .rst_ni, .clear_i (drain), .start_i (start),
      .height_i (cfg.height), .tile_i (cfg.tile), .bud_en_i (cfg.bud.pixels != '0),
      .row_idx_o (bud_row), .row_ok_i (bud_row_ok), .row_m_i (bud_row_m),
      .smask_o (bud_smask), .nty_s_o (bud_nty_s),
      .nty_i (tg_nty), .tx_i (tg_tx[7:0]), .ty_i (tg_ty), .row_step_i (tg_row_step),
      .row_next_o (tg_row_next), .row_last_o (tg_row_last), .row_go_o (tg_row_go),
      .adv_i (tg_adv), .desc_i (tg_pipe_desc), .desc_o (tg_tail_desc)
    );
    logic unused_tx;                              // the dither reads the column mod 256
    assign unused_tx = ^tg_tx[COORD_W-3:8];
    msr_budget #(.NUM_IN(NUM_ENGINES)) u_budget (
      .clk_i, .rst_ni, .clear_i (clear),
      .raw_i (raw_q), .check_i (bud_check), .check_done_o (bud_done),
      .err_budget_o (bud_err_budget), .err_profile_o (bud_err_profile),
      .start_i (start), .busy_o (bud_busy),
      .row_idx_i (bud_row), .row_ok_o (bud_row_ok), .row_m_o (bud_row_m),
      .ntx_i (tg_ntx), .nty_i (tg_nty), .smask_i (bud_smask), .nty_s_i (bud_nty_s),
      .pix_fire_i (wr_pix_valid & wr_pix_ready),
      .pix_y_i (wr_pix_y), .pix_src_i (wr_pix_src), .pix_last_i (wr_pix_last),
      .scale_out_o (scale_out), .scale_out_valid_o (scale_out_valid)
    );
  end else begin : g_no_budget
    // row-major and free: the generator's own walk, its descriptor straight to the engines
    assign tg_row_next     = '0;
    assign tg_row_last     = 1'b0;
    assign tg_row_go       = 1'b1;
    assign tg_tail_desc    = '0;
    assign bud_done        = 1'b0;
    assign bud_err_budget  = 1'b0;
    assign bud_err_profile = 1'b0;
    assign bud_busy        = 1'b0;
    assign scale_out       = '0;
    assign scale_out_valid = 1'b0;
    logic unused_budget;
    assign unused_budget = ^{bud_check, raw_q, cfg.bud, tg_ntx, tg_nty, tg_tx, tg_ty, tg_row_step,
                             tg_adv, tg_pipe_desc};
  end

  // ---- Watchdog progress -------------------------------------------------------------------------
  // Render requests and finished pixels, the write channels, and B responses the writer expected
  // (a spurious B is not progress); the controller adds render responses while running.
  assign moved = (rnd_req_valid_o && rnd_req_ready_i) || ((eng_pix_valid & eng_pix_ready) != '0) ||
                 (m_axi_awvalid && m_axi_awready) || (m_axi_wvalid && m_axi_wready) ||
                 (m_axi_bvalid && m_axi_bready && !b_unexpected);

  // ---- Performance counters and read-back ---------------------------------------------------------
  msr_perf_counters #(.NUM_ENGINES(NUM_ENGINES)) u_perf (
    .clk_i, .rst_ni, .clear_i (start || clear), .en_i (run),
    .pix_hs_i (wr_pix_valid & wr_pix_ready), .pix_src_i (wr_pix_src),
    .rstall_i (rnd_req_valid_o && !rnd_req_ready_i),
    .mstall_i ((wr_pix_valid & ~wr_pix_ready) != '0),
    .err_i (err_counts), .readback_o (readback)
  );

  // ---- Debug ports -----------------------------------------------------------------------------------
  assign dbg_desc_fire_o = |eng_desc_valid;
  assign dbg_desc_x0_o   = desc.x0;
  assign dbg_desc_y0_o   = desc.y0;
  assign dbg_tile_done_o = wr_tile_done;
  assign dbg_pix_x_o     = wr_pix_x;
  assign dbg_pix_y_o     = wr_pix_y;

  logic unused_top;
  assign unused_top = ^{tg_busy, eng_busy, rmux_busy};

endmodule : msr_top
