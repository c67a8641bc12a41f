"""`python -m msr_flow.asic`: the standard-cell flow's command line."""
import sys

from .cli import main

sys.exit(main())
