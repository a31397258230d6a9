"""Accuracy-versus-run-time benchmarks: ``flumekit bench AREA`` runs ``flumekit.bench.AREA.run``."""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

__all__ = ["areas", "best_time"]


def areas() -> list[str]:
    """Return the benchmark areas: the modules of this package that define ``run``.

    They are found without importing them: the command line lists them in its help.

    Returns
    -------
    list of str
        Module names, sorted.

    Examples
    --------
    >>> from flumekit.bench import areas
    >>> "waves" in areas() and "truth" not in areas()
    True
    """
    import os
    import re

    here = os.path.dirname(os.path.abspath(__file__))
    out = []
    for name in sorted(os.listdir(here)):
        stem, ext = os.path.splitext(name)
        if ext != ".py" or stem.startswith("_"):
            continue
        with open(os.path.join(here, name), encoding="utf-8") as f:
            if re.search(r"^def run\(", f.read(), re.M):
                out.append(stem)
    return out


def best_time(fn: Callable[[], Any], repeat: int = 3) -> tuple[float, Any]:
    """Return the best wall-clock time of ``repeat`` calls of ``fn`` and the last result.

    On a shared machine the best of several calls is the cost of the code; the others carry
    the load of the other processes.

    Parameters
    ----------
    fn : callable
        Function of no argument.
    repeat : int
        Calls (at least one).

    Returns
    -------
    seconds : float
        Best wall-clock time of one call [s].
    result : object
        What the last call returned.

    Examples
    --------
    >>> from flumekit.bench import best_time
    >>> seconds, result = best_time(lambda: sum(range(10)), repeat=2)
    >>> seconds >= 0.0, result
    (True, 45)
    """
    best, out = float("inf"), None
    for _ in range(max(1, repeat)):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out
