"""Python constants from the SystemRDL register map: entry point of `python -m msr_flow.regs_gen` (the logic and the options are there)."""
import sys

from msr_flow.regs_gen import main

if __name__ == "__main__":
    sys.exit(main())
