// Types shared by the system units around the engines (configuration, error codes).
package msr_sys_pkg;
  import msr_pkg::*;

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
    logic [31:0]           fb_base;
    logic [31:0]           fb_stride;
    logic                  src_en;
    logic [31:0]           src_base;
    logic [31:0]           src_stride;
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
    logic [31:0]           fb_base;
    logic [31:0]           fb_stride;
    logic                  src_en;
    logic [31:0]           src_base;
    logic [31:0]           src_stride;
  } cfg_t;

  // STATUS.ERROR codes (rtl/regs/msr_regs.rdl).
  typedef enum logic [3:0] {
    ERR_NONE       = 4'd0,
    ERR_FRAME_SIZE = 4'd1,
    ERR_TILE       = 4'd2,
    ERR_LEVELS     = 4'd3,
    ERR_FB_STRIDE  = 4'd4,
    ERR_FB_BASE    = 4'd5,
    ERR_SRC_STRIDE = 4'd6,
    ERR_SRC_BASE   = 4'd7,
    ERR_AXI_WRITE  = 4'd8,
    ERR_FB_WRAP    = 4'd9,
    ERR_SRC_WRAP   = 4'd10,
    ERR_OVERLAP    = 4'd11,
    ERR_WATCHDOG   = 4'd12,  // no progress for WATCHDOG cycles: frame or drain ended by force
    ERR_RULE       = 4'd13   // CONFIG.RULE not 0 (patent) or 1 (lindilate)
  } err_e;

endpackage : msr_sys_pkg
