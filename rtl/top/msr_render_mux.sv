// Render mux: the NUM_ENGINES engines' render requests onto the one request port, and the
// responses back to the engine named in their tag.
//
// Requests: a 4-entry queue per engine (an engine whose request waits for the shared port
// would stall its decision pipeline) with its head in a spill register, a round-robin arbiter
// over the heads (msr_rr_arb)
// and a spill register on the port: the port's valid, data and ready are all registered, and
// an offered request stays until taken. The tag on the port is {engine, engine tag}. While
// hold_i (soft reset) no new request enters a queue; queued ones still go out (the engines
// count them in flight, so the drain waits for their responses).
// Responses: a spill register on the port (rnd_rsp_ready_o is a register), then the engine id
// in the tag selects the engine. A response whose engine id does not exist (possible when
// NUM_ENGINES is not a power of two) is taken and dropped, and flagged on bad_eid_o.
`include "msr_assert.svh"

module msr_render_mux import msr_pkg::*; #(
  parameter int unsigned NUM_ENGINES = 4,                                  // engines
  parameter int unsigned ETAG_W      = 6,                                  // engine tag bits
  // a response's data: the colour, or with the engines' depth channel {inverse depth, colour}
  parameter int unsigned DATA_W      = $bits(rgb_t),
  localparam int unsigned EID_W  = (NUM_ENGINES > 1) ? $clog2(NUM_ENGINES) : 1,
  localparam int unsigned RTAG_W = EID_W + ETAG_W
) (
  input  logic                   clk_i,            // clock
  input  logic                   rst_ni,           // asynchronous reset, active low
  input  logic                   clear_i,          // synchronous clear (nothing in flight)
  input  logic                   hold_i,           // no new request enters the queues
  // Engines' requests.
  input  logic   [NUM_ENGINES-1:0]             eng_req_valid_i,
  output logic   [NUM_ENGINES-1:0]             eng_req_ready_o,
  input  coord_t [NUM_ENGINES-1:0]             eng_req_x_i,
  input  coord_t [NUM_ENGINES-1:0]             eng_req_y_i,
  input  logic   [NUM_ENGINES-1:0][ETAG_W-1:0] eng_req_tag_i,
  // Engines' responses (data shared; valid to the engine named in the tag).
  output logic   [NUM_ENGINES-1:0]             eng_rsp_valid_o,
  input  logic   [NUM_ENGINES-1:0]             eng_rsp_ready_i,
  output logic   [ETAG_W-1:0]                  eng_rsp_tag_o,
  output logic   [DATA_W-1:0]                  eng_rsp_rgb_o,
  // Render request port.
  output logic              rnd_req_valid_o,    // a request
  input  logic              rnd_req_ready_i,    // the rendering unit takes it
  output coord_t            rnd_req_x_o,        // global x
  output coord_t            rnd_req_y_o,        // global y
  output logic [RTAG_W-1:0] rnd_req_tag_o,      // {engine, engine tag}
  // Render response port.
  input  logic              rnd_rsp_valid_i,    // a traced colour
  output logic              rnd_rsp_ready_o,    // taken
  input  logic [RTAG_W-1:0] rnd_rsp_tag_i,      // tag of the request
  input  logic [DATA_W-1:0] rnd_rsp_rgb_i,      // colour (and inverse depth)
  // Status.
  output logic              busy_o,             // a request queued / offered or a response held
  output logic              bad_eid_o           // pulse: a response for an engine that is not there
);
  typedef struct packed {
    coord_t            x;
    coord_t            y;
    logic [RTAG_W-1:0] tag;
  } rreq_t;

  typedef struct packed {
    logic [RTAG_W-1:0] tag;
    logic [DATA_W-1:0] rgb;
  } rrsp_t;

  // ---- Request queues ------------------------------------------------------------------------
  // Each queue's head sits in a spill register: the arbiter's requests and the data it picks
  // come from flip-flops, not from the FIFO's count and its LUT-RAM read (in the flat top that
  // path, queue state -> arbiter -> the pick of the head -> the port register, was too long).
  logic  [NUM_ENGINES-1:0] fq_valid, fq_ready, rq_valid, rq_pop, rq_push_ready;
  rreq_t [NUM_ENGINES-1:0] fq_data, rq_data;

  for (genvar i = 0; i < NUM_ENGINES; i++) begin : g_queue
    logic [2:0] count;
    logic       unused_count;
    msr_fifo #(.WIDTH($bits(rreq_t)), .DEPTH(4)) u_req_fifo (
      .clk_i, .rst_ni, .flush_i (clear_i),
      .valid_i (eng_req_valid_i[i] && !hold_i), .ready_o (rq_push_ready[i]),
      .data_i  ({eng_req_x_i[i], eng_req_y_i[i], EID_W'(i), eng_req_tag_i[i]}),
      .valid_o (fq_valid[i]), .ready_i (fq_ready[i]), .data_o (fq_data[i]),
      .count_o (count)
    );
    msr_spill_reg #(.WIDTH($bits(rreq_t))) u_head (
      .clk_i, .rst_ni, .clear_i,
      .valid_i (fq_valid[i]), .ready_o (fq_ready[i]), .data_i (fq_data[i]),
      .valid_o (rq_valid[i]), .ready_i (rq_pop[i]),   .data_o (rq_data[i])
    );
    assign unused_count       = ^count;
    assign eng_req_ready_o[i] = rq_push_ready[i] && !hold_i;
  end

  // ---- Arbiter and the port's spill register -----------------------------------------------------
  logic [NUM_ENGINES-1:0] gnt;
  logic [EID_W-1:0]       gnt_idx;
  logic                   arb_valid, sp_ready;
  rreq_t                  req_out;

  // PREFIX and MASKS: the engines' queue heads are spread over the die (see msr_rr_arb)
  msr_rr_arb #(.N(NUM_ENGINES), .LOCK(1'b0), .PREFIX(1'b1), .MASKS(1'b1), .IDX_W(EID_W)) u_req_arb (
    .clk_i, .rst_ni, .clear_i,
    .req_i   (rq_valid), .gnt_o (gnt), .idx_o (gnt_idx),
    .valid_o (arb_valid), .ready_i (sp_ready)
  );
  assign rq_pop = gnt & {NUM_ENGINES{sp_ready}};

  msr_spill_reg #(.WIDTH($bits(rreq_t))) u_req_spill (
    .clk_i, .rst_ni, .clear_i,
    .valid_i (arb_valid),       .ready_o (sp_ready),        .data_i (rq_data[gnt_idx]),
    .valid_o (rnd_req_valid_o), .ready_i (rnd_req_ready_i), .data_o (req_out)
  );
  // By field name, not position: a reordered rreq_t cannot swap them silently.
  assign rnd_req_x_o   = req_out.x;
  assign rnd_req_y_o   = req_out.y;
  assign rnd_req_tag_o = req_out.tag;

  // ---- Responses -----------------------------------------------------------------------------------
  logic             rsp_valid, rsp_ready, eid_ok;
  rrsp_t            rsp;
  logic [EID_W-1:0] rsp_eid;

  msr_spill_reg #(.WIDTH($bits(rrsp_t))) u_rsp_spill (
    .clk_i, .rst_ni, .clear_i,
    .valid_i (rnd_rsp_valid_i), .ready_o (rnd_rsp_ready_o),
    .data_i  ({rnd_rsp_tag_i, rnd_rsp_rgb_i}),
    .valid_o (rsp_valid), .ready_i (rsp_ready), .data_o (rsp)
  );

  assign rsp_eid = rsp.tag[RTAG_W-1 -: EID_W];
  assign eid_ok  = (32'(rsp_eid) < NUM_ENGINES);
  for (genvar i = 0; i < NUM_ENGINES; i++) begin : g_rsp
    assign eng_rsp_valid_o[i] = rsp_valid && (rsp_eid == EID_W'(i));
  end
  assign rsp_ready     = eid_ok ? eng_rsp_ready_i[rsp_eid] : 1'b1;
  assign eng_rsp_tag_o = rsp.tag[ETAG_W-1:0];
  assign eng_rsp_rgb_o = rsp.rgb;
  assign bad_eid_o     = rsp_valid && !eid_ok;

  assign busy_o = (fq_valid != '0) || (rq_valid != '0) || rnd_req_valid_o || rsp_valid;

  /* verilator lint_off SYNCASYNCNET */
  `MSR_ASSERT_NXT(a_req_stable, rnd_req_valid_o && !rnd_req_ready_i,
              rnd_req_valid_o && $stable(rnd_req_tag_o), clk_i, !rst_ni || clear_i)
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_render_mux
