"""Budget laws compared on the scenes' curves: entry point of `python -m msr_eval.budget_lab` (the logic and the options are there)."""
import sys

from msr_eval.budget_lab import main

if __name__ == "__main__":
    sys.exit(main())
