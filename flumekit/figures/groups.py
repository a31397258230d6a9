"""Runs grouped for the campaign figures: one curve per wave height, points sorted by period."""

from __future__ import annotations

import numpy as np
import xarray as xr


def runs_of(datasets) -> list[xr.Dataset]:
    """Per-run datasets from a list of them or from one dataset stacked along ``run``."""
    if isinstance(datasets, xr.Dataset):
        if "run" in datasets.dims:
            return [datasets.isel(run=i) for i in range(datasets.sizes["run"])]
        return [datasets]
    runs = list(datasets)
    if not runs:
        raise ValueError("no run datasets given")
    return runs


def height_of(ds: xr.Dataset) -> float:
    if "wave_height" in ds.variables:
        return float(ds["wave_height"])
    if "incident_height" not in ds.variables:
        raise ValueError("a run dataset needs a 'wave_height' or an 'incident_height'")
    return round(float(ds["incident_height"]) / 0.005) * 0.005


def period_of(ds: xr.Dataset) -> float:
    return float(ds["wave_period"]) if "wave_period" in ds.variables else float(ds.measured_period)


def by_height(datasets, *names: str) -> dict[float, tuple[np.ndarray, dict[str, np.ndarray]]]:
    """{wave height [m]: (periods [s], {name: values})}, each group sorted by period."""
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
