// Reference model of an in-order queue, for the formal harnesses of msr_fifo and msr_spill_reg
// (formal/fifo, formal/spill_reg; the spill register is a queue of DEPTH 2): the words held,
// counted from the handshakes (one bit wider than DEPTH needs, so a wrap would show), and one
// word chosen by the solver (track_i on its push): its value and how many words are ahead of
// it. clear_i empties it, as the unit's flush or clear does. Formal only (FORMAL, make formal).
module msr_fv_queue_ref #(
  parameter int unsigned  WIDTH = 4,
  parameter int unsigned  DEPTH = 4,
  localparam int unsigned PTR_W = $clog2(DEPTH)
) (
  input  logic             clk_i,
  input  logic             rst_ni,
  input  logic             clear_i,
  input  logic             push_i,
  input  logic             pop_i,
  input  logic             track_i,     // on a push: track this word
  input  logic [WIDTH-1:0] data_i,
  output logic [PTR_W+1:0] ref_o,       // words held
  output logic             trk_o,       // the tracked word is inside
  output logic [WIDTH-1:0] trk_data_o,  // its value
  output logic [PTR_W:0]   trk_pos_o    // words ahead of it
);
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni)      ref_o <= '0;
    else if (clear_i) ref_o <= '0;
    else              ref_o <= ref_o + push_i - pop_i;
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      trk_o <= 1'b0; trk_data_o <= '0; trk_pos_o <= '0;
    end else if (clear_i) begin
      trk_o <= 1'b0;
    end else if (!trk_o) begin
      if (push_i && track_i) begin
        trk_o      <= 1'b1;
        trk_data_o <= data_i;
        trk_pos_o  <= (PTR_W+1)'(ref_o) - (PTR_W+1)'(pop_i);
      end
    end else if (pop_i) begin
      if (trk_pos_o == '0) trk_o <= 1'b0;      // the tracked word left
      else trk_pos_o <= trk_pos_o - 1'b1;
    end
  end
endmodule
