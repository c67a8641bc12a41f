"""Switching activity from a value-change dump: per signal bit the number of toggles and the
time spent at 1, over the whole dump (an FST is read through GTKWave's fst2vcd)."""
from __future__ import annotations

import re
import shutil
import subprocess
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Iterable


@dataclass
class Var:
    path: str                 # scope.name, array brackets as [i]
    msb: int
    lsb: int
    width: int


@dataclass
class Activity:
    """Toggles and high time per bit of every selected signal, over `span` time units."""
    span: int = 0
    toggles: dict[str, list[int]] = field(default_factory=dict)     # path -> per bit, lsb first
    high: dict[str, list[int]] = field(default_factory=dict)
    vars: dict[str, Var] = field(default_factory=dict)

    def bit(self, path: str, i: int | None) -> tuple[int, float] | None:
        """(toggles, duty) of one bit (i=None: a scalar, or bit 0), None when not traced."""
        v = self.vars.get(path)
        if v is None:
            return None
        j = 0 if i is None else (i - v.lsb if v.msb >= v.lsb else v.lsb - i)
        if not 0 <= j < v.width:
            return None
        return self.toggles[path][j], self.high[path][j] / self.span if self.span else 0.0


def norm(name: str) -> str:
    """A signal name as the mapped netlist spells it: no escapes, array indexes in [ ]."""
    name = name.lstrip("\\").replace("(", "[").replace(")", "]")
    return re.sub(r"\s+", "", name)


def vcd_lines(path: Path) -> Iterable[str]:
    """The lines of a VCD, or of an FST converted on the fly by fst2vcd."""
    if path.suffix == ".fst":
        tool = shutil.which("fst2vcd")
        if tool is None:
            raise RuntimeError("fst2vcd (Debian gtkwave) is not on PATH")
        proc = subprocess.Popen([tool, "-f", str(path)], stdout=subprocess.PIPE, text=True, bufsize=1 << 20)
        assert proc.stdout is not None
        yield from proc.stdout
        if proc.wait() != 0:
            raise RuntimeError(f"fst2vcd {path} failed (exit {proc.returncode})")
    else:
        with open(path) as fh:
            yield from fh


def read_activity(lines: Iterable[str], want: Callable[[str], bool] = lambda p: True) -> Activity:
    """Count toggles and high time of every variable whose path `want` accepts. x and z read as 0."""
    act = Activity()
    scope: list[str] = []
    ids: dict[str, list[str]] = {}
    it = iter(lines)
    for line in it:
        s = line.strip()
        if s.startswith("$scope"):
            scope.append(norm(s.split()[2]))
        elif s.startswith("$upscope"):
            scope.pop()
        elif s.startswith("$var"):
            parts = s.split()
            width, code, name = int(parts[2]), parts[3], parts[4]
            rng = parts[5] if len(parts) > 6 and parts[5].startswith("[") else ""
            while name.count("[") > name.count("]"):
                name += parts[5]
            m = re.fullmatch(r"\[(\d+)(?::(\d+))?\]", rng)
            msb, lsb = (int(m.group(1)), int(m.group(2) if m.group(2) is not None else m.group(1))) if m \
                else (width - 1, 0)
            path = ".".join(scope + [norm(name)])
            if want(path) and path not in act.vars:
                act.vars[path] = Var(path, msb, lsb, width)
                ids.setdefault(code, []).append(path)
        elif s.startswith("$enddefinitions"):
            break
    # state per id code: [value, time of the last change (None before the first value), toggles, high time]
    state = {c: [0, None, [0] * act.vars[ps[0]].width, [0] * act.vars[ps[0]].width] for c, ps in ids.items()}
    t, t0 = 0, None
    for line in it:
        if not line or line[0] in "$\n":
            continue
        c0 = line[0]
        if c0 == "#":
            t = int(line[1:])
            if t0 is None:
                t0 = t
            continue
        if c0 in "01xzXZ":
            val, code = (1 if c0 == "1" else 0), line[1:].strip()
        elif c0 in "bB":
            raw, code = line[1:].split()
            try:
                val = int(raw, 2)
            except ValueError:
                val = int("".join(ch if ch in "01" else "0" for ch in raw), 2)
        else:
            continue          # real values
        st = state.get(code)
        if st is None:
            continue
        if st[1] is None:        # the initial value is no toggle
            st[0], st[1] = val, t
            continue
        old = st[0]
        if old:
            dt, high, v = t - st[1], st[3], old
            while v:
                low = v & -v
                high[low.bit_length() - 1] += dt
                v ^= low
        diff = old ^ val
        if diff:
            tog = st[2]
            while diff:
                low = diff & -diff
                tog[low.bit_length() - 1] += 1
                diff ^= low
        st[0], st[1] = val, t
    for st in state.values():        # the time since the last change
        v = st[0] if st[1] is not None else 0
        while v:
            low = v & -v
            st[3][low.bit_length() - 1] += t - st[1]
            v ^= low
    act.span = t - (t0 or 0)
    for code, ps in ids.items():
        for p in ps:
            act.toggles[p], act.high[p] = state[code][2], state[code][3]
    return act
