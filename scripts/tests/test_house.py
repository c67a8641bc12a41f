"""The repository's floor plan stays a reference, not a notebook: page lengths, no tracker
numbers or links out of the repository, no hand-written Python file over 600 lines, and the
PSNR formula written once outside the tests."""
import re
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
GENERATED_PAGES = {"docs/regs.md"}          # peakrdl-markdown's register map
OUTSIDE, OUTSIDE_SPEC = "../" + "shared", "shared/" + "spec"
TRACKER = re.compile(r"\b[Ii]ssue ?#?\d+\b|\(#\d+\)")


def tracked(*patterns: str) -> list[Path]:
    out = subprocess.run(["git", "ls-files", *patterns], cwd=ROOT, capture_output=True, text=True,
                         check=True).stdout.split()
    return [ROOT / p for p in out if (ROOT / p).is_file()]


def test_docs_pages_are_short():
    for page in tracked("docs/*.md", "docs/**/*.md", "README.md"):
        rel = str(page.relative_to(ROOT))
        if rel in GENERATED_PAGES:
            continue
        n = len(page.read_text().splitlines())
        assert n <= (300 if rel == "docs/results.md" else 400), f"{rel}: {n} lines"


def test_no_tracker_numbers_and_no_links_out_of_the_repository():
    files = tracked("*.md", "*.py", "*.sv", "*.svh", "*.rdl", "*.cpp", "*.h", "*.mk", "*.sby",
                    "Makefile", "*.f", "*.core", ".ci/run")
    for f in files:
        text = f.read_text(errors="replace")
        rel = f.relative_to(ROOT)
        assert not TRACKER.search(text), f"{rel}: cites a tracker number: {TRACKER.search(text).group(0)}"
        if f.name != "test_house.py":                      # this test names what it looks for
            assert OUTSIDE not in text and OUTSIDE_SPEC not in text, f"{rel}: refers outside the repository"


def test_no_hand_written_python_file_over_600_lines():
    for f in tracked("*.py"):
        if f.name == "regs.py" and f.parent.name == "msr_flow":
            continue                      # generated from the register map
        n = len(f.read_text().splitlines())
        assert n <= 600, f"{f.relative_to(ROOT)}: {n} lines"


def test_psnr_is_written_once_outside_the_tests():
    hits = [f.relative_to(ROOT) for f in tracked("*.py")
            if "/tests/" not in str(f) and not f.parent.name.startswith("test")
            and re.search(r"log10\(", f.read_text())]
    assert [str(h) for h in hits] == ["sw_model/msr_model/metrics.py"], hits
