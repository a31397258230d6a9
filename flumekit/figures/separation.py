"""The incident/reflected separation of one regular-wave run: series, spectra and Kr.

Reads the processed waves dataset of one run (:func:`flumekit.waves.analyse_run`).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from flumekit.figures.style import COLOURS, new_figure, style


def figure_separation(waves: xr.Dataset, n_periods: int = 6):
    """Incident and reflected waves at the reference point, their spectra and Kr.

    Parameters
    ----------
    waves : Processed waves dataset of one run (output of ``analyse_run``).
    n_periods : Periods of the quasi-steady window shown in the time series [-].

    Returns
    -------
    matplotlib.figure.Figure: (a) measured elevation at the probe nearest ``x_ref`` and the
    separated incident and reflected waves at ``x_ref`` over the first ``n_periods`` of the
    quasi-steady window; (b) their variance spectra over the analysis band, with the
    first-harmonic reflection coefficient Kr and the harmonic ones in the legend.
    """
    for name in ("eta_incident", "spectrum_incident", "reflection_coefficient"):
        if name not in waves:
            raise ValueError(f"the waves dataset lacks '{name}': pass the output of analyse_run")
    x_ref = float(waves.attrs.get("x_ref", 0.0))
    t = waves.time.values
    t0, period = float(waves.steady_start), float(waves.measured_period)
    sel = (t >= t0) & (t <= t0 + n_periods * period)
    near = int(np.argmin(np.abs(waves.x.values - x_ref)))
    kr = float(waves.reflection_coefficient)
    with style():
        fig, axes = new_figure(2, 1, figsize=(6.5, 5.0))
        ax = axes[0, 0]
        ax.plot(t[sel], waves.eta.isel(probe=near).values[sel] * 1e3, color="0.6", lw=0.8,
                label=f"measured, {waves.probe.values[near]} (x = {waves.x.values[near]:g} m)")
        ax.plot(t[sel], waves.eta_incident.values[sel] * 1e3, color=COLOURS["incident"],
                label=f"incident at x = {x_ref:g} m")
        ax.plot(t[sel], waves.eta_reflected.values[sel] * 1e3, color=COLOURS["reflected"],
                label=f"reflected at x = {x_ref:g} m")
        ax.set_xlabel("t [s]")
        ax.set_ylabel(r"$\eta$ [mm]")
        ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.0), ncols=3, fontsize=7)
        ax = axes[1, 0]
        f = waves.frequency.values
        ax.semilogy(f, waves.spectrum_incident.values, color=COLOURS["incident"],
                    label="incident")
        ax.semilogy(f, waves.spectrum_reflected.values, color=COLOURS["reflected"],
                    label="reflected")
        harm = waves["harmonic_reflection_coefficient"].values
        text = ", ".join(f"{v:.3f}" for v in harm[1:] if np.isfinite(v))
        ax.set_title(f"first-harmonic Kr = {kr:.3f}" + (f" (harmonics 2+: {text})" if text
                                                         else ""), fontsize=8, loc="left")
        ax.set_xlabel("f [Hz]")
        ax.set_ylabel(r"S [m$^2$ s]")
        ax.legend(fontsize=7)
    return fig
