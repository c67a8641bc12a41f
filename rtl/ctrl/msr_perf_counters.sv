// Performance counters of the accelerator (registers PERF_*): cycles, traced pixels per
// level (entry 0 = initial samples), interpolated pixels per level, render-stall cycles (a
// request offered and not taken) and memory-stall cycles (some engine offered a finished pixel
// the writer could not take). Up to NUM_ENGINES pixels are counted per clock. Each engine's
// handshake and source code are registered as they arrive, then counted per kind into a second
// register, then added into saturating counters (msr_sat_counter), so the pixel counters sit
// three clocks behind the events (the cycle and stall counters two). The unit also holds
// the read-back registers of every count the register block shows, these and the
// controller's error counts (err_i), one clock old.
`include "msr_assert.svh"
`include "msr_flops.svh"

module msr_perf_counters import msr_pkg::*; import msr_sys_pkg::*; #(
  parameter int unsigned NUM_ENGINES = 4,
  localparam int unsigned N_W = $clog2(NUM_ENGINES + 1)
) (
  input  logic                   clk_i,        // clock
  input  logic                   rst_ni,       // asynchronous reset, active low
  input  logic                   clear_i,      // synchronous: counters to 0 (START, soft reset)
  input  logic                   en_i,         // a frame runs: count
  input  logic [NUM_ENGINES-1:0] pix_hs_i,     // a finished pixel went to the writer
  input  src_t [NUM_ENGINES-1:0] pix_src_i,    // its source code
  input  logic                   rstall_i,     // a render request waits
  input  logic                   mstall_i,     // a finished pixel waits for the writer
  input  err_counts_t            err_i,        // the controller's error counts
  output readback_t              readback_o    // every count, registered (one clock old)
);
  logic [31:0]      cycles, rstall, mstall;
  logic [3:0][31:0] traced;                    // [k]: traced at level k (0: initial samples)
  logic [2:0][31:0] interp;                    // [k-1]: interpolated at level k
  logic [3:0][N_W-1:0] n_traced_d, n_traced_q;
  logic [2:0][N_W-1:0] n_interp_d, n_interp_q;
  logic                en_q, rstall_q, mstall_q;
  logic [NUM_ENGINES-1:0] hs_q;
  src_t [NUM_ENGINES-1:0] src_q;

  // Each engine's handshake (counted only while a frame runs) and its source code, registered
  // by the writer's inputs: the per-kind counts below then start at flip-flops, not at the
  // handshakes' wires and the controller's state decode (those wires into this sum, 9 LUT
  // levels, were the default top's worst path on ECP5).
  `MSR_CLR_REG(u_hs_q, NUM_ENGINES * (1 + $bits(src_t)), clear_i, 1'b1,
               {pix_hs_i & {NUM_ENGINES{en_i}}, pix_src_i}, {hs_q, src_q})

  // Pixels taken a clock ago, per kind: codes 0..3 traced at level k, 17..19 interpolated;
  // none outside a frame.
  always_comb begin
    n_traced_d = '0;
    n_interp_d = '0;
    for (int unsigned i = 0; i < NUM_ENGINES; i++) begin
      if (hs_q[i]) begin
        if (src_q[i][4]) n_interp_d[src_q[i][1:0] - 2'd1] += 1'b1;
        else             n_traced_d[src_q[i][1:0]] += 1'b1;
      end
    end
  end

  `MSR_CLR_REG(u_events, 7 * N_W + 3, clear_i, 1'b1,
               {n_traced_d, n_interp_d, en_i, en_i && rstall_i, en_i && mstall_i},
               {n_traced_q, n_interp_q, en_q, rstall_q, mstall_q})

  msr_sat_counter #(.WIDTH(32), .INC_W(1)) u_cycles (
    .clk_i (clk_i), .rst_ni (rst_ni), .clear_i (clear_i), .en_i (en_q), .inc_i (1'b1),
    .count_o (cycles)
  );
  msr_sat_counter #(.WIDTH(32), .INC_W(1)) u_rstall (
    .clk_i (clk_i), .rst_ni (rst_ni), .clear_i (clear_i), .en_i (rstall_q), .inc_i (1'b1),
    .count_o (rstall)
  );
  msr_sat_counter #(.WIDTH(32), .INC_W(1)) u_mstall (
    .clk_i (clk_i), .rst_ni (rst_ni), .clear_i (clear_i), .en_i (mstall_q), .inc_i (1'b1),
    .count_o (mstall)
  );
  for (genvar k = 0; k < 4; k++) begin : g_traced
    msr_sat_counter #(.WIDTH(32), .INC_W(N_W)) u_cnt (
      .clk_i (clk_i), .rst_ni (rst_ni), .clear_i (clear_i), .en_i (1'b1),
      .inc_i (n_traced_q[k]), .count_o (traced[k])
    );
  end
  for (genvar k = 0; k < 3; k++) begin : g_interp
    msr_sat_counter #(.WIDTH(32), .INC_W(N_W)) u_cnt (
      .clk_i (clk_i), .rst_ni (rst_ni), .clear_i (clear_i), .en_i (1'b1),
      .inc_i (n_interp_q[k]), .count_o (interp[k])
    );
  end

  // Read-back registers: the register block's read multiplexer then selects among flip-flops
  // placed next to it, not among counters spread over the die (the address decode's fan-out
  // to them and back set the glue's clock). A read returns a count one clock old; the status
  // bits (BUSY, DONE, ...) are not delayed, so a frame's counts are final when DONE reads 1.
  `MSR_CLR_REG(u_readback_q, $bits(readback_t), 1'b0, 1'b1,
               readback_t'{cycles: cycles, traced: traced, interp: interp, rstall: rstall,
                           mstall: mstall, err: err_i},
               readback_o)

endmodule : msr_perf_counters
