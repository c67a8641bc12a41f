// Ray budget controller: the operands of the shared multiplier's next product (docs/budget.md
// section 6c). Every product of a frame runs on one bit-serial multiplier (msr_shift_add_mul in
// msr_budget_ctrl); which operands it takes depends only on the state that loads it, so the
// choice is combinational and lives here, beside the controller's state machine.
//
// A check or a start (seq_load_i) loads G = line(W) * line(H) whatever the state; otherwise the
// state's own product (a product done in a chain state starts the next: start G, W * H, g and p
// of the last row, N0, m0; the law's numerator, then its denominator; the row's floor and
// activity; the seed pass's b_k; the new scale's square).
//
// Timing: each operand is one flat AND-OR choice of its sources, a source shared by the
// products that use it. A multiplexer per product and state, nested, was the controller's
// largest part.
module msr_budget_mul_ops import msr_pkg::*; import msr_budget_pkg::*; #(
  localparam int unsigned MC_W = BUD_MC_W,                 // multiplicand
  localparam int unsigned MP_W = BUD_MP_W,                 // multiplier
  localparam int unsigned ST_W = BUD_ST_W                  // its bits, 0..MP_W
) (
  input  budget_state_e    state_i,        // the controller's state
  input  logic             seq_load_i,     // a check or start pulse loads G
  // (whole structs: each product takes a few of their fields)
  /* verilator lint_off UNUSEDSIGNAL */
  input  budget_grid_t     cfg_i,          // the configuration and the grid constants
  input  budget_frame_t    frm_i,          // the frame's constants
  input  budget_law_t      law_i,          // the law's running sums
  /* verilator lint_on UNUSEDSIGNAL */
  input  logic [5:0]       n0_last_i,      // n0 of the last row (registered)
  input  logic [MC_W-1:0]  nn0_i,          // N + N0
  input  logic [17:0]      floor_ex_i,     // the row's activity floor
  input  logic [10:0]      u_row_i,        // the finished row's scale u_j
  input  logic [10:0]      u_new_i,        // the new scale u_{j+2}
  input  logic [27:0]      pass_a_i,       // the seed pass: a'_k ...
  input  logic [10:0]      pass_w_i,       // ... and w(u'_k, u0)
  output budget_mul_op_t   op_o            // the product's operands
);

  always_comb begin
    logic g, seed_law;
    g        = !seq_load_i;                                 // the state machine's product
    seed_law = state_i == ST_LAW && frm_i.seeded;
    op_o.a = (MC_W'(cfg_i.line_w)   & {MC_W{!g || state_i == ST_WH}})
           | (MC_W'(cfg_i.width)    & {MC_W{g && state_i inside {ST_G, ST_GL}}})
           | (MC_W'(frm_i.spare)    & {MC_W{g && state_i == ST_PL}})
           | (MC_W'(frm_i.u0)       & {MC_W{g && (state_i == ST_N0 || seed_law)}})
           | (MC_W'(law_i.pp0)      & {MC_W{g && state_i == ST_NUM}})
           | (nn0_i                 & {MC_W{g && state_i == ST_LAW && !frm_i.seeded}})
           | (MC_W'(floor_ex_i)     & {MC_W{g && state_i == ST_FLR}})
           | (MC_W'(pass_a_i)       & {MC_W{g && state_i == ST_PMUL}})
           | (MC_W'(u_new_i)        & {MC_W{g && state_i == ST_SQ0}});
    // the multiplier left-aligned: n bits at the top
    op_o.b = ({cfg_i.line_h, 12'd0}             & {MP_W{!g}})
           | ({cfg_i.height, 12'd0}             & {MP_W{g && state_i == ST_G}})
           | ({n0_last_i, 19'd0}                & {MP_W{g && state_i == ST_WH}})
           | ({frm_i.h_last, 19'd0}             & {MP_W{g && state_i == ST_GL}})
           | ({frm_i.u0, 14'd0}                 & {MP_W{g && state_i inside {ST_PL, ST_N0}}})
           | (law_i.x_rem[MP_W-1:0]             & {MP_W{g && (state_i == ST_NUM || seed_law)}})
           | (law_i.p_left                      & {MP_W{g && state_i == ST_LAW && !frm_i.seeded}})
           | ({u_row_i, 14'd0}                  & {MP_W{g && state_i == ST_FLR}})
           | ({pass_w_i, 14'd0}                 & {MP_W{g && state_i == ST_PMUL}})
           | ({u_new_i, 14'd0}                  & {MP_W{g && state_i == ST_SQ0}});
    op_o.n = !g                                   ? ST_W'(13) :
             (state_i == ST_G)                    ? ST_W'(13) :
             (state_i inside {ST_WH, ST_GL})      ? ST_W'(6)  :
             (state_i inside {ST_NUM, ST_LAW})    ? ST_W'(MP_W) : ST_W'(11);
  end

endmodule : msr_budget_mul_ops
