"""Per-run netCDF files held open together: what each holds, and its values on demand.

:func:`open_runs` describes every file first (variables, dimensions, attributes) and reads a
variable's values only when asked, straight into the caller's array where it can; the
stacking in :mod:`flumekit.io.processed` places them. Values and attributes are those
``xr.open_dataset(path, engine="netcdf4", decode_times=False)`` gives: floats NaN where
their ``_FillValue`` stands, variable-length strings as a NumPy string array.

Two readers give the same description. The HDF5 one lists each file's variables with h5py,
decodes their headers and attributes from the file's bytes (:mod:`flumekit.io.hdf5_headers`)
and reads a contiguous record with one system call into place; the netCDF-C library's own
open reads megabytes of each file to recognise its format and costs more than all that. It
takes the netCDF-4 files the netCDF library writes; for anything it does not know (groups,
user-defined types, big-endian records, attributes xarray would decode such as
``scale_factor``, a block that does not match its checksum) it declines, and the netCDF4
reader reads the files.
"""

from __future__ import annotations

from contextlib import ExitStack, contextmanager
from pathlib import Path

import numpy as np

from flumekit.io.hdf5_headers import (
    SKIPPED,
    Unsupported,
    check_superblock,
    checksums_match,
    read_header,
    root_attributes,
)

__all__ = ["Hdf5Runs", "Netcdf4Runs", "open_runs"]

#: attributes xarray's decoding consumes that neither reader applies
_DECODED = frozenset({"scale_factor", "add_offset", "missing_value", "dtype"})
#: the first words of the NAME of a netCDF-4 dimension that is no variable
_DIMENSION_ONLY = "This is a netCDF dimension but not a netCDF variable"
#: netCDF-4 bookkeeping attributes the netCDF library does not list
_HIDDEN = ("CLASS", "NAME", "_Netcdf4Dimid", "_Netcdf4Coordinates")


@contextmanager
def open_runs(files):
    """Open per-run netCDF files together, with the HDF5 reader where it can read them all.

    Parameters
    ----------
    files : sequence of str or pathlib.Path
        netCDF files, one run each.

    Yields
    ------
    Hdf5Runs or Netcdf4Runs
        ``metas[i]``: (variables, global attributes, coordinate names) of file ``i``, a
        variable as name -> (dimensions, shape, attributes, fill value, dtype) with the
        attributes lacking ``_FillValue`` and ``coordinates``, strings of dtype object;
        ``values(i, name)`` and ``read_into(i, name, view)`` give its decoded values. The
        files are closed on leaving the block.

    Examples
    --------
    >>> import tempfile
    >>> import xarray as xr
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = Path(folder) / "run.nc"
    ...     xr.Dataset({"theta": ("time", [0.5, 1.0])}).to_netcdf(path)
    ...     with open_runs([path]) as runs:
    ...         dims, shape, attrs, fill, dtype = runs.metas[0][0]["theta"]
    ...         print(type(runs).__name__, dims, shape, runs.values(0, "theta"))
    Hdf5Runs ('time',) (2,) [0.5 1. ]
    """
    try:
        runs = Hdf5Runs(files)
    except Unsupported:
        runs = Netcdf4Runs(files)
    with runs:
        yield runs


def _decoded(values: np.ndarray, fill) -> np.ndarray:
    """Decode values as xarray does what flumekit writes: NaN for a non-NaN float fill."""
    if fill is not None and values.dtype.kind == "f" and not np.isnan(fill):
        values[values == fill] = np.nan
    return values


class _Runs:
    """What both readers share: the description, decoding, placing and closing."""

    def __init__(self):
        self.metas: list[tuple[dict, dict, set]] = []
        self._closing = ExitStack()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self._closing.close()

    def raw(self, i: int, name: str) -> np.ndarray:
        """Read variable ``name`` of file ``i`` as stored (strings as a str array)."""
        raise NotImplementedError

    def values(self, i: int, name: str) -> np.ndarray:
        """Read variable ``name`` of file ``i``, decoded (a new array)."""
        return _decoded(self.raw(i, name), self.metas[i][0][name][3])

    def read_into(self, i: int, name: str, view: np.ndarray) -> None:
        """Read variable ``name`` of file ``i`` into ``view`` (of its shape), decoded."""
        view[...] = self.values(i, name)


class Netcdf4Runs(_Runs):
    """The files read with the netCDF4 library.

    Parameters
    ----------
    files : sequence of str or pathlib.Path
        netCDF files.
    """

    def __init__(self, files):
        import netCDF4

        super().__init__()
        try:
            self._ncs = [self._closing.enter_context(netCDF4.Dataset(Path(f))) for f in files]
            for nc in self._ncs:
                nc.set_auto_mask(False)
                self.metas.append(self._metadata(nc))
        except BaseException:
            self._closing.close()
            raise

    @staticmethod
    def _metadata(nc) -> tuple[dict, dict, set]:
        out, coords = {}, set()
        for name, var in nc.variables.items():
            attrs = {k: var.getncattr(k) for k in var.ncattrs()}
            fill = attrs.pop("_FillValue", None)
            coords.update(attrs.pop("coordinates", "").split())
            dtype = np.dtype(object) if var.dtype is str else np.dtype(var.dtype)
            out[name] = (var.dimensions, var.shape, attrs, fill, dtype)
        return out, {k: nc.getncattr(k) for k in nc.ncattrs()}, coords

    def raw(self, i: int, name: str) -> np.ndarray:
        """Read variable ``name`` of file ``i`` as stored (strings as a str array)."""
        values = np.asarray(self._ncs[i].variables[name][...])
        return values.astype(str) if values.dtype.kind == "O" else values


def _library_attributes(obj) -> dict:
    """Read an object's attributes with h5py as ``netCDF4`` gives them, one call each.

    For the attributes :mod:`flumekit.io.hdf5_headers` does not decode (one is a list of
    strings, or there are thirty or more). The dimension scales' reference lists are left
    out.
    """
    import h5py
    from h5py import h5a, h5t

    out = {}
    for k in range(h5a.get_num_attrs(obj)):
        attr = h5a.open(obj, index=k, index_type=h5py.h5.INDEX_CRT_ORDER)
        name, kind, space = attr.name.decode("utf-8"), attr.get_type(), attr.shape
        if name in SKIPPED:
            continue
        null = attr.get_space().get_simple_extent_type() == h5py.h5s.NULL
        if null or space is None or len(space) > 1:
            raise Unsupported(f"attribute '{name}': empty or of more than one dimension")
        if kind.get_class() == h5t.STRING and kind.is_variable_str():
            values = np.empty(space, dtype=h5py.string_dtype())
            attr.read(values)
            text = [(v.decode("utf-8", errors="replace") if isinstance(v, bytes) else v or "")
                    .replace("\x00", "") for v in values.reshape(-1)]
            out[name] = text[0] if len(text) == 1 else text
        elif kind.get_class() == h5t.STRING and not space:
            value = np.empty((), f"S{kind.get_size()}")
            attr.read(value, kind)
            out[name] = value.tobytes().decode("utf-8", errors="replace").replace("\x00", "")
        elif (kind.get_class() in (h5t.INTEGER, h5t.FLOAT) and attr.dtype.kind in "iuf"
              and h5py.check_enum_dtype(attr.dtype) is None):
            values = np.empty(space, attr.dtype)
            attr.read(values)
            values = values.reshape(-1).astype(attr.dtype.newbyteorder("="))
            out[name] = values[0] if values.size == 1 else values
        else:
            raise Unsupported(f"attribute '{name}' of HDF5 type class {kind.get_class()}")
    return out


class Hdf5Runs(_Runs):
    """The netCDF-4 files read with h5py, their variables' attributes from the headers' bytes.

    Parameters
    ----------
    files : sequence of str or pathlib.Path
        netCDF-4 files as the netCDF library writes them.

    Raises
    ------
    flumekit.io.hdf5_headers.Unsupported
        For a file this reader does not read as the netCDF4 library would.
    """

    def __init__(self, files):
        super().__init__()
        #: per file: its bytes (memory-mapped), the HDF5 file, name -> Header
        self._files: list[tuple] = []
        self._raw: list = []  # the files open for reading into place
        self._decoded: dict = {}  # attribute messages decoded (read_header)
        self._pieces: list = []  # the headers' chunks with their checksums
        try:
            for f in files:
                self._open(Path(f))
            if not checksums_match(self._pieces).all():
                raise Unsupported("an object header does not match its checksum")
            self._pieces.clear()
        except BaseException:
            self._closing.close()
            raise

    def _open(self, path: Path) -> None:
        import mmap
        import os

        import h5py

        raw = self._closing.enter_context(open(path, "rb", buffering=0))
        check_superblock(raw.read(11))
        buffer = self._closing.enter_context(mmap.mmap(raw.fileno(), 0, access=mmap.ACCESS_READ))
        try:  # the default access: the file may be open elsewhere in this process
            fid = h5py.h5f.open(os.fsencode(path), h5py.h5f.ACC_RDONLY)
        except OSError as e:  # the netCDF4 library says what is wrong with it
            raise Unsupported(f"{path}: {e}") from None
        self._closing.callback(fid.close)
        root = h5py.h5g.open(fid, b"/")
        names: list[bytes] = []
        root.links.iterate(names.append, idx_type=h5py.h5.INDEX_CRT_ORDER)
        found, scales = {}, {}
        for key in names:
            link = root.links.get_info(key)
            if link.type != h5py.h5l.TYPE_HARD:
                raise Unsupported(f"{path}: '{key.decode()}' is a link to another object")
            header = read_header(buffer, link.u, self._decoded, self._pieces)
            attrs = header.attributes
            if attrs is None:
                attrs = _library_attributes(h5py.h5o.open(fid, key))
            name = key.decode("utf-8")
            if attrs.get("CLASS") == "DIMENSION_SCALE" and "_Netcdf4Dimid" in attrs:
                scales[int(attrs["_Netcdf4Dimid"])] = name
                if str(attrs.get("NAME", "")).startswith(_DIMENSION_ONLY):
                    continue
            elif "CLASS" in attrs or "NAME" in attrs:
                raise Unsupported(f"{path}: '{name}' is an HDF5 dimension scale unknown to netCDF")
            found[name] = (header, attrs)
        variables, coords = {}, set()
        for name, (header, attrs) in found.items():
            ids = attrs.get("_Netcdf4Coordinates", ())
            dims = tuple(scales.get(int(k), "") for k in np.atleast_1d(ids))
            for hidden in _HIDDEN:
                attrs.pop(hidden, None)
            odd = [k for k in attrs if (k.startswith("_") and k != "_FillValue") or k in _DECODED]
            odd += ["its type"] if header.dtype is None else []
            if odd or len(dims) != len(header.shape) or "" in dims or name.startswith("_nc4_"):
                raise Unsupported(f"{path}: variable '{name}' ({', '.join(odd) or 'dims'})")
            fill = attrs.pop("_FillValue", None)
            coords.update(attrs.pop("coordinates", "").split())
            variables[name] = (dims, header.shape, attrs, fill, header.dtype)
        globals_ = root_attributes(buffer, self._decoded, self._pieces)
        globals_ = _library_attributes(root) if globals_ is None else globals_
        globals_.pop("_NCProperties", None)
        if any(k.startswith("_") for k in globals_):
            raise Unsupported(f"{path}: global attributes {sorted(globals_)}")
        self.metas.append((variables, globals_, coords))
        self._files.append((buffer, fid, {name: h for name, (h, _) in found.items()}))
        self._raw.append(raw)

    def raw(self, i: int, name: str) -> np.ndarray:
        """Read variable ``name`` of file ``i`` as stored (strings as a str array)."""
        import h5py

        buffer, fid, headers = self._files[i]
        header = headers[name]
        if header.contiguous is not None and header.dtype.kind != "O":
            stored = np.dtype(header.dtype).newbyteorder("<")
            count = int(np.prod(header.shape))
            if header.contiguous[1] == count * stored.itemsize:
                values = np.frombuffer(buffer, stored, count, header.contiguous[0])
                return values.astype(header.dtype).reshape(header.shape)  # a copy
        obj = h5py.h5o.open(fid, name.encode("utf-8"))
        if header.dtype.kind == "O":
            return np.asarray(h5py.Dataset(obj).asstr()[()]).astype(str)
        values = np.empty(header.shape, header.dtype)
        obj.read(h5py.h5s.ALL, h5py.h5s.ALL, values)
        return values

    def read_into(self, i: int, name: str, view: np.ndarray) -> None:
        """Read variable ``name`` of file ``i`` into ``view`` (of its shape), decoded.

        Values stored contiguously in the file, as the netCDF library writes an
        uncompressed variable, are read with one system call into ``view``.
        """
        _, _, headers = self._files[i]
        raw, header = self._raw[i], headers[name]
        if (header.contiguous is None or view.dtype != header.dtype.newbyteorder("<")
                or not view.flags.c_contiguous or header.contiguous[1] != view.nbytes):
            return super().read_into(i, name, view)
        raw.seek(header.contiguous[0])
        target, done = memoryview(view).cast("B"), 0
        while done < view.nbytes:  # one read but for more than the system gives at once
            got = raw.readinto(target[done:])
            if not got:
                raise OSError(f"{raw.name}: variable '{name}' ends before its declared size")
            done += got
        _decoded(view, self.metas[i][0][name][3])


def text_attributes(files, name: str) -> list[str | None]:
    """Return the text global attribute ``name`` of each netCDF file, None where it has none.

    Read with h5py from the files' HDF5 root group alone (a netCDF-4 file), not by opening each
    file with the netCDF library, which reads every variable's description first: the make
    summary reads one attribute of each product built, a thousand files for a paper campaign.
    A file h5py cannot open (netCDF-3) is read with the netCDF library.

    Parameters
    ----------
    files : sequence of str or pathlib.Path
        netCDF files.
    name : str
        The attribute's name.

    Returns
    -------
    list of str or None
        Its text in each file (as the netCDF library returns it: ASCII as characters, other
        text as UTF-8 strings), in the order of ``files``.

    Examples
    --------
    >>> import tempfile
    >>> import xarray as xr
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     paths = [Path(folder) / "a.nc", Path(folder) / "b.nc"]
    ...     xr.Dataset(attrs={"note": "θ held at its bound"}).to_netcdf(paths[0])
    ...     xr.Dataset().to_netcdf(paths[1])
    ...     text_attributes(paths, "note")
    ['θ held at its bound', None]
    """
    import h5py

    out: list[str | None] = []
    for f in files:
        try:
            with h5py.File(f, "r") as h5:
                value = h5.attrs.get(name)
        except OSError:  # not HDF5: a netCDF-3 file
            import netCDF4

            with netCDF4.Dataset(f) as nc:
                value = getattr(nc, name, None)
        out.append(_text(value))
    return out


def _text(value) -> str | None:
    """Return an attribute's value as the netCDF library's text: one string, decoded."""
    if isinstance(value, np.ndarray):  # a netCDF string attribute is an array of strings
        items = [_text(v) for v in value.ravel().tolist()]
        return items[0] if len(items) == 1 else str(items)
    if isinstance(value, bytes):
        return value.decode("utf-8")
    return None if value is None else str(value)
