// A B over two register stages, sized for an FPGA's 18 x 18 multipliers: the partial products of
// 17-bit pieces (zero-extended; a signed A's top piece keeps its sign) registered on en_i[0],
// their sum on en_i[1]. Written as one *, synthesis joins the multipliers' outputs with adders
// in the same clock, and a 38 x 25 product then limits the clock (ECP5: 64 MHz).
module msr_pipe_mul #(
  parameter int unsigned A_W      = 18,          // A bits
  parameter int unsigned B_W      = 18,          // B bits, unsigned
  parameter bit          A_SIGNED = 1'b0,        // A is two's complement
  parameter bit          NEGATE   = 1'b0,        // p_o = -A B (the sum subtracts each piece)
  parameter int unsigned P_W      = A_W + B_W    // product bits kept (the low ones)
) (
  input  logic           clk_i,                  // clock
  input  logic [1:0]     en_i,                   // load: [0] the partial products, [1] the sum
  input  logic [A_W-1:0] a_i,                    // A
  input  logic [B_W-1:0] b_i,                    // B
  output logic [P_W-1:0] p_o                     // A B mod 2^P_W two clocks after a_i, b_i
);

  localparam int unsigned PC_W = 17;                         // piece bits
  localparam int unsigned NA   = (A_W + PC_W - 1) / PC_W;    // pieces of A
  localparam int unsigned NB   = (B_W + PC_W - 1) / PC_W;    // pieces of B
  localparam int unsigned PP_W = 2 * (PC_W + 1);             // 18 x 18 signed

  logic [NA*PC_W-1:0]    a_ext;
  logic [NB*PC_W-1:0]    b_ext;
  logic [NA-1:0][PC_W:0] pa;      // 18-bit signed pieces
  logic [NB-1:0][PC_W:0] pb;

  if (A_SIGNED) begin : g_sext
    assign a_ext = (NA * PC_W)'($signed(a_i));
  end else begin : g_zext
    assign a_ext = (NA * PC_W)'(a_i);
  end
  assign b_ext = (NB * PC_W)'(b_i);

  for (genvar i = 0; i < NA; i++) begin : g_pa
    assign pa[i] = {A_SIGNED && i == NA - 1 && a_ext[(i + 1) * PC_W - 1], a_ext[i*PC_W +: PC_W]};
  end
  for (genvar j = 0; j < NB; j++) begin : g_pb
    assign pb[j] = {1'b0, b_ext[j*PC_W +: PC_W]};
  end

  /* verilator lint_off UNUSEDSIGNAL */
  logic [NA-1:0][NB-1:0][PP_W-1:0] pp_q;   // an unsigned piece's product fits LO_W bits
  /* verilator lint_on UNUSEDSIGNAL */

  always_ff @(posedge clk_i) begin
    if (en_i[0]) begin
      for (int i = 0; i < NA; i++) begin
        for (int j = 0; j < NB; j++) begin
          pp_q[i][j] <= PP_W'($signed(pa[i])) * PP_W'($signed(pb[j]));
        end
      end
    end
  end

  // The sum without a long chain of adders: the products of B's piece j and A's pieces i, i + 2,
  // i + 4 .. sit 34 bits apart and each but a signed top piece's is below 2^34, so they share one
  // row, side by side (their OR is wiring); the 2 NB rows are then summed in pairs.
  localparam int unsigned LO_W = 2 * PC_W;

  logic [NB-1:0][1:0][P_W-1:0] row;
  logic [NB-1:0][P_W-1:0]      pair;
  logic [P_W-1:0]              sum;

  always_comb begin
    row = '0;
    for (int i = 0; i < NA; i++) begin
      for (int j = 0; j < NB; j++) begin
        if (A_SIGNED && i == NA - 1) begin
          // sign-extended
          row[j][i%2] = row[j][i%2]
                        | (P_W'({{P_W{pp_q[i][j][PP_W-1]}}, pp_q[i][j]}) << (PC_W * (i + j)));
        end else begin
          row[j][i%2] = row[j][i%2] | (P_W'(pp_q[i][j][LO_W-1:0]) << (PC_W * (i + j)));
        end
      end
    end
    sum = '0;
    for (int j = 0; j < NB; j++) begin
      pair[j] = NEGATE ? -row[j][0] - row[j][1] : row[j][0] + row[j][1];
      sum     = sum + pair[j];
    end
  end

  always_ff @(posedge clk_i) begin
    if (en_i[1]) begin
      p_o <= sum;
    end
  end

endmodule : msr_pipe_mul
