// The tile engine's render tags and responses: the tag pool (msr_tag_pool: free list, where
// each answer goes, the tags in flight) and the check of every response against it.
//
//   rsp: spill register -> R1 (tag looked up: its entry, and whether it is in flight) -> R2
//        (write the colour into the tag's context, or drop the answer)
//
// R1 looks the tag up, minus the tag R2 releases this cycle, so a duplicate right behind its
// original is caught. R2 writes the colour when its context's port is free this cycle (the
// pipeline's interpolated write, pipe_we_i, goes first), or drops an answer whose tag was not
// in flight (stale, duplicate, invented): nothing is written, no tag is freed twice, drop_o
// pulses. A tag is released when its answer is written. port_ok_i says whether the answer's
// context's port may take a write at all this cycle (a macro's cycle, msr_ctx_write; else 1).
`include "msr_assert.svh"
`include "msr_flops.svh"

module msr_rsp_check
  import msr_pkg::*;
#(
  parameter int unsigned MAX_OUTSTANDING = 16,                      // tags (power of two, 2..64)
  parameter int unsigned TAG_W           = $clog2(MAX_OUTSTANDING),
  parameter int unsigned CTX_W           = 3,                       // context index bits
  // a response's data: the colour, or with the engine's depth channel {inverse depth, colour}
  parameter int unsigned DATA_W          = $bits(rgb_t)
) (
  input  logic                       clk_i,          // clock
  input  logic                       rst_ni,         // asynchronous reset, active low
  input  logic                       clear_i,        // synchronous soft reset: every tag free again
  // render response, any order
  input  logic                       rsp_valid_i,
  output logic                       rsp_ready_o,
  input  logic [TAG_W-1:0]           rsp_tag_i,
  input  logic [DATA_W-1:0]          rsp_rgb_i,      // colour (and inverse depth)
  // tag allocation for a render request: where its answer goes
  output logic                       tag_avail_o,    // a tag is free ...
  output logic [TAG_W-1:0]           free_tag_o,     // ... this one
  input  logic                       alloc_i,        // take it for this entry:
  input  logic [CTX_W-1:0]           alloc_ctx_i,    //   the context,
  input  logic [TADDR_W-1:0]         alloc_addr_i,   //   the tile-buffer address,
  input  level_t                     alloc_level_i,  //   the level (its source code)
  // the pipeline writes this context in this cycle (its port is taken)
  input  logic                       pipe_we_i,
  input  logic [CTX_W-1:0]           pipe_ctx_i,
  input  logic                       port_ok_i,      // the port of wctx_o may be written now
  // the answer's write
  output logic                       we_o,           // write now
  output logic [CTX_W-1:0]           wctx_o,
  output logic [TADDR_W-1:0]         waddr_o,
  output level_t                     wlevel_o,
  output logic [DATA_W-1:0]          wrgb_o,
  // status
  output logic                       drop_o,         // pulse: a response not in flight was dropped
  output logic [TAG_W:0]             inflight_o,     // tags handed out and not yet answered
  output logic                       tags_out_o,     // registered: a tag may be out (0: none is)
  output logic                       init_o          // the tags are being reset
);

  typedef struct packed {
    logic [CTX_W-1:0]   ctx;
    logic [TADDR_W-1:0] addr;
    level_t             level;
  } tag_entry_t;

  typedef struct packed {
    logic [TAG_W-1:0] tag;
    logic [DATA_W-1:0] rgb;
  } rsp_t;

  logic       rs_valid, rs_ready;
  rsp_t       rs_data, rsp_in;
  logic       r1_valid_q, r1_ready;
  rsp_t       r1_q;
  tag_entry_t r1_entry, alloc_entry;
  logic       r1_inflight;
  logic       r2_valid_q, r2_ok_q, r2_write, r2_drop, r2_done;
  rsp_t       r2_q;
  tag_entry_t r2_entry_q;

  assign rsp_in = '{tag: rsp_tag_i, rgb: rsp_rgb_i};

  msr_spill_reg #(
    .WIDTH ($bits(rsp_t))
  ) u_rsp_spill (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .clear_i (clear_i),
    .valid_i (rsp_valid_i),
    .ready_o (rsp_ready_o),
    .data_i  (rsp_in),
    .valid_o (rs_valid),
    .ready_i (rs_ready),
    .data_o  (rs_data)
  );

  assign r2_drop  = r2_valid_q && !r2_ok_q;
  assign r2_write = r2_valid_q && r2_ok_q && port_ok_i &&
                    !(pipe_we_i && pipe_ctx_i == r2_entry_q.ctx);
  assign r2_done  = r2_drop || r2_write;
  assign r1_ready = !r2_valid_q || r2_done;
  assign rs_ready = !r1_valid_q || r1_ready;

  `MSR_CLR_REG(u_r1_valid, 1, clear_i, rs_ready, rs_valid, r1_valid_q)

  `MSR_CLR_REG(u_r2_valid, 1, clear_i, r1_ready, r1_valid_q, r2_valid_q)

  always_ff @(posedge clk_i) begin
    if (rs_ready && rs_valid) r1_q <= rs_data;
    if (r1_ready && r1_valid_q) begin
      r2_q       <= r1_q;
      r2_entry_q <= r1_entry;
      r2_ok_q    <= r1_inflight && !(r2_write && r2_q.tag == r1_q.tag);
    end
  end

  assign we_o     = r2_write;
  assign wctx_o   = r2_entry_q.ctx;
  assign waddr_o  = r2_entry_q.addr;
  assign wlevel_o = r2_entry_q.level;
  assign wrgb_o   = r2_q.rgb;
  assign drop_o   = r2_drop;

  // ---- Tags -------------------------------------------------------------------------------------
  assign alloc_entry = '{ctx: alloc_ctx_i, addr: alloc_addr_i, level: alloc_level_i};

  msr_tag_pool #(
    .N       (MAX_OUTSTANDING),
    .ENTRY_W ($bits(tag_entry_t)),
    .TAG_W   (TAG_W)
  ) u_tag_pool (
    .clk_i            (clk_i),
    .rst_ni           (rst_ni),
    .clear_i          (clear_i),
    .avail_o          (tag_avail_o),
    .tag_o            (free_tag_o),
    .alloc_i          (alloc_i),
    .entry_i          (alloc_entry),
    .query_tag_i      (r1_q.tag),
    .query_entry_o    (r1_entry),
    .query_inflight_o (r1_inflight),
    .release_tag_i    (r2_q.tag),
    .release_i        (r2_write),
    .inflight_o       (inflight_o),
    .out_q_o          (tags_out_o),
    .init_o           (init_o)
  );

  /* verilator lint_off SYNCASYNCNET */
  `MSR_ASSERT(a_no_port_clash, !(we_o && pipe_we_i && pipe_ctx_i == wctx_o))
  `MSR_ASSERT(a_drop_or_write, !(drop_o && we_o))
  `MSR_COVER(c_rsp_dropped, drop_o)
  `MSR_COVER(c_rsp_waits, r2_valid_q && r2_ok_q && !r2_write)
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_rsp_check
