"""The marker of a virtual-flume campaign: which runs it plans and which it has written.

The virtual flume writes its marker with the campaign's base files and records each run it
writes afterwards (lazy synthesis, one run at a time), so that a run missing later is known to
have been removed by hand, not never written (:mod:`flumekit.pipeline.raw`). The marker is a
file of the virtual flume's own, not raw data: only the synthesis that created the campaign
replaces it.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

from flumekit.synth import MARKER

__all__ = ["record_written", "start_record"]


def record_written(raw: Path, run: str) -> None:
    """Add ``run`` to the runs the marker of the virtual campaign ``raw`` lists as written.

    Called by the synthesis right after it wrote the run, so that a run missing later is known
    to have been removed by hand, not never written. The marker is replaced atomically, under
    an exclusive lock on the campaign folder (runs synthesised in parallel processes).

    Parameters
    ----------
    raw : Path
        A campaign folder holding :data:`MARKER`.
    run : str
        The run just written.
    """
    import fcntl

    from flumekit.io.atomic import atomic_path

    fd = os.open(raw, os.O_RDONLY)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)
        marker = raw / MARKER
        info = json.loads(marker.read_text(encoding="utf-8"))
        written = set(info.get("written") or [])
        if run in written:
            return
        info["written"] = sorted(written | {run})
        with atomic_path(marker) as tmp:
            tmp.write_text(json.dumps(info) + "\n", encoding="utf-8")
    finally:
        os.close(fd)  # releases the lock


def start_record(raw: Path) -> None:
    """Mark the virtual campaign ``raw``, just written without runs, as synthesised run by run:
    an empty list of written runs (:func:`record_written` adds each)."""
    from flumekit.io.atomic import atomic_path

    marker = raw / MARKER
    info = json.loads(marker.read_text(encoding="utf-8"))
    if "written" not in info:
        info["written"] = []
        with atomic_path(marker) as tmp:
            tmp.write_text(json.dumps(info) + "\n", encoding="utf-8")
