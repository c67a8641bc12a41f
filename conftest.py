"""The order of a test session, for `make test`'s `pytest -n 2` (pytest-xdist).

A handful of cocotb benches (a Verilator build and a long simulation each) take minutes; the
other six hundred tests take seconds. Run in collection order, the long ones come last and one
worker runs the tail alone while the other is idle. So the long tests go first, longest first,
and xdist hands out one test at a time (--maxschedchunk 1: each worker holds the test it runs and
one more), which keeps both workers busy until the short tests run out together.

LONG: seconds of the long tests on one core of a two-core machine under `pytest -n 2` (the
`--durations` table of a CI log), keyed by the start of their node id. Only the order follows
from it: an estimate that is off moves a test up or down the list, nothing else. A test that
shares a Verilator build with another (runner.run_cocotb waits for a build in progress) runs
after it by having no entry."""
from __future__ import annotations

LONG = {
    "tb/msr_top/test_msr_top.py::test_msr_top[4-16-8-256]": 400,
    "tb/msr_top/test_msr_top.py::test_msr_top[3-4-3-64]": 190,
    "tb/tile_engine/test_tile_engine.py::test_tile_engine[16-8-": 190,
    "tb/tile_engine/test_tile_engine.py::test_tile_engine[2-2-": 125,
    "tb/tile_engine/test_tile_engine.py::test_tile_engine[64-5-": 115,
    "tb/msr_top/test_msr_top.py::test_msr_top_budget": 115,
    "tb/level_ctrl/": 130,
    "tb/budget_ctrl/": 80,
    "tb/msr_top/test_msr_top.py::test_msr_top_patent_only": 60,
    "tb/tile_engine/test_tile_engine.py::test_tile_engine_depth": 70,
    "tb/depth_interp/": 60,
}


def estimate(nodeid: str) -> float:
    return max((s for k, s in LONG.items() if nodeid.startswith(k)), default=0.0)


def pytest_configure(config):
    # one test at a time from xdist's load scheduler (option absent without xdist)
    if getattr(config.option, "maxschedchunk", 0) is None:
        config.option.maxschedchunk = 1


def pytest_collection_modifyitems(session, config, items):
    # stable: the tests without an estimate keep their collection order, after the long ones
    items.sort(key=lambda item: -estimate(item.nodeid))
