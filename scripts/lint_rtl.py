"""make lint: entry point of `python -m msr_flow.lint` (the logic and the options are there)."""
import sys

from msr_flow.lint import main

if __name__ == "__main__":
    sys.exit(main())
