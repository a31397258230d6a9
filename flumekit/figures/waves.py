"""Wave figures: Figs. 5a and 6a of Brito et al. (2020) and the separation of one run.

All read the processed waves dataset of one run (:func:`flumekit.waves.analyse_run`); the
separation figure also takes the output of :func:`flumekit.waves.separate`.

%(references_brito2020)s, Figs. 5a and 6a.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from flumekit.docstrings import fill, filler
from flumekit.figures.registry import register
from flumekit.figures.separated import separated_elevations, separated_series
from flumekit.figures.snippets import SNIPPETS
from flumekit.figures.style import (
    COLOURS,
    TWO_COLUMNS,
    figure_axes,
    label,
    legend,
    new_figure,
    run_title,
    thin,
    title,
)

__doc__ = fill(__doc__)

#: parameters that Figs. 5a and 6a share, written once
_doc = filler(
    SNIPPETS,
    waves_run=("waves : xarray.Dataset\n"
               "    Processed waves dataset of one run (output of "
               ":func:`flumekit.waves.analyse_run`)."),
    probe_shown=("probe : str, optional\n"
                 "    Probe to show; default the probe closest to the dataset's ``x_ref``."),
    ax_new=("ax : matplotlib.axes.Axes, optional\n"
            "    Axes to draw into; default a new two-column figure."))

_TIME_OVER_PERIOD = label(text="Time over wave period $t/T$", units="1")
#: the number of waves of Fig. 6a in its title, in words up to ten (the paper's "five waves")
_COUNTS = ("no waves", "one wave", *(f"{n} waves" for n in (
    "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten")))


def _probe(waves: xr.Dataset, probe) -> str:
    if probe is not None:
        if probe not in waves.probe.values:
            raise ValueError(f"probe {probe!r} is not in the dataset "
                             f"({waves.probe.values.tolist()})")
        return probe
    x_ref = float(waves.attrs.get("x_ref", 0.0))
    return waves.probe.values[int(np.argmin(np.abs(waves.x.values - x_ref)))]


def _normalised(waves: xr.Dataset, probe) -> tuple[str, np.ndarray, np.ndarray, float, float]:
    for name in ("eta", "amplitude_scale", "measured_period", "steady_start"):
        if name not in waves:
            raise ValueError(f"the waves dataset lacks '{name}': pass the output of analyse_run")
    p = _probe(waves, probe)
    period = float(waves.measured_period)
    scale = float(waves.amplitude_scale.sel(probe=p))
    return p, waves.time.values / period, waves.eta.sel(probe=p).values / scale, period, scale


def _elevation_axes(fig, ax, xlim: tuple[float, float], waves: xr.Dataset, what: str, p: str,
                    scale: float, period: float) -> None:
    """Label the axes of η/A_s against t/T, add the legend and a title with the probe and scales.

    The title names the run, ``what`` is shown at probe ``p`` (its position) and the
    normalising scales: the amplitude scale A_s [m] and the period T [s].
    """
    ax.set_xlim(*xlim)
    ax.set_xlabel(_TIME_OVER_PERIOD)
    ax.set_ylabel(label(text=r"$\eta/A_s$", units="1"))
    where = f"probe {p} at x = {float(waves.x.sel(probe=p)):.2f} m"
    title(fig, run_title(waves, f"{what}, {where}")
          + f"\n$A_s$ = {scale:.3f} m, $T$ = {period:.2f} s")
    legend(fig)


@register("fig05a")
@_doc
def figure_5a(waves: xr.Dataset, probe=None, ax=None):
    """Draw the full time series of the normalised elevation η/A_s against t/T (Fig. 5a).

    Parameters
    ----------
    %(waves_run)s
    %(probe_shown)s
    %(ax_new)s

    Returns
    -------
    matplotlib.figure.Figure
        η/A_s [-] against t/T [-]. The dash-dotted line is the amplitude scale A_s
        (η/A_s = 1), the vertical line the start of the quasi-steady window (the paper's
        crest criterion) and, dashed where it opens later, the start of the analysis window
        (the separated reflection settled too).

    %(references_brito2020)s, Fig. 5a.

    Examples
    --------
    Ten periods of a regular wave (T = 2 s, amplitude 0.05 m) ramped up over its first two:

    >>> import numpy as np
    >>> import xarray as xr
    >>> from flumekit.figures import figure_5a
    >>> t = np.arange(0.0, 20.0, 0.05)
    >>> eta = 0.05 * np.minimum(t / 4.0, 1.0) * np.sin(np.pi * t)
    >>> waves = xr.Dataset({"eta": (("probe", "time"), [eta]), "measured_period": 2.0,
    ...                     "amplitude_scale": ("probe", [0.05]), "steady_start": 4.0},
    ...                    coords={"probe": ["WP1"], "x": ("probe", [0.0]), "time": t})
    >>> fig = figure_5a(waves)
    >>> fig.axes[0].get_xlabel()
    'Time over wave period $t/T$ [-]'
    >>> measured, scale, steady = fig.axes[0].lines
    >>> float(max(measured.get_ydata())), float(steady.get_xdata()[0])  # η/A_s; 4 s / 2 s
    (1.0, 2.0)
    """
    p, tt, eta, period, scale = _normalised(waves, probe)
    fig, ax = figure_axes(ax, height=2.4)
    ax.plot(*thin(tt, eta, fig.get_figwidth()), color=COLOURS["experiment"], lw=0.5,
            label=f"measured, {p}")
    ax.axhline(1.0, color="0.3", ls="-.", lw=0.9, label="amplitude scale $A_s$")
    crest = float(waves["crest_steady_start"]) if "crest_steady_start" in waves else None
    ax.axvline((float(waves.steady_start) if crest is None else crest) / period,
               color="tab:red", lw=0.9, label="quasi-steady from (crests within "
               f"{float(waves.attrs.get('tolerance', 0.02)):.0%})")
    if crest is not None and float(waves.steady_start) > crest + 0.5 * period:
        ax.axvline(float(waves.steady_start) / period, color="tab:red", lw=0.9, ls="--",
                   label="analysis window from (reflection settled)")
    _elevation_axes(fig, ax, (tt[0], tt[-1]), waves, "Normalised surface elevation", p,
                    scale, period)
    return fig


@register("fig06a")
@_doc
def figure_6a(waves: xr.Dataset, start: float = 65.0, n_waves: int = 5, probe=None, ax=None):
    """Draw five consecutive waves of the normalised elevation (Brito et al. 2020, Fig. 6a).

    Parameters
    ----------
    %(waves_run)s
    %(fig6_window)s
    %(probe_shown)s
    %(ax_new)s

    Returns
    -------
    matplotlib.figure.Figure
        η/A_s [-] against t/T [-], with the amplitude scale as a dash-dotted line at
        η/A_s = 1.

    %(references_brito2020)s, Fig. 6a.

    Examples
    --------
    The paper's window (t/T = 65 to 70) lies beyond a record of 15 periods; another is chosen:

    >>> import numpy as np
    >>> import xarray as xr
    >>> from flumekit.figures import figure_6a
    >>> t = np.linspace(0.0, 30.0, 601)  # T = 2 s, 40 samples per period
    >>> eta = xr.DataArray([0.04 * np.sin(np.pi * t)], dims=("probe", "time"),
    ...                    coords={"probe": ["WP2"], "x": ("probe", [-1.5]), "time": t})
    >>> waves = eta.to_dataset(name="eta").assign(
    ...     amplitude_scale=eta.max("time"), measured_period=2.0, steady_start=6.0)
    >>> figure_6a(waves)
    Traceback (most recent call last):
    ...
    ValueError: t/T = 65..70 lies outside the record (t/T = 0.0..15.0)
    >>> fig = figure_6a(waves, start=10.0, n_waves=3)
    >>> ax = fig.axes[0]
    >>> [float(v) for v in ax.get_xlim()], len(ax.lines[0].get_xdata())  # 3 x 40 + 1 samples
    ([10.0, 13.0], 121)
    >>> fig.get_suptitle().split(",")[0]
    'Three waves'
    """
    p, tt, eta, period, scale = _normalised(waves, probe)
    stop = start + n_waves
    if start < tt[0] or stop > tt[-1]:
        raise ValueError(f"t/T = {start:g}..{stop:g} lies outside the record "
                         f"(t/T = {tt[0]:.1f}..{tt[-1]:.1f})")
    sel = (tt >= start) & (tt <= stop)
    fig, ax = figure_axes(ax, height=2.2)
    ax.plot(tt[sel], eta[sel], color=COLOURS["experiment"], label=f"measured, {p}")
    ax.axhline(1.0, color="0.3", ls="-.", lw=0.9, label="amplitude scale $A_s$")
    shown = (_COUNTS[n_waves] if 0 <= n_waves < len(_COUNTS) else f"{n_waves} waves"
             ).capitalize()
    _elevation_axes(fig, ax, (start, stop), waves, shown, p, scale, period)
    return fig


def _spans(mask: np.ndarray) -> list[tuple[int, int]]:
    """Return the (first, last) indices of each run of True in ``mask``."""
    edges = np.diff(np.concatenate([[0], mask.astype(np.int8), [0]]))
    return list(zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1) - 1))


@register("separation")
def separation(waves: xr.Dataset, n_waves: int = 5, n_bins: int = 4):
    """Draw the incident/reflected separation of one run: what a wave engineer checks first.

    (a) Incident and reflected elevation at the reference point ``x_ref`` over ``n_waves``
    periods from the start of the separated window; (b) their variance density spectra
    (log scale), averaged over bands of ``n_bins`` periodogram bins (2 ``n_bins`` degrees of
    freedom, stated in the panel title; Bendat & Piersol 2010, §11.5: a raw periodogram has 2
    and scatters by its own size), with the bins masked as ill-conditioned shaded and the
    analysis band marked. The title gives Kr, H_I and the masked energy fraction.

    Parameters
    ----------
    waves : xarray.Dataset
        Output of :func:`flumekit.waves.analyse_run` (a processed waves dataset) or of
        :func:`flumekit.waves.separate`: ``eta_incident``, ``eta_reflected`` [m] over time,
        ``spectrum_incident``, ``spectrum_reflected`` [m2 s], ``masked`` over frequency,
        ``reflection_coefficient`` [-], ``incident_height`` [m].
    n_waves : int, optional
        Periods shown in (a) [-]; the whole separated series if the dataset gives no period.
    n_bins : int, optional
        Periodogram bins per band of the spectra in (b) [-]; 1 shows the periodogram.

    Returns
    -------
    matplotlib.figure.Figure
        Two columns wide: (a) elevations [m] against time [s], (b) variance densities [m2 s]
        against frequency [Hz].

    References
    ----------
    Bendat, J. S. & Piersol, A. G. (2010). Random Data: Analysis and Measurement Procedures,
    4th ed. Wiley, §11.5.
    """
    need = ("eta_incident", "eta_reflected", "spectrum_incident", "spectrum_reflected",
            "reflection_coefficient", "incident_height")
    t, inc, ref = separated_series(waves, need, "analyse_run or separate")
    ok = np.isfinite(inc) & np.isfinite(ref)
    if not ok.any():
        raise ValueError("the separated series hold no finite sample")
    t0 = float(t[ok][0])
    period = next((float(waves[n]) for n in ("measured_period", "period")
                   if n in waves.variables), None)
    f1 = waves.attrs.get("fundamental_frequency")  # the output of separate
    if period is None and f1 is not None and float(f1) > 0:
        period = 1.0 / float(f1)
    shown = ok & (t <= t0 + n_waves * period) if period else ok
    f = waves["frequency"].values
    masked = (waves["masked"].values.astype(bool) if "masked" in waves.variables
              else np.zeros(f.size, bool))
    fig, axes = new_figure(1, 2, width=TWO_COLUMNS, height=2.8)
    ax_t, ax_f = axes[0]
    x_ref = float(waves.attrs.get("x_ref", 0.0))
    separated_elevations(ax_t, t[shown], inc[shown], ref[shown],
                         f"at the reference point x = {x_ref:g} m")
    from flumekit.waves.irregular import band_average

    # masked bins stay out of the bands: their separation is not defined
    n_bins = int(max(1, min(n_bins, f.size)))
    fb, *bands = band_average(f, waves["spectrum_incident"].values,
                              waves["spectrum_reflected"].values, n_bins=n_bins,
                              valid=~masked)
    peak = 0.0
    for name, s in zip(("incident", "reflected"), bands):
        pos = np.isfinite(s) & (s > 0)
        ax_f.semilogy(fb[pos], s[pos], ".-", ms=2, lw=0.7, color=COLOURS[name])
        peak = max(peak, float(s[pos].max())) if pos.any() else peak
    if masked.any():
        df = float(np.median(np.diff(f))) if f.size > 1 else 0.0
        for i, j in _spans(masked):
            ax_f.axvspan(f[i] - df / 2, f[j] + df / 2, color="0.8", lw=0,
                         label="masked (ill-conditioned)")
    band = waves.attrs.get("band")
    if band is not None:
        for edge in np.ravel(band):
            ax_f.axvline(float(edge), color="0.4", ls=":", lw=0.9, label="analysis band")
    if peak > 0:  # seven decades below the peak: the noise floor, not the round-off
        ax_f.set_ylim(bottom=peak * 1e-7)
    ax_f.set_xlabel(label("frequency", "$f$"))
    ax_f.set_ylabel(label(text="Variance density $S$", units="m2 s"))
    ax_f.set_title(f"(b) spectra, bands of {n_bins} bins, {2 * n_bins} degrees of freedom"
                   if n_bins > 1 else "(b) periodograms, 2 degrees of freedom")
    kr = float(waves["reflection_coefficient"])
    h_i = float(waves["incident_height"])
    extra = ""
    if "masked_energy_fraction" in waves.variables:
        extra = f", masked energy {100 * float(waves['masked_energy_fraction']):.1f} %"
    title(fig, run_title(waves, "Wave separation") + "\n"
          + f"$K_r$ = {kr:.3f}, $H_I$ = {h_i:.3f} m{extra}")
    legend(fig, ncols=4)
    return fig
