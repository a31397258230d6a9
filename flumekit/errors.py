"""Errors that the command line turns into one clear message and a non-zero exit."""

from __future__ import annotations

from pathlib import Path


class FlumekitError(Exception):
    """Base class of the errors flumekit reports to users without a traceback.

    Examples
    --------
    Every such error derives from it, so one ``except`` clause catches them all; the command
    line prints the message alone:

    >>> from flumekit.ballscrew.screw import BallScrew
    >>> from flumekit.errors import FlumekitError
    >>> try:
    ...     BallScrew(lead=0.0)
    ... except FlumekitError as error:
    ...     print(f"{type(error).__name__}: {error}")
    GeometryError: ball screw: need lead > 0 and pitch diameter > ball diameter > 0
    """


class InputError(FlumekitError):
    r"""Bad input: a missing, truncated or malformed file, or impossible parameters.

    The message always names the file (and the line or field where known) and what was expected.

    Parameters
    ----------
    path : str or path-like or None
        The file at fault (kept as ``path``, a :class:`pathlib.Path`); None for parameters that
        come from no file.
    problem : str
        What is wrong and what was expected.
    line : int, optional
        Line number in the file, from 1.
    field : str, optional
        The key or column at fault (e.g. ``"flume.water_depth"``).

    Examples
    --------
    A probe record with a typing slip in its third line, as the table reader reports it:

    >>> import pathlib, tempfile
    >>> from flumekit.errors import InputError
    >>> from flumekit.io.tables import read_text
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder) / "WP1.csv"
    ...     _ = path.write_text("time,eta\n0.00,0.001\n0.04,0.0o3\n0.08,0.002\n")
    ...     try:
    ...         read_text(path)
    ...     except InputError as error:
    ...         print(error)
    /.../WP1.csv, line 3: column 2: '0.0o3' is not a number

    The message is built from the parts, which a program can read back:

    >>> error = InputError("raw/runs/R001/run.toml", "expected a number [s]", line=7,
    ...                    field="wave.period")
    >>> print(error)
    raw/runs/R001/run.toml, line 7, field 'wave.period': expected a number [s]
    >>> error.path.name, error.line, error.field
    ('run.toml', 7, 'wave.period')
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
