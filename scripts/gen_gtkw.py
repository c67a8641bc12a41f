"""GTKWave save file for a make sim WAVES=1 dump: entry point of `python -m msr_flow.waves` (the logic and the options are there)."""
import sys

from msr_flow.waves import main

if __name__ == "__main__":
    sys.exit(main())
