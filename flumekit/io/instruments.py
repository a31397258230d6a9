"""Readers of the raw campaign's instrument files, returning CF-annotated xarray objects.

One function per instrument file (raw/README.md):

* ``calibration/probes.csv``: static submersions, ``level [m]`` then one voltage column per probe;
* ``runs/<run>/probes.csv``: ``time [s]`` then one voltage column per probe, 25 Hz;
* ``runs/<run>/flap.csv``: ``time [s]``, ``encoder [counts]``, ``pressure [<pressure unit>]``,
  100 Hz.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from flumekit import conventions
from flumekit.errors import InputError
from flumekit.io.tables import Column, check_time, read_table


def _require(path: Path, cols: list[Column], name: str, quantity: str) -> int:
    for j, c in enumerate(cols):
        if c.name == name:
            if c.quantity != quantity:
                raise InputError(path, f"column '{name}' has unit [{c.unit}], expected a "
                                 f"{quantity} unit", field=name)
            return j
    raise InputError(path, f"missing column '{name}' (columns: {[c.name for c in cols]})")


def _probe_columns(path: Path, cols: list[Column], probes: tuple[str, ...],
                   first: str) -> list[int]:
    known = {first, *probes}
    unknown = [c.name for c in cols if c.name not in known]
    if unknown:
        raise InputError(path, f"unknown probe column(s) {unknown}; the campaign declares "
                         f"{list(probes)}")
    return [_require(path, cols, p, "voltage") for p in probes]


def read_calibration(path: str | Path, probes: tuple[str, ...]) -> xr.Dataset:
    """Static calibration: voltage of each probe at known water levels (relative to still water)."""
    path = Path(path)
    cols, data = read_table(path)
    jl = _require(path, cols, "level", "length")
    jp = _probe_columns(path, cols, probes, "level")
    levels = data[:, jl]
    if np.unique(levels).size < 2:
        raise InputError(path, "calibration needs at least two distinct levels")
    ds = xr.Dataset(
        {"calibration_voltage": (("sample", "probe"), data[:, jp])},
        coords={"level": ("sample", levels), "probe": list(probes)},
        attrs={"source_file": str(path)})
    return conventions.annotate(ds)


def read_probes(path: str | Path, probes: tuple[str, ...], sampling_rate: float) -> xr.Dataset:
    """Wave probe voltages, dims (probe, time)."""
    path = Path(path)
    cols, data = read_table(path)
    jt = _require(path, cols, "time", "time")
    jp = _probe_columns(path, cols, probes, "time")
    time = data[:, jt]
    check_time(path, time, sampling_rate)
    ds = xr.Dataset({"probe_voltage": (("probe", "time"), data[:, jp].T)},
                    coords={"probe": list(probes), "time": time},
                    attrs={"source_file": str(path), "sampling_rate": sampling_rate})
    return conventions.annotate(ds)


def read_flap(path: str | Path, sampling_rate: float) -> xr.Dataset:
    """Encoder counts and cylinder chamber gauge pressure [Pa], dim time."""
    path = Path(path)
    cols, data = read_table(path)
    jt = _require(path, cols, "time", "time")
    je = _require(path, cols, "encoder", "count")
    jp = _require(path, cols, "pressure", "pressure")
    extra = {c.name for c in cols} - {"time", "encoder", "pressure"}
    if extra:
        raise InputError(path, f"unexpected column(s) {sorted(extra)}")
    time = data[:, jt]
    check_time(path, time, sampling_rate)
    counts = data[:, je]
    if np.any(counts != np.round(counts)):
        raise InputError(path, "encoder counts must be integers", field="encoder")
    ds = xr.Dataset({"encoder_counts": ("time", counts.astype(np.int64)),
                     "chamber_pressure": ("time", data[:, jp])},
                    coords={"time": time},
                    attrs={"source_file": str(path), "sampling_rate": sampling_rate})
    return conventions.annotate(ds)
