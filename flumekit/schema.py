"""Declarative validation of the TOML files (campaign, run, pipeline): every problem at once.

A schema is a mapping ``key -> Key``. :func:`validate` walks a parsed TOML document against it
and returns every problem it finds (missing keys, wrong types, values out of range, unknown keys
with the closest known name, from :mod:`difflib`); :func:`raise_problems` turns them into one
:class:`~flumekit.errors.InputError` whose lines each name the file, the key and what was
expected. The same schemas document the files (``raw/README.md`` and ``flumekit new``).
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

from flumekit.docstrings import doc
from flumekit.errors import InputError


@doc
def read_toml(path: Path) -> dict[str, Any]:
    """Read a TOML file.

    Parameters
    ----------
    %(path)s

    Returns
    -------
    dict
        Its contents.

    Raises
    ------
    flumekit.errors.InputError
        Naming the file, when it is missing, a folder, not UTF-8 or not valid TOML.
    """
    try:
        with open(path, "rb") as f:
            return tomllib.load(f)
    except FileNotFoundError:
        raise InputError(path, "file not found") from None
    except IsADirectoryError:
        raise InputError(path, "is a folder, not a file") from None
    except UnicodeDecodeError as e:
        raise InputError(path, f"not UTF-8 text, as TOML must be ({e.reason} at byte "
                         f"{e.start})") from None
    except tomllib.TOMLDecodeError as e:
        raise InputError(path, f"not valid TOML ({e})") from None

#: value kinds and what a user is told when a value is not of that kind
KINDS = {
    "number": "a finite number",
    "integer": "an integer",
    "text": "a string",
    "bool": "true or false",
    "names": "a non-empty list of unique names",
    "point": "[x, z] in metres",
    "numbers": "a list of numbers",
    "datetime": "a date and time (2024-03-05T10:12:00Z, or without Z on the lab's clock)",
    "any": "a value",
}


@dataclass(frozen=True)
class Key:
    """One key of a TOML table.

    Parameters
    ----------
    kind : str
        One of :data:`KINDS`, or ``"table"``.
    doc : str, optional
        What the key means, for messages and generated documentation.
    unit : str, optional
        Its unit (e.g. ``"m"``), shown in brackets.
    required : bool, default True
        A missing key is a problem.
    default : object, optional
        The value of an optional key that is not set (:func:`defaults`).
    positive, nonnegative : bool, default False
        A number must be > 0 (>= 0).
    choices : tuple, optional
        The allowed values.
    table : mapping of str to Key, optional
        The schema of a ``"table"``.
    items : Key, optional
        The schema of every key of an open table (names chosen by the user, e.g. probe names).
    check : callable, optional
        ``check(value) -> problem or None``, a custom test.
    kinds : tuple of str, optional
        Alternatives to ``kind``.

    Examples
    --------
    >>> from pathlib import Path
    >>> schema = {"depth": Key("number", "water depth", unit="m", positive=True)}
    >>> [str(p) for p in validate({"depth": -1.0}, schema, Path("run.toml"))]
    ["run.toml, key 'depth': must be > 0, got -1.0"]
    """

    kind: str
    doc: str = ""
    unit: str = ""
    required: bool = True
    default: Any = None
    positive: bool = False
    nonnegative: bool = False
    choices: tuple = ()
    table: Mapping[str, Key] | None = None
    items: Key | None = None
    check: Callable[[Any], str | None] | None = None
    kinds: tuple[str, ...] = field(default_factory=tuple)  # alternatives to ``kind``


@doc
@dataclass(frozen=True)
class Problem:
    """One problem of a TOML file: the file, the key (dotted; empty: the file) and what is wrong.

    Parameters
    ----------
    %(path)s
    key : str
        The dotted key, e.g. ``"probes.x"``; empty for the file as a whole.
    message : str
        What was expected.
    """

    path: Path
    key: str
    message: str

    def __str__(self) -> str:
        """Return ``"<file>, key '<key>': <message>"``."""
        return f"{self.path}, key '{self.key}': {self.message}" if self.key else \
            f"{self.path}: {self.message}"


def _is_kind(v: Any, kind: str) -> bool:
    if kind == "number":
        return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
    if kind == "integer":
        return isinstance(v, int) and not isinstance(v, bool)
    if kind == "text":
        return isinstance(v, str)
    if kind == "bool":
        return isinstance(v, bool)
    if kind == "names":
        return (isinstance(v, list) and bool(v) and all(isinstance(a, str) for a in v)
                and len(set(v)) == len(v))
    if kind == "point":
        return isinstance(v, list) and len(v) == 2 and all(_is_kind(a, "number") for a in v)
    if kind == "numbers":
        return isinstance(v, list) and all(_is_kind(a, "number") for a in v)
    if kind == "datetime":  # a TOML date-time (offset or local); a date alone is not enough
        import datetime

        return isinstance(v, datetime.datetime)
    if kind == "table":
        return isinstance(v, dict)
    return True


def _check_value(key: Key, v: Any, name: str, path: Path) -> list[Problem]:
    kinds = (key.kind, *key.kinds)
    if not any(_is_kind(v, k) for k in kinds):
        want = " or ".join("a table" if k == "table" else KINDS[k] for k in kinds)
        return [Problem(path, name, f"expected {want}, got {v!r}")]
    if isinstance(v, dict):
        if key.table is not None or key.items is not None:
            return validate(v, key.table or {}, path, name, items=key.items)
        return []
    out = []
    if key.choices and v not in key.choices:
        out.append(Problem(path, name, f"expected one of {list(key.choices)}, got {v!r}"
                           + suggest(str(v), [str(c) for c in key.choices])))
    if _is_kind(v, "number") and key.kind in ("number", "integer"):
        if key.positive and v <= 0:
            out.append(Problem(path, name, f"must be > 0, got {v}"))
        if key.nonnegative and v < 0:
            out.append(Problem(path, name, f"must be >= 0, got {v}"))
    if key.check is not None and not out:
        msg = key.check(v)
        if msg:
            out.append(Problem(path, name, msg))
    return out


def suggest(word: str, known: list[str]) -> str:
    """Return ``"; did you mean 'X'?"`` for the closest known name (difflib), or ``""``.

    Parameters
    ----------
    word : str
        The unknown name.
    known : list of str
        The known names.

    Returns
    -------
    str
        The suggestion, or an empty string when no name is close.

    Examples
    --------
    >>> suggest("dpeth", ["depth", "width"])
    "; did you mean 'depth'?"
    """
    import difflib  # only on a problem: planning a sound campaign need not import it

    close = difflib.get_close_matches(word, known, n=1, cutoff=0.6)
    return f"; did you mean '{close[0]}'?" if close else ""


def validate(data: Mapping[str, Any], schema: Mapping[str, Key], path: Path, section: str = "",
             items: Key | None = None) -> list[Problem]:
    """Return every problem of a parsed TOML table against its schema.

    Missing keys, wrong types, values out of range and unknown keys (with the closest known
    name) are all reported; a missing key that an unknown key's closest name points at is that
    typo, reported once.

    Parameters
    ----------
    data : mapping
        The parsed table.
    schema : mapping of str to Key
        Its schema.
    path : pathlib.Path
        The file, named in every problem.
    section : str, optional
        The table's dotted name, prefixed to the keys.
    items : Key, optional
        The schema of every key not in ``schema`` (an open table).

    Returns
    -------
    list of Problem
        Empty when the table is sound.
    """
    out: list[Problem] = []

    def full(k: str) -> str:
        return f"{section}.{k}" if section else k

    # a missing key that an unknown key's closest name points at is that typo, reported once
    unknown = [k for k in data if k not in schema] if items is None else []
    typos: set[str] = set()
    if unknown:
        import difflib

        typos = {c for k in unknown for c in difflib.get_close_matches(k, list(schema), 1, 0.6)}
    for k, key in schema.items():
        if k not in data:
            if key.required and k not in typos:
                what = "table" if key.kind == "table" else f"key ({KINDS.get(key.kind, '')})"
                unit = f" [{key.unit}]" if key.unit else ""
                out.append(Problem(path, full(k), f"missing {what}{unit}: {key.doc}".rstrip(": ")))
            continue
        out += _check_value(key, data[k], full(k), path)
    for k in data:
        if k in schema:
            continue
        if items is not None:
            out += _check_value(items, data[k], full(k), path)
            continue
        where = f"[{section}]" if section else "the top level"
        out.append(Problem(path, full(k), f"unknown key in {where}; known: "
                           f"{', '.join(schema) or 'none'}" + suggest(k, list(schema))))
    return out


def raise_problems(path: Path, problems: list[Problem]) -> None:
    """Raise one error listing every problem (nothing if there is none).

    Parameters
    ----------
    path : pathlib.Path
        The file the problems are in.
    problems : list of Problem
        From :func:`validate`.

    Raises
    ------
    flumekit.errors.InputError
        Naming the file and key of a single problem, or listing several (``problems``
        attribute).
    """
    if not problems:
        return
    if len(problems) == 1:
        p = problems[0]
        raise InputError(p.path, p.message, field=p.key or None)
    lines = "\n".join(f"  {p}" for p in problems)
    err = InputError(path, f"{len(problems)} problems:\n{lines}")
    err.problems = problems
    raise err


def defaults(schema: Mapping[str, Key], data: Mapping[str, Any]) -> dict[str, Any]:
    """Return ``data`` with the defaults of the optional keys it does not set (one level).

    Examples
    --------
    >>> defaults({"n": Key("integer", required=False, default=3)}, {})
    {'n': 3}
    """
    return {**{k: key.default for k, key in schema.items() if not key.required}, **data}


def describe(schema: Mapping[str, Key], section: str = "") -> list[tuple[str, str]]:
    """Return ``(key, description)`` of every key, for generated documentation.

    Parameters
    ----------
    schema : mapping of str to Key
        The schema; sub-tables are described key by key.
    section : str, optional
        Dotted name prefixed to the keys.

    Returns
    -------
    list of tuple of (str, str)
        Dotted key and its description with unit and default.

    Examples
    --------
    >>> describe({"depth": Key("number", "water depth", unit="m")})
    [('depth', 'water depth [m]')]
    """
    rows = []
    for k, key in schema.items():
        name = f"{section}.{k}" if section else k
        if key.kind == "table" and key.table:
            rows += describe(key.table, name)
            continue
        unit = f" [{key.unit}]" if key.unit else ""
        default = "" if key.default is None else f", default {key.default!r}"
        opt = "" if key.required else f" (optional{default})"
        rows.append((name, f"{key.doc}{unit}{opt}"))
    return rows
