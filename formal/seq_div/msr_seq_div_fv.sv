// Formal harness of msr_seq_div: the loads, the preset and the data are free, in any order and
// any number of times, while no division runs; the solver may start one at any moment with
// go_i, which steps the divider on Q_W + 1 consecutive clocks as the controller does. Proves:
// the step count (last_o on the last step, never on another), and the quotient after the last
// step: floor(num / den), or Q_SAT when that is 2^Q_W or more, for the operands loaded last.
// Bounded (bmc): from reset, one division of any operands ends within the depth.
module msr_seq_div_fv #(
  parameter int unsigned R_W = 8,
  parameter int unsigned Q_W = 3,
  parameter logic [Q_W-1:0] Q_SAT = 3'd5
) (
  input logic           clk_i, rst_ni,
  input logic           init_i, load_num_i, load_den_i, go_i,
  input logic [Q_W-1:0] quo_init_i,
  input logic [R_W-1:0] num_i, den_i
);
  logic           step, last;
  logic [Q_W-1:0] quo;

  msr_fv_init #(.ONCE(1'b1)) u_init (.clk_i, .rst_ni, .init_o());

  // The harness's own sequence: idle (free loads), then Q_W + 1 steps, then the check.
  logic [3:0]     steps_q;                  // steps left, 0 = idle
  logic           done_q;                   // the last step was the clock before
  logic           inited_q, num_ok_q, den_ok_q;
  logic [R_W-1:0] num_q, den_q;
  wire            idle = steps_q == '0;
  wire            go   = idle && go_i && inited_q && num_ok_q && den_ok_q;
  assign step = !idle;

  // The divider's contract: den << Q_W fits R_W bits and is not zero; no loads while it runs.
  always_comb begin
    if (load_den_i) assume (den_i != '0 && (den_i >> (R_W - Q_W)) == '0);
    if (!idle) assume (!init_i && !load_num_i && !load_den_i);
    if (go_i) assume (!init_i && !load_num_i && !load_den_i);
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      steps_q  <= '0;
      done_q   <= 1'b0;
      inited_q <= 1'b0;
      num_ok_q <= 1'b0;
      den_ok_q <= 1'b0;
    end else begin
      done_q <= steps_q == 4'd1;
      if (go) steps_q <= 4'(Q_W + 1);
      else if (!idle) steps_q <= steps_q - 4'd1;
      if (init_i) inited_q <= 1'b1;
      if (load_num_i) num_ok_q <= 1'b1;
      if (load_den_i) den_ok_q <= 1'b1;
      if (go) {inited_q, num_ok_q, den_ok_q} <= '0;
    end
  end
  always_ff @(posedge clk_i) begin
    if (load_num_i) num_q <= num_i;
    if (load_den_i) den_q <= den_i;
  end

  msr_seq_div #(.R_W(R_W), .Q_W(Q_W), .Q_SAT(Q_SAT)) dut (
    .clk_i, .rst_ni, .init_i, .quo_init_i, .load_num_i, .num_i, .load_den_i, .den_i,
    .step_i(step), .last_o(last), .quo_o(quo)
  );

  // The reference without a divider (cheap for the solver): saturated iff num >= den << Q_W,
  // else q * den <= num < (q + 1) * den.
  wire [2*R_W-1:0] lo  = (2*R_W)'(quo) * (2*R_W)'(den_q);
  wire [2*R_W-1:0] hi  = lo + (2*R_W)'(den_q);
  wire             sat = (2*R_W)'(num_q) >= ((2*R_W)'(den_q) << Q_W);
  wire             q_ok = sat ? quo == Q_SAT : lo <= (2*R_W)'(num_q) && (2*R_W)'(num_q) < hi;

  a_last:     assert property (@(posedge clk_i) disable iff (!rst_ni) !step || last == (steps_q == 4'd1));
  a_quotient: assert property (@(posedge clk_i) disable iff (!rst_ni) !done_q || q_ok);

  // Non-vacuity: a saturated quotient, and a full-width one below it.
  c_sat:  cover property (@(posedge clk_i) disable iff (!rst_ni) done_q && sat);
  c_full: cover property (@(posedge clk_i) disable iff (!rst_ni) done_q && quo == '1 && Q_SAT != '1);
endmodule
