// Ray budget controller, the activity memory's port and the seed pass's registers
// (docs/budget.md sections 4 and 6c; golden model sw_model/msr_model/budget.py, Controller's
// prof_words). msr_budget_ctrl's state machine steps the pass (ST_PRD .. ST_PB, one row's word
// per round) and says when the memory reads and writes; this unit says where and what:
//
//   - outside the pass the address is the row being updated (rows_done) and a write stores
//     that row's {u_j, a_j} (a_j the product of ST_ACT);
//   - in the pass the address is the pass's own row counter k, the read word is the previous
//     frame's {u'_k, a'_k}, the weight w = min(u'_k, u0) is registered from it, and a write
//     stores the product b_k = a'_k * w in its place.
//
// The pass flag is a flip-flop set from the controller's next state, not a decode of its
// present state: the decode into the memory's address (the DP16KD's) was the budget top's
// worst path. a_in_pass checks it is the same value every clock.
`include "msr_assert.svh"

module msr_budget_pass import msr_budget_pkg::*; #(
  parameter int unsigned  MEM_W  = 39,               // {u_j, a_j} (11 + 28 bits) or b_k < 2^38
  parameter int unsigned  ROW_W  = BUD_ROW_W,        // tile row index
  localparam int unsigned DEPTH  = 512               // tile rows (two ECP5 EBRs at 512 x 39)
) (
  input  logic              clk_i,           // clock
  input  logic              rst_ni,          // asynchronous reset, active low
  input  logic              restart_i,       // a clear, check or start overrides the controller
  input  budget_state_e     state_i,         // the controller's state ...
  input  budget_state_e     state_d_i,       // ... and its next state (ignored on restart_i)
  input  logic              mul_done_i,      // the multiplier's product is done
  input  logic [MEM_W-1:0]  mul_prod_i,      // (its low bits: b_k and a_j fit a word)
  input  logic              mem_re_i,        // read the word at the address below
  input  logic              mem_we_i,        // write the word below at the address below
  input  logic [ROW_W-1:0]  rows_done_i,     // the row being updated
  input  logic [10:0]       u_row_i,         // its scale u_j
  input  logic [10:0]       u0_i,            // the frame's seed u0
  input  logic [ROW_W-1:0]  nty_i,           // tile rows of the frame
  output logic              pass_o,          // the seed pass is on
  output logic              pass_last_o,     // its row k is the frame's last
  output logic [MEM_W-1:0]  mem_word_o,      // the word read, two clocks after mem_re_i
  output logic [27:0]       pass_a_o,        // a'_k of the word read
  output logic [10:0]       pass_w_o         // w(u'_k, u0), registered from the word read
);
  logic             in_pass_q;
  logic [ROW_W-1:0] pass_q;                  // the pass's row k
  logic [8:0]       mem_addr;
  logic [MEM_W-1:0] mem_wdata;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      in_pass_q <= 1'b0;
      pass_q    <= '0;
    end else if (restart_i) begin
      in_pass_q <= 1'b0;
    end else begin
      in_pass_q <= state_d_i inside {ST_PRD, ST_PWT, ST_PW, ST_PMUL, ST_PB};
      // the pass starts at row 0 once the start's sequence ends (ST_M0), a word per round
      if (state_i == ST_M0 && mul_done_i) pass_q <= '0;
      if (state_i == ST_PB && mul_done_i) pass_q <= pass_q + ROW_W'(1);
    end
  end

  assign pass_o      = in_pass_q;
  assign pass_last_o = pass_q + ROW_W'(1) == nty_i;
  assign mem_addr    = in_pass_q ? pass_q[8:0] : rows_done_i[8:0];
  assign mem_wdata   = in_pass_q ? mul_prod_i : {u_row_i, 28'(mul_prod_i)};

  msr_budget_mem #(.W(MEM_W), .DEPTH(DEPTH)) u_mem (
    .clk_i,
    .re_i    (mem_re_i),
    .we_i    (mem_we_i),
    .addr_i  (mem_addr),
    .wdata_i (mem_wdata),
    .word_o  (mem_word_o)
  );

  // The word's {u'_k, a'_k}. The weight is registered from the word's register every clock:
  // the word is there from ST_PW on, so w is at ST_PMUL, which loads a'_k * w (a compare into
  // the multiplier's load was the top's worst path).
  logic [10:0] pass_u;
  logic [10:0] pass_w_q;
  assign {pass_u, pass_a_o} = mem_word_o;
  always_ff @(posedge clk_i) begin
    pass_w_q <= (pass_u > u0_i) ? u0_i : pass_u;
  end
  assign pass_w_o = pass_w_q;

  // (rows beyond the memory's depth: the configuration check refuses such a frame)
  logic unused_row;
  assign unused_row = ^rows_done_i[ROW_W-1:9];

  /* verilator lint_off SYNCASYNCNET */
  `MSR_ASSERT(a_in_pass, in_pass_q == (state_i inside {ST_PRD, ST_PWT, ST_PW, ST_PMUL, ST_PB}))
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_budget_pass
