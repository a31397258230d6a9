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
    for name in [*ds.coords, *ds.data_vars]:  # Variables: no DataArray built for each
        var = ds.variables[name]
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
    coords = {n: ds.variables[n] for n in ds.coords}
    names = [n for n, c in coords.items() if c.dtype.kind in "fiu" and (
        n == "time" or (c.attrs.get("units") == "s" and c.attrs.get(conventions.RECORD_START)))]
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

    Examples
    --------
    A probe record, its variable named as :mod:`flumekit.conventions` knows it (``eta``, which
    takes its units on the way), written twice: the same bytes, and read back, the same values.

    >>> import tempfile
    >>> from flumekit import conventions
    >>> eta = xr.Dataset({"eta": ("time", [0.0, 0.012, -0.008])},
    ...                  coords={"time": [0.0, 0.01, 0.02]},
    ...                  attrs=conventions.global_attrs("Probe record", "typed in"))
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     a = write_dataset(eta, Path(folder) / "a.nc")
    ...     b = write_dataset(eta, Path(folder) / "b.nc")
    ...     same_bytes = a.path.read_bytes() == b.path.read_bytes()
    ...     back = read_dataset(a.path)
    >>> same_bytes, a.digest == b.digest
    (True, True)
    >>> back["eta"].values.tolist(), back["eta"].attrs["units"]
    ([0.0, 0.012, -0.008], 'm')

    Without its global attributes nothing is written (no file, not even a temporary one):

    >>> write_dataset(xr.Dataset({"eta": ("time", [0.0])}), "never.nc")
    Traceback (most recent call last):
    ...
    ValueError: never.nc: dataset lacks global attributes ['Conventions', 'title', ...]
    """
    path = Path(path)
    ds = conventions.annotate(ds)
    conventions.check(ds)
    missing = [a for a in ("Conventions", "title", "source", "history") if a not in ds.attrs]
    if missing:
        raise ValueError(f"{path}: dataset lacks global attributes {missing}")
    ds.attrs = conventions.provenance(ds.attrs)
    ds = _cf_time(_signed_bytes(ds))
    encoding = _encoding(ds, compress)
    with atomic_path(path) as tmp:
        if not _netcdf4_written(ds, tmp, encoding):
            ds.to_netcdf(tmp, engine="netcdf4", encoding=encoding)
    return Written(path, conventions.content_digest(ds))


#: variable encodings the netCDF4 library takes as they are (xarray passes the same on)
_PASSED = frozenset({"complevel", "fletcher32", "contiguous", "shuffle", "endian"})
#: encodings of a variable read from a file that say nothing for writing
_READ_ONLY = frozenset({"source", "original_shape", "zlib", "szip", "bzip2", "blosc", "zstd",
                        "chunksizes", "dtype", "_FillValue", "coordinates"})
#: encodings naming variables in CF attributes, which xarray treats apart (CF 5-7)
_RELATED = frozenset({"bounds", "grid_mapping", "climatology", "geometry", "node_coordinates",
                      "node_count", "part_node_count", "interior_ring", "cell_measures",
                      "formula_terms"})


def _netcdf4_written(ds: xr.Dataset, path, encoding: dict[str, dict]) -> bool:
    """Write ``ds`` with the netCDF4 library as xarray's ``to_netcdf`` writes it, if it can.

    The same file, byte for byte, as ``ds.to_netcdf(path, engine="netcdf4",
    encoding=encoding)`` for the datasets flumekit writes (a test holds them equal): the global
    attributes, then the dimensions in the order the variables first use them, then each
    variable with its attributes (and the ``coordinates`` attribute xarray gives it) and its
    values; floats, integers and variable-length strings, compressed as ``encoding`` says.
    xarray's store (file manager and locks taken for every call, array wrappers, encoders)
    costs about as much as the library's own writing for a product of many small variables.
    Anything else (a type, an attribute, an
    encoding or a name this function does not know, cell bounds, whose attributes xarray
    thins) returns False before the file is created, for xarray to write it.
    """
    import netCDF4

    variables = {}
    for name, var in ds.variables.items():
        enc = encoding.get(name)
        if enc is None:  # a variable read from a file keeps what xarray would pass on
            extra = {k: v for k, v in var.encoding.items() if k not in _READ_ONLY}
            if set(extra) - _PASSED or any(var.encoding.get(k) for k in _READ_ONLY - {
                    "source", "original_shape", "dtype", "_FillValue", "coordinates"}):
                return False
            if var.encoding.get("dtype", var.dtype) != var.dtype or var.encoding.get(
                    "_FillValue") is not None:
                return False
            enc = extra
        kind = var.dtype.kind
        if (not isinstance(name, str) or not name or "/" in name or _RELATED & set(var.encoding)
                or not _plain_attrs(var.attrs) or {"coordinates", "bounds"} & set(var.attrs)
                or "_FillValue" in var.attrs or kind not in "fiuUO"):
            return False
        values = var.values
        if kind in "UO":
            if enc.get("dtype") is not str or (kind == "O" and not all(
                    isinstance(v, str) for v in values.reshape(-1).tolist())):
                return False
            values, datatype = values.astype(object), str
        else:
            datatype = np.dtype(enc.get("dtype", var.dtype))
            if datatype.kind not in "fiu" or datatype.byteorder not in "=|":
                return False
            values = values.astype(datatype, copy=False)
        variables[str(name)] = (var.dims, values, datatype, enc, dict(var.attrs))
    if not _plain_attrs(ds.attrs) or "coordinates" in ds.attrs:
        return False
    # xarray's coordinates attributes (CF 5): on each variable, the coordinates that are not
    # dimensions and whose dimensions it has, sorted; on the dataset, those no variable names
    others = [c for c in ds.coords if c not in ds.dims]
    named = set()
    for name, (dims, _, _, _, attrs) in variables.items():
        read = ds.variables[name].encoding
        if "coordinates" in read:  # as read from a file: written as it was (or not at all)
            if read["coordinates"]:
                attrs["coordinates"] = str(read["coordinates"])
                named.update(attrs["coordinates"].split())
            continue
        if name in dims or name in others:
            continue
        mine = sorted(c for c in others if set(ds.variables[c].dims) <= set(dims))
        if mine:
            attrs["coordinates"] = " ".join(mine)
            named.update(mine)
    global_attrs = dict(ds.attrs)
    if set(others) - named:
        global_attrs["coordinates"] = " ".join(sorted(set(others) - named))
    sizes: dict = {}
    for dims, values, *_ in variables.values():
        for dim, n in zip(dims, values.shape, strict=True):
            if sizes.setdefault(dim, n) != n:
                return False
    with netCDF4.Dataset(path, "w", format="NETCDF4") as nc:
        for key, value in global_attrs.items():
            if np.asarray(value).dtype.kind == "U" and np.size(value) > 1:
                nc.setncattr_string(key, value)
            else:
                nc.setncattr(key, value)
        for dim, n in sizes.items():
            nc.createDimension(dim, n)
        for name, (dims, values, datatype, enc, attrs) in variables.items():
            fill = np.nan if datatype is not str and encoding.get(name, {}).get(
                "_FillValue", None) is not None else None
            compressed = enc.get("zlib", False)
            v = nc.createVariable(
                name, datatype, dims, compression="zlib" if compressed else None,
                complevel=enc.get("complevel", 4), shuffle=enc.get("shuffle", True),
                fletcher32=enc.get("fletcher32", False), contiguous=enc.get("contiguous", False),
                chunksizes=None, endian=enc.get("endian", "native"), fill_value=fill)
            v.setncatts(attrs)
            v.set_auto_maskandscale(False)
            v.set_auto_chartostring(False)
            v[...] = values
    return True


def _plain_attrs(attrs: dict) -> bool:
    """Tell whether every attribute is a string, a number or a flat array of either."""
    for key, value in attrs.items():
        if not isinstance(key, str) or isinstance(value, (bool, np.bool_)):
            return False
        if isinstance(value, (list, tuple)):
            value = np.asarray(value)
        if isinstance(value, np.ndarray):
            if value.ndim > 1 or value.dtype.kind not in "fiuU" or value.size == 0:
                return False
        elif not isinstance(value, (str, int, float, np.integer, np.floating)):
            return False
    return True


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

    Examples
    --------
    A flap record whose start is known: the file counts its time from that instant (CF 4.4),
    and the dataset read back still holds plain seconds, not dates.

    >>> import tempfile
    >>> from flumekit import conventions
    >>> start = {"record_start": "2024-03-05T10:12:00Z"}
    >>> theta = xr.Dataset({"theta": ("time", [0.0, 0.1, 0.0])},
    ...                    coords={"time": ("time", [0.0, 0.5, 1.0], start)},
    ...                    attrs=conventions.global_attrs("Flap angle", "typed in"))
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     back = read_dataset(write_dataset(theta, Path(folder) / "theta.nc").path)
    >>> back["time"].attrs["units"], back["time"].values.tolist()
    ('seconds since 2024-03-05T10:12:00Z', [0.0, 0.5, 1.0])
    """
    if _remembered is None:
        ds = _netcdf4_read(path)
        return _xarray_read(path) if ds is None else ds
    return _remembered_read(path)


#: the datasets this process read (:func:`remember_reads`): path -> (file identity, dataset);
#: None where they are not remembered
_remembered = None
_remembered_limit = 0


def remember_reads(max_bytes: int | None) -> None:
    """Let :func:`read_dataset` remember what it reads in this process, or stop (None).

    A file read again, unchanged, is then copied from memory instead of read and decoded again:
    the pipeline's worker processes, which live for one build, read each run's products for
    several rules (the calibration for every run). Unchanged means the same file: the same
    device, inode, size, modification and status-change times (a product is replaced by a new
    file, :func:`flumekit.io.atomic.atomic_path`, never rewritten in place). The caller gets a
    deep copy each time, so nothing it changes reaches the next reader. The least recently
    read datasets are forgotten beyond ``max_bytes`` of data.

    Parameters
    ----------
    max_bytes : int or None
        Memory for the remembered datasets' values [B]; None forgets them all and stops.

    Examples
    --------
    >>> from flumekit.io.netcdf import remember_reads
    >>> remember_reads(64 * 2**20)
    >>> remember_reads(None)
    """
    global _remembered, _remembered_limit
    from collections import OrderedDict

    _remembered = None if max_bytes is None else OrderedDict()
    _remembered_limit = 0 if max_bytes is None else int(max_bytes)


def _remembered_read(path) -> xr.Dataset:
    """Read ``path`` through the memory of :func:`remember_reads`."""
    import os

    name = os.path.abspath(path)
    st = os.stat(name)
    key = (st.st_dev, st.st_ino, st.st_size, st.st_mtime_ns, st.st_ctime_ns)
    known = _remembered.get(name)
    if known is not None and known[0] == key:
        _remembered.move_to_end(name)
        return known[1].copy(deep=True)
    ds = _netcdf4_read(path)
    if ds is None:
        ds = _xarray_read(path)
    _remembered[name] = (key, ds.copy(deep=True))
    total = sum(d.nbytes for _, d in _remembered.values())
    while total > _remembered_limit and _remembered:
        total -= _remembered.popitem(last=False)[1][1].nbytes
    return ds


def _xarray_read(path) -> xr.Dataset:
    """Read ``path`` as :func:`read_dataset` does, through xarray."""
    with xr.open_dataset(path, engine="netcdf4", decode_times=False,
                         decode_timedelta=False) as ds:
        ds = ds.load()
    for var in ds.variables.values():
        if var.dtype.kind in "USO":
            # the width of this file's strings is no property of the data: kept in the
            # encoding it would cut longer strings of any dataset this one is stacked into
            var.encoding.pop("dtype", None)
    return ds


#: attributes xarray's decoding would apply (scale, other missing values, types), which
#: :func:`_netcdf4_read` leaves to xarray
_DECODED = frozenset({"scale_factor", "add_offset", "missing_value", "valid_range", "valid_min",
                      "valid_max", "_Unsigned", "dtype", "_Encoding", "flag_masks"})


def _netcdf4_read(path) -> xr.Dataset | None:
    """Read a netCDF-4 file with the netCDF4 library as :func:`read_dataset` reads it, if it can.

    The dataset ``xr.open_dataset(path, engine="netcdf4", decode_times=False,
    decode_timedelta=False).load()`` gives for the files flumekit writes (a test holds them
    equal, encodings included): data variables then coordinates (those named by a
    ``coordinates`` attribute, and the dimensions'), each in the file's order; floats NaN
    where their ``_FillValue`` stands; variable-length strings as a NumPy string array;
    without xarray's store, lazy arrays and decoders, which cost about half as much again as
    the library's reading. A file with anything else (attributes xarray decodes, an integer
    with a fill value, character arrays, enumerations or other types, groups, an unlimited
    dimension, another format than netCDF-4) gives None before anything is read, for xarray
    to read it.
    """
    import netCDF4

    path = Path(path)
    with netCDF4.Dataset(path) as nc:
        if nc.data_model != "NETCDF4" or nc.groups or any(
                d.isunlimited() for d in nc.dimensions.values()):
            return None
        global_attrs = {k: nc.getncattr(k) for k in nc.ncattrs()}
        described = []
        for name, v in nc.variables.items():
            attrs = {k: v.getncattr(k) for k in v.ncattrs()}
            # variable-length strings (their dtype str), or a primitive number type (not an
            # enumeration's or a ragged array's, whose dtype is that of their values)
            text = v.dtype is str
            if _DECODED & set(attrs) or not (text or isinstance(v.datatype, np.dtype)
                                             and v.datatype.kind in "fiu"):
                return None
            fill = attrs.pop("_FillValue", None)
            if fill is not None and (text or v.datatype.kind != "f"):
                return None
            described.append((name, v, attrs, fill))
        variables, coords = {}, set()
        for name, v, attrs, fill in described:
            v.set_auto_maskandscale(False)
            values = np.asarray(v[...])
            encoding = {"dtype": v.dtype, **v.filters()}
            chunking = v.chunking()
            encoding.update(contiguous=chunking == "contiguous",
                            chunksizes=None if chunking == "contiguous" else tuple(chunking))
            if chunking != "contiguous":
                encoding["preferred_chunks"] = dict(zip(v.dimensions, chunking, strict=True))
            encoding.update(source=str(path), original_shape=values.shape)
            if v.dtype is str:
                # as xarray: no encoding (the width of this file's strings, no property of
                # the data, would cut longer strings of a dataset stacked with it)
                values, encoding = values.astype(object).astype(str), {}
            elif fill is not None:
                encoding["_FillValue"] = fill
                if not np.isnan(fill):
                    values = np.where(values == fill, np.nan, values)
            named = attrs.pop("coordinates", None)
            if named is not None:
                encoding["coordinates"] = named
                coords.update(str(named).split())
            kind = xr.IndexVariable if v.dimensions == (name,) else xr.Variable
            variables[name] = kind(v.dimensions, values, attrs, encoding)
    if isinstance(global_attrs.get("coordinates"), str):
        coords.update(global_attrs.pop("coordinates").split())
    coords = {k for k in variables if k in coords or variables[k].dims == (k,)}
    data_vars = {k: v for k, v in variables.items() if k not in coords}
    coord_vars = {k: v for k, v in variables.items() if k in coords}
    return conventions.dataset_of_variables(data_vars, coord_vars, global_attrs,
                                            dims_from_data=True)
