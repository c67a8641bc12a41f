// AXI signal groups of the protocol checkers (rtl/checkers), written once: the checkers' port
// lists, their binds (rtl/checkers/msr_checker_binds.sv) and the formal harnesses that drive
// or watch them (formal/checkers, formal/regs, formal/fb_writer) all expand these macros, so a
// channel's signals, widths and names are listed in one place.
//
// Include it as `include "msr_chk_axi.svh"`: the flows find it through their
// rtl/prim include folder (+incdir+rtl/prim of rtl/msr.f; the .sby files copy rtl/prim and
// rtl/checkers headers to prim/ and checkers/ and read with -I prim).
//
// Names are the AXI names in lower case without a prefix (awaddr, wvalid, ...), as the
// checkers' ports are named.
//   `MSR_AXIL_PORTS(M, S, ADDR_W, DATA_W)          AXI4-Lite AW, W, B, AR, R
//   `MSR_AXI4_W_PORTS(M, S, ADDR_W, DATA_W, ID_W)  AXI4 AW, W, B
// declare the ports of a port list (no trailing comma): M is the direction of what the master
// drives, S of what the slave drives (input, input for a passive checker; input, output for a
// harness that plays the master of a slave under test; output, input for one that watches a
// master under test).
//   `MSR_AXIL_PORTS_P(P, ...), `MSR_AXI4_AW_PORTS_P(P, ...) (and _WD_, _B_): the same with
// the names prefixed by P (the accelerator's own ports, rtl/top/msr_axi_ports.svh).
//   `MSR_AXIL_CONN(P, X)  `MSR_AXI4_W_CONN(P, X) (and _AW_, _WD_, _B_ per channel)
// connect an instance's ports PORT<name> to the signals SIG<name> (either prefix may be empty:
// `MSR_AXIL_CONN(, s_axil_) binds a checker to a slave's s_axil_* ports).
`ifndef MSR_CHK_AXI_SVH
`define MSR_CHK_AXI_SVH

`define MSR_AXIL_PORTS_P(P, M, S, ADDR_W, DATA_W) \
  M logic [ADDR_W-1:0] P``awaddr, P``araddr, M logic [2:0] P``awprot, P``arprot, \
  M logic [DATA_W-1:0] P``wdata, M logic [DATA_W/8-1:0] P``wstrb, \
  M logic P``awvalid, P``wvalid, P``bready, P``arvalid, P``rready, \
  S logic [DATA_W-1:0] P``rdata, S logic [1:0] P``bresp, P``rresp, \
  S logic P``awready, P``wready, P``bvalid, P``arready, P``rvalid

`define MSR_AXIL_PORTS(M, S, ADDR_W, DATA_W) `MSR_AXIL_PORTS_P(, M, S, ADDR_W, DATA_W)

// One signal, and one channel's VALID/READY pair (CH: aw, w, b, ar, r).
`define MSR_AXI_SIG(P, X, N) .P``N(X``N)
`define MSR_AXI_VR(P, X, CH) .P``CH``valid(X``CH``valid), .P``CH``ready(X``CH``ready)

`define MSR_AXIL_CONN(P, X) \
  `MSR_AXI_VR(P, X, aw), `MSR_AXI_VR(P, X, w), `MSR_AXI_VR(P, X, b), \
  `MSR_AXI_VR(P, X, ar), `MSR_AXI_VR(P, X, r), `MSR_AXI_SIG(P, X, awaddr), \
  `MSR_AXI_SIG(P, X, awprot), `MSR_AXI_SIG(P, X, wdata), `MSR_AXI_SIG(P, X, wstrb), \
  `MSR_AXI_SIG(P, X, bresp), `MSR_AXI_SIG(P, X, araddr), `MSR_AXI_SIG(P, X, arprot), \
  `MSR_AXI_SIG(P, X, rdata), `MSR_AXI_SIG(P, X, rresp)

// The AXI4 write channels one by one (the frame-buffer writer's AW side carries AW and B, its
// W side W), then together.
`define MSR_AXI4_AW_PORTS_P(P, M, S, ADDR_W, ID_W) \
  M logic [ID_W-1:0] P``awid, M logic [ADDR_W-1:0] P``awaddr, M logic [7:0] P``awlen, \
  M logic [2:0] P``awsize, P``awprot, M logic [1:0] P``awburst, M logic [3:0] P``awcache, \
  M logic P``awlock, P``awvalid, S logic P``awready

`define MSR_AXI4_WD_PORTS_P(P, M, S, DATA_W) \
  M logic [DATA_W-1:0] P``wdata, M logic [DATA_W/8-1:0] P``wstrb, \
  M logic P``wlast, P``wvalid, S logic P``wready

`define MSR_AXI4_B_PORTS_P(P, M, S, ID_W) \
  S logic [ID_W-1:0] P``bid, S logic [1:0] P``bresp, S logic P``bvalid, M logic P``bready

`define MSR_AXI4_W_PORTS(M, S, ADDR_W, DATA_W, ID_W) \
  `MSR_AXI4_AW_PORTS_P(, M, S, ADDR_W, ID_W), `MSR_AXI4_WD_PORTS_P(, M, S, DATA_W), \
  `MSR_AXI4_B_PORTS_P(, M, S, ID_W)

`define MSR_AXI4_AW_CONN(P, X) \
  `MSR_AXI_VR(P, X, aw), `MSR_AXI_SIG(P, X, awid), `MSR_AXI_SIG(P, X, awaddr), \
  `MSR_AXI_SIG(P, X, awlen), `MSR_AXI_SIG(P, X, awsize), `MSR_AXI_SIG(P, X, awburst), \
  `MSR_AXI_SIG(P, X, awlock), `MSR_AXI_SIG(P, X, awcache), `MSR_AXI_SIG(P, X, awprot)

`define MSR_AXI4_WD_CONN(P, X) \
  `MSR_AXI_VR(P, X, w), `MSR_AXI_SIG(P, X, wdata), `MSR_AXI_SIG(P, X, wstrb), \
  `MSR_AXI_SIG(P, X, wlast)

`define MSR_AXI4_B_CONN(P, X) \
  `MSR_AXI_VR(P, X, b), `MSR_AXI_SIG(P, X, bid), `MSR_AXI_SIG(P, X, bresp)

`define MSR_AXI4_W_CONN(P, X) \
  `MSR_AXI4_AW_CONN(P, X), `MSR_AXI4_WD_CONN(P, X), `MSR_AXI4_B_CONN(P, X)

// One rule of a checker: the labelled assertion NAME on bit I of the checker's masked
// violations chk, off while `MSR_CHK_OFF, printing MSG (an $error argument list in parentheses).
`define MSR_CHK_RULE(NAME, I, MSG) \
  NAME: assert property (@(posedge clk_i) disable iff (`MSR_CHK_OFF) !chk[I]) else $error MSG;

`endif  // MSR_CHK_AXI_SVH
