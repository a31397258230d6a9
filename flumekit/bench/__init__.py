"""Accuracy-versus-run-time benchmarks: ``flumekit bench AREA`` runs ``flumekit.bench.AREA.run``."""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

__all__ = ["areas", "best_time"]


def areas() -> list[str]:
    """The benchmark areas: the modules of this package that define ``run`` (found without
    importing them: the command line lists them in its help)."""
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
    """Best wall-clock time [s] of ``repeat`` calls of ``fn`` and the last result."""
    best, out = float("inf"), None
    for _ in range(max(1, repeat)):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out
