"""Golden-model speed: entry point of `python -m msr_flow.bench.golden` (the logic and the options are there)."""
from msr_flow.bench.golden import main

if __name__ == "__main__":
    main()
