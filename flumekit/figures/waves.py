"""Figures 5a and 6a of Brito et al. 2020: normalised free-surface elevation of a regular-wave run.

Both read the processed waves dataset of one run (:func:`flumekit.waves.analyse_run`).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from flumekit.figures.style import COLOURS, figure_axes, style


def _probe(waves: xr.Dataset, probe) -> str:
    if probe is not None:
        if probe not in waves.probe.values:
            raise ValueError(f"probe {probe!r} is not in the dataset "
                             f"({waves.probe.values.tolist()})")
        return probe
    x_ref = float(waves.attrs.get("x_ref", 0.0))
    return waves.probe.values[int(np.argmin(np.abs(waves.x.values - x_ref)))]


def _normalised(waves: xr.Dataset, probe) -> tuple[str, np.ndarray, np.ndarray, float]:
    for name in ("eta", "amplitude_scale", "measured_period", "steady_start"):
        if name not in waves:
            raise ValueError(f"the waves dataset lacks '{name}': pass the output of analyse_run")
    p = _probe(waves, probe)
    period = float(waves.measured_period)
    scale = float(waves.amplitude_scale.sel(probe=p))
    return p, waves.time.values / period, waves.eta.sel(probe=p).values / scale, period


def figure_5a(waves: xr.Dataset, probe=None, ax=None):
    """Full time series of the normalised elevation η/A_s against t/T (Brito et al. 2020, Fig. 5a).

    Parameters
    ----------
    waves : Processed waves dataset of one run (output of ``analyse_run``).
    probe : Probe to show; default the probe closest to the dataset's ``x_ref``.
    ax : Axes to draw into; default a new figure.

    Returns
    -------
    matplotlib.figure.Figure. The dash-dotted line is the amplitude scale A_s (η/A_s = 1), the
    vertical line the start of the quasi-steady window.
    """
    p, tt, eta, period = _normalised(waves, probe)
    fig, ax = figure_axes(ax)
    with style():
        ax.plot(tt, eta, color=COLOURS["experiment"], lw=0.6, label=f"{p}")
        ax.axhline(1.0, color="0.3", ls="-.", lw=0.9, label="amplitude scale")
        ax.axvline(float(waves.steady_start) / period, color="tab:red", lw=0.9,
                   label="quasi-steady")
        ax.set_xlim(tt[0], tt[-1])
        ax.set_xlabel("t/T")
        ax.set_ylabel(r"$\eta/A_s$")
        ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.0), ncols=3, fontsize=7)
    return fig


def figure_6a(waves: xr.Dataset, start: float = 65.0, n_waves: int = 5, probe=None, ax=None):
    """Five consecutive waves of the normalised elevation (Brito et al. 2020, Fig. 6a).

    Parameters
    ----------
    waves : Processed waves dataset of one run (output of ``analyse_run``).
    start : First t/T shown [-] (the paper: 65).
    n_waves : Number of periods shown [-].
    probe : Probe to show; default the probe closest to the dataset's ``x_ref``.
    ax : Axes to draw into; default a new figure.

    Returns
    -------
    matplotlib.figure.Figure with the amplitude scale as a dash-dotted line at η/A_s = 1.
    """
    p, tt, eta, _ = _normalised(waves, probe)
    stop = start + n_waves
    if start < tt[0] or stop > tt[-1]:
        raise ValueError(f"t/T = {start:g}..{stop:g} lies outside the record "
                         f"(t/T = {tt[0]:.1f}..{tt[-1]:.1f})")
    sel = (tt >= start) & (tt <= stop)
    fig, ax = figure_axes(ax)
    with style():
        ax.plot(tt[sel], eta[sel], color=COLOURS["experiment"], label=f"{p}")
        ax.axhline(1.0, color="0.3", ls="-.", lw=0.9)
        ax.set_xlim(start, stop)
        ax.set_xlabel("t/T")
        ax.set_ylabel(r"$\eta/A_s$")
    return fig
