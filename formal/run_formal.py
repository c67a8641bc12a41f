"""make formal: entry point of `python -m msr_flow.formal` (the logic and the options are there)."""
import sys

from msr_flow.formal import main

if __name__ == "__main__":
    sys.exit(main())
