// Configuration check and frame control of the accelerator.
//
// START in idle samples the registers (SAMPLE) and checks them from registers (CHECK, 27
// clocks): every field check into a flag of its own (CONFIG.TILE: 8, 16 or 32 and at most the
// top's TILE_LIMIT, code 2); the byte range of each plane, whether it
// wraps past 4 GiB and whether the two overlap (msr_cfg_ranges); the rule encoding
// (CONFIG.RULE 2 or 3, or 1 in a top built without it, LINDILATE 0: code 13); with a ray budget
// (BUDGET non-zero), the budget controller's own check, run beside these from the sampled registers
// (codes 14 and 15; a top built without it, BUDGET_EN 0, refuses any budget with 14); with
// GAZE.EN, a gaze point outside the frame (code 16), and the gaze in half tiles, cx = (2X + T/2)
// >> log2 T (likewise cy), latched with the configuration (msr_cfg_gaze). The first
// failing check in the order of the error codes wins: the configuration is latched and the frame
// starts, or the error is reported (STATUS.ERROR, STATUS.CFG_ERR and the interrupt) and the
// accelerator stays idle (no render request, no memory write). A frame ends when the tile generator
// has handed out every tile, every tile's last pixel has reached the writer and the writer is idle.
// SOFT_RESET in any state: DRAIN until no render request is in flight and the writer is idle, then
// one CLEAR cycle (every unit's synchronous clear, sent a clock later from one register per engine
// and one for the rest), then idle. The interrupt pin is registered here too.
//
// Watchdog (docs/system.md "Watchdog"): WATCHDOG cycles in a row without progress end a frame
// (CLEAR at once, STATUS.ERROR 12, STATUS.WDOG) and bound a soft reset's drain (DRAIN_TIMEOUT
// when 0); responses are not progress in a drain, so no unit can hold it open.
//
// Memory errors (SLVERR / DECERR write responses) set STATUS.ERROR = 8 for the frame (the
// frame still completes), are counted (saturating), and the address of the first failing burst
// is kept; all three survive a soft reset (a drain is when errors tend to show) and are
// cleared by the next START.
`include "msr_assert.svh"
`include "msr_flops.svh"

module msr_cfg_ctrl import msr_pkg::*; import msr_sys_pkg::*; #(
  parameter int unsigned NUM_ENGINES   = 4,      // tile engines (tile-done inputs)
  parameter int unsigned DRAIN_TIMEOUT = 16384,  // drain bound without progress when WATCHDOG is 0
  parameter int unsigned LINDILATE     = 1,      // 0: patent-only engines, CONFIG.RULE 1 refused
  parameter int unsigned TILE_LIMIT    = 32,     // the largest T the tile buffers hold (8, 16, 32)
  parameter bit          BUDGET_EN     = 1'b0    // the ray-budget controller is built in
) (
  input  logic                   clk_i,          // clock
  input  logic                   rst_ni,         // asynchronous reset, active low
  // Register interface.
  input  logic                   start_i,        // CTRL.START written (a pulse)
  input  logic                   soft_reset_i,   // CTRL.SOFT_RESET written (a pulse)
  input  logic [31:0]            wdog_limit_i,   // WATCHDOG: cycles without progress, 0 = off
  input  cfg_raw_t               raw_i,          // configuration registers
  output cfg_t                   cfg_o,          // checked configuration of the frame
  output logic                   busy_o,         // STATUS.BUSY
  output err_e                   err_o,          // STATUS.ERROR
  output logic                   done_set_o,     // STATUS.DONE: the frame is complete
  output logic                   done_clr_o,     // STATUS.DONE, CFG_ERR cleared (START, SOFT_RESET)
  output logic                   cfg_err_set_o,  // STATUS.CFG_ERR: a START was refused
  output logic                   wdog_set_o,     // STATUS.WDOG: the watchdog forced a CLEAR
  output err_counts_t            err_counts_o,   // MEM_ERR, MEM_ERR_ADDR, RSP_DROP
  input  logic                   irq_en_i,       // CTRL.IRQ_EN
  input  logic [2:0]             irq_flags_i,    // STATUS.DONE, CFG_ERR, WDOG
  output logic                   irq_o,          // the interrupt pin, a clock after the flags
  // Units.
  output logic                   start_o,        // pulse: the frame starts with cfg_o
  output logic                   run_o,          // a frame runs: tiles may be handed out
  output logic                   drain_o,        // soft reset: hold requests, drop pixels
  output logic [NUM_ENGINES-1:0] eng_drain_o,    // drain_o, the same clock, a register per engine
  output logic                   clear_o,        // pulse: synchronous clear of the system units
  output logic [NUM_ENGINES-1:0] eng_clear_o,    // the same pulse, one register per engine
  input  logic                   desc_fire_i,    // a tile went to an engine
  input  logic [NUM_ENGINES-1:0] tile_done_i,    // the last pixel of a tile reached the writer
  input  logic                   tg_done_i,      // the tile generator handed out every tile
  input  logic                   rnd_idle_i,     // no render request in flight in any engine
  input  logic                   wr_idle_i,      // the writer has nothing open or outstanding
  input  logic                   bresp_err_i,    // pulse: a write error response
  input  logic [31:0]            bresp_addr_i,   // its burst's address
  input  logic                   b_unexp_i,      // pulse: a write response with nothing outstanding
  input  logic [NUM_ENGINES-1:0] rsp_drop_i,     // engine i dropped a render response
  input  logic                   bad_eid_i,      // the render mux dropped one (no such engine)
  input  logic                   moved_i,        // a handshake on the ports (watchdog progress)
  input  logic                   rsp_taken_i,    // a render response taken (progress in RUN)
  // Ray budget controller (BUDGET_EN).
  output cfg_raw_t               raw_o,          // the sampled registers, from bud_check_o on
  output logic                   bud_check_o,    // pulse: check the sampled budget registers
  input  logic                   bud_done_i,     // its check is done (within 21 clocks) ...
  input  logic                   bud_err_budget_i,   // ... BUDGET below the initial grid
  input  logic                   bud_err_profile_i,  // ... SEEDED without a matching memory
  input  logic                   bud_busy_i      // a budget frame's rows are not all accounted
);
  if (!(TILE_LIMIT inside {8, 16, 32})) begin : g_check_tile_limit
    $fatal(1, "msr_cfg_ctrl: TILE_LIMIT must be 8, 16 or 32, got %0d", TILE_LIMIT);
  end
  if (NUM_ENGINES > 30) begin : g_check_engines
    $fatal(1, "msr_cfg_ctrl: NUM_ENGINES must be 1..30 (5-bit drop count), got %0d", NUM_ENGINES);
  end
  typedef enum logic [2:0] {
    ST_IDLE   = 3'd0,   // no frame
    ST_SAMPLE = 3'd1,   // registers sampled
    ST_CHECK  = 3'd2,   // checks running
    ST_RUN    = 3'd3,   // frame in progress
    ST_DRAIN  = 3'd4,   // soft reset: waiting for outstanding responses and writes
    ST_CLEAR  = 3'd5    // soft reset: every unit clears
  } state_e;

  localparam int unsigned NCHK  = 10;
  localparam int unsigned TIF_W = 8;                  // tiles in flight: engines x (contexts + 1)
  // CHECK steps: 0..19 the plane ranges' ends (msr_cfg_ranges), 20..25 their compares, 26
  // decide.
  localparam int unsigned STEP_CMP = 20, STEP_END = 26;

  state_e           state_q, state_d;
  cfg_raw_t         raw_q;
  cfg_t             cfg_q;
  err_e             err_q, err_d;
  logic [NCHK-1:0]  chk_q;             // check k failed (error code order)
  logic             rule_chk_q;        // CONFIG.RULE 2, 3 or not built (code 13, after the overlap)
  logic             gaze_err;          // GAZE.EN and the point outside the frame (code 16, last)
  half_t            gaze_cx, gaze_cy;  // the gaze in half tiles, from the sampled registers
  logic [4:0]       step_q;
  logic             frame_done_q;
  logic [TIF_W-1:0] tif_q;             // tiles handed out and not yet fully written
  logic [$clog2(NUM_ENGINES+1)-1:0] n_done;
  logic             start_q, refused_q;
  logic [15:0]      mem_err_cnt_q;
  logic [31:0]      mem_err_addr_q;
  logic             b_unexp_q;
  logic             accept;            // CHECK ends with every check passed
  logic             wd_fire;           // the watchdog ends the frame or the drain

  // ---- Clear and drain fan-out ---------------------------------------------------------------
  // The soft reset's clear reaches every flip-flop of the design: one register per engine and
  // one for the rest, so that no path runs from the state register across the die into some
  // forty thousand loads. Every unit clears on the same clock, one after ST_CLEAR (the next
  // frame's START is two clocks further at the earliest: ST_SAMPLE, ST_CHECK). Each engine's
  // pixel slice drains from a register of its own, loaded from the next state: drain_o on every
  // clock, not its decode across the die (that decode set the default top's clock).
  logic                   clear_q;
  logic [NUM_ENGINES-1:0] eng_clear_q, eng_drain_q;
  // The copies are msr_dup_reg flip-flops: as one register, synthesis merged them into one.
  msr_dup_reg #(.COPIES(1 + NUM_ENGINES)) u_clear_q (
    .clk_i, .rst_ni,
    .d_i (state_q == ST_CLEAR),
    .q_o ({clear_q, eng_clear_q})
  );
  msr_dup_reg #(.COPIES(NUM_ENGINES)) u_drain_q (
    .clk_i, .rst_ni,
    .d_i (state_d == ST_DRAIN || state_d == ST_CLEAR),
    .q_o (eng_drain_q)
  );

  // The events of the tiles-in-flight count are registered on their way in: a tile handed to
  // an engine (the generator's dispatch, which reads RUN) and a tile's last pixel taken by the
  // writer (its row state). Each path through the count's adder set the clock (in the glue
  // and in the flat top). The count moves a clock later; DONE also waits while a dispatch is on
  // its way, so DONE comes a clock later, never earlier. Events in the units' clear clock are
  // dropped, as the units drop them.
  logic                   desc_fire_q;
  logic [NUM_ENGINES-1:0] tile_done_q;
  `MSR_CLR_REG(u_events_q, 1 + NUM_ENGINES, clear_q, 1'b1, {desc_fire_i, tile_done_i},
               {desc_fire_q, tile_done_q})

  // Watchdog progress, registered: the handshakes come from every engine and both ports, and
  // a watchdog one clock late loses nothing. Responses count only while running: during a
  // drain they cannot keep the wait open.
  logic progress_q;
  `MSR_CLR_REG(u_progress_q, 1, 1'b0, 1'b1, moved_i || (state_q == ST_RUN && rsp_taken_i),
               progress_q)

  // The writer's idle flag, registered on its way in: it is an OR over every stage of the
  // writer, and that tree into the state register set the flat top's clock. It reads a clock
  // late, and only late in turning false: the writer leaves idle
  // only by taking a pixel. In RUN the frame's last pixel reaches the count two clocks after
  // the writer takes it (tile_done_q, then tif_q), when the registered flag already shows
  // the writer busy, so DONE never comes early. In DRAIN no pixel reaches the writer (drain_o
  // gates them from the first DRAIN clock), so the flag is exact from the second DRAIN clock
  // on, and the drain does not end in its first clock (drain_seen_q).
  logic wr_idle_q, drain_seen_q;
  `MSR_CLR_REG(u_wr_idle_q, 2, 1'b0, 1'b1, {wr_idle_i, state_q == ST_DRAIN},
               {wr_idle_q, drain_seen_q})

  // Responses dropped this clock: the engines' and the mux's (at most NUM_ENGINES + 1).
  logic [4:0] rsp_drop_n;
  always_comb begin
    rsp_drop_n = 5'(bad_eid_i);
    for (int unsigned i = 0; i < NUM_ENGINES; i++) rsp_drop_n += 5'(rsp_drop_i[i]);
  end

  // ---- Field checks (from the sampled registers) ---------------------------------------------
  logic [6:0] fchk;
  always_comb begin
    fchk    = '0;
    fchk[0] = raw_q.width == '0 || raw_q.width > dim_t'(MAX_FRAME) ||
              raw_q.height == '0 || raw_q.height > dim_t'(MAX_FRAME);
    fchk[1] = !(raw_q.tile inside {6'd8, 6'd16, 6'd32}) || 32'(raw_q.tile) > TILE_LIMIT;
    fchk[2] = raw_q.levels == '0;
    fchk[3] = (raw_q.fb.fb_stride[31:15] == '0 && raw_q.fb.fb_stride[14:0] < {raw_q.width, 2'b0}) ||
              raw_q.fb.fb_stride[1:0] != '0;
    fchk[4] = raw_q.fb.fb_base[1:0] != '0;
    fchk[5] = raw_q.fb.src_en && ((raw_q.fb.src_stride[31:13] == '0 &&
                                   raw_q.fb.src_stride[12:0] < raw_q.width) ||
                                  raw_q.fb.src_stride[1:0] != '0);
    fchk[6] = raw_q.fb.src_en && raw_q.fb.src_base[1:0] != '0;
  end

  // ---- Plane ranges: whether a plane wraps past 4 GiB, whether the two overlap --------------
  logic [1:0] wraps;                   // the frame buffer's, the source plane's end > 2^32
  logic       overlap;
  msr_cfg_ranges #(.STEP_CMP(STEP_CMP), .STEP_END(STEP_END)) u_ranges (
    .clk_i, .rst_ni,
    .fb_i (raw_q.fb), .width_i (raw_q.width), .height_i (raw_q.height),
    .sample_i (state_q == ST_SAMPLE), .check_i (state_q == ST_CHECK), .step_i (step_q),
    .wraps_o (wraps), .overlap_o (overlap)
  );

  logic [NCHK-1:0] chk_all;
  always_comb begin
    chk_all      = {3'b0, fchk};
    chk_all[7]   = 1'b0;                                // code 8 is the memory error
    chk_all[8]   = wraps[0];
    chk_all[9]   = wraps[1];
  end

  msr_cfg_gaze u_gaze (
    .clk_i, .rst_ni,
    .gaze_i (raw_q.gaze), .width_i (raw_q.width), .height_i (raw_q.height), .tile_i (raw_q.tile),
    .check_i (state_q == ST_CHECK), .decide_i (state_q == ST_CHECK && step_q == STEP_CMP[4:0]),
    .err_o (gaze_err), .cx_o (gaze_cx), .cy_o (gaze_cy)
  );

  // The first failing check, in the order of the codes (code k + 1 for flag k).
  function automatic err_e first_err(logic [NCHK-1:0] chk, logic ovl, logic rule_bad,
                                     logic [1:0] bud_bad, logic gaze_bad);
    for (int unsigned k = 0; k < NCHK; k++) begin
      if (chk[k]) return err_e'(k + 1);
    end
    if (ovl) return ERR_OVERLAP;
    if (rule_bad) return ERR_RULE;
    if (bud_bad[0]) return ERR_BUDGET;
    if (bud_bad[1]) return ERR_PROFILE;
    if (gaze_bad) return ERR_GAZE;
    return ERR_NONE;
  endfunction

  // ---- Ray budget: the controller's check, or every budget refused ---------------------------
  // Read when CHECK decides: off (0) always passes; a top without the controller refuses any
  // budget; an unfinished check (the controller takes at most 21 of CHECK's 27 clocks:
  // asserted) would refuse rather than start unchecked.
  logic       bud_on;
  logic [1:0] bud_bad;
  bud_cfg_t   bud_cfg;                 // the frame's budget registers, latched at the accept
  assign bud_on = raw_q.bud.pixels != '0;
  if (BUDGET_EN) begin : g_budget
    assign bud_bad = !bud_on ? 2'b00 : (!bud_done_i || bud_err_budget_i) ? 2'b01 :
                     {bud_err_profile_i, 1'b0};
    assign bud_cfg = raw_q.bud;
    `MSR_ASSERT_IMP(a_bud_check_in_time,
                state_q == ST_CHECK && step_q == 5'(STEP_END - 1) && bud_on, bud_done_i)
  end else begin : g_no_budget
    assign bud_bad = {1'b0, bud_on};
    assign bud_cfg = '0;
    logic unused_budget;
    assign unused_budget = ^{bud_done_i, bud_err_budget_i, bud_err_profile_i};
  end

  always_comb begin
    n_done = '0;
    for (int unsigned i = 0; i < NUM_ENGINES; i++) n_done += $bits(n_done)'(tile_done_q[i]);
  end

  // ---- Control ----------------------------------------------------------------------------------
  // CHECK decides from flip-flops: the clock before (step STEP_END-1) registers that the next
  // clock decides, that no check failed and the budget's verdict (all settled by then: the
  // checks at STEP_CMP, the budget check within 21 clocks, asserted below). Decided from the
  // step compare and bud_bad in the same clock, accept was six LUTs deep into the memory
  // error registers' enable: the BUDGET_EN = 1 top's worst path on some placement seeds.
  logic       decide_q, chk_none_q;
  logic [1:0] bud_bad_q;
  assign accept  = (state_q == ST_CHECK) && decide_q && chk_none_q && !overlap && !rule_chk_q &&
                   bud_bad_q == '0 && !gaze_err;

  always_comb begin
    state_d = state_q;
    err_d   = err_q;
    unique case (state_q)
      ST_IDLE:   if (start_i) state_d = ST_SAMPLE;
      ST_SAMPLE: state_d = ST_CHECK;
      ST_CHECK: begin
        if (decide_q) begin
          err_d   = first_err(chk_q, overlap, rule_chk_q, bud_bad_q, gaze_err);
          state_d = accept ? ST_RUN : ST_IDLE;
        end
      end
      ST_RUN: begin
        if (bresp_err_i) err_d = ERR_AXI_WRITE;
        if (frame_done_q) state_d = ST_IDLE;
      end
      ST_DRAIN: begin
        if (bresp_err_i) err_d = ERR_AXI_WRITE;
        if (rnd_idle_i && wr_idle_q && drain_seen_q) state_d = ST_CLEAR;
      end
      ST_CLEAR: begin
        // STATUS returns to 0, except a memory error or a watchdog seen in the frame or the drain
        if (err_q != ERR_AXI_WRITE && err_q != ERR_WATCHDOG) err_d = ERR_NONE;
        state_d = ST_IDLE;
      end
      default: state_d = ST_IDLE;
    endcase
    if (soft_reset_i && state_q != ST_DRAIN && state_q != ST_CLEAR) state_d = ST_DRAIN;
    if (wd_fire) begin
      state_d = ST_CLEAR;
      err_d   = ERR_WATCHDOG;
    end
  end

  // ---- Watchdog: cycles without progress in RUN and DRAIN (its compare registered) ----------
  // A soft reset written while running starts the drain with a fresh count.
  msr_watchdog #(.DRAIN_TIMEOUT(DRAIN_TIMEOUT)) u_watchdog (
    .clk_i, .rst_ni,
    .run_i      (state_q == ST_RUN),
    .drain_i    (state_q == ST_DRAIN),
    .restart_i  (soft_reset_i),
    .progress_i (progress_q),
    .limit_i    (wdog_limit_i),
    .fire_o     (wd_fire)
  );

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      state_q        <= ST_IDLE;
      err_q          <= ERR_NONE;
      raw_q          <= '0;
      cfg_q          <= '0;
      chk_q          <= '0;
      rule_chk_q     <= 1'b0;
      step_q         <= '0;
      decide_q       <= 1'b0;
      chk_none_q     <= 1'b1;
      bud_bad_q      <= '0;
      start_q        <= 1'b0;
      refused_q      <= 1'b0;
      frame_done_q   <= 1'b0;
      tif_q          <= '0;
      mem_err_cnt_q  <= '0;
      mem_err_addr_q <= '0;
      b_unexp_q      <= 1'b0;
    end else begin
      state_q      <= state_d;
      err_q        <= err_d;
      start_q      <= accept && state_d == ST_RUN;
      refused_q    <= (state_q == ST_CHECK) && decide_q && !accept &&
                      state_d == ST_IDLE;
      frame_done_q <= (state_q == ST_RUN) && !start_q && tg_done_i && tif_q == '0 && !desc_fire_q &&
                      wr_idle_q && !bud_busy_i && !frame_done_q;
      step_q       <= (state_q == ST_CHECK) ? step_q + 1'b1 : '0;
      decide_q     <= (state_q == ST_CHECK) && (step_q == 5'(STEP_END - 1));
      chk_none_q   <= (chk_q == '0);
      bud_bad_q    <= bud_bad;
      if (state_q == ST_IDLE && start_i) raw_q <= raw_i;
      if (state_q == ST_CHECK && step_q == STEP_CMP[4:0]) begin
        chk_q      <= chk_all;
        rule_chk_q <= raw_q.rule[1] || (LINDILATE == 0 && raw_q.rule[0]);
      end
      if (accept) begin
        cfg_q.width      <= raw_q.width;
        cfg_q.height     <= raw_q.height;
        cfg_q.tile       <= (raw_q.tile == 6'd8)  ? TILE_8  :
                            (raw_q.tile == 6'd32) ? TILE_32 : TILE_16;
        cfg_q.levels     <= raw_q.levels;
        cfg_q.metric     <= raw_q.metric;
        cfg_q.rule       <= rule_e'(raw_q.rule[0]);
        cfg_q.thr        <= raw_q.thr;
        cfg_q.fov_gain   <= raw_q.fov_gain;
        cfg_q.gaze       <= '{en: raw_q.gaze.en, cx: gaze_cx, cy: gaze_cy};
        cfg_q.fb         <= raw_q.fb;
        cfg_q.bud        <= bud_cfg;
      end
      // Counted in RUN and DRAIN only: the units clear a clock after ST_CLEAR (clear_q), and a
      // tile finishing in that clock is not in flight.
      if (state_q == ST_CLEAR || start_q) begin
        tif_q <= '0;
      end else if (state_q == ST_RUN || state_q == ST_DRAIN) begin
        tif_q <= tif_q + TIF_W'(desc_fire_q) - TIF_W'(n_done);
      end
      // Memory errors: counted, the first address kept, until the next accepted START (so they
      // survive a soft reset; dropped responses likewise, in u_rsp_drop_cnt below).
      if (accept) begin
        mem_err_cnt_q  <= '0;
        b_unexp_q      <= 1'b0;
      end else begin
        if (bresp_err_i) begin
          if (mem_err_cnt_q == '0) mem_err_addr_q <= bresp_addr_i;
          if (mem_err_cnt_q != '1) mem_err_cnt_q <= mem_err_cnt_q + 1'b1;
        end
        if (b_unexp_i) b_unexp_q <= 1'b1;
      end
    end
  end

  assign cfg_o          = cfg_q;
  assign busy_o         = (state_q != ST_IDLE);
  assign err_o          = err_q;
  // A soft reset in the very clock the frame completes aborts it (the state goes to ST_DRAIN):
  // DONE stays clear. The register block's hwset outranks its hwclr, so without the gate a
  // STATUS read after that soft reset would say DONE.
  assign done_set_o     = frame_done_q && (state_q == ST_RUN) && !soft_reset_i;
  assign done_clr_o     = start_q || soft_reset_i;
  assign cfg_err_set_o  = refused_q;
  assign wdog_set_o     = wd_fire;
  assign err_counts_o.mem_err_cnt  = mem_err_cnt_q;
  assign err_counts_o.mem_err_addr = mem_err_addr_q;
  assign err_counts_o.b_unexpected = b_unexp_q;
  // Several engines and the mux may drop a response in the same clock: the count takes their
  // sum (a segmented saturating counter, its carry registered; it reads true a clock later).
  msr_sat_counter #(.WIDTH(16), .INC_W(5), .SEG_W(8)) u_rsp_drop_cnt (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .clear_i (accept),
    .en_i    (1'b1),
    .inc_i   (rsp_drop_n),
    .count_o (err_counts_o.rsp_drop_cnt)
  );
  assign raw_o          = raw_q;
  assign bud_check_o    = (state_q == ST_SAMPLE);
  assign start_o        = start_q;
  assign run_o          = (state_q == ST_RUN);
  assign drain_o        = (state_q == ST_DRAIN) || (state_q == ST_CLEAR);
  assign eng_drain_o    = eng_drain_q;
  assign clear_o        = clear_q;
  assign eng_clear_o    = eng_clear_q;

  // The interrupt leaves from a flip-flop of its own, a clock after STATUS: the pin is far
  // from the register block, and without it the STATUS bits were pulled towards the pin and
  // the register block's write decode into them set the glue's clock.
  `MSR_CLR_REG(u_irq_q, 1, 1'b0, 1'b1, irq_en_i && irq_flags_i != '0, irq_o)

  /* verilator lint_off SYNCASYNCNET */
  `MSR_ASSERT_IMP(a_tif_no_underflow,
              (state_q == ST_RUN), !(tif_q == '0 && n_done != '0 && !desc_fire_q))
  `MSR_ASSERT(a_tif_no_overflow, tif_q != '1)
  `MSR_COVER(c_refused, refused_q)
  `MSR_COVER(c_overlap_refused, refused_q && err_q == ERR_OVERLAP)
  `MSR_COVER(c_rule_refused, refused_q && err_q == ERR_RULE)
  `MSR_COVER(c_gaze_refused, refused_q && err_q == ERR_GAZE)
  // An accepted gaze lies in the frame: its half-tile position is at most 2 * 512 tiles.
  `MSR_ASSERT_IMP(a_gaze_in_range, accept && raw_q.gaze.en,
              gaze_cx <= half_t'(1024) && gaze_cy <= half_t'(1024))

  `MSR_COVER(c_drain_with_mem_err, state_q == ST_CLEAR && err_q == ERR_AXI_WRITE)
  `MSR_COVER(c_wdog_run, wd_fire && state_q == ST_RUN)
  `MSR_COVER(c_wdog_drain, wd_fire && state_q == ST_DRAIN)
  // The registered decision equals the one it replaces (the step compare, the live flags).
  `MSR_ASSERT_IMP(a_decide_at_end, state_q == ST_CHECK, decide_q == (step_q == STEP_END[4:0]))
  `MSR_ASSERT_IMP(a_decide_flags, state_q == ST_CHECK && decide_q,
              chk_none_q == (chk_q == '0) && bud_bad_q == bud_bad)
  `MSR_ASSERT(a_eng_drain_is_drain, eng_drain_q == {NUM_ENGINES{drain_o}})
  /* verilator lint_on SYNCASYNCNET */
endmodule : msr_cfg_ctrl
