"""Build and run library of the accelerator: filelist (rtl/msr.f), runner (cocotb on
Verilator), harness (the Verilator frame harness), regs (register constants, generated) and the
implementation flows."""
