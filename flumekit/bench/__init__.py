"""Accuracy-versus-run-time benchmarks: ``flumekit bench AREA`` runs ``flumekit.bench.AREA.run``."""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any


def best_time(fn: Callable[[], Any], repeat: int = 3) -> tuple[float, Any]:
    """Best wall-clock time [s] of ``repeat`` calls of ``fn`` and the last result."""
    best, out = float("inf"), None
    for _ in range(max(1, repeat)):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out
