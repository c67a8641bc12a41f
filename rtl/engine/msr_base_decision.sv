// Base decision of the `lindilate` rule (docs/rules.md, steps 1-3) for one position of one
// line: D = P or Q, from the four samples A' (at a - g), A, B and B' (at b + g) of the line.
//   P  the patent's test:            d(A, B) * n_k < thr_k' * g
//   Q  the second-difference test:   c2 * n_k < thr_k' * g, c2 the larger of
//        e_A' = d(A' - 2A + B) and e_B' = d(A - 2B + B') over the outer samples that exist,
//        false when neither exists
// d(.) is the run-time metric over the three channels: the largest |channel| or their sum.
// The dilation across lines (step 4) is not here: it combines the D of three lines.
//
// Data-only pipeline stages S1..S4 that move when en_i is high (the caller's global stall,
// as in msr_decision_pipe): inputs are expected from flip-flops (the caller's S0), base_o is
// the decision of the inputs taken four enabled clocks before. Each stage stays well under
// 30 levels of generic logic:
//   S1  per-channel |A - B|, the signed second differences, thr * g
//   S2  |second differences|; d of A, B (max or sum)
//   S3  e_A', e_B' (max or sum); P
//   S4  c2 over the outer samples that exist; Q; D = P or Q (output register)
module msr_base_decision
  import msr_pkg::*;
(
  input  logic       clk_i,
  input  logic       en_i,          // every stage moves
  input  rgb_t       outer_a_i,     // A' (colour; ignored unless outer_a_ok_i)
  input  logic       outer_a_ok_i,  // A' exists: inside the tile and final before the pass
  input  rgb_t       a_i,           // A
  input  rgb_t       b_i,           // B
  input  rgb_t       outer_b_i,     // B'
  input  logic       outer_b_ok_i,  // B' exists
  input  metric_e    metric_i,
  input  thr_t       thr_i,         // foveated threshold thr_k'
  input  gap_t       gap_i,         // g = b - a, 2..8
  input  logic [1:0] nshift_i,      // log2(n_k)
  output logic       base_o,        // D = P or Q
  output logic       patent_o,      // P alone (waveforms, tests)
  output logic       second_o       // Q alone
);

  localparam int unsigned SD_W   = 10;               // signed second difference, -510..510
  localparam int unsigned E_W    = 11;               // e over the channels, sum metric <= 1530
  localparam int unsigned PROD_W = THR_W + GAP_W;    // thr * g <= 2040
  localparam int unsigned LHS_W  = E_W + 3;          // e << log2(n_k)

  // outer - 2 * near + far, one channel, as a signed value
  function automatic logic signed [SD_W-1:0] second_diff(chan_t outer, chan_t near, chan_t far);
    return $signed({2'b00, outer}) - $signed({1'b0, near, 1'b0}) + $signed({2'b00, far});
  endfunction

  function automatic logic [SD_W-2:0] magnitude(logic signed [SD_W-1:0] v);
    return (SD_W-1)'(v[SD_W-1] ? -v : v);
  endfunction

  // max or sum of three channel values (widths up to E_W)
  function automatic logic [E_W-1:0] reduce3(logic [E_W-1:0] c2, logic [E_W-1:0] c1,
                                             logic [E_W-1:0] c0, metric_e metric);
    logic [E_W-1:0] m;
    m = c2;
    if (c1 > m) m = c1;
    if (c0 > m) m = c0;
    return (metric == METRIC_SUM) ? c2 + c1 + c0 : m;
  endfunction

  // ---- S1 -------------------------------------------------------------------------------------
  chan_t [2:0] oa_ch, a_ch, b_ch, ob_ch;       // the samples' channels as arrays: [2] = R
  assign oa_ch = outer_a_i;
  assign a_ch  = a_i;
  assign b_ch  = b_i;
  assign ob_ch = outer_b_i;

  // What the tests need from S1 to S4 unchanged: the bound, which outer samples exist, n_k.
  typedef struct packed {
    logic [PROD_W-1:0] rhs;     // thr * g
    logic              oka;
    logic              okb;
    logic [1:0]        nshift;
  } carry_t;

  chan_t [2:0]                   s1_abs_q;
  logic  signed [2:0][SD_W-1:0]  s1_sda_q, s1_sdb_q;   // A' - 2A + B, A - 2B + B'
  carry_t                        s1_q;
  metric_e                       s1_metric_q;

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      for (int unsigned c = 0; c < 3; c++) begin   // channel 2 = R, 1 = G, 0 = B
        s1_abs_q[c] <= chan_absdiff(a_ch[c], b_ch[c]);
        s1_sda_q[c] <= second_diff(oa_ch[c], a_ch[c], b_ch[c]);
        s1_sdb_q[c] <= second_diff(ob_ch[c], b_ch[c], a_ch[c]);
      end
      s1_q         <= '{rhs: thr_times_gap(thr_i, gap_i), oka: outer_a_ok_i, okb: outer_b_ok_i,
                        nshift: nshift_i};
      s1_metric_q  <= metric_i;
    end
  end

  // ---- S2 -------------------------------------------------------------------------------------
  logic [2:0][SD_W-2:0] s2_ea_q, s2_eb_q;     // |second differences| per channel, <= 510
  logic [E_W-1:0]       s2_d_q;
  carry_t               s2_q;
  metric_e              s2_metric_q;

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      for (int unsigned c = 0; c < 3; c++) begin
        s2_ea_q[c] <= magnitude(s1_sda_q[c]);
        s2_eb_q[c] <= magnitude(s1_sdb_q[c]);
      end
      s2_d_q      <= reduce3(E_W'(s1_abs_q[2]), E_W'(s1_abs_q[1]), E_W'(s1_abs_q[0]), s1_metric_q);
      s2_q        <= s1_q;
      s2_metric_q <= s1_metric_q;
    end
  end

  // ---- S3 -------------------------------------------------------------------------------------
  logic [E_W-1:0]    s3_ea_q, s3_eb_q;
  logic              s3_p_q;
  carry_t            s3_q;

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      s3_ea_q     <= reduce3(E_W'(s2_ea_q[2]), E_W'(s2_ea_q[1]), E_W'(s2_ea_q[0]), s2_metric_q);
      s3_eb_q     <= reduce3(E_W'(s2_eb_q[2]), E_W'(s2_eb_q[1]), E_W'(s2_eb_q[0]), s2_metric_q);
      s3_p_q      <= (LHS_W'(s2_d_q) << s2_q.nshift) < LHS_W'(s2_q.rhs);
      s3_q        <= s2_q;
    end
  end

  // ---- S4: c2, Q and D -------------------------------------------------------------------------
  // Each outer sample's test is taken alone: c2 < bound for the larger of the two that exist
  // is both tests passing, so no max is formed.
  logic qa, qb;
  assign qa = (LHS_W'(s3_ea_q) << s3_q.nshift) < LHS_W'(s3_q.rhs);
  assign qb = (LHS_W'(s3_eb_q) << s3_q.nshift) < LHS_W'(s3_q.rhs);

  logic q;
  assign q = (s3_q.oka || s3_q.okb) && (qa || !s3_q.oka) && (qb || !s3_q.okb);

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      patent_o <= s3_p_q;
      second_o <= q;
      base_o   <= s3_p_q || q;
    end
  end

endmodule : msr_base_decision
