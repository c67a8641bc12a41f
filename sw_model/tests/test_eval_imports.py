"""msr_eval's modules import one another without a circle: the pages' shared
helpers live in msr_eval.present and the scene set in msr_eval.scenes, so report, conv_report,
headline and textured each import only what sits below them. Imports inside functions count."""
import ast
from pathlib import Path

import msr_eval

PKG = Path(msr_eval.__file__).parent


def imports_of(path: Path) -> set[str]:
    """The msr_eval modules a file imports anywhere in it (relative or absolute)."""
    out = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom):
            mod = node.module or ""
            if node.level == 1 or mod.startswith("msr_eval"):
                base = mod.removeprefix("msr_eval").lstrip(".")
                if base:
                    out.add(base.split(".")[0])
                else:                                  # from . import a, b
                    out.update(a.name for a in node.names)
        elif isinstance(node, ast.Import):
            out.update(a.name.split(".")[1] for a in node.names if a.name.startswith("msr_eval."))
    return out


def graph() -> dict[str, set[str]]:
    mods = {p.stem for p in PKG.glob("*.py") if p.stem != "__init__"}
    return {m: imports_of(PKG / f"{m}.py") & mods - {m} for m in mods}


def cycle(g: dict[str, set[str]]) -> list[str] | None:
    """One import circle of the graph, as the list of its modules, or None."""
    state = {}

    def visit(m, path):
        state[m] = "open"
        for n in sorted(g[m]):
            if state.get(n) == "open":
                return path[path.index(n):] + [n]
            if n not in state:
                found = visit(n, path + [n])
                if found:
                    return found
        state[m] = "done"
        return None

    for m in sorted(g):
        if m not in state:
            found = visit(m, [m])
            if found:
                return found
    return None


def test_cycle_finder_finds_a_circle():
    assert cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert cycle({"a": {"b"}, "b": set(), "c": {"a", "b"}}) is None


def test_msr_eval_has_no_import_circle():
    g = graph()
    assert {"report", "conv_report", "headline", "textured", "present", "scenes", "sweep", "executors"} <= set(g)
    assert cycle(g) is None, " -> ".join(cycle(g))


def test_the_pages_share_present_and_scenes():
    g = graph()
    assert g["present"] == set() and g["scenes"] == set()          # the bottom of the pages
    assert "report" not in g["conv_report"] | g["headline"] | g["textured"]
    assert "sweep" not in g["textured"]                          # the scene set, not the sweep
    assert "executors" not in g["sweep"]                         # the caller picks the executor
