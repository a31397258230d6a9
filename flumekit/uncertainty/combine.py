"""A condition's combined uncertainty and budget: Type A from its repeats, Type B propagated.

GUM §5.1.2 and G.4: u_c² = u_A² + u_B², effective degrees of freedom after Welch-Satterthwaite
ν_eff = u_c⁴ / (u_A⁴ / ν_A + u_B⁴ / ν_B) and the coverage factor k = t_0.975(ν_eff) of the
95 % expanded uncertainty U = k u_c (ITTC 7.5-02-01-01 §2.5).

u_B of a condition is the root-mean-square of its runs' Type B uncertainties: most declared
components (calibration, probe positions, depth, inertia) are common to every repeat and do
not average out; the random ones (noise, resolution) are also in the repeats' scatter, so they
are counted twice, on the safe side, where a condition has repeats.
"""

from __future__ import annotations

import numpy as np
import xarray as xr


def _condition_of(runs: xr.Dataset, conditions: xr.Dataset) -> np.ndarray:
    """Index of each run's condition (-1: none) by the condition coordinates."""
    keys = [k for k in conditions.coords if k != "condition" and k in runs.coords]
    a = np.stack([np.asarray(runs[k].values, float) for k in keys], axis=-1)  # (run, key)
    b = np.stack([np.asarray(conditions[k].values, float) for k in keys], axis=-1)
    same = (a[:, None, :] == b[None, :, :]) | (np.isnan(a[:, None, :]) & np.isnan(b[None, :, :]))
    match = same.all(axis=-1)
    return np.where(match.any(axis=1), match.argmax(axis=1), -1)


def combine(conditions: xr.Dataset, runs: xr.Dataset) -> tuple[xr.Dataset, xr.Dataset]:
    """Combine the Type A and Type B uncertainty of every condition result, with the budget.

    Parameters
    ----------
    conditions : xarray.Dataset
        Repeat statistics (:func:`flumekit.uncertainty.condition_statistics`).
    runs : xarray.Dataset
        The per-run propagation (:func:`flumekit.uncertainty.propagation.propagate`) of the
        runs, stacked along ``run`` with their condition coordinates.

    Returns
    -------
    conditions : xarray.Dataset
        ``conditions`` with, for each propagated result X, ``X_uncertainty_type_b``,
        ``X_uncertainty`` (combined; attributes ``method``) and ``X_expanded_uncertainty``
        (attributes ``coverage_factor`` per condition, ``effective_degrees_of_freedom``,
        ``coverage_probability``), linked from X by ``ancillary_variables``.
    budget : xarray.Dataset
        Along ``condition`` and ``uncertainty_component`` (the Type B components and
        ``repeatability``, Type A): ``component_type``, ``input_standard_uncertainty`` and
        ``input_units``, and for each result X ``X_sensitivity``, ``X_budget`` (c u, unit of
        X) and ``X_contribution`` [%] of the combined variance.

    References
    ----------
    JCGM 100:2008 (GUM), §5.1.2, G.4.1 (Welch-Satterthwaite), G.6.

    Examples
    --------
    Three repeats, u_A = s / sqrt(3) = 0.001 / sqrt(3), and a Type B of 0.001 m each:

    >>> import xarray as xr
    >>> from flumekit.uncertainty import condition_statistics
    >>> from flumekit.uncertainty.combine import combine
    >>> s = xr.Dataset({"incident_height": ("run", [0.150, 0.152, 0.151])},
    ...                coords={"wave_period": ("run", [2.0] * 3),
    ...                        "wave_height": ("run", [0.15] * 3)})
    >>> runs = s.assign(incident_height_uncertainty_type_b=(
    ...     "run", [0.001] * 3, {"degrees_of_freedom": 49}))
    >>> runs = runs.assign_coords(uncertainty_component=["probe_noise"])
    >>> c, budget = combine(condition_statistics(s), runs)
    >>> round(float(c.incident_height_uncertainty[0]), 7)  # sqrt(u_A² + u_B²)
    0.0011547
    >>> k = c.incident_height_expanded_uncertainty.attrs["coverage_factor"]
    >>> round(float(k[0]), 3)  # t_0.975 of ν_eff = 23.4
    2.067

    The pipeline writes the results as ``conditions.nc`` and ``budget.nc`` (the
    ``uncertainty`` scene).
    """
    from scipy import stats

    from flumekit import conventions

    idx = _condition_of(runs, conditions)
    nc = conditions.sizes["condition"]
    onehot = (idx[:, None] == np.arange(nc)[None, :]).astype(float)  # (run, condition)
    results = [q for q in conditions.data_vars if f"{q}_uncertainty_type_b" in runs]
    comps = [str(c) for c in runs["uncertainty_component"].values]
    out = conditions.copy()
    budget = {}
    for q in results:
        ub2 = np.asarray(runs[f"{q}_uncertainty_type_b"].values, float) ** 2
        ok = np.isfinite(ub2)
        w = onehot * ok[:, None]
        cnt = w.sum(axis=0)
        u_b = np.sqrt(np.where(cnt > 0, (w * np.where(ok, ub2, 0.0)[:, None]).sum(axis=0)
                               / np.maximum(cnt, 1), np.nan))
        dof_b = float(runs[f"{q}_uncertainty_type_b"].attrs.get("degrees_of_freedom", np.inf))
        u_a = conditions[f"{q}_uncertainty_type_a"].values
        dof_a = conditions[f"{q}_dof"].values
        has_a = np.isfinite(u_a) & (dof_a > 0)
        u_a0 = np.where(has_a, u_a, 0.0)
        u_c = np.sqrt(u_a0 ** 2 + u_b ** 2)
        denom = np.where(has_a, u_a0 ** 4 / np.where(has_a, dof_a, 1.0), 0.0) + u_b ** 4 / dof_b
        nu = np.where(denom > 0, u_c ** 4 / np.where(denom > 0, denom, 1.0), np.inf)
        k = stats.t.ppf(0.975, nu)
        out[f"{q}_uncertainty_type_b"] = ("condition", u_b, {
            "method": "root-mean-square of the runs' Monte Carlo (JCGM 101) Type B standard "
                      "uncertainties"})
        out[f"{q}_uncertainty"] = ("condition", u_c, {
            "method": "GUM combined standard uncertainty sqrt(u_A^2 + u_B^2); u_A = 0 where "
                      "the condition has a single run (repeatability not evaluated)",
            "repeatability_evaluated": has_a.astype(np.int8)})
        out[f"{q}_expanded_uncertainty"] = ("condition", k * u_c, {
            "coverage_probability": 0.95, "coverage_factor": k,
            "effective_degrees_of_freedom": np.where(np.isfinite(nu), nu, -1.0),
            "method": "k u_c with k = t_0.975 of the Welch-Satterthwaite effective degrees of "
                      "freedom (-1: infinite)"})
        anc = out[q].attrs.get("ancillary_variables", "")
        out[q].attrs["ancillary_variables"] = " ".join(
            [anc, f"{q}_uncertainty_type_b", f"{q}_uncertainty", f"{q}_expanded_uncertainty"]
        ).strip()
        if f"{q}_budget" in runs:
            # runs without a budget (the linear propagation runs on one run per condition:
            # the sensitivities of repeats are the same) are left out of its mean
            raw = np.asarray(runs[f"{q}_budget"].values, float)  # (run, component)
            has = np.isfinite(raw).all(axis=1).astype(float)
            wb = onehot * has[:, None]
            nb = np.maximum(wb.sum(axis=0), 1)[:, None]
            cu = np.sqrt((wb.T @ np.nan_to_num(raw ** 2)) / nb)  # (condition, component)
            sens = np.sqrt((wb.T @ np.nan_to_num(
                np.asarray(runs[f"{q}_sensitivity"].values, float) ** 2)) / nb)
            cu = np.concatenate([cu, u_a0[:, None]], axis=1)
            sens = np.concatenate([sens, np.ones((nc, 1))], axis=1)
            total = (cu ** 2).sum(axis=1, keepdims=True)
            budget[f"{q}_budget"] = (("condition", "uncertainty_component"), cu)
            budget[f"{q}_sensitivity"] = (("condition", "uncertainty_component"), sens, {
                "comment": "root-mean-square over the condition's runs; repeatability: 1"})
            budget[f"{q}_contribution"] = (("condition", "uncertainty_component"),
                                           100.0 * cu ** 2 / np.where(total > 0, total, 1.0))
    names = comps + ["repeatability"]
    if "input_units" in runs:
        first = runs.isel(run=int(np.argmax([str(v) != "nan" for v in
                                             runs["input_units"].values[:, 0]]))
                          if runs["input_units"].ndim == 2 else 0)
        budget["input_units"] = ("uncertainty_component",
                                 [str(v) for v in first["input_units"].values] + ["(result)"])
        budget["input_standard_uncertainty"] = (
            "uncertainty_component",
            np.append(first["input_standard_uncertainty"].values.astype(float), np.nan),
            {"comment": "repeatability: the Type A uncertainty of each result (its budget)"})
        budget["component_type"] = ("uncertainty_component", ["B"] * len(comps) + ["A"])
    coords = {k: v for k, v in conditions.coords.items()}
    bds = xr.Dataset(budget, coords={**coords, "uncertainty_component": names})
    bds["n_repeats"] = conditions["n_repeats"]
    return conventions.annotate(out), conventions.annotate(bds)
