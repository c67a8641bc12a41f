import sys

from msr_flow.synth.cli import main

sys.exit(main())
