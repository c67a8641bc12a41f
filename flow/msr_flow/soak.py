"""make soak: random configurations and frames through msr_top until a time limit.

Runs the cocotb test `test_soak` of tb/msr_top (random frames, back-pressure, render latency,
soft resets mid-frame; every frame bit-exact with the golden model) in chunks of at most
--chunk seconds. Each chunk is a new simulation with its own seed (SEED, random unless given:
then the first chunk uses it), a random initial state (+verilator+rand+reset+2) and one of the
two parameter sets of tb/msr_top, alternating. Logs into build/soak/: soak.jsonl (one line per
chunk: seed, build, frames, result, seconds) and frames.jsonl (one line per checked frame with
its configuration). A failure prints its seed and the command that replays it, exit status 1.
Each chunk runs in a child process of its own session (msr_flow.soak_chunk) with a hard limit
of its seconds plus CHUNK_GRACE_S (the Verilator build, the test's wind-down): a hung
simulation ends the soak as a failure, its simulator and build jobs with it.

    python scripts/soak.py --minutes 1 [--seed N] [--chunk 300]"""
from __future__ import annotations

import argparse
import json
import os
import random
import sys
import time
from pathlib import Path

from . import proc
from .filelist import ROOT

# The two builds of tb/msr_top (NUM_ENGINES, MAX_OUTSTANDING, NUM_CTX, AXI_DATA_W).
BUILDS = [(4, 16, 8, 256), (3, 4, 3, 64)]
BUILD_OVERHEAD_S = 45      # a chunk shorter than this is not worth starting
CHUNK_GRACE_S = 900        # a cold build of msr_top on two cores, and the test's wind-down


def run_chunk(bi: int, secs: float, frames_log: Path, result_file: Path, seed: int) -> tuple[str, str]:
    """One chunk in a child session: ("pass", "") or ("fail", why). The hard limit ends the
    child and every process it started (simulator, compiler)."""
    result_file.unlink(missing_ok=True)
    cmd = [sys.executable, "-m", "msr_flow.soak_chunk", "--build", str(bi), "--seconds", f"{secs:.0f}",
           "--frames-log", str(frames_log), "--result", str(result_file)]
    limit = secs + CHUNK_GRACE_S
    done = proc.run(cmd, cwd=ROOT, timeout=limit, env={**os.environ, "SEED": str(seed)}, capture=False)
    if done.timed_out:
        return "fail", f"TIMEOUT: the chunk ran past {limit:.0f} s; it was ended with everything it started"
    if result_file.exists():
        rec = json.loads(result_file.read_text())
        return rec["result"], rec["error"]
    return "fail", f"the chunk exited with status {done.returncode} and no result"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--minutes", type=float, default=float(os.environ.get("SOAK_MINUTES", "10")))
    ap.add_argument("--seed", type=int, default=int(os.environ["SEED"]) if os.environ.get("SEED") else None)
    ap.add_argument("--chunk", type=float, default=300.0, help="seconds of frames per simulation")
    ap.add_argument("--build", type=int, default=0, choices=range(len(BUILDS)),
                    help="parameter set of the first chunk (index into BUILDS)")
    ap.add_argument("--out", type=Path, default=ROOT / "build" / "soak")
    args = ap.parse_args(argv)

    args.out.mkdir(parents=True, exist_ok=True)
    frames_log = args.out / "frames.jsonl"
    chunk_log = args.out / "soak.jsonl"
    os.environ["MSR_RAND_RESET"] = "1"
    os.environ.setdefault("MSR_FUNCOV_FILE", str(args.out / "func.jsonl"))
    t_end = time.monotonic() + 60.0 * args.minutes
    sysrand = random.SystemRandom()
    total = chunks = 0
    k = 0
    # At least one chunk, however short the limit (a soak that runs nothing proves nothing).
    while chunks == 0 or time.monotonic() + BUILD_OVERHEAD_S < t_end:
        seed = args.seed if (k == 0 and args.seed is not None) else sysrand.randrange(1, 2**31)
        bi = (args.build + k) % len(BUILDS)
        e, o, c, w = BUILDS[bi]
        k += 1
        secs = max(5.0, min(args.chunk, t_end - time.monotonic() - 15.0))
        before = sum(1 for _ in open(frames_log)) if frames_log.exists() else 0
        t0 = time.monotonic()
        result, err = run_chunk(bi, secs, frames_log, args.out / "chunk_result.json", seed)
        after = sum(1 for _ in open(frames_log)) if frames_log.exists() else 0
        n = after - before
        total += n
        chunks += 1
        rec = {"seed": seed, "build": f"e{e}_o{o}_c{c}_w{w}", "frames": n, "result": result,
               "seconds": round(time.monotonic() - t0, 1), "rand_reset": 2, "time": time.strftime("%F %T")}
        with open(chunk_log, "a") as fh:
            fh.write(json.dumps(rec) + "\n")
        print(f"soak: chunk {chunks} seed {seed} build {rec['build']}: {n} frames, {result} ({rec['seconds']} s)",
              flush=True)
        if result != "pass":
            # the frames follow from the seed alone, so a run at least as long replays the failure
            print(f"soak: FAILED with SEED={seed} on {rec['build']}; replay: python scripts/soak.py "
                  f"--seed {seed} --build {bi} --chunk {secs:.0f} --minutes {(secs + BUILD_OVERHEAD_S + 60) / 60:.1f}"
                  f"\n{err}", flush=True)
            return 1
        if n == 0:
            print(f"soak: chunk with seed {seed} checked no frame", flush=True)
            return 1
    print(f"soak: passed: {total} frames in {chunks} chunks, log {chunk_log}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
