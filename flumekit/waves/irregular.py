"""Incident and reflected sea states of one irregular-wave run.

The pure function behind the pipeline's waves stage for ``kind = "irregular"`` runs: the span
after the wavemaker's ramp, the least-squares separation of every frequency bin (Zelt &
Skjelbreia with three or more probes), the incident and reflected spectra smoothed over
frequency bands, the reflection function Kr(f) and the bulk Kr, the spectral parameters and
the zero-crossing statistics of the incident wave at the device, and its energy flux.
"""

from __future__ import annotations

import warnings

import numpy as np
import xarray as xr

from flumekit import conventions
from flumekit.docstrings import doc
from flumekit.waves.layout import MAX_CONDITION
from flumekit.waves.records import probe_record
from flumekit.waves.separation import as_probe_time, separate
from flumekit.waves.spectra import energy_flux, spectral_parameters
from flumekit.waves.statistics import wave_statistics
from flumekit.waves.theory import G, group_velocity

__all__ = ["LowFrequencyWarning", "active_span", "analyse_irregular_run", "band_average"]

#: the analysis band in multiples of the peak frequency: JONSWAP spectra hold nothing below
#: fp/2 and 0.25 % of Hm0 above 4 fp (the f^-5 tail of a Pierson-Moskowitz spectrum)
BAND = (0.5, 4.0)


class LowFrequencyWarning(UserWarning):
    """The records hold energy below half the peak frequency (bound long waves, seiching).

    Examples
    --------
    A sea of 90 components at 0.3-0.6 Hz, 2 mm each, and a 20 s seiche of 1 cm: the seiche
    holds 1² / (1² + 90 × 0.2²) = 22 % of the variance, outside the analysis band, and
    :func:`analyse_irregular_run` says so:

    >>> import warnings
    >>> import numpy as np
    >>> from flumekit.waves import analyse_irregular_run, wavenumber
    >>> from flumekit.waves.irregular import LowFrequencyWarning
    >>> t, x = np.arange(3000) / 10.0, np.array([-3.0, -2.4, -2.0])  # 300 s at 10 Hz [s], [m]
    >>> f = np.append(np.arange(90, 180) / 300.0, 0.05)  # [Hz]
    >>> a = np.append(np.full(90, 0.002), 0.01)  # [m]
    >>> phase = np.random.default_rng(1).uniform(0.0, 2 * np.pi, f.size)
    >>> arg = 2 * np.pi * f * t[:, None, None] - wavenumber(2 * np.pi * f, 0.8) * x[:, None]
    >>> eta = (a * np.cos(arg + phase)).sum(-1).T  # (probe, time)
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     r = analyse_irregular_run(eta, 0.8, x=x, sampling_rate=10.0, peak_period=2.2,
    ...                               span=(0.0, 300.0))
    >>> caught[0].category is LowFrequencyWarning, round(float(r.low_frequency_energy_fraction), 3)
    (True, 0.217)
    >>> print(caught[0].message)
    21.7% of the records' variance lies below fp/2 = 0.227 Hz (bound long waves or seiching)...
    """


def active_span(values: np.ndarray, time: np.ndarray, peak_frequency: float,
                travel_time: float = 0.0, threshold: float = 0.25, periods: float = 20.0
                ) -> tuple[float, float]:
    """Find the span of a record where the sea state is established.

    The variance over a running window of ``periods`` peak periods is compared with its
    median over the record: the span begins where the window, wholly inside the record,
    first reaches ``threshold`` times that level (the end of the wavemaker's ramp),
    plus ``travel_time`` (the reflected waves must have reached every probe), and ends at the
    start of the last window that does (a wavemaker stopped before the record ends), or at the
    end of the record.

    Parameters
    ----------
    values : numpy.ndarray
        Surface elevation [m], (probe, time) or (time,); probes are averaged.
    time : numpy.ndarray
        Sample times [s], uniform.
    peak_frequency : float
        Peak frequency of the sea state [Hz].
    travel_time : float
        Time added to the start for reflections to reach the probes [s].
    threshold : float
        Share of the median running variance that counts as established [-]. The variance of
        a window of 20 peak periods of a JONSWAP sea has about 12 degrees of freedom: it falls
        below a quarter of its mean in a wave group's lull with a probability of 0.4 %.
    periods : float
        Length of the running window in peak periods [-].

    Returns
    -------
    start, end : float
        The span [s].

    Examples
    --------
    A unit sine ramped over 50 s, 40 s windows: the established variance is 0.5 m², and the
    first window whose mean variance reaches a quarter of it ends at 42.3 s, before the ramp
    does (the threshold lets a wave group's lull pass):

    >>> import numpy as np
    >>> t = np.arange(0, 400, 0.04)
    >>> eta = np.minimum(t / 50, 1) * np.sin(2 * np.pi * 0.5 * t)
    >>> start, end = active_span(eta, t, 0.5)
    >>> round(start, 1), round(end, 1)
    (42.3, 400.0)
    """
    v = np.atleast_2d(np.asarray(values, dtype=float))
    v = v - v.mean(axis=1, keepdims=True)
    power = np.mean(v * v, axis=0)
    dt = (time[-1] - time[0]) / (time.size - 1)
    w = max(int(round(periods / peak_frequency / dt)), 1)
    if w >= time.size:
        raise ValueError(f"the record ({time[-1] - time[0]:.4g} s) is shorter than {periods:g} "
                         f"peak periods ({periods / peak_frequency:.4g} s)")
    csum = np.concatenate([[0.0], np.cumsum(power)])
    running = (csum[w:] - csum[:-w]) / w  # window [i, i + w)
    level = np.median(running)
    active = np.flatnonzero(running >= threshold * level)
    start = float(time[active[0] + w - 1]) + travel_time  # window wholly past the ramp
    if active[-1] == running.size - 1:  # established to the end of the record
        return start, float(time[-1] + dt)
    return start, float(time[active[-1]]) + dt  # window wholly before the decay


def band_average(frequency: np.ndarray, *densities: np.ndarray, n_bins: int,
                 valid: np.ndarray | None = None) -> tuple[np.ndarray, ...]:
    """Densities averaged over consecutive groups of ``n_bins`` frequency bins.

    Each band of ``n_bins`` periodogram bins has 2 ``n_bins`` degrees of freedom (Bendat &
    Piersol 2010, §11.5); the bins left over at the top are dropped.

    Parameters
    ----------
    frequency : numpy.ndarray
        Bin frequencies [Hz], uniform.
    *densities : numpy.ndarray
        Densities on those bins (e.g. [m2 s]).
    n_bins : int
        Bins per band [-].
    valid : numpy.ndarray of bool, optional
        Bins to average (masked bins left out; a band of no valid bin is NaN).

    Returns
    -------
    tuple of numpy.ndarray
        The band centres [Hz], then each density averaged.

    Examples
    --------
    >>> import numpy as np
    >>> f, s = band_average(np.arange(1.0, 9.0), np.arange(8.0), n_bins=4)
    >>> f.tolist(), s.tolist()
    ([2.5, 6.5], [1.5, 5.5])
    """
    n = (frequency.size // n_bins) * n_bins
    if n == 0:
        raise ValueError(f"fewer than {n_bins} bins to average")
    shape = (n // n_bins, n_bins)
    ok = np.ones(n, bool) if valid is None else np.asarray(valid, bool)[:n]
    count = ok.reshape(shape).sum(axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        out = tuple(np.where(count > 0, np.where(ok, d[:n], 0.0).reshape(shape).sum(axis=1)
                             / count, np.nan) for d in densities)
    return (frequency[:n].reshape(shape).mean(axis=1), *out)


@doc
def analyse_irregular_run(eta, depth: float, x_ref: float = 0.0, *, x=None,
                          sampling_rate: float | None = None, method: str = "zelt_skjelbreia",
                          separation_probes=None, gauge_weights=None,
                          peak_period: float | None = None,
                          span: tuple[float, float] | None = None,
                          band: tuple[float, float] | None = None, n_bins: int | None = None,
                          max_condition: float = MAX_CONDITION,
                          low_frequency_warning: float = 0.05, rho: float = 1000.0,
                          g: float = G) -> xr.Dataset:
    """Analyse the probe records of one irregular-wave run.

    Parameters
    ----------
    eta : xarray.DataArray, pandas.DataFrame or array_like
        Calibrated surface elevation [m], dims ("probe", "time") with coordinate ``x`` [m] on
        ``probe`` and ``time`` [s]; or a DataFrame or array with ``x`` and ``sampling_rate``
        (:func:`flumekit.waves.probe_record`).
    %(depth)s
    x_ref : float
        Position where the incident and reflected waves are returned [m] (the device).
    %(probe_positions)s
    %(sampling_rate_eta)s
    method : str
        Separation method (:func:`flumekit.waves.separate`); Zelt & Skjelbreia (1992) by
        default, which takes any number of probes from two.
    separation_probes : sequence of str, optional
        The probes used for the separation; default all.
    gauge_weights : sequence of float, optional
        Weight of each separation probe in the least squares (Zelt & Skjelbreia 1992);
        default equal weights.
    peak_period : float, optional
        The sea state's peak period, as targeted [s]: it sets the analysis band, the running
        window of the span detection and the smoothing, where the records' own peak could be
        a seiche's; default the peak of the probes' mean spectrum (smoothed over 0.01 Hz).
        The reported Tp is measured either way.
    span : tuple of float, optional
        (start, end) of the analysed span [s], either of them None to detect it; default
        both detected by :func:`active_span` (after the wavemaker's ramp and the time the
        reflection from ``x_ref`` takes to reach the farthest probe at the group velocity of
        1.5 fp; a wave returning from further away, from a beach, is not seen: declare the
        start then).
    band : tuple of float, optional
        Analysis band (f_min, f_max) [Hz]; default :data:`BAND` times the peak frequency,
        below the Nyquist frequency.
    n_bins : int, optional
        Periodogram bins averaged into one band of the smoothed spectra and Kr(f) [-];
        default the number spanning fp/8 (at least 8: 16 degrees of freedom). Kr(f) is a
        ratio of two such estimates: on the virtual flume's 280 s span (fp = 0.5 Hz, 0.5 mm
        probe noise) its largest error over the bands holding 90 % of the energy is 0.07 with
        bands of fp/16 and 0.009 with fp/8. The peak period is found on finer bands of fp/16
        (at least 4 bins) whatever ``n_bins`` is.
    max_condition : float
        Bins whose least-squares system has a larger condition number are masked [-].
    low_frequency_warning : float
        Share of the records' variance below fp/2 above which a
        :class:`LowFrequencyWarning` is issued (and the dataset says so) [-].
    rho : float
        Water density [kg m-3] (the energy flux).
    %(g)s

    Returns
    -------
    xarray.Dataset
        ``eta`` (probe, time): the records; ``eta_incident``, ``eta_reflected`` (time) at
        ``x_ref``, NaN outside the analysed span; scalars ``analysis_start``,
        ``analysis_end`` [s], ``reflection_coefficient`` (bulk, sqrt(m0R / m0I)),
        ``masked_energy_fraction``, ``low_frequency_energy_fraction``, ``energy_flux`` J [W
        m-1], the spectral parameters of the incident wave
        (:func:`flumekit.waves.spectral_parameters`: ``hm0``, ``tp``, ``te``, ...) and of
        the reflected one (``reflected_hm0``), its zero-crossing statistics
        (:func:`flumekit.waves.wave_statistics`: ``h1_3``, ``hmax``, ...), the individual
        incident wave heights and periods over ``wave``; over ``frequency`` (band centres):
        ``spectrum_incident``, ``spectrum_reflected`` [m2 s] and
        ``reflection_coefficient_spectrum`` Kr(f) [-], smoothed over bands of ``n_bins``
        bins (attribute ``degrees_of_freedom``).

    Raises
    ------
    ValueError
        An analysed span shorter than 20 peak periods, or no separable energy.

    References
    ----------
    Mansard, E. P. D. & Funke, E. R. (1980). The measurement of incident and reflected spectra
    using a least squares method. Proc. 17th Coastal Engineering Conference, 154-172.

    Zelt, J. A. & Skjelbreia, J. E. (1992). Estimating incident and reflected wave fields
    using an arbitrary number of wave gauges. Proc. 23rd Coastal Engineering Conference,
    777-789.

    ITTC (2021). Recommended procedure 7.5-02-07-03.7, Wave energy converter model test
    experiments, §4.

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.waves import analyse_irregular_run, wavenumber
    >>> rng = np.random.default_rng(1)
    >>> t = np.arange(0, 900, 0.04)
    >>> f = np.arange(1, 400) / 900 + 0.2
    >>> a = 0.004 * np.exp(-((f - 0.5) / 0.08) ** 2)
    >>> k = wavenumber(2 * np.pi * f, 0.8)
    >>> x = np.array([-3.0, -2.4, -2.0])
    >>> ph = rng.uniform(0, 2 * np.pi, f.size)
    >>> arg = 2 * np.pi * f * t[:, None] + ph
    >>> eta = np.stack([(a * (np.cos(arg - k * xp) + 0.3 * np.cos(arg + k * xp))).sum(1)
    ...                 for xp in x])
    >>> r = analyse_irregular_run(eta, 0.8, x=x, sampling_rate=25.0, span=(0, 900))
    >>> round(float(r.reflection_coefficient), 2)
    0.3
    """
    if x is not None or sampling_rate is not None or not isinstance(eta, xr.DataArray):
        eta = probe_record(eta, x=x, sampling_rate=sampling_rate)
    eta = eta.transpose("probe", "time")
    v, t, xs, probes = as_probe_time(eta.fillna(0.0))
    sep = eta if separation_probes is None else eta.sel(probe=list(separation_probes))
    dt = (t[-1] - t[0]) / (t.size - 1)
    nyq = 0.5 / dt

    # the peak of the probes' mean spectrum, smoothed (the raw periodogram's peak is a
    # random bin), unless the target is given
    vs = sep.fillna(0.0).values
    vs = vs - vs.mean(axis=1, keepdims=True)
    freq = np.fft.rfftfreq(t.size, dt)
    power = np.mean(np.abs(np.fft.rfft(vs, axis=1)) ** 2, axis=0)
    if peak_period is None:
        smooth = max(int(round(0.01 / freq[1])), 1)
        kernel = np.ones(smooth) / smooth
        fp = float(freq[1 + np.argmax(np.convolve(power[1:], kernel, mode="same"))])
    else:
        fp = 1.0 / float(peak_period)
    xsep = sep["x"].values.astype(float)
    given = (None, None) if span is None else tuple(span)
    detected = None in given
    if detected:
        cg = float(group_velocity(1.0 / (1.5 * fp), depth, g))
        found = active_span(vs, t, fp, travel_time=float(np.max(np.abs(xsep - x_ref))) / cg)
        given = tuple(f if v is None else v for v, f in zip(given, found))
    start, end = float(given[0]), float(given[1])
    inside = (t >= start) & (t < end)
    if inside.sum() * dt < 20.0 / fp:
        raise ValueError(f"the analysed span {start:.1f}-{end:.1f} s holds fewer than 20 peak "
                         f"periods ({1 / fp:.3g} s); a longer record is needed")
    i0, i1 = int(np.argmax(inside)), int(inside.size - np.argmax(inside[::-1]))
    if band is None:
        band = (BAND[0] * fp, min(BAND[1] * fp, 0.98 * nyq))

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        s = separate(sep.isel(time=slice(i0, i1)), depth, method=method, band=band,
                     x_ref=x_ref, regular=False, max_condition=max_condition,
                     gauge_weights=gauge_weights, g=g)
    for w in caught:
        warnings.warn(w.message, w.category, stacklevel=2)

    f = s["frequency"].values
    df = 1.0 / ((i1 - i0) * dt)
    if n_bins is None:
        n_bins = max(int(round(fp / 8 / df)), 8)
    valid = s["masked"].values == 0
    fb, si, sr = band_average(f, s["spectrum_incident"].values, s["spectrum_reflected"].values,
                              n_bins=n_bins, valid=valid)
    f_peak, s_peak = band_average(f, s["spectrum_incident"].values, valid=valid,
                                  n_bins=max(int(round(fp / 16 / df)), 4))
    with np.errstate(invalid="ignore", divide="ignore"):
        kr_f = np.sqrt(sr / si)
    dof = 2 * n_bins

    raw_i = xr.DataArray(np.where(valid, s["spectrum_incident"].values, 0.0),
                         dims="frequency", coords={"frequency": f})
    # Te is the name every wave-energy standard uses for Tm-1,0 (IEC TS 62600-100)
    params = spectral_parameters(raw_i).rename(tm_10="te")
    smoothed = spectral_parameters(xr.DataArray(np.nan_to_num(s_peak), dims="frequency",
                                                coords={"frequency": f_peak}))
    # the peak of the smoothed spectrum: the raw periodogram's is one random bin
    for name in ("tp", "tp_smoothed"):
        params[name] = smoothed[name]
    reflected = spectral_parameters(xr.DataArray(np.where(valid, s["spectrum_reflected"]
                                                          .values, 0.0),
                                                 dims="frequency", coords={"frequency": f}))
    stats = wave_statistics(s["eta_incident"].values, 1.0 / dt)
    flux = energy_flux(raw_i, depth, rho=rho, g=g)

    # energy below fp/2 in the records (bound long waves, seiching), outside the band
    seg = vs[:, i0:i1] - vs[:, i0:i1].mean(axis=1, keepdims=True)
    fseg = np.fft.rfftfreq(seg.shape[1], dt)
    pseg = np.mean(np.abs(np.fft.rfft(seg, axis=1)) ** 2, axis=0)
    inband = (fseg > 0) & (fseg < nyq)
    low = float(pseg[inband & (fseg < 0.5 * fp)].sum() / pseg[inband].sum())
    low_flag = low > low_frequency_warning
    if low_flag:
        warnings.warn(f"{low:.1%} of the records' variance lies below fp/2 = {0.5 * fp:.3g} Hz "
                      "(bound long waves or seiching), outside the separation band: the "
                      "incident sea state and Kr leave it out", LowFrequencyWarning,
                      stacklevel=2)

    inc = np.full(t.size, np.nan)
    ref = np.full(t.size, np.nan)
    inc[i0:i1] = s["eta_incident"].values
    ref[i0:i1] = s["eta_reflected"].values
    fill = {"comment": "NaN outside the analysed span [analysis_start, analysis_end]"}
    smooth_attrs = {"degrees_of_freedom": dof,
                    "smoothing": f"periodogram of the analysed span averaged over bands of "
                                 f"{n_bins} bins ({n_bins * df:.4g} Hz; masked bins left out)"}
    data = {
        "eta": (("probe", "time"), v),
        "eta_incident": ("time", inc, fill), "eta_reflected": ("time", ref, fill),
        # the times of the first and last samples analysed: inside any other instrument's
        # record that spans the probes' (an end one step later would not be)
        "analysis_start": ((), float(t[i0])), "analysis_end": ((), float(t[i1 - 1])),
        "spectrum_incident": ("frequency", si, smooth_attrs),
        "spectrum_reflected": ("frequency", sr, smooth_attrs),
        "reflection_coefficient_spectrum": ("frequency", kr_f, smooth_attrs),
        "reflection_coefficient": s["reflection_coefficient"],
        "masked_energy_fraction": s["masked_energy_fraction"],
        "low_frequency_energy_fraction": ((), low, {"flag": int(low_flag),
                                                    "threshold": low_frequency_warning}),
        "energy_flux": flux.assign_attrs(definition="rho g integral of S_I(f) c_g(f, h) df "
                                         "over the band"),
        "reflected_hm0": reflected["hm0"],
        **{name: params[name] for name in params.data_vars},
        **{name: stats[name] for name in stats.data_vars},
    }
    ds = xr.Dataset(data, coords={"probe": eta.probe.values, "x": ("probe", xs), "time": t,
                                  "frequency": fb},
                    attrs={"method": method, "x_ref": float(x_ref), "depth": float(depth),
                           "separation_probes": s.attrs["probes"], "band": s.attrs["band"],
                           "max_condition": max_condition, "peak_frequency_estimate": fp,
                           "span": ", ".join(f"{name} {'detected' if v is None else 'given'}"
                                             for name, v in zip(("start", "end"),
                                                                (None, None) if span is None
                                                                else span))})
    return conventions.annotate(ds)
