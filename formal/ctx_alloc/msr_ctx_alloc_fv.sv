// Formal harness of msr_ctx_alloc (the tile engine's tile start). The contexts are modelled
// as the engine's are: a context is free until it starts (its free bit falls the clock after
// its start bit) and becomes free again whenever it has finished (a free input). The
// descriptor port follows valid / ready (held until taken); hold_i (the tag pool's reset) and
// the soft reset are free. Reset assumed in the first cycle.
// Proves: a start goes to one context, a free one, and only for a descriptor taken the clock
// before (the descriptor it holds); every descriptor taken starts exactly one context the
// next clock (none is lost), unless a clear drops it; no descriptor is taken while hold_i is
// high or no context is free and unclaimed.
module msr_ctx_alloc_fv
  import msr_pkg::*;
#(
  parameter int unsigned NUM_CTX = 3,
  parameter int unsigned CTX_W   = 2
) (
  input logic               clk_i, rst_ni, clear_i,
  input logic [NUM_CTX-1:0] finish_i,      // a busy context finishes (frees itself)
  input logic               hold_i,
  input logic               desc_valid_i,
  input tile_desc_t         desc_i
);
  logic               desc_ready_o;
  logic [NUM_CTX-1:0] start_o, busy_q;
  tile_desc_t         desc_o;

  msr_ctx_alloc #(.NUM_CTX(NUM_CTX), .CTX_W(CTX_W)) dut (
    .clk_i, .rst_ni, .clear_i, .ctx_free_i (~busy_q), .hold_i, .desc_valid_i, .desc_ready_o,
    .desc_i, .start_o, .desc_o
  );

  msr_fv_init u_init (.clk_i, .rst_ni, .init_o());

  // The contexts: busy from the clock after a start until a finish (a clear does not free a
  // context at once: the engine's contexts drain what they hold).
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) busy_q <= '0;
    else         busy_q <= (busy_q & ~finish_i) | start_o;
  end

  // The descriptor port: held, unchanged, until taken.
  logic       stall_q;
  tile_desc_t desc_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) stall_q <= 1'b0;
    else         stall_q <= desc_valid_i && !desc_ready_o && !clear_i;
  end
  always_ff @(posedge clk_i) desc_q <= desc_i;
  always_comb if (rst_ni && stall_q) assume (desc_valid_i && desc_i == desc_q);

  wire hs = desc_valid_i && desc_ready_o;

  // What the last clock did.
  logic       hs_q, clear_q, rst_q;
  tile_desc_t taken_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      hs_q <= 1'b0; clear_q <= 1'b0; rst_q <= 1'b1;
    end else begin
      hs_q <= hs; clear_q <= clear_i; rst_q <= 1'b0;
    end
  end
  always_ff @(posedge clk_i) taken_q <= desc_i;

  always_comb begin
    if (rst_ni) begin
      a_onehot:       assert ($onehot0(start_o));
      a_start_free:   assert ((start_o & busy_q) == '0);
      a_start_only_after_hs: assert (start_o == '0 || (hs_q && !clear_q));
      a_hs_starts:    assert (!hs_q || clear_q || rst_q || start_o != '0);
      a_desc_held:    assert (start_o == '0 || desc_o == taken_q);
      a_hold:         assert (!hold_i || !desc_ready_o);
    end
  end

  // a descriptor is taken only when some context is free and not being started
  logic room_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) room_q <= 1'b0;
    else         room_q <= ((~busy_q & ~start_o) != '0);
  end
  always_comb if (rst_ni && !rst_q) a_ready_room: assert (!desc_ready_o || room_q || hold_i);

  always_comb begin
    if (rst_ni) begin
      c_all_busy:  cover (busy_q == '1);
      c_back2back: cover (hs && hs_q && !clear_q);
      c_last_ctx:  cover (start_o[NUM_CTX-1]);
    end
  end
endmodule
