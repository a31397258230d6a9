"""The report's uncertainty sections, as HTML for :func:`flumekit.report.write_report`.

Results with their uncertainties, full-scale values and the budgets.
"""

from __future__ import annotations

import html

import numpy as np
import xarray as xr

#: results shown per condition: (variable, symbol)
RESULTS = (("incident_height", "H<sub>I</sub>"), ("measured_period", "T"),
           ("reflection_coefficient", "K<sub>r</sub>"), ("theta_amplitude", "θ amplitude"),
           ("mean_power", "P̄"), ("capture_factor", "C<sub>f</sub>"), ("hm0", "H<sub>m0</sub>"),
           ("te", "T<sub>e</sub>"))
#: results whose full-scale value is shown when the campaign declares [scale]
PROTOTYPE = ("incident_height", "measured_period", "mean_power", "hm0", "te")


def _e(x) -> str:
    return html.escape(str(x), quote=True)


def _g(v, digits: int = 4) -> str:
    return "" if v is None or not np.isfinite(v) else f"{v:.{digits}g}"


def _table(header, rows, left: int = 1) -> str:
    th = "".join(f'<th class="l">{h}</th>' if i < left else f"<th>{h}</th>"
                 for i, h in enumerate(header))
    body = "".join("<tr>" + "".join(f'<td class="l">{c}</td>' if i < left else f"<td>{c}</td>"
                                    for i, c in enumerate(r)) + "</tr>" for r in rows)
    return f"<table><thead><tr>{th}</tr></thead><tbody>{body}</tbody></table>"


def _units(var: xr.DataArray) -> str:
    u = var.attrs.get("units", "1")
    return "" if u in ("1", "") else f" [{_e(u)}]"


def _condition_name(ds: xr.Dataset, i: int) -> str:
    c = ds.isel(condition=i)
    parts = []
    for k, fmt in (("wave_period", "T = {:g} s"), ("wave_height", "H = {:g} m"),
                   ("wave_hm0", "Hm0 = {:g} m"), ("wave_tp", "Tp = {:g} s"),
                   ("wave_te", "Te = {:g} s")):
        if k in c.coords and np.isfinite(float(c[k])):
            parts.append(fmt.format(float(c[k])))
    return ", ".join(parts)


def _value(ds: xr.Dataset, q: str, i: int) -> str:
    v = float(ds[q].values[i])
    if not np.isfinite(v):
        return ""
    key = f"{q}_expanded_uncertainty"
    if key in ds and np.isfinite(float(ds[key].values[i])):
        return f"{_g(v)} ± {_g(float(ds[key].values[i]), 2)}"
    key = f"{q}_uncertainty_type_a"
    if key in ds and np.isfinite(float(ds[key].values[i])):
        return f"{_g(v)} ± {_g(2 * float(ds[key].values[i]), 2)}*"
    return _g(v)


def results_section(conditions: xr.Dataset) -> str:
    """Render the per-condition results with their expanded uncertainties as HTML.

    Each result is shown as mean ± expanded uncertainty (or ± twice the Type A uncertainty,
    marked, where no Type B propagation was made), with a table of full-scale values when
    ``conditions`` carries a Froude scale (attributes ``froude_scale``, ``model_density`` and
    ``prototype_density``).

    Parameters
    ----------
    conditions : xarray.Dataset
        ``conditions.nc``: :func:`flumekit.uncertainty.condition_statistics` with the combined
        uncertainties of :func:`flumekit.uncertainty.combine.combine`.

    Returns
    -------
    str
        An HTML fragment: a note and one or two tables.

    References
    ----------
    JCGM 100:2008 (GUM), §6 (expanded uncertainty). JCGM 101:2008 (Monte Carlo propagation).

    Examples
    --------
    >>> import xarray as xr
    >>> from flumekit.uncertainty.html import results_section
    >>> c = xr.Dataset({"n_repeats": ("condition", [1]),
    ...                 "incident_height": ("condition", [0.15], {"units": "m"})},
    ...                coords={"wave_period": ("condition", [2.0])})
    >>> "<td>0.15</td>" in results_section(c)
    True
    """
    shown = [(q, s) for q, s in RESULTS if q in conditions]
    header = ["condition", "repeats"] + [f"{s}{_units(conditions[q])}" for q, s in shown]
    rows = [[_e(_condition_name(conditions, i)), str(int(conditions.n_repeats.values[i]))]
            + [_value(conditions, q, i) for q, _ in shown]
            for i in range(conditions.sizes["condition"])]
    k = [np.atleast_1d(conditions[f"{q}_expanded_uncertainty"].attrs.get("coverage_factor",
                                                                          np.nan))
         for q, _ in shown if f"{q}_expanded_uncertainty" in conditions]
    kk = np.concatenate(k) if k else np.array([])
    kk = kk[np.isfinite(kk)]
    note = ("<p>Each value is the mean over the condition's repeats ± its expanded uncertainty "
            "at 95 % coverage: Type A from the repeats combined with the Type B components of "
            "<code>[uncertainty]</code> propagated by Monte Carlo (JCGM 101) through the "
            "analysis; coverage factors from the Welch-Satterthwaite effective degrees of "
            f"freedom ({_g(kk.min(), 3)} to {_g(kk.max(), 3)}). "
            if kk.size else "<p>")
    note += ("* repeat scatter only (2 u<sub>A</sub>): no Type B propagation for this result. "
             "A condition with one run has no Type A evaluation (its repeatability is not "
             "known).</p>")
    out = note + _table(header, rows, left=1)
    scale = conditions.attrs.get("froude_scale")
    if scale:
        from flumekit.scaling import froude_factor

        r = (float(conditions.attrs["prototype_density"])
             / float(conditions.attrs["model_density"]))
        proto = [q for q in PROTOTYPE if q in conditions]
        head = ["condition"] + [f"{q.replace('_', ' ')}{_units(conditions[q])}" for q in proto]
        rows = []
        for i in range(conditions.sizes["condition"]):
            row = [_e(_condition_name(conditions, i))]
            for q in proto:
                f = froude_factor(conditions[q].attrs.get("units", "1"), float(scale), r)
                v = float(conditions[q].values[i]) * f
                key = f"{q}_expanded_uncertainty"
                u = float(conditions[key].values[i]) * f if key in conditions else np.nan
                row.append(f"{_g(v)} ± {_g(u, 2)}" if np.isfinite(u) else _g(v))
            rows.append(row)
        out += (f"<h3>Full scale (Froude similitude, 1:{_g(float(scale))}, ρ "
                f"{_g(float(conditions.attrs['model_density']))} → "
                f"{_g(float(conditions.attrs['prototype_density']))} kg m<sup>-3</sup>)</h3>"
                + _table(head, rows))
    return out


def budget_section(budget: xr.Dataset, figure: str | None = None) -> str:
    """Render the uncertainty budget of each result as HTML.

    Per result: each component's type, input uncertainty, sensitivity, contribution c u and
    share of the combined variance (median and largest over the conditions).

    Parameters
    ----------
    budget : xarray.Dataset
        ``budget.nc`` (:func:`flumekit.uncertainty.combine.combine`).
    figure : str, optional
        Relative path of the budget figure from the report page; None: no figure.

    Returns
    -------
    str
        An HTML fragment: a note, the figure and one table per result.

    References
    ----------
    JCGM 100:2008 (GUM), §5.1.3 (sensitivity coefficients) and G.4.
    """
    parts = []
    comps = [str(c) for c in budget.uncertainty_component.values]
    units = ([str(u) for u in budget.input_units.values] if "input_units" in budget
             else [""] * len(comps))
    kind = ([str(u) for u in budget.component_type.values] if "component_type" in budget
            else [""] * len(comps))
    u_in = (budget.input_standard_uncertainty.values if "input_standard_uncertainty" in budget
            else np.full(len(comps), np.nan))
    for q, sym in RESULTS:
        if f"{q}_contribution" not in budget:
            continue
        share = budget[f"{q}_contribution"].values  # (condition, component)
        cu = budget[f"{q}_budget"].values
        sens = budget[f"{q}_sensitivity"].values
        rows = []
        for j, c in enumerate(comps):
            rows.append([_e(c.replace("_", " ")), _e(kind[j]),
                         f"{_g(float(u_in[j]), 3)} {_e(units[j])}".strip()
                         if np.isfinite(u_in[j]) else "", _g(float(np.median(sens[:, j])), 3),
                         _g(float(np.median(cu[:, j])), 3),
                         _g(float(np.median(share[:, j])), 3),
                         _g(float(np.max(share[:, j])), 3)])
        parts.append(f"<h3>{sym}{_units(budget[f'{q}_budget'])}</h3>" + _table(
            ["component", "type", "standard uncertainty of the input", "sensitivity (median)",
             "c u (median)", "share of variance % (median)", "share % (largest)"], rows))
    fig = (f'<figure><img src="{_e(figure)}" alt="uncertainty budgets"><figcaption>Share of '
           "each component in the combined variance, per condition</figcaption></figure>"
           if figure else "")
    return (f"<p>Budgets over {budget.sizes['condition']} conditions (GUM linear propagation "
            "with numerically estimated sensitivity coefficients; repeatability: the Type A "
            "uncertainty of the condition, sensitivity 1). Sensitivities are per unit of the "
            "component's input.</p>" + fig + "".join(parts))


def report_sections(conditions: xr.Dataset, budget: xr.Dataset | None = None,
                    figure: str | None = "figures/uncertainty_budget.png"
                    ) -> list[tuple[str, str, str]]:
    """Return the report's uncertainty sections as ``(anchor, heading, html)``.

    Parameters
    ----------
    conditions : xarray.Dataset
        ``conditions.nc`` (:func:`flumekit.uncertainty.condition_statistics` with the
        combined uncertainties).
    budget : xarray.Dataset, optional
        ``budget.nc``; no budget section without it (or when it is empty).
    figure : str, optional
        Relative path of the budget figure from the report page.

    Returns
    -------
    list of (str, str, str)
        Sections for :func:`flumekit.report.write_report`'s ``sections`` list.

    Examples
    --------
    >>> import xarray as xr
    >>> c = xr.Dataset({"n_repeats": ("condition", [1]),
    ...                 "incident_height": ("condition", [0.15], {"units": "m"})},
    ...                coords={"wave_period": ("condition", [2.0])})
    >>> [a for a, _, _ in report_sections(c)]
    ['uncertainty-results']
    """
    out = [("uncertainty-results", "Results with uncertainties", results_section(conditions))]
    if budget is not None and "uncertainty_component" in budget.dims and any(
            v.endswith("_contribution") for v in budget.data_vars):
        out.append(("uncertainty-budget", "Uncertainty budgets", budget_section(budget,
                                                                                 figure)))
    return out
