// Depth interpolation (docs/spec/reuse.md, "the engines carry it as a fourth channel"): the
// inverse depth of a position between neighbours A and B, the spec's interpolation on a 16-bit
// channel,
//   W = ((g - o) * WA + o * WB + floor(g / 2)) / g,
// except where exactly one neighbour is sky (0): then the other one (the nearer surface).
// It runs beside msr_decision_pipe, stage for stage (the same advance and the same six
// stages), so its output is valid with the decision's. The division by g in 2..8 is a multiply
// by RECIP[g] = ceil(2^22 / g) and a shift by 22: exact for every numerator below 2^19
// (8 * 65535 + 4 = 524284; tb/depth_interp checks every g over the whole range).
//   S0  inputs registered; g - o
//   S1  (g - o) * WA and o * WB (4-bit factors: adds); the sky choice
//   S2  numerator (g - o) * WA + o * WB + floor(g / 2); RECIP[g]
//   S3  numerator times the six 4-bit pieces of RECIP[g]
//   S4  pieces summed in pairs
//   S5  product = pair0 + pair1 << 8 + pair2 << 16; W is its bits 22..37 (output register)
// As in msr_interp (msr_pkg's mul4), no stage holds more than a 19 x 4 product or a three-term
// sum.
`include "msr_flops.svh"

module msr_depth_interp
  import msr_pkg::*;
(
  input  logic        clk_i,
  input  logic        rst_ni,
  input  logic        clear_i,     // synchronous flush (with the decision pipeline's)
  input  logic        advance_i,   // the decision pipeline moves on
  input  logic        valid_i,     // a position enters S0 (with the pipeline's valid_i)
  input  logic [15:0] wa_i,        // neighbour A's inverse depth
  input  logic [15:0] wb_i,        // neighbour B's inverse depth
  input  gap_t        gap_i,       // g, 2..8 wherever W is used
  input  gap_t        off_i,       // o, 0..g-1
  output logic        valid_o,     // W valid (with the pipeline's valid_o)
  output logic [15:0] invz_o       // W
);

  localparam int unsigned W_W     = 16;
  localparam int unsigned NUM_W   = 19;               // 8 * 65535 + 4: numerator, products
  localparam int unsigned SHIFT   = 22;
  localparam int unsigned PIECE_W = 4;
  localparam int unsigned NPIECE  = 6;                // RECIP[g] < 2^22: six 4-bit pieces
  localparam int unsigned PART_W  = NUM_W + PIECE_W;  // 23
  localparam int unsigned PAIR_W  = PART_W + PIECE_W; // 27: p0 + p1 << 4
  localparam int unsigned TOP     = SHIFT + W_W;      // bits below 38 hold W

  // ceil(2^SHIFT / g); entries 0 and 1 are never used (g >= 2 wherever W is used).
  function automatic logic [NPIECE*PIECE_W-1:0] recip(gap_t g);
    unique case (g)
      4'd2:    return 24'd2097152;
      4'd3:    return 24'd1398102;
      4'd4:    return 24'd1048576;
      4'd5:    return 24'd838861;
      4'd6:    return 24'd699051;
      4'd7:    return 24'd599187;
      4'd8:    return 24'd524288;
      default: return 24'd0;
    endcase
  endfunction


  logic [5:0] stage_valid_q;    // S0..S5 hold a position; S5's bit is valid_o

  // ---- S0: inputs registered --------------------------------------------------------------
  logic [W_W-1:0] s0_wa_q, s0_wb_q;
  gap_t           s0_gap_q, s0_off_q, s0_gmo_q;
  always_ff @(posedge clk_i) begin
    if (advance_i && valid_i) begin
      s0_wa_q  <= wa_i;
      s0_wb_q  <= wb_i;
      s0_gap_q <= gap_i;
      s0_off_q <= off_i;
      s0_gmo_q <= gap_i - off_i;
    end
  end

  // ---- S1: the weighted neighbours, and where exactly one neighbour is sky --------------------
  logic [NUM_W-1:0]  s1_pa_q, s1_pb_q;   // (g - o) * WA, o * WB
  gap_t              s1_gap_q;
  logic              s1_sky_q;       // exactly one of WA, WB is 0: W is the other
  logic [W_W-1:0]    s1_near_q;      // max(WA, WB)
  always_ff @(posedge clk_i) begin
    if (advance_i && stage_valid_q[0]) begin
      s1_pa_q   <= NUM_W'(mul4(s0_gmo_q, MUL4_X_W'(s0_wa_q)));
      s1_pb_q   <= NUM_W'(mul4(s0_off_q, MUL4_X_W'(s0_wb_q)));
      s1_gap_q  <= s0_gap_q;
      s1_sky_q  <= (s0_wa_q == '0) != (s0_wb_q == '0);
      s1_near_q <= (s0_wa_q > s0_wb_q) ? s0_wa_q : s0_wb_q;
    end
  end

  // ---- S2: numerator and reciprocal ----------------------------------------------------------
  logic [NUM_W-1:0]          s2_num_q;
  logic [NPIECE*PIECE_W-1:0] s2_recip_q;
  logic [2:0]                sky_q;   // the sky choice carried to S5: [0] S2, [1] S3, [2] S4
  logic [2:0][W_W-1:0]       near_q;
  always_ff @(posedge clk_i) begin
    if (advance_i && stage_valid_q[1]) begin
      s2_num_q      <= s1_pa_q + s1_pb_q + NUM_W'(s1_gap_q >> 1);
      s2_recip_q    <= recip(s1_gap_q);
      sky_q[0]   <= s1_sky_q;
      near_q[0]  <= s1_near_q;
    end
    if (advance_i && stage_valid_q[2]) {sky_q[1], near_q[1]} <= {sky_q[0], near_q[0]};
    if (advance_i && stage_valid_q[3]) {sky_q[2], near_q[2]} <= {sky_q[1], near_q[1]};
  end

  // ---- S3: the numerator times six 4-bit pieces of RECIP[g] ----------------------------------
  logic [NPIECE-1:0][PART_W-1:0] s3_part_q;
  always_ff @(posedge clk_i) begin
    if (advance_i && stage_valid_q[2]) begin
      for (int unsigned k = 0; k < NPIECE; k++) begin
        s3_part_q[k] <= mul4(s2_recip_q[PIECE_W*k +: PIECE_W], s2_num_q);
      end
    end
  end

  // ---- S4: pairs of pieces summed ---------------------------------------------------------------
  logic [NPIECE/2-1:0][PAIR_W-1:0] s4_pair_q;
  always_ff @(posedge clk_i) begin
    if (advance_i && stage_valid_q[3]) begin
      for (int unsigned j = 0; j < NPIECE / 2; j++) begin
        s4_pair_q[j] <= PAIR_W'(s3_part_q[2*j]) + (PAIR_W'(s3_part_q[2*j+1]) << PIECE_W);
      end
    end
  end

  // ---- S5: output register ----------------------------------------------------------------------
  // The quotient is <= 65535, so nothing at or above bit TOP is ever set.
  // Bits below SHIFT are the fraction W drops.
  /* verilator lint_off UNUSEDSIGNAL */
  logic [TOP-1:0] prod;
  /* verilator lint_on UNUSEDSIGNAL */
  assign prod = TOP'(s4_pair_q[0]) + (TOP'(s4_pair_q[1]) << (2 * PIECE_W)) +
                (TOP'(s4_pair_q[2]) << (4 * PIECE_W));
  always_ff @(posedge clk_i) begin
    if (advance_i && stage_valid_q[4]) begin
      invz_o <= sky_q[2] ? near_q[2] : prod[SHIFT +: W_W];
    end
  end

  // ---- Valid bits: one shift register, as the pipeline's ----------------------------------------
  `MSR_CLR_REG(u_valid, 6, clear_i, advance_i, {stage_valid_q[4:0], valid_i}, stage_valid_q)
  assign valid_o = stage_valid_q[5];

endmodule : msr_depth_interp
