"""One reader per instrument, from its file in any declared dialect to CF-annotated xarray.

The declarative part is :data:`CHANNELS`: what each instrument records (channel, physical
quantity, default unit). Where and how a file is written is its :class:`Dialect`
(``[files.<instrument>]`` of campaign.toml, raw/README.md); the default is the raw campaign's
own CSV:

* ``calibration/probes.csv``: static submersions, ``level [m]`` then one voltage column per probe;
* ``runs/<run>/probes.csv``: ``time [s]`` then one column per probe (voltages, or lengths when the
  probes are already calibrated);
* ``runs/<run>/flap.csv``: ``time [s]``, ``encoder [counts]``, ``pressure [<pressure unit>]``.

The readers are pure (a file in, a dataset out) so that quality control and analysis stages can
both call them. A declared clock offset [s] is added to the time stamps and recorded.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from flumekit import conventions
from flumekit.docstrings import filler
from flumekit.errors import InputError
from flumekit.io.dialects import Channel, Dialect, Record, read_channels
from flumekit.io.tables import check_time
from flumekit.units import UNITS

#: docstring text that several functions of this module share
_doc = filler(
    dialect=("dialect : Dialect or dict, optional\n"
             "    How the file is written (default: the raw campaign's CSV)."),
    probes=("probes : tuple of str\n"
            "    Probe names, in the campaign's order."),
    time_offset=("time_offset : float, optional\n"
                 "    Declared clock offset [s], added to the time stamps and recorded."))


def _probe_channels(probes: tuple[str, ...], units: str) -> list[Channel]:
    return [Channel(p, UNITS[units][0], units) for p in probes]


#: instrument -> its channels (probes: one per probe name, see :func:`read_probes`)
CHANNELS = {
    "flap": [Channel("encoder", "count", "counts"), Channel("pressure", "pressure")],
}
#: the flap record's channels -> the variables of :func:`read_flap`'s dataset
FLAP_VARIABLES = {"encoder": "encoder_counts", "pressure": "chamber_pressure"}


def _dialect(dialect: Dialect | dict | None) -> Dialect:
    return dialect if isinstance(dialect, Dialect) else Dialect.from_dict(dialect)


def _read(path: Path, dialect: Dialect, channels: list[Channel], what: str) -> Record:
    return read_channels(path, dialect, channels, strict=what)


def _time(path: Path, rec: Record, sampling_rate: float, time_offset: float) -> np.ndarray:
    n = rec.values.shape[1]
    if rec.step is not None and abs(rec.step * sampling_rate - 1.0) > 0.01:
        # the file's own sample interval is the truth about its samples: a declared rate that
        # contradicts it would stretch the record's time axis
        raise InputError(path, f"{rec.step_label} is {rec.step:g} s ({1 / rec.step:g} Hz), but "
                         f"the campaign declares a sampling rate of {sampling_rate:g} Hz "
                         f"({1 / sampling_rate:g} s): correct sampling_rate in campaign.toml or"
                         " check that this is the right file")
    if rec.time is None:
        if n < 2:
            raise InputError(path, "fewer than two samples")
        time = np.arange(n) / sampling_rate
    else:
        time = rec.time
        check_time(path, time, sampling_rate, rec.first_line)
    return time + time_offset


def _dataset(data_vars: dict, coords: dict, path: Path, rec: Record, sampling_rate: float,
             time_offset: float) -> xr.Dataset:
    """Build the instrument's dataset, CF-annotated.

    The record's start, where the file gives it, goes on the time coordinate
    (``record_start``: the instant of time 0 before the clock offset).
    """
    ds = conventions.annotate(xr.Dataset(data_vars, coords=coords,
                                         attrs=_attrs(path, rec, sampling_rate, time_offset)))
    if rec.start is not None:
        ds["time"].attrs[conventions.RECORD_START] = rec.start
    return ds


def _attrs(path: Path, rec: Record, sampling_rate: float, time_offset: float) -> dict:
    return {"source_file": str(path), "sampling_rate": sampling_rate,
            "time_offset": time_offset,
            "time_offset_comment": "declared clock offset [s] added to the file's time stamps",
            "recorded_units": ", ".join(f"{c} [{u}]" for c, u in zip(rec.labels, rec.units))}


@_doc
def read_calibration(path: str | Path, probes: tuple[str, ...],
                     dialect: Dialect | dict | None = None) -> xr.Dataset:
    r"""Read a static calibration: each probe's voltage at known water levels.

    Parameters
    ----------
    path : str or pathlib.Path
        The calibration file (``calibration/probes.csv`` of a raw campaign): ``level [m]``,
        the still-water level of each static submersion relative to the test's still-water
        level, then one voltage column per probe.
    %(probes)s
    dialect : Dialect or dict, optional
        How the file is written (default: the raw campaign's CSV); a calibration file has no
        time column.

    Returns
    -------
    xarray.Dataset
        ``calibration_voltage`` [V], dims (sample, probe), with the coordinate ``level`` [m]
        along ``sample``.

    Raises
    ------
    flumekit.errors.InputError
        When the file is missing or unreadable, a unit is not a voltage (a length for
        ``level``), or fewer than two distinct levels were recorded.

    Examples
    --------
    A file in the raw campaign's format, as :func:`flumekit.io.tables.write_table` writes it:

    >>> import tempfile
    >>> from flumekit.io.tables import write_table
    >>> levels = [[-0.05, 0.5], [0.0, 1.0], [0.05, 1.5]]  # level [m], WP1 [V]
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     f = write_table(Path(folder) / "probes.csv", [("level", "m"), ("WP1", "V")], levels)
    ...     cal = read_calibration(f, ("WP1",))
    >>> cal["calibration_voltage"].values.ravel(), cal["level"].values
    (array([0.5, 1. , 1.5]), array([-0.05,  0.  ,  0.05]))
    """
    path = Path(path)
    d = _dialect(dialect)
    if d.time == "time":  # a calibration file has no time column
        d = Dialect(**{**d.__dict__, "time": "rate"})
    channels = [Channel("level", "length", "m"), *_probe_channels(probes, "V")]
    rec = _read(path, d, channels, "probe")
    levels = rec.values[0]
    if np.unique(levels).size < 2:
        raise InputError(path, "calibration needs at least two distinct levels")
    ds = xr.Dataset(
        {"calibration_voltage": (("sample", "probe"), rec.values[1:].T)},
        coords={"level": ("sample", levels), "probe": list(probes)},
        attrs={"source_file": str(path)})
    return conventions.annotate(ds)


@_doc
def read_probes(path: str | Path, probes: tuple[str, ...], sampling_rate: float,
                dialect: Dialect | dict | None = None, *, units: str = "V",
                time_offset: float = 0.0) -> xr.Dataset:
    r"""Read a run's wave probe records.

    Parameters
    ----------
    path : str or pathlib.Path
        The run's probe file.
    %(probes)s
    sampling_rate : float
        Declared sampling rate [Hz]: checked against a time column (or a TDMS waveform's own
        increment), or the time axis when the dialect has none.
    %(dialect)s
    units : str, optional
        Unit of channels whose unit the file does not state: a voltage unit gives
        ``probe_voltage`` [V] (to calibrate), a length unit ``probe_elevation`` [m]
        (calibrated, still-water level not yet removed).
    %(time_offset)s

    Returns
    -------
    xarray.Dataset
        ``probe_voltage`` [V] or ``probe_elevation`` [m], dims (probe, time), time [s] from
        the record's start; the record's start instant, where the file gives it, in the time
        coordinate's ``record_start``.

    Raises
    ------
    flumekit.errors.InputError
        When the file is missing or unreadable, a column or unit is missing or wrong, the time
        stamps are irregular or contradict ``sampling_rate``, or a value is not finite; the
        message names the file, and the line or column where it can.

    Examples
    --------
    Two probes sampled at 100 Hz, written as the virtual flume writes them:

    >>> import tempfile
    >>> from flumekit.io.tables import write_table
    >>> t = np.arange(3) / 100.0
    >>> columns = [("time", "s"), ("WP1", "V"), ("WP2", "V")]
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     f = write_table(Path(folder) / "probes.csv", columns, np.c_[t, 1 + t, 2 - t])
    ...     ds = read_probes(f, ("WP1", "WP2"), sampling_rate=100.0)
    >>> ds["probe_voltage"].dims, ds["probe_voltage"].values[1], ds["time"].values
    (('probe', 'time'), array([2.  , 1.99, 1.98]), array([0.  , 0.01, 0.02]))
    """
    path = Path(path)
    d = _dialect(dialect)
    quantity = UNITS[units][0]
    if quantity not in ("voltage", "length"):
        raise InputError(path, f"probe channels are voltages or lengths, not [{units}]")
    rec = _read(path, d, _probe_channels(probes, units), "probe")
    time = _time(path, rec, sampling_rate, time_offset)
    name = "probe_voltage" if quantity == "voltage" else "probe_elevation"
    return _dataset({name: (("probe", "time"), rec.values)},
                    {"probe": list(probes), "time": time}, path, rec, sampling_rate, time_offset)


@_doc
def read_flap(path: str | Path, sampling_rate: float, dialect: Dialect | dict | None = None, *,
              time_offset: float = 0.0) -> xr.Dataset:
    r"""Read a run's flap record: encoder counts and the cylinder chamber's gauge pressure.

    Parameters
    ----------
    path : str or pathlib.Path
        The run's flap file (``time [s]``, ``encoder [counts]``, ``pressure [<unit>]`` in the
        raw campaign's CSV).
    sampling_rate : float
        Declared sampling rate [Hz], checked as :func:`read_probes` checks it.
    %(dialect)s
    %(time_offset)s

    Returns
    -------
    xarray.Dataset
        ``encoder_counts`` (integers) and ``chamber_pressure`` [Pa], dim time [s].

    Raises
    ------
    flumekit.errors.InputError
        As :func:`read_probes`, and when an encoder count is not a whole number.

    Examples
    --------
    >>> import tempfile
    >>> from flumekit.io.tables import write_table
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     f = write_table(Path(folder) / "flap.csv",
    ...                     [("time", "s"), ("encoder", "counts"), ("pressure", "kPa")],
    ...                     [[0.0, 0, 1.0], [0.01, 3, 1.2]], fmt=["%.2f", "%d", "%.1f"])
    ...     ds = read_flap(f, sampling_rate=100.0)
    >>> ds["encoder_counts"].values, ds["chamber_pressure"].values
    (array([0, 3]), array([1000., 1200.]))
    """
    path = Path(path)
    d = _dialect(dialect)
    rec = read_channels(path, d, CHANNELS["flap"], strict="flap")
    time = _time(path, rec, sampling_rate, time_offset)
    counts = rec.values[0]
    if np.any(counts != np.round(counts)):
        raise InputError(path, "encoder counts must be integers", field="encoder")
    return _dataset({FLAP_VARIABLES["encoder"]: ("time", counts.astype(np.int64)),
                     FLAP_VARIABLES["pressure"]: ("time", rec.values[1])},
                    {"time": time}, path, rec, sampling_rate, time_offset)
