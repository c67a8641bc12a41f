// Synchronous FIFO with a fill count, in the manner of common_cells' fifo_v3: first-word
// fall-through, one push and one pop per cycle (a push into a full FIFO waits for ready_o even
// when a pop happens in the same cycle, so ready_o is a register compare), synchronous flush.
// Storage is a plain array without reset so a hand-off can map it to a register file or SRAM.
// OUT_REG = 1 keeps the oldest entry in a register of its own (data_o from a flip-flop, not
// from the array's read multiplexer): on a pop it loads the next entry, read at a registered
// address, or the word pushed in the same clock when that is the only one left.
`include "msr_assert.svh"

module msr_fifo #(
  parameter int unsigned WIDTH = 8,    // bits per entry
  parameter int unsigned DEPTH = 4,    // entries, a power of two >= 2
  parameter bit          OUT_REG = 1'b0 // data_o from a register (see above)
) (
  input  logic             clk_i,      // clock
  input  logic             rst_ni,     // asynchronous reset, active low
  input  logic             flush_i,    // synchronous clear: drop every entry
  input  logic             valid_i,    // push request
  output logic             ready_o,    // not full
  input  logic [WIDTH-1:0] data_i,     // pushed entry
  output logic             valid_o,    // not empty
  input  logic             ready_i,    // pop request
  output logic [WIDTH-1:0] data_o,     // oldest entry
  output logic [$clog2(DEPTH):0] count_o  // entries held
);
  localparam int unsigned PTR_W = $clog2(DEPTH);

  if (DEPTH < 2 || (1 << PTR_W) != DEPTH) begin : gen_bad_depth
    $fatal(1, "msr_fifo: DEPTH must be a power of two >= 2, got %0d", DEPTH);
  end

  logic [WIDTH-1:0] mem_q [DEPTH];
  logic [PTR_W-1:0] wptr_q, rptr_q;
  logic [PTR_W:0]   count_q, count_d;
  logic             push, pop;
  // "not empty" and "not full" as flip-flops, registered from the next count: the handshake
  // flags leave the FIFO without the compare of the count behind them (a FIFO's flags are
  // what the logic on both sides waits for, often across the die).
  logic             nonempty_q, notfull_q;

  assign count_d = count_q + {{PTR_W{1'b0}}, push} - {{PTR_W{1'b0}}, pop};

  // The flags' next values are count_d compares, written without count_d: the compares of
  // count_q are ready early, and the late push / pop (which the logic around the FIFO decides)
  // pass through one gate instead of the count adder and a compare behind it. Same values
  // (a_flags; formal/fifo proves them).
  logic cnt_is1, cnt_ge2, cnt_lt_dm1, cnt_is_dm1;
  logic nonempty_d, notfull_d;
  assign cnt_is1    = (count_q == (PTR_W+1)'(1));
  assign cnt_ge2    = (count_q >= (PTR_W+1)'(2));
  assign cnt_lt_dm1 = (count_q < (PTR_W+1)'(DEPTH - 1));
  assign cnt_is_dm1 = (count_q == (PTR_W+1)'(DEPTH - 1));
  assign nonempty_d = push || cnt_ge2 || (cnt_is1 && !pop);
  assign notfull_d  = pop || cnt_lt_dm1 || (cnt_is_dm1 && !push);
  assign ready_o = notfull_q;
  assign valid_o = nonempty_q;
  assign push    = valid_i && ready_o;
  assign pop     = valid_o && ready_i;
  assign count_o = count_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      wptr_q     <= '0;
      rptr_q     <= '0;
      count_q    <= '0;
      nonempty_q <= 1'b0;
      notfull_q  <= 1'b1;
    end else if (flush_i) begin
      wptr_q     <= '0;
      rptr_q     <= '0;
      count_q    <= '0;
      nonempty_q <= 1'b0;
      notfull_q  <= 1'b1;
    end else begin
      if (push) wptr_q <= wptr_q + 1'b1;
      if (pop)  rptr_q <= rptr_q + 1'b1;
      count_q    <= count_d;
      nonempty_q <= nonempty_d;
      notfull_q  <= notfull_d;
    end
  end

  // The array has no reset (memory); it is written only on a push.
  always_ff @(posedge clk_i) begin
    if (push) mem_q[wptr_q] <= data_i;
  end

  if (OUT_REG) begin : g_out_reg
    // many_q: two entries or more, so the entry after the head is in the array.
    logic             many_q;
    logic [PTR_W-1:0] rnext_q;     // rptr_q + 1
    logic [WIDTH-1:0] head_q;
    logic             many_d;    // count_d > 1, as the flags above
    assign many_d = (count_q >= (PTR_W+1)'(3)) || (count_q == (PTR_W+1)'(2) && (push || !pop)) ||
                    (cnt_is1 && push && !pop);

    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        many_q  <= 1'b0;
        rnext_q <= PTR_W'(1);
      end else if (flush_i) begin
        many_q  <= 1'b0;
        rnext_q <= PTR_W'(1);
      end else begin
        many_q  <= many_d;
        if (pop) rnext_q <= rnext_q + 1'b1;
      end
    end

    always_ff @(posedge clk_i) begin
      if (pop && many_q) begin
        head_q <= mem_q[rnext_q];
      end else if (push && (pop || !nonempty_q)) begin
        head_q <= data_i;
      end
    end

    assign data_o = head_q;

    /* verilator lint_off SYNCASYNCNET */
    `MSR_ASSERT_IMP(a_head, nonempty_q, head_q == mem_q[rptr_q])
    `MSR_ASSERT(a_many, many_q == (count_q > (PTR_W+1)'(1)) && rnext_q == rptr_q + 1'b1)
    /* verilator lint_on SYNCASYNCNET */
  end else begin : g_out_mux
    assign data_o = mem_q[rptr_q];
  end

  /* verilator lint_off SYNCASYNCNET */
  `MSR_ASSERT(a_count_range, count_q <= DEPTH[PTR_W:0])
  `MSR_ASSERT(a_flags, nonempty_q == (count_q != '0) && notfull_q == (count_q != DEPTH[PTR_W:0]))
  /* verilator lint_on SYNCASYNCNET */

endmodule : msr_fifo
