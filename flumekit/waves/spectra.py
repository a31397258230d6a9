"""Sea-state analysis in the frequency domain: spectrum, spectral parameters, energy flux.

:func:`spectrum` estimates the one-sided variance density of a surface-elevation record by
Welch's method, with its equivalent degrees of freedom and a chi-squared confidence interval;
:func:`spectral_parameters` reduces a variance density to the spectral moments and the
sea-state parameters of the IAHR/PIANC (1986) list (Hm0, Tp, Tm01, Tm02, Tm-1,0, width,
narrowness, peakedness) over a declared frequency band; :func:`energy_flux` gives the
finite-depth energy flux of a spectrum. Nothing here assumes the ocean: no density of sea
water, no spectral tail added beyond the measured band.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from flumekit import conventions
from flumekit.docstrings import doc
from flumekit.signal import uniform_step
from flumekit.waves.theory import G, group_velocity

__all__ = ["as_time_series", "energy_flux", "jonswap", "spectral_parameters", "spectrum"]

#: methods of the smoothed peak period of :func:`spectral_parameters`
TP_METHODS = ("delft", "parabolic")


def as_time_series(eta, sampling_rate: float | None = None,
                   what: str = "eta") -> tuple[xr.DataArray, float]:
    """Return a surface-elevation record as a DataArray with ``time`` last, and its rate.

    Parameters
    ----------
    eta : xarray.DataArray or array_like
        A DataArray with a uniformly sampled ``time`` dimension [s] and any other dimensions,
        or a 1-D array sampled at ``sampling_rate``.
    sampling_rate : float, optional
        Sampling rate [Hz]; required for an array, checked against the time step of a
        DataArray when given.
    what : str
        What the record is, for the error messages.

    Returns
    -------
    tuple of (xarray.DataArray, float)
        The record with ``time`` as its last dimension (coordinate ``time`` [s] from 0 for an
        array), and the sampling rate [Hz].

    Raises
    ------
    ValueError
        Without a uniform time or a sampling rate, with a sampling rate that contradicts the
        time, or with non-finite samples (a gap is not a wave: cut or fill it first).

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.waves.spectra import as_time_series
    >>> da, fs = as_time_series(np.zeros(8), sampling_rate=4.0)
    >>> da.dims, fs, float(da.time[-1])
    (('time',), 4.0, 1.75)
    """
    if isinstance(eta, xr.DataArray):
        if "time" not in eta.dims:
            raise ValueError(f"{what} needs a 'time' dimension, got dims {eta.dims}")
        step = uniform_step(eta["time"].values, f"{what}'s time", min_samples=2)
        fs = 1.0 / step
        if sampling_rate is not None and not np.isclose(sampling_rate, fs, rtol=1e-6):
            raise ValueError(f"{what}: sampling_rate {sampling_rate} Hz contradicts the time "
                             f"step {step} s ({fs} Hz)")
        da = eta.transpose(..., "time")
    else:
        x = np.asarray(eta, dtype=float)
        if x.ndim != 1:
            raise ValueError(f"{what} as an array must be 1-D (time), got shape {x.shape}; pass "
                             "an xarray.DataArray with a 'time' dimension for several records")
        if sampling_rate is None or not (np.isfinite(sampling_rate) and sampling_rate > 0):
            raise ValueError(f"{what} as an array needs a positive sampling_rate [Hz], "
                             f"got {sampling_rate}")
        fs = float(sampling_rate)
        da = xr.DataArray(x, dims=("time",), coords={"time": np.arange(x.size) / fs})
    values = np.asarray(da.values, dtype=float)
    if not np.all(np.isfinite(values)):
        raise ValueError(f"{what} holds {int(np.sum(~np.isfinite(values)))} non-finite samples; "
                         "cut or fill the gaps before a sea-state analysis")
    return da, float(fs)


def _equivalent_dof(window: np.ndarray, step: int, n_segments: int) -> float:
    """Equivalent degrees of freedom of Welch's estimate, Percival & Walden (1993) Eq. (292b).

    From ``n_segments`` segments of the taper ``window`` shifted by ``step`` samples.
    """
    n = window.size
    # autocorrelation of the taper at every lag by one FFT (zero-padded: no wrap-around)
    r = np.fft.irfft(np.abs(np.fft.rfft(window, 2 * n)) ** 2, 2 * n)[:n]
    m = np.arange(1, n_segments)
    lags = m * step
    inside = lags < n
    rho2 = np.zeros(m.size)
    rho2[inside] = (r[lags[inside]] / r[0]) ** 2
    return float(2 * n_segments / (1 + 2 * np.sum((1 - m / n_segments) * rho2)))


@doc
def spectrum(eta, sampling_rate: float | None = None, *, segment_duration: float | None = None,
             overlap: float = 0.5, window="hann", confidence: float = 0.90,
             detrend="constant") -> xr.Dataset:
    """One-sided variance density of a surface-elevation record by Welch's method.

    The record is cut into segments overlapping by ``overlap``, each detrended and tapered by
    ``window``; the average of their periodograms, scaled to a density, is the estimate
    (Welch 1967). Its equivalent degrees of freedom ν account for the taper and the overlap
    (Percival & Walden 1993, Eq. 292b):

        ν = 2K / (1 + 2 Σ_{m=1}^{K-1} (1 - m/K) ρ²(mS)),

    with K segments shifted by S samples and ρ the normalised autocorrelation of the taper
    (ν ≈ 1.89 K for Hann windows overlapping by half, not 2K). The confidence interval is the
    chi-squared one, ν Ŝ / χ²_ν((1 ± c)/2), in which the true spectrum lies with probability
    ``confidence`` at each frequency.

    Parameters
    ----------
    %(eta)s
    %(sampling_rate_array)s
    segment_duration : float, optional
        Length of a segment [s]; the frequency resolution is its inverse. Default: 1/8 of the
        record (the even number of samples 2 floor(N/16)), which with the default overlap of
        one half gives 15 segments covering the whole record but for fewer than 16 samples
        (ν ≈ 28.5 for Hann windows) and a resolution of 8/duration.
    overlap : float
        Overlap of consecutive segments as a fraction of a segment [-], in [0, 1).
    window : str or tuple
        Taper of each segment, any window :func:`scipy.signal.get_window` knows.
    confidence : float
        Probability of the confidence interval [-], in (0, 1).
    detrend : str or False
        Detrending of each segment: ``"constant"`` (mean), ``"linear"`` or ``False``.

    Returns
    -------
    xarray.Dataset
        ``variance_density`` (..., frequency) [m2 s]; ``variance_density_lower`` and
        ``variance_density_upper`` (..., frequency) [m2 s], the bounds of the confidence
        interval; ``degrees_of_freedom`` (frequency) [-], ν at every frequency (ν/2 at zero
        frequency and at the Nyquist frequency, where the periodogram is real); coordinate
        ``frequency`` [Hz] from 0 to the Nyquist frequency. Attributes:
        ``equivalent_degrees_of_freedom`` (ν), ``segments`` (K), ``segment_duration`` [s],
        ``frequency_resolution`` [Hz], ``overlap``, ``window``, ``detrend``, ``confidence``,
        ``sampling_rate`` [Hz]. Samples after the last whole segment are not used.

    Raises
    ------
    ValueError
        For a record shorter than 16 samples or than one segment, an overlap outside [0, 1), a
        confidence outside (0, 1), or an input :func:`as_time_series` refuses.

    Notes
    -----
    The estimate integrates to the variance of the record (Σ S Δf over all frequencies),
    to within the taper's unequal weighting of the samples and the variance below the first
    resolved frequency that the detrending removes.

    References
    ----------
    %(holthuijsen2007)s, Chapter 3.

    Percival, D. B. & Walden, A. T. (1993). Spectral analysis for physical applications.
    Cambridge University Press, Section 6.17, Eq. (292b).

    Welch, P. D. (1967). The use of fast Fourier transform for the estimation of power spectra:
    a method based on time averaging over short, modified periodograms. IEEE Transactions on
    Audio and Electroacoustics 15(2), 70-73.

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.waves import spectrum
    >>> fs = 16.0
    >>> t = np.arange(int(512 * fs)) / fs  # 512 s: segments of 64 s, bins of 1/64 Hz
    >>> eta = 0.05 * np.cos(2 * np.pi * 0.5 * t)  # 0.5 Hz, amplitude 0.05 m
    >>> s = spectrum(eta, sampling_rate=fs)
    >>> float(s.frequency[int(s.variance_density.argmax("frequency"))])  # [Hz]
    0.5
    >>> round(float(s.variance_density.sum() * s.frequency_resolution), 6)  # a²/2 [m2]
    0.00125
    >>> round(s.equivalent_degrees_of_freedom, 1), s.segments
    (28.5, 15)
    """
    from scipy import signal as sig
    from scipy import stats

    da, fs = as_time_series(eta, sampling_rate, "spectrum: eta")
    n = da.sizes["time"]
    if not 0 <= overlap < 1:
        raise ValueError(f"spectrum: overlap must lie in [0, 1), got {overlap}")
    if not 0 < confidence < 1:
        raise ValueError(f"spectrum: confidence must lie in (0, 1), got {confidence}")
    if n < 16:
        raise ValueError(f"spectrum: the record has {n} samples, fewer than 16")
    if segment_duration is None:
        nperseg = 2 * (n // 16)
    else:
        nperseg = int(round(segment_duration * fs))
        if not 8 <= nperseg <= n:
            raise ValueError(f"spectrum: segment_duration {segment_duration} s is {nperseg} "
                             f"samples; it must lie between 8 samples and the record's {n}")
    noverlap = int(round(overlap * nperseg))
    step = nperseg - noverlap
    if step < 1:
        raise ValueError(f"spectrum: overlap {overlap} leaves no step between segments")
    n_segments = (n - noverlap) // step
    taper = sig.get_window(window, nperseg)
    freq, pxx = sig.welch(np.asarray(da.values, dtype=float), fs=fs, window=taper,
                          nperseg=nperseg, noverlap=noverlap, detrend=detrend,
                          return_onesided=True, scaling="density", axis=-1)
    dof = _equivalent_dof(taper, step, n_segments)
    # zero frequency and, for an even segment, the Nyquist frequency have a real periodogram:
    # half the degrees of freedom
    dof_f = np.full(freq.size, dof)
    dof_f[0] = dof / 2
    if nperseg % 2 == 0:
        dof_f[-1] = dof / 2
    alpha = 1.0 - confidence
    # two distinct values of ν: the quantiles once each, not per bin
    nus, inverse = np.unique(dof_f, return_inverse=True)
    lower = (nus / stats.chi2.ppf(1 - alpha / 2, nus))[inverse]
    upper = (nus / stats.chi2.ppf(alpha / 2, nus))[inverse]
    dims = (*da.dims[:-1], "frequency")
    coords = {k: v for k, v in da.coords.items() if "time" not in v.dims}
    coords["frequency"] = freq
    ds = xr.Dataset(
        {"variance_density": (dims, pxx),
         "variance_density_lower": (dims, pxx * lower),
         "variance_density_upper": (dims, pxx * upper),
         "degrees_of_freedom": (("frequency",), dof_f)},
        coords=coords,
        attrs={"equivalent_degrees_of_freedom": dof, "segments": int(n_segments),
               "segment_duration": nperseg / fs, "frequency_resolution": fs / nperseg,
               "overlap": noverlap / nperseg,
               "window": window if isinstance(window, str) else repr(window),
               "detrend": str(detrend), "confidence": float(confidence),
               "sampling_rate": fs,
               "method": "Welch (1967); degrees of freedom of Percival & Walden (1993) "
                         "Eq. (292b); chi-squared confidence interval"})
    return conventions.annotate(ds)


def _band_indices(f: np.ndarray, band, what: str) -> np.ndarray:
    """Return the indices of the bins with f > 0 in the closed ``band`` [Hz] (None: all)."""
    if f.ndim != 1 or f.size < 2 or not np.all(np.diff(f) > 0):
        raise ValueError(f"{what}: the frequency must be 1-D and increasing, of two bins or more")
    keep = f > 0
    if band is not None:
        lo, hi = (float(b) for b in band)
        if not lo < hi:
            raise ValueError(f"{what}: band ({lo}, {hi}) Hz must be increasing")
        keep &= (f >= lo) & (f <= hi)
    idx = np.flatnonzero(keep)
    if idx.size == 0:
        raise ValueError(f"{what}: no frequency bin lies in the band {band} Hz")
    return idx


def _in_band(variance_density: xr.DataArray, band, what: str) -> tuple[xr.DataArray,
                                                                        xr.DataArray]:
    """Return the variance density over the band and the width of each of its bins [Hz]."""
    if not isinstance(variance_density, xr.DataArray) or "frequency" not in variance_density.dims:
        raise ValueError(f"{what} needs an xarray.DataArray with a 'frequency' dimension")
    f = np.asarray(variance_density["frequency"].values, dtype=float)
    idx = _band_indices(f, band, what)
    s = variance_density.isel(frequency=idx).astype(float)
    values = s.values
    if not np.all(np.isfinite(values)) or np.any(values < 0):
        raise ValueError(f"{what}: the variance density holds non-finite or negative values "
                         "in the band")
    # bin widths of the full grid (Δf of a uniform grid): Σ S Δf is the variance the bins hold
    width = xr.DataArray(np.gradient(f)[idx], dims=("frequency",),
                         coords={"frequency": f[idx]})
    return s, width


@doc
def spectral_parameters(variance_density: xr.DataArray, band=None, *,
                        method: str = "delft") -> xr.Dataset:
    """Spectral moments and sea-state parameters of a variance density spectrum.

    The moments m_n = Σ f^n S(f) Δf over the bins with f > 0 inside ``band`` (the bin widths
    of the frequency grid, so that m0 is the variance the bins hold), and from them
    (IAHR/PIANC 1986; Holthuijsen 2007, Chapter 4):

    - ``hm0`` = 4 sqrt(m0), the spectral significant wave height;
    - ``tp`` = 1/f of the largest bin, the peak period of the discrete spectrum;
    - ``tp_smoothed``: a peak period less tied to the bins. ``method="delft"`` (default): the
      peak frequency as the centroid of S⁴, Tp = Σ S⁴ Δf / Σ f S⁴ Δf (Young 1995), which
      uses the whole peak and so is the steadier on a noisy estimate; ``"parabolic"``: the
      vertex of the parabola through the largest bin and its two neighbours, the smoothed
      peak period TPS of SWAN (the largest bin itself at the edge of the band);
    - ``tm01`` = m0/m1, ``tm02`` = sqrt(m0/m2), ``tm_10`` = m-1/m0 (the energy period Te);
    - ``spectral_width`` ε = sqrt(1 - m2²/(m0 m4)) (Cartwright & Longuet-Higgins 1956);
    - ``spectral_narrowness`` ν = sqrt(m0 m2/m1² - 1) (Longuet-Higgins 1975);
    - ``peakedness`` Qp = 2/m0² Σ f S² Δf (Goda 1970).

    Parameters
    ----------
    variance_density : xarray.DataArray
        One-sided variance density S(f) [m2 s] with a ``frequency`` dimension [Hz]
        (increasing) and any other dimensions, which are kept (one set of parameters each).
    band : tuple of float, optional
        Closed frequency band (f_low, f_high) [Hz] the moments are taken over; default every
        bin with f > 0. No tail is added beyond it: the moments are those of the measured band.
    method : {"delft", "parabolic"}
        Method of ``tp_smoothed``.

    Returns
    -------
    xarray.Dataset
        Over the other dimensions of ``variance_density``: ``m_minus1`` [m2 s], ``m0``
        [m2], ``m1`` [m2 s-1], ``m2`` [m2 s-2], ``m4`` [m2 s-4], ``hm0`` [m], ``tp``,
        ``tp_smoothed``, ``tm01``, ``tm02``, ``tm_10`` [s], ``spectral_width``,
        ``spectral_narrowness``, ``peakedness`` [-]; attributes ``band`` [Hz] (the first and
        last bin used) and ``tp_smoothed_method``. A spectrum with no variance in the band
        gives NaN periods.

    Raises
    ------
    ValueError
        Without a ``frequency`` dimension, with no bin in the band, with a non-finite or
        negative density in the band, or an unknown ``method``.

    References
    ----------
    IAHR/PIANC (1986). List of sea-state parameters. Supplement to PIANC Bulletin 52;
    also J. Waterway, Port, Coastal and Ocean Eng. 115(6), 793-808 (1989).

    %(holthuijsen2007)s.

    Goda, Y. (1970). Numerical experiments on wave statistics with spectral simulation. Report
    of the Port and Harbour Research Institute 9(3), 3-57; Goda, Y. (2010). Random seas and
    design of maritime structures, 3rd ed., World Scientific, Chapter 2 (peakedness Qp).

    Longuet-Higgins, M. S. (1975). On the joint distribution of the periods and amplitudes of
    sea waves. J. Geophys. Res. 80(18), 2688-2694.

    Cartwright, D. E. & Longuet-Higgins, M. S. (1956). The statistical distribution of the
    maxima of a random function. Proc. R. Soc. Lond. A 237, 212-232.

    Young, I. R. (1995). The determination of confidence limits associated with estimates of
    the spectral peak frequency. Ocean Engineering 22(7), 669-686.

    The SWAN team (2024). SWAN user manual, output quantity TPS (smoothed peak period).

    Examples
    --------
    >>> import numpy as np
    >>> import xarray as xr
    >>> from flumekit.waves import spectral_parameters
    >>> f = np.linspace(0.0, 2.0, 2001)
    >>> s = xr.DataArray(np.exp(-0.5 * ((f - 0.5) / 0.02) ** 2), dims="frequency",
    ...                  coords={"frequency": f})  # a narrow Gaussian peak at 0.5 Hz
    >>> p = spectral_parameters(s)
    >>> round(float(p.tp), 6), round(float(p.tp_smoothed), 3), round(float(p.tm01), 3)
    (2.0, 2.0, 2.0)
    >>> round(float(p.spectral_narrowness), 3)  # σ_f / f_mean of the Gaussian peak
    0.04
    """
    if method not in TP_METHODS:
        raise ValueError(f"spectral_parameters: method must be one of {TP_METHODS}, "
                         f"got {method!r}")
    s, width = _in_band(variance_density, band, "spectral_parameters")
    s = s.transpose(..., "frequency")
    fv = s["frequency"].values
    w = width.values
    sv = s.values  # (..., frequency): the sums below are matrix products over the last axis
    orders = (-1, 0, 1, 2, 4)
    moments = sv @ np.stack([fv**n * w for n in orders], axis=-1)
    m_1, m0, m1, m2, m4 = np.moveaxis(moments, -1, 0)
    ipeak = np.argmax(sv, axis=-1)
    with np.errstate(divide="ignore", invalid="ignore"):
        if method == "delft":
            # S⁴ of the spectrum scaled by its peak: the ratio is unchanged, no underflow
            s4 = (sv / np.take_along_axis(sv, ipeak[..., None], axis=-1)) ** 4
            tp_s = (s4 @ w) / (s4 @ (fv * w))
        else:
            tp_s = 1.0 / _parabolic_peak(sv, fv, ipeak)
        has = m0 > 0
        out = {
            "m_minus1": m_1, "m0": m0, "m1": m1, "m2": m2, "m4": m4,
            "hm0": 4.0 * np.sqrt(m0),
            "tp": np.where(has, 1.0 / fv[ipeak], np.nan),
            "tp_smoothed": np.where(has, tp_s, np.nan),
            "tm01": m0 / m1,
            "tm02": np.sqrt(m0 / m2),
            "tm_10": m_1 / m0,
            "spectral_width": np.sqrt(np.clip(1.0 - m2**2 / (m0 * m4), 0.0, None)),
            "spectral_narrowness": np.sqrt(np.clip(m0 * m2 / m1**2 - 1.0, 0.0, None)),
            "peakedness": 2.0 / m0**2 * ((sv**2) @ (fv * w)),
        }
    dims = s.dims[:-1]
    coords = {k: v for k, v in s.coords.items() if "frequency" not in v.dims}
    ds = xr.Dataset({k: (dims, np.asarray(v, dtype=float)) for k, v in out.items()},
                    coords=coords)
    ds.attrs = {"band": [float(fv[0]), float(fv[-1])], "tp_smoothed_method": method,
                "moments": "m_n = sum of f^n S(f) df over the band, df the bin width; "
                           "no tail added"}
    return conventions.annotate(ds)


def _parabolic_peak(s: np.ndarray, f: np.ndarray, ipeak: np.ndarray) -> np.ndarray:
    """Frequency of the vertex of the parabola through the peak bin and its neighbours.

    For every spectrum (frequency last); the peak bin's own frequency at an edge of the band.
    """
    ipeak = np.asarray(ipeak)
    i = np.clip(ipeak, 1, f.size - 2)
    take = np.take_along_axis
    y0, y1, y2 = (take(s, (i + d)[..., None], axis=-1)[..., 0] for d in (-1, 0, 1))
    x0, x1, x2 = f[i - 1], f[i], f[i + 1]
    # vertex of the Lagrange parabola through three points with any spacing
    num = (x1 - x0) ** 2 * (y1 - y2) - (x1 - x2) ** 2 * (y1 - y0)
    den = (x1 - x0) * (y1 - y2) - (x1 - x2) * (y1 - y0)
    with np.errstate(divide="ignore", invalid="ignore"):
        vertex = x1 - 0.5 * num / den
    edge = (ipeak == 0) | (ipeak == f.size - 1) | ~(den != 0)
    return np.where(edge, f[ipeak], vertex)


@doc
def energy_flux(variance_density: xr.DataArray, depth, rho: float = 1000.0, g: float = G, *,
                band=None) -> xr.DataArray:
    """Energy flux per unit crest width of a wave spectrum in finite depth [W m-1].

    J = ρ g Σ S(f) c_g(f, h) Δf over the bins with f > 0 in ``band``, with the linear group
    velocity :func:`~flumekit.waves.group_velocity` of each frequency (IEC TS 62600-101;
    Holthuijsen 2007, Section 5.4, per frequency). For a narrow spectrum J is the regular-wave
    flux of the height Hm0/√2; in deep water J = ρ g² Hm0² Te / (64 π).

    Parameters
    ----------
    variance_density : xarray.DataArray
        One-sided variance density S(f) [m2 s] with a ``frequency`` dimension [Hz] and any
        other dimensions.
    depth : float or xarray.DataArray
        Water depth h [m]; a DataArray broadcasts against the other dimensions.
    rho : float
        Water density [kg m-3]; fresh water by default (a flume).
    %(g)s
    band : tuple of float, optional
        Closed frequency band (f_low, f_high) [Hz]; default every bin with f > 0.

    Returns
    -------
    xarray.DataArray
        ``spectral_energy_flux`` [W m-1] over the other dimensions.

    Raises
    ------
    ValueError
        As :func:`spectral_parameters`, and for a non-positive depth.

    %(references_holthuijsen2007)s, Section 5.4.

    IEC TS 62600-101 (2015). Marine energy - Wave, tidal and other water current converters -
    Part 101: Wave energy resource assessment and characterization (omnidirectional
    wave power).

    Examples
    --------
    >>> import numpy as np
    >>> import xarray as xr
    >>> from flumekit.waves.spectra import energy_flux
    >>> f = np.linspace(0.0, 2.0, 4001)
    >>> s = xr.DataArray(np.exp(-0.5 * ((f - 0.5) / 0.005) ** 2), dims="frequency",
    ...                  coords={"frequency": f})
    >>> s = s * 0.1**2 / 16 / float(s.sum() * (f[1] - f[0]))  # Hm0 = 0.1 m at 0.5 Hz
    >>> round(float(energy_flux(s, depth=0.5)), 2)  # [W m-1]
    10.5
    >>> from flumekit.waves import theory  # the regular wave of height Hm0/√2 at 2 s
    >>> round(float(theory.energy_flux(0.1 / np.sqrt(2), 2.0, 0.5)), 2)
    10.5
    """
    s, width = _in_band(variance_density, band, "energy_flux")
    f = s["frequency"]
    if np.any(~(np.asarray(depth, dtype=float) > 0)):
        raise ValueError(f"energy_flux: depth must be positive, got {depth}")
    cg = xr.apply_ufunc(group_velocity, 1.0 / f, depth, kwargs={"g": g})
    flux = rho * g * (s * cg * width).sum("frequency")
    flux = flux.drop_vars("frequency", errors="ignore").rename("spectral_energy_flux")
    flux.attrs = {}
    return conventions.annotate(flux)


@doc
def jonswap(frequency, hm0: float, peak_period: float, gamma: float = 3.3,
            band: tuple[float, float] | None = None) -> np.ndarray:
    """JONSWAP variance density S(f) [m2 s] scaled so that ∫S df = Hm0²/16 on the given grid.

    The one JONSWAP of flumekit: the target spectrum of the virtual flume's irregular runs
    (:func:`flumekit.synth.waves.random_phase_components`), of the synthetic records of the
    tests and benchmarks (:func:`flumekit.synth.waves.irregular_wave_field`) and the energy
    period of a declared sea state (:func:`flumekit.performance.matrix.target_te`).

    Parameters
    ----------
    frequency : array_like
        Uniform frequency grid [Hz] (f = 0 allowed: S(0) = 0).
    hm0 : float
        Spectral significant wave height Hm0 = 4 sqrt(m0) of the components [m].
    peak_period : float
        Peak period Tp = 1/fp [s].
    gamma : float
        Peak enhancement factor γ [-] (3.3: the mean JONSWAP spectrum).
    band : tuple of float, optional
        (f_min, f_max) [Hz]: S = 0 outside it (a wavemaker's band); Hm0 is then that of the
        band. Default: every f > 0 of the grid.

    Returns
    -------
    numpy.ndarray
        S(f) [m2 s] on ``frequency``.

    Notes
    -----
    S ∝ f⁻⁵ exp(-5/4 (fp/f)⁴) γ^exp(-(f - fp)² / (2 σ² fp²)), σ = 0.07 (f ≤ fp), 0.09 (f > fp)
    (Hasselmann et al. 1973). The scale is fixed numerically on the (uniform) ``frequency``
    grid, so that the discrete components hold exactly Hm0²/16 of variance (the usual closed-form
    scale, e.g. Goda's, is within a few per cent of it for γ = 1-7).

    %(references_hasselmann1973)s.

    Examples
    --------
    >>> import numpy as np
    >>> f = np.arange(0, 2001) / 1000.0
    >>> s = jonswap(f, 0.1, 2.0)
    >>> round(4 * float(np.sqrt(s.sum() * 0.001)), 6)
    0.1
    """
    f = np.asarray(frequency, dtype=float)
    fp = 1.0 / peak_period
    sigma = np.where(f <= fp, 0.07, 0.09)
    fs = np.where(f > 0, f, fp)  # S(0) = 0: evaluate the formula at f > 0 only
    shape = (fs ** -5.0 * np.exp(-1.25 * (fp / fs) ** 4)
             * gamma ** np.exp(-((fs - fp) ** 2) / (2 * sigma**2 * fp**2)))
    inside = f > 0
    if band is not None:
        # a bin on an edge is inside, however the grid was rounded
        inside &= (f >= band[0] * (1 - 1e-9)) & (f <= band[1] * (1 + 1e-9))
    shape = np.where(inside, shape, 0.0)
    df = f[1] - f[0]
    return shape * (hm0**2 / 16.0) / (shape.sum() * df)
