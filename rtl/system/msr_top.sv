// The accelerator: registers (AXI4-Lite), tile generation, NUM_ENGINES tile engines sharing
// one render request/response port, and one frame-buffer writer (AXI4 write master).
//
// Render port: requests carry tag {engine id, engine tag}; responses may come back in any
// order and are routed to the engine named in their tag. Soft reset: new requests are held,
// responses are still taken until no engine has one outstanding, finished pixels are
// dropped, open bursts complete; then every unit is cleared (docs/architecture_system.md).
module msr_top import msr_pkg::*; #(
  parameter int unsigned NUM_ENGINES     = 4,    // parallel tile engines (claim 11)
  parameter int unsigned MAX_OUTSTANDING = 64,   // render requests in flight per engine (tags)
  parameter int unsigned NUM_CTX         = 8,    // tile contexts per engine (2..16)
  parameter int unsigned AXI_ID_W        = 4,    // frame-buffer AXI ID width
  parameter int unsigned AXI_DATA_W      = 256,  // frame-buffer AXI data width (32..256)
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
  output logic [AXI_DATA_W-1:0]   m_axi_wdata,
  output logic [AXI_DATA_W/8-1:0] m_axi_wstrb,
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
  logic    wr_idle, wr_bresp_err;
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

  msr_tile_gen #(.NUM_ENGINES(NUM_ENGINES)) u_tile_gen (
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
    msr_tile_engine #(
      .NUM_CTX         (NUM_CTX),
      .MAX_OUTSTANDING (MAX_OUTSTANDING)
    ) u_engine (
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

  // ---- Render request queues: a short FIFO per engine ---------------------------------------
  // An engine whose request waits for the shared port stalls its decision pipeline; a queue
  // per engine lets it go on deciding while other engines' requests go first (its tag is
  // already counted in flight). During a soft reset no new request enters, queued ones go
  // out, so every tag in flight comes home.
  typedef struct packed {
    coord_t              x;
    coord_t              y;
    logic [ETAG_W-1:0]   tag;
  } rreq_t;
  logic  [NUM_ENGINES-1:0] rq_valid, rq_pop, rq_push_ready;
  rreq_t [NUM_ENGINES-1:0] rq_data;

  for (genvar i = 0; i < NUM_ENGINES; i++) begin : gen_req_queue
    msr_fifo #(.WIDTH($bits(rreq_t)), .DEPTH(4)) u_req_fifo (
      .clk_i   (clk_i),
      .rst_ni  (rst_ni),
      .flush_i (clear),
      .valid_i (eng_req_valid[i] && !drain),
      .ready_o (rq_push_ready[i]),
      .data_i  ({eng_req_x[i], eng_req_y[i], eng_req_tag[i]}),
      .valid_o (rq_valid[i]),
      .ready_i (rq_pop[i]),
      .data_o  (rq_data[i]),
      .count_o ()
    );
    assign eng_req_ready[i] = rq_push_ready[i] && !drain;
  end

  // ---- Render request arbiter: round robin over the queues, held while offered -------------
  logic [EID_W-1:0] req_ptr_q, req_ptr_d, req_sel, req_lock_q;
  logic             req_hs;

  always_comb begin
    req_sel         = req_pending_q ? req_lock_q : rr_pick(rq_valid, req_ptr_q);
    rnd_req_valid_o = rq_valid[req_sel] && (state_q != ST_IDLE);
    rnd_req_x_o     = rq_data[req_sel].x;
    rnd_req_y_o     = rq_data[req_sel].y;
    rnd_req_tag_o   = {req_sel, rq_data[req_sel].tag};
    req_hs          = rnd_req_valid_o && rnd_req_ready_i;
    rq_pop          = '0;
    rq_pop[req_sel] = req_hs;
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

  // ---- Pixel path: every engine has its own writer input (no arbitration) -----------------
  logic [NUM_ENGINES-1:0] wr_pix_valid, wr_pix_ready, pix_hs, wr_tile_done;

  assign wr_pix_valid  = drain ? '0 : eng_pix_valid;
  assign eng_pix_ready = drain ? '1 : wr_pix_ready;     // soft reset: finished pixels are dropped
  assign pix_hs        = wr_pix_valid & wr_pix_ready;

  // ---- Frame-buffer writer ----------------------------------------------------------------------
  msr_fb_writer #(
    .NUM_IN     (NUM_ENGINES),
    .AXI_DATA_W (AXI_DATA_W),
    .ID_W       (AXI_ID_W)
  ) u_fb_writer (
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
    .pix_x_i       (eng_pix_x),
    .pix_y_i       (eng_pix_y),
    .pix_rgb_i     (eng_pix_rgb),
    .pix_src_i     (eng_pix_src),
    .pix_last_i    (eng_pix_last),
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

  assign count_en = (state_q == ST_RUN);

  // Pixels taken this clock, per kind (up to NUM_ENGINES per clock).
  logic [3:0][EID_W:0] n_traced;
  logic [2:0][EID_W:0] n_interp;
  logic [EID_W:0]      n_tiles;
  always_comb begin
    n_traced = '0;
    n_interp = '0;
    n_tiles  = '0;
    for (int unsigned i = 0; i < NUM_ENGINES; i++) begin
      n_tiles += (EID_W + 1)'(wr_tile_done[i]);
      if (pix_hs[i]) begin
        // source codes: 0..3 traced at level k, 17..19 interpolated at level 1..3
        if (eng_pix_src[i][4]) n_interp[eng_pix_src[i][1:0] - 2'd1] += 1'b1;
        else                   n_traced[eng_pix_src[i][1:0]] += 1'b1;
      end
    end
  end

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
      tiles_written_q <= tiles_written_q + 24'(n_tiles);
      perf_cycles_q <= perf_cycles_q + 1'b1;
      if (rnd_req_valid_o && !rnd_req_ready_i) perf_rstall_q <= perf_rstall_q + 1'b1;
      // memory stall: some engine offers a pixel the writer cannot take
      if ((eng_pix_valid & ~wr_pix_ready) != '0) perf_mstall_q <= perf_mstall_q + 1'b1;
      for (int unsigned k = 0; k < 4; k++) perf_traced_q[k] <= perf_traced_q[k] + 32'(n_traced[k]);
      for (int unsigned k = 0; k < 3; k++) perf_interp_q[k] <= perf_interp_q[k] + 32'(n_interp[k]);
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
  assign unused_top = ^{tg_busy, eng_busy};

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
