"""Opening what the pipeline wrote: one dataset, or the runs of a stage along ``run``."""

from __future__ import annotations

from pathlib import Path

import xarray as xr

from flumekit.errors import InputError
from flumekit.io.netcdf import read_dataset

__all__ = ["open_processed", "processed_names"]


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
    runs = [read_dataset(f) for f in files]
    return xr.concat(runs, dim="run", join="outer", combine_attrs="drop_conflicts",
                     coords="different", compat="equals")
