// Generated from rtl/regs/msr_regs.rdl by `make regs` (msr_flow.regs_codes); do not edit.
// Included inside msr_sys_pkg: the encoded register fields as enums.

// STATUS.ERROR
typedef enum logic [3:0] {
  // No error.
  ERR_NONE       = 4'd0,
  // Bad frame size (0 or > 4096).
  ERR_FRAME_SIZE = 4'd1,
  // Tile size not 8, 16 or 32.
  ERR_TILE       = 4'd2,
  // Levels not 1..3.
  ERR_LEVELS     = 4'd3,
  // Frame-buffer stride smaller than a row or not a multiple of 4.
  ERR_FB_STRIDE  = 4'd4,
  // Frame-buffer base not 4-byte aligned.
  ERR_FB_BASE    = 4'd5,
  // Source-map stride smaller than a row or not a multiple of 4.
  ERR_SRC_STRIDE = 4'd6,
  // Source-map base not 4-byte aligned.
  ERR_SRC_BASE   = 4'd7,
  // AXI write error response (BRESP SLVERR/DECERR) during the frame or the soft reset after it;
  // kept through the soft reset (MEM_ERR counts them, MEM_ERR_ADDR has the first address).
  ERR_AXI_WRITE  = 4'd8,
  // The frame-buffer plane wraps past 4 GiB.
  ERR_FB_WRAP    = 4'd9,
  // The source-map plane wraps past 4 GiB.
  ERR_SRC_WRAP   = 4'd10,
  // The two planes overlap.
  ERR_OVERLAP    = 4'd11,
  // Watchdog: no progress for WATCHDOG cycles; the frame (or the soft reset's wait) was ended by
  // force (kept through the soft reset).
  ERR_WATCHDOG   = 4'd12,
  // CONFIG.RULE not 0 or 1, or 1 in a top built without the lindilate rule (msr_top LINDILATE =
  // 0).
  ERR_RULE       = 4'd13,
  // Ray budget: 0 < BUDGET below the frame's initial grid (docs/budget.md), or BUDGET non-zero in
  // a top built without the budget controller (msr_top BUDGET_EN = 0).
  ERR_BUDGET     = 4'd14,
  // Ray budget: BUDGET_CTRL.SEEDED but the activity memory was not written by a budget frame with
  // the same number of tile rows.
  ERR_PROFILE    = 4'd15
} err_e;
