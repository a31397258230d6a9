"""Performance figures of the irregular runs: the power matrix and the capture width ratio.

The capture width ratio is drawn against the energy period; both figures read the power-matrix
product (:mod:`flumekit.stages.performance`, :func:`flumekit.performance.power_matrix`).

References
----------
IEC TS 62600-100:2012, Marine energy - Wave, tidal and other water current converters -
Part 100: Electricity producing wave energy converters - Power performance assessment.
Babarit, A. (2015). A database of capture width ratio of wave energy converters. Renewable
Energy 80, 610-628.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from flumekit.figures.registry import register
from flumekit.figures.simulator import MARKERS, SOURCE_LINES, height_colours
from flumekit.figures.style import (
    COLOURS,
    TWO_COLUMNS,
    label,
    legend,
    new_figure,
    title,
    value_label,
)

_HM0 = label(text="Significant wave height $H_{m0}$", units="m")
_TE = label(text="Energy period $T_e$", units="s")
_CWR = label(text="Capture width ratio", units="1")


def _require(ds: xr.Dataset, *names: str) -> None:
    missing = [n for n in names if n not in ds.variables]
    if missing:
        raise ValueError(f"the power-matrix dataset lacks {missing}: pass the output of the "
                         "power_matrix stage (flumekit.performance.power_matrix)")


def _edges(bounds: xr.DataArray) -> np.ndarray:
    b = bounds.values
    return np.concatenate([b[:, 0], b[-1:, 1]])


@register("power_matrix")
def figure_power_matrix(ds: xr.Dataset, quantity: str = "capture_width_ratio"):
    r"""Draw the power matrix, one panel per source (experiment and models).

    Cells are coloured by the mean of ``quantity`` over their runs, with the count and the
    mean written in each cell.

    Parameters
    ----------
    ds : xarray.Dataset
        Power-matrix dataset (``run_count``, ``<quantity>`` over ``hm0_bin``, ``te_bin`` and
        ``source``, the bins' bounds [m], [s]).
    quantity : {"capture_width_ratio", "mean_power", "capture_width"}, optional
        The quantity coloured: CWR [-], mean power [W] or capture width [m].

    Returns
    -------
    matplotlib.figure.Figure
        Hm0 [m] against Te [s], one panel per source.

    References
    ----------
    IEC TS 62600-100:2012, Marine energy - Wave, tidal and other water current converters -
    Part 100: Electricity producing wave energy converters - Power performance assessment
    (the power matrix: the runs binned by Hm0 and Te).

    Examples
    --------
    Three runs in two cells of the matrix, measured only (one panel and its colour bar):

    >>> from flumekit.figures import figure_power_matrix
    >>> from flumekit.performance import power_matrix
    >>> ds = power_matrix([0.05, 0.07, 0.12], [1.5, 1.6, 2.4],
    ...                   {"capture_width_ratio": [0.2, 0.4, 0.5]},
    ...                   hm0_edges=[0.0, 0.1, 0.2], te_edges=[1.0, 2.0, 3.0])
    >>> fig = figure_power_matrix(ds)
    >>> len(fig.axes), [text.get_text() for text in fig.axes[0].texts]  # cell mean, count
    (2, ['0.3\nn = 2', '0.5\nn = 1'])
    >>> fig.axes[1].get_ylabel()
    'Cell mean capture width ratio [-]'
    """
    from flumekit.conventions import VARIABLES

    _require(ds, "run_count", quantity, "hm0_bin_bounds", "te_bin_bounds")
    sources = [str(s) for s in ds["source"].values] if "source" in ds.dims else [None]
    he, te = _edges(ds.hm0_bin_bounds), _edges(ds.te_bin_bounds)
    values = ds[quantity]
    finite = values.values[np.isfinite(values.values)]
    vmax = float(finite.max()) if finite.size else 1.0
    fig, axes = new_figure(1, len(sources), width=TWO_COLUMNS, height=2.9, sharey=True)
    count = ds.run_count.values
    for ax, src in zip(axes[0], sources):
        v = values.sel(source=src).values if src is not None else values.values
        mesh = ax.pcolormesh(te, he, np.ma.masked_invalid(v), cmap="viridis", vmin=0.0,
                             vmax=vmax, edgecolors="w", linewidth=0.5)
        for i, h in enumerate(ds.hm0_bin.values):
            for j, t in enumerate(ds.te_bin.values):
                if count[i, j] == 0:
                    continue
                bright = v[i, j] > 0.6 * vmax  # dark text on the light end of viridis
                ax.text(t, h, f"{v[i, j]:.2g}\nn = {count[i, j]}", ha="center", va="center",
                        fontsize=8, color="k" if bright else "w")
        ax.set_xlabel(_TE)
        ax.set_title(value_label(src) if src is not None else "")
    axes[0, 0].set_ylabel(_HM0)
    units = VARIABLES[quantity].units if quantity in VARIABLES else "1"
    text = {"capture_width_ratio": "Capture width ratio", "mean_power": "Mean power",
            "capture_width": "Capture width"}.get(quantity, quantity)
    fig.colorbar(mesh, ax=axes[0].tolist(), label=label(text=f"Cell mean {text.lower()}",
                                                        units=units))
    n = int(count.sum())
    title(fig, f"Power matrix: {n} irregular run{'s' if n != 1 else ''}, cell mean "
               f"{text.lower()} and number of runs n")
    return fig


@register("capture_width_ratio")
def figure_capture_width_ratio(ds: xr.Dataset):
    """Draw the capture width ratio of each irregular run against its energy period Te.

    One colour per Hm0 bin: the experiment as markers, the models as lines (per Hm0 bin, in
    order of Te).

    Parameters
    ----------
    ds : xarray.Dataset
        Power-matrix dataset with the per-run ``run_hm0`` [m], ``run_te`` [s] and
        ``run_capture_width_ratio`` [-] (over ``run`` and ``source``).

    Returns
    -------
    matplotlib.figure.Figure
        CWR [-] against Te [s].

    References
    ----------
    Babarit, A. (2015). A database of capture width ratio of wave energy converters.
    Renewable Energy 80, 610-628.

    Examples
    --------
    The power-matrix product with its per-run values, as the power_matrix stage writes it, of
    three runs and a model. The lines: per Hm0 bin (about 0.05 m, then 0.15 m) the
    experiment's markers and the model's line, each in order of Te:

    >>> import xarray as xr
    >>> from flumekit.figures import figure_capture_width_ratio
    >>> from flumekit.performance import power_matrix
    >>> hm0, te = [0.07, 0.05, 0.12], [1.6, 1.5, 2.4]  # [m], [s]
    >>> cwr = xr.DataArray([[0.4, 0.45], [0.2, 0.25], [0.5, 0.6]], dims=("run", "source"),
    ...                    coords={"source": ["experiment", "analytical"]})
    >>> ds = power_matrix(hm0, te, {"capture_width_ratio": cwr}, [0.0, 0.1, 0.2], [1.0, 3.0])
    >>> ds = ds.assign(run_hm0=("run", hm0), run_te=("run", te), run_capture_width_ratio=cwr)
    >>> for line in figure_capture_width_ratio(ds).axes[0].lines:
    ...     print(line.get_xdata().tolist(), line.get_ydata().tolist())
    [1.5, 1.6] [0.2, 0.4]
    [1.5, 1.6] [0.25, 0.45]
    [2.4] [0.5]
    [2.4] [0.6]
    """
    _require(ds, "run_hm0", "run_te", "run_capture_width_ratio", "hm0_bin_bounds")
    he = _edges(ds.hm0_bin_bounds)
    hm0 = ds.run_hm0.values
    row = np.clip(np.searchsorted(he, hm0, side="right") - 1, 0, he.size - 2)
    centres = ds.hm0_bin.values
    colours = height_colours(list(centres))
    fig, axes = new_figure(1, 1, width=TWO_COLUMNS, height=3.2)
    ax = axes[0, 0]
    te = ds.run_te.values
    for k, c in enumerate(centres):
        sel = row == k
        if not sel.any():
            continue
        order = np.argsort(te[sel])
        for src in ds["source"].values:
            y = ds.run_capture_width_ratio.sel(source=src).values[sel][order]
            x = te[sel][order]
            name = f"$H_{{m0}}$ ≈ {c:.3g} m ({value_label(src)})"
            if str(src) == "experiment":
                ax.plot(x, y, MARKERS[k % len(MARKERS)], color=colours[c], mec=COLOURS[
                    "experiment"], label=name)
            else:
                ax.plot(x, y, SOURCE_LINES.get(str(src), "-."), marker=".", color=colours[c],
                        label=name)
    ax.set_xlabel(_TE)
    ax.set_ylabel(_CWR)
    ax.set_ylim(bottom=0)
    legend(fig, ncols=2)
    n = ds.sizes["run"]
    title(fig, f"Capture width ratio against the energy period: {n} irregular "
               f"run{'s' if n != 1 else ''}, experiment (markers) and models (lines)")
    return fig
