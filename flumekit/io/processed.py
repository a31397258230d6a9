"""Opening what the pipeline wrote: one dataset, or the runs of a stage along ``run``."""

from __future__ import annotations

from pathlib import Path

import xarray as xr

from flumekit.errors import InputError
from flumekit.io.netcdf import read_dataset

__all__ = ["open_processed", "processed_names", "stack_files"]


def processed_names(processed: str | Path) -> list[str]:
    """List the names :func:`open_processed` accepts for a processed campaign folder.

    Parameters
    ----------
    processed : str or pathlib.Path
        A processed campaign folder (``processed/<pipeline>``).

    Returns
    -------
    list of str
        Campaign datasets (``waves_summary``, ``calibration``, ...) and stage folders of
        per-run datasets (``waves``, ``flap``, ...), sorted.

    Examples
    --------
    A campaign dataset, a stage folder with one run and a folder of figures, which holds no
    dataset and so is no name:

    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     root = Path(folder)
    ...     for name in ("waves_summary.nc", "waves/T2.00_H0.150_r0.nc", "figures/fig10.png"):
    ...         (root / name).parent.mkdir(exist_ok=True)
    ...         (root / name).touch()
    ...     names = processed_names(root)
    >>> names
    ['waves', 'waves_summary']
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
    # ".nc" appended, not put for a suffix: a run id's dots ("T3.50_H0.250_r0") are no suffix
    if path.suffix != ".nc" and path.with_name(f"{path.name}.nc").is_file():
        path = path.with_name(f"{path.name}.nc")
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


def stack_files(files, scalars: bool = False, coords: str = "different",
                run_attrs: list | None = None) -> xr.Dataset:
    """Stack per-run datasets along a new ``run`` dimension, read without xarray.

    The result is that of ``xr.concat([read_dataset(f) for f in files], dim="run",
    join="outer", combine_attrs="drop_conflicts", coords="different", compat="equals")``
    (a test holds them equal) at about the cost of reading the bytes: the runs' dimension
    coordinates (``time``, ``frequency``, ...) are joined (their union, sorted), every
    variable is read straight into its place in one preallocated array (a slice wherever a
    run's coordinate values are contiguous in the union, as records sampled on one clock
    are), NaN where a run has no value (integers padded so become floats, as xarray promotes
    them: 32-bit for 8- and 16-bit integers), and attributes kept where every run agrees. A
    1-D coordinate that is equal in every run is not stacked (``x`` of the probes); a scalar
    one is (``wave_period``). The files are read by :func:`flumekit.io.run_files.open_runs`:
    netCDF-4 files as the netCDF library writes them with h5py, a record with one read
    straight into its place, anything else with the netCDF4 library.

    Parameters
    ----------
    files : sequence of str or pathlib.Path
        netCDF files written by flumekit, one run each.
    scalars : bool, default False
        Stack only the variables without a dimension (a run's results, the rows of a campaign
        summary): the records are not read at all.
    coords : {"different", "all"}
        As xarray's ``concat``: a coordinate equal in every run is not stacked, or every
        coordinate but the dimensions' is.
    run_attrs : list, optional
        Filled with each file's global attributes, in the order of ``files``.

    Returns
    -------
    xarray.Dataset
        Loaded; the files are closed.

    Examples
    --------
    >>> import tempfile
    >>> import numpy as np
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     files = [Path(folder) / f"run{n}.nc" for n in (1, 2)]
    ...     for n, f in zip((1, 2), files):
    ...         run = xr.Dataset({"theta": ("time", np.ones(n))}, {"time": np.arange(n) / 100})
    ...         run.to_netcdf(f)
    ...     ds = stack_files(files)
    >>> ds["theta"].values
    array([[ 1., nan],
           [ 1.,  1.]])
    """
    from flumekit.io.run_files import open_runs

    with open_runs(files) as runs:
        if run_attrs is not None:
            run_attrs += [m[1] for m in runs.metas]
        return _stack(runs, scalars, coords == "all")


def _placement(values, union):
    """Locate a run's dimension coordinate ``values`` in the sorted ``union``.

    A slice when they are one contiguous stretch of it, else their indices.
    """
    import numpy as np

    at = np.searchsorted(union, values)
    if at.size and at[-1] - at[0] + 1 == at.size and np.all(np.diff(at) == 1):
        return slice(int(at[0]), int(at[-1]) + 1)
    return at


def _stack(runs, scalars: bool = False, all_coords: bool = False) -> xr.Dataset:
    """Stack the open files ``runs`` (:func:`flumekit.io.run_files.open_runs`).

    With ``scalars``, only the variables without a dimension; with ``all_coords``, a coordinate
    equal in every run stacked too (xarray's ``coords="all"``).
    """
    import numpy as np

    metas = runs.metas
    n = len(metas)
    names: list[str] = []
    for variables, *_ in metas:
        names += [k for k, v in variables.items()
                  if k not in names and not (scalars and v[0])]
    coord_names = set().union(*(c for *_, c in metas))
    dims: dict[str, tuple] = {}
    for variables, *_ in metas:
        for name, (d, *_) in variables.items():
            dims.setdefault(name, d)

    values = runs.values

    # dimension coordinates: the union of the runs' values (an outer join)
    index = {}
    for name in names:
        if dims[name] == (name,):
            have = [i for i in range(n) if name in metas[i][0]]
            axes = {i: values(i, name) for i in have}
            first = axes[have[0]]
            longest = max(axes.values(), key=len)
            if all(_equal(v, first) for v in axes.values()):
                index[name] = (first, None)
            elif (longest.dtype.kind in "iuf" and np.all(np.diff(longest) > 0)
                  and all(_equal(v, longest[:v.size]) for v in axes.values())):
                # each run's axis begins the longest (records sampled on one clock): their
                # union is the longest, sorted as np.unique would give it
                index[name] = (longest, [slice(0, axes[i].size) if i in axes else None
                                         for i in range(n)])
            else:
                union = np.unique(np.concatenate(list(axes.values())))
                index[name] = (union, [_placement(axes[i], union) if i in axes else None
                                       for i in range(n)])
    data_vars, coords = {}, {}
    for name in names:
        present = [m[0].get(name) for m in metas]
        attrs = _common_attrs([v[2] for v in present if v is not None])
        if name in index:
            coords[name] = xr.Variable((name,), index[name][0], attrs)
            continue
        d = dims[name]
        have = [i for i, v in enumerate(present) if v is not None]
        dtype = present[have[0]][4]
        small = name in coord_names or dtype.kind == "O" or not d
        read = {i: values(i, name) for i in have} if small else {}
        if (not all_coords and len(have) == n and name in coord_names
                and all(_equal(read[i], read[have[0]]) for i in have[1:])):
            coords[name] = xr.Variable(d, read[have[0]], attrs)  # equal in every run
            continue
        shape = tuple(index[k][0].size if k in index else present[have[0]][1][j]
                      for j, k in enumerate(d))
        padded = any(v is None or tuple(v[1]) != shape for v in present)
        if read:
            dtype = read[have[0]].dtype
        if padded and dtype.kind in "iu":  # as xarray promotes them to hold NaN
            dtype = np.dtype(np.float32 if dtype.itemsize <= 2 else float)
        elif padded and dtype.kind == "b":
            dtype = np.dtype(object)
        if dtype.kind == "U":
            if padded:
                dtype = np.dtype(object)
            else:  # the widest of the runs' strings
                dtype = np.result_type(*(v.dtype for v in read.values()))
        pad = np.nan if dtype.kind in "fcO" else 0
        out = np.empty((n, *shape), dtype)
        for i in range(n):
            if i not in have:
                out[i] = pad
                continue
            if not d:
                out[i] = read[i]
                continue
            where = tuple(index[k][1][i] if k in index and index[k][1] is not None
                          else slice(0, present[i][1][j]) for j, k in enumerate(d))
            if not all(isinstance(w, slice) for w in where):
                out[i] = pad
                out[i][np.ix_(*(np.arange(shape[j])[w] if isinstance(w, slice) else w
                                for j, w in enumerate(where)))] = (
                    read[i] if read else values(i, name))
                continue
            for j, w in enumerate(where):  # around the run's values: padding
                out[i][(slice(None),) * j + (slice(0, w.start),)] = pad
                out[i][(slice(None),) * j + (slice(w.stop, None),)] = pad
            if read:
                out[i][where] = read[i]
            else:  # straight into its place
                runs.read_into(i, name, out[i][where])
        var = xr.Variable(("run", *d), out, attrs)
        (coords if name in coord_names else data_vars)[name] = var
    return xr.Dataset(data_vars, coords=coords, attrs=_common_attrs([m[1] for m in metas]))
