"""Separation of incident and reflected waves from an array of wave probes.

One least-squares core serves the three classical methods: Goda & Suzuki (1976, two probes),
Mansard & Funke (1980, three probes) and Zelt & Skjelbreia (1992, any number ≥ 2 of probes,
here without their frequency-dependent pair weights). Per frequency bin f the Fourier
coefficients B_p of the probe records are fitted, in the least-squares sense, by

    B_p = A_I e^(-i k_I x_p) + A_R e^(+i k_R x_p),

and the normal equations of all bins are solved at once (batched, no loop over bins).

Sign convention (pinned by a test): numpy's forward FFT has kernel e^(-iωt), so a record
a cos(ωt - kx + φ) has coefficient (N/2) a e^(iφ) e^(-ikx). A wave travelling towards +x
(towards the flap and the beach, the flume's x axis) therefore has the column e^(-ikx) and is
called *incident*; a wave travelling towards -x has e^(+ikx) and is *reflected*.

Bound harmonics: the second-order harmonics of a steep regular wave are phase-locked to the
primary wave and travel with its phase speed, i.e. with wavenumber n·k1 at frequency n·f1,
not with the free wavenumber k(n f1). Fitted with free waves they leak into the "reflected"
part; with ``bound_harmonics=True`` the bins of harmonic n ≥ 2 are solved with n·k1.
"""

from __future__ import annotations

import warnings
from typing import NamedTuple

import numpy as np
import xarray as xr

from flumekit import conventions
from flumekit.docstrings import filler
from flumekit.signal import uniform_step
from flumekit.waves.layout import MAX_CONDITION
from flumekit.waves.records import (
    REGULAR_FRACTION,
    mean_power,
    probe_record,
    refine_frequency,
    spectrum_harmonic_fraction,
)
from flumekit.waves.theory import G, wavenumber

#: docstring text that several functions of this module share
_doc = filler(probe_arrays=("values : numpy.ndarray\n"
                            "    Elevation [m], shape (probe, time).\n"
                            "time : numpy.ndarray\n"
                            "    Time [s].\n"
                            "x : numpy.ndarray\n"
                            "    Probe positions [m].\n"
                            "probes : list\n"
                            "    Probe labels."))

__all__ = ["METHODS", "SeparationWarning", "as_probe_time", "lstsq_normal", "separate"]

METHODS = {"mansard_funke": (3, 3), "goda_suzuki": (2, 2), "zelt_skjelbreia": (2, None)}


class SeparationWarning(UserWarning):
    """The probe layout is ill-conditioned for part of the wave energy (bins were masked).

    Examples
    --------
    Two probes 0.5 m apart in 0.5 m of water see a 2 s wave well, but for a 1.25 Hz wave
    they are half a wavelength apart (k Δx = π), where two probes cannot tell incident from
    reflected: those bins are masked, and :func:`separate` says so. They hold the 1 cm
    wave's share of the variance, 1² / (5² + 1²) = 3.8 %:

    >>> import warnings
    >>> import numpy as np
    >>> from flumekit.waves import separate, wavenumber
    >>> from flumekit.waves.separation import SeparationWarning
    >>> t, x = np.arange(2000) / 20.0, np.array([0.0, 0.5])  # 100 s at 20 Hz [s], [m]
    >>> w = 2 * np.pi * np.array([0.5, 1.25])  # [rad s-1]
    >>> k = wavenumber(w, 0.5)
    >>> eta = (np.array([0.05, 0.01]) * np.cos(w * t[:, None, None] - k * x[:, None])).sum(-1)
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     r = separate(eta.T, 0.5, "goda_suzuki", x=x, sampling_rate=20.0, regular=False)
    >>> caught[0].category is SeparationWarning, round(float(r.masked_energy_fraction), 3)
    (True, 0.038)
    >>> print(caught[0].message)
    separation: 3.8% of the wave energy in the band lies in ... bins where the probe layout ...
    """


def lstsq_normal(columns: np.ndarray, rhs: np.ndarray, max_condition: float,
                 index: np.ndarray | None = None
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Batched complex least squares by the normal equations, with ill-conditioned systems masked.

    Parameters
    ----------
    columns : numpy.ndarray
        Design matrices, complex, shape (U, P, K): systems of P equations in K unknowns.
    rhs : numpy.ndarray
        Right-hand sides, shape (F, P, R): F systems, R right-hand sides each.
    max_condition : float
        Systems whose 2-norm condition number exceeds this are masked [-].
    index : numpy.ndarray, optional
        Design matrix of each system, integers into the U matrices, shape (F,): systems that
        share a matrix (the bins of one harmonic of a regular wave) share its Gram matrix,
        condition number and inverse. Default: one matrix per system (U = F).

    Returns
    -------
    solution : numpy.ndarray
        Shape (F, K, R); zero for masked systems.
    condition : numpy.ndarray
        2-norm condition number of each system's design matrix, shape (F,); inf if singular.
    masked : numpy.ndarray
        Bool, shape (F,).

    Examples
    --------
    >>> import numpy as np
    >>> m = np.array([[[1, 1], [1, -1], [1, 1j]]], dtype=complex)   # 3 equations, 2 unknowns
    >>> b = m[0] @ np.array([2.0, 0.5])                             # exact right-hand side
    >>> sol, cond, masked = lstsq_normal(m, b[None, :, None], 10.0)
    >>> np.round(sol[0, :, 0].real, 12).tolist(), bool(masked[0])
    ([2.0, 0.5], False)
    """
    mc = np.conj(columns)
    if columns.shape[-1] == 2:
        # closed form for 2 unknowns: the Gram matrix [[a, b], [b*, d]] from sums over the
        # probes, its eigenvalues m ± q and Cramer's rule
        c0, c1 = columns[..., 0], columns[..., 1]
        a = (c0.real ** 2 + c0.imag ** 2).sum(axis=1)
        d = (c1.real ** 2 + c1.imag ** 2).sum(axis=1)
        b = (mc[..., 0] * c1).sum(axis=1)
        m, q = 0.5 * (a + d), np.hypot(0.5 * (a - d), np.abs(b))
        lo, hi = m - q, m + q
    else:
        # Gram matrices MᴴM (U, K, K), accumulated over the handful of probes (3x faster than
        # a batched matmul or einsum of tiny matrices)
        gram = mc[:, 0, :, None] * columns[:, 0, None, :]
        for p in range(1, columns.shape[1]):
            gram += mc[:, p, :, None] * columns[:, p, None, :]
        eig = np.linalg.eigvalsh(gram)  # ascending, (U, K)
        lo, hi = eig[:, 0], eig[:, -1]
    with np.errstate(divide="ignore", invalid="ignore"):
        cond = np.where(lo > 1e-14 * hi, np.sqrt(hi / lo), np.inf)
    masked = ~(cond <= max_condition)
    if index is not None:
        # few matrices for many systems: each matrix's pseudo-inverse G⁻¹Mᴴ (U, K, P), zero
        # where masked, then one product per system
        if columns.shape[-1] == 2:
            det = np.where(masked, 1.0, a * d - np.abs(b) ** 2)[:, None]
            inv = np.stack([d[:, None] * mc[..., 0] - b[:, None] * mc[..., 1],
                            a[:, None] * mc[..., 1] - np.conj(b)[:, None] * mc[..., 0]], axis=1)
            inv /= det[:, None]
        else:
            inv = np.linalg.solve(np.where(masked[:, None, None], np.eye(gram.shape[-1]), gram),
                                  mc.transpose(0, 2, 1))
        inv[masked] = 0.0
        # np.take: a gather along one axis, several times faster than fancy indexing
        return (np.einsum("fkp,fpr->fkr", np.take(inv, index, axis=0), rhs),
                np.take(cond, index), np.take(masked, index))
    r = np.einsum("fpk,fpr->fkr", mc, rhs)  # Mᴴb (F, K, R)
    if columns.shape[-1] == 2:
        det = np.where(masked, 1.0, a * d - np.abs(b) ** 2)[:, None]
        sol = np.stack([d[:, None] * r[:, 0] - b[:, None] * r[:, 1],
                        a[:, None] * r[:, 1] - np.conj(b)[:, None] * r[:, 0]], axis=1)
        sol /= det[:, None]
        sol[masked] = 0.0
        return sol, cond, masked
    if masked.any():  # replace masked systems by identity / zero so the batch solve stays finite
        eye = np.eye(gram.shape[-1], dtype=gram.dtype)
        gram = np.where(masked[:, None, None], eye, gram)
        r = np.where(masked[:, None, None], 0.0, r)
    return np.linalg.solve(gram, r), cond, masked


@_doc
def as_probe_time(eta: xr.DataArray) -> tuple[np.ndarray, np.ndarray, np.ndarray, list]:
    """Check an elevation record for separation and return its arrays.

    Parameters
    ----------
    eta : xarray.DataArray
        Surface elevation [m] over ('probe', 'time') with probe positions ``x`` [m] on
        ``probe``, uniformly sampled, finite.

    Returns
    -------
    %(probe_arrays)s

    Raises
    ------
    TypeError
        When ``eta`` is not a DataArray.
    ValueError
        Wrong dims, missing or repeated positions, fewer than 8 samples, non-uniform time or
        non-finite samples (the message names the first probe holding one).
    """
    v, t, x, probes = unpack_probe_time(eta)
    check_probe_arrays(v, t, x, probes)
    return v, t, x, probes


def unpack_probe_time(eta: xr.DataArray) -> tuple[np.ndarray, np.ndarray, np.ndarray, list]:
    """Return the arrays of an elevation record, its values unchecked (:func:`as_probe_time`).

    Parameters
    ----------
    eta : xarray.DataArray
        Surface elevation [m] over ('probe', 'time') with probe positions ``x`` [m] on
        ``probe``.

    Returns
    -------
    tuple
        Values (probe, time) [m], time [s], positions [m] and probe labels.

    Raises
    ------
    TypeError
        When ``eta`` is not a DataArray.
    ValueError
        Wrong dims or no positions.
    """
    if not isinstance(eta, xr.DataArray):
        raise TypeError(f"eta must be an xarray.DataArray with dims ('probe', 'time'), got "
                        f"{type(eta).__name__}")
    if set(eta.dims) != {"probe", "time"}:
        raise ValueError(f"eta must have dims ('probe', 'time'), got {eta.dims}")
    coords = eta.coords.variables  # the variables: no DataArray per coordinate
    if "x" not in coords or coords["x"].dims != ("probe",):
        raise ValueError("eta needs a coordinate 'x' [m] on dimension 'probe' (probe positions) "
                         "or the argument x")
    if eta.dims != ("probe", "time"):
        eta = eta.transpose("probe", "time")
    x = np.asarray(coords["x"].values, dtype=float)
    t = np.asarray(coords["time"].values, dtype=float)
    v = np.asarray(eta.values, dtype=float)
    probes = coords["probe"].values.tolist() if "probe" in coords else list(range(x.size))
    return v, t, x, probes


@_doc
def check_probe_arrays(values: np.ndarray, time: np.ndarray, x: np.ndarray, probes: list, *,
                       masked: bool = False) -> None:
    """Check the arrays of an elevation record as :func:`as_probe_time` checks its DataArray.

    Parameters
    ----------
    %(probe_arrays)s
    masked : bool
        Whether NaN samples (masked by quality control) are allowed; infinite ones never are.

    Raises
    ------
    ValueError
        Missing or repeated positions, fewer than 8 samples, non-uniform time or non-finite
        samples (the message names the first probe holding one).
    """
    if not np.all(np.isfinite(x)) or np.unique(x).size != x.size:
        raise ValueError(f"probe positions x must be finite and distinct, got {x.tolist()}")
    if time.size < 8:
        raise ValueError(f"eta has {time.size} samples; separation needs at least 8")
    uniform_step(time, "eta")
    bad = np.isinf(values) if masked else ~np.isfinite(values)
    if bad.any():
        p = int(np.flatnonzero(bad.any(axis=1))[0])
        raise ValueError(f"eta holds {int(bad.sum())} non-finite samples (first in probe "
                         f"{probes[p]!r}); fill or cut gaps before separating")


def separate(eta, depth: float, method: str = "mansard_funke",
             band: tuple[float, float] | None = None, x_ref: float = 0.0, *,
             x=None, sampling_rate: float | None = None,
             regular: bool | None = None, period: float | None = None,
             bound_harmonics: bool | None = None,
             wavenumbers: tuple[float, float] | None = None,
             window: str | None = None, max_condition: float = MAX_CONDITION,
             warn_fraction: float = 0.01, gauge_weights=None, g: float = G) -> xr.Dataset:
    """Separate incident and reflected waves from simultaneous probe records.

    Parameters
    ----------
    eta : xarray.DataArray, pandas.DataFrame or array_like
        Surface elevation [m]: a DataArray with dims ("probe", "time"), coordinate ``x`` on
        ``probe`` (probe positions [m], x positive in the direction of the incident wave) and
        ``time`` [s] (uniform sampling); or a DataFrame (one column per probe) or an array
        (probe, time) with ``x`` and ``sampling_rate`` (see
        :func:`flumekit.waves.probe_record`). The mean of each probe is removed.
    depth : float
        Still water depth [m].
    method : str
        "mansard_funke" (exactly 3 probes), "goda_suzuki" (exactly 2) or
        "zelt_skjelbreia" (2 or more); all use the same least-squares core.
    band : tuple of float, optional
        (f_min, f_max) analysis band [Hz]; default every bin between 0 and the Nyquist
        frequency (both excluded).
    x_ref : float, optional
        Position [m] where the incident and reflected elevations and phases are returned;
        default 0, the device (the flap hinge): by the coordinate convention of the raw
        format (``x`` = 0 at the hinge, positive towards the beach) the waves that reach and
        leave the device are what an analysis of its response needs, and the pipeline's
        ``[stages.waves] x_ref`` has the same default, so a result computed here and the
        processed dataset agree without an option.
    x : sequence of float, optional
        Probe positions [m] when ``eta`` does not carry them.
    sampling_rate : float, optional
        Sampling rate [Hz] when ``eta`` has no time coordinate.
    regular : bool, optional
        Treat the record as a regular wave of fundamental frequency f1 = 1/``period``:
        every bin within f1/2 of harmonic n·f1 is fitted with the wavenumber of that harmonic
        (spectral leakage keeps its spatial structure). The statistics (harmonic amplitudes,
        Kr, heights, phase) come from a least-squares fit of the harmonics n·f1 in the band to
        each probe record at their exact frequencies, separated with the same core, so they
        are unbiased for any record length; the time series still come from the bins and show
        edge transients unless the record holds a whole number of periods. Default (None):
        decided from the record. A record that holds at least
        :data:`~flumekit.waves.records.REGULAR_FRACTION` of its variance at its peak
        frequency and the harmonics of it (:func:`~flumekit.waves.harmonic_energy_fraction`)
        is regular and its harmonics are bound (``bound_harmonics`` then defaults to True);
        the ``regular_detection`` attribute of the result says what was found. Pass
        ``regular=False`` to fit every bin as a free wave.
    period : float, optional
        Fundamental period [s] for ``regular``; default the peak of the mean spectrum.
    bound_harmonics : bool, optional
        Fit harmonics n ≥ 2 as bound (phase-locked) waves with wavenumber n·k1
        instead of free waves (implies ``regular``). Default: True for a record detected as
        regular, False otherwise.
    wavenumbers : tuple of float, optional
        First-harmonic wavenumbers (k_I, k_R) [rad m-1] of the incident and the reflected wave
        of a ``regular`` record, when they differ from the linear k(f1): a steep wave travels
        faster than linear theory says (amplitude dispersion), by up to 5 % in the flume of
        Brito et al. 2020, and its reflection, lower, nearly at the linear speed. Bound
        harmonics then travel with n k_I and n k_R. Default: both from linear dispersion
        (see :func:`flumekit.waves.analyse_run` for the nonlinear ones).
    window : str, optional
        Taper (any ``scipy.signal.get_window`` name, e.g. "hann") for the spectra
        and the irregular-wave statistics (Kr, Hm0, masked energy); the elevation time series
        and the regular-wave statistics never use it. The taper is normalised to unit mean
        square so variances are preserved.
    max_condition : float
        Bins whose least-squares matrix has a larger condition number are masked
        (excluded) [-]. Default cot(π/20) ≈ 6.3, the Goda–Suzuki two-probe limits.
    warn_fraction : float
        Warn (:class:`SeparationWarning`) when masked bins hold more than this
        fraction of the measured energy in the band [-].
    gauge_weights : sequence of float, optional
        Weight of each probe's equation in the least squares, one per probe (Zelt &
        Skjelbreia 1992: a noisier probe weighs less); default equal weights. Their pair
        weights W_p W_q sin²(k Δx_pq) follow from the weighted normal equations.
    g : float
        Gravitational acceleration [m s-2].

    Returns
    -------
    xarray.Dataset
        ``eta_incident``, ``eta_reflected`` (time) [m]: separated elevations at ``x_ref``;
        ``spectrum_incident``, ``spectrum_reflected`` (frequency) [m2 s]: one-sided variance
        densities (periodogram) of the band bins;
        ``condition_number``, ``masked``, ``wave_number`` (frequency);
        ``reflection_coefficient`` [-]: irregular waves: Kr = sqrt(m0_R / m0_I) over the
        unmasked band bins (the energy ratio of Mansard & Funke 1980); ``regular``: the
        first-harmonic ratio abs(A_R1) / abs(A_I1) (bound harmonics are not reflection; see
        ``harmonic_reflection_coefficient`` for the others);
        ``incident_height``, ``reflected_height`` [m]: Hm0 = 4 sqrt(m0) for irregular waves;
        for ``regular`` the crest-to-trough height of the sum of the separated harmonics over
        one period (equal to 2|a1| for a linear wave), see the ``definition`` attribute;
        ``masked_energy_fraction`` [-]: measured energy of the masked bins / energy of the band;
        for ``regular`` also, over ``harmonic``: ``incident_harmonic_amplitude``,
        ``reflected_harmonic_amplitude`` [m] and ``harmonic_reflection_coefficient`` [-]
        (NaN where the incident harmonic amplitude is below 1e-3 of the first harmonic's, i.e.
        where the ratio is undefined); ``incident_amplitude`` a1 [m] and ``incident_phase``
        [rad] of the first harmonic at x_ref, η_I1 = a1 cos(2π f t + phase) in the record's
        time.

    Raises
    ------
    ValueError
        Bad arguments, non-finite samples, an empty band, or no separable incident
        energy at all (every bin holding energy masked).

    References
    ----------
    Goda, Y. & Suzuki, Y. (1976). Estimation of incident and reflected waves in random wave
    experiments. Proc. 15th Coastal Engineering Conference, 828-845.

    Mansard, E. P. D. & Funke, E. R. (1980). The measurement of incident and reflected spectra
    using a least squares method. Proc. 17th Coastal Engineering Conference, 154-172.

    Zelt, J. A. & Skjelbreia, J. E. (1992). Estimating incident and reflected wave fields
    using an arbitrary number of wave gauges. Proc. 23rd Coastal Engineering Conference,
    777-789.

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.waves import separate, wavenumber
    >>> t = np.arange(4000) / 20.0                       # 200 s at 20 Hz
    >>> x = np.array([0.0, 0.6, 0.9])                     # probe positions [m]
    >>> w = 2 * np.pi / 2.0
    >>> k = wavenumber(w, 0.5)
    >>> eta = (0.05 * np.cos(w * t - k * x[:, None])     # incident, 5 cm amplitude
    ...        + 0.01 * np.cos(w * t + k * x[:, None]))  # reflected, Kr = 0.2
    >>> r = separate(eta, 0.5, x=x, sampling_rate=20.0)  # regular: detected
    >>> round(float(r.reflection_coefficient), 3)
    0.2
    """
    if x is not None or sampling_rate is not None or not isinstance(eta, xr.DataArray):
        eta = probe_record(eta, x=x, sampling_rate=sampling_rate)
    v, t, x, probes = check_separation_inputs(eta, depth, method, max_condition)
    detection = "given"
    # one transform of the demeaned records serves the detection and the separation
    v = v - v.mean(axis=1, keepdims=True)
    spectrum = np.fft.rfft(v, axis=1)
    if regular is None and not bound_harmonics:
        # A regular record fitted bin by bin puts its bound harmonics into the "reflected"
        # wave (WaveLabX record: Kr 0.136 instead of 0.028), so the default looks first.
        dt = (t[-1] - t[0]) / (t.size - 1)
        f_peak, share = spectrum_harmonic_fraction(spectrum, np.fft.rfftfreq(t.size, dt), dt)
        regular = share >= REGULAR_FRACTION
        detection = (f"{'regular' if regular else 'irregular'}: {share:.1%} of the variance at "
                     f"the peak {f_peak:.4g} Hz and its harmonics (regular from "
                     f"{REGULAR_FRACTION:.0%}; pass regular=True/False to decide)")
        if bound_harmonics is None:
            bound_harmonics = regular
    bound_harmonics = bool(bound_harmonics)
    regular = bool(regular) or bound_harmonics
    rec = prepare_separation(v, t, band, window, regular, period, spectrum=spectrum)
    return separation_dataset(separate_prepared(
        rec, x, probes, depth, method, x_ref, regular=regular,
        bound_harmonics=bound_harmonics, wavenumbers=wavenumbers, window=window,
        max_condition=max_condition, warn_fraction=warn_fraction,
        gauge_weights=gauge_weights, g=g, detection=detection))


class PreparedRecord(NamedTuple):
    """What the separation of a record needs that does not depend on the wavenumbers.

    The band's Fourier coefficients of the demeaned records and, for a regular record, its
    period and harmonic fit: the passes of :func:`flumekit.waves.analyse_run` with refined
    wavenumbers share them.
    """

    t: np.ndarray  # time [s]
    freq: np.ndarray  # FFT frequencies [Hz]
    sel: np.ndarray  # indices of the band's bins
    rhs: list  # the band's coefficients (F, P), untapered and (with a window) tapered
    period: float | None  # fundamental period [s] of a regular record
    coef: np.ndarray | None  # harmonic fit (P, nh) of a regular record (_harmonic_fit)


def prepare_separation(v: np.ndarray, t: np.ndarray, band, window: str | None, regular: bool,
                       period: float | None, spectrum: np.ndarray | None = None
                       ) -> PreparedRecord:
    """Prepare checked records for :func:`separate_prepared`: what no wavenumber changes.

    Parameters
    ----------
    v : numpy.ndarray
        Surface elevation (probe, time) [m], checked (:func:`check_separation_inputs`).
    t : numpy.ndarray
        Time [s], uniform.
    band : tuple of float or None
        Analysis band [Hz] (see :func:`separate`).
    window : str or None
        Taper of the spectra (see :func:`separate`).
    regular : bool
        Whether the record is separated as a regular wave.
    period : float or None
        Fundamental period [s] of a regular record; None: the refined peak.
    spectrum : numpy.ndarray, optional
        ``numpy.fft.rfft`` of ``v`` along time, when the caller has it; ``v`` must then be
        demeaned already (else its mean is removed here).

    Returns
    -------
    PreparedRecord
        The band's Fourier coefficients and, for a regular record, its period and harmonic fit.
    """
    n = t.size
    freq, sel = _band_bins(t, band)
    f = freq[sel]

    if spectrum is None:
        v = v - v.mean(axis=1, keepdims=True)
        spectrum = np.fft.rfft(v, axis=1)
    # one-sided complex amplitudes: a cos(ωt + φ) on a bin -> a e^(iφ); the band's bins are
    # consecutive, a slice of the spectrum
    c = spectrum[:, sel[0]:sel[-1] + 1] * (2.0 / n)  # (P, F)
    rhs = [c.T]
    if window is not None:
        from scipy import signal as _sig  # seconds to import; only a windowed fit needs it

        w = _sig.get_window(window, n)
        w = w / np.sqrt(np.mean(w * w))
        rhs.append((np.fft.rfft(v * w, axis=1)[:, sel] * (2.0 / n)).T)
    coef = None
    if regular:
        if period is None:  # the peak bin, refined: up to half a bin off otherwise
            f_bin = float(f[np.argmax(mean_power(c, axis=0))])
            period = 1.0 / refine_frequency(v, (t[-1] - t[0]) / (n - 1), f_bin)
        if period > 0:  # else _harmonic_wavenumbers says so
            f1 = 1.0 / float(period)
            nyq = 0.5 / ((t[-1] - t[0]) / (n - 1))
            top = max(int(np.rint(f / f1).astype(int).max()), 1)
            nh = max(min(top, int(np.floor(nyq / f1 - 1e-9))), 1)  # below Nyquist
            # (P, nh), a e^(iψ) for cos(2π n f1 (t - t0) + ψ)
            coef = _harmonic_fit(v, t, f1, nh)
    return PreparedRecord(t, freq, sel, rhs, period, coef)


def separate_prepared(rec: PreparedRecord, x: np.ndarray, probes, depth: float, method: str,
                      x_ref: float, *, regular: bool, bound_harmonics: bool, wavenumbers,
                      window: str | None, max_condition: float, warn_fraction: float,
                      gauge_weights, g: float, detection: str,
                      elevations: bool = True) -> tuple[dict, dict, dict]:
    """Separate a prepared record; return the parts of the dataset of :func:`separate`.

    Parameters
    ----------
    rec : PreparedRecord
        The record (:func:`prepare_separation`).
    x : numpy.ndarray
        Probe positions [m].
    probes : list
        Probe labels.
    depth : float
        Still water depth [m].
    method : str
        Separation method.
    x_ref : float
        Position where the waves are returned [m].
    regular, bound_harmonics, wavenumbers, window, max_condition, warn_fraction, gauge_weights, g
        As in :func:`separate` (wavenumbers [rad m-1], g [m s-2]).
    detection : str
        What the regular-wave detection found ("given" when the caller said).
    elevations : bool
        Whether to synthesise ``eta_incident`` and ``eta_reflected`` (an inverse FFT of the
        record each); a caller that reads the statistics alone leaves them out.

    Returns
    -------
    tuple of dict
        Data variables, coordinates and attributes of the dataset
        (:func:`separation_dataset`).

    Raises
    ------
    ValueError
        As :func:`separate`.
    """
    t, freq, sel, rhs, period = rec.t, rec.freq, rec.sel, rec.rhs, rec.period
    x_ref = float(x_ref)
    n = t.size
    f = freq[sel]
    if regular:
        k1 = (None, None) if wavenumbers is None else wavenumbers
        f1, kh, ks, group = _harmonic_wavenumbers(f, depth, period, bound_harmonics, g, k1[0])
        if k1[1] == k1[0]:  # the reflected wave travels with the same wavenumbers
            kh_r, ks_r = kh, ks
        else:
            _, kh_r, ks_r, _ = _harmonic_wavenumbers(f, depth, period, bound_harmonics, g, k1[1])
    else:
        if wavenumbers is not None:
            raise ValueError("wavenumbers applies to a regular record (regular=True)")
        ks = ks_r = wavenumber(2 * np.pi * f, depth, g)
        group = None  # every bin its own wavenumber

    # the distinct design matrices: one per harmonic of a regular wave, else one per bin
    phase = np.exp(-1j * ks[:, None] * x[None, :])  # (U, P): incident column
    # reflected column e^(+ik_r x): the conjugate when k_r is k (half the complex exponentials)
    phase_r = np.conj(phase) if ks_r is ks else np.exp(1j * ks_r[:, None] * x[None, :])
    columns = np.stack([phase, phase_r], axis=-1)  # (U, P, 2)
    rows = rhs[0][:, :, None] if len(rhs) == 1 else np.stack(rhs, axis=-1)  # (F, P, R)
    if gauge_weights is not None:
        w = np.asarray(gauge_weights, dtype=float)
        if w.shape != x.shape or not np.all(w > 0) or not np.all(np.isfinite(w)):
            raise ValueError(f"gauge_weights: one positive weight per probe ({x.size}), got "
                             f"{np.asarray(gauge_weights).tolist()}")
        root = np.sqrt(w / w.mean())[None, :, None]
        columns, rows = columns * root, rows * root
    sol, cond, masked = lstsq_normal(columns, rows, max_condition, index=group)
    a_inc, a_ref = sol[:, 0, :], sol[:, 1, :]  # (F, R)
    k, k_r = (ks, ks_r) if group is None else (np.take(ks, group), np.take(ks_r, group))
    # energy bookkeeping on the (tapered) spectrum used for statistics
    e_inc, e_ref, masked_fraction = _band_energy(rhs[-1], a_inc[:, -1], a_ref[:, -1], masked,
                                                 f, k, x, max_condition, warn_fraction)
    m0_i, m0_r = float(e_inc.sum()), float(e_ref.sum())
    # the waves' phase shifts from the probes' origin to x_ref, per distinct wavenumber
    data = {}
    if elevations:
        shift_i = np.exp(-1j * ks * x_ref)
        shift_r = np.conj(shift_i) if ks_r is ks else np.exp(1j * ks_r * x_ref)
        if group is not None:
            shift_i, shift_r = np.take(shift_i, group), np.take(shift_r, group)
        eta_i, eta_r = _elevations_at(a_inc[:, 0] * shift_i, a_ref[:, 0] * shift_r, sel, n)
        data = {"eta_incident": ("time", eta_i), "eta_reflected": ("time", eta_r)}

    df = freq[1]
    data.update({
        "spectrum_incident": ("frequency", e_inc / df),
        "spectrum_reflected": ("frequency", e_ref / df),
        "condition_number": ("frequency", cond), "masked": ("frequency", masked.astype(np.int8)),
        "wave_number": ("frequency", k),
        "masked_energy_fraction": ((), masked_fraction),
    })
    coords = {"time": t, "frequency": f}
    if regular:
        nh = rec.coef.shape[1]
        stats, coords["harmonic"] = _regular_statistics(rec.coef, t, x, f1, kh[:nh], kh_r[:nh],
                                                        x_ref, max_condition)
        data.update(stats)
    else:
        definition = "spectral significant wave height Hm0 = 4 sqrt(m0) over the unmasked band"
        kr_definition = ("energy ratio sqrt(m0_R / m0_I) over the unmasked band "
                         "(Mansard & Funke 1980)")
        data["reflection_coefficient"] = ((), float(np.sqrt(m0_r / m0_i)),
                                          {"definition": kr_definition})
        for name, m0 in (("incident_height", m0_i), ("reflected_height", m0_r)):
            data[name] = ((), float(4.0 * np.sqrt(m0)), {"definition": definition})

    attrs = {
        "method": method, "x_ref": x_ref, "probes": [str(p) for p in probes],
        "probe_x": x.tolist(), "band": [float(f[0]), float(f[-1])], "window": window or "none",
        "regular": int(regular), "regular_detection": detection,
        "bound_harmonics": int(bound_harmonics),
        "max_condition": max_condition, "depth": float(depth),
        **({"fundamental_frequency": f1,
            "fundamental_wavenumbers": [float(kh[0]), float(kh_r[0])],
            "wavenumber_source": "linear dispersion" if wavenumbers is None else "given"}
           if regular else {}),
        "sign_convention": "incident travels towards +x: coefficient e^(-ikx) with numpy's FFT"}
    return data, coords, attrs


def separation_dataset(parts: tuple[dict, dict, dict]) -> xr.Dataset:
    """Return the dataset of :func:`separate` from the parts :func:`separate_prepared` made.

    Parameters
    ----------
    parts : tuple of dict
        Data variables, coordinates and attributes.

    Returns
    -------
    xarray.Dataset
        The dataset, annotated (:func:`flumekit.conventions.annotate`).
    """
    return conventions.annotated_dataset(*parts)


def check_separation_inputs(eta: xr.DataArray, depth: float, method: str,
                            max_condition: float):
    """Check the arguments of :func:`separate`; return the arrays of :func:`as_probe_time`.

    Parameters
    ----------
    eta : xarray.DataArray
        Surface elevation [m] (probe, time) with ``x`` [m].
    depth : float
        Still water depth [m].
    method : str
        Separation method (:data:`METHODS`).
    max_condition : float
        Largest condition number accepted [-].

    Returns
    -------
    tuple
        Values [m], time [s], positions [m] and probe labels.

    Raises
    ------
    ValueError
        An unknown method, a non-positive depth, a max_condition not above 1, the wrong number
        of probes, or a record :func:`as_probe_time` refuses.
    """
    _check_arguments(depth, method, max_condition)
    v, t, x, probes = as_probe_time(eta)
    _check_probe_count(x, probes, method)
    return v, t, x, probes


def check_separation_arrays(values: np.ndarray, time: np.ndarray, x: np.ndarray, probes: list,
                            depth: float, method: str, max_condition: float) -> None:
    """Check the arguments of :func:`separate` given as the arrays of :func:`as_probe_time`.

    Parameters
    ----------
    values : numpy.ndarray
        Surface elevation [m], shape (probe, time).
    time : numpy.ndarray
        Time [s].
    x : numpy.ndarray
        Probe positions [m].
    probes : list
        Probe labels.
    depth, method, max_condition
        As in :func:`check_separation_inputs`: depth [m], method, condition number [-].

    Raises
    ------
    ValueError
        As :func:`check_separation_inputs`.
    """
    _check_arguments(depth, method, max_condition)
    check_probe_arrays(values, time, x, probes)
    _check_probe_count(x, probes, method)


def _check_arguments(depth: float, method: str, max_condition: float) -> None:
    if method not in METHODS:
        raise ValueError(f"unknown separation method {method!r}; choose one of {sorted(METHODS)}")
    if not depth > 0 or not np.isfinite(depth):
        raise ValueError(f"depth must be positive and finite, got {depth}")
    if not max_condition > 1:
        raise ValueError(f"max_condition must exceed 1, got {max_condition}")


def _check_probe_count(x: np.ndarray, probes: list, method: str) -> None:
    n_min, n_max = METHODS[method]
    if x.size < n_min or (n_max is not None and x.size > n_max):
        need = f"exactly {n_min}" if n_min == n_max else f"at least {n_min}"
        raise ValueError(f"method {method!r} needs {need} probes, got {x.size} ({probes})")


def _band_bins(t: np.ndarray, band: tuple[float, float] | None
               ) -> tuple[np.ndarray, np.ndarray]:
    """FFT frequencies [Hz] of a record sampled at ``t`` [s] and the indices of the band's bins.

    The bins lie in ``band`` and strictly between 0 and the Nyquist frequency.
    """
    n = t.size
    dt = (t[-1] - t[0]) / (n - 1)
    freq = np.fft.rfftfreq(n, dt)
    nyq = 0.5 / dt
    f_lo, f_hi = (0.0, nyq) if band is None else (float(band[0]), float(band[1]))
    if not 0 <= f_lo < f_hi:
        raise ValueError(f"band must satisfy 0 <= f_min < f_max, got {band}")
    sel = np.flatnonzero((freq > 0) & (freq < nyq) & (freq >= f_lo) & (freq <= f_hi))
    if sel.size == 0:
        raise ValueError(f"no frequency bin of this record ({freq[1]:.3g} Hz apart, Nyquist "
                         f"{nyq:.3g} Hz) lies in the band {band}")
    return freq, sel


def _harmonic_wavenumbers(f: np.ndarray, depth: float, period: float, bound_harmonics: bool,
                          g: float, k1: float | None = None):
    """Wavenumbers of the bins of a regular wave (see ``regular`` in :func:`separate`).

    Returns the fundamental frequency f1 = 1/``period`` [Hz], the wavenumber per harmonic
    [rad m-1] (free, or n k1 when bound), the distinct wavenumbers of the bins [rad m-1] (those
    of the harmonics, then the free ones of the bins below f1/2) and, per bin, the index of its
    wavenumber among them: the bins of one harmonic share one. ``k1`` replaces the linear
    wavenumber of the first harmonic (and so of the bound ones).
    """
    if not period > 0:
        raise ValueError(f"period must be positive, got {period}")
    f1 = 1.0 / float(period)
    harmonic = np.rint(f / f1).astype(int)  # 0 below f1/2
    hmax = max(int(harmonic.max()), 1)
    below = harmonic == 0
    # free waves: the harmonics n f1, then the bins below f1/2 (one solve of the dispersion)
    ks = wavenumber(2 * np.pi * np.concatenate([f1 * np.arange(1, hmax + 1), f[below]]),
                    depth, g)
    kh = ks[:hmax]  # per harmonic
    if k1 is not None:
        kh[0] = float(k1)
    if bound_harmonics:
        kh[1:] = kh[0] * np.arange(2, hmax + 1)  # bound: n k1
    group = harmonic - 1
    group[below] = hmax + np.arange(int(below.sum()))
    return f1, kh.copy(), ks, group


def _band_energy(measured: np.ndarray, a_inc: np.ndarray, a_ref: np.ndarray,
                 masked: np.ndarray, f: np.ndarray, k: np.ndarray, x: np.ndarray,
                 max_condition: float, warn_fraction: float):
    """Variance per bin [m2] of the separated waves and the measured fraction in masked bins.

    ``measured`` (F, P) are the probes' coefficients, ``a_inc``/``a_ref`` (F,) the separated
    ones. Raises when no incident energy was separated; warns (:class:`SeparationWarning`) when
    the masked bins hold more than ``warn_fraction`` of the band's energy.
    """
    e_meas = 0.5 * mean_power(measured, axis=1)  # measured variance per bin
    e_total = float(e_meas.sum())
    masked_fraction = float(e_meas[masked].sum() / e_total) if e_total > 0 else 0.0
    e_inc = 0.5 * np.abs(a_inc) ** 2
    e_ref = 0.5 * np.abs(a_ref) ** 2
    if not float(e_inc.sum()) > 0:
        raise ValueError(
            f"no incident energy could be separated: the {int(masked.sum())} masked bins (of "
            f"{f.size}) hold {masked_fraction:.1%} of the energy in the band. The probe layout "
            f"x = {x.tolist()} m is singular or ill-conditioned (condition number > "
            f"{max_condition:.3g}) where the waves are; change the spacing or max_condition")
    if masked_fraction > warn_fraction:
        worst = int(np.argmax(np.where(masked, e_meas, -1.0)))
        dxs = np.abs(x[:, None] - x[None, :])[np.triu_indices(x.size, 1)]
        warnings.warn(
            f"separation: {masked_fraction:.1%} of the wave energy in the band lies in "
            f"{int(masked.sum())} of {f.size} bins where the probe layout x = {x.tolist()} m "
            f"is ill-conditioned (condition number > {max_condition:.3g}; worst at "
            f"f = {f[worst]:.4g} Hz, k·Δx/π = {np.round(k[worst] * dxs / np.pi, 3).tolist()}). "
            "These bins are excluded from the incident and reflected waves; change the probe "
            "spacing or narrow the band.", SeparationWarning, stacklevel=4)
    return e_inc, e_ref, masked_fraction


def _elevations_at(a_inc: np.ndarray, a_ref: np.ndarray, sel: np.ndarray, n: int
                   ) -> tuple[np.ndarray, np.ndarray]:
    """Incident and reflected elevations [m] from their complex amplitudes at the band's bins.

    The amplitudes ``a_inc``, ``a_ref`` [m] (untapered, at the position wanted) of the bins
    ``sel`` of an ``n``-sample record, by inverse FFT.
    """
    spec = np.zeros((2, n // 2 + 1), complex)
    spec[0, sel] = a_inc
    spec[1, sel] = a_ref
    spec *= n / 2.0
    eta_i, eta_r = np.fft.irfft(spec, n, axis=1)
    return eta_i, eta_r


def _regular_statistics(coef: np.ndarray, t: np.ndarray, x: np.ndarray, f1: float,
                        kh: np.ndarray, kh_r: np.ndarray, x_ref: float, max_condition: float):
    """Statistics of a regular wave from its harmonics at their exact frequencies.

    A least-squares harmonic fit per probe (leakage-free for any record length), separated by
    the same core as the bins. ``coef`` (P, nh) the probes' fit (:func:`_harmonic_fit`) [m],
    ``t`` their time [s], ``kh``, ``kh_r`` the incident and reflected wavenumbers of each
    harmonic kept [rad m-1]. Returns the dataset variables (see :func:`separate`) and the
    ``harmonic`` coordinate.
    """
    nh = kh.size
    ph_h = np.exp(-1j * kh[:, None] * x[None, :])  # (nh, P)
    ph_r = np.exp(1j * kh_r[:, None] * x[None, :])
    sol_h, cond_h, masked_h = lstsq_normal(np.stack([ph_h, ph_r], axis=-1),
                                           coef.T[:, :, None], max_condition)
    if masked_h[0]:
        raise ValueError(
            f"the probe layout x = {x.tolist()} m is ill-conditioned at the wave frequency "
            f"{f1:.4g} Hz (condition number {cond_h[0]:.3g} > {max_condition:.3g}): the "
            "incident and reflected waves cannot be separated; change the spacing")
    z = np.stack([sol_h[:, 0, 0] * np.exp(-1j * kh * x_ref),
                  sol_h[:, 1, 0] * np.exp(1j * kh_r * x_ref)])  # (2, nh) at x_ref
    amp_i, amp_r = np.abs(z)
    # Re Σ_n z_n e^(i n ψ) at 512 phases ψ over a period (more if the harmonics need them),
    # by one inverse FFT: irfft(X, M) = (2/M) Re Σ_n X_n e^(2πi n j / M) for 0 < n < M/2
    n_psi = max(512, 2 * (nh + 1))
    spec = np.zeros((2, n_psi // 2 + 1), complex)
    spec[:, 1:nh + 1] = z
    wave = np.fft.irfft(spec, n_psi, axis=1) * (0.5 * n_psi)
    hi, hr = wave.max(axis=1) - wave.min(axis=1)
    definition = ("crest-to-trough height over one period of the sum of the separated "
                  "harmonics at x_ref")
    # a harmonic's Kr is meaningless where it holds no incident wave: NaN below 1e-3 a1
    resolved = (amp_i > 1e-3 * amp_i[0]) & ~masked_h
    kr_n = np.where(resolved, amp_r / np.where(resolved, amp_i, 1.0), np.nan)
    # phase in the record's time: a cos(2π f1 t + phase)
    phase_1 = float(np.angle(z[0, 0] * np.exp(-2j * np.pi * f1 * t[0])))
    kr_definition = "first-harmonic amplitude ratio |A_R1| / |A_I1|"
    data = {
        "incident_harmonic_amplitude": ("harmonic", amp_i),
        "reflected_harmonic_amplitude": ("harmonic", amp_r),
        "harmonic_reflection_coefficient": ("harmonic", kr_n),
        "incident_amplitude": ((), float(amp_i[0])),
        "incident_phase": ((), phase_1),
        "reflection_coefficient": ((), float(kr_n[0]), {"definition": kr_definition}),
        "incident_height": ((), float(hi), {"definition": definition}),
        "reflected_height": ((), float(hr), {"definition": definition})}
    return data, np.arange(1, amp_i.size + 1)


def _harmonic_fit(series: np.ndarray, t: np.ndarray, f1: float, n_harmonics: int) -> np.ndarray:
    """Least-squares fit of Σ_n Re{z_n e^(2πi n f1 (t - t0))} to each row of ``series``.

    A fit at the exact harmonic frequencies, unlike FFT bins, is unbiased for a record holding a
    non-whole number of periods. Returns z (rows, n_harmonics) complex [m]: amplitude |z_n| and
    phase arg z_n relative to the first sample t0.

    The basis is cos, sin of n ω1 (t - t0), n = 1..nh, and a constant. Its Gram matrix needs no
    product of basis rows (O(nh² N)): with S(k) = Σ_j e^(i k ω1 (t_j - t0)), the product rules
    cos a cos b = (cos(a-b) + cos(a+b))/2 etc. give every entry from S(m ± n), so the fit needs
    the 2 nh sums S(k) and the nh projections Σ_j v_j e^(i n ω1 (t_j - t0))
    (:func:`_harmonic_sums`).
    """
    nh = n_harmonics
    n = t.size
    proj, s = _harmonic_sums(series, (t[-1] - t[0]) / (n - 1), f1, nh)
    m = np.arange(1, nh + 1)
    s_sum = s[m[:, None] + m[None, :]]  # S(m + n)
    d = m[:, None] - m[None, :]
    s_diff = np.where(d >= 0, s[np.abs(d)], np.conj(s[np.abs(d)]))  # S(m - n) = S(n - m)*
    gram = np.empty((2 * nh + 1, 2 * nh + 1))  # rows/columns: cos, sin, constant
    gram[:nh, :nh] = 0.5 * (s_diff.real + s_sum.real)  # Σ cos_m cos_n
    gram[nh:2 * nh, nh:2 * nh] = 0.5 * (s_diff.real - s_sum.real)  # Σ sin_m sin_n
    gram[:nh, nh:2 * nh] = 0.5 * (s_sum.imag - s_diff.imag)  # Σ cos_m sin_n
    gram[nh:2 * nh, :nh] = gram[:nh, nh:2 * nh].T
    gram[:nh, -1] = gram[-1, :nh] = s[1:nh + 1].real
    gram[nh:2 * nh, -1] = gram[-1, nh:2 * nh] = s[1:nh + 1].imag
    gram[-1, -1] = n
    rhs = np.concatenate([proj.real, proj.imag, series.sum(axis=1)[None, :]])
    coef = np.linalg.solve(gram, rhs)  # (2 nh + 1, rows)
    return (coef[:nh] - 1j * coef[nh:2 * nh]).T


#: samples per block of :func:`_harmonic_sums`: the products within a block are one matrix
#: product with a (block, 2 nh) table of phasors, small enough to stay in cache
_BLOCK = 128


def _harmonic_sums(series: np.ndarray, dt: float, f1: float, nh: int
                   ) -> tuple[np.ndarray, np.ndarray]:
    """Projections of uniformly sampled rows on the harmonics of f1, and the phasor sums.

    With θ = 2π f1 dt, returns b (nh, rows), b_kp = Σ_j v_pj e^(i k θ j), k = 1..nh, and
    S (2 nh + 1,), S(k) = Σ_j e^(i k θ j), k = 0..2 nh (j = 0..N-1). Written j = q L + r with
    blocks of L = :data:`_BLOCK` samples, e^(i k θ j) = e^(i k θ q L) e^(i k θ r): the sums
    within the blocks are one real matrix product of the records, cut into blocks, with the
    table cos, sin(k θ r), and the blocks' sums are weighted by e^(i k θ q L). O(N nh) products
    like the direct sums, but as one cache-friendly matrix product, and only N/L + L phasors
    per harmonic (:func:`_harmonic_powers`).
    """
    rows, n = series.shape
    size = min(_BLOCK, n)
    blocks = -(-n // size)
    theta = 2 * np.pi * f1 * dt
    inner = _harmonic_powers(np.exp(1j * theta * np.arange(size)), 2 * nh).T  # e^(i k θ r)
    outer = _harmonic_powers(np.exp(1j * theta * size * np.arange(blocks)), 2 * nh).T
    table = np.concatenate([inner[:, :nh].real, inner[:, :nh].imag], axis=1)  # (L, 2 nh)
    part = np.empty((rows, blocks, 2 * nh))
    whole = n // size  # whole blocks: a view of the records; then the partial last one
    part[:, :whole] = series[:, :whole * size].reshape(rows, whole, size) @ table
    if whole < blocks:
        part[:, whole] = series[:, whole * size:] @ table[:n - whole * size]
    # Σ_q (c + i s)_q e^(i k θ q L), in real products (no complex copy of the blocks' sums)
    cos_sum, sin_sum = part[..., :nh], part[..., nh:]
    o_re, o_im = outer[:, :nh].real, outer[:, :nh].imag
    proj = (np.einsum("pqk,qk->kp", cos_sum, o_re) - np.einsum("pqk,qk->kp", sin_sum, o_im)
            + 1j * (np.einsum("pqk,qk->kp", cos_sum, o_im)
                    + np.einsum("pqk,qk->kp", sin_sum, o_re)))
    # S(k): every block sums the whole table, the last one its first n - (blocks - 1) L rows
    table_sum = inner.sum(axis=0)
    last = inner[:n - (blocks - 1) * size].sum(axis=0)
    s = np.empty(2 * nh + 1, complex)
    s[0] = n
    s[1:] = outer[:-1].sum(axis=0) * table_sum + outer[-1] * last
    return proj, s


def _harmonic_powers(e1: np.ndarray, k_max: int) -> np.ndarray:
    """Powers e1^k, k = 1..k_max, of unit phasors e1 (M,), as rows (k_max, M).

    By doubling (e1^(k+j) = e1^j e1^k for the j ≤ k already known): log2(k_max) vectorised
    products instead of k_max M complex exponentials, and a round-off that grows with log k
    rather than with k as a running product's.
    """
    e = np.empty((k_max, e1.size), complex)
    e[0] = e1
    k = 1
    while k < k_max:
        step = min(k, k_max - k)
        np.multiply(e[:step], e[k - 1], out=e[k:k + step])
        k += step
    return e
