"""Where rules run: in this process, in a local thread/process pool, or on a Dask cluster.

Dask is the only scale-out engine (DESIGN.md §4): a scheduler address given with
``--scheduler`` or the standard ``DASK_SCHEDULER_ADDRESS`` sends rules to its workers.
"""

from __future__ import annotations

import concurrent.futures as cf
import os
from collections.abc import Callable
from typing import Any


class Executor:
    def submit(self, fn: Callable, *args: Any):
        raise NotImplementedError

    def wait_any(self, futures: list) -> list:
        raise NotImplementedError

    def close(self) -> None:
        pass

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


class SerialExecutor(Executor):
    """Runs each rule at once in this process (the default, and the easiest to debug)."""

    def submit(self, fn, *args):
        fut: cf.Future = cf.Future()
        try:
            fut.set_result(fn(*args))
        except BaseException as e:  # broad on purpose: delivered through the future
            fut.set_exception(e)
        return fut

    def wait_any(self, futures):
        return futures


class PoolExecutor(Executor):
    """A local pool of ``jobs`` processes (or threads)."""

    def __init__(self, jobs: int, kind: str = "processes"):
        if kind == "threads":
            self.pool: cf.Executor = cf.ThreadPoolExecutor(jobs)
        else:
            import multiprocessing as mp

            method = "fork" if "fork" in mp.get_all_start_methods() else "spawn"
            self.pool = cf.ProcessPoolExecutor(jobs, mp_context=mp.get_context(method))

    def submit(self, fn, *args):
        return self.pool.submit(fn, *args)

    def wait_any(self, futures):
        done, _ = cf.wait(futures, return_when=cf.FIRST_COMPLETED)
        return list(done)

    def close(self):
        self.pool.shutdown(wait=True, cancel_futures=True)


class DaskExecutor(Executor):
    """Rules as tasks on a dask.distributed cluster (``pip install flumekit[dask]``)."""

    def __init__(self, address: str):
        try:
            from distributed import Client
        except ImportError as e:
            from flumekit.errors import FlumekitError

            raise FlumekitError("a Dask scheduler was given but dask.distributed is not "
                                "installed: pip install 'flumekit[dask]'") from e
        self.client = Client(address)

    def submit(self, fn, *args):
        return self.client.submit(fn, *args, pure=False)

    def wait_any(self, futures):
        from distributed import wait

        done, _ = wait(futures, return_when="FIRST_COMPLETED")
        return list(done)

    def close(self):
        self.client.close()


def executor_for(jobs: int = 1, scheduler: str | None = None, kind: str = "processes") -> Executor:
    address = scheduler or os.environ.get("DASK_SCHEDULER_ADDRESS")
    if address:
        return DaskExecutor(address)
    if jobs > 1:
        return PoolExecutor(jobs, kind)
    return SerialExecutor()
