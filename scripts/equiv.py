"""Formal equivalence of a refactored RTL unit against an older revision: entry point of `python -m msr_flow.equiv` (the logic and the options are there)."""
import sys

from msr_flow.equiv import main

if __name__ == "__main__":
    sys.exit(main())
