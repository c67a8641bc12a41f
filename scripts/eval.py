"""make eval: entry point of `python -m msr_eval.cli` (the logic and the options are there)."""
from msr_eval.cli import main

if __name__ == "__main__":
    main()
