"""make power: entry point of `python -m msr_flow.power` (the logic and the options are there)."""
import sys

from msr_flow.power.cli import main

if __name__ == "__main__":
    sys.exit(main())
