// The flat AXI port lists of the accelerator, from the AXI signal groups of the checkers
// (rtl/checkers/msr_chk_axi.svh) with the bus prefixes: the top keeps flat, prefixed names
// (s_axil_*, m_axi_*) because cocotbext-axi, the Verilator harness and the formal harnesses bind
// to them by name, and every unit on the path declares and connects the same lists through
// these macros (in the manner of the pulp-platform AXI typedef and assign macros). A unit
// passes its own width parameters; a connect macro ties each port to the signal of the same
// name in the instantiating scope. Included through the include folder rtl/prim as
// "../top/msr_axi_ports.svh". A macro ends its list (no trailing comma) and stands last in
// a port or connection list, one to a list: Verible parses a macro call only there.
`ifndef MSR_AXI_PORTS_SVH
`define MSR_AXI_PORTS_SVH
`include "msr_chk_axi.svh"

// AXI4-Lite slave: ADDR_W byte-address bits, DATA_W data bits (AWPROT and ARPROT are ignored).
`define MSR_AXIL_SLAVE_PORTS(ADDR_W, DATA_W) \
  `MSR_AXIL_PORTS_P(s_axil_, input, output, ADDR_W, DATA_W)
`define MSR_AXIL_SLAVE_CONNECT `MSR_AXIL_CONN(s_axil_, s_axil_)

// AXI4 write master (32-bit addresses): AW and B (the writer's AW side), W, and all of it.
`define MSR_AXI_AWB_MASTER_PORTS(ID_W) \
  `MSR_AXI4_AW_PORTS_P(m_axi_, output, input, 32, ID_W), \
  `MSR_AXI4_B_PORTS_P(m_axi_, output, input, ID_W)
`define MSR_AXI_W_MASTER_PORTS(DATA_W) `MSR_AXI4_WD_PORTS_P(m_axi_, output, input, DATA_W)
`define MSR_AXI_WR_MASTER_PORTS(ID_W, DATA_W) \
  `MSR_AXI_AWB_MASTER_PORTS(ID_W), `MSR_AXI_W_MASTER_PORTS(DATA_W)

// The accelerator's two buses: the register slave and the frame-buffer write master.
`define MSR_TOP_BUS_PORTS(ID_W, DATA_W) \
  `MSR_AXIL_SLAVE_PORTS(7, 32), \
  `MSR_AXI_WR_MASTER_PORTS(ID_W, DATA_W)

`define MSR_AXI_AWB_CONNECT `MSR_AXI4_AW_CONN(m_axi_, m_axi_), `MSR_AXI4_B_CONN(m_axi_, m_axi_)
`define MSR_AXI_W_CONNECT `MSR_AXI4_WD_CONN(m_axi_, m_axi_)
`define MSR_AXI_WR_CONNECT `MSR_AXI4_W_CONN(m_axi_, m_axi_)

`endif // MSR_AXI_PORTS_SVH
