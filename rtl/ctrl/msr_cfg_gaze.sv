// The configuration controller's gaze check (algorithm.md section 1, docs/regs.md GAZE): with
// GAZE.EN, a point outside the frame is refused (code 16), and the gaze in half tiles,
// cx = (2X + T/2) >> log2 T (likewise cy), is formed from the sampled registers while the
// checks run, for the configuration latched at the accept.
module msr_cfg_gaze import msr_pkg::*; import msr_sys_pkg::*; (
  input  logic       clk_i,       // clock
  input  logic       rst_ni,      // asynchronous reset, active low
  input  gaze_raw_t  gaze_i,      // the sampled registers: GAZE, ...
  input  dim_t       width_i,     // ... W, H
  input  dim_t       height_i,
  input  logic [5:0] tile_i,      // ... and T as written
  input  logic       check_i,     // the checks run (CHECK)
  input  logic       decide_i,    // this CHECK clock registers the field checks' verdicts
  output logic       err_o,       // GAZE.EN and the point outside the frame (code 16)
  output half_t      cx_o,        // the gaze in half tiles, settled during CHECK
  output half_t      cy_o
);
  logic  gaze_chk_q;
  half_t gaze_cx_q, gaze_cy_q;

  // The gaze in half tiles: (2p + T/2) >> log2 T = (p + T/4) >> (log2 T - 1). Only a frame
  // with a good tile size and the point inside the frame (p < 4096) uses it: at most 1024.
  function automatic half_t half_pos(logic [12:0] p, logic [5:0] tile);
    logic [13:0] v;
    v = {1'b0, p} + 14'(tile[5:2]);
    return (tile == 6'd8) ? half_t'(v >> 2) : (tile == 6'd32) ? half_t'(v >> 4) : half_t'(v >> 3);
  endfunction

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      gaze_chk_q <= 1'b0;
      gaze_cx_q  <= '0;
      gaze_cy_q  <= '0;
    end else begin
      if (decide_i) begin
        gaze_chk_q <= gaze_i.en &&
                      (gaze_i.x >= width_i || gaze_i.y >= height_i);
      end
      if (check_i) begin
        gaze_cx_q  <= half_pos(gaze_i.x, tile_i);
        gaze_cy_q  <= half_pos(gaze_i.y, tile_i);
      end
    end
  end

  assign err_o = gaze_chk_q;
  assign cx_o  = gaze_cx_q;
  assign cy_o  = gaze_cy_q;

endmodule : msr_cfg_gaze
