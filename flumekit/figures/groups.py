"""Runs grouped for the campaign figures: one curve per wave height, points sorted by period."""

from __future__ import annotations

import numpy as np
import xarray as xr

from flumekit.docstrings import filler

#: the Parameters section of the functions that read one value of a run
_doc = filler(run_only="Parameters\n----------\n%(run_dataset)s")


def runs_of(datasets) -> list[xr.Dataset]:
    """Return the per-run datasets from a list of them or from one stacked along ``run``.

    Parameters
    ----------
    datasets : xarray.Dataset or iterable of xarray.Dataset
        One dataset (stacked along ``run``, or a single run) or a list of run datasets.

    Returns
    -------
    list of xarray.Dataset
        One dataset per run.

    Raises
    ------
    ValueError
        An empty list.
    """
    if isinstance(datasets, xr.Dataset):
        if "run" in datasets.dims:
            return [datasets.isel(run=i) for i in range(datasets.sizes["run"])]
        return [datasets]
    runs = list(datasets)
    if not runs:
        raise ValueError("no run datasets given")
    return runs


@_doc
def height_of(ds: xr.Dataset) -> float:
    """Return the wave height [m] that groups a run.

    The declared ``wave_height``, else the measured ``incident_height`` rounded to 5 mm.

    %(run_only)s

    Returns
    -------
    float
        The height [m].

    Raises
    ------
    ValueError
        Neither ``wave_height`` nor ``incident_height`` in the dataset.

    Examples
    --------
    >>> import xarray as xr
    >>> from flumekit.figures.groups import height_of
    >>> round(height_of(xr.Dataset({"incident_height": 0.1234})), 3)
    0.125
    """
    if "wave_height" in ds.variables:
        return float(ds["wave_height"])
    if "incident_height" not in ds.variables:
        raise ValueError("a run dataset needs a 'wave_height' or an 'incident_height'")
    return round(float(ds["incident_height"]) / 0.005) * 0.005


@_doc
def period_of(ds: xr.Dataset) -> float:
    """Return the wave period [s] of a run: ``wave_period``, else ``measured_period``.

    %(run_only)s

    Returns
    -------
    float
        The period [s].

    Examples
    --------
    >>> import xarray as xr
    >>> from flumekit.figures.groups import period_of
    >>> period_of(xr.Dataset({"wave_period": 2.0, "measured_period": 1.98}))
    2.0
    """
    return float(ds["wave_period"]) if "wave_period" in ds.variables else float(ds.measured_period)


def by_height(datasets, *names: str) -> dict[float, tuple[np.ndarray, dict[str, np.ndarray]]]:
    """Group runs by wave height, each group sorted by period.

    Parameters
    ----------
    datasets : xarray.Dataset or iterable of xarray.Dataset
        The runs (:func:`runs_of`).
    *names : str
        Scalar variables to collect.

    Returns
    -------
    dict
        {wave height [m]: (periods [s], {name: values})}, heights ascending.

    Raises
    ------
    ValueError
        A run lacks one of ``names``, or has no height.

    Examples
    --------
    >>> import xarray as xr
    >>> from flumekit.figures.groups import by_height
    >>> runs = [xr.Dataset({"wave_height": 0.1, "wave_period": t, "mean_power": p})
    ...         for t, p in ((3.0, 2.0), (2.0, 1.0))]
    >>> periods, values = by_height(runs, "mean_power")[0.1]
    >>> periods.tolist(), values["mean_power"].tolist()
    ([2.0, 3.0], [1.0, 2.0])
    """
    groups: dict[float, list[xr.Dataset]] = {}
    for ds in runs_of(datasets):
        missing = [n for n in names if n not in ds.variables]
        if missing:
            raise ValueError(f"a run dataset lacks {missing}")
        groups.setdefault(height_of(ds), []).append(ds)
    out = {}
    for h in sorted(groups):
        runs = sorted(groups[h], key=period_of)
        out[h] = (np.array([period_of(r) for r in runs]),
                  {n: np.array([float(r[n]) for r in runs]) for n in names})
    return out
