// Interpolation unit (spec section 3, claim 12): per channel
//   C = ((g - o) * A + o * B + floor(g / 2)) / g,   g = b - a in 2..8, o = m - a in 1..g-1.
// The numerator is at most 8 * 255 + 4 = 2044 (11 bit). Division by the constant g is a
// multiply by RECIP[g] = ceil(2^14 / g) and a shift by 14, which is exact for every
// numerator 0..2047 and every g in 2..8 (proven by tb/interp/test_interp.py over the
// whole range). No divider. Two register stages, one result per clock.
module msr_interp
  import msr_pkg::*;
#(
  parameter int unsigned USER_W = 1   // sideband carried alongside each result
) (
  input  logic              clk_i,
  input  logic              rst_ni,
  input  logic              clear_i,    // synchronous flush of the pipeline
  input  logic              valid_i,    // one interpolation to do
  output logic              ready_o,
  input  rgb_t              a_i,        // colour at a
  input  rgb_t              b_i,        // colour at b
  input  gap_t              gap_i,      // g, 2..8
  input  gap_t              off_i,      // o = m - a, 1..g-1
  input  logic [USER_W-1:0] user_i,
  output logic              valid_o,    // result ready
  input  logic              ready_i,
  output rgb_t              rgb_o,      // interpolated colour
  output logic [USER_W-1:0] user_o
);

  localparam int unsigned NUM_W   = 11;           // numerator <= 2044
  localparam int unsigned RECIP_W = 14;           // ceil(2^14 / g) <= 8192
  localparam int unsigned SHIFT   = 14;
  localparam int unsigned PROD_W  = NUM_W + RECIP_W;

  // ceil(2^SHIFT / g); entries 0 and 1 are never used (g >= 2).
  function automatic logic [RECIP_W-1:0] recip(gap_t g);
    unique case (g)
      4'd2:    return 14'd8192;
      4'd3:    return 14'd5462;
      4'd4:    return 14'd4096;
      4'd5:    return 14'd3277;
      4'd6:    return 14'd2731;
      4'd7:    return 14'd2341;
      4'd8:    return 14'd2048;
      default: return 14'd0;
    endcase
  endfunction

  logic advance;
  assign advance = !valid_o || ready_i;
  assign ready_o = advance;

  // ---- Stage 1: weighted sum plus rounding term ----------------------------------------------
  logic                    s1_valid_q;
  logic [2:0][NUM_W-1:0]   s1_num_q, s1_num_d;
  logic [RECIP_W-1:0]      s1_recip_q;
  logic [USER_W-1:0]       s1_user_q;
  gap_t                    wa;

  always_comb begin
    wa = gap_i - off_i;
    s1_num_d[2] = NUM_W'(wa) * NUM_W'(a_i.r) + NUM_W'(off_i) * NUM_W'(b_i.r) + NUM_W'(gap_i >> 1);
    s1_num_d[1] = NUM_W'(wa) * NUM_W'(a_i.g) + NUM_W'(off_i) * NUM_W'(b_i.g) + NUM_W'(gap_i >> 1);
    s1_num_d[0] = NUM_W'(wa) * NUM_W'(a_i.b) + NUM_W'(off_i) * NUM_W'(b_i.b) + NUM_W'(gap_i >> 1);
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      s1_valid_q <= 1'b0;
    end else if (clear_i) begin
      s1_valid_q <= 1'b0;
    end else if (advance) begin
      s1_valid_q <= valid_i;
    end
  end

  always_ff @(posedge clk_i) begin
    if (advance && valid_i) begin
      s1_num_q   <= s1_num_d;
      s1_recip_q <= recip(gap_i);
      s1_user_q  <= user_i;
    end
  end

  // ---- Stage 2: multiply by the reciprocal and shift ---------------------------------------
  logic [2:0][PROD_W-1:0] prod;
  rgb_t                   rgb_d;

  always_comb begin
    for (int unsigned c = 0; c < 3; c++) begin
      prod[c] = PROD_W'(s1_num_q[c]) * PROD_W'(s1_recip_q);
    end
    // The quotient is <= 255, so the 8 bits above the shift are the whole result.
    rgb_d.r = prod[2][SHIFT +: 8];
    rgb_d.g = prod[1][SHIFT +: 8];
    rgb_d.b = prod[0][SHIFT +: 8];
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      valid_o <= 1'b0;
    end else if (clear_i) begin
      valid_o <= 1'b0;
    end else if (advance) begin
      valid_o <= s1_valid_q;
    end
  end

  always_ff @(posedge clk_i) begin
    if (advance && s1_valid_q) begin
      rgb_o  <= rgb_d;
      user_o <= s1_user_q;
    end
  end

`ifndef SYNTHESIS
  // Lint: disable iff (!rst_ni) looks like a synchronous use of the asynchronous reset.
  /* verilator lint_off SYNCASYNCNET */
  a_hold : assert property (@(posedge clk_i) disable iff (!rst_ni || clear_i)
      valid_o && !ready_i |=> valid_o && $stable({rgb_o, user_o}))
    else $error("msr_interp: output changed while stalled");
  // Only checked for real interpolations: the engine also pushes trace steps through.
  a_range : assert property (@(posedge clk_i) disable iff (!rst_ni)
      valid_i && ready_o && off_i != '0 |-> gap_i inside {[2 : 8]} && off_i < gap_i)
    else $error("msr_interp: gap %0d / offset %0d out of range", gap_i, off_i);
  /* verilator lint_on SYNCASYNCNET */
`endif

endmodule : msr_interp
