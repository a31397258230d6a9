"""Where rules run: in this process, in a local process/thread pool, or on a Dask cluster.

Dask is the only scale-out engine: a scheduler address given with
``--scheduler`` or the standard ``DASK_SCHEDULER_ADDRESS`` sends rules to its workers.

Pool workers die with their driver: they ignore Ctrl-C (the driver handles it and stops them),
on SIGTERM remove the temporary files they were writing and exit, and on Linux ask the kernel
for a SIGTERM when the driver dies, even by ``kill -9``.
"""

from __future__ import annotations

import os
import signal
import sys
import time
from collections.abc import Callable
from concurrent.futures import CancelledError
from typing import Any

from flumekit.errors import FlumekitError

#: seconds a Dask scheduler may take to answer, and a cluster may stay without any worker,
#: before the build stops with an error
DASK_TIMEOUT = 30.0


class Executor:
    """Where the engine sends rules: submit a call, wait for some to finish, close.

    A context manager: leaving it by an interrupt closes with ``abort=True``.
    """

    def submit(self, fn: Callable, *args: Any):
        """Start ``fn(*args)`` and return its future (``concurrent.futures``-like)."""
        raise NotImplementedError

    def wait_any(self, futures: list) -> list:
        """Return the futures of ``futures`` that are done, waiting for at least one."""
        raise NotImplementedError

    def close(self, abort: bool = False) -> None:
        """Release the workers; ``abort``: stop running calls instead of waiting for them."""

    def __enter__(self):
        """Return the executor itself."""
        return self

    def __exit__(self, exc_type, *exc):
        """Close, aborting running calls on KeyboardInterrupt or SystemExit."""
        self.close(abort=exc_type is not None and issubclass(exc_type, (KeyboardInterrupt,
                                                                       SystemExit)))


class SerialExecutor(Executor):
    """Runs each rule at once in this process (the default, and the easiest to debug).

    With ``exit_on_interrupt`` (the command line) a Ctrl-C while a rule runs removes the
    temporary files the rule was writing and ends the process at once (status 130), as a pool
    worker ends on SIGTERM: a KeyboardInterrupt raised at an arbitrary point of library code
    is not safe: raised inside xarray's netCDF writing, between taking its (non-reentrant)
    file lock and the ``try`` that releases it, it leaves the lock held, and the writer's
    cleanup then waits for it forever. Finished rules are in the build state already (saved
    after each), so nothing else is lost. Without it (the library use, a notebook), Ctrl-C
    raises KeyboardInterrupt as Python does.

    Parameters
    ----------
    exit_on_interrupt : bool, default False
        End the process on Ctrl-C while a rule runs (the command line).
    """

    def __init__(self, exit_on_interrupt: bool = False):
        self.exit_on_interrupt = exit_on_interrupt

    def submit(self, fn, *args):
        """Run ``fn(*args)`` now and return a finished future holding its result or error."""
        import concurrent.futures as cf  # here: a no-op make never needs it

        fut = cf.Future()
        previous = None
        if self.exit_on_interrupt and signal.getsignal(signal.SIGINT) not in (
                signal.SIG_IGN, None):
            previous = signal.signal(signal.SIGINT, _exit_interrupted)
        try:
            fut.set_result(fn(*args))
        except Exception as e:  # delivered through the future; Ctrl-C is not caught
            fut.set_exception(e)
        finally:
            if previous is not None:
                signal.signal(signal.SIGINT, previous)
        return fut

    def wait_any(self, futures):
        """Return ``futures``: every one is finished when submitted."""
        return futures


#: what the command line says when Ctrl-C ends a build
INTERRUPTED = ("flumekit: interrupted (finished targets are kept; `flumekit make` goes on from "
               "there)")


def _exit_interrupted(signum, frame):
    from flumekit.io.atomic import remove_active

    remove_active()
    print(f"\n{INTERRUPTED}", file=sys.stderr, flush=True)
    os._exit(130)


def _terminate(signum, frame):
    # not SystemExit: concurrent.futures would catch it inside a task, report it to a driver
    # that may be dead, and wait for the next task forever. Remove what this worker was
    # writing and leave at once.
    from flumekit.io.atomic import remove_active

    remove_active()
    os._exit(128 + signum)


#: memory of a pool worker for the datasets it has read [B] (:func:`flumekit.io.netcdf.
#: remember_reads`)
WORKER_READ_MEMORY = 128 * 2**20


def _worker_init() -> None:
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, _terminate)
    if sys.platform.startswith("linux"):
        import ctypes

        PR_SET_PDEATHSIG = 1
        try:
            ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGTERM)
        except (OSError, AttributeError):
            pass
    # the driver may have died between the fork and the prctl above
    if os.getppid() == 1:
        raise SystemExit(1)
    # a worker lives for one build, in which no product is rewritten in place: the products
    # several rules read (a run's waves, the calibration) are read once per worker
    from flumekit.io.netcdf import remember_reads

    remember_reads(WORKER_READ_MEMORY)


class PoolExecutor(Executor):
    """A local pool of ``jobs`` processes (or threads).

    Parameters
    ----------
    jobs : int
        Number of workers.
    kind : {"processes", "threads"}, default "processes"
        Worker kind; processes are forked where the platform allows.
    """

    def __init__(self, jobs: int, kind: str = "processes"):
        import concurrent.futures as cf

        self.kind = kind
        if kind == "threads":
            self.pool = cf.ThreadPoolExecutor(jobs)
        else:
            import multiprocessing as mp

            method = "fork" if "fork" in mp.get_all_start_methods() else "spawn"
            self.pool = cf.ProcessPoolExecutor(jobs, mp_context=mp.get_context(method),
                                               initializer=_worker_init)

    def submit(self, fn, *args):
        """Queue ``fn(*args)`` on the pool and return its future."""
        return self.pool.submit(fn, *args)

    def wait_any(self, futures):
        """Return the futures that are done, waiting for the first to finish."""
        import concurrent.futures as cf

        done, _ = cf.wait(futures, return_when=cf.FIRST_COMPLETED)
        return list(done)

    def close(self, abort: bool = False):
        """Shut the pool down; ``abort``: terminate the worker processes (SIGTERM, then kill)."""
        if not abort or self.kind == "threads":
            self.pool.shutdown(wait=True, cancel_futures=True)
            return
        import multiprocessing as mp

        self.pool.shutdown(wait=False, cancel_futures=True)
        workers = mp.active_children()
        for p in workers:
            p.terminate()  # SIGTERM: the worker removes its temporaries and exits
        deadline = time.monotonic() + 10.0
        for p in workers:
            p.join(max(0.0, deadline - time.monotonic()))
            if p.is_alive():
                p.kill()


#: the loggers of dask.distributed that report a lost scheduler with tracebacks
LOST_SCHEDULER_LOGS = ("distributed.client", "distributed.batched", "distributed.comm",
                       "distributed.core")


class DaskExecutor(Executor):
    """Rules as tasks on a dask.distributed cluster (``pip install flumekit[dask]``).

    A scheduler that does not answer within ``timeout`` seconds, and a cluster that has no
    worker for ``timeout`` seconds while rules wait, are errors (not a silent hang).

    Parameters
    ----------
    address : str
        The scheduler address (``tcp://HOST:PORT``, or ``inproc://`` of this process).
    timeout : float, default :data:`DASK_TIMEOUT`
        Time the scheduler may take to answer and the cluster may stay without a worker [s].

    Raises
    ------
    flumekit.errors.FlumekitError
        When dask.distributed is not installed, or the scheduler cannot be reached.
    """

    def __init__(self, address: str, timeout: float = DASK_TIMEOUT):
        try:
            from distributed import Client
        except ImportError as e:
            raise FlumekitError("a Dask scheduler was given but dask.distributed is not "
                                "installed: pip install 'flumekit[dask]'") from e
        self.address, self.timeout = address, timeout
        parts = address.removeprefix("inproc://").split("/")
        if address.startswith("inproc://") and (len(parts) < 2 or parts[1] != str(os.getpid())):
            # refused before a Client exists: a Client that fails on it leaves a half-started
            # event loop whose clean-up prints a traceback at exit
            raise FlumekitError(f"not a Dask scheduler address this process can reach: "
                                f"{address} (an inproc:// address of another process); give "
                                "tcp://HOST:PORT, or unset DASK_SCHEDULER_ADDRESS to build "
                                "locally")
        try:
            # not the default client: a Client that is sets dask's global scheduler to
            # "dask.distributed", and xarray/dask code later in the same process (tests, a
            # notebook) then fails with "no Client active" once this one is closed
            self.client = Client(address, timeout=timeout, set_as_default=False)
            # a lost scheduler is reported once, in one line (wait_any); the client's own
            # logs would print a traceback for each attempt to reconnect and for the closed
            # batched stream
            import logging

            self._logs = {name: logging.getLogger(name) for name in LOST_SCHEDULER_LOGS}
            self._levels = {name: log.level for name, log in self._logs.items()}
            for log in self._logs.values():
                log.setLevel(logging.CRITICAL)
        except (OSError, TimeoutError) as e:
            raise FlumekitError(f"cannot reach the Dask scheduler at {address} within "
                                f"{timeout:g} s ({type(e).__name__}); check the address, or "
                                "unset DASK_SCHEDULER_ADDRESS to build locally") from None
        except ValueError as e:  # a malformed address, or another process's inproc:// one
            raise FlumekitError(f"not a Dask scheduler address this process can reach: "
                                f"{address} ({e}); give tcp://HOST:PORT, or unset "
                                "DASK_SCHEDULER_ADDRESS to build locally") from None

    def lost(self, e: BaseException) -> FlumekitError:
        """Return the error that says the scheduler was lost (``e``: what the client raised)."""
        return FlumekitError(f"lost the Dask scheduler at {self.address} "
                             f"({type(e).__name__}); the rules that had finished are kept: "
                             "restart the scheduler and make again, or build locally (-j N)")

    def submit(self, fn, *args):
        """Send ``fn(*args)`` to the cluster as a task and return its future."""
        try:
            return self.client.submit(fn, *args, pure=False)
        except (OSError, CancelledError) as e:
            raise self.lost(e) from None

    def wait_any(self, futures):
        """Return the futures that are done; an error when the cluster stays without workers."""
        from distributed import wait

        alone_since: float | None = None
        while True:
            try:
                with self.client.as_current():  # wait() looks up the current client
                    done, _ = wait(futures, timeout=1.0, return_when="FIRST_COMPLETED")
                return list(done)
            except TimeoutError:
                pass
            except (OSError, CancelledError) as e:  # the client lost its scheduler
                raise self.lost(e) from None
            try:
                workers = self.client.scheduler_info(n_workers=-1)["workers"]
            except TypeError:  # older distributed: no n_workers argument
                workers = self.client.scheduler_info()["workers"]
            except (OSError, TimeoutError, CancelledError) as e:
                raise self.lost(e) from None
            if workers:
                alone_since = None
                continue
            alone_since = alone_since or time.monotonic()
            if time.monotonic() - alone_since > self.timeout:
                raise FlumekitError(f"the Dask cluster at {self.address} has had no worker for "
                                    f"{self.timeout:g} s; {len(futures)} rule(s) were waiting. "
                                    "Start workers, or build locally (-j N)")

    def close(self, abort: bool = False):
        """Close the client (the cluster keeps running) and restore its loggers' levels."""
        try:
            self.client.close(timeout=self.timeout)
        except (OSError, TimeoutError, CancelledError):
            pass  # a scheduler already lost: reported by wait_any
        finally:
            for name, log in self._logs.items():
                log.setLevel(self._levels[name])


#: memory a worker process may need [bytes]: the default campaign's heaviest rules (a UVP
#: run, an uncertainty Monte Carlo, the comparison) peak at about 0.45 GB in one process
WORKER_MEMORY = 2**30


def default_jobs() -> int:
    """Return the number of local worker processes of a make without ``-j``.

    One per CPU this process may run on, but no more than the machine's memory holds at
    :data:`WORKER_MEMORY` each (a many-core machine with little memory would otherwise swap).

    Returns
    -------
    int
        At least 1.

    Examples
    --------
    >>> default_jobs() >= 1
    True
    """
    try:
        cpus = len(os.sched_getaffinity(0))
    except AttributeError:  # not on every platform
        cpus = os.cpu_count() or 1
    try:
        memory = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (AttributeError, ValueError, OSError):  # not on every platform
        memory = cpus * WORKER_MEMORY
    return max(1, min(cpus, memory // WORKER_MEMORY))


def executor_for(jobs: int | None = 1, scheduler: str | None = None, kind: str = "processes",
                 timeout: float = DASK_TIMEOUT, exit_on_interrupt: bool = False) -> Executor:
    """Return the executor for a number of jobs or a Dask scheduler.

    Parameters
    ----------
    jobs : int or None, default 1
        Local workers; 1: this process (:class:`SerialExecutor`); None: one per CPU this
        process may use (:func:`default_jobs`).
    scheduler : str, optional
        A Dask scheduler address; default: the ``DASK_SCHEDULER_ADDRESS`` environment
        variable. When given, rules run on that cluster whatever ``jobs`` says.
    kind : {"processes", "threads"}, default "processes"
        Worker kind of a local pool.
    timeout : float, default :data:`DASK_TIMEOUT`
        Time a Dask scheduler may take to answer [s].
    exit_on_interrupt : bool, default False
        Serial only: end the process on Ctrl-C (the command line).

    Returns
    -------
    Executor
        A :class:`DaskExecutor`, :class:`PoolExecutor` or :class:`SerialExecutor`.

    Raises
    ------
    flumekit.errors.FlumekitError
        When a Dask scheduler is given but cannot be used.

    Examples
    --------
    >>> with executor_for(1) as ex:
    ...     ex.submit(sum, [1, 2]).result()
    3
    """
    address = scheduler or os.environ.get("DASK_SCHEDULER_ADDRESS")
    if address:
        return DaskExecutor(address, timeout)
    if jobs is None:
        jobs = default_jobs()
    if jobs > 1:
        return PoolExecutor(jobs, kind)
    return SerialExecutor(exit_on_interrupt=exit_on_interrupt)
