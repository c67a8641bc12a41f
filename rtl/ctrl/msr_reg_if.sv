// The register interface of the accelerator: the AXI4-Lite front end (msr_axil_cpuif) in
// front of the register block generated from rtl/regs/msr_regs.rdl (msr_regs, PeakRDL's
// passthrough CPU interface). Every request reaches the block from a flip-flop of the front
// end, so a write reaches a field through its address compare and enable only (docs/system.md).
// The generated block's field structs (hwif) stay in here: the system sees the registers as
// the typed bundles of msr_sys_pkg (the configuration as written, the control fields, the
// status, the counters' read-back).
`include "msr_axi_ports.svh"
module msr_reg_if
  import msr_sys_pkg::*;
(
  input  logic                         clk_i,     // clock
  input  logic                         rst_ni,    // asynchronous reset, active low
  // the fields, to and from the hardware
  output cfg_raw_t                     raw_o,              // the configuration as written
  output reg_ctrl_t                    ctrl_o,             // CTRL, WATCHDOG, the held flags
  input  reg_status_t                  status_i,           // STATUS
  input  readback_t                    readback_i,         // PERF_*, MEM_ERR*, RSP_DROP
  input  logic [10:0]                  scale_out_i,        // BUDGET_CTRL.SCALE_OUT
  input  logic                         scale_out_valid_i,  // BUDGET_CTRL.SCALE_OUT_VALID
  // AXI4-Lite slave (7-bit byte address)
  `MSR_AXIL_SLAVE_PORTS(7, 32)
);

  msr_regs_pkg::msr_regs__in_t  hwif_in;
  msr_regs_pkg::msr_regs__out_t hwif_out;

  assign raw_o = '{
    width:      hwif_out.FRAME_SIZE.WIDTH.value,
    height:     hwif_out.FRAME_SIZE.HEIGHT.value,
    tile:       hwif_out.CONFIG.TILE.value,
    levels:     hwif_out.CONFIG.LEVELS.value,
    metric:     msr_pkg::metric_e'(hwif_out.CONFIG.METRIC.value),
    rule:       hwif_out.CONFIG.RULE.value,
    thr:        {hwif_out.THRESH.THR3.value, hwif_out.THRESH.THR2.value,
                 hwif_out.THRESH.THR1.value},
    fov_gain:   hwif_out.FOV_GAIN.GAIN.value,
    gaze:       '{en: hwif_out.GAZE.EN.value, x: hwif_out.GAZE.X.value, y: hwif_out.GAZE.Y.value},
    fb:         '{fb_base:    hwif_out.FB_BASE.ADDR.value,
                  fb_stride:  hwif_out.FB_STRIDE.STRIDE.value,
                  src_en:     hwif_out.SRC_CTRL.ENABLE.value,
                  src_base:   hwif_out.SRC_BASE.ADDR.value,
                  src_stride: hwif_out.SRC_STRIDE.STRIDE.value},
    bud:        '{pixels:      hwif_out.BUDGET.PIXELS.value,
                  scale_init:  hwif_out.BUDGET_CTRL.SCALE_INIT.value,
                  prior_shift: hwif_out.BUDGET_CTRL.PRIOR_SHIFT.value,
                  seeded:      hwif_out.BUDGET_CTRL.SEEDED.value}
  };

  assign ctrl_o = '{start:      hwif_out.CTRL.START.value,
                    soft_reset: hwif_out.CTRL.SOFT_RESET.value,
                    irq_en:     hwif_out.CTRL.IRQ_EN.value,
                    irq_flags:  {hwif_out.STATUS.DONE.value, hwif_out.STATUS.CFG_ERR.value,
                                 hwif_out.STATUS.WDOG.value},
                    wdog_limit: hwif_out.WATCHDOG.CYCLES.value};

  assign hwif_in.STATUS.BUSY.next     = status_i.busy;
  assign hwif_in.STATUS.ERROR.next    = status_i.err;
  assign hwif_in.STATUS.DONE.hwset    = status_i.done_set;
  assign hwif_in.STATUS.DONE.hwclr    = status_i.done_clr;
  assign hwif_in.STATUS.CFG_ERR.hwset = status_i.cfg_err_set;
  assign hwif_in.STATUS.CFG_ERR.hwclr = status_i.done_clr;
  assign hwif_in.STATUS.WDOG.hwset    = status_i.wdog_set;
  assign hwif_in.STATUS.WDOG.hwclr    = status_i.done_clr;

  assign hwif_in.PERF_CYCLES.COUNT.next       = readback_i.cycles;
  assign hwif_in.PERF_RENDER_STALL.COUNT.next = readback_i.rstall;
  assign hwif_in.PERF_MEM_STALL.COUNT.next    = readback_i.mstall;
  for (genvar k = 0; k < 4; k++) begin : g_perf_traced
    assign hwif_in.PERF_TRACED[k].COUNT.next = readback_i.traced[k];
  end
  for (genvar k = 0; k < 3; k++) begin : g_perf_interp
    assign hwif_in.PERF_INTERP[k].COUNT.next = readback_i.interp[k];
  end
  assign hwif_in.MEM_ERR.COUNT.next        = readback_i.err.mem_err_cnt;
  assign hwif_in.MEM_ERR.UNEXPECTED_B.next = readback_i.err.b_unexpected;
  assign hwif_in.MEM_ERR_ADDR.ADDR.next    = readback_i.err.mem_err_addr;
  assign hwif_in.RSP_DROP.COUNT.next       = readback_i.err.rsp_drop_cnt;

  assign hwif_in.BUDGET_CTRL.SCALE_OUT.next       = scale_out_i;
  assign hwif_in.BUDGET_CTRL.SCALE_OUT_VALID.next = scale_out_valid_i;

  // The AXI4-Lite front end registers every request before the block decodes it.
  logic                 cpuif_req, cpuif_req_is_wr, cpuif_stall_wr, cpuif_stall_rd;
  logic [6:0]           cpuif_addr;
  logic [31:0]          cpuif_wr_data, cpuif_wr_biten, cpuif_rd_data;
  logic                 cpuif_rd_ack, cpuif_rd_err, cpuif_wr_ack, cpuif_wr_err;

  // verilog_lint: waive-start module-port (the bus ports connect by name, macro last)
  msr_axil_cpuif #(.ADDR_W(7), .DATA_W(32)) u_axil (
    .clk_i, .rst_ni,
    .cpuif_req_o          (cpuif_req),
    .cpuif_req_is_wr_o    (cpuif_req_is_wr),
    .cpuif_addr_o         (cpuif_addr),
    .cpuif_wr_data_o      (cpuif_wr_data),
    .cpuif_wr_biten_o     (cpuif_wr_biten),
    .cpuif_req_stall_wr_i (cpuif_stall_wr),
    .cpuif_req_stall_rd_i (cpuif_stall_rd),
    .cpuif_rd_ack_i       (cpuif_rd_ack),
    .cpuif_rd_err_i       (cpuif_rd_err),
    .cpuif_rd_data_i      (cpuif_rd_data),
    .cpuif_wr_ack_i       (cpuif_wr_ack),
    .cpuif_wr_err_i       (cpuif_wr_err),
    `MSR_AXIL_SLAVE_CONNECT
  );
  // verilog_lint: waive-stop module-port

  msr_regs u_regs (
    .clk                  (clk_i),
    .arst_n               (rst_ni),
    .s_cpuif_req          (cpuif_req),
    .s_cpuif_req_is_wr    (cpuif_req_is_wr),
    .s_cpuif_addr         (cpuif_addr),
    .s_cpuif_wr_data      (cpuif_wr_data),
    .s_cpuif_wr_biten     (cpuif_wr_biten),
    .s_cpuif_req_stall_wr (cpuif_stall_wr),
    .s_cpuif_req_stall_rd (cpuif_stall_rd),
    .s_cpuif_rd_ack       (cpuif_rd_ack),
    .s_cpuif_rd_err       (cpuif_rd_err),
    .s_cpuif_rd_data      (cpuif_rd_data),
    .s_cpuif_wr_ack       (cpuif_wr_ack),
    .s_cpuif_wr_err       (cpuif_wr_err),
    .hwif_in              (hwif_in),
    .hwif_out             (hwif_out)
  );

endmodule : msr_reg_if
