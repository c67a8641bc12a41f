"""The runs of a report as a declared graph: `plan` lists them as `Job`s (what each calls,
with which arguments, after which other runs) and `run_graph` runs them, a few at a time, each
once its dependencies are done; a run that needs a failed one is reported with that failure,
not run."""
from __future__ import annotations

from concurrent.futures import FIRST_COMPLETED, ThreadPoolExecutor, wait
from dataclasses import dataclass
from typing import Callable

from .config import ECP5_SEED_TIMEOUT_S, ECP5_TARGET_MHZ, ECP5_UNITS, ENGINE, SRAM_HINT, TOP
from .ecp5 import ecp5, ecp5_place
from .yosys import ecp5_cut, ecp5_netlist, ecp5_stitch, generic


@dataclass(frozen=True)
class Job:
    """One Yosys or nextpnr run of the report. It runs as `fn(*results of deps, *args)` once
    every job named in `deps` is done, and its result is filed under `key`: ("generic",
    (module, kind)), ("net", name) for a mapped netlist, ("ecp5", name) for a placed row."""

    key: tuple
    fn: Callable
    args: tuple = ()
    deps: tuple = ()


def plan(args, files: list[str], mods: list[str], engine_params: dict, sram: str, seeds: tuple) -> list[Job]:
    """Every run that the options (`args`, as `parser()` parses them) ask for, in the order
    they start when ready: the long chain (engine and glue netlists, then the flat top's place
    and route) first."""
    mhz = getattr(args, "target_mhz", ECP5_TARGET_MHZ)
    top_flat = TOP in mods and not args.no_top_ecp5 and not args.glue_only
    jobs = []
    if not args.no_ecp5:
        if ENGINE in mods or top_flat:
            jobs.append(Job(("net", ENGINE), ecp5_netlist, (files, ENGINE, engine_params, None, f"{ENGINE}_ecp5")))
        if TOP in mods:
            jobs.append(Job(("net", f"{TOP}_glue"), ecp5_netlist, (files, TOP, None, ENGINE, f"{TOP}_glue_ecp5")))
        if top_flat:
            jobs.append(Job(("net", TOP), ecp5_stitch, (f"{TOP}_ecp5",), (("net", f"{TOP}_glue"), ("net", ENGINE))))
            for seed in seeds:
                jobs.append(Job(("ecp5", f"{TOP}@{seed}"), ecp5_place,
                                (f"{TOP}_ecp5" + ("" if seed == seeds[0] else f"_s{seed}"), seed, True,
                                 ECP5_SEED_TIMEOUT_S, mhz),
                                (("net", TOP),)))
        if ENGINE in mods:
            jobs.append(Job(("ecp5", ENGINE), ecp5_place, (f"{ENGINE}_ecp5", 1, False, None, mhz), (("net", ENGINE),)))
        if TOP in mods:
            jobs.append(Job(("net", f"{TOP}_glue_cut"), ecp5_cut, (f"{TOP}_glue_cut",), (("net", f"{TOP}_glue"),)))
            jobs.append(Job(("ecp5", f"{TOP}_glue"), ecp5_place, (f"{TOP}_glue_ecp5", 1, False, None, mhz),
                            (("net", f"{TOP}_glue_cut"),)))
        jobs += [Job(("ecp5", m), ecp5, (files, m, None, mhz)) for m in mods
                 if m in ECP5_UNITS or (args.modules and m not in (TOP, ENGINE))]
    if ENGINE in mods or (TOP in mods and not args.glue_only):
        jobs += [Job(("generic", (ENGINE, "inferred")), generic, (files, ENGINE, None, False, engine_params)),
                 Job(("generic", (ENGINE, "black box")), generic, (files, ENGINE, sram, False, engine_params))]
    if TOP in mods:
        jobs.append(Job(("generic", (TOP, "glue")), generic, (files, TOP, ENGINE, False, None, f"{TOP}_glue")))
    jobs += [Job(("generic", (m, "inferred")), generic, (files, m, None, SRAM_HINT in m))
             for m in mods if m not in (ENGINE, TOP)]
    return jobs


def run_graph(jobs: list[Job], workers: int, bar=None) -> tuple[dict, list[str]]:
    """Run the jobs, at most `workers` at once. A job starts when its dependencies are done;
    among the ready jobs the one listed first goes first. A RuntimeError of a job is its result
    ({"error": ...}) and a failure; a job that needs a failed one does not run, its result says
    which failure it needed (and so on down the graph); a dependency no job provides is a
    failure of the job that names it. `bar` (tqdm) counts the jobs. Returns (results by key,
    failures)."""
    results, failures = {}, []
    pending = list(jobs)
    with ThreadPoolExecutor(max_workers=workers) as pool:
        running = {}
        while pending or running:
            for job in [j for j in pending if all(d in results for d in j.deps)]:
                if len(running) >= workers:
                    break
                pending.remove(job)
                dep_results = [results[d] for d in job.deps]
                bad = [r for r in dep_results if isinstance(r, dict) and "error" in r]
                if bad:
                    results[job.key] = {"error": f"needs a run that failed: {bad[0]['error']}"}
                    if bar is not None:
                        bar.update()
                    continue
                running[pool.submit(job.fn, *dep_results, *job.args)] = job.key
            if not running:
                if pending:   # dependencies that no run provides: a bug in the plan
                    for job in pending:
                        results[job.key] = {"error": "a dependency was never scheduled"}
                        failures.append(f"{job.key[0]} {job.key[1]}: a dependency was never scheduled")
                    pending.clear()
                continue
            done, _ = wait(running, return_when=FIRST_COMPLETED)
            for fut in done:
                key = running.pop(fut)
                try:
                    results[key] = fut.result()
                except RuntimeError as e:
                    results[key] = {"error": str(e)}
                    failures.append(str(e))
                if bar is not None:
                    what = key[1]
                    bar.set_postfix_str(f"{key[0]} {what if isinstance(what, str) else ' '.join(what)} done")
                    bar.update()
    return results, failures
