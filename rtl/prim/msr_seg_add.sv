// Adder cut into SEG_W-bit segments, each with a carry in and a carry out of its own, for sums
// whose carries are registered between the segments (the carry out of segment k comes back as
// the carry into segment k + 1 a clock later): no carry runs across more than one segment in a
// clock. Combinational; the caller holds the registers.
module msr_seg_add #(
  parameter int unsigned  WIDTH = 32,            // bits, a multiple of SEG_W
  parameter int unsigned  SEG_W = 8,             // segment bits
  localparam int unsigned NSEG  = WIDTH / SEG_W
) (
  input  logic [WIDTH-1:0] a_i,                  // addends
  input  logic [WIDTH-1:0] b_i,
  input  logic [NSEG-1:0]  c_i,                  // carry into segment k
  output logic [WIDTH-1:0] s_o,                  // segment k: a + b + c_i[k], mod 2^SEG_W
  output logic [NSEG-1:0]  c_o                   // carry out of segment k
);

  if (WIDTH % SEG_W != 0 || SEG_W < 1) begin : g_check_widths
    $fatal(1, "msr_seg_add: WIDTH %0d must be a multiple of SEG_W %0d", WIDTH, SEG_W);
  end

  for (genvar k = 0; k < NSEG; k++) begin : g_seg
    assign {c_o[k], s_o[SEG_W*k +: SEG_W]} = {1'b0, a_i[SEG_W*k +: SEG_W]} +
                                             {1'b0, b_i[SEG_W*k +: SEG_W]} + (SEG_W+1)'(c_i[k]);
  end

endmodule : msr_seg_add
