"""The separation of one irregular-wave run: elevations, spectra with Kr(f), wave heights.

Reads the processed waves dataset of an irregular run
(:func:`flumekit.waves.analyse_irregular_run`).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from flumekit.figures.registry import register
from flumekit.figures.separated import separated_elevations, separated_series
from flumekit.figures.style import (
    COLOURS,
    TWO_COLUMNS,
    label,
    legend,
    new_figure,
    run_title,
    title,
)

__all__ = ["separation"]

_NEEDS = ("eta_incident", "eta_reflected", "spectrum_incident", "spectrum_reflected",
          "reflection_coefficient_spectrum", "reflection_coefficient", "hm0", "tp", "te",
          "individual_wave_height", "analysis_start")


@register("separation_irregular")
def separation(waves: xr.Dataset, n_waves: int = 12):
    """Draw the incident/reflected separation of one irregular run.

    (a) Incident and reflected elevation at the device over ``n_waves`` peak periods from the
    start of the analysed span; (b) their variance density spectra, smoothed over frequency
    bands (the degrees of freedom in the title of the panel), with the reflection function
    Kr(f) on a second axis over the bands holding 99 % of the incident energy; (c) the
    exceedance probability of the individual incident wave heights (zero up-crossing) against
    the Rayleigh distribution of a narrow-band sea, P(H > h) = exp(-2 h² / Hm0²)
    (Longuet-Higgins 1952).

    Parameters
    ----------
    waves : xarray.Dataset
        A processed waves dataset of an irregular run
        (:func:`flumekit.waves.analyse_irregular_run`).
    n_waves : int
        Peak periods shown in (a) [-].

    Returns
    -------
    matplotlib.figure.Figure
        Two columns wide: (a) elevations [m] against time [s], (b) variance densities
        [m2 s] and Kr(f) [-] against frequency [Hz], (c) exceedance probability [-] against
        H/Hm0 [-].

    References
    ----------
    Longuet-Higgins, M. S. (1952). On the statistical distribution of the heights of sea
    waves. Journal of Marine Research 11, 245-266.
    """
    t, inc, ref = separated_series(waves, _NEEDS, "analyse_irregular_run")
    tp = float(waves["tp"])
    t0 = float(waves["analysis_start"])
    shown = np.isfinite(inc) & (t >= t0) & (t <= t0 + n_waves * tp)
    f = waves["frequency"].values
    s_i, s_r = waves["spectrum_incident"].values, waves["spectrum_reflected"].values
    kr = waves["reflection_coefficient_spectrum"].values
    dof = waves["spectrum_incident"].attrs.get("degrees_of_freedom")
    x_ref = float(waves.attrs.get("x_ref", 0.0))
    hm0 = float(waves["hm0"])

    fig, axes = new_figure(1, 3, width=TWO_COLUMNS, height=2.9,
                           gridspec_kw={"width_ratios": [1.3, 1.2, 1.0]})
    ax_t, ax_f, ax_h = axes[0]
    separated_elevations(ax_t, t[shown], inc[shown], ref[shown], f"at x = {x_ref:g} m",
                         lw=0.7)

    good = np.isfinite(s_i) & np.isfinite(s_r)
    for name, s in (("incident", s_i), ("reflected", s_r)):
        ax_f.plot(f[good], s[good], color=COLOURS[name])
    ax_f.set_xlabel(label("frequency", "$f$"))
    ax_f.set_ylabel(label(text="Variance density $S$", units="m2 s"))
    ax_f.set_title("(b) spectra" + (f", {int(dof)} degrees of freedom" if dof else ""))
    ax_f.set_xlim(f[0], f[-1])
    ax_f.set_ylim(bottom=0)
    # Kr(f) where the incident wave has energy: elsewhere the ratio of two noises
    energy = np.cumsum(np.where(good, s_i, 0.0))
    energy = energy / energy[-1] if energy[-1] > 0 else energy
    held = good & (energy >= 0.005) & (energy <= 0.995)
    ax_k = ax_f.twinx()
    ax_k.plot(f[held], kr[held], "o", ms=2.5, color="0.3", label="$K_r(f)$")
    ax_k.axhline(float(waves["reflection_coefficient"]), color="0.3", ls="--", lw=0.8,
                 label="bulk $K_r$")
    ax_k.set_ylim(0, max(1.0, float(np.nanmax(kr[held])) * 1.1) if held.any() else 1.0)
    ax_k.set_ylabel(label("reflection_coefficient_spectrum", "$K_r(f)$", text=" "))
    ax_k.grid(False)

    h = waves["individual_wave_height"].values
    h = np.sort(h[np.isfinite(h)])[::-1]
    exceed = np.arange(1, h.size + 1) / (h.size + 1)
    ax_h.semilogy(h / hm0, exceed, ".", ms=2.5, color=COLOURS["incident"],
                  label="incident waves")
    x = np.linspace(0, max(float(h[0] / hm0) * 1.05, 1.0), 100) if h.size else np.array([0])
    ax_h.semilogy(x, np.exp(-2 * x ** 2), color="k", lw=0.8, label="Rayleigh")
    ax_h.set_ylim(bottom=0.5 / (h.size + 1) if h.size else 1e-3, top=1.0)
    ax_h.set_xlabel(label(text="$H/H_{m0}$", units="1"))
    ax_h.set_ylabel(label(text="Exceedance probability", units="1"))
    ax_h.set_title(f"(c) {h.size} waves")

    title(fig, run_title(waves, "Wave separation, irregular sea") + "\n"
          + f"$H_{{m0}}$ = {hm0:.3f} m, $T_p$ = {tp:.2f} s, $T_e$ = "
          f"{float(waves['te']):.2f} s, bulk $K_r$ = "
          f"{float(waves['reflection_coefficient']):.3f}")
    legend(fig, ncols=6)
    return fig
