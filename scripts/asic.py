"""make asic's entry point: the standard-cell flow (OSU 0.18 um cells with Yosys, OpenSTA, the
gate-level netlist, docs/asic.md) is the package msr_flow.asic (flow/msr_flow/asic/), and
`python -m msr_flow.asic` is the same command.

    python scripts/asic.py [--modules a,b] [--period-ns 5.0] [--netlist-only] [--doc-only]
"""
import sys

from msr_flow.asic import main

if __name__ == "__main__":
    sys.exit(main())
