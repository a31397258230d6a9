"""Atomic netCDF writing with explicit encoding and the CF checks of flumekit.conventions.

Time coordinates are seconds since the start of the record (float64, ``units = "s"``), which
analysts can use directly; absolute instants, where known, are datetime64 variables whose CF
units are set in the encoding.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from flumekit import conventions
from flumekit.io.atomic import atomic_path


def _encoding(ds: xr.Dataset) -> dict[str, dict]:
    enc: dict[str, dict] = {}
    for name, var in {**ds.coords, **ds.data_vars}.items():
        e: dict = {}
        if var.dtype.kind == "f":
            e["dtype"] = "float64" if var.dtype == np.float64 else str(var.dtype)
            e["_FillValue"] = np.nan
            if var.ndim >= 1 and var.size > 4096:
                e.update(zlib=True, complevel=1)
        elif var.dtype.kind == "c":
            raise TypeError(f"variable '{name}' is complex: store real and imaginary parts")
        if np.issubdtype(var.dtype, np.datetime64):
            e.update(units="seconds since 1970-01-01T00:00:00", calendar="proleptic_gregorian")
        if e:
            enc[str(name)] = e
    return enc


def write_dataset(ds: xr.Dataset, path: str | Path) -> Path:
    """Check CF attributes and write ``ds`` to ``path`` atomically (temporary file, then rename).

    A failure at any point leaves no file at ``path`` (nor a temporary one behind).
    """
    path = Path(path)
    ds = conventions.annotate(ds)
    conventions.check(ds)
    missing = [a for a in ("Conventions", "title", "source", "history") if a not in ds.attrs]
    if missing:
        raise ValueError(f"{path}: dataset lacks global attributes {missing}")
    with atomic_path(path) as tmp:
        ds.to_netcdf(tmp, engine="netcdf4", encoding=_encoding(ds))
    return path


def write_product(ds: xr.Dataset, path: str | Path, title: str, source: str,
                  parameters: dict | None = None) -> Path:
    """Write a product of flumekit: the global attributes of
    :func:`flumekit.conventions.global_attrs` (title, source, history with the parameters) set
    on ``ds``, then :func:`write_dataset`."""
    ds.attrs.update(conventions.global_attrs(title, source, parameters))
    return write_dataset(ds, path)


def read_dataset(path: str | Path) -> xr.Dataset:
    """Open a flumekit netCDF file fully into memory (the file is closed on return)."""
    with xr.open_dataset(path, engine="netcdf4") as ds:
        return ds.load()
