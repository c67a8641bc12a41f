"""Where the sweep's tasks run. An executor has `submit(fn, *args, priority=0)` (a future with
`result()`), `scatter(value)` (a handle to pass to tasks in place of a large value),
`results(futures, progress=None)` (the results in order; `progress.update(1)` for each) and
`close()`; `name` says what it is in logs and results.json.

- `SerialExecutor`: every task in this process, in submission order, when its result is collected;
- `DaskExecutor`: Dask distributed, on an existing scheduler or a LocalCluster of this machine.

Each task of msr_eval.sweep is a pure function of its arguments, so both give the same records.
"""
from __future__ import annotations

import os


class _Deferred:
    def __init__(self, fn, args):
        self._fn, self._args = fn, args

    def result(self):
        return self._fn(*self._args)


class SerialExecutor:
    """Runs every task in this process, in submission order, when its result is collected."""

    name = "serial"

    def submit(self, fn, *args, priority: int = 0):
        return _Deferred(fn, args)

    def scatter(self, value):
        return value

    def results(self, futures, progress=None):
        out = []
        for f in futures:
            out.append(f.result())
            if progress is not None:
                progress.update(1)
        return out

    def close(self):
        pass


class DaskExecutor:
    """Tasks on Dask distributed: an existing scheduler, or a LocalCluster of this machine."""

    def __init__(self, scheduler: str | None = None, workers: int | None = None):
        import logging

        import dask
        from distributed import Client, LocalCluster
        # The nanny starts each worker with MALLOC_TRIM_THRESHOLD_=65536, which turns off
        # glibc's adaptive mmap threshold: every large numpy temporary is then mapped and
        # faulted in afresh, and a sweep's tasks run about 1.5 times slower than in this
        # process. The workers here get the environment of this process instead.
        dask.config.set({"distributed.nanny.pre-spawn-environ": {}})
        self.cluster = None
        if scheduler:
            self.client = Client(scheduler)
            self.name = f"dask {scheduler}"
        else:
            n = workers or _cpus()
            # One thread a worker: the tasks are numpy code that holds the GIL most of the time.
            self.cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                                        dashboard_address=None, silence_logs=logging.ERROR)
            self.client = Client(self.cluster)
            self.name = f"dask LocalCluster, {n} workers"

    def submit(self, fn, *args, priority: int = 0):
        # priority: a pair's key metrics (submitted once its settings are in) run before the
        # settings of later pairs, so each pair's records are complete and cached early
        return self.client.submit(fn, *args, pure=False, priority=priority)

    def scatter(self, value):
        return self.client.scatter(value, broadcast=False)

    def results(self, futures, progress=None):
        from distributed import as_completed
        for _ in as_completed(futures):
            if progress is not None:
                progress.update(1)
        return self.client.gather(futures)

    def close(self):
        self.client.close()
        if self.cluster is not None:
            self.cluster.close()


def _cpus() -> int:
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:
        return max(1, os.cpu_count() or 1)


def make_executor(scheduler: str | None = None, workers: int | None = None):
    """`scheduler`: "serial", a Dask address (tcp://host:port), or None for $MSR_DASK_SCHEDULER
    and else a LocalCluster with `workers` workers (default: one per CPU)."""
    if scheduler == "serial" or workers == 0:
        return SerialExecutor()
    return DaskExecutor(scheduler or os.environ.get("MSR_DASK_SCHEDULER") or None, workers)
