"""make waves-shot: a screenshot of the GTKWave view: entry point of `python -m msr_flow.waves_shot` (the logic and the options are there)."""
import sys

from msr_flow.waves_shot import main

if __name__ == "__main__":
    sys.exit(main())
