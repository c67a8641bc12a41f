// Formal harness of msr_lin_dilate (lindilate's dilation): decisions and results free, within
// the engine's contract: a result at the output is held, unchanged, until it leaves, and it
// leaves only outside its retro phase (msr_req_out). Reset assumed in the first cycle.
// Proves: the line store keeps, per address, D and "interpolated" of the last lindilate
// decision there (a reference of one address chosen by the solver), and a decision is
// interpolated / retro-traced from it as the rule says (docs/rules.md step 4); Q is aligned two
// clocks behind base_q_i; a result with a retro trace is first in its retro phase until that
// request takes a tag, then never again; the retro request names the line before (ldelta
// back along the pass's line axis) in frame coordinates and tile-buffer address, any other
// request the result's own pixel.
module msr_lin_dilate_fv
  import msr_pkg::*;
#(
  parameter int unsigned NUM_CTX = 2,
  parameter int unsigned CTX_W   = 1
) (
  input logic                clk_i, rst_ni, clear_i,
  input logic                base_q_i, pv_valid_i, pv_interp_i, pv_lin_i, pv_fline_i,
  input logic [CTX_W-1:0]    pv_ctx_i,
  input logic [LCOORD_W-2:0] pv_mh_i,
  input logic                out_valid_i, out_retro_i, out_done_i, alloc_i, out_vert_i,
  input lcoord_t             out_x_i, out_y_i,
  input coord_t              out_gx_i, out_gy_i,
  input logic [3:0]          out_ldelta_i,
  input logic [CTX_W+LCOORD_W-2:0] trk_i           // the store address the reference follows
);
  logic               pv_lin_interp_o, pv_retro_o, retro_phase_o;
  coord_t             req_x_o, req_y_o;
  logic [TADDR_W-1:0] req_addr_o;

  msr_lin_dilate #(.NUM_CTX(NUM_CTX), .CTX_W(CTX_W)) dut (
    .clk_i, .rst_ni, .clear_i, .base_q_i, .pv_valid_i, .pv_interp_i, .pv_lin_i, .pv_fline_i,
    .pv_ctx_i, .pv_mh_i, .pv_lin_interp_o, .pv_retro_o, .out_valid_i, .out_retro_i, .out_done_i,
    .alloc_i, .out_vert_i, .out_x_i, .out_y_i, .out_gx_i, .out_gy_i, .out_ldelta_i,
    .retro_phase_o, .req_x_o, .req_y_o, .req_addr_o
  );

  logic init;
  msr_fv_init #(.ONCE(1'b1)) u_init (.clk_i, .rst_ni, .init_o(init));

  // ---- The environment -----------------------------------------------------------------------
  logic held_q;
  logic [$bits(coord_t)*2+2*LCOORD_W+6-1:0] res_q;
  wire [$bits(res_q)-1:0] res = {out_retro_i, out_vert_i, out_x_i, out_y_i, out_gx_i, out_gy_i,
                                 out_ldelta_i};
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni)      held_q <= 1'b0;
    else if (clear_i) held_q <= 1'b0;
    else              held_q <= out_valid_i && !out_done_i;
  end
  logic [$bits(trk_i)-1:0] trk_q;
  always_ff @(posedge clk_i) begin
    res_q <= res;
    trk_q <= trk_i;
  end
  always_comb begin
    if (!init) assume (trk_i == trk_q);
    if (out_done_i) assume (out_valid_i && !retro_phase_o);
    if (held_q && !clear_i) assume (out_valid_i && res == res_q);
  end

  // ---- Reference: Q two clocks late, the store at trk_i, the retro request sent -----------------
  logic [1:0] age_q;                       // clocks since reset, saturating (Q's registers fill)
  logic       b1_q, b2_q, ref_v_q, ref_d_q, ref_i_q, rs_q;
  always_ff @(posedge clk_i) begin
    b1_q <= base_q_i;
    b2_q <= b1_q;
  end
  wire base = pv_interp_i || b2_q;
  wire at   = {pv_ctx_i, pv_mh_i} == trk_i;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      age_q <= '0; ref_v_q <= 1'b0; ref_d_q <= 1'b0; ref_i_q <= 1'b0; rs_q <= 1'b0;
    end else begin
      if (age_q != 2'd3) age_q <= age_q + 1'b1;
      // known from a first line on (the store is not reset), once Q's registers have filled
      if (pv_valid_i && pv_lin_i && at) begin
        ref_v_q <= age_q >= 2'd2 && (pv_fline_i || ref_v_q);
        ref_d_q <= base;
        ref_i_q <= (pv_fline_i || ref_d_q) && base;
      end
      if (clear_i) rs_q <= 1'b0;
      else         rs_q <= !out_done_i && (rs_q || (retro_phase_o && alloc_i));
    end
  end

  wire on = rst_ni && !init;
  always_comb begin
    if (on && age_q >= 2'd1) assert (dut.base_q1_q == b1_q);
    if (on && age_q >= 2'd2) assert (dut.base_q2_q == b2_q);
    if (on && ref_v_q) assert (dut.dl_mem[trk_i] == {ref_d_q, ref_i_q});
    if (on && age_q >= 2'd2 && pv_valid_i && at && ref_v_q) begin
      assert (pv_lin_interp_o == ((pv_fline_i || ref_d_q) && base));
      assert (pv_retro_o == (pv_lin_i && !pv_fline_i && ref_i_q && !base));
    end
    if (on) assert (dut.retro_sent_q == rs_q);
    if (on) assert (retro_phase_o == (out_valid_i && out_retro_i && !rs_q));
    if (on && retro_phase_o) begin
      assert (out_vert_i ? (req_x_o == out_gx_i - coord_t'(out_ldelta_i) && req_y_o == out_gy_i &&
                            req_addr_o == {out_y_i, out_x_i - lcoord_t'(out_ldelta_i)})
                         : (req_x_o == out_gx_i && req_y_o == out_gy_i - coord_t'(out_ldelta_i) &&
                            req_addr_o == {out_y_i - lcoord_t'(out_ldelta_i), out_x_i}));
    end
    if (on && !retro_phase_o) begin
      assert (req_x_o == out_gx_i && req_y_o == out_gy_i && req_addr_o == {out_y_i, out_x_i});
    end
  end

  c_retro_lin:   cover property (@(posedge clk_i) disable iff (!rst_ni) pv_valid_i && pv_retro_o && at);
  c_retro_sent:  cover property (@(posedge clk_i) disable iff (!rst_ni) out_done_i && rs_q);
endmodule
