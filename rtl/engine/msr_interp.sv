// Interpolation unit (spec section 3): the colour of a position between neighbours A and B,
//   C = ((g - o) * A + o * B + floor(g / 2)) / g   per channel,
// with the division by g in 2..8 a multiply by RECIP[g] = ceil(2^14 / g) and a shift by 14,
// exact for every numerator 0..2047 (tb/interp proves it over the whole range). It is the
// colour half of msr_decision_pipe and moves with that pipeline's stages: stage k + 1 loads
// when the pipeline advances and stage k holds a position.
//   S1  (g - o) * A and o * B (4-bit factors: adds, no multiplier)
//   S2  numerator (g - o) * A + o * B + floor(g / 2); RECIP[g]
//   S3  numerator times the four 4-bit pieces of RECIP[g]
//   S4  pieces summed in pairs: p0 + p1 << 4, p2 + p3 << 4
//   S5  product = pair0 + pair1 << 8; C is its bits 14..21 (output register)
// No stage holds more than an 11 x 4 product or a 15-bit sum: both stay under 30 levels of
// generic logic (an 11 x 7 product is 34), which is what an ASIC clock of several hundred MHz
// asks for; msr_pkg's mul4 keeps the products out of the FPGA's multiplier blocks, whose fixed rows
// cost long wires on the placed top.
module msr_interp
  import msr_pkg::*;
(
  input  logic       clk_i,
  input  logic       advance_i,     // the pipeline moves on (its output is empty or taken)
  input  logic [4:0] stage_valid_i, // S0..S4 hold a position: S(k+1) loads from S(k)
  input  rgb_t       a_i,           // neighbour A, from S0's registers
  input  rgb_t       b_i,           // neighbour B, from S0's registers
  input  gap_t       gap_i,         // g, 2..8 wherever C is used
  input  gap_t       off_i,         // o, 0..g-1
  input  gap_t       gmo_i,         // g - o, formed at S0
  output rgb_t       rgb_o          // C, valid with the pipeline's output
);

  localparam int unsigned PROD_W  = THR_W + GAP_W;    // 12 bit: 255 * 8, 255 * 7 + 255 * 1
  localparam int unsigned NUM_W   = 11;               // numerator <= 8 * 255 + 4 = 2044
  localparam int unsigned SHIFT   = 14;
  localparam int unsigned PIECE_W = 4;
  localparam int unsigned PART_W  = NUM_W + PIECE_W;  // 15: an 11-bit value times 4 bits
  localparam int unsigned PAIR_W  = PART_W + PIECE_W; // 19: p0 + p1 << 4
  localparam int unsigned OUT_MSB = SHIFT + 8;        // bits 14..21 hold C

  // ceil(2^SHIFT / g); entries 0 and 1 are never used (g >= 2 wherever C is used).
  function automatic logic [15:0] recip(gap_t g);
    unique case (g)
      4'd2:    return 16'd8192;
      4'd3:    return 16'd5462;
      4'd4:    return 16'd4096;
      4'd5:    return 16'd3277;
      4'd6:    return 16'd2731;
      4'd7:    return 16'd2341;
      4'd8:    return 16'd2048;
      default: return 16'd0;
    endcase
  endfunction


  // ---- S1: the two weighted neighbours ---------------------------------------------------
  logic [2:0][PROD_W-1:0] s1_pa_q, s1_pb_q;   // (g - o) * A, o * B per channel
  gap_t                   s1_gap_q;

  always_ff @(posedge clk_i) begin
    if (advance_i && stage_valid_i[0]) begin
      s1_pa_q[2] <= PROD_W'(mul4(gmo_i, MUL4_X_W'(a_i.r)));
      s1_pa_q[1] <= PROD_W'(mul4(gmo_i, MUL4_X_W'(a_i.g)));
      s1_pa_q[0] <= PROD_W'(mul4(gmo_i, MUL4_X_W'(a_i.b)));
      s1_pb_q[2] <= PROD_W'(mul4(off_i, MUL4_X_W'(b_i.r)));
      s1_pb_q[1] <= PROD_W'(mul4(off_i, MUL4_X_W'(b_i.g)));
      s1_pb_q[0] <= PROD_W'(mul4(off_i, MUL4_X_W'(b_i.b)));
      s1_gap_q   <= gap_i;
    end
  end

  // ---- S2: numerator and reciprocal ------------------------------------------------------
  logic [2:0][NUM_W-1:0] s2_num_q;
  logic [15:0]           s2_recip_q;   // 14 bits and two zeros: four 4-bit pieces

  always_ff @(posedge clk_i) begin
    if (advance_i && stage_valid_i[1]) begin
      for (int unsigned c = 0; c < 3; c++) begin
        s2_num_q[c] <= NUM_W'(s1_pa_q[c]) + NUM_W'(s1_pb_q[c]) + NUM_W'(s1_gap_q >> 1);
      end
      s2_recip_q <= recip(s1_gap_q);
    end
  end

  // ---- S3: the numerator times four 4-bit pieces of RECIP[g] -----------------------------
  logic [2:0][3:0][PART_W-1:0] s3_part_q;

  always_ff @(posedge clk_i) begin
    if (advance_i && stage_valid_i[2]) begin
      for (int unsigned c = 0; c < 3; c++) begin
        for (int unsigned k = 0; k < 4; k++) begin
          s3_part_q[c][k] <= PART_W'(mul4(s2_recip_q[PIECE_W*k +: PIECE_W],
                                          MUL4_X_W'(s2_num_q[c])));
        end
      end
    end
  end

  // ---- S4: pairs of pieces summed --------------------------------------------------------
  logic [2:0][1:0][PAIR_W-1:0] s4_pair_q;   // p0 + p1 << 4, p2 + p3 << 4

  always_ff @(posedge clk_i) begin
    if (advance_i && stage_valid_i[3]) begin
      for (int unsigned c = 0; c < 3; c++) begin
        for (int unsigned j = 0; j < 2; j++) begin
          s4_pair_q[c][j] <= PAIR_W'(s3_part_q[c][2*j]) +
                             (PAIR_W'(s3_part_q[c][2*j+1]) << PIECE_W);
        end
      end
    end
  end

  // ---- S5: output register; product = pair0 + pair1 << 8 ---------------------------------
  // Only bits up to 21 are formed: the quotient is <= 255, so the 8 bits above the shift are
  // the whole result and nothing above them is ever set.
  logic [2:0][OUT_MSB-1:0] prod;

  always_comb begin
    for (int unsigned c = 0; c < 3; c++) begin
      prod[c] = OUT_MSB'(s4_pair_q[c][0]) + (OUT_MSB'(s4_pair_q[c][1]) << (2 * PIECE_W));
    end
  end

  always_ff @(posedge clk_i) begin
    if (advance_i && stage_valid_i[4]) begin
      rgb_o <= '{r: prod[2][SHIFT +: 8], g: prod[1][SHIFT +: 8], b: prod[0][SHIFT +: 8]};
    end
  end

endmodule : msr_interp
