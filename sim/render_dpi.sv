// Rendering unit for the Verilator harness (not synthesizable): answers the accelerator's
// render port by DPI-C calls into the rendering library (sim/msr_dpi.h).
//
// Plusargs: +scene=NAME|FILE (default cornell; a .ppm is answered from the picture),
// +width=W +height=H (the frame, for the camera), +quality=0|1, +rnd_latency=N (cycles from
// request to earliest response, default 1), +rnd_jitter=J (extra 0..J random cycles, and the
// answer is picked at random among the oldest RND_WINDOW requests that are due: reordering).
// A request is traced when it is taken; the colour waits in a queue of DEPTH entries.
// DEPTH_EN: each answer also carries the primary hit's inverse depth (+invz_exp=E, default 0;
// msr_dpi_render_cz), else rsp_invz_o is 0.
module render_dpi import msr_pkg::*; #(
  parameter int unsigned TAG_W      = 6,   // request tag bits
  parameter int unsigned DEPTH      = 64,  // requests held (outstanding) at most
  parameter int unsigned RND_WINDOW = 4,   // reordering window, oldest entries
  parameter bit          DEPTH_EN   = 1'b0 // answer with the inverse depth too
) (
  input  logic             clk_i,        // clock
  input  logic             rst_ni,       // asynchronous reset, active low
  input  logic             req_valid_i,  // render request
  output logic             req_ready_o,  // taken
  input  coord_t           req_x_i,      // pixel x
  input  coord_t           req_y_i,      // pixel y
  input  logic [TAG_W-1:0] req_tag_i,    // tag, echoed in the response
  output logic             rsp_valid_o,  // colour available
  input  logic             rsp_ready_i,  // taken
  output logic [TAG_W-1:0] rsp_tag_o,    // tag of its request
  output rgb_t             rsp_rgb_o,    // colour
  output logic [15:0]      rsp_invz_o    // its inverse depth (DEPTH_EN)
);
  import "DPI-C" function chandle msr_dpi_open(input string scene, input int width, input int height,
                                               input int quality);
  import "DPI-C" function int msr_dpi_render(input chandle ctx, input int x, input int y);
  import "DPI-C" function longint msr_dpi_render_cz(input chandle ctx, input int x, input int y,
                                                   input int invz_exp);
  import "DPI-C" function void msr_dpi_close(input chandle ctx);

  chandle          ctx;
  int unsigned     latency, jitter;
  int              invz_exp;
  longint unsigned now;

  // Queue in arrival order (circular); an entry leaves from the oldest RND_WINDOW.
  logic [TAG_W-1:0] q_tag [DEPTH];
  rgb_t             q_rgb [DEPTH];
  logic [15:0]      q_invz [DEPTH];
  longint unsigned  q_due [DEPTH];
  int unsigned      head, count;
  logic             rsp_valid_q;
  logic [TAG_W-1:0] rsp_tag_q;
  rgb_t             rsp_rgb_q;
  logic [15:0]      rsp_invz_q;

  initial begin
    string scene;
    int    width, height, quality;
    if (!$value$plusargs("scene=%s", scene)) scene = "cornell";
    if (!$value$plusargs("width=%d", width)) width = 320;
    if (!$value$plusargs("height=%d", height)) height = 240;
    if (!$value$plusargs("quality=%d", quality)) quality = 0;
    if (!$value$plusargs("rnd_latency=%d", latency)) latency = 1;
    if (!$value$plusargs("rnd_jitter=%d", jitter)) jitter = 0;
    if (!$value$plusargs("invz_exp=%d", invz_exp)) invz_exp = 0;
    ctx = msr_dpi_open(scene, width, height, quality);
    if (ctx == null) $fatal(1, "render_dpi: cannot open scene %s", scene);
  end

  final msr_dpi_close(ctx);

  assign req_ready_o = (count < DEPTH);
  assign rsp_valid_o = rsp_valid_q;
  assign rsp_tag_o   = rsp_tag_q;
  assign rsp_rgb_o   = rsp_rgb_q;
  assign rsp_invz_o  = rsp_invz_q;

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      head        = 0;
      count       <= 0;
      now         <= 0;
      rsp_valid_q <= 1'b0;
      rsp_tag_q   <= '0;
      rsp_rgb_q   <= '0;
      rsp_invz_q  <= '0;
    end else begin
      int unsigned n, pick, idx, tail, cands;
      n = count;
      // Take a request: trace it now, answer it after the latency.
      if (req_valid_i && req_ready_o) begin
        tail        = (head + n) % DEPTH;
        q_tag[tail] = req_tag_i;
        if (DEPTH_EN) begin
          longint unsigned cz;
          cz           = longint'(msr_dpi_render_cz(ctx, int'(req_x_i), int'(req_y_i), invz_exp));
          q_rgb[tail]  = rgb_t'(cz[23:0]);
          q_invz[tail] = cz[39:24];
        end else begin
          q_rgb[tail]  = rgb_t'(msr_dpi_render(ctx, int'(req_x_i), int'(req_y_i)));
          q_invz[tail] = '0;
        end
        q_due[tail] = now + longint'(latency) + ((jitter != 0) ? longint'($urandom % (jitter + 1)) : 0);
        n++;
      end
      // Present the next response when the port is free.
      if (!rsp_valid_q || rsp_ready_i) begin
        rsp_valid_q <= 1'b0;
        pick  = DEPTH;
        cands = 0;
        for (int unsigned i = 0; i < RND_WINDOW && i < n; i++) begin
          idx = (head + i) % DEPTH;
          if (q_due[idx] <= now) begin
            cands++;
            // Reservoir choice among the due entries (the oldest one without jitter).
            if (pick == DEPTH || (jitter != 0 && $urandom % cands == 0)) pick = idx;
          end
        end
        if (pick != DEPTH) begin
          rsp_valid_q <= 1'b1;
          rsp_tag_q   <= q_tag[pick];
          rsp_rgb_q   <= q_rgb[pick];
          rsp_invz_q  <= q_invz[pick];
          // Remove it: the oldest entry moves into its slot.
          q_tag[pick] = q_tag[head];
          q_rgb[pick] = q_rgb[head];
          q_invz[pick] = q_invz[head];
          q_due[pick] = q_due[head];
          head = (head + 1) % DEPTH;
          n--;
        end
      end
      count <= n;
      now   <= now + 1;
    end
  end
endmodule
