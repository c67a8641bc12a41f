// Types and helpers of the frame-buffer writer (msr_fb_writer) and its units: the frame-buffer
// settings, a complete row's metadata, the row-buffer ring. The types whose widths follow the
// writer's parameters (the addressed row, the burst) are macros in msr_fbw_types.svh.
package msr_fbw_pkg;
  import msr_pkg::*;

  // Not every unit uses every constant (each is linted on its own with the package).
  /* verilator lint_off UNUSEDPARAM */

  // Frame-buffer settings: where the two planes go (stable during a frame).
  typedef struct packed {
    logic [31:0] fb_base;      // frame-buffer byte address of pixel (0, 0)
    logic [31:0] fb_stride;    // frame-buffer bytes per row
    logic        src_en;       // also write the source-code plane
    logic [31:0] src_base;     // source-plane byte address of pixel (0, 0)
    logic [31:0] src_stride;   // source-plane bytes per row
  } fb_cfg_t;

  // A complete row in a row buffer: where it goes in the frame.
  typedef struct packed {
    coord_t  y;                // row
    coord_t  x0;               // first column (the tile's left edge)
    lcoord_t l;                // pixels of the row - 1
  } row_meta_t;

  localparam int unsigned NBUF   = 3;   // row buffers per input, a ring
  localparam int unsigned BUF_W  = 2;   // buffer index
  localparam int unsigned CODE_W = 5;   // source-code bits kept in the buffers (codes 0..19)

  /* verilator lint_on UNUSEDPARAM */

  typedef logic [BUF_W-1:0] buf_t;

  // The buffer after b in the ring.
  function automatic buf_t buf_next(buf_t b);
    return (b == buf_t'(NBUF - 1)) ? '0 : b + 1'b1;
  endfunction

  // T - 1, the mask of a tile-local coordinate.
  function automatic lcoord_t tile_mask(tile_size_e t);
    unique case (t)
      TILE_8:  return lcoord_t'(7);
      TILE_32: return lcoord_t'(31);
      default: return lcoord_t'(15);
    endcase
  endfunction

  // First beat of buffer b (0..2) in a memory of n beats per buffer: b * n, for the pixel
  // memory and the code memory; n is a constant, so this is a 3-way mux.
  function automatic int unsigned buf_base(buf_t b, int unsigned n);
    unique case (b)
      2'd1:    return n;
      2'd2:    return 2 * n;
      default: return 0;
    endcase
  endfunction

  // Beats of a row's pixels / codes in a bus beat of wpb 32-bit lanes, at most (a row of
  // MAX_TILE pixels from any lane); a row buffer holds that many.
  function automatic int unsigned pix_beats(int unsigned wpb);
    return (MAX_TILE + 2 * wpb - 2) / wpb;
  endfunction
  function automatic int unsigned code_beats(int unsigned wpb);
    return (MAX_TILE / 4 + 2 * wpb - 2) / wpb;
  endfunction

endpackage : msr_fbw_pkg
