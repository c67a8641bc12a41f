"""make sim: entry point of `python -m msr_flow.sim` (the logic and the options are there)."""
import sys

from msr_flow.sim import main

if __name__ == "__main__":
    sys.exit(main())
