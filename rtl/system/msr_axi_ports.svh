// The flat AXI port lists of the accelerator, written once: the top keeps flat, prefixed names
// (s_axil_*, m_axi_*) because cocotbext-axi, the Verilator harness and the formal harnesses bind
// to them by name, and every unit on the path declares and connects the same lists through
// these macros (in the manner of the pulp-platform AXI typedef and assign macros). A unit
// passes its own width parameters; a connect macro ties each port to the signal of the same
// name in the instantiating scope. Included through the include folder rtl/prim as
// "../system/msr_axi_ports.svh". A macro ends its list (no trailing comma) and stands last in
// a port or connection list, one to a list: Verible parses a macro call only there.
`ifndef MSR_AXI_PORTS_SVH
`define MSR_AXI_PORTS_SVH

// AXI4-Lite slave: ADDR_W byte-address bits, DATA_W data bits (AWPROT and ARPROT are ignored).
`define MSR_AXIL_SLAVE_PORTS(ADDR_W, DATA_W) \
  input  logic                s_axil_awvalid, \
  output logic                s_axil_awready, \
  input  logic [(ADDR_W)-1:0] s_axil_awaddr, \
  input  logic [2:0]          s_axil_awprot, \
  input  logic                s_axil_wvalid, \
  output logic                s_axil_wready, \
  input  logic [(DATA_W)-1:0] s_axil_wdata, \
  input  logic [(DATA_W)/8-1:0] s_axil_wstrb, \
  output logic                s_axil_bvalid, \
  input  logic                s_axil_bready, \
  output logic [1:0]          s_axil_bresp, \
  input  logic                s_axil_arvalid, \
  output logic                s_axil_arready, \
  input  logic [(ADDR_W)-1:0] s_axil_araddr, \
  input  logic [2:0]          s_axil_arprot, \
  output logic                s_axil_rvalid, \
  input  logic                s_axil_rready, \
  output logic [(DATA_W)-1:0] s_axil_rdata, \
  output logic [1:0]          s_axil_rresp

`define MSR_AXIL_SLAVE_CONNECT \
  .s_axil_awvalid, .s_axil_awready, .s_axil_awaddr, .s_axil_awprot, \
  .s_axil_wvalid, .s_axil_wready, .s_axil_wdata, .s_axil_wstrb, \
  .s_axil_bvalid, .s_axil_bready, .s_axil_bresp, \
  .s_axil_arvalid, .s_axil_arready, .s_axil_araddr, .s_axil_arprot, \
  .s_axil_rvalid, .s_axil_rready, .s_axil_rdata, .s_axil_rresp

// AXI4 write master, address channel (32-bit addresses, ID_W ID bits).
`define MSR_AXI_AW_MASTER_PORTS(ID_W) \
  output logic [(ID_W)-1:0]   m_axi_awid, \
  output logic [31:0]         m_axi_awaddr, \
  output logic [7:0]          m_axi_awlen, \
  output logic [2:0]          m_axi_awsize, \
  output logic [1:0]          m_axi_awburst, \
  output logic                m_axi_awlock, \
  output logic [3:0]          m_axi_awcache, \
  output logic [2:0]          m_axi_awprot, \
  output logic                m_axi_awvalid, \
  input  logic                m_axi_awready

// AXI4 write master, data channel (DATA_W data bits).
`define MSR_AXI_W_MASTER_PORTS(DATA_W) \
  output logic [(DATA_W)-1:0]   m_axi_wdata, \
  output logic [(DATA_W)/8-1:0] m_axi_wstrb, \
  output logic                  m_axi_wlast, \
  output logic                  m_axi_wvalid, \
  input  logic                  m_axi_wready

// AXI4 write master, response channel.
`define MSR_AXI_B_MASTER_PORTS(ID_W) \
  input  logic [(ID_W)-1:0]   m_axi_bid, \
  input  logic [1:0]          m_axi_bresp, \
  input  logic                m_axi_bvalid, \
  output logic                m_axi_bready

// The AXI4 write master's address and response channels (the writer's AW side).
`define MSR_AXI_AWB_MASTER_PORTS(ID_W) \
  `MSR_AXI_AW_MASTER_PORTS(ID_W), \
  `MSR_AXI_B_MASTER_PORTS(ID_W)

// The whole AXI4 write master (no read channels).
`define MSR_AXI_WR_MASTER_PORTS(ID_W, DATA_W) \
  `MSR_AXI_AWB_MASTER_PORTS(ID_W), \
  `MSR_AXI_W_MASTER_PORTS(DATA_W)

// The accelerator's two buses: the register slave and the frame-buffer write master.
`define MSR_TOP_BUS_PORTS(ID_W, DATA_W) \
  `MSR_AXIL_SLAVE_PORTS(7, 32), \
  `MSR_AXI_WR_MASTER_PORTS(ID_W, DATA_W)

`define MSR_AXI_AW_CONNECT \
  .m_axi_awid, .m_axi_awaddr, .m_axi_awlen, .m_axi_awsize, .m_axi_awburst, .m_axi_awlock, \
  .m_axi_awcache, .m_axi_awprot, .m_axi_awvalid, .m_axi_awready

`define MSR_AXI_W_CONNECT \
  .m_axi_wdata, .m_axi_wstrb, .m_axi_wlast, .m_axi_wvalid, .m_axi_wready

`define MSR_AXI_B_CONNECT \
  .m_axi_bid, .m_axi_bresp, .m_axi_bvalid, .m_axi_bready

`define MSR_AXI_AWB_CONNECT \
  `MSR_AXI_AW_CONNECT, `MSR_AXI_B_CONNECT

`define MSR_AXI_WR_CONNECT \
  `MSR_AXI_AWB_CONNECT, `MSR_AXI_W_CONNECT

`endif // MSR_AXI_PORTS_SVH
