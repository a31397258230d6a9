"""Build state: content hashes of files and the signature each target was last built with.

File hashes are cached by (size, modification time) so that an unchanged tree costs one
``stat`` per file; touching a file without changing it costs one re-hash and rebuilds nothing.

A dataset's *identity* is the digest of the data it holds, without the attributes that say how
it was made (:func:`flumekit.conventions.content_digest`), when its writer reported one; else
the hash of its bytes. A rebuild that reproduces the same data under new provenance (other
parameters, other input hashes) therefore changes nothing downstream.
"""

from __future__ import annotations

import json
import os
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from flumekit.docstrings import filler
from flumekit.io.atomic import atomic_path
from flumekit.pipeline.rules import file_digest

#: docstring text that several functions of this module share
_doc = filler(
    returns_digest=("Returns\n"
                    "-------\n"
                    "str\n"
                    "    Hex digest."))


def _key(p) -> str:
    s = os.fspath(p)
    return s if s.startswith("/") else os.path.abspath(s)


class State:
    """The build state of a processed folder, read from and saved to a JSON file.

    A corrupt or absent file is an empty state: it only costs a rebuild.

    Parameters
    ----------
    path : pathlib.Path
        The state file (:attr:`flumekit.pipeline.Pipeline.state_file`).
    """

    def __init__(self, path: Path):
        self.path = path
        self.files: dict[str, list] = {}
        self.targets: dict[str, dict] = {}
        self.content: dict[str, str] = {}  # file hash -> content digest
        self.dirty = False  # a file was hashed anew since the state was read
        self._stats: dict[str, os.stat_result | None] | None = None  # see scan()
        if path.exists():
            try:
                data = json.loads(path.read_text())
                self.files = data.get("files", {})
                self.targets = data.get("targets", {})
                self.content = data.get("content", {})
            except (json.JSONDecodeError, OSError):
                pass  # a corrupt state only costs a rebuild

    @contextmanager
    def scan(self) -> Iterator[None]:
        """Stat each file once within the block.

        A file read by many targets (the campaign file, a run's dataset feeding every summary)
        costs one system call per scan of the targets, not one per reader. For a block in which
        no file that was stat-ed changes: the engine scans the targets whose inputs are
        complete, and the outputs of a rule started in a scan are read only by targets that
        wait for it.
        """
        self._stats = {}
        try:
            yield
        finally:
            self._stats = None

    def _stat(self, key: str) -> os.stat_result | None:
        """``os.stat`` of the absolute path ``key``, None when absent (memoised in a scan)."""
        memo = self._stats
        if memo is not None and key in memo:
            return memo[key]
        try:
            st = os.stat(key)
        except (FileNotFoundError, NotADirectoryError):
            st = None
        if memo is not None:
            memo[key] = st
        return st

    def exists(self, path) -> bool:
        """Return whether ``path`` exists (one ``stat`` per scan)."""
        return self._stat(_key(path)) is not None

    @_doc
    def hash(self, path: Path) -> str:
        """Return the SHA-256 of a file's bytes, cached while its size and mtime are unchanged.

        Parameters
        ----------
        %(path)s

        %(returns_digest)s

        Raises
        ------
        FileNotFoundError
            When the file is absent.
        """
        key = _key(path)
        st = self._stat(key)
        if st is None:
            raise FileNotFoundError(2, "No such file or directory", os.fspath(path))
        cached = self.files.get(key)
        if cached and cached[0] == st.st_size and cached[1] == st.st_mtime_ns:
            return cached[2]
        h = file_digest(path)
        self.files[key] = [st.st_size, st.st_mtime_ns, h]
        self.dirty = True
        return h

    @_doc
    def identity(self, path: Path) -> str:
        """Return the identity of a file: its writer's content digest, else its bytes' hash.

        The writer's digest is keyed by the bytes' hash, so a moved project keeps it.

        Parameters
        ----------
        %(path)s

        %(returns_digest)s
        """
        h = self.hash(path)
        return self.content.get(h, h)

    def written(self, path: Path, digest: str) -> None:
        """Record the content digest a writer reported for the current bytes of ``path``."""
        self.content[self.hash(path)] = digest
        self.dirty = True

    def save(self) -> None:
        """Write the state atomically, dropping content digests of bytes no file holds."""
        live = {entry[2] for entry in self.files.values()}
        self.content = {h: d for h, d in self.content.items() if h in live}
        self.dirty = False
        try:
            with atomic_path(self.path) as tmp:
                tmp.write_text(json.dumps({"files": self.files, "targets": self.targets,
                                           "content": self.content}))
        except OSError as e:  # a full disk says no file name: the message needs one
            if e.filename:
                raise
            raise OSError(e.errno, e.strerror, str(self.path)) from None
