"""Errors that the command line turns into one clear message and a non-zero exit."""

from __future__ import annotations

from pathlib import Path


class FlumekitError(Exception):
    """Base class of the errors flumekit reports to users without a traceback."""


class InputError(FlumekitError):
    """Bad input: a missing, truncated or malformed file, or impossible parameters.

    The message always names the file (and the line or field where known) and what was expected.
    """

    def __init__(self, path: str | Path | None, problem: str, *, line: int | None = None,
                 field: str | None = None):
        self.path = None if path is None else Path(path)
        self.problem = problem
        self.line = line
        self.field = field
        where = "" if path is None else str(path)
        if line is not None:
            where += f", line {line}"
        if field is not None:
            where += f", field '{field}'"
        super().__init__(f"{where}: {problem}" if where else problem)

    def __reduce__(self):
        """Rebuild from the fields, so the error survives pickling to processes and workers."""
        return (_rebuild_input_error, (self.path, self.problem, self.line, self.field, self.args))


def _rebuild_input_error(path, problem, line, field, args):
    e = InputError(path, problem, line=line, field=field)
    e.args = args
    return e


class GeometryError(FlumekitError):
    """Impossible geometry (rod shorter than its anchors allow, negative lengths, ...)."""
