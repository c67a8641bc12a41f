"""The frame-budget controller's evaluation: entry point of `python -m msr_eval.budget_eval` (the logic and the options are there)."""
from msr_eval.budget_eval import main

if __name__ == "__main__":
    main()
