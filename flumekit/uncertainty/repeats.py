"""Repeat statistics: a condition's mean, scatter and Type A uncertainty over its repeats.

GUM (JCGM 100:2008) §4.2: the best estimate of a quantity measured in n independent repeats is
their mean q̄; its Type A standard uncertainty is the experimental standard deviation of the mean
s(q̄) = s(q) / sqrt(n), with n - 1 degrees of freedom. ITTC 7.5-02-01-01 (2021) §2.3 applies it
to repeated model tests of one condition.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import xarray as xr

from flumekit.conventions import UNCERTAIN_QUANTITIES

#: per-run summary quantities whose repeat statistics a condition dataset holds, in this order
#: (those present in the summaries): regular waves, the flap, irregular seas
QUANTITIES = UNCERTAIN_QUANTITIES
#: the coordinates that name a condition: the targets of regular and of irregular runs
CONDITION_COORDS = ("wave_period", "wave_height", "wave_hm0", "wave_tp", "wave_te")


def condition_statistics(summary: xr.Dataset, quantities=None) -> xr.Dataset:
    """Compute the repeat statistics and Type A standard uncertainty of each test condition.

    Per test condition: the number of repeats and each quantity's mean, standard deviation,
    standard error and Type A standard uncertainty.

    Parameters
    ----------
    summary : xarray.Dataset
        Per-run summary along ``run`` (e.g. ``waves_summary`` merged with ``flap_summary``)
        with the condition coordinates present among :data:`CONDITION_COORDS` (a regular run
        has NaN irregular targets and the reverse) and scalar quantities per run.
    quantities : sequence of str, optional
        Quantities to summarise; default those of :data:`QUANTITIES` in ``summary``.

    Returns
    -------
    xarray.Dataset
        Along ``condition`` (sorted by the condition coordinates): the condition coordinates,
        ``n_repeats`` (runs of the condition), for each quantity ``X`` its mean ``X`` [unit of
        X], ``X_std`` (ddof = 1; NaN for a single run), ``X_standard_error`` and
        ``X_uncertainty_type_a`` = s / sqrt(n) (attribute ``degrees_of_freedom`` = n - 1 per
        condition in ``X_dof``), linked by ``ancillary_variables``. Runs whose value is NaN
        (a quantity that does not apply) are left out of that quantity's statistics.

    Raises
    ------
    ValueError
        When ``summary`` has no condition coordinate or lacks a requested quantity.

    References
    ----------
    JCGM 100:2008 (GUM), §4.2.1-4.2.3. ITTC Recommended procedure 7.5-02-01-01 (2021),
    Guide to the expression of uncertainty in experimental hydrodynamics.

    Examples
    --------
    >>> import xarray as xr
    >>> s = xr.Dataset({"incident_height": ("run", [0.150, 0.152, 0.251])},
    ...                coords={"wave_period": ("run", [2.0, 2.0, 3.5]),
    ...                        "wave_height": ("run", [0.15, 0.15, 0.25])})
    >>> c = condition_statistics(s)
    >>> c.n_repeats.values.tolist(), round(float(c.incident_height_std[0]), 5)
    ([2, 1], 0.00141)
    """
    from flumekit import conventions

    keys = [k for k in CONDITION_COORDS if k in summary.coords]
    if not keys:
        raise ValueError("the summary has no condition coordinates "
                         f"({', '.join(CONDITION_COORDS)})")
    names = [q for q in (quantities or QUANTITIES) if q in summary.data_vars]
    missing = [q for q in (quantities or ()) if q not in summary.data_vars]
    if missing:
        raise ValueError(f"quantities {missing} are not in the summary")
    frame = pd.DataFrame({k: np.asarray(summary[k].values, float) for k in keys + names})
    # NaN targets (a regular run's Hm0) are part of the key: pandas groups them with dropna=False
    groups = frame.groupby(keys, dropna=False, sort=True)
    n_runs = groups.size()
    count = groups[names].count()
    mean = groups[names].mean()
    std = groups[names].std(ddof=1)
    index = n_runs.index.to_frame(index=False)
    coords = {k: ("condition", index[k].to_numpy(float)) for k in keys}
    data = {"n_repeats": ("condition", n_runs.to_numpy(np.int64))}
    for q in names:
        n = count[q].to_numpy(float)
        se = std[q].to_numpy(float) / np.sqrt(np.where(n > 0, n, np.nan))
        anc = f"{q}_std {q}_standard_error {q}_uncertainty_type_a"
        data[q] = ("condition", mean[q].to_numpy(float),
                   {"cell_methods": "run: mean", "ancillary_variables": anc})
        data[f"{q}_std"] = ("condition", std[q].to_numpy(float),
                            {"cell_methods": "run: standard_deviation"})
        data[f"{q}_standard_error"] = ("condition", se)
        data[f"{q}_uncertainty_type_a"] = ("condition", se, {
            "method": "GUM Type A: s / sqrt(n) over the repeats of the condition",
            "degrees_of_freedom_variable": f"{q}_dof"})
        data[f"{q}_dof"] = ("condition", n - 1.0)
    ds = xr.Dataset(data, coords={"condition": np.arange(len(n_runs)), **coords})
    return conventions.annotate(ds)
