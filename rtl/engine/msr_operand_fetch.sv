// Operand fetch: the granted position's operands, from the grant (GR) to the AB registers
// that feed the decision pipeline and msr_base_decision.
//
//   GR -> IS : the issued context and position, registered (the tile buffer reads in GR)
//   IS -> RD : the context's descriptor fields (global coordinates, the level's threshold,
//              metric, rule), registered while the read data pass the block RAM and the
//              register beside it in the context
//   RD -> AB : the issued context's read data (A, B and lindilate's A', B') registered with
//              everything else the decision needs
//
// gr_*_i is the grant as the tile buffers' read latency leaves it: the engine delays the grant
// by RD_LAT - 1 clocks (none by default), so the read data meet their position in RD.
// lindilate's line tracking and outer samples (msr_lin_track) run beside IS and RD. No stage
// stalls (the issue holds a credit for the output buffer), so the data registers have no
// enable but their stage's valid bit, and only the valid bits are reset.
`include "msr_flops.svh"
module msr_operand_fetch
  import msr_pkg::*;
#(
  parameter int unsigned NUM_CTX   = 8,
  parameter int unsigned CTX_W     = $clog2(NUM_CTX),
  parameter int unsigned LINDILATE = 1
) (
  input  logic                          clk_i,
  input  logic                          rst_ni,
  input  logic                          clear_i,     // synchronous soft reset
  // the grant, registered (msr_ctx_issue)
  input  logic                          gr_valid_i,
  input  logic       [NUM_CTX-1:0]      gr_gnt_i,
  input  logic       [CTX_W-1:0]        gr_ctx_i,
  input  eng_pos_t                      gr_pos_i,
  // the contexts
  input  tile_desc_t [NUM_CTX-1:0]      desc_i,
  input  rgb_t       [NUM_CTX-1:0]      rd_a_i,      // port 1: A
  input  rgb_t       [NUM_CTX-1:0]      rd_b_i,      // port 0: B
  input  rgb_t       [NUM_CTX-1:0]      rd_o2_i,     // port 2: B' (or A' where o2a)
  // RD: a position is there, and the context whose read data are valid now (a unit beside
  // this one registers its own read data into AB with them: the depth channel's)
  output logic                          rd_valid_o,
  output logic       [CTX_W-1:0]        rd_ctx_o,
  // AB: the operands
  output logic                          valid_o,
  output logic       [CTX_W-1:0]        ctx_o,
  output eng_pos_t                      pos_o,
  output coord_t                        gx_o,        // global coordinates
  output coord_t                        gy_o,
  output metric_e                       metric_o,
  output thr_t                          thr_o,       // the level's threshold (0: initial grid)
  output rgb_t                          a_o,
  output rgb_t                          b_o,
  // lindilate
  output logic                          lin_o,       // decided by the lindilate rule
  output logic       [LCOORD_W-2:0]     mh_o,        // index on its line, m >> 1
  output logic                          fline_o,     // first line of its pass
  output logic       [3:0]              ldelta_o,    // distance to the line before (1..8)
  output rgb_t                          oa_o,        // A' and whether it exists
  output logic                          oka_o,
  output rgb_t                          ob_o,        // B' and whether it exists
  output logic                          okb_o
);

  logic is_valid_q, rd_valid_q;

  `MSR_CLR_REG(u_valid_q, 3, clear_i, 1'b1, {gr_valid_i, is_valid_q, rd_valid_q},
               {is_valid_q, rd_valid_q, valid_o})

  // ---- IS: no enable (an enable would hang the grant's fan-out on every one of these) ----
  logic [CTX_W-1:0] is_ctx_q;
  eng_pos_t         is_pos_q;

  always_ff @(posedge clk_i) begin
    is_ctx_q <= gr_ctx_i;
    is_pos_q <= gr_pos_i;
  end

  // ---- RD: the descriptor's fields (the tile buffer's data arrive two clocks after gr_*_i) --
  logic [CTX_W-1:0]    rd_ctx_q;
  eng_pos_t            rd_pos_q;
  coord_t              rd_gx_q, rd_gy_q;
  logic                rd_lin_q;
  logic [LCOORD_W-2:0] rd_mh_q, is_mh;
  metric_e             rd_metric_q;
  thr_t                rd_thr_q;
  // read in part: the tile's size goes elsewhere
  /* verilator lint_off UNUSEDSIGNAL */
  tile_desc_t          is_desc;
  /* verilator lint_on UNUSEDSIGNAL */

  assign is_desc = desc_i[is_ctx_q];

  always_ff @(posedge clk_i) begin
    if (is_valid_q) begin
      rd_ctx_q    <= is_ctx_q;
      rd_pos_q    <= is_pos_q;
      rd_gx_q     <= is_desc.x0 + coord_t'(is_pos_q.x);
      rd_gy_q     <= is_desc.y0 + coord_t'(is_pos_q.y);
      rd_lin_q    <= LINDILATE != 0 && is_desc.rule == RULE_LINDILATE && !is_pos_q.init;
      rd_mh_q     <= is_mh;
      rd_metric_q <= is_desc.metric;
      // threshold of the position's level; an initial-grid position gets 0 (always trace)
      rd_thr_q    <= is_pos_q.init ? '0 : is_desc.thr[is_pos_q.level - 1'b1];
    end
  end

  // lindilate: line tracking, the outer samples' existence (IS -> RD) and A' (RD)
  logic       rd_fline, rd_oka, rd_okb;
  logic [3:0] rd_ldelta;
  rgb_t       rd_a, rd_o2, rd_oa;

  assign rd_a  = rd_a_i[rd_ctx_q];
  assign rd_o2 = rd_o2_i[rd_ctx_q];

  msr_lin_track #(.NUM_CTX(NUM_CTX), .CTX_W(CTX_W)) u_lin_track (
    .clk_i, .rst_ni, .clear_i,
    .gr_valid_i  (gr_valid_i),
    .gr_gnt_i    (gr_gnt_i),
    .gr_pos_i    (gr_pos_i),
    .is_valid_i  (is_valid_q),
    .is_ctx_i    (is_ctx_q),
    .is_pos_i    (is_pos_q),
    .is_desc_i   (is_desc),
    .is_mh_o     (is_mh),
    .rd_valid_i  (rd_valid_q),
    .rd_ctx_i    (rd_ctx_q),
    .rd_o2a_i    (rd_pos_q.o2a),
    .rd_a_i      (rd_a),
    .rd_o2_i     (rd_o2),
    .rd_fline_o  (rd_fline),
    .rd_ldelta_o (rd_ldelta),
    .rd_oka_o    (rd_oka),
    .rd_okb_o    (rd_okb),
    .rd_oa_o     (rd_oa)
  );

  // ---- AB: the issued context's read data, registered ------------------------------------
  typedef struct packed {
    logic [CTX_W-1:0]    ctx;
    eng_pos_t            pos;
    coord_t              gx, gy;
    metric_e             metric;
    thr_t                thr;
    rgb_t                a, b;
    logic                lin;
    logic [LCOORD_W-2:0] mh;
    logic                fline;
    logic [3:0]          ldelta;
    rgb_t                oa;
    logic                oka;
    rgb_t                ob;
    logic                okb;
  } ab_t;
  ab_t ab_q;

  always_ff @(posedge clk_i) begin
    if (rd_valid_q) begin
      ab_q <= '{ctx: rd_ctx_q, pos: rd_pos_q, gx: rd_gx_q, gy: rd_gy_q, metric: rd_metric_q,
                thr: rd_thr_q, a: rd_a, b: rd_b_i[rd_ctx_q], lin: rd_lin_q, mh: rd_mh_q,
                fline: rd_fline, ldelta: rd_ldelta,
                oa: rd_oa, oka: rd_oka,    // A': port 2 where o2a, else the context's previous A
                ob: rd_o2, okb: rd_okb};   // B': port 2
    end
  end

  assign rd_valid_o = rd_valid_q;
  assign rd_ctx_o   = rd_ctx_q;

  assign ctx_o    = ab_q.ctx;
  assign pos_o    = ab_q.pos;
  assign gx_o     = ab_q.gx;
  assign gy_o     = ab_q.gy;
  assign metric_o = ab_q.metric;
  assign thr_o    = ab_q.thr;
  assign a_o      = ab_q.a;
  assign b_o      = ab_q.b;
  assign lin_o    = ab_q.lin;
  assign mh_o     = ab_q.mh;
  assign fline_o  = ab_q.fline;
  assign ldelta_o = ab_q.ldelta;
  assign oa_o     = ab_q.oa;
  assign oka_o    = ab_q.oka;
  assign ob_o     = ab_q.ob;
  assign okb_o    = ab_q.okb;

endmodule : msr_operand_fetch
