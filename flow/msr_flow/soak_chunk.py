"""One chunk of make soak (msr_flow.soak starts it in a session of its own): the cocotb test
test_soak of tb/msr_top on one parameter set for --seconds of frames, with the seed of SEED.
Writes {"result": "pass" | "fail", "error": ...} to --result; the caller reads it."""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from .filelist import ROOT
from .soak import BUILDS


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--build", type=int, required=True, choices=range(len(BUILDS)))
    ap.add_argument("--seconds", required=True, help="SOAK_SECONDS of the test")
    ap.add_argument("--frames-log", type=Path, required=True)
    ap.add_argument("--result", type=Path, required=True)
    args = ap.parse_args(argv)
    from .runner import checked_sources, run_cocotb

    e, o, c, w = BUILDS[args.build]
    result, err = "pass", ""
    try:
        # the protocol checkers bound in, and tb/msr_top's build of the same parameters (_chk)
        run_cocotb("msr_top", "test_msr_top", ROOT / "tb" / "msr_top",
                   {"NUM_ENGINES": e, "MAX_OUTSTANDING": o, "NUM_CTX": c, "AXI_DATA_W": w},
                   f"e{e}_o{o}_c{c}_w{w}_chk", sources=checked_sources(), testcase="test_soak",
                   extra_env={"NUM_ENGINES": e, "SOAK_SECONDS": args.seconds, "MSR_SOAK_LOG": args.frames_log})
    except Exception as ex:          # a failing test, or the simulator stopped by an SVA
        result, err = "fail", str(ex)
    args.result.write_text(json.dumps({"result": result, "error": err}) + "\n")
    return 0 if result == "pass" else 1


if __name__ == "__main__":
    sys.exit(main())
