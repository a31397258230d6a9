"""Atomic file writing: every writer of flumekit goes through :func:`atomic_path`."""

from __future__ import annotations

import os
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

#: every temporary name :func:`atomic_path` makes contains this, so that a build can find the
#: temporaries a killed build left behind (and nothing else)
TMP_MARK = ".flumekit-tmp"
#: temporaries being written in this process, for :func:`remove_active` on a fatal signal
_ACTIVE: set[str] = set()


@dataclass(frozen=True)
class Written:
    """A file a writer wrote, with the content digest of what it holds.

    Returned by :func:`flumekit.io.netcdf.write_dataset` to its caller, which hands it on to
    the pipeline's rule (an action returns what it wrote): the engine stops a rebuild's cascade
    where a dataset's content is unchanged although its bytes (provenance) differ. A
    path-like object: it opens as its ``path``.

    Parameters
    ----------
    path : Path
        The file written.
    digest : str
        SHA-256 (hex) of its content without the provenance attributes
        (:func:`flumekit.conventions.content_digest`).

    Examples
    --------
    >>> import os
    >>> os.fspath(Written(Path("a.nc"), "0" * 64))
    'a.nc'
    """

    path: Path
    digest: str

    def __fspath__(self) -> str:
        """Return the path written, so that the object opens as a path."""
        return os.fspath(self.path)


def umask() -> int:
    """Return the process umask, read without changing it.

    ``os.umask`` can only read the mask by setting it, which races with threads writing
    files meanwhile; ``/proc/self/status`` says it without touching it (Linux), else the
    mask is read by setting and restoring it.

    Returns
    -------
    int
        The file mode creation mask (e.g. ``0o022``).

    Examples
    --------
    >>> 0 <= umask() <= 0o777
    True
    """
    try:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except OSError:
        pass
    old = os.umask(0o022)
    os.umask(old)
    return old


@contextmanager
def atomic_path(path: str | Path) -> Iterator[Path]:
    """Yield a temporary path beside ``path``; rename it onto ``path`` if the block succeeds.

    The temporary name keeps the suffix (``.x.nc.flumekit-tmp.abc.nc``) so that writers which
    infer the format from it work. On any failure the temporary file is removed and ``path`` is
    left as it was: a failed write never leaves a partial output. The file gets the mode a plain
    ``open`` would give it (0666 minus the umask), not ``mkstemp``'s private 0600, which would
    otherwise survive the rename and hide shared outputs from colleagues.

    Parameters
    ----------
    path : str or pathlib.Path
        The file to write; its folder is created if missing.

    Yields
    ------
    pathlib.Path
        The temporary file to write to (it exists, empty).

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     with atomic_path(Path(folder) / "a.txt") as tmp:
    ...         _ = tmp.write_text("done")
    ...     print((Path(folder) / "a.txt").read_text())
    done
    """
    import tempfile  # here: a no-op make writes nothing and need not import it

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    # the temporary is registered before a signal handler can run (one arriving between its
    # creation and its registration would leave it behind): Ctrl-C and SIGTERM wait meanwhile
    masked = _mask_signals()
    tmp = None
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}{TMP_MARK}.", suffix=path.suffix,
                                   dir=path.parent)
        _ACTIVE.add(tmp)
        try:
            os.fchmod(fd, 0o666 & ~umask())
        finally:
            os.close(fd)
            # a signal held back meanwhile is delivered here, inside the block that removes
            # the temporary (with other threads running, the mask may not hold it at all)
            _unmask_signals(masked)
            masked = None
        yield Path(tmp)
        os.replace(tmp, path)
    except BaseException:
        if masked is not None:
            _unmask_signals(masked)
        if tmp is not None:
            Path(tmp).unlink(missing_ok=True)
        raise
    finally:
        if tmp is not None:
            _ACTIVE.discard(tmp)


def _mask_signals():
    """Block SIGINT and SIGTERM in this thread and return the previous mask.

    None where the platform has no signal masks.
    """
    import signal

    if not hasattr(signal, "pthread_sigmask"):
        return None
    return signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT, signal.SIGTERM})


def _unmask_signals(previous) -> None:
    """Restore the mask of :func:`_mask_signals`; a signal that waited is delivered now."""
    import signal

    if previous is not None:
        signal.pthread_sigmask(signal.SIG_SETMASK, previous)


def remove_active() -> None:
    """Remove the temporaries this process is writing.

    Called by a process about to die of a signal, which will not unwind through
    :func:`atomic_path`.
    """
    for tmp in list(_ACTIVE):
        try:
            os.unlink(tmp)
        except OSError:
            pass


def remove_orphans(folder: Path) -> list[Path]:
    """Remove the temporary files of :func:`atomic_path` that a killed process left behind.

    Call it only while no other writer can be active there (under the build lock).

    Parameters
    ----------
    folder : pathlib.Path
        Searched recursively; a missing folder has none.

    Returns
    -------
    list of pathlib.Path
        The files removed.
    """
    if not folder.is_dir():
        return []
    gone = [p for p in folder.rglob(f".*{TMP_MARK}.*") if p.is_file()]
    for p in gone:
        p.unlink(missing_ok=True)
    return gone
