"""Tile engine throughput (make bench-engine): entry point of `python -m msr_flow.bench.engine` (the logic and the options are there)."""
import sys

from msr_flow.bench.engine import main

if __name__ == "__main__":
    sys.exit(main())
