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
from pathlib import Path

from flumekit.io.atomic import atomic_path
from flumekit.pipeline.rules import file_digest


def _key(p) -> str:
    s = os.fspath(p)
    return s if s.startswith("/") else os.path.abspath(s)


class State:
    def __init__(self, path: Path):
        self.path = path
        self.files: dict[str, list] = {}
        self.targets: dict[str, dict] = {}
        self.content: dict[str, str] = {}  # file hash -> content digest
        self.dirty = False  # a file was hashed anew since the state was read
        if path.exists():
            try:
                data = json.loads(path.read_text())
                self.files = data.get("files", {})
                self.targets = data.get("targets", {})
                self.content = data.get("content", {})
            except (json.JSONDecodeError, OSError):
                pass  # a corrupt state only costs a rebuild

    def hash(self, path: Path) -> str:
        """Content hash of ``path`` (cached while its size and mtime are unchanged)."""
        st = os.stat(path)
        key = _key(path)
        cached = self.files.get(key)
        if cached and cached[0] == st.st_size and cached[1] == st.st_mtime_ns:
            return cached[2]
        h = file_digest(path)
        self.files[key] = [st.st_size, st.st_mtime_ns, h]
        self.dirty = True
        return h

    def identity(self, path: Path) -> str:
        """The content digest its writer reported for the current bytes of ``path``, else the
        hash of its bytes (keyed by the bytes' hash, so a moved project keeps it)."""
        h = self.hash(path)
        return self.content.get(h, h)

    def written(self, path: Path, digest: str) -> None:
        self.content[self.hash(path)] = digest
        self.dirty = True

    def save(self) -> None:
        live = {entry[2] for entry in self.files.values()}
        self.content = {h: d for h, d in self.content.items() if h in live}
        self.dirty = False
        with atomic_path(self.path) as tmp:
            tmp.write_text(json.dumps({"files": self.files, "targets": self.targets,
                                       "content": self.content}))
