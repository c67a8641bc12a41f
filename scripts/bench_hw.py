"""make bench: the hardware benchmark: entry point of `python -m msr_flow.bench.hw` (the logic and the options are there)."""
import sys

from msr_flow.bench.hw import main

if __name__ == "__main__":
    sys.exit(main())
