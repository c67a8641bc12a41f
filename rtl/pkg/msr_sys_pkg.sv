// Types shared by the system units around the engines (configuration, error codes).
package msr_sys_pkg;
  import msr_pkg::*;

  // Where the frame goes: the frame-buffer plane and the optional source-map plane. The
  // registers' values and the checked ones are the same (the checks only refuse), so both
  // configuration types below carry this one struct, and the writer takes it whole.
  typedef struct packed {
    logic [31:0] fb_base;      // frame-buffer plane: byte address of pixel (0, 0)
    logic [31:0] fb_stride;    // bytes per row, a multiple of 4
    logic        src_en;       // write the source map too
    logic [31:0] src_base;     // source-map plane: byte address of pixel (0, 0)
    logic [31:0] src_stride;   // bytes per row, a multiple of 4
  } fb_cfg_t;

  // Counts the controller keeps for the register block beside the performance counters:
  // memory errors, the first failing address, a write response with nothing outstanding,
  // dropped render responses (docs/regs.md: MEM_ERR, MEM_ERR_ADDR, RSP_DROP).
  typedef struct packed {
    logic [15:0] mem_err_cnt;
    logic [31:0] mem_err_addr;
    logic        b_unexpected;
    logic [15:0] rsp_drop_cnt;
  } err_counts_t;

  // What the register block reads back from the counters (registered beside it).
  typedef struct packed {
    logic [31:0]      cycles;       // PERF_CYCLES
    logic [3:0][31:0] traced;       // PERF_TRACED[k]
    logic [2:0][31:0] interp;       // PERF_INTERP[k]
    logic [31:0]      rstall;       // PERF_RENDER_STALL
    logic [31:0]      mstall;       // PERF_MEM_STALL
    err_counts_t      err;          // MEM_ERR, MEM_ERR_ADDR, RSP_DROP
  } readback_t;

  // Ray budget registers (docs/budget.md): BUDGET.PIXELS and BUDGET_CTRL.
  typedef struct packed {
    logic [23:0] pixels;      // 0 = off
    logic [10:0] scale_init;  // u_0, 1.0 = 256 (0 reads as 256)
    logic [2:0]  prior_shift;
    logic        seeded;
  } bud_cfg_t;

  // A position in half tiles, 0..1024: the gaze (cx, cy) of the foveation.
  typedef logic [COORD_W-2:0] half_t;

  // GAZE: the gaze point in pixels, read only when en is set (else the frame centre).
  typedef struct packed {
    logic        en;
    logic [12:0] x;
    logic [12:0] y;
  } gaze_raw_t;

  // The checked gaze of a frame: en, and then (cx, cy) = ((2X + T/2) div T, (2Y + T/2) div T).
  typedef struct packed {
    logic  en;                 // 0: the default gaze, (cx, cy) = (ntx, nty)
    half_t cx;
    half_t cy;
  } gaze_t;

  // Frame configuration as the registers hold it (sampled at START, checked, then latched).
  typedef struct packed {
    dim_t                  width;
    dim_t                  height;
    logic [5:0]            tile;       // tile edge in pixels as written (8, 16 or 32)
    level_t                levels;
    metric_e               metric;
    logic [1:0]            rule;       // decision rule as written (0 patent, 1 lindilate)
    thr_t [MAX_LEVELS-1:0] thr;
    logic [7:0]            fov_gain;
    gaze_raw_t             gaze;
    fb_cfg_t               fb;
    bud_cfg_t              bud;
  } cfg_raw_t;

  // The checked configuration the units run a frame with.
  typedef struct packed {
    dim_t                  width;
    dim_t                  height;
    tile_size_e            tile;
    level_t                levels;
    metric_e               metric;
    rule_e                 rule;
    thr_t [MAX_LEVELS-1:0] thr;
    logic [7:0]            fov_gain;
    gaze_t                 gaze;
    fb_cfg_t               fb;
    bud_cfg_t              bud;
  } cfg_t;

  // STATUS.ERROR codes: err_e, generated from rtl/regs/msr_regs.rdl (make regs).
`include "msr_err_codes.svh"

  // The register fields the configuration controller acts on.
  typedef struct packed {
    logic        start;        // CTRL.START written (a pulse)
    logic        soft_reset;   // CTRL.SOFT_RESET written (a pulse)
    logic        irq_en;       // CTRL.IRQ_EN
    logic [2:0]  irq_flags;    // STATUS.DONE, CFG_ERR, WDOG as they are held
    logic [31:0] wdog_limit;   // WATCHDOG.CYCLES: cycles without progress, 0 = off
  } reg_ctrl_t;

  // What the configuration controller reports in STATUS.
  typedef struct packed {
    logic busy;                // STATUS.BUSY
    err_e err;                 // STATUS.ERROR
    logic done_set;            // STATUS.DONE set: the frame is complete
    logic done_clr;            // STATUS.DONE, CFG_ERR, WDOG cleared (START, SOFT_RESET)
    logic cfg_err_set;         // STATUS.CFG_ERR set: a START was refused
    logic wdog_set;            // STATUS.WDOG set: the watchdog forced a CLEAR
  } reg_status_t;

endpackage : msr_sys_pkg
