"""make soak: entry point of `python -m msr_flow.soak` (the logic and the options are there)."""
import sys

from msr_flow.soak import main

if __name__ == "__main__":
    sys.exit(main())
