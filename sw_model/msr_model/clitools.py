"""What every command line of the project shares: one error type, one exit-code convention,
argument converters, output-path checks and all-or-nothing writing of the outputs.

Exit status: 0 done, 1 the run itself failed (for `make sim`: not bit exact, or the RTL
simulation failed), 2 bad input (arguments, unreadable or unsuitable files, output paths).
Either way the last line printed says which, in one line on stderr:

    <prog>: error: <what was wrong with the input>        (status 2)
    <prog>: failed: <what went wrong in the run>          (status 1)
"""
from __future__ import annotations

import argparse
import os
import sys
import tempfile
from pathlib import Path
from typing import Callable, Iterable

from .spec import SpecError

EXIT_OK = 0
EXIT_FAILED = 1
EXIT_BAD_INPUT = 2


class UsageError(SpecError):
    """Bad input: an argument, an input file or an output path. Exit status 2."""


class RunFailed(Exception):
    """The inputs were fine but the run failed or gave a wrong result. Exit status 1."""


class Parser(argparse.ArgumentParser):
    """argparse, but every error is a UsageError (one line, exit status 2)."""

    def error(self, message):  # noqa: D401
        raise UsageError(message)


def one_line(e: BaseException) -> str:
    text = str(e.args[0]) if e.args else repr(e)
    return " ".join(text.split()) or type(e).__name__


def run_main(prog: str, fn: Callable[[], int], unexpected_is_failure: bool = False) -> int:
    """Call fn(); turn the two kinds of failure into their line on stderr and exit status.
    With `unexpected_is_failure`, any other exception prints its traceback and then the
    "failed" line (exit status 1), so the last line still says what happened."""
    try:
        return fn()
    except SpecError as e:            # UsageError included
        print(f"{prog}: error: {one_line(e)}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except RunFailed as e:
        print(f"{prog}: failed: {one_line(e)}", file=sys.stderr)
        return EXIT_FAILED
    except Exception as e:  # noqa: BLE001
        if not unexpected_is_failure:
            raise
        import traceback
        traceback.print_exc()
        print(f"{prog}: failed: {type(e).__name__}: {one_line(e)}", file=sys.stderr)
        return EXIT_FAILED


# --- argument converters (raise UsageError; usable as argparse types) -------------------------

def int_in(text, what: str, lo: int, hi: int) -> int:
    try:
        v = int(str(text).strip(), 0)
    except ValueError:
        raise UsageError(f"{what} must be an integer, got {text!r}") from None
    if not lo <= v <= hi:
        raise UsageError(f"{what} {v} outside {lo}..{hi}")
    return v


def int_list(text, what: str, lo: int | None = None, hi: int | None = None) -> tuple[int, ...]:
    """A comma-separated list of integers (each in lo..hi when given), at least one."""
    parts = str(text).split(",")
    try:
        vals = tuple(int(p.strip(), 0) for p in parts)
    except ValueError:
        raise UsageError(f"{what} must be a comma-separated list of integers, got {text!r}") from None
    for v in vals:
        if (lo is not None and v < lo) or (hi is not None and v > hi):
            raise UsageError(f"{what}: {v} outside {lo}..{hi}")
    return vals



def gaze_of(text, what: str, width: int, height: int) -> tuple[int, int] | None:
    """A gaze point X,Y in pixels inside a width x height frame; None for an empty argument."""
    if text is None or not str(text).strip():
        return None
    vals = int_list(text, what)
    if len(vals) != 2:
        raise UsageError(f"{what} must be X,Y (two integers), got {text!r}")
    x, y = vals
    if not (0 <= x < width and 0 <= y < height):
        raise UsageError(f"{what} {x},{y} outside the {width}x{height} frame "
                         f"(0 <= X < {width}, 0 <= Y < {height})")
    return x, y

# --- outputs --------------------------------------------------------------------------------

def _probe_writable(folder: Path, path) -> None:
    """Create and remove a file in `folder` (the only test that also holds for root)."""
    try:
        fd, probe = tempfile.mkstemp(dir=folder, prefix=".msr_probe_")
        os.close(fd)
        os.unlink(probe)
    except OSError as e:
        raise UsageError(f"cannot write {path}: cannot create a file in {folder} ({e.strerror or e})") from None


def check_outputs(outputs: dict[str, tuple[str | os.PathLike | None, tuple[str, ...]]],
                  inputs: Iterable[str | os.PathLike | None] = ()) -> None:
    """Check output paths before any work: {flag: (path or None, allowed suffixes)}.

    Refused: an unknown suffix, the same file named twice (or an input named as an output),
    a path that is a folder, a parent that is not a folder, a folder that cannot be written."""
    seen: dict[str, str] = {}
    for name in inputs:
        if name is not None:
            seen[os.path.realpath(name)] = "the input"
    for flag, (path, suffixes) in outputs.items():
        if path is None:
            continue
        p = Path(path)
        if p.suffix.lower() not in suffixes:
            raise UsageError(f"{flag} {path}: the name must end in {' or '.join(suffixes)}")
        real = os.path.realpath(p)
        if real in seen:
            raise UsageError(f"{flag} {path} is the same file as {seen[real]}")
        seen[real] = flag
        if p.is_dir():
            raise UsageError(f"cannot write {path}: it is a folder")
        folder = p.absolute().parent
        while not folder.exists():
            folder = folder.parent
        if not folder.is_dir():
            raise UsageError(f"cannot write {path}: {folder} is not a folder")
        _probe_writable(folder, path)


class OutputSet:
    """Write several outputs all or nothing: each goes to a temporary file in its own folder;
    leaving the `with` block normally renames them all into place, an exception removes them.

        with OutputSet() as out:
            out.write(path, lambda f: save(f))     # f: the temporary path to write
    """

    def __init__(self):
        self._pending: list[tuple[Path, Path]] = []

    def write(self, path, writer: Callable[[Path], None]) -> None:
        dest = Path(path)
        dest.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=dest.parent, prefix=f".{dest.name}.", suffix=".part")
        os.close(fd)
        self._pending.append((Path(tmp), dest))
        writer(Path(tmp))

    def write_text(self, path, text: str) -> None:
        self.write(path, lambda t: t.write_text(text))

    def __enter__(self):
        return self

    def __exit__(self, exc_type, exc, tb):
        if exc_type is None:
            for tmp, dest in self._pending:
                os.replace(tmp, dest)
        else:
            for tmp, _ in self._pending:
                tmp.unlink(missing_ok=True)
        self._pending = []
        return False
