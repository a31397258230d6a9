"""Opening what the pipeline wrote: one dataset, or the runs of a stage along ``run``."""

from __future__ import annotations

from pathlib import Path

import xarray as xr

from flumekit.errors import InputError
from flumekit.io.netcdf import read_dataset

__all__ = ["open_processed", "processed_names", "stack_files"]


def processed_names(processed: str | Path) -> list[str]:
    """Names :func:`open_processed` accepts for a processed campaign folder.

    Parameters
    ----------
    processed : str or pathlib.Path
        A processed campaign folder (``processed/<pipeline>``).

    Returns
    -------
    list of str
        Campaign datasets (``waves_summary``, ``calibration``, ...) and stage folders of
        per-run datasets (``waves``, ``flap``, ...), sorted.
    """
    root = Path(processed)
    files = [p.stem for p in root.glob("*.nc")]
    folders = [p.name for p in root.iterdir() if p.is_dir() and any(p.glob("*.nc"))]
    return sorted(files + folders)


def open_processed(processed: str | Path, name: str | None = None) -> xr.Dataset:
    """Open a processed dataset into memory, or all runs of a stage along ``run``.

    Parameters
    ----------
    processed : str or pathlib.Path
        A processed campaign folder (``processed/<pipeline>``), a stage folder in it or one
        netCDF file.
    name : str, optional
        In a campaign folder: a campaign dataset (``"waves_summary"``, ``"calibration"``,
        ``"uvp_field"``, ...), a stage (``"waves"``, ``"flap"``, ``"comparison"``: every run
        of it, concatenated along ``run``) or one run of a stage (``"waves/T3.50_H0.250_r0"``).
        Leave out with a stage folder or a file.

    Returns
    -------
    xarray.Dataset
        Loaded (the files are closed). Runs are concatenated along a new ``run`` dimension
        with their coordinates outer-joined (NaN where a run has no value), as
        ``xr.open_mfdataset(files, combine="nested", concat_dim="run")`` would.

    Raises
    ------
    flumekit.errors.InputError
        When nothing of that name exists; the message lists the names that do.

    Examples
    --------
    >>> import flumekit
    >>> summary = flumekit.open_processed("processed/default", "waves_summary")  # doctest: +SKIP
    >>> waves = flumekit.open_processed("processed/default", "waves")  # doctest: +SKIP
    """
    path = Path(processed) if name is None else Path(processed) / name
    if path.suffix != ".nc" and path.with_suffix(".nc").is_file():
        path = path.with_suffix(".nc")
    if path.is_file():
        return read_dataset(path)
    files = sorted(path.glob("*.nc")) if path.is_dir() else []
    if not files:
        base = Path(processed) if Path(processed).is_dir() else Path(processed).parent
        have = processed_names(base) if base.is_dir() else []
        raise InputError(path, "no processed dataset here" + (
            f"; {base} has: {', '.join(have)}" if have else
            " (run `flumekit make` first, or check the path)"))
    return stack_files(files)


def _read_variables(path: Path) -> tuple[dict, dict, dict, set]:
    """Read every variable of a flumekit netCDF file.

    Returns (name -> (dims, values, attrs)), the global attributes, the dimension sizes and
    the names its variables list as coordinates. Floats with a ``_FillValue`` are NaN there,
    as xarray decodes them; nothing else needs decoding in what flumekit writes (times stay
    seconds, as :func:`read_dataset` keeps them).
    """
    import netCDF4
    import numpy as np

    out, coords = {}, set()
    with netCDF4.Dataset(path) as nc:
        nc.set_auto_mask(False)
        for name, var in nc.variables.items():
            attrs = {k: var.getncattr(k) for k in var.ncattrs()}
            values = np.asarray(var[...])
            fill = attrs.pop("_FillValue", None)
            if fill is not None and values.dtype.kind == "f" and not np.isnan(fill):
                values = np.where(values == fill, np.nan, values)
            coords.update(attrs.pop("coordinates", "").split())
            if values.dtype.kind == "O":  # variable-length strings
                values = values.astype(str)
            out[name] = (var.dimensions, np.asarray(values), attrs)
        globals_ = {k: nc.getncattr(k) for k in nc.ncattrs()}
        sizes = {d: len(v) for d, v in nc.dimensions.items()}
    return out, globals_, sizes, coords


def _common_attrs(dicts: list[dict]) -> dict:
    """Keep the attributes whose values agree wherever set (xarray's ``drop_conflicts``)."""
    import numpy as np

    out, dropped = {}, set()
    for d in dicts:
        for k, v in d.items():
            if k in dropped:
                continue
            if k not in out:
                out[k] = v
            elif not np.array_equal(np.asarray(out[k]), np.asarray(v)):
                del out[k]
                dropped.add(k)
    return out


def _equal(a, b) -> bool:
    """Tell whether two arrays have the same shape and values, NaN equal to NaN."""
    import numpy as np

    if a.shape != b.shape:
        return False
    return bool(np.array_equal(a, b, equal_nan=a.dtype.kind in "fc" and b.dtype.kind in "fc"))


def stack_files(files) -> xr.Dataset:
    """Per-run datasets stacked along a new ``run`` dimension, read with netCDF4 directly.

    The result is that of ``xr.concat([read_dataset(f) for f in files], dim="run",
    join="outer", combine_attrs="drop_conflicts", coords="different", compat="equals")``
    (a test holds them equal) at about the cost of reading the bytes: the runs' dimension
    coordinates (``time``, ``frequency``, ...) are joined (their union, sorted), every
    variable is placed into one preallocated array, NaN where a run has no value (integers
    padded so become floats, as xarray promotes them), and attributes kept where every run
    agrees. A 1-D coordinate that is equal in every run is not stacked (``x`` of the
    probes); a scalar one is (``wave_period``).

    Parameters
    ----------
    files : sequence of str or pathlib.Path
        netCDF files written by flumekit, one run each.

    Returns
    -------
    xarray.Dataset
        Loaded; the files are closed.
    """
    import numpy as np

    parts = [_read_variables(Path(f)) for f in files]
    n = len(parts)
    names: list[str] = []
    for variables, *_ in parts:
        names += [k for k in variables if k not in names]
    coord_names = set().union(*(c for *_, c in parts))
    dims = {name: parts[0][0][name][0] for name in names if name in parts[0][0]}
    for variables, *_ in parts[1:]:
        for name, (d, *_) in variables.items():
            dims.setdefault(name, d)
    # dimension coordinates: the union of the runs' values (an outer join)
    index = {}
    for name in names:
        if dims[name] == (name,):
            values = [p[0][name][1] for p in parts if name in p[0]]
            if all(_equal(v, values[0]) for v in values[1:]):
                index[name] = (values[0], None)
            else:
                union = np.unique(np.concatenate(values))
                index[name] = (union, [np.searchsorted(union, p[0][name][1])
                                       if name in p[0] else None for p in parts])
    data_vars, coords = {}, {}
    for name in names:
        present = [p[0].get(name) for p in parts]
        attrs = _common_attrs([v[2] for v in present if v is not None])
        if name in index:
            coords[name] = xr.Variable((name,), index[name][0], attrs)
            continue
        d = dims[name]
        sample = next(v[1] for v in present if v is not None)
        if (all(v is not None for v in present) and name in coord_names
                and all(_equal(v[1], sample) for v in present[1:])):
            coords[name] = xr.Variable(d, sample, attrs)  # equal in every run: not stacked
            continue
        shape = tuple(index[k][0].size if k in index else sample.shape[i]
                      for i, k in enumerate(d))
        padded = any(v is None or v[1].shape != shape for v in present)
        dtype = sample.dtype
        if padded and dtype.kind in "iub":
            dtype = np.dtype(float)
        if dtype.kind == "U":
            if padded:
                dtype = np.dtype(object)
            else:  # the widest of the runs' strings
                dtype = np.result_type(*(v[1].dtype for v in present))
        if dtype.kind in "fcO":
            out = np.full((n, *shape), np.nan, dtype)
        else:
            out = np.zeros((n, *shape), dtype)
        for i, v in enumerate(present):
            if v is None:
                continue
            if not d:
                out[i] = v[1]
                continue
            where = np.ix_(*(index[k][1][i] if k in index and index[k][1] is not None
                             else np.arange(shape[j]) for j, k in enumerate(d)))
            out[i][where] = v[1]
        var = xr.Variable(("run", *d), out, attrs)
        (coords if name in coord_names else data_vars)[name] = var
    ds = xr.Dataset(data_vars, coords=coords, attrs=_common_attrs([p[1] for p in parts]))
    return ds
