"""The record of the runs a virtual campaign holds, in its marker (:data:`flumekit.synth.MARKER`).

A campaign written run by run (``flumekit make`` synthesises only the runs a target reads) lists
in its marker the runs written so far, so that a run missing later is known to have been removed
by hand, never to be synthesised again (:mod:`flumekit.pipeline.raw`). A campaign written whole
(:func:`flumekit.synth.campaign.write_campaign`) lists none: all its planned runs are there.
No numpy here: the marker is small JSON.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

from flumekit.synth import MARKER


def record_written(raw: Path, run: str) -> None:
    """Add ``run`` to the runs the marker of the virtual campaign ``raw`` lists as written.

    Called by :func:`flumekit.synth.campaign.write_virtual_run` right after it wrote the run,
    so that a run missing later is known to have been removed by hand rather than never
    written. The marker is replaced atomically, under an exclusive lock on the campaign folder
    (runs synthesised in parallel processes).

    Parameters
    ----------
    raw : Path
        A campaign folder holding :data:`MARKER`.
    run : str
        The run just written.
    """
    import fcntl

    from flumekit.io.atomic import atomic_path

    raw = Path(raw)
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
    """Mark the virtual campaign ``raw``, being written without runs, as synthesised run by run.

    The marker gains an empty list of written runs (:func:`record_written` adds each).

    Parameters
    ----------
    raw : pathlib.Path
        Folder of the virtual campaign (it holds :data:`flumekit.synth.MARKER`).
    """
    from flumekit.io.atomic import atomic_path

    marker = Path(raw) / MARKER
    info = json.loads(marker.read_text(encoding="utf-8"))
    if "written" not in info:
        info["written"] = []
        with atomic_path(marker) as tmp:
            tmp.write_text(json.dumps(info) + "\n", encoding="utf-8")


__all__ = ["record_written", "start_record"]
