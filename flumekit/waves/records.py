"""Probe records from numpy, pandas or xarray, and whether a record is a regular wave.

The wave functions work on one shape, an :class:`xarray.DataArray` of surface elevation with
dims ``("probe", "time")`` and the probe positions as coordinate ``x``. :func:`probe_record`
builds it from what an analyst has at hand: a numpy array, a pandas DataFrame read from a
laboratory's CSV file, or a DataArray already in shape. :func:`harmonic_energy_fraction`
tells a regular record (one dominant frequency and its harmonics) from an irregular sea.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import xarray as xr

from flumekit import conventions
from flumekit.docstrings import doc

__all__ = ["REGULAR_FRACTION", "harmonic_energy_fraction", "probe_record", "refine_frequency"]

#: Share of the variance within the peak's harmonic lines above which a record is regular [-]
REGULAR_FRACTION = 0.9


def probe_record(eta, x: Sequence[float] | None = None,
                 sampling_rate: float | None = None) -> xr.DataArray:
    """Surface elevation of a probe array as a DataArray with dims ("probe", "time").

    Parameters
    ----------
    eta : xarray.DataArray, pandas.DataFrame or array_like
        Surface elevation [m]. A DataArray with dims ``("probe", "time")`` (in either order)
        is returned as it is, with ``x`` and ``time`` added when given. A DataFrame holds one
        column per probe (the column names become the probe names) and one row per sample;
        its index is the time [s] when it is numeric, increasing and not the default
        0, 1, 2, ... row counter, otherwise ``sampling_rate`` is needed. An array has shape
        (probe, time).
    x : sequence of float, optional
        Probe positions [m], one per probe, positive in the direction of the incident wave.
        Required unless ``eta`` is a DataArray that has the coordinate ``x`` already.
    sampling_rate : float, optional
        Sampling rate [Hz]; the time of sample n is n / ``sampling_rate``. Required for an
        array and for a DataFrame without a time index.

    Returns
    -------
    xarray.DataArray
        ``eta`` (probe, time) [m] with coordinates ``probe``, ``x`` (probe) [m] and ``time`` [s].

    Raises
    ------
    ValueError
        When the shape is not two-dimensional, ``x`` does not give one position per probe, or
        neither a time coordinate nor ``sampling_rate`` says when the samples were taken.

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.waves import probe_record
    >>> eta = probe_record(np.zeros((3, 100)), x=[0.0, 0.6, 0.9], sampling_rate=100.0)
    >>> eta.dims, float(eta.time[-1])
    (('probe', 'time'), 0.99)
    """
    if sampling_rate is not None and not (np.isfinite(sampling_rate) and sampling_rate > 0):
        raise ValueError(f"sampling_rate must be positive and finite, got {sampling_rate}")
    time = None
    if isinstance(eta, xr.DataArray):
        if set(eta.dims) != {"probe", "time"}:
            raise ValueError(f"eta must have dims ('probe', 'time'), got {eta.dims}")
        da = eta.transpose("probe", "time")
        if "time" in da.coords:
            time = np.asarray(da["time"].values, dtype=float)
        probes = da["probe"].values.tolist() if "probe" in da.coords else None
        values = da.values
        if x is None and "x" in da.coords:
            x = da["x"].values
    elif _is_dataframe(eta):
        values = eta.to_numpy(dtype=float).T
        probes = [str(c) for c in eta.columns]
        index = eta.index
        counter = index.dtype.kind in "iu" and np.array_equal(index, np.arange(len(index)))
        if index.dtype.kind in "iuf" and not counter:
            time = np.asarray(index, dtype=float)
    else:
        values = np.asarray(eta, dtype=float)
        probes = None
    if values.ndim != 2:
        raise ValueError(f"eta must be two-dimensional (probe, time), got shape {values.shape}")
    if probes is None:
        probes = [str(i) for i in range(values.shape[0])]
    if sampling_rate is not None:
        time = np.arange(values.shape[1]) / float(sampling_rate)
    if time is None:
        raise ValueError("eta has no time coordinate: give sampling_rate [Hz] (or a DataFrame "
                         "indexed by time [s])")
    if x is None:
        raise ValueError("give the probe positions x [m], one per probe "
                         f"({len(probes)} probes: {probes})")
    x = np.asarray(x, dtype=float)
    if x.shape != (values.shape[0],):
        raise ValueError(f"x gives {x.size} positions for {values.shape[0]} probes {probes}")
    da = xr.DataArray(np.asarray(values, dtype=float), dims=("probe", "time"),
                      coords={"probe": probes, "x": ("probe", x), "time": time}, name="eta")
    da.attrs = conventions.attrs("eta")
    return da


def _is_dataframe(obj) -> bool:
    # pandas is a dependency, but checking by duck type keeps this import-light
    return hasattr(obj, "columns") and hasattr(obj, "to_numpy") and hasattr(obj, "index")


@doc
def harmonic_energy_fraction(values: np.ndarray, dt: float, max_harmonic: int = 10
                             ) -> tuple[float, float]:
    """Peak frequency and the share of variance within the lines of its harmonics.

    A regular wave train (a monochromatic wavemaker signal, steep or not) puts nearly all of
    its variance at the peak frequency f1 and its harmonics n f1; an irregular sea spreads it
    over a band. The line width is max(2 bins, 2 % of f1) on either side of each n f1, wide
    enough for the leakage of a record that does not hold a whole number of periods and for
    a slow drift of the wavemaker, narrow enough that a JONSWAP spectrum with a peak
    enhancement of 7 keeps well under :data:`REGULAR_FRACTION` there.

    Parameters
    ----------
    values : numpy.ndarray
        Surface elevation [m], shape (probe, time) or (time,); the mean of each row is removed.
    %(dt_sampling)s
    max_harmonic : int
        Highest harmonic counted [-].

    Returns
    -------
    f1 : float
        Frequency of the peak of the probe-averaged periodogram [Hz].
    fraction : float
        Variance within the lines of f1, 2 f1, ..., ``max_harmonic`` f1 over the variance of
        the record between 0 and the Nyquist frequency (both excluded) [-].

    Examples
    --------
    A steep 2.6 s wave (a second harmonic of a fifth of the first) in a 120 s record at 20 Hz
    is regular; f1 is the periodogram's bin nearest 1/2.6 = 0.3846 Hz
    (:func:`refine_frequency` refines it):

    >>> import numpy as np
    >>> from flumekit.waves import REGULAR_FRACTION, harmonic_energy_fraction, jonswap
    >>> t = np.arange(2400) * 0.05
    >>> theta = 2 * np.pi * t / 2.6
    >>> f1, share = harmonic_energy_fraction(0.05 * np.cos(theta) + 0.01 * np.cos(2 * theta), 0.05)
    >>> round(f1, 4), round(share, 2), share > REGULAR_FRACTION
    (0.3833, 0.97, True)

    A random-phase JONSWAP sea of the same peak period (Hm0 = 0.1 m) is not:

    >>> f = np.fft.rfftfreq(t.size, 0.05)
    >>> amplitude = np.sqrt(2 * jonswap(f, 0.1, 2.6) * f[1])  # of each component [m]
    >>> phase = np.random.default_rng(0).uniform(0, 2 * np.pi, f.size)
    >>> sea = np.fft.irfft(amplitude * np.exp(1j * phase) * t.size / 2, t.size)
    >>> f1, share = harmonic_energy_fraction(sea, 0.05)
    >>> round(share, 2), share > REGULAR_FRACTION
    (0.26, False)
    """
    v = np.atleast_2d(np.asarray(values, dtype=float))
    v = v - v.mean(axis=1, keepdims=True)
    n = v.shape[1]
    return spectrum_harmonic_fraction(np.fft.rfft(v, axis=1), np.fft.rfftfreq(n, dt), dt,
                                      max_harmonic)


def spectrum_harmonic_fraction(spectrum: np.ndarray, freq: np.ndarray, dt: float,
                               max_harmonic: int = 10) -> tuple[float, float]:
    """:func:`harmonic_energy_fraction` of records whose Fourier transform is at hand.

    Parameters
    ----------
    spectrum : numpy.ndarray
        ``numpy.fft.rfft`` of the demeaned records along time, shape (probe, frequency).
    freq : numpy.ndarray
        Its frequencies [Hz].
    dt, max_harmonic : float, int
        As in :func:`harmonic_energy_fraction` (dt [s]).

    Returns
    -------
    tuple of float
        The peak frequency f1 [Hz] and the share of the variance in its harmonic lines [-],
        as :func:`harmonic_energy_fraction` returns them.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(2000) / 20.0
    >>> v = np.cos(2 * np.pi * 0.4 * t)[None, :]
    >>> f1, share = spectrum_harmonic_fraction(np.fft.rfft(v, axis=1),
    ...                                        np.fft.rfftfreq(t.size, 0.05), 0.05)
    >>> round(f1, 3), round(share, 3)
    (0.4, 1.0)
    """
    power = mean_power(spectrum, axis=0)
    inside = (freq > 0) & (freq < 0.5 / dt)
    power = np.where(inside, power, 0.0)
    total = float(power.sum())
    if not total > 0:
        return float("nan"), 0.0
    f1 = float(freq[np.argmax(power)])
    half_width = max(2.0 * freq[1], 0.02 * f1)
    nearest = np.clip(np.rint(freq / f1), 1, max_harmonic)
    lines = np.abs(freq - nearest * f1) <= half_width
    return f1, float(power[lines].sum() / total)


@doc
def refine_frequency(values: np.ndarray, dt: float, f_guess: float) -> float:
    """Frequency of a record's dominant sinusoid, refined from a periodogram peak.

    The peak bin of a record that does not hold a whole number of periods lies up to half a
    bin (1/(2 N dt)) off the wave frequency, and a harmonic fit at that frequency is biased
    (a 120 s record of 2.485 s waves: 0.6 % in f1, 13 % in the amplitude). The frequency that
    maximises the variance of the least-squares fit of a cos + b sin + c, summed over the
    probes, is exact for a noise-free sinusoid of any length (nonlinear least squares); it is
    searched within one bin of ``f_guess``.

    Parameters
    ----------
    values : numpy.ndarray
        Records [m], shape (probe, time) or (time,).
    %(dt_sampling)s
    f_guess : float
        Starting frequency, the periodogram peak [Hz].

    Returns
    -------
    float
        Refined frequency [Hz], within one bin of ``f_guess``; relative precision about 1e-9.

    Examples
    --------
    That 120 s record at 20 Hz on three probes: the periodogram's peak is 0.6 % low, the
    refined frequency is 1/2.485 Hz.

    >>> import numpy as np
    >>> from flumekit.waves import harmonic_energy_fraction, refine_frequency
    >>> time = np.arange(2400) / 20.0
    >>> x = np.array([0.0, 0.5, 0.9])  # probe positions [m]
    >>> eta = 0.05 * np.cos(2 * np.pi * time / 2.485 - 0.8 * x[:, None])
    >>> peak = harmonic_energy_fraction(eta, 0.05)[0]
    >>> round(peak * 2.485, 4)  # f T
    0.994
    >>> round(refine_frequency(eta, 0.05, peak) * 2.485, 9)
    1.0
    """
    v = np.atleast_2d(np.asarray(values, dtype=float))
    mean = v.mean(axis=1)  # removed from the moments below (no demeaned copy of the records)
    df = 1.0 / (v.shape[1] * dt)

    # Every evaluation needs Σ_j w_j e^(iδ t_j), δ = 2π (f - f_guess), |δ| ≤ 2π df, for
    # w = v e^(iω_g t) (the right-hand sides), e^(iω_g t) and e^(2iω_g t) (the Gram matrix of
    # cos, sin and 1: cos² = (1 + cos 2a)/2 ...; with 2δ). About the centres c_b of blocks of L
    # samples, e^(iδ t) = e^(iδ c_b) Σ_m (iδ τ)^m / m! with |δ τ| ≤ π L / N, so the moments
    # Σ_j w_j τ_j^m of each block, taken once, make an evaluation cost O(blocks), not O(N)
    # complex exponentials. 64 blocks: |2 δ τ| ≤ π/32, and 14 terms leave a remainder below
    # 1e-24 of the sums, far under their round-off.
    p, n = v.shape
    n_blocks, n_terms = 64, 14
    size = -(-n // n_blocks)  # samples per block
    full, rest = divmod(n, size)  # whole blocks, samples of the last (partial) one
    half = 0.5 * size * dt
    tau = ((np.arange(size) - 0.5 * (size - 1)) * dt) / half  # block-local time / half [-]
    m = np.arange(n_terms)
    taylor = np.empty((size, n_terms))  # (L, terms): τ^m / m!, as running products
    taylor[:, 0] = 1.0
    taylor[:, 1:] = tau[:, None] / m[1:]
    np.cumprod(taylor, axis=1, out=taylor)
    # e^(iω_g t) of sample r of block b is e^(iω_g b L dt) e^(iω_g r dt): the moments are the
    # blocks' phasors times those of one table, (L, terms) per row kind, and the records' ones
    # one real matrix product of the records cut into blocks (no (rows, N) complex array)
    w_r = np.exp(2j * np.pi * f_guess * dt * np.arange(size))  # in-block phasors (L,)
    table = w_r[:, None] * taylor  # Σ_r w_r τ_r^m / m! (L, terms)
    table_2 = (w_r * w_r)[:, None] * taylor
    n_all = full + (rest > 0)
    ones = np.empty((n_all, n_terms), complex)  # Σ_r e^(iω_g r dt) τ^m / m! per block
    ones_2 = np.empty((n_all, n_terms), complex)
    ones[:full], ones_2[:full] = table.sum(axis=0), table_2.sum(axis=0)
    cs = np.concatenate([table.real, table.imag], axis=1)  # (L, 2 terms)
    part = np.empty((p, n_all, 2 * n_terms))
    part[:, :full] = v[:, :full * size].reshape(p, full, size) @ cs
    if rest:
        ones[full], ones_2[full] = table[:rest].sum(axis=0), table_2[:rest].sum(axis=0)
        part[:, full] = v[:, full * size:] @ cs[:rest]
    block_phase = np.exp(2j * np.pi * f_guess * dt * size * np.arange(n_all))  # (blocks,)
    # moments of (v - mean) e^(iω_g t): those of v e^(iω_g t) less mean times those of e^(iω_g t)
    rec = part[..., :n_terms] + 1j * part[..., n_terms:] - mean[:, None, None] * ones
    moments = np.concatenate([rec, ones[None], ones_2[None]]) * block_phase[:, None]
    moments[-1] *= block_phase[:, None]  # e^(2iω_g t): the square of the blocks' phasors
    centres = (np.arange(n_all) * size + 0.5 * (size - 1)) * dt
    scale = np.ones(p + 2)
    scale[-1] = 2.0  # the last row turns at 2δ
    total = v.sum(axis=1) - n * mean  # Σ_j (v_pj - mean_p): the constant column's right side

    def fitted_variance(f: np.ndarray) -> np.ndarray:  # at the frequencies f (M,)
        delta = 2 * np.pi * (f - f_guess) * scale[:, None]  # (rows, M)
        powers = np.empty((p + 2, n_terms, f.size), complex)  # (iδ half)^m (rows, terms, M)
        powers[:, 0] = 1.0
        powers[:, 1:] = (1j * half * delta)[:, None, :]
        np.cumprod(powers, axis=1, out=powers)
        poly = moments @ powers  # (rows, blocks, M)
        sums = (poly * np.exp(1j * delta[:, None, :] * centres[:, None])).sum(axis=1)
        proj, s1, s2 = sums[:p], sums[p], sums[p + 1]  # Σ v e^(iωt), Σ e^(iωt), Σ e^(2iωt)
        gram = np.empty((f.size, 3, 3))  # of cos, sin and 1
        gram[:, 0, 0], gram[:, 1, 1], gram[:, 2, 2] = 0.5 * (n + s2.real), 0.5 * (n - s2.real), n
        gram[:, 0, 1] = gram[:, 1, 0] = 0.5 * s2.imag
        gram[:, 0, 2] = gram[:, 2, 0] = s1.real
        gram[:, 1, 2] = gram[:, 2, 1] = s1.imag
        rhs = np.empty((f.size, 3, p))
        rhs[:, 0], rhs[:, 1], rhs[:, 2] = proj.real.T, proj.imag.T, total
        coef = np.linalg.solve(gram, rhs)
        return np.sum(coef * rhs, axis=(1, 2))  # Σ_p b_pᵀ G⁻¹ b_p: projected variance

    # A grid of the search interval (many evaluations in one), then parabolas through three
    # points about the best, each spaced by the previous step: superlinear convergence near the
    # smooth maximum. The spacing stays above 1e-4 df, where the objective's round-off would
    # blur the parabola's curvature.
    lo, hi = max(f_guess - df, 0.5 * df), min(f_guess + df, 0.5 / dt)
    xatol = 1e-9 * f_guess
    grid = np.linspace(lo, hi, 9)
    y = fitted_variance(grid)
    i = int(np.clip(np.argmax(y), 1, grid.size - 2))
    f, h = float(grid[i]), float(grid[1] - grid[0])
    y0, y1, y2 = y[i - 1:i + 2]  # the first parabola's points are on the grid
    for _ in range(20):
        curvature = y0 - 2 * y1 + y2
        if not curvature < 0:  # flat or convex: the best of the three points
            f = min(max(f + h * float(np.argmax([y0, y1, y2]) - 1), lo), hi)
            break
        step = float(np.clip(0.5 * h * (y0 - y2) / curvature, -h, h))
        f_new = min(max(f + step, lo), hi)
        if abs(f_new - f) <= xatol:
            f = f_new
            break
        h = max(abs(f_new - f), 1e-4 * df)
        f = f_new
        y0, y1, y2 = fitted_variance(np.array([f - h, f, f + h]))
    return f


def mean_power(z: np.ndarray, axis: int) -> np.ndarray:
    """Mean of abs(z)² over one axis of a 2-D complex array, without a temporary copy of it.

    Parameters
    ----------
    z : numpy.ndarray
        Complex array, two-dimensional (e.g. Fourier coefficients (probe, frequency) [m]).
    axis : int
        The axis averaged over, 0 or 1.

    Returns
    -------
    numpy.ndarray
        The mean squared modulus along ``axis`` (in the squared unit of ``z``).

    Examples
    --------
    >>> import numpy as np
    >>> mean_power(np.array([[3 + 4j, 1j], [0, 1]]), axis=0).tolist()
    [12.5, 1.0]
    """
    sub = "ij,ij->j" if axis == 0 else "ij,ij->i"
    return (np.einsum(sub, z.real, z.real) + np.einsum(sub, z.imag, z.imag)) / z.shape[axis]
