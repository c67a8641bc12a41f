// lindilate, the tile engine's output side of the rule (docs/rules.md step 4): the dilation's
// line store where a decision leaves the pipeline (PV), and the retro request at the output.
//
// The base decision D = P or Q: P is the decision pipeline's own (pv_interp_i), Q comes from
// msr_base_decision four clocks after AB; two registers align it with the pipeline's six
// stages (neither stalls).
//
// Dilation in decision order. A position's D is known when it leaves the pipeline, the next
// line's only when the same position of the next line does. So the position is interpolated
// (for now) iff D(l-) and D(l); when D(l+) fails later, a retro trace of (l-, m) follows, and
// its render answer overwrites the interpolated pixel (same final pixel and code as the rule,
// one request per traced pixel). Per context and position index the line store keeps D of the
// last line and whether that line's pixel was interpolated. The passes of a context leave the
// pipeline in order, so no clearing: the first line of a pass reads nothing. The store is a
// small memory (read and written at one address a clock, the read of the old value):
// distributed RAM on an FPGA.
//
// Retro request: a result with a retro trace takes two clocks at the output, first the retro
// request (the previous line's pixel at the same position: its frame coordinates and the
// tile-buffer address its answer writes), then the result's own write or request.
// retro_sent_q remembers that the first half went.
`include "msr_flops.svh"
module msr_lin_dilate import msr_pkg::*; #(
  parameter int unsigned NUM_CTX = 8, parameter int unsigned CTX_W = $clog2(NUM_CTX)  // contexts
) (
  input  logic                clk_i, rst_ni, clear_i,  // clear: synchronous soft reset
  // PV: the decision leaving the pipeline
  input  logic                base_q_i,         // msr_base_decision's Q, two clocks before PV
  input  logic                pv_valid_i,       // a decision leaves the pipeline
  input  logic                pv_interp_i,      // its P: the patent rule interpolates
  input  logic                pv_lin_i,         // it is decided by lindilate
  input  logic                pv_fline_i,       // first line of its pass
  input  logic [CTX_W-1:0]    pv_ctx_i,         // its context
  input  logic [LCOORD_W-2:0] pv_mh_i,          // its index on the line
  output logic                pv_lin_interp_o,  // lindilate interpolates it (for now)
  output logic                pv_retro_o,       // first trace the line before's pixel
  // OUT: the result at the output
  input  logic                out_valid_i,      // a result is at the output
  input  logic                out_retro_i,      // it carries a retro trace
  input  logic                out_done_i,       // it leaves (valid and ready)
  input  logic                alloc_i,          // a render request takes a tag now
  input  logic                out_vert_i,       // its pass is vertical
  input  lcoord_t             out_x_i,          // its tile-local coordinates
  input  lcoord_t             out_y_i,
  input  coord_t              out_gx_i,         // its frame coordinates
  input  coord_t              out_gy_i,
  input  logic [3:0]          out_ldelta_i,     // distance to the line before (1..8)
  output logic                retro_phase_o,    // the retro request is due (first half)
  output coord_t              req_x_o,          // the request's frame coordinates: the retro's
  output coord_t              req_y_o,          // in the retro phase, else the result's own
  output logic [TADDR_W-1:0]  req_addr_o        // the tile-buffer address its answer writes
);

  // ---- PV: base decision and line store -------------------------------------------------------
  logic base_q1_q, base_q2_q, pv_base;

  always_ff @(posedge clk_i) begin
    base_q1_q <= base_q_i;
    base_q2_q <= base_q1_q;
  end
  assign pv_base = pv_interp_i || base_q2_q;

  localparam int unsigned DL_AW = CTX_W + LCOORD_W - 1;
  logic [1:0] dl_mem [NUM_CTX * 16];               // {D(l-), "(l-) was interpolated"}
  logic [1:0] dl_rd;
  logic [DL_AW-1:0] dl_addr;
  logic pv_dprev, pv_tprev;

  assign dl_addr         = {pv_ctx_i, pv_mh_i};
  assign dl_rd           = dl_mem[dl_addr];
  assign pv_dprev        = pv_fline_i || dl_rd[1];
  assign pv_tprev        = !pv_fline_i && dl_rd[0];
  assign pv_lin_interp_o = pv_dprev && pv_base;
  assign pv_retro_o      = pv_lin_i && pv_tprev && !pv_base;

  always_ff @(posedge clk_i) begin
    if (pv_valid_i && pv_lin_i) begin
      dl_mem[dl_addr] <= {pv_base, pv_lin_interp_o};
    end
  end

  // ---- OUT: retro request ------------------------------------------------------------------------
  logic    retro_sent_q;
  coord_t  rt_gx, rt_gy, rt_line_g;
  lcoord_t rt_line;

  assign rt_line       = (out_vert_i ? out_x_i : out_y_i) - lcoord_t'(out_ldelta_i);
  assign rt_line_g     = (out_vert_i ? out_gx_i : out_gy_i) - coord_t'(out_ldelta_i);
  assign rt_gx         = out_vert_i ? rt_line_g : out_gx_i;
  assign rt_gy         = out_vert_i ? out_gy_i : rt_line_g;
  assign retro_phase_o = out_valid_i && out_retro_i && !retro_sent_q;

  assign req_x_o    = retro_phase_o ? rt_gx : out_gx_i;
  assign req_y_o    = retro_phase_o ? rt_gy : out_gy_i;
  assign req_addr_o = !retro_phase_o ? {out_y_i, out_x_i} :
                      out_vert_i     ? {out_y_i, rt_line} : {rt_line, out_x_i};

  // set when the retro request takes its tag, clear when the result leaves
  `MSR_CLR_REG(u_retro_sent, 1, clear_i, out_done_i || (retro_phase_o && alloc_i), !out_done_i,
               retro_sent_q)

endmodule : msr_lin_dilate
