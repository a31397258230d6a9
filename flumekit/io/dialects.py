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

from flumekit.docstrings import doc
from flumekit.errors import InputError
from flumekit.units import UNITS


@dataclass(frozen=True)
class Dialect:
    """How an instrument file is written. Defaults: the raw campaign's own CSV format.

    The keys of ``[files.<instrument>]`` in campaign.toml (raw/README.md); each field's
    comment says what it holds.

    Examples
    --------
    >>> d = Dialect.from_dict({"delimiter": ";", "decimal": ",", "units": {"pressure": "kPa"}})
    >>> d.delimiter, d.unit("pressure"), d.unit("encoder"), d.column("encoder", 0)
    (';', 'kPa', None, 'encoder')
    """

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
    encoding: str = "utf-8"  # csv: text encoding (a UTF-8 byte-order mark is always accepted)
    timezone: str = ""  # csv, date-time stamps without an offset: IANA zone they are in

    @classmethod
    def from_dict(cls, d: dict | None) -> Dialect:
        """Make a dialect from a campaign's table; keys that are no field are ignored."""
        names = {f.name for f in fields(cls)}
        return cls(**{k: v for k, v in (d or {}).items() if k in names})

    @property
    def declares_columns(self) -> bool:
        """Whether the dialect maps channels to columns."""
        return self.columns is not None

    def column(self, channel: str, index: int) -> str | int:
        """Return the column (name or 1-based number) of the ``index``-th channel ``channel``."""
        if isinstance(self.columns, dict):
            return self.columns.get(channel, channel)
        if isinstance(self.columns, list):
            return self.columns[index]
        return channel

    def unit(self, channel: str) -> str | None:
        """Return the unit the dialect declares for ``channel``, or None."""
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
    # the sample interval the file itself records beside the channels [s] (TDMS
    # wf_increment), and where it says so; None when it does not
    step: float | None = None
    step_label: str = ""


#: file or group attributes that give the start of a record (HDF5, netCDF; ISO 8601)
START_ATTRIBUTES = ("record_start", "time_coverage_start", "start_time")


def read_channels(path: str | Path, dialect: Dialect, channels: list[Channel],
                  strict: str = "") -> Record:
    r"""Read ``channels`` from ``path`` as ``dialect`` says; convert to SI, check units.

    A file whose first bytes prove another format than the declared one is an error naming
    the real format (a CSV declaration pointing at an HDF5 file).

    Parameters
    ----------
    path : str or pathlib.Path
        The instrument file.
    dialect : Dialect
        How it is written.
    channels : list of Channel
        The channels to read, in order.
    strict : str, optional
        An instrument name, for the message: when the dialect does not map columns to
        channels, a text file's columns must be exactly the channels and time (the raw
        campaign's own format names every column; another is a typo or a wrong file).

    Returns
    -------
    Record
        The channels' values in SI units (channel, sample), the time [s] (None when the
        dialect takes it from the sampling rate), the units recorded, and the record's start
        where the file gives it.

    Raises
    ------
    flumekit.errors.InputError
        Naming the file (and line, column or channel) for a missing or unreadable file,
        another format than declared, a missing column, a unit that is unknown or of the
        wrong quantity, a non-finite value or channels of different lengths.

    Examples
    --------
    A pressure recorded in kPa is returned in Pa:

    >>> import tempfile
    >>> from flumekit.io.tables import write_table
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     f = write_table(Path(folder) / "flap.csv", [("time", "s"), ("pressure", "kPa")],
    ...                     [[0.0, 1.5], [0.01, 2.0]], fmt="%g")
    ...     rec = read_channels(f, Dialect(), [Channel("pressure", "pressure")])
    >>> rec.values, rec.units, rec.time
    (array([[1500., 2000.]]), ('kPa',), array([0.  , 0.01]))
    """
    path = Path(path)
    if not path.exists():
        raise InputError(path, "file not found")
    if path.is_dir():
        raise InputError(path, "is a folder, not a file")
    reader = {"csv": _read_csv, "tdms": _read_tdms, "hdf5": _read_hdf5,
              "netcdf": _read_netcdf}.get(dialect.format)
    if reader is None:
        raise InputError(path, f"unknown format {dialect.format!r}; known: csv, tdms, hdf5, "
                         "netcdf")
    with open(path, "rb") as f:
        head = f.read(8)
    for sig, what in FOREIGN:
        if head.startswith(sig):
            raise InputError(path, f"this is {what}, which no dialect reads: export the record "
                             "as CSV text (or TDMS, HDF5, netCDF)")
    real = sniff_format(path)
    if real is not None and real != dialect.format and {real, dialect.format} != {"hdf5",
                                                                                 "netcdf"}:
        raise InputError(path, f"this is a{'n' if real[0] in 'h' else ''} {FORMAT_NAMES[real]} "
                         f"file, but its dialect declares format = {dialect.format!r}: declare "
                         f'format = "{real}" in [files.<instrument>] of campaign.toml')
    if strict and dialect.format == "csv" and not dialect.declares_columns and dialect.header:
        from flumekit.io.tables import header_labels

        labels = header_labels(path, delimiter=dialect.delimiter, comment=dialect.comment,
                               skip_lines=dialect.skip_lines, encoding=dialect.encoding)
        names = [c.name for c in channels]
        unknown = [x for x in labels if x not in names and x != dialect.time]
        if unknown:
            raise InputError(path, f"unknown {strict} column(s) {unknown}; expected {names}")
    return reader(path, dialect, channels)


#: the first bytes of each binary format (an HDF5 signature is also a netCDF-4 file's)
SIGNATURES = ((b"\x89HDF\r\n\x1a\n", "hdf5"), (b"TDSm", "tdms"), (b"TDSh", "tdms"),
              (b"CDF\x01", "netcdf"), (b"CDF\x02", "netcdf"), (b"CDF\x05", "netcdf"))
FORMAT_NAMES = {"hdf5": "HDF5 (or netCDF-4)", "tdms": "TDMS (LabVIEW)",
                "netcdf": "netCDF (classic)", "csv": "text"}
#: first bytes of files no dialect reads, and what they are
FOREIGN = ((b"PK\x03\x04", "a ZIP archive (an Excel .xlsx workbook?)"),
           (b"\xd0\xcf\x11\xe0", "an Office document (an Excel .xls workbook?)"),
           (b"\x1f\x8b", "a gzip-compressed file"))


@doc
def sniff_format(path: Path) -> str | None:
    r"""Return the format a file's first bytes prove (:data:`SIGNATURES`), or None.

    Parameters
    ----------
    %(path)s

    Returns
    -------
    str or None
        ``"hdf5"`` (also netCDF-4), ``"tdms"`` or ``"netcdf"`` (classic); None for text and
        anything else.

    Examples
    --------
    An HDF5 file saved under a ``.csv`` name is still HDF5:

    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     f = Path(folder) / "run.csv"
    ...     _ = f.write_bytes(b"\x89HDF\r\n\x1a\n" + bytes(8))
    ...     sniff_format(f), sniff_format(Path(__file__))
    ('hdf5', None)
    """
    with open(path, "rb") as f:
        head = f.read(8)
    for sig, fmt in SIGNATURES:
        if head.startswith(sig):
            return fmt
    return None


def _si(path: Path, ch: Channel, label: str, declared: str | None, found: str | None,
        line: int | None = None) -> tuple[str, float]:
    """Return a channel's unit (declared > found in the file > the channel's default), checked."""
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
    """Format an instant as ISO 8601, to the nanosecond it holds.

    Parameters
    ----------
    t : numpy.datetime64 or str
        The instant.
    utc : bool
        Whether it is in UTC (then the text ends in ``Z``).

    Returns
    -------
    str
        ISO 8601, trailing zeros of the fraction dropped.

    Examples
    --------
    >>> iso_instant(np.datetime64("2024-03-05T10:12:01.500"), True)
    '2024-03-05T10:12:01.5Z'
    """
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


#: an ISO 8601 date-time ending in a UTC offset or Z
_OFFSET = re.compile(r"\d[T ]\d{2}:\d{2}(?::\d{2}(?:\.\d*)?)?\s*(?:Z|[+-]\d{2}:?\d{2})$")


def _seconds(path: Path, values: np.ndarray, label: str, unit: str | None,
             first_line: int | None = None, header_line: int | None = None,
             utc: bool = True, timezone: str = "", line_of=None) -> tuple[np.ndarray, str | None]:
    """Convert a time column to seconds, with the record's start when the column gives it.

    The start is the instant of time 0 (ISO 8601). Datetimes count from the first (which is
    the start; ``utc`` says whether datetime64 values are UTC), numbers are in ``unit`` or in
    CF units ``<unit> since <instant>`` (then the start is that instant).

    Text stamps with a UTC offset (ISO 8601, ``2024-03-31T01:59:59.96+01:00``) are read in
    UTC, whatever offsets they mix (a daylight-saving change); stamps without one are the
    logger's clock, or local time in the IANA zone ``timezone`` when one is declared (then
    converted to UTC, a repeated hour resolved by the stamps' order). ``line_of(k)`` gives the
    file line of row ``k`` (for messages; default ``first_line + k``).
    """
    import pandas as pd

    if line_of is None:
        def line_of(k):
            return None if first_line is None else first_line + k

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
    zoned = s.str.contains(_OFFSET)
    if zoned.any() and not zoned.all():
        k = int(np.flatnonzero(~zoned.to_numpy() if zoned.iloc[0] else zoned.to_numpy())[0])
        raise InputError(path, f"time column '{label}': {s.iloc[k]!r} "
                         + ("has no UTC offset, the stamps before it have one" if zoned.iloc[0]
                            else "has a UTC offset, the stamps before it have none"),
                         line=line_of(k))
    if zoned.all() and timezone:
        raise InputError(path, f"time column '{label}': the stamps give their UTC offset; "
                         f"remove timezone = {timezone!r} from the file's dialect")
    try:
        dt = pd.to_datetime(s, errors="raise", format="mixed", utc=bool(zoned.all()))
    except (ValueError, TypeError):
        dt = pd.to_datetime(s, errors="coerce", format="mixed", utc=bool(zoned.all()))
        bad = int(np.flatnonzero(dt.isna().to_numpy())[0]) if dt.isna().any() else 0
        raise InputError(path, f"time column '{label}': {s.iloc[bad]!r} is neither a number nor"
                         " a date and time", line=line_of(bad)) from None
    if timezone:
        dt = _localise(path, dt, label, timezone, s, line_of)
    # stamps with a UTC offset are read in UTC; without one, in the logger's own clock
    return _seconds(path, dt.dt.tz_localize(None).to_numpy(dtype="datetime64[ns]")
                    if dt.dt.tz is not None else dt.to_numpy(dtype="datetime64[ns]"),
                    label, unit, utc=dt.dt.tz is not None)


def _localise(path: Path, dt, label: str, timezone: str, s, line_of):
    """Put naive local stamps in the IANA zone ``timezone`` on UTC.

    An hour repeated when the clocks go back is told apart by the stamps' order; a stamp in
    the hour skipped when they go forward is an error naming its line.
    """
    import zoneinfo

    try:
        zoneinfo.ZoneInfo(timezone)
    except (zoneinfo.ZoneInfoNotFoundError, ValueError):
        raise InputError(path, f"unknown time zone {timezone!r}: an IANA name such as "
                         "'Europe/Lisbon' or 'America/Montevideo'", field="timezone") from None
    try:
        local = dt.dt.tz_localize(timezone, ambiguous="infer", nonexistent="NaT")
    except Exception as e:  # pytz/pandas raise their own types for an unresolvable hour
        raise InputError(path, f"time column '{label}': local stamps in {timezone} cannot be "
                         f"put on UTC ({e}); write them with their UTC offset") from None
    if local.isna().any():
        k = int(np.flatnonzero(local.isna().to_numpy())[0])
        raise InputError(path, f"time column '{label}': {s.iloc[k]!r} does not exist in "
                         f"{timezone} (the hour skipped when the clocks go forward)",
                         line=line_of(k))
    return local.dt.tz_convert("UTC")


def _read_csv(path: Path, d: Dialect, channels: list[Channel]) -> Record:
    from flumekit.io.tables import data_line, header_labels, read_text

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
                         skip_lines=d.skip_lines, header=d.header, encoding=d.encoding)
    jt = None if d.time == "rate" else index(d.time, head, "time")
    kw = dict(delimiter=d.delimiter, decimal=d.decimal, comment=d.comment,
              skip_lines=d.skip_lines, header=d.header, encoding=d.encoding)
    t = None
    if jt is not None:
        # a time column of numbers (the usual case) is parsed by pandas' C parser with the
        # others; the text path (datetimes, and the messages naming a bad time cell) only
        # when that fails: parsing a column as text and converting it costs several times
        # the whole numeric read
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
        def line_of(k):
            return data_line(path, t.first_line, k, comment=d.comment, encoding=d.encoding)

        time, start = _seconds(path, t.columns[jt], labels[jt], d.unit("time") or t.units[jt],
                               t.first_line, t.first_line - 1 if d.header else None,
                               timezone=d.timezone, line_of=line_of)
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
    """Read channels of a LabVIEW TDMS file.

    A waveform channel's own timing (``wf_increment`` [s], ``wf_start_time`` in UTC) is
    trusted and checked: the channels read must agree on both, the caller checks the
    increment against the declared rate (:attr:`Record.step`), and where the dialect leaves
    the time at its default and the group has no ``time`` channel, the increment gives the
    time.
    """
    import dataclasses

    from nptdms import TdmsFile

    try:
        f = TdmsFile.read(path)
    except Exception as e:  # npTDMS raises several types for a damaged file
        raise InputError(path, f"not a readable TDMS file ({type(e).__name__}: {e})") from None
    groups = [g.name for g in f.groups()]
    default_group = d.group or (groups[0] if len(groups) == 1 else "")

    def get(spec):
        g, name = _split_spec(spec, default_group)
        if g not in groups:
            raise InputError(path, f"no TDMS group '{g}' (groups: {groups}); declare group")
        names = [c.name for c in f[g].channels()]
        if name not in names:
            raise InputError(path, f"no channel '{name}' in TDMS group '{g}' (channels: {names})")
        ch = f[g][name]
        return f"{g}/{name}", ch[:], ch.properties.get("unit_string")

    def prop(label, key):
        g, _, name = label.rpartition("/")
        return f[g][name].properties.get(key)

    def first_sample(labels):
        # a waveform channel's start (LabVIEW writes it in UTC), the first that has one
        for label in labels:
            t0 = prop(label, "wf_start_time")
            if t0 is not None:
                return np.datetime64(t0, "ns")
        return None

    # the default time channel absent, the waveform channels' increment gives the time
    wanted = [_split_spec(d.column(c.name, i), default_group) for i, c in enumerate(channels)]
    own_time = False
    if d.time == "time":
        g, name = _split_spec("time", default_group)
        has_time = g in groups and name in [c.name for c in f[g].channels()]
        own_time = not has_time and all(
            g in groups and n in [c.name for c in f[g].channels()]
            and f[g][n].properties.get("wf_increment") is not None for g, n in wanted)
    rec = _binary(path, dataclasses.replace(d, time="rate") if own_time else d, channels, get,
                  first_sample)
    steps = {label: prop(label, "wf_increment") for label in rec.labels}
    given = {k: float(v) for k, v in steps.items() if v is not None}
    if len(set(given.values())) > 1:
        raise InputError(path, "the channels' wf_increment disagree: " + ", ".join(
            f"{k} {v:g} s" for k, v in given.items()) + ": they are not one record")
    starts = {label: prop(label, "wf_start_time") for label in rec.labels}
    starts = {k: np.datetime64(v, "ns") for k, v in starts.items() if v is not None}
    if len(set(starts.values())) > 1:
        raise InputError(path, "the channels' wf_start_time disagree: " + ", ".join(
            f"{k} {iso_instant(v, True)}" for k, v in starts.items())
            + ": they are not one record")
    if not given:
        return rec
    label, step = next(iter(given.items()))
    if step <= 0 or not np.isfinite(step):
        raise InputError(path, f"channel '{label}': wf_increment = {step!r} is not a sample "
                         "interval")
    if own_time:
        rec = dataclasses.replace(rec, time=np.arange(rec.values.shape[1]) * step)
    return dataclasses.replace(rec, step=step, step_label=f"{label} wf_increment")


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
    """Return the start a file or group attribute gives (:data:`START_ATTRIBUTES`), in UTC.

    A time without a zone is taken as UTC, as CF and ACDD say.
    """
    for name in START_ATTRIBUTES:
        v = attrs.get(name)
        if v is not None:
            v = v.decode() if isinstance(v, bytes) else v
            return _instant(path, v, f"attribute '{name}'")[0]
    return None


def _samples(path: Path, label: str, data, ch: Channel, unit: str) -> np.ndarray:
    """Return a binary file's channel as float64 samples, its shape and dtype checked.

    One dimension ((n, 1) and (1, n) are squeezed), numbers; integers only for a channel in
    counts (a voltage written as integers is a logger's raw ADC counts, which no declared unit
    converts).
    """
    data = np.asarray(data)
    expected = (f"expected one dataset per channel of shape (n,) holding {ch.quantity}s "
                f"[{unit}] as " + ("integers or floats" if ch.quantity == "count"
                                   else "floating-point numbers"))
    if data.dtype.kind == "V":
        fields_ = list(data.dtype.names or ())
        raise InputError(path, f"'{label}' is a compound dataset (fields {fields_}), dtype "
                         f"{data.dtype}; {expected}", field=ch.name)
    if data.dtype.kind in "SUOb":
        raise InputError(path, f"'{label}' holds {'text' if data.dtype.kind != 'b' else 'booleans'}"
                         f" (dtype {data.dtype}); {expected}", field=ch.name)
    if data.ndim == 2 and 1 in data.shape:
        data = data.reshape(-1)
    if data.ndim != 1:
        hint = (f" (it holds {data.shape[1]} columns: all channels in one dataset? write one "
                "dataset per channel)" if data.ndim == 2 else "")
        raise InputError(path, f"'{label}' has shape {data.shape}; {expected}{hint}",
                         field=ch.name)
    if data.dtype.kind in "iu" and ch.quantity != "count":
        raise InputError(path, f"'{label}' holds integers (dtype {data.dtype}), but it is a "
                         f"{ch.quantity} in [{unit}]: raw ADC counts? Convert them with the "
                         f"logger's gain and write floating-point {ch.quantity}s; {expected}",
                         field=ch.name)
    if data.dtype.kind not in "fiu":
        raise InputError(path, f"'{label}' has dtype {data.dtype}; {expected}", field=ch.name)
    return data.astype(np.float64)


def _binary(path: Path, d: Dialect, channels: list[Channel], get, first_sample=None) -> Record:
    """Read channels through ``get(spec) -> (label, data, unit)``.

    ``first_sample(labels)`` gives the instant of the first sample that the file records
    beside the channels (datetime64, in UTC: TDMS ``wf_start_time``, an HDF5 or netCDF start
    attribute) or None.
    """
    values, units, labels = [], [], []
    for i, c in enumerate(channels):
        label, data, found = get(d.column(c.name, i))
        u, f = _si(path, c, label, d.unit(c.name), found)
        values.append(_samples(path, label, data, c, u) * f)
        units.append(u)
        labels.append(label)
    n = {v.size for v in values}
    if len(n) > 1:
        longest = max(n)
        short = [f"'{lab}' {v.size}" for lab, v in zip(labels, values) if v.size < longest]
        raise InputError(path, f"channels of one record have different lengths: {short} "
                         f"samples, the others {longest}: a record cut short (truncated "
                         "file?) or channels of another record")
    values = np.array(values)
    _finite(path, values, labels)
    time = start = None
    if d.time != "rate":
        label, data, found = get(d.time)
        data = np.asarray(data)
        if data.ndim == 2 and 1 in data.shape:
            data = data.reshape(-1)
        if data.ndim != 1 or data.dtype.kind == "V":
            raise InputError(path, f"time '{label}' has shape {data.shape} and dtype "
                             f"{data.dtype}: expected shape ({values.shape[1]},), numbers or "
                             "date-times")
        if data.dtype.kind == "S" or (data.dtype.kind == "O" and data.size
                                      and isinstance(data.flat[0], bytes)):
            data = np.char.decode(data.astype("S"), "utf-8") if data.size else data
        time, start = _seconds(path, data, label, d.unit("time") or found)
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
