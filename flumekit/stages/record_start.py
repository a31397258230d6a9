"""A run's record start as run.toml declares it, where the record gives none."""

from __future__ import annotations


def declared_start(ds, declared: str, run: str):
    """Return ``ds`` with the start run.toml declares, where its record gives none.

    A record whose own start departs from the declared one by more than 1 s (both in UTC, or
    both on the lab's clock) is an error: metadata that contradicts the record is not used
    silently.

    Parameters
    ----------
    ds : xarray.Dataset
        A run's product with a ``time`` coordinate.
    declared : str
        The start run.toml declares (ISO 8601; a trailing ``Z``: UTC).
    run : str
        The run, named in the error.

    Returns
    -------
    xarray.Dataset
        ``ds``, or a copy whose time axis carries ``declared`` when its record gives no start.

    Raises
    ------
    flumekit.errors.InputError
        When the record's own start departs from the declared one by more than 1 s.
    """
    import numpy as np

    from flumekit import conventions
    from flumekit.errors import InputError

    found = conventions.record_start(ds)
    if found is None:
        ds = ds.copy()
        ds["time"].attrs[conventions.RECORD_START] = declared
        return ds
    if found.endswith("Z") == declared.endswith("Z"):
        gap = abs(np.datetime64(found.rstrip("Z"), "ns") - np.datetime64(declared.rstrip("Z"),
                                                                         "ns"))
        if gap > np.timedelta64(1, "s"):
            raise InputError(ds.attrs.get(conventions.SOURCE_FILE) or f"run {run}",
                             f"the record starts at {found}, but run.toml of run {run} declares "
                             f"start = {declared}: correct or remove 'start' in run.toml",
                             field="start")
    return ds
