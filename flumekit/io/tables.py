"""Instrument CSV tables: one header line of ``name [unit]`` columns, then numeric rows.

This is the text format of the raw campaign (raw/README.md) for probe voltages, encoder counts,
cylinder pressure and static calibrations. Reading converts every column to SI and checks the
file thoroughly, naming the file, line and column of any problem.
"""

from __future__ import annotations

import io
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from flumekit.errors import InputError
from flumekit.io.atomic import atomic_path

#: unit -> (quantity, factor to SI)
UNITS: dict[str, tuple[str, float]] = {
    "s": ("time", 1.0), "ms": ("time", 1e-3),
    "V": ("voltage", 1.0), "mV": ("voltage", 1e-3),
    "Pa": ("pressure", 1.0), "kPa": ("pressure", 1e3), "bar": ("pressure", 1e5),
    "mbar": ("pressure", 1e2),
    "m": ("length", 1.0), "cm": ("length", 1e-2), "mm": ("length", 1e-3),
    "counts": ("count", 1.0),
}

_HEADER = re.compile(r"^\s*([A-Za-z_][A-Za-z0-9_ ]*?)\s*\[([^\]]*)\]\s*$")


@dataclass(frozen=True)
class Column:
    name: str
    unit: str
    quantity: str
    factor: float


def _parse_header(path: Path, line: str) -> list[Column]:
    cols = []
    for j, cell in enumerate(line.rstrip("\r\n").split(",")):
        m = _HEADER.match(cell)
        if not m:
            raise InputError(path, f"header cell {j + 1} {cell!r} is not of the form 'name [unit]'",
                             line=1)
        name, unit = m.group(1), m.group(2).strip()
        if unit not in UNITS:
            raise InputError(path, f"unknown unit [{unit}] for column '{name}'; known units: "
                             + ", ".join(UNITS), line=1, field=name)
        q, f = UNITS[unit]
        cols.append(Column(name, unit, q, f))
    names = [c.name for c in cols]
    if len(set(names)) != len(names):
        raise InputError(path, f"duplicate column names in {names}", line=1)
    return cols


def _locate_bad_cell(path: Path, text: str, ncol: int) -> InputError:
    """Slow path, run only after the fast parser failed: find the first malformed line."""
    lines = text.splitlines()
    for i, line in enumerate(lines[1:], start=2):
        cells = line.split(",")
        if len(cells) != ncol:
            hint = " (truncated file?)" if i == len(lines) else ""
            return InputError(path, f"{len(cells)} fields, expected {ncol}{hint}", line=i)
        for j, c in enumerate(cells):
            try:
                v = float(c)
            except ValueError:
                return InputError(path, f"column {j + 1}: {c!r} is not a number", line=i)
            if not np.isfinite(v):
                return InputError(path, f"column {j + 1}: non-finite value {c!r}", line=i)
    return InputError(path, "could not be parsed as numeric CSV")


def read_table(path: str | Path) -> tuple[list[Column], np.ndarray]:
    """Read an instrument CSV; return its columns and an (n_rows, n_columns) array in SI units."""
    path = Path(path)
    try:
        text = path.read_text()
    except FileNotFoundError:
        raise InputError(path, "file not found") from None
    except UnicodeDecodeError:
        raise InputError(path, "not a text file") from None
    if not text.strip():
        raise InputError(path, "file is empty")
    header, _, body = text.partition("\n")
    cols = _parse_header(path, header)
    if not body.strip():
        raise InputError(path, "no data rows after the header", line=2)
    try:
        df = pd.read_csv(io.StringIO(body), header=None, dtype=np.float64, engine="c",
                         skip_blank_lines=False)
    except (ValueError, pd.errors.ParserError):
        raise _locate_bad_cell(path, text, len(cols)) from None
    data = df.to_numpy()
    if data.shape[1] != len(cols) or not np.all(np.isfinite(data)):
        raise _locate_bad_cell(path, text, len(cols))
    return cols, data * np.array([c.factor for c in cols])


def check_time(path: Path, time: np.ndarray, sampling_rate: float | None = None) -> None:
    """Time must increase strictly and, if a rate is given, step by 1/rate (within 1 %)."""
    if time.size < 2:
        raise InputError(path, "fewer than two samples")
    dt = np.diff(time)
    bad = np.flatnonzero(dt <= 0)
    if bad.size:
        raise InputError(path, f"time is not increasing ({time[bad[0]]} s then "
                         f"{time[bad[0] + 1]} s)", line=int(bad[0]) + 3)
    if sampling_rate is not None:
        expected = 1.0 / sampling_rate
        off = np.flatnonzero(np.abs(dt - expected) > 0.01 * expected)
        if off.size:
            raise InputError(path, f"sampling interval {dt[off[0]]:.6g} s does not match the "
                             f"declared sampling rate {sampling_rate:g} Hz",
                             line=int(off[0]) + 3)


def write_table(path: str | Path, columns: list[tuple[str, str]], data: np.ndarray,
                fmt: str | list[str] = "%.6f") -> Path:
    """Write an instrument CSV atomically. ``columns`` are (name, unit); ``data`` is in those
    units."""
    path = Path(path)
    header = ",".join(f"{n} [{u}]" for n, u in columns)
    with atomic_path(path) as tmp:
        np.savetxt(tmp, data, delimiter=",", header=header, comments="", fmt=fmt)
    return path
