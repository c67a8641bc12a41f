// Generated from rtl/regs/msr_regs.rdl by `make regs` (msr_flow.regs_codes); do not edit.
// Included inside msr_sys_pkg: the encoded register fields as enums.

// STATUS.ERROR
typedef enum logic [4:0] {
  // No error.
  ERR_NONE       = 5'd0,
  // Bad frame size (0 or > 4096).
  ERR_FRAME_SIZE = 5'd1,
  // Tile size not 8, 16 or 32, or above the largest the top's tile buffers hold (msr_top
  // TILE_LIMIT, 32 by default).
  ERR_TILE       = 5'd2,
  // Levels not 1..3.
  ERR_LEVELS     = 5'd3,
  // Frame-buffer stride smaller than a row or not a multiple of 4.
  ERR_FB_STRIDE  = 5'd4,
  // Frame-buffer base not 4-byte aligned.
  ERR_FB_BASE    = 5'd5,
  // Source-map stride smaller than a row or not a multiple of 4.
  ERR_SRC_STRIDE = 5'd6,
  // Source-map base not 4-byte aligned.
  ERR_SRC_BASE   = 5'd7,
  // AXI write error response (BRESP SLVERR/DECERR) during the frame or the soft reset after it;
  // kept through the soft reset (MEM_ERR counts them, MEM_ERR_ADDR has the first address).
  ERR_AXI_WRITE  = 5'd8,
  // The frame-buffer plane wraps past 4 GiB.
  ERR_FB_WRAP    = 5'd9,
  // The source-map plane wraps past 4 GiB.
  ERR_SRC_WRAP   = 5'd10,
  // The two planes overlap.
  ERR_OVERLAP    = 5'd11,
  // Watchdog: no progress for WATCHDOG cycles; the frame (or the soft reset's wait) was ended by
  // force (kept through the soft reset).
  ERR_WATCHDOG   = 5'd12,
  // CONFIG.RULE not 0 or 1, or 1 in a top built without the lindilate rule (msr_top LINDILATE =
  // 0).
  ERR_RULE       = 5'd13,
  // Ray budget: 0 < BUDGET below the frame's initial grid (docs/budget.md), or BUDGET non-zero in
  // a top built without the budget controller (msr_top BUDGET_EN = 0).
  ERR_BUDGET     = 5'd14,
  // Ray budget: BUDGET_CTRL.SEEDED but the activity memory was not written by a budget frame with
  // the same number of tile rows.
  ERR_PROFILE    = 5'd15,
  // GAZE.EN with the gaze point outside the frame (X >= W or Y >= H).
  ERR_GAZE       = 5'd16
} err_e;
