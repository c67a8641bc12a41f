// The accelerator: registers (AXI4-Lite), tile generation, NUM_ENGINES tile engines sharing
// one render request/response port, and one frame-buffer writer (AXI4 write master).
//
// Render port: requests carry tag {engine id, engine tag}; responses may come back in any
// order and are routed to the engine named in their tag. Soft reset: new requests are held,
// responses are still taken until no engine has one outstanding, finished pixels are
// dropped, open bursts complete; then every unit is cleared (docs/architecture_system.md).
module msr_top import msr_pkg::*; #(
  parameter int unsigned NUM_ENGINES     = 4,    // parallel tile engines (claim 11)
  parameter int unsigned MAX_OUTSTANDING = 16,   // render requests in flight per engine
  parameter int unsigned AXI_ID_W        = 4,    // frame-buffer AXI ID width
  localparam int unsigned EID_W  = (NUM_ENGINES > 1) ? $clog2(NUM_ENGINES) : 1,
  localparam int unsigned ETAG_W = $clog2(MAX_OUTSTANDING),
  localparam int unsigned RTAG_W = EID_W + ETAG_W
) (
  input  logic              clk_i,              // clock
  input  logic              rst_ni,             // asynchronous reset, active low
  // AXI4-Lite register port (7-bit byte address).
  input  logic              s_axil_awvalid,
  output logic              s_axil_awready,
  input  logic [6:0]        s_axil_awaddr,
  input  logic [2:0]        s_axil_awprot,
  input  logic              s_axil_wvalid,
  output logic              s_axil_wready,
  input  logic [31:0]       s_axil_wdata,
  input  logic [3:0]        s_axil_wstrb,
  output logic              s_axil_bvalid,
  input  logic              s_axil_bready,
  output logic [1:0]        s_axil_bresp,
  input  logic              s_axil_arvalid,
  output logic              s_axil_arready,
  input  logic [6:0]        s_axil_araddr,
  input  logic [2:0]        s_axil_arprot,
  output logic              s_axil_rvalid,
  input  logic              s_axil_rready,
  output logic [31:0]       s_axil_rdata,
  output logic [1:0]        s_axil_rresp,
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
  // AXI4 frame-buffer write master.
  output logic [AXI_ID_W-1:0] m_axi_awid,
  output logic [31:0]       m_axi_awaddr,
  output logic [7:0]        m_axi_awlen,
  output logic [2:0]        m_axi_awsize,
  output logic [1:0]        m_axi_awburst,
  output logic              m_axi_awlock,
  output logic [3:0]        m_axi_awcache,
  output logic [2:0]        m_axi_awprot,
  output logic              m_axi_awvalid,
  input  logic              m_axi_awready,
  output logic [31:0]       m_axi_wdata,
  output logic [3:0]        m_axi_wstrb,
  output logic              m_axi_wlast,
  output logic              m_axi_wvalid,
  input  logic              m_axi_wready,
  input  logic [AXI_ID_W-1:0] m_axi_bid,
  input  logic [1:0]        m_axi_bresp,
  input  logic              m_axi_bvalid,
  output logic              m_axi_bready,
  // Interrupt: STATUS.DONE while CTRL.IRQ_EN.
  output logic              irq_o
);
  if (NUM_ENGINES < 1 || NUM_ENGINES > 16) begin : gen_bad_engines
    $fatal(1, "msr_top: NUM_ENGINES must be 1..16, got %0d", NUM_ENGINES);
  end
  if (MAX_OUTSTANDING < 2 || (1 << ETAG_W) != MAX_OUTSTANDING) begin : gen_bad_outstanding
    $fatal(1, "msr_top: MAX_OUTSTANDING must be a power of two >= 2, got %0d", MAX_OUTSTANDING);
  end

  // Error codes of STATUS.ERROR (rtl/regs/msr_regs.rdl).
  typedef enum logic [3:0] {
    ERR_NONE       = 4'd0,
    ERR_FRAME_SIZE = 4'd1,
    ERR_TILE       = 4'd2,
    ERR_LEVELS     = 4'd3,
    ERR_FB_STRIDE  = 4'd4,
    ERR_FB_BASE    = 4'd5,
    ERR_SRC_STRIDE = 4'd6,
    ERR_SRC_BASE   = 4'd7,
    ERR_AXI_WRITE  = 4'd8
  } err_e;

  typedef enum logic [1:0] {
    ST_IDLE  = 2'd0,   // no frame
    ST_RUN   = 2'd1,   // frame in progress
    ST_DRAIN = 2'd2    // soft reset: waiting for outstanding responses and writes
  } state_e;

  // ---- Registers --------------------------------------------------------------------------------
  msr_regs_pkg::msr_regs__in_t  hwif_in;
  msr_regs_pkg::msr_regs__out_t hwif_out;

  msr_regs u_regs (
    .clk            (clk_i),
    .arst_n         (rst_ni),
    .s_axil_awready (s_axil_awready),
    .s_axil_awvalid (s_axil_awvalid),
    .s_axil_awaddr  (s_axil_awaddr),
    .s_axil_awprot  (s_axil_awprot),
    .s_axil_wready  (s_axil_wready),
    .s_axil_wvalid  (s_axil_wvalid),
    .s_axil_wdata   (s_axil_wdata),
    .s_axil_wstrb   (s_axil_wstrb),
    .s_axil_bready  (s_axil_bready),
    .s_axil_bvalid  (s_axil_bvalid),
    .s_axil_bresp   (s_axil_bresp),
    .s_axil_arready (s_axil_arready),
    .s_axil_arvalid (s_axil_arvalid),
    .s_axil_araddr  (s_axil_araddr),
    .s_axil_arprot  (s_axil_arprot),
    .s_axil_rready  (s_axil_rready),
    .s_axil_rvalid  (s_axil_rvalid),
    .s_axil_rdata   (s_axil_rdata),
    .s_axil_rresp   (s_axil_rresp),
    .hwif_in        (hwif_in),
    .hwif_out       (hwif_out)
  );

  // ---- Configuration check and latch ----------------------------------------------------------
  typedef struct packed {
    dim_t                  width;
    dim_t                  height;
    tile_size_e            tile;
    level_t                levels;
    metric_e               metric;
    thr_t [MAX_LEVELS-1:0] thr;
    logic [7:0]            fov_gain;
    logic [31:0]           fb_base;
    logic [31:0]           fb_stride;
    logic                  src_en;
    logic [31:0]           src_base;
    logic [31:0]           src_stride;
  } cfg_t;

  cfg_t cfg_q, cfg_new;
  err_e cfg_err;

  always_comb begin
    cfg_new.width      = hwif_out.FRAME_SIZE.WIDTH.value;
    cfg_new.height     = hwif_out.FRAME_SIZE.HEIGHT.value;
    unique case (hwif_out.CONFIG.TILE.value)
      6'd8:    cfg_new.tile = TILE_8;
      6'd32:   cfg_new.tile = TILE_32;
      default: cfg_new.tile = TILE_16;
    endcase
    cfg_new.levels     = hwif_out.CONFIG.LEVELS.value;
    cfg_new.metric     = metric_e'(hwif_out.CONFIG.METRIC.value);
    cfg_new.thr        = {hwif_out.THRESH.THR3.value, hwif_out.THRESH.THR2.value,
                          hwif_out.THRESH.THR1.value};
    cfg_new.fov_gain   = hwif_out.FOV_GAIN.GAIN.value;
    cfg_new.fb_base    = hwif_out.FB_BASE.ADDR.value;
    cfg_new.fb_stride  = hwif_out.FB_STRIDE.STRIDE.value;
    cfg_new.src_en     = hwif_out.SRC_CTRL.ENABLE.value;
    cfg_new.src_base   = hwif_out.SRC_BASE.ADDR.value;
    cfg_new.src_stride = hwif_out.SRC_STRIDE.STRIDE.value;

    // First failing check wins; the order is the order of the codes.
    if (cfg_new.width == '0 || cfg_new.width > dim_t'(MAX_FRAME) ||
        cfg_new.height == '0 || cfg_new.height > dim_t'(MAX_FRAME)) begin
      cfg_err = ERR_FRAME_SIZE;
    end else if (!(hwif_out.CONFIG.TILE.value inside {6'd8, 6'd16, 6'd32})) begin
      cfg_err = ERR_TILE;
    end else if (cfg_new.levels == '0) begin
      cfg_err = ERR_LEVELS;
    end else if (cfg_new.fb_stride < {17'b0, cfg_new.width, 2'b0} ||
                 cfg_new.fb_stride[1:0] != '0) begin
      cfg_err = ERR_FB_STRIDE;
    end else if (cfg_new.fb_base[1:0] != '0) begin
      cfg_err = ERR_FB_BASE;
    end else if (cfg_new.src_en &&
                 (cfg_new.src_stride < {19'b0, cfg_new.width} ||
                  cfg_new.src_stride[1:0] != '0)) begin
      cfg_err = ERR_SRC_STRIDE;
    end else if (cfg_new.src_en && cfg_new.src_base[1:0] != '0) begin
      cfg_err = ERR_SRC_BASE;
    end else begin
      cfg_err = ERR_NONE;
    end
  end

  // ---- Control ----------------------------------------------------------------------------------
  state_e  state_q, state_d;
  err_e    err_q, err_d;
  logic    start_frame;        // a valid START in idle
  logic    clear;              // synchronous clear of every unit (end of a soft reset)
  logic    frame_done;
  logic    drain;
  logic    tg_done;
  logic    wr_idle, wr_tile_done, wr_bresp_err;
  logic [23:0] tiles_given_q, tiles_written_q;     // up to 512 x 512 tiles
  logic [NUM_ENGINES-1:0] eng_desc_valid, eng_desc_ready, eng_busy;
  logic    tg_busy;
  logic    inflight_any;
  logic    req_pending_q;     // a render request was offered and not yet taken

  assign drain = (state_q == ST_DRAIN);

  always_comb begin
    state_d     = state_q;
    err_d       = err_q;
    start_frame = 1'b0;
    clear       = 1'b0;
    unique case (state_q)
      ST_IDLE: begin
        if (hwif_out.CTRL.START.value) begin
          err_d = cfg_err;
          if (cfg_err == ERR_NONE) begin
            start_frame = 1'b1;
            state_d     = ST_RUN;
          end
        end
      end
      ST_RUN: begin
        if (wr_bresp_err) err_d = ERR_AXI_WRITE;
        if (frame_done) state_d = ST_IDLE;
      end
      ST_DRAIN: begin
        // Every response is home, no request half-offered, every open burst finished.
        if (!inflight_any && !req_pending_q && wr_idle) begin
          clear   = 1'b1;
          err_d   = ERR_NONE;
          state_d = ST_IDLE;
        end
      end
      default: state_d = ST_IDLE;
    endcase
    if (hwif_out.CTRL.SOFT_RESET.value && state_q != ST_DRAIN) begin
      state_d     = ST_DRAIN;
      start_frame = 1'b0;
    end
  end

  assign frame_done = (state_q == ST_RUN) && tg_done && (tiles_written_q == tiles_given_q) &&
                      wr_idle;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      state_q <= ST_IDLE;
      err_q   <= ERR_NONE;
      cfg_q   <= '0;
    end else begin
      state_q <= state_d;
      err_q   <= err_d;
      if (start_frame) cfg_q <= cfg_new;
    end
  end

  assign hwif_in.STATUS.BUSY.next   = (state_q != ST_IDLE);
  assign hwif_in.STATUS.ERROR.next  = err_q;
  assign hwif_in.STATUS.DONE.hwset  = frame_done;
  assign hwif_in.STATUS.DONE.hwclr  = start_frame || hwif_out.CTRL.SOFT_RESET.value;
  assign irq_o = hwif_out.CTRL.IRQ_EN.value && hwif_out.STATUS.DONE.value;

  // ---- Tile generation -------------------------------------------------------------------------
  tile_desc_t desc;

  tile_gen #(.NUM_ENGINES(NUM_ENGINES)) u_tile_gen (
    .clk_i        (clk_i),
    .rst_ni       (rst_ni),
    .clear_i      (clear || (hwif_out.CTRL.SOFT_RESET.value)),
    .start_i      (start_frame),
    .width_i      (start_frame ? cfg_new.width : cfg_q.width),
    .height_i     (start_frame ? cfg_new.height : cfg_q.height),
    .tile_i       (start_frame ? cfg_new.tile : cfg_q.tile),
    .levels_i     (cfg_q.levels),
    .metric_i     (cfg_q.metric),
    .thr_i        (cfg_q.thr),
    .fov_gain_i   (cfg_q.fov_gain),
    .desc_valid_o (eng_desc_valid),
    .desc_ready_i (eng_desc_ready & {NUM_ENGINES{state_q == ST_RUN}}),
    .desc_o       (desc),
    .busy_o       (tg_busy),
    .done_o       (tg_done)
  );

  // ---- Engines ----------------------------------------------------------------------------------
  logic   [NUM_ENGINES-1:0] eng_req_valid, eng_req_ready;
  coord_t [NUM_ENGINES-1:0] eng_req_x, eng_req_y;
  logic   [NUM_ENGINES-1:0][ETAG_W-1:0] eng_req_tag;
  logic   [NUM_ENGINES-1:0] eng_rsp_valid, eng_rsp_ready;
  logic   [NUM_ENGINES-1:0] eng_pix_valid, eng_pix_ready, eng_pix_last;
  coord_t [NUM_ENGINES-1:0] eng_pix_x, eng_pix_y;
  rgb_t   [NUM_ENGINES-1:0] eng_pix_rgb;
  src_t   [NUM_ENGINES-1:0] eng_pix_src;
  logic   [NUM_ENGINES-1:0][ETAG_W:0] eng_inflight;
  logic   [EID_W-1:0] rsp_eid;

  assign rsp_eid = rnd_rsp_tag_i[RTAG_W-1 -: EID_W];

  for (genvar i = 0; i < NUM_ENGINES; i++) begin : gen_engine
    tile_engine #(.MAX_OUTSTANDING(MAX_OUTSTANDING)) u_engine (
      .clk_i        (clk_i),
      .rst_ni       (rst_ni),
      .clear_i      (clear),
      .desc_valid_i (eng_desc_valid[i]),
      .desc_ready_o (eng_desc_ready[i]),
      .desc_i       (desc),
      .req_valid_o  (eng_req_valid[i]),
      .req_ready_i  (eng_req_ready[i]),
      .req_x_o      (eng_req_x[i]),
      .req_y_o      (eng_req_y[i]),
      .req_tag_o    (eng_req_tag[i]),
      .rsp_valid_i  (eng_rsp_valid[i]),
      .rsp_ready_o  (eng_rsp_ready[i]),
      .rsp_tag_i    (rnd_rsp_tag_i[ETAG_W-1:0]),
      .rsp_rgb_i    (rnd_rsp_rgb_i),
      .pix_valid_o  (eng_pix_valid[i]),
      .pix_ready_i  (eng_pix_ready[i]),
      .pix_x_o      (eng_pix_x[i]),
      .pix_y_o      (eng_pix_y[i]),
      .pix_rgb_o    (eng_pix_rgb[i]),
      .pix_src_o    (eng_pix_src[i]),
      .pix_last_o   (eng_pix_last[i]),
      .busy_o       (eng_busy[i]),
      .inflight_o   (eng_inflight[i])
    );
    assign eng_rsp_valid[i] = rnd_rsp_valid_i && (rsp_eid == EID_W'(i));
  end

  always_comb begin
    inflight_any = 1'b0;
    for (int i = 0; i < NUM_ENGINES; i++) inflight_any |= (eng_inflight[i] != '0);
  end

  // Response demux: the engine named in the tag answers ready.
  assign rnd_rsp_ready_o = eng_rsp_ready[rsp_eid];

  // ---- Round-robin pick: the first set bit at or after `ptr` ------------------------------------
  function automatic logic [EID_W-1:0] rr_pick(logic [NUM_ENGINES-1:0] mask, logic [EID_W-1:0] ptr);
    logic [EID_W-1:0] sel;
    sel = ptr;
    for (int k = NUM_ENGINES - 1; k >= 0; k--) begin
      logic [EID_W-1:0] idx;
      idx = EID_W'((int'(ptr) + k) % NUM_ENGINES);
      if (mask[idx]) sel = idx;
    end
    return sel;
  endfunction

  // ---- Render request arbiter: round robin, held while offered and not taken ----------------
  logic [EID_W-1:0] req_ptr_q, req_ptr_d, req_sel, req_lock_q;
  logic             req_hs;

  always_comb begin
    req_sel         = req_pending_q ? req_lock_q : rr_pick(eng_req_valid, req_ptr_q);
    // During a soft reset only a request already on the port may complete.
    rnd_req_valid_o = eng_req_valid[req_sel] && (!drain || req_pending_q) && (state_q != ST_IDLE);
    rnd_req_x_o     = eng_req_x[req_sel];
    rnd_req_y_o     = eng_req_y[req_sel];
    rnd_req_tag_o   = {req_sel, eng_req_tag[req_sel]};
    req_hs          = rnd_req_valid_o && rnd_req_ready_i;
    eng_req_ready   = '0;
    eng_req_ready[req_sel] = rnd_req_ready_i && rnd_req_valid_o;
    req_ptr_d       = req_ptr_q;
    if (req_hs) req_ptr_d = (req_sel == EID_W'(NUM_ENGINES - 1)) ? '0 : req_sel + 1'b1;
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      req_ptr_q     <= '0;
      req_lock_q    <= '0;
      req_pending_q <= 1'b0;
    end else if (clear) begin
      req_ptr_q     <= '0;
      req_lock_q    <= '0;
      req_pending_q <= 1'b0;
    end else begin
      req_ptr_q     <= req_ptr_d;
      req_lock_q    <= req_sel;
      req_pending_q <= rnd_req_valid_o && !rnd_req_ready_i;
    end
  end

  // ---- Pixel arbiter: round robin, locked on a tile row (one burst per row) ---------------
  // Lint: Verilator sees ready -> engine -> valid -> pix_sel as a loop over the whole vectors;
  // an engine's pix_valid_o is a register (msr_tile_stream), so there is no real loop.
  /* verilator lint_off UNOPTFLAT */
  logic [EID_W-1:0] pix_sel;
  /* verilator lint_on UNOPTFLAT */
  logic [EID_W-1:0] pix_ptr_q, pix_ptr_d, pix_lock_q, pix_lock_d;
  logic             pix_locked_q, pix_locked_d;
  logic             wr_pix_valid, wr_pix_ready, wr_row_end, pix_hs;

  always_comb begin
    pix_sel       = pix_locked_q ? pix_lock_q : rr_pick(eng_pix_valid, pix_ptr_q);
    wr_pix_valid  = eng_pix_valid[pix_sel] && !drain;
    pix_hs        = wr_pix_valid && wr_pix_ready;
    eng_pix_ready = '0;
    eng_pix_ready[pix_sel] = wr_pix_ready;
    if (drain) eng_pix_ready = '1;     // soft reset: finished pixels are dropped
    pix_ptr_d    = pix_ptr_q;
    pix_lock_d   = pix_lock_q;
    pix_locked_d = pix_locked_q;
    if (pix_hs) begin
      pix_locked_d = !wr_row_end;
      pix_lock_d   = pix_sel;
      if (wr_row_end) pix_ptr_d = (pix_sel == EID_W'(NUM_ENGINES - 1)) ? '0 : pix_sel + 1'b1;
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      pix_ptr_q    <= '0;
      pix_lock_q   <= '0;
      pix_locked_q <= 1'b0;
    end else if (clear) begin
      pix_ptr_q    <= '0;
      pix_lock_q   <= '0;
      pix_locked_q <= 1'b0;
    end else begin
      pix_ptr_q    <= pix_ptr_d;
      pix_lock_q   <= pix_lock_d;
      pix_locked_q <= pix_locked_d;
    end
  end

  // ---- Frame-buffer writer ----------------------------------------------------------------------
  fb_writer #(.ID_W(AXI_ID_W)) u_fb_writer (
    .clk_i         (clk_i),
    .rst_ni        (rst_ni),
    .clear_i       (clear),
    .width_i       (cfg_q.width),
    .tile_i        (cfg_q.tile),
    .fb_base_i     (cfg_q.fb_base),
    .fb_stride_i   (cfg_q.fb_stride),
    .src_en_i      (cfg_q.src_en),
    .src_base_i    (cfg_q.src_base),
    .src_stride_i  (cfg_q.src_stride),
    .pix_valid_i   (wr_pix_valid),
    .pix_ready_o   (wr_pix_ready),
    .pix_x_i       (eng_pix_x[pix_sel]),
    .pix_y_i       (eng_pix_y[pix_sel]),
    .pix_rgb_i     (eng_pix_rgb[pix_sel]),
    .pix_src_i     (eng_pix_src[pix_sel]),
    .pix_last_i    (eng_pix_last[pix_sel]),
    .pix_row_end_o (wr_row_end),
    .m_axi_awid    (m_axi_awid),
    .m_axi_awaddr  (m_axi_awaddr),
    .m_axi_awlen   (m_axi_awlen),
    .m_axi_awsize  (m_axi_awsize),
    .m_axi_awburst (m_axi_awburst),
    .m_axi_awlock  (m_axi_awlock),
    .m_axi_awcache (m_axi_awcache),
    .m_axi_awprot  (m_axi_awprot),
    .m_axi_awvalid (m_axi_awvalid),
    .m_axi_awready (m_axi_awready),
    .m_axi_wdata   (m_axi_wdata),
    .m_axi_wstrb   (m_axi_wstrb),
    .m_axi_wlast   (m_axi_wlast),
    .m_axi_wvalid  (m_axi_wvalid),
    .m_axi_wready  (m_axi_wready),
    .m_axi_bid     (m_axi_bid),
    .m_axi_bresp   (m_axi_bresp),
    .m_axi_bvalid  (m_axi_bvalid),
    .m_axi_bready  (m_axi_bready),
    .idle_o        (wr_idle),
    .tile_done_o   (wr_tile_done),
    .bresp_err_o   (wr_bresp_err)
  );

  // ---- Tile accounting and performance counters -------------------------------------------------
  logic [31:0] perf_cycles_q, perf_rstall_q, perf_mstall_q;
  logic [3:0][31:0] perf_traced_q;
  logic [2:0][31:0] perf_interp_q;
  logic        count_en;
  src_t        hs_src;

  assign count_en = (state_q == ST_RUN);
  assign hs_src   = eng_pix_src[pix_sel];

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      tiles_given_q   <= '0;
      tiles_written_q <= '0;
      perf_cycles_q   <= '0;
      perf_rstall_q   <= '0;
      perf_mstall_q   <= '0;
      perf_traced_q   <= '0;
      perf_interp_q   <= '0;
    end else if (start_frame || clear) begin
      tiles_given_q   <= '0;
      tiles_written_q <= '0;
      perf_cycles_q   <= '0;
      perf_rstall_q   <= '0;
      perf_mstall_q   <= '0;
      perf_traced_q   <= '0;
      perf_interp_q   <= '0;
    end else if (count_en) begin
      if (|eng_desc_valid) tiles_given_q <= tiles_given_q + 1'b1;   // valid only to a ready engine
      if (wr_tile_done)    tiles_written_q <= tiles_written_q + 1'b1;
      perf_cycles_q <= perf_cycles_q + 1'b1;
      if (rnd_req_valid_o && !rnd_req_ready_i) perf_rstall_q <= perf_rstall_q + 1'b1;
      if ((|eng_pix_valid) && !pix_hs)          perf_mstall_q <= perf_mstall_q + 1'b1;
      if (pix_hs) begin
        if (hs_src[4]) begin
          perf_interp_q[hs_src[1:0] - 2'd1] <= perf_interp_q[hs_src[1:0] - 2'd1] + 1'b1;
        end else begin
          perf_traced_q[hs_src[1:0]] <= perf_traced_q[hs_src[1:0]] + 1'b1;
        end
      end
    end
  end

  assign hwif_in.PERF_CYCLES.COUNT.next       = perf_cycles_q;
  assign hwif_in.PERF_RENDER_STALL.COUNT.next = perf_rstall_q;
  assign hwif_in.PERF_MEM_STALL.COUNT.next    = perf_mstall_q;
  for (genvar k = 0; k < 4; k++) begin : gen_perf_traced
    assign hwif_in.PERF_TRACED[k].COUNT.next = perf_traced_q[k];
  end
  for (genvar k = 0; k < 3; k++) begin : gen_perf_interp
    assign hwif_in.PERF_INTERP[k].COUNT.next = perf_interp_q[k];
  end

  logic unused_top;
  assign unused_top = ^{tg_busy, eng_busy, hs_src[7:5], hs_src[3:2]};

`ifndef SYNTHESIS
  // Lint: disable iff (!rst_ni) looks like a synchronous use of the asynchronous reset.
  /* verilator lint_off SYNCASYNCNET */
  // Render port: an offered request stays until taken (also across a soft reset).
  assert property (@(posedge clk_i) disable iff (!rst_ni || clear)
                   rnd_req_valid_o && !rnd_req_ready_i |=>
                   rnd_req_valid_o && $stable(rnd_req_tag_o));
  // A response always names an engine that exists.
  assert property (@(posedge clk_i) disable iff (!rst_ni)
                   rnd_rsp_valid_i |->
                   rsp_eid < EID_W'(NUM_ENGINES) || NUM_ENGINES == (1 << EID_W));
`endif
endmodule
