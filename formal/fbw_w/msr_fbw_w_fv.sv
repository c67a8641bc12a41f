// Formal harness of msr_fbw_w, the frame-buffer writer's W side: two inputs, a 32-bit bus. The
// bursts pushed are free except that, within one run, their length, first buffer beat, first
// and last byte and plane are constants the solver picks (so the harness knows what each beat
// must carry); the row buffers answer every read with the address read (the beat's pixel lane
// carries it, the code lane too, in the four codes' bits). Checks, on every W beat taken: WLAST
// exactly on beat AWLEN+1; the data read from the burst's buffer address plus the beat index,
// formatted for its plane; the strobes (from the first byte on the first beat, to the last byte
// on the last); W held, unchanged, until taken; no more bursts closed than pushed and no more
// buffers freed than row-last bursts pushed. Bounded: beats of a run are few.
module msr_fbw_w_fv import msr_fbw_pkg::*; #(
  localparam int unsigned DW   = 32,
  localparam int unsigned MA_W = $clog2(NBUF * pix_beats(DW / 32)),
  localparam int unsigned BB_W = $clog2(DW / 8)
) (
  input logic            clk_i, rst_ni,
  input logic            wb_push_i,
  input logic            in_i, row_last_i,       // the burst's input and row-last mark (free)
  input buf_t            buf_i,
  input logic [1:0]      len_i,                  // these four: constants of the run
  input logic [MA_W-1:0] mbase_i,
  input logic [BB_W-1:0] lo_i, hi_i,
  input logic            src_i,
  input logic            wready_i
);
  typedef struct packed {
    logic [7:0]        len;
    logic              in;
    buf_t              bufi;
    logic              src;
    logic [MA_W-1:0]   mbase;
    logic [BB_W-1:0]   lo;
    logic [BB_W-1:0]   hi;
    logic              row_last;
  } wburst_t;
  wburst_t               wb;
  logic                  room, rd_in, free_valid, free_in, wlast, wvalid, idle;
  buf_t                  free_buf;
  logic [1:0][MA_W-1:0]  raddr;
  logic [31:0]           wdata;
  logic [3:0]            wstrb;
  logic [6:0]            ra;
  assign wb = '{len: 8'(len_i), in: in_i, bufi: buf_i, src: src_i, mbase: mbase_i, lo: lo_i, hi: hi_i,
                row_last: row_last_i};
  assign ra = 7'(raddr[rd_in]);

  msr_fbw_w #(.NUM_IN(2), .AXI_DATA_W(DW), .wburst_t(wburst_t)) dut (
    .clk_i, .rst_ni, .clear_i (1'b0),
    .wb_push_i, .wb_room_o (room), .wb_i (wb),
    .raddr_o (raddr), .rd_in_o (rd_in), .rd_pix_i ({17'b0, ra}), .rd_code_i (20'(ra)),
    .free_valid_o (free_valid), .free_in_o (free_in), .free_buf_o (free_buf),
    .m_axi_wdata (wdata), .m_axi_wstrb (wstrb), .m_axi_wlast (wlast), .m_axi_wvalid (wvalid),
    .m_axi_wready (wready_i), .idle_o (idle)
  );

  logic init_q;
  msr_fv_init #(.ONCE(1'b1)) u_init (.clk_i, .rst_ni, .init_o(init_q));

  // The run's constants, and a push only with room (msr_fbw_aw's AWVALID waits for it).
  logic [1:0]      len_q;
  logic [MA_W-1:0] mbase_q;
  logic [BB_W-1:0] lo_q, hi_q;
  logic            src_q;
  always_ff @(posedge clk_i) begin
    len_q <= len_i; mbase_q <= mbase_i; lo_q <= lo_i; hi_q <= hi_i; src_q <= src_i;
  end
  always_comb begin
    assume (!wb_push_i || room);
    if (!init_q) assume (len_i == len_q && mbase_i == mbase_q && lo_i == lo_q && hi_i == hi_q
                         && src_i == src_q);
    assume (len_i != 2'd0 || lo_i <= hi_i);      // a one-beat burst writes lo..hi
  end

  // The beat index of the burst going out; bursts pushed and closed; row-last bursts and frees.
  wire       w_hs = wvalid && wready_i;
  logic [1:0] k_q;
  logic [4:0] pushed_q, closed_q, rl_q, freed_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      k_q <= '0; pushed_q <= '0; closed_q <= '0; rl_q <= '0; freed_q <= '0;
    end else begin
      if (w_hs) k_q <= wlast ? '0 : k_q + 1'b1;
      pushed_q <= pushed_q + 5'(wb_push_i);
      closed_q <= closed_q + 5'(w_hs && wlast);
      rl_q     <= rl_q + 5'(wb_push_i && row_last_i);
      freed_q  <= freed_q + 5'(free_valid);
    end
  end
  logic [6:0] want;
  assign want = 7'(mbase_q) + 7'(k_q);
  logic [3:0] strb;
  always_comb begin
    for (int unsigned b = 0; b < 4; b++) begin
      strb[b] = (k_q != '0 || b >= 32'(lo_q)) && (k_q != len_q || b <= 32'(hi_q));
    end
  end

  logic w_viol;
  msr_chk_stable #(.W(37)) u_w_hold (
    .clk_i, .rst_ni, .valid_i(wvalid), .ready_i(wready_i), .payload_i({wdata, wstrb, wlast}),
    .viol_o(w_viol)
  );

  a_wlast:  assert property (@(posedge clk_i) disable iff (!rst_ni) !w_hs || wlast == (k_q == len_q));
  a_data:   assert property (@(posedge clk_i) disable iff (!rst_ni)
                             !w_hs || (src_q ? {wdata[9:8], wdata[4:0]} == want && wdata[7:5] == '0
                                             : wdata[6:0] == want && wdata[31:24] == '0));
  a_strb:   assert property (@(posedge clk_i) disable iff (!rst_ni) !w_hs || wstrb == strb);
  a_w_hold: assert property (@(posedge clk_i) disable iff (!rst_ni) !w_viol);
  a_closed: assert property (@(posedge clk_i) disable iff (!rst_ni) closed_q <= pushed_q);
  a_freed:  assert property (@(posedge clk_i) disable iff (!rst_ni) freed_q <= rl_q);
  a_idle:   assert property (@(posedge clk_i) disable iff (!rst_ni) !idle || closed_q == pushed_q);

  // Non-vacuity: a three-beat burst closed while the next waits; a buffer freed.
  c_burst3: cover property (@(posedge clk_i) disable iff (!rst_ni) w_hs && wlast && len_q == 2'd2 && !idle);
  c_free:   cover property (@(posedge clk_i) disable iff (!rst_ni) free_valid && closed_q == 5'd2);
endmodule
