"""Uncertainty figures: the budget of each result per test condition.

References
----------
JCGM 100:2008. Evaluation of measurement data - Guide to the expression of uncertainty in
measurement (GUM).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from flumekit.figures.registry import register
from flumekit.figures.style import TWO_COLUMNS, label, legend, new_figure, title

#: the results whose budgets the figure shows, with their symbols
BUDGET_RESULTS = (("incident_height", "$H_I$"), ("reflection_coefficient", "$K_r$"),
                  ("theta_amplitude", r"$\theta$ amplitude"), ("capture_factor", "$C_f$"))


def _condition_labels(budget: xr.Dataset) -> list[str]:
    out = []
    for i in range(budget.sizes["condition"]):
        c = budget.isel(condition=i)
        if "wave_period" in c.coords and np.isfinite(float(c.wave_period)):
            h = float(c.wave_height) if "wave_height" in c.coords else np.nan
            out.append(f"{float(c.wave_period):g}/{h:g}")
        else:
            out.append(f"{float(c.wave_hm0):g}/{float(c.wave_tp):g}")
    return out


@register("uncertainty_budget")
def figure_budget(budget: xr.Dataset, axes=None):
    """Draw the uncertainty budget as stacked bars, one panel per result.

    Each component's share of the combined variance of H_I, Kr, θ amplitude and C_f in every
    condition (the budget of ``budget.nc``), with the combined standard uncertainty, relative
    to the result, above each bar.

    Parameters
    ----------
    budget : xarray.Dataset
        The budget (:func:`flumekit.uncertainty.combine.combine`), along ``condition`` and
        ``uncertainty_component``.
    axes : array of matplotlib Axes, optional
        Four axes to draw in.

    Returns
    -------
    matplotlib.figure.Figure
        Variance shares [%] per condition, four panels.

    References
    ----------
    JCGM 100:2008. Evaluation of measurement data - Guide to the expression of uncertainty in
    measurement (GUM), §5.1.
    """
    import matplotlib
    from matplotlib.collections import PolyCollection

    shown = [(q, s) for q, s in BUDGET_RESULTS if f"{q}_contribution" in budget]
    if not shown:
        raise ValueError("the budget holds none of "
                         f"{[q for q, _ in BUDGET_RESULTS]}: pass budget.nc")
    comps = [str(c) for c in budget.uncertainty_component.values]
    # components that reach at least 1 % of one result's variance, the rest as "other"
    share = np.stack([budget[f"{q}_contribution"].values for q, _ in shown])
    major = [j for j in range(len(comps)) if np.nanmax(share[..., j]) >= 1.0]
    minor = [j for j in range(len(comps)) if j not in major]
    cmap = matplotlib.colormaps["tab10"]
    names = [comps[j].replace("_", " ") for j in major] + (["other"] if minor else [])
    colours = [cmap(k % 10) for k in range(len(names))]
    labels = _condition_labels(budget)
    nrow = (len(shown) + 1) // 2
    if axes is None:
        fig, axes = new_figure(nrow, 2, width=TWO_COLUMNS, row_height=2.3, sharex=True)
    fig = np.ravel(axes)[0].figure
    x = np.arange(len(labels))
    for ax, (q, sym) in zip(np.ravel(axes), shown, strict=False):
        c = budget[f"{q}_contribution"].values  # (condition, component)
        parts = [c[:, j] for j in major] + ([c[:, minor].sum(axis=1)] if minor else [])
        # one collection of bars per component (hundreds of bar patches, each its own
        # artist, cost more to create and draw than the rest of the figure)
        top = np.cumsum(parts, axis=0)
        for part, high, colour, name in zip(parts, top, colours, names, strict=True):
            low = high - part
            bars = np.stack([np.column_stack([x - 0.4, low]), np.column_stack([x + 0.4, low]),
                             np.column_stack([x + 0.4, high]),
                             np.column_stack([x - 0.4, high])], axis=1)
            ax.add_collection(PolyCollection(bars, facecolors=colour, edgecolors="none",
                                             linewidths=0, label=name))
        ax.autoscale_view()
        ax.set_ylim(0, 100)
        ax.set_title(sym, fontsize=9)
        ax.set_ylabel(label(text="Share of variance", units="percent"))
        # a tick per condition, a label on every step-th: at 8 pt, about 20 rotated labels
        # fit the axis side by side
        step = -(-len(labels) // 20)
        ax.set_xticks(x, [t if i % step == 0 else "" for i, t in enumerate(labels)],
                      rotation=90 if len(labels) > 6 else 0)
    for ax in np.ravel(axes)[-2:]:
        ax.set_xlabel(label(text="Condition T / H", units="s / m"))
    for ax in np.ravel(axes)[len(shown):]:
        ax.set_visible(False)
    n = int(budget.sizes["condition"])
    title(fig, f"Uncertainty budgets of {n} condition{'s' if n != 1 else ''}: share of each "
               "component in the combined variance")
    legend(fig, ncols=min(len(names), 4))
    return fig
