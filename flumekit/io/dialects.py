"""Instrument files in a declared dialect: CSV/ASCII, LabVIEW TDMS, HDF5 and netCDF.

A :class:`Dialect` says how one instrument's file is written (``[files.<instrument>]`` of
campaign.toml, raw/README.md); :func:`read_channels` returns the channels an instrument needs,
in SI units, with their time axis. The raw campaign's own CSV (``name [unit]`` header, comma,
decimal point, a ``time`` column) is the default dialect. This module knows files, not
instruments: :mod:`flumekit.io.instruments` says which channels each instrument has.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, fields
from pathlib import Path
from typing import Any

import numpy as np

from flumekit.errors import InputError
from flumekit.units import UNITS


@dataclass(frozen=True)
class Dialect:
    """How an instrument file is written. Defaults: the raw campaign's own CSV format."""

    format: str = "csv"  # csv | tdms | hdf5 | netcdf
    delimiter: str = ","  # csv: one character, or "whitespace"
    decimal: str = "."  # csv: "." or ","
    comment: str = ""  # csv: lines starting with this are skipped
    skip_lines: int = 0  # csv: preamble lines before the header (or the first row)
    header: bool = True  # csv: a header row names the columns
    columns: Any = None  # channel -> column (dict), or columns in channel order (list)
    units: Any = None  # one unit for every channel, or channel -> unit (also "time")
    time: str | int = "time"  # time column / channel / variable, or "rate"
    group: str = ""  # tdms, hdf5, netcdf: group of the channels
    file: str = ""  # file name in the run folder (used by the campaign, not here)

    @classmethod
    def from_dict(cls, d: dict | None) -> Dialect:
        names = {f.name for f in fields(cls)}
        return cls(**{k: v for k, v in (d or {}).items() if k in names})

    @property
    def declares_columns(self) -> bool:
        return self.columns is not None

    def column(self, channel: str, index: int) -> str | int:
        if isinstance(self.columns, dict):
            return self.columns.get(channel, channel)
        if isinstance(self.columns, list):
            return self.columns[index]
        return channel

    def unit(self, channel: str) -> str | None:
        if isinstance(self.units, str):
            return None if channel == "time" else self.units
        if isinstance(self.units, dict):
            return self.units.get(channel)
        return None


@dataclass(frozen=True)
class Channel:
    """A channel an instrument needs: its name, physical quantity and fallback unit."""

    name: str
    quantity: str  # "voltage", "length", "pressure", "count", ...
    default_unit: str | None = None


@dataclass(frozen=True)
class Record:
    """Channels read from one file, in SI units."""

    time: np.ndarray | None  # [s], None when the dialect takes time from the sampling rate
    values: np.ndarray  # (channel, sample)
    units: tuple[str, ...]  # the unit each channel was recorded in
    labels: tuple[str, ...]  # where each channel came from in the file (for messages)
    unused: tuple[str, ...]  # columns of the file no channel uses
    first_line: int = 1  # file line of the first sample (text files)
    # the instant of time 0 as ISO 8601 (ending in Z when the file gives the time zone, in UTC;
    # without a zone it is the recording computer's clock), None when the file does not say
    start: str | None = None


#: file or group attributes that give the start of a record (HDF5, netCDF; ISO 8601)
START_ATTRIBUTES = ("record_start", "time_coverage_start", "start_time")


def read_channels(path: str | Path, dialect: Dialect, channels: list[Channel],
                  strict: str = "") -> Record:
    """Read ``channels`` from ``path`` as ``dialect`` says; convert to SI, check units.

    ``strict`` (an instrument name, for the message): when the dialect does not map columns to
    channels, a text file's columns must be exactly the channels and time (the raw campaign's
    own format names every column; another is a typo or a wrong file).
    """
    path = Path(path)
    if not path.exists():
        raise InputError(path, "file not found")
    reader = {"csv": _read_csv, "tdms": _read_tdms, "hdf5": _read_hdf5,
              "netcdf": _read_netcdf}.get(dialect.format)
    if reader is None:
        raise InputError(path, f"unknown format {dialect.format!r}; known: csv, tdms, hdf5, "
                         "netcdf")
    if strict and dialect.format == "csv" and not dialect.declares_columns and dialect.header:
        from flumekit.io.tables import header_labels

        labels = header_labels(path, delimiter=dialect.delimiter, comment=dialect.comment,
                               skip_lines=dialect.skip_lines)
        names = [c.name for c in channels]
        unknown = [x for x in labels if x not in names and x != dialect.time]
        if unknown:
            raise InputError(path, f"unknown {strict} column(s) {unknown}; expected {names}")
    return reader(path, dialect, channels)


def _si(path: Path, ch: Channel, label: str, declared: str | None, found: str | None,
        line: int | None = None) -> tuple[str, float]:
    """The unit of a channel (declared > found in the file > the channel's default), checked."""
    if declared and found and declared != found:
        raise InputError(path, f"column '{label}' is declared in [{declared}] but the file says "
                         f"[{found}]", line=line, field=ch.name)
    unit = declared or found or ch.default_unit
    if unit is None:
        raise InputError(path, f"no unit for column '{label}': write the header cell as "
                         "'name [unit]' or declare the units of the file's dialect", line=line,
                         field=ch.name)
    if unit not in UNITS:
        raise InputError(path, f"unknown unit [{unit}] for column '{label}'; known units: "
                         + ", ".join(UNITS), line=line, field=ch.name)
    q, f = UNITS[unit]
    if q != ch.quantity:
        raise InputError(path, f"column '{label}' has unit [{unit}], expected a {ch.quantity} "
                         "unit", line=line, field=ch.name)
    return unit, f


def iso_instant(t, utc: bool) -> str:
    """ISO 8601 of an instant (numpy datetime64), to the nanosecond it holds (trailing zeros of
    the fraction dropped), with ``Z`` when it is in UTC."""
    s = np.datetime_as_string(np.datetime64(t, "ns"), unit="ns")
    return s.rstrip("0").rstrip(".") + ("Z" if utc else "")


def _instant(path: Path, text: str, what: str) -> tuple[np.datetime64, bool]:
    """(instant as datetime64[ns] in UTC or local, whether in UTC) of an ISO 8601 text."""
    import pandas as pd

    try:
        t = pd.Timestamp(str(text).strip())
    except (ValueError, TypeError):
        raise InputError(path, f"{what}: {text!r} is not a date and time (ISO 8601)") from None
    if t.tz is not None:
        return np.datetime64(t.tz_convert("UTC").tz_localize(None).to_datetime64(), "ns"), True
    return np.datetime64(t.to_datetime64(), "ns"), False


#: CF-style time units: "<unit> since <instant>" (CF 4.4)
_SINCE = re.compile(r"^\s*(\S+)\s+since\s+(.+?)\s*$")


def _seconds(path: Path, values: np.ndarray, label: str, unit: str | None,
             first_line: int | None = None, header_line: int | None = None,
             utc: bool = True) -> tuple[np.ndarray, str | None]:
    """Time in seconds, and the record's start (the instant of time 0, ISO 8601) when the
    column gives it: datetimes count from the first (which is the start; ``utc`` says whether
    datetime64 values are UTC), numbers in ``unit`` or in CF units ``<unit> since <instant>``
    (then the start is that instant)."""
    import pandas as pd

    if values.dtype.kind == "M":
        t = values.astype("datetime64[ns]")
        ns = t.astype(np.int64)
        # divided, not multiplied by 1e-9: k * 40 ms then reads as the double nearest k * 0.04,
        # the same number a text column of seconds gives
        return (ns - ns[0]) / 1e9, iso_instant(t[0], utc)
    if values.dtype.kind in "fiu":
        m = _SINCE.match(unit) if isinstance(unit, str) else None
        if m:
            origin, _ = _instant(path, m.group(2), f"time '{label}' units")
            _, f = _si(path, Channel("time", "time"), label, None, m.group(1), line=header_line)
            # a date without a zone in CF units is UTC (CF 4.4)
            return np.asarray(values, dtype=np.float64) * f, iso_instant(origin, True)
        u, f = _si(path, Channel("time", "time"), label, None, unit, line=header_line)
        return np.asarray(values, dtype=np.float64) * f, None
    s = pd.Series(values).astype(str).str.strip()
    num = pd.to_numeric(s.str.replace(",", ".", regex=False), errors="coerce")
    if num.notna().all():
        return _seconds(path, num.to_numpy(np.float64), label, unit, first_line, header_line)
    try:
        dt = pd.to_datetime(s, errors="raise", format="mixed")
    except (ValueError, TypeError):
        bad = int(np.flatnonzero(num.isna())[0])
        line = None if first_line is None else first_line + bad
        raise InputError(path, f"time column '{label}': {s.iloc[bad]!r} is neither a number nor"
                         " a date and time", line=line) from None
    # stamps with a UTC offset are read in UTC; without one, in the logger's own clock
    return _seconds(path, dt.to_numpy(dtype="datetime64[ns]"), label, unit,
                    utc=getattr(dt.dt, "tz", None) is not None)


def _read_csv(path: Path, d: Dialect, channels: list[Channel]) -> Record:
    from flumekit.io.tables import header_labels, read_text

    def index(spec: str | int, labels: list[str], what: str) -> int:
        if isinstance(spec, int) and not isinstance(spec, bool):
            if not 1 <= spec <= len(labels):
                raise InputError(path, f"{what}: column {spec} does not exist (the file has "
                                 f"{len(labels)})")
            return spec - 1
        if spec in labels:
            return labels.index(spec)
        import difflib

        close = difflib.get_close_matches(str(spec), labels, n=1)
        hint = f"; did you mean '{close[0]}'?" if close else ""
        raise InputError(path, f"missing column '{spec}' (columns: {labels}){hint}")

    # the header first, to know which column is time (it may hold datetimes, read as text)
    head = header_labels(path, delimiter=d.delimiter, comment=d.comment,
                         skip_lines=d.skip_lines, header=d.header)
    jt = None if d.time == "rate" else index(d.time, head, "time")
    kw = dict(delimiter=d.delimiter, decimal=d.decimal, comment=d.comment,
              skip_lines=d.skip_lines, header=d.header)
    t = None
    if jt is not None:
        # a time column of numbers (the usual case) is parsed by pandas' C parser with the
        # others; the text path (datetimes, and the messages naming a bad time cell) only
        # when that fails. Parsing it as text and converting cost 5x the whole numeric read
        try:
            t = read_text(path, **kw)
        except InputError:
            t = None
    if t is None:
        t = read_text(path, **kw, text_columns=() if jt is None else (jt,))
    labels = t.labels
    if not d.header and not d.declares_columns:  # no names: the columns in channel order
        free = [j for j in range(len(labels)) if j != jt]
        if len(free) < len(channels):
            raise InputError(path, f"{len(free)} data column(s) for {len(channels)} channels "
                             f"{[c.name for c in channels]}")
        cols = free[:len(channels)]
    else:
        cols = [index(d.column(c.name, i), labels, c.name) for i, c in enumerate(channels)]
    values, units = [], []
    for c, j in zip(channels, cols):
        u, f = _si(path, c, labels[j], d.unit(c.name), t.units[j], line=t.first_line - 1
                   if d.header else None)
        units.append(u)
        values.append(t.columns[j] * f)
    time = start = None
    if jt is not None:
        time, start = _seconds(path, t.columns[jt], labels[jt], d.unit("time") or t.units[jt],
                               t.first_line, t.first_line - 1 if d.header else None)
    used = set(cols) | ({jt} if jt is not None else set())
    return Record(time, np.array(values), tuple(units), tuple(labels[j] for j in cols),
                  tuple(lab for j, lab in enumerate(labels) if j not in used), t.first_line,
                  start)


def _finite(path: Path, values: np.ndarray, labels: list[str]) -> None:
    bad = ~np.isfinite(values)
    if bad.any():
        i, k = np.argwhere(bad)[0]
        raise InputError(path, f"channel '{labels[i]}': non-finite value at sample {k}")


def _split_spec(spec: str | int, group: str) -> tuple[str, str]:
    spec = str(spec)
    if "/" in spec:
        g, _, name = spec.rpartition("/")
        return g, name
    return group, spec


def _read_tdms(path: Path, d: Dialect, channels: list[Channel]) -> Record:
    from nptdms import TdmsFile

    try:
        f = TdmsFile.read(path)
    except Exception as e:  # npTDMS raises several types for a damaged file
        raise InputError(path, f"not a readable TDMS file ({type(e).__name__}: {e})") from None
    groups = [g.name for g in f.groups()]

    def get(spec):
        g, name = _split_spec(spec, d.group or (groups[0] if len(groups) == 1 else ""))
        if g not in groups:
            raise InputError(path, f"no TDMS group '{g}' (groups: {groups}); declare group")
        names = [c.name for c in f[g].channels()]
        if name not in names:
            raise InputError(path, f"no channel '{name}' in TDMS group '{g}' (channels: {names})")
        ch = f[g][name]
        return f"{g}/{name}", ch[:], ch.properties.get("unit_string")

    def first_sample(labels):
        # a waveform channel's start (LabVIEW writes it in UTC), the first that has one
        for label in labels:
            g, _, name = label.rpartition("/")
            t0 = f[g][name].properties.get("wf_start_time")
            if t0 is not None:
                return np.datetime64(t0, "ns")
        return None

    return _binary(path, d, channels, get, first_sample)


def _read_hdf5(path: Path, d: Dialect, channels: list[Channel]) -> Record:
    import h5py

    try:
        f = h5py.File(path, "r")
    except OSError as e:
        raise InputError(path, f"not a readable HDF5 file ({e})") from None
    with f:
        def get(spec):
            g, name = _split_spec(spec, d.group)
            key = f"{g}/{name}" if g else name
            if key not in f or not isinstance(f[key], h5py.Dataset):
                raise InputError(path, f"no dataset '{key}' in the HDF5 file")
            u = f[key].attrs.get("units")
            return key, f[key][()], u.decode() if isinstance(u, bytes) else u

        def first_sample(labels):
            attrs = f[d.group].attrs if d.group and d.group in f else f.attrs
            return _start_attribute(path, dict(attrs))

        return _binary(path, d, channels, get, first_sample)


def _read_netcdf(path: Path, d: Dialect, channels: list[Channel]) -> Record:
    import xarray as xr

    try:
        ds = xr.open_dataset(path, group=d.group or None, decode_timedelta=False)
    except (OSError, ValueError) as e:
        raise InputError(path, f"not a readable netCDF file ({e})") from None
    with ds:
        def get(spec):
            name = str(spec)
            if name not in ds.variables:
                raise InputError(path, f"no variable '{name}' (variables: {list(ds.variables)})")
            v = ds[name]
            return name, v.values, v.attrs.get("units")

        return _binary(path, d, channels, get, lambda labels: _start_attribute(path, ds.attrs))


def _start_attribute(path: Path, attrs: dict) -> np.datetime64 | None:
    """The start a file or group attribute gives (:data:`START_ATTRIBUTES`), in UTC (a time
    without a zone is taken as UTC, as CF and ACDD say)."""
    for name in START_ATTRIBUTES:
        v = attrs.get(name)
        if v is not None:
            v = v.decode() if isinstance(v, bytes) else v
            return _instant(path, v, f"attribute '{name}'")[0]
    return None


def _binary(path: Path, d: Dialect, channels: list[Channel], get, first_sample=None) -> Record:
    """Channels through ``get(spec) -> (label, data, unit)``; ``first_sample(labels)`` gives the
    instant of the first sample that the file records beside the channels (datetime64, in
    UTC: TDMS ``wf_start_time``, an HDF5 or netCDF start attribute) or None."""
    values, units, labels = [], [], []
    for i, c in enumerate(channels):
        label, data, found = get(d.column(c.name, i))
        u, f = _si(path, c, label, d.unit(c.name), found)
        values.append(np.asarray(data, dtype=np.float64) * f)
        units.append(u)
        labels.append(label)
    n = {v.size for v in values}
    if len(n) > 1:
        raise InputError(path, f"channels {labels} have different lengths {sorted(n)}")
    values = np.array(values)
    _finite(path, values, labels)
    time = start = None
    if d.time != "rate":
        label, data, found = get(d.time)
        time, start = _seconds(path, np.asarray(data), label, d.unit("time") or found)
        labels_read = [*labels, label]
        if time.size != values.shape[1]:
            raise InputError(path, f"time '{label}' has {time.size} samples, the channels "
                             f"{values.shape[1]}")
    else:
        labels_read = labels
    if start is None and first_sample is not None:
        t0 = first_sample(labels_read)
        if t0 is not None:
            # the start is the instant of time 0; the first sample is at time[0]
            shift = 0 if time is None else int(round(float(time[0]) * 1e9))
            start = iso_instant(np.datetime64(t0, "ns") - np.timedelta64(shift, "ns"), True)
    return Record(time, values, tuple(units), tuple(labels), (), start=start)
