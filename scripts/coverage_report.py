"""make coverage, second half: build/coverage/summary.json and report.md: entry point of `python -m msr_flow.coverage` (the logic and the options are there)."""
import sys

from msr_flow.coverage import main

if __name__ == "__main__":
    sys.exit(main())
