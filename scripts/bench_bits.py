"""make bench-bits: tile-buffer bits against throughput: entry point of `python -m msr_flow.bench.bits` (the logic and the options are there)."""
import sys

from msr_flow.bench.bits import main

if __name__ == "__main__":
    sys.exit(main())
