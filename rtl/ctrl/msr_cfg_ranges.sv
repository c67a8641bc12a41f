// The configuration controller's plane-range check (docs/regs.md, codes 9, 10 and 11): the byte
// range of each plane, end = base + (H-1)*stride + row bytes (0 the frame buffer, 1 the source
// plane), as a shift-and-add over 12 CHECK clocks into a 48-bit accumulator in 8-bit segments (a
// carry goes one segment per clock; 6 more clocks settle it), so a plane that wraps past 4 GiB is
// seen (wraps_o from step STEP_CMP); then whether the two ranges [base, end) overlap, compared
// segment by segment from the least significant one (overlap_o from step STEP_END).
module msr_cfg_ranges import msr_pkg::*; import msr_sys_pkg::*; #(
  parameter int unsigned STEP_CMP = 20,       // the first compare step (the ends settled)
  parameter int unsigned STEP_END = 26        // the step after the last compare
) (
  input  logic       clk_i,                   // clock
  input  logic       rst_ni,                  // asynchronous reset, active low
  input  fb_cfg_t    fb_i,                    // the sampled registers: the planes, ...
  input  dim_t       width_i,                 // ... W, H
  input  dim_t       height_i,
  input  logic       sample_i,                // the registers are sampled (SAMPLE)
  input  logic       check_i,                 // the checks run (CHECK) ...
  input  logic [4:0] step_i,                  // ... at this step
  output logic [1:0] wraps_o,                 // the frame buffer's, the source plane's end > 2^32
  output logic       overlap_o                // the two planes' ranges overlap
);
  localparam int unsigned ACC_W = 48;         // (H-1)*stride + base + row < 2^45
  localparam int unsigned NSEG  = ACC_W / 8;
  // steps 0..11 shift-and-add, 12 base, 13 row bytes, 14..19 carries settle
  localparam int unsigned STEP_H = 12, STEP_BASE = 12, STEP_ROW = 13;

  logic [1:0][ACC_W-1:0]  sh_q;        // stride << step
  logic [11:0]            hm1_q;       // H-1, shifted right each step
  logic [1:0][ACC_W-1:0]  acc_q;       // accumulated value (segments)
  logic [1:0][NSEG-1:0]   cy_q;        // carry pending into segment k
  logic [1:0]             lt_q;        // fb_base < src_end, src_base < fb_end (so far)
  logic [1:0][ACC_W-1:0]  addend;
  logic [1:0][ACC_W-1:0]  acc_d;
  logic [1:0][NSEG-1:0]   cy_d;
  logic [1:0]             lt_d;
  logic [4:0]             cmp_seg;     // segment compared this step
  assign cmp_seg = step_i - STEP_CMP[4:0];

  always_comb begin
    for (int unsigned p = 0; p < 2; p++) begin
      addend[p] = '0;
      if (step_i < STEP_H[4:0]) begin
        addend[p] = hm1_q[0] ? sh_q[p] : '0;
      end else if (step_i == STEP_BASE[4:0]) begin
        addend[p] = ACC_W'((p != 0) ? fb_i.src_base : fb_i.fb_base);
      end else if (step_i == STEP_ROW[4:0]) begin
        addend[p] = (p != 0) ? ACC_W'(width_i) : ACC_W'({width_i, 2'b0});
      end
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      sh_q  <= '0;
      hm1_q <= '0;
      acc_q <= '0;
      cy_q  <= '0;
      lt_q  <= '0;
    end else if (sample_i) begin
      sh_q  <= {ACC_W'(fb_i.src_stride), ACC_W'(fb_i.fb_stride)};
      hm1_q <= 12'(height_i - 1'b1);
      acc_q <= '0;
      cy_q  <= '0;
      lt_q  <= '0;
    end else if (check_i) begin
      sh_q  <= {sh_q[1] << 1, sh_q[0] << 1};
      hm1_q <= hm1_q >> 1;
      acc_q <= acc_d;
      cy_q  <= cy_d;
      // ranges overlap iff fb_base < src_end and src_base < fb_end: compared from segment 0 up
      if (step_i >= STEP_CMP[4:0] && step_i < STEP_END[4:0]) lt_q <= lt_d;
    end
  end

  // The accumulators: segment 0 takes no carry, the top segment's carry out is dropped.
  for (genvar p = 0; p < 2; p++) begin : g_acc
    logic [NSEG-1:0] co;
    msr_seg_add #(.WIDTH(ACC_W), .SEG_W(8)) u_add (
      .a_i (acc_q[p]),
      .b_i (addend[p]),
      .c_i (cy_q[p] & ~NSEG'(1)),
      .s_o (acc_d[p]),
      .c_o (co)
    );
    assign cy_d[p] = NSEG'({co, 1'b0});
  end

  always_comb begin
    for (int unsigned p = 0; p < 2; p++) begin
      logic [7:0] a, b;
      a       = 8'(ACC_W'((p != 0) ? fb_i.src_base : fb_i.fb_base) >> (8 * cmp_seg));
      b       = 8'(acc_q[1-p] >> (8 * cmp_seg));
      lt_d[p] = (a < b) || (a == b && lt_q[p]);
    end
  end

  // Wraps past 4 GiB: end > 2^32 (the end is exclusive).
  function automatic logic wraps(logic [ACC_W-1:0] e);
    return e[ACC_W-1:32] != '0 && !(e[ACC_W-1:32] == (ACC_W-32)'(1) && e[31:0] == '0);
  endfunction

  assign wraps_o[0] = wraps(acc_q[0]);
  assign wraps_o[1] = fb_i.src_en && wraps(acc_q[1]);
  assign overlap_o  = fb_i.src_en && lt_q[0] && lt_q[1];

endmodule : msr_cfg_ranges
