// Saturating event counter for the performance registers: adds inc_i (0..2^INC_W-1) per clock
// while en_i, stops at all ones. The count is kept in SEG_W-bit segments with a registered
// carry between them, so no carry runs across more than one segment in a clock (a 32-bit
// counter is four 8-bit adders, not one 32-bit one); the value read is exact once the carries
// have settled, SEG-count - 1 clocks after the last event (the registers are read after a
// frame, when the counters are still).
`include "msr_assert.svh"
`include "msr_flops.svh"

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
  logic [NSEG-1:0]            cout;
  logic                       ovf;       // the top segment overflows this clock
  // Segment 0 takes the increment (no carry), segment k > 0 its pending carry.
  msr_seg_add #(.WIDTH(WIDTH), .SEG_W(SEG_W)) u_add (
    .a_i (seg_q),
    .b_i (WIDTH'(en_i ? inc_i : '0)),
    .c_i (cin_q & ~NSEG'(1)),
    .s_o (seg_d),
    .c_o (cout)
  );
  assign cin_d = NSEG'({cout, 1'b0});
  assign ovf   = cout[NSEG-1];

  `MSR_CLR_REG(u_seg, NSEG * SEG_W + NSEG, clear_i, 1'b1, {seg_d, cin_d}, {seg_q, cin_q})
  // Sticky: once the top segment overflows, the count reads all ones until a clear.
  `MSR_CLR_REG(u_sat, 1, clear_i, ovf, 1'b1, sat_q)

  assign count_o = sat_q ? '1 : seg_q;

endmodule : msr_sat_counter
