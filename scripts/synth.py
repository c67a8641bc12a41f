"""Synthesis reports (make synth): a thin entry point over the package msr_flow.synth
(flow/msr_flow/synth/); `python -m msr_flow.synth` takes the same options.

    python scripts/synth.py [--modules a,b] [--no-ecp5] [--no-top-ecp5] [--jobs N] [--merge] [--render]

The names below are re-exported for the scripts that still import them by this script's name
(scripts/asic.py, tb/gate_level/test_gate_level.py); new code imports msr_flow.synth.
"""
import sys

from msr_flow.synth import (ENGINE, TOP, bb_param_names, default_params, main, modules_in,  # noqa: F401
                            params_text, pixels_per_clock, read_cmd, read_filelist)

if __name__ == "__main__":
    sys.exit(main())
