"""Build state: content hashes of files and the signature each target was last built with.

File hashes are cached by (size, modification time) so that an unchanged tree costs one
``stat`` per file; touching a file without changing it costs one re-hash and rebuilds nothing.
"""

from __future__ import annotations

import json
import os
import tempfile
from pathlib import Path

from flumekit.pipeline.rules import file_digest


class State:
    def __init__(self, path: Path):
        self.path = path
        self.files: dict[str, list] = {}
        self.targets: dict[str, dict] = {}
        if path.exists():
            try:
                data = json.loads(path.read_text())
                self.files = data.get("files", {})
                self.targets = data.get("targets", {})
            except (json.JSONDecodeError, OSError):
                pass  # a corrupt state only costs a rebuild

    def hash(self, path: Path) -> str:
        """Content hash of ``path`` (cached while its size and mtime are unchanged)."""
        st = path.stat()
        key = str(path.resolve())
        cached = self.files.get(key)
        if cached and cached[0] == st.st_size and cached[1] == st.st_mtime_ns:
            return cached[2]
        h = file_digest(path)
        self.files[key] = [st.st_size, st.st_mtime_ns, h]
        return h

    def save(self) -> None:
        self.path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=self.path.parent, prefix=".state.", suffix=".tmp")
        with os.fdopen(fd, "w") as f:
            json.dump({"files": self.files, "targets": self.targets}, f)
        os.replace(tmp, self.path)
