"""Atomic netCDF writing with explicit encoding and the CF checks of flumekit.conventions.

Time coordinates are seconds since the start of the record (float64): ``units = "s"`` in
memory, ``seconds since <record start>`` in the file (CF 4.4), which :func:`read_dataset` reads
back as plain seconds; absolute instants, where known, are datetime64 variables whose CF units
are set in the encoding.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from flumekit import conventions
from flumekit.docstrings import filler
from flumekit.io.atomic import Written, atomic_path

#: docstring text that several functions of this module share
_doc = filler(
    netcdf_path=("path : str or pathlib.Path\n"
                 "    The netCDF-4 file to write."))


def _encoding(ds: xr.Dataset, compress: bool = True) -> dict[str, dict]:
    enc: dict[str, dict] = {}
    for name, var in {**ds.coords, **ds.data_vars}.items():
        e: dict = {}
        if var.dtype.kind == "f":
            e["dtype"] = "float64" if var.dtype == np.float64 else str(var.dtype)
            # CF 2.5.1: a coordinate variable must not have a _FillValue
            e["_FillValue"] = None if name in ds.dims else np.nan
            if compress and var.ndim >= 1 and var.size > 4096:
                e.update(zlib=True, complevel=1)
        elif var.dtype.kind in "iu" and var.dtype.itemsize == 8:
            # CF 1.8 knows no 64-bit integers; counts and indices fit in 32 bits
            info = np.iinfo(np.int32)
            if var.size == 0 or (info.min <= var.values.min() and var.values.max() <= info.max):
                e["dtype"] = "int32"
            if name in ds.dims:
                e["_FillValue"] = None
        elif var.dtype.kind in "USO":
            # variable-length strings: a width taken from the encoding of the first file read
            # (a run name 'run1') would cut every longer name of a summary ('run10' -> 'run1')
            e["dtype"] = str
        elif var.dtype.kind == "c":
            raise TypeError(f"variable '{name}' is complex: store real and imaginary parts")
        if np.issubdtype(var.dtype, np.datetime64):
            e.update(units="seconds since 1970-01-01T00:00:00", calendar="proleptic_gregorian")
        if e:
            enc[str(name)] = e
    return enc


#: the origin of the time units when the record's start is not known (a stand-in, said so)
_UNKNOWN_START = "1970-01-01T00:00:00Z"
_COMMENTS = {"unknown": "the record's start time is not known: the origin of the units stands "
                        "for the start of the record",
             "local": "the record's start is on the recording computer's clock, time zone "
                      "unknown"}


def _cf_time(ds: xr.Dataset) -> xr.Dataset:
    """Give ``time`` the units seconds since the record's start, as CF 4.4 wants.

    The start is the one the raw file or the run gave (its ``record_start`` attribute), else a
    nominal origin said to stand for the start of the record (``record_start = "unknown"``).
    Another time axis in seconds that knows its record's start (a UVP beam's own) is encoded
    so too. :func:`read_dataset` does not decode them, so code and analysts keep plain
    seconds.
    """
    names = [n for n in ds.coords if ds[n].dtype.kind in "fiu" and (
        n == "time" or (ds[n].attrs.get("units") == "s"
                        and ds[n].attrs.get(conventions.RECORD_START)))]
    if not names:
        return ds
    ds = ds.copy()
    for name in names:
        start = conventions.record_start(ds, name)
        attrs = dict(ds[name].attrs, units=f"seconds since {start or _UNKNOWN_START}")
        attrs[conventions.RECORD_START] = start or conventions.UNKNOWN_START
        if attrs.get("comment") in _COMMENTS.values():  # read back from a product: said anew
            del attrs["comment"]
        if not start or not start.endswith("Z"):
            attrs["comment"] = _COMMENTS["local" if start else "unknown"]
        ds[name].attrs = attrs
    return ds


def _signed_bytes(ds: xr.Dataset) -> xr.Dataset:
    """Store unsigned bytes whose values fit (QARTOD flags 1-9) as signed bytes.

    ``flag_values`` too: CF 1.8 knows no unsigned types (compliance-checker: "the datatype is
    uint8").
    """
    names = [n for n, v in ds.data_vars.items()
             if v.dtype == np.uint8 and (v.size == 0 or int(v.max()) <= np.iinfo(np.int8).max)]
    if not names:
        return ds
    ds = ds.copy()
    for name in names:
        attrs = dict(ds[name].attrs)
        if "flag_values" in attrs:
            attrs["flag_values"] = np.asarray(attrs["flag_values"]).astype(np.int8)
        ds[name] = (ds[name].dims, ds[name].values.astype(np.int8), attrs)
    return ds


@_doc
def write_dataset(ds: xr.Dataset, path: str | Path, *, compress: bool = True) -> Written:
    """Check CF attributes and write ``ds`` to ``path`` atomically (temporary file, then rename).

    Variables take their units and names from :mod:`flumekit.conventions` (annotated, then
    checked: CF 1.8); the provenance attributes are added; ``time`` is stored in seconds since
    the record's start (CF 4.4). A failure at any point leaves no file at ``path`` (nor a
    temporary one behind). The same dataset gives the same bytes.

    Parameters
    ----------
    ds : xarray.Dataset
        With the global attributes ``Conventions``, ``title``, ``source`` and ``history``
        (:func:`write_product` sets them); no complex variables.
    %(netcdf_path)s
    compress : bool, optional
        Deflate float arrays of more than 4096 values (zlib level 1 with shuffle, one chunk
        per variable). False stores them contiguous, as they are: for dense float records of
        measured noise, which deflate by a third only, and slowly, and are read whole.

    Returns
    -------
    flumekit.io.atomic.Written
        The file's path and the content digest of the dataset
        (:func:`flumekit.conventions.content_digest`), for the caller to hand on to the
        pipeline (a stage's action returns it).

    Raises
    ------
    ValueError
        When a global attribute is missing, or a variable lacks ``units`` or ``long_name``
        (and the registry of :mod:`flumekit.conventions` does not give them).
    TypeError
        For a complex variable (store its real and imaginary parts).

    See Also
    --------
    write_product : Sets the global attributes, then writes.
    read_dataset : Reads the file back.
    """
    path = Path(path)
    ds = conventions.annotate(ds)
    conventions.check(ds)
    missing = [a for a in ("Conventions", "title", "source", "history") if a not in ds.attrs]
    if missing:
        raise ValueError(f"{path}: dataset lacks global attributes {missing}")
    ds.attrs = conventions.provenance(ds.attrs)
    ds = _cf_time(_signed_bytes(ds))
    with atomic_path(path) as tmp:
        ds.to_netcdf(tmp, engine="netcdf4", encoding=_encoding(ds, compress))
    return Written(path, conventions.content_digest(ds))


@_doc
def write_product(ds: xr.Dataset, path: str | Path, title: str, source: str,
                  parameters: dict | None = None, *, compress: bool = True) -> Written:
    """Write a product of flumekit: its global attributes set, then :func:`write_dataset`.

    The global attributes are those of :func:`flumekit.conventions.global_attrs` (title,
    source, history with the parameters); they are set on ``ds`` itself.

    Parameters
    ----------
    ds : xarray.Dataset
        The product; variable names from :mod:`flumekit.conventions`.
    %(netcdf_path)s
    title : str
        What the dataset holds (the CF ``title``).
    source : str
        How it was made (the CF ``source``).
    parameters : dict, optional
        The parameters it was made with, recorded in ``history``.
    compress : bool, optional
        As :func:`write_dataset`.

    Returns
    -------
    flumekit.io.atomic.Written
        The file's path and the content digest of the dataset.

    Examples
    --------
    >>> import tempfile
    >>> ds = xr.Dataset({"theta": ("time", np.zeros(3))}, coords={"time": np.arange(3) / 100})
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     written = write_product(ds, Path(folder) / "x.nc", "Example", "a docstring")
    ...     back = read_dataset(written)
    >>> back["theta"].attrs["units"], back["time"].values
    ('rad', array([0.  , 0.01, 0.02]))
    """
    ds.attrs.update(conventions.global_attrs(title, source, parameters))
    return write_dataset(ds, path, compress=compress)


def read_dataset(path: str | Path) -> xr.Dataset:
    """Open a flumekit netCDF file fully into memory (the file is closed on return).

    Times are not decoded: a time coordinate stays seconds since the record's start, as the
    code and analysts use it (its units attribute says since when).

    Parameters
    ----------
    path : str or pathlib.Path
        A netCDF file written by :func:`write_dataset`.

    Returns
    -------
    xarray.Dataset
        Loaded, with the file's attributes; strings keep no fixed width from the file.

    See Also
    --------
    flumekit.open_processed : Every run of a stage along ``run``.
    """
    with xr.open_dataset(path, engine="netcdf4", decode_times=False,
                         decode_timedelta=False) as ds:
        ds = ds.load()
    for var in ds.variables.values():
        if var.dtype.kind in "USO":
            # the width of this file's strings is no property of the data: kept in the
            # encoding it would cut longer strings of any dataset this one is stacked into
            var.encoding.pop("dtype", None)
    return ds
