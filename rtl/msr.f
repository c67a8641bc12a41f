rtl/msr_pkg.sv
rtl/msr_decide.sv
rtl/msr_interp.sv
