"""One build at a time per processed folder.

``make`` holds an exclusive lock on ``<processed>/.flumekit.lock`` (``flock``: released by the
kernel when the holder dies, even by ``kill -9``, so a crash never leaves a stale lock). A
second ``make`` says who holds the lock and waits for it.
"""

from __future__ import annotations

import fcntl
import json
import os
import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from flumekit.errors import FlumekitError


@contextmanager
def build_lock(folder: Path, wait: float | None = None,
               say=lambda s: print(s, file=sys.stderr)) -> Iterator[None]:
    """Hold the build lock of a processed folder.

    Parameters
    ----------
    folder : pathlib.Path
        The processed folder (created if absent); the lock is ``.flumekit.lock`` in it.
    wait : float, optional
        Longest wait for another build's lock [s]; None: as long as it takes.
    say : callable, optional
        Prints who holds the lock before waiting (default: standard error).

    Yields
    ------
    None
        While the lock is held.

    Raises
    ------
    flumekit.errors.FlumekitError
        When the lock is still held after ``wait`` seconds.
    """
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / ".flumekit.lock"
    fd = os.open(path, os.O_RDWR | os.O_CREAT, 0o666)
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            # the holder writes who it is just after taking the lock: give it a moment
            for _ in range(20):
                holder = _holder(fd)
                if holder is not None:
                    break
                time.sleep(0.05)
            holder = holder or "another process"
            say(f"waiting for the build lock of {folder}: held by {holder}")
            deadline = None if wait is None else time.monotonic() + wait
            while True:
                try:
                    fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
                    break
                except BlockingIOError:
                    if deadline is not None and time.monotonic() > deadline:
                        raise FlumekitError(f"{path}: another build holds the lock ({holder}); "
                                            f"gave up after {wait:g} s") from None
                    time.sleep(0.2)
        me = {"pid": os.getpid(), "host": os.uname().nodename, "command": " ".join(sys.argv),
              "since": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())}
        os.ftruncate(fd, 0)
        os.pwrite(fd, json.dumps(me).encode(), 0)
        try:
            yield
        finally:
            os.ftruncate(fd, 0)
            fcntl.flock(fd, fcntl.LOCK_UN)
    finally:
        os.close(fd)


def _holder(fd: int) -> str | None:
    """Who holds the lock, as its holder wrote it; None while nothing readable is written."""
    try:
        info = json.loads(os.pread(fd, 4096, 0).decode() or "{}")
        return (f"pid {info['pid']} on {info['host']} since {info['since']} "
                f"({info['command']})")
    except (ValueError, KeyError, OSError):
        return None
