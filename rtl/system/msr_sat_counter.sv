// Saturating event counter for the performance registers: adds inc_i (0..2^INC_W-1) per clock
// while en_i, stops at all ones. The count is kept in SEG_W-bit segments with a registered
// carry between them, so no carry runs across more than one segment in a clock (a 32-bit
// counter is four 8-bit adders, not one 32-bit one); the value read is exact once the carries
// have settled, SEG-count - 1 clocks after the last event (the registers are read after a
// frame, when the counters are still).
`include "msr_assert.svh"

module msr_sat_counter #(
  parameter int unsigned WIDTH = 32,    // counter bits, a multiple of SEG_W
  parameter int unsigned INC_W = 1,     // increment bits, <= SEG_W
  parameter int unsigned SEG_W = 8      // segment bits
) (
  input  logic             clk_i,       // clock
  input  logic             rst_ni,      // asynchronous reset, active low
  input  logic             clear_i,     // synchronous: back to 0
  input  logic             en_i,        // count this clock
  input  logic [INC_W-1:0] inc_i,       // amount
  output logic [WIDTH-1:0] count_o      // value, all ones once saturated
);
  localparam int unsigned NSEG = WIDTH / SEG_W;

  if (WIDTH % SEG_W != 0 || INC_W > SEG_W || INC_W < 1) begin : g_check_widths
    $fatal(1, "msr_sat_counter: WIDTH %0d must be a multiple of SEG_W %0d >= INC_W %0d >= 1",
           WIDTH, SEG_W, INC_W);
  end

  logic [NSEG-1:0][SEG_W-1:0] seg_q;
  logic [NSEG-1:0]            cin_q;     // carry into segment k (k > 0), pending
  logic                       sat_q;

  logic [NSEG-1:0][SEG_W-1:0] seg_d;
  logic [NSEG-1:0]            cin_d;
  logic                       ovf;       // the top segment overflows this clock
  always_comb begin
    cin_d = '0;
    ovf   = 1'b0;
    for (int unsigned k = 0; k < NSEG; k++) begin
      logic [SEG_W:0] sum;
      if (k == 0) sum = {1'b0, seg_q[0]} + (SEG_W+1)'(en_i ? inc_i : '0);
      else        sum = {1'b0, seg_q[k]} + (SEG_W+1)'(cin_q[k]);
      seg_d[k] = sum[SEG_W-1:0];
      if (k + 1 < NSEG) cin_d[k+1] = sum[SEG_W];
      else              ovf        = sum[SEG_W];
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      seg_q <= '0;
      cin_q <= '0;
      sat_q <= 1'b0;
    end else if (clear_i) begin
      seg_q <= '0;
      cin_q <= '0;
      sat_q <= 1'b0;
    end else begin
      seg_q <= seg_d;
      cin_q <= cin_d;
      if (ovf) sat_q <= 1'b1;
    end
  end

  assign count_o = sat_q ? '1 : seg_q;

  logic unused_cin;
  assign unused_cin = cin_q[0];   // segment 0 takes the increment, not a carry

endmodule : msr_sat_counter
