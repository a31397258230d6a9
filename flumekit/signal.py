"""Shared signal tools: uniform sampling, filtering, differentiation, cycles, phase averages.

The uniform-sampling check, zero-phase filtering, differentiation, cycles, the quasi-steady
window, phase averaging and the per-cycle amplitude.

These are the only implementations of these operations in flumekit: waves, flap and UVP code
call them. Functions take numpy arrays with time along the last axis and uniform sampling.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from flumekit.docstrings import doc

#: largest deviation of a sampling interval from the mean step, relative to the step: far above
#: the rounding of float times (1e-16 relative per value, 1e-10 of a 0.01 s step at t = 1e4 s)
#: and far below any real clock irregularity worth resampling for
UNIFORM_RTOL = 1e-6


def uniform_step(time, what: str = "time", min_samples: int = 2) -> float:
    """Step [s] of a finite, 1-D, increasing, uniformly sampled time.

    The one uniform-sampling check of flumekit: every interval within :data:`UNIFORM_RTOL` of
    the mean step (t[-1] − t[0]) / (n − 1), which is returned.

    Parameters
    ----------
    time : Sample times [s].
    what : What the times belong to, for the error message.
    min_samples : Fewest samples accepted.

    Raises
    ------
    ValueError : naming ``what`` and the failed condition.
    """
    t = np.asarray(time, dtype=float)
    if t.ndim != 1 or t.size < max(min_samples, 2):
        raise ValueError(f"{what} needs a 1-D time of at least {max(min_samples, 2)} samples, "
                         f"got shape {t.shape}")
    if not np.all(np.isfinite(t)):
        raise ValueError(f"{what}: the time holds non-finite values")
    step = (t[-1] - t[0]) / (t.size - 1)
    dev = np.diff(t)
    dev -= step  # in place: the records are long and each uncertainty rerun checks its own
    np.abs(dev, out=dev)
    if not step > 0 or dev.max() > UNIFORM_RTOL * step:
        raise ValueError(f"{what} must be sampled uniformly in increasing time")
    return float(step)


def nanmedian(x) -> float:
    """Return the median of the values of ``x`` that are not NaN, as :func:`numpy.nanmedian`.

    The same number as ``float(numpy.nanmedian(x))`` (the mean of the two middle values of an
    even count summed from +0.0, as numpy's mean sums), at a fraction of its cost on the short
    series of per-cycle crests that the window searches take many medians of.

    Parameters
    ----------
    x : array_like
        Values, any shape (flattened).

    Returns
    -------
    float
        The median; NaN when every value is NaN.

    Examples
    --------
    >>> from flumekit.signal import nanmedian
    >>> nanmedian([3.0, float("nan"), 1.0, 2.0, 10.0])
    2.5
    """
    a = np.asarray(x, dtype=float).reshape(-1)
    a = a[~np.isnan(a)]  # a copy, partitioned in place
    n = a.size
    if n == 0:
        return float("nan")
    k = n // 2
    if n % 2:
        a.partition(k)
        return float(0.0 + a[k])
    a.partition((k - 1, k))
    return float((0.0 + a[k - 1] + a[k]) / 2.0)


def median_rows(rows: np.ndarray) -> np.ndarray:
    """Return the median over the rows of each column, as ``numpy.median(rows, axis=0)``.

    For an odd number of rows (the middle value, NaN in a column holding a NaN): the same
    numbers at a fraction of numpy's cost on the few-row running medians of the window
    searches.

    Parameters
    ----------
    rows : numpy.ndarray
        Values, shape (odd number of rows, columns).

    Returns
    -------
    numpy.ndarray
        One median per column.

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.signal import median_rows
    >>> median_rows(np.array([[1.0, 5.0], [3.0, np.nan], [2.0, 0.0]])).tolist()
    [2.0, nan]
    """
    rows = np.asarray(rows, dtype=float)
    if rows.ndim != 2 or rows.shape[0] % 2 == 0:
        raise ValueError(f"median_rows needs an odd number of rows, got shape {rows.shape}")
    ordered = np.sort(rows.T, axis=-1)  # NaN sorts last
    out = 0.0 + ordered[:, rows.shape[0] // 2]
    out[np.isnan(ordered[:, -1])] = np.nan
    return out


def _check_rate(sampling_rate: float, cutoff: float) -> None:
    if not np.isfinite(sampling_rate) or sampling_rate <= 0:
        raise ValueError(f"sampling rate must be positive, got {sampling_rate}")
    if not 0 < cutoff < sampling_rate / 2:
        raise ValueError(
            f"cut-off {cutoff} Hz must lie between 0 and the Nyquist frequency "
            f"{sampling_rate / 2} Hz")


@doc
def lowpass(x: np.ndarray, sampling_rate: float, cutoff: float, order: int = 4,
            axis: int = -1) -> np.ndarray:
    """Zero-phase Butterworth low-pass filter (forward-backward, second-order sections).

    Parameters
    ----------
    x : numpy.ndarray
        Signal, time along ``axis``.
    %(sampling_rate)s
    cutoff : float
        -3 dB cut-off of the single pass [Hz]. Forward-backward filtering squares the
        magnitude response, so the combined response is -6 dB at ``cutoff``.
    order : int
        Order of the single-pass Butterworth design (4 in Brito et al. 2020, §2.3).
    """
    # scipy.signal costs seconds to import: paid by the callers that filter, not by every import
    from scipy import signal as _sig

    _check_rate(sampling_rate, cutoff)
    # a copy: the cached design stays as designed whatever a filter routine does with it
    sos = _butter_lowpass(order, float(cutoff), float(sampling_rate)).copy()
    return _sig.sosfiltfilt(sos, np.asarray(x, dtype=float), axis=axis)


@functools.lru_cache(maxsize=64)
def _butter_lowpass(order: int, cutoff: float, sampling_rate: float) -> np.ndarray:
    """Return the second-order sections of the Butterworth low-pass of :func:`lowpass`.

    Cached: the design costs as much as filtering a record of ten thousand samples, and the
    reruns of one record (uncertainty draws) filter with the same one.
    """
    from scipy import signal as _sig

    return _sig.butter(order, cutoff, btype="low", fs=sampling_rate, output="sos")


def derivative(x: np.ndarray, sampling_rate: float, axis: int = -1) -> np.ndarray:
    """First time derivative by second-order central differences (one-sided at the ends)."""
    return np.gradient(np.asarray(x, dtype=float), 1.0 / sampling_rate, axis=axis, edge_order=2)


def smooth_derivatives(x: np.ndarray, sampling_rate: float, cutoff: float, order: int = 4,
                       axis: int = -1) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Low-passed signal and its first and second derivatives.

    The zero-phase low-pass removes the noise (quantisation, sensor noise) that differentiation
    would amplify by ω and ω²; central differences of the band-limited signal then carry an
    error of order (ω Δt)²/6, below 0.3 % for ω Δt < 0.13.
    """
    xs = lowpass(x, sampling_rate, cutoff, order=order, axis=axis)
    v = derivative(xs, sampling_rate, axis=axis)
    a = derivative(v, sampling_rate, axis=axis)
    return xs, v, a


@doc
def zero_upcrossings(x: np.ndarray, time: np.ndarray) -> np.ndarray:
    """Find the zero up-crossings of a 1-D signal, linearly interpolated.

    Parameters
    ----------
    x : numpy.ndarray
        Signal, 1-D.
    %(time)s

    Returns
    -------
    numpy.ndarray
        Times of the up-crossings [s].
    """
    x = np.asarray(x, dtype=float)
    i = np.flatnonzero((x[:-1] < 0) & (x[1:] >= 0))
    frac = -x[i] / (x[i + 1] - x[i])
    return time[i] + frac * (time[i + 1] - time[i])


@dataclass(frozen=True)
class Cycles:
    """Per-cycle statistics between consecutive zero up-crossings."""

    start: np.ndarray  # [s]
    period: np.ndarray  # [s]
    crest: np.ndarray  # maximum in the cycle
    trough: np.ndarray  # minimum in the cycle

    @property
    def height(self) -> np.ndarray:
        """Crest-to-trough height of each cycle, in the signal's units."""
        return self.crest - self.trough


def _spaced(tc: np.ndarray, min_period: float) -> list[int]:
    """Return the crossings kept: the first, then each first one ``min_period`` after the last.

    ``tc`` the crossing times [s], increasing. The next crossing of each is searched for all at
    once, with the test ``tc[j] - tc[k] >= min_period`` itself (a search for
    ``tc[k] + min_period`` alone can round to the neighbouring crossing); only the kept
    crossings, one per wave, are then followed in turn.
    """
    n = tc.size
    ahead = np.arange(n)
    nxt = np.searchsorted(tc, tc + min_period)
    while True:  # at most a step or two, where the sum rounded
        down = (nxt - 1 > ahead) & (tc[np.maximum(nxt - 1, 0)] - tc >= min_period)
        up = (nxt < n) & ~(tc[np.minimum(nxt, n - 1)] - tc >= min_period)
        if not (down.any() or up.any()):
            break
        nxt = nxt - down + up
    nxt = nxt.tolist()
    keep = [0]
    while nxt[keep[-1]] < n:
        keep.append(nxt[keep[-1]])
    return keep


def cycles(x: np.ndarray, time: np.ndarray, min_period: float = 0.0) -> Cycles:
    """Split a 1-D signal into zero-up-crossing cycles and return crest, trough and period.

    Crossings closer than ``min_period`` to the previous kept one (noise around zero) are merged.
    """
    x = np.asarray(x, dtype=float)
    idx = np.flatnonzero((x[:-1] < 0) & (x[1:] >= 0)) + 1
    # with every crossing min_period after the one before, the loop below keeps them all
    if min_period > 0 and idx.size > 1 and not np.all(np.diff(time[idx]) >= min_period):
        idx = idx[_spaced(time[idx], min_period)]
    if idx.size < 2:
        empty = np.empty(0)
        return Cycles(empty, empty, empty, empty)
    # interpolated crossing time for each kept index
    t_all = time[idx - 1] + (-x[idx - 1] / (x[idx] - x[idx - 1])) * (time[idx] - time[idx - 1])
    crest = np.maximum.reduceat(x, idx)[:-1]
    trough = np.minimum.reduceat(x, idx)[:-1]
    return Cycles(start=t_all[:-1], period=np.diff(t_all), crest=crest, trough=trough)


@dataclass(frozen=True)
class SteadyWindow:
    """Quasi-steady part of a record (Brito et al. 2020, §2.5)."""

    start: float  # [s]
    end: float  # [s]
    amplitude_scale: float  # same unit as the signal
    n_cycles: int
    period: float  # mean period of the window [s]
    height: float  # mean crest-to-trough height of the window
    tolerance: float = 0.02  # relative crest tolerance applied [-]
    settled: float | None = None  # start of the first cycle within the tolerance [s]


def quasi_steady_window(x: np.ndarray, time: np.ndarray, tolerance: float = 0.02,
                        min_period: float = 0.0, noise_factor: float = 0.0,
                        zero_cycles: Cycles | None = None) -> SteadyWindow:
    """Longest run of cycles whose crest lies within a tolerance of the amplitude scale.

    Brito et al. (2020, §2.5) compare each cycle's maximum with the amplitude scale and call the
    record quasi-steady where the relative difference is below 2 %. The amplitude scale is taken
    as the median crest of the second half of the cycles (the ramp-up lies in the first half).

    Parameters
    ----------
    x : Signal (surface elevation about still water) [m].
    time : Sample times [s].
    tolerance : Relative crest tolerance [-] (the paper: 0.02).
    min_period : Up-crossings closer than this to the previous one are merged [s].
    noise_factor : When > 0, the tolerance is at least ``noise_factor`` times the crests' own
        relative scatter (1.4826 × median absolute deviation of the second-half crests about the
        scale, a robust standard deviation) [-]. On a record whose cycle-to-cycle crest noise
        (probe resolution, short-crested disturbances, seiching) exceeds the paper's 2 %, a
        fixed 2 % rejects steady cycles at random and the "longest run" is a few cycles long;
        with 3 σ a steady cycle is rejected with probability 0.3 % (Gaussian scatter) while a
        ramp-up still is. The test then applies to the median deviation of each cycle and its
        four neighbours: the crest of a noisy cycle is the largest of several samples near
        the peak, whose scatter has a heavier upper tail than a Gaussian's, and one or two
        such crests must not cut a window of a hundred steady cycles in two (a ramp-up, a
        trend over consecutive cycles, is still rejected). 0 applies ``tolerance`` alone.
    zero_cycles : :func:`cycles` of ``x``, ``time`` and ``min_period`` when the caller has them
        (it tries several criteria on one record).
    """
    c = cycles(x, time, min_period=min_period) if zero_cycles is None else zero_cycles
    if c.crest.size < 4:
        raise ValueError("fewer than four wave cycles: no quasi-steady window can be found")
    # nanmedian: a cycle holding masked (NaN) samples has a NaN crest and is never steady
    half = c.crest[c.crest.size // 2:]
    scale = nanmedian(half)
    if noise_factor > 0:
        scatter = 1.4826 * nanmedian(np.abs(half - scale)) / abs(scale)
        tolerance = max(tolerance, noise_factor * scatter)
    dev = np.abs(c.crest - scale)
    if noise_factor > 0:  # the median of each cycle's deviation and its four neighbours'
        padded = np.concatenate([dev[:1], dev[:1], dev, dev[-1:], dev[-1:]])
        n = dev.size
        dev = median_rows(np.stack([padded[i:i + n] for i in range(5)]))
    ok = dev <= tolerance * abs(scale)
    # longest run of consecutive True
    padded = np.concatenate([[False], ok, [False]])
    edges = np.flatnonzero(np.diff(padded.astype(int)))
    starts, ends = edges[::2], edges[1::2]
    if starts.size == 0:
        raise ValueError(f"no cycle has its crest within {tolerance:.1%} of the amplitude scale")
    k = int(np.argmax(ends - starts))
    a, b = starts[k], ends[k]
    return SteadyWindow(
        start=float(c.start[a]), end=float(c.start[b - 1] + c.period[b - 1]),
        amplitude_scale=scale, n_cycles=int(b - a),
        period=float(np.mean(c.period[a:b])), height=float(np.mean(c.height[a:b])),
        tolerance=float(tolerance), settled=float(c.start[starts[0]]))


def steady_window_or_centred(x: np.ndarray, time: np.ndarray, tolerance: float = 0.02,
                             min_period: float = 0.0, min_cycles: int = 2) -> SteadyWindow:
    """:func:`quasi_steady_window` of x, or of x about its median when that finds none.

    A flap that leans far to one side (short steep waves against a single-acting PTO) may
    cross θ = 0 barely or not at all once steady, so its zero up-crossings give no cycles whose
    crests repeat within the tolerance. The paper's reference (t/T = 0 at the up-crossing of
    θ = 0) is kept wherever it works; otherwise the cycles are those of x minus its median
    over the second half of the record (the crests then measured from that median).
    """
    try:
        win = quasi_steady_window(x, time, tolerance=tolerance, min_period=min_period)
        if win.n_cycles >= min_cycles:
            return win
    except ValueError:
        pass
    x = np.asarray(x, dtype=float)
    return quasi_steady_window(x - np.median(x[x.size // 2:]), time, tolerance=tolerance,
                               min_period=min_period)


@dataclass(frozen=True)
class PhaseAverage:
    """Phase average over N cycles (Brito et al. 2020, Eqs. 2-3) and its statistics."""

    phase: np.ndarray  # t/T in [0, 1)
    mean: np.ndarray  # (..., phase)
    std: np.ndarray  # fluctuation RMS about the phase mean, (..., phase)
    ci95: np.ndarray  # half-width of the 95 % confidence interval of the mean, (..., phase)
    n_cycles: int


def resample_cycles(x: np.ndarray, time: np.ndarray, period: float, start: float,
                    n_cycles: int, n_phase: int = 100, kind: str = "linear") -> np.ndarray:
    """Values of ``x`` at t = start + (i + p) T for i < n_cycles and p on a phase grid.

    Returns an array of shape ``x.shape[:-1] + (n_cycles, n_phase)`` by linear interpolation on
    the uniform time grid (vectorised over all leading axes). ``kind="cubic"`` uses Keys' cubic
    convolution (a = -1/2) instead: linear interpolation, averaged over the cycles' random
    sub-sample offsets, acts as a triangle filter and biases a phase average by about
    -(ω dt)²/12 of each harmonic's amplitude (0.2 % at 3.5 s and 11.6 Hz); cubic convolution
    reduces this to O((ω dt)⁴).
    """
    if kind not in ("linear", "cubic"):
        raise ValueError(f"kind must be 'linear' or 'cubic', got {kind!r}")
    time = np.asarray(time, dtype=float)
    dt = uniform_step(time, "phase averaging")
    t_end = start + n_cycles * period
    if start < time[0] - 1e-9 or t_end > time[-1] + dt:
        raise ValueError(
            f"{n_cycles} cycles of {period:g} s from t = {start:g} s end at {t_end:g} s, "
            f"beyond the record [{time[0]:g}, {time[-1]:g}] s")
    phase = np.arange(n_phase) / n_phase
    tq = start + (np.arange(n_cycles)[:, None] + phase[None, :]) * period
    pos = np.clip((tq - time[0]) / dt, 0, time.size - 1 - 1e-9)
    i0 = np.floor(pos).astype(int)
    w = pos - i0
    x = np.asarray(x, dtype=float)
    if kind == "linear":
        return x[..., i0] * (1 - w) + x[..., i0 + 1] * w
    # Keys (1981) cubic convolution weights for the samples i0-1 .. i0+2 (clamped at the ends),
    # accumulated in place (the cost is memory traffic over the (..., cycle, phase) arrays)
    w2, w3 = w * w, w * w * w
    last = time.size - 1
    taps = ((np.maximum(i0 - 1, 0), 0.5 * (-w3 + 2 * w2 - w)), (i0, 0.5 * (3 * w3 - 5 * w2 + 2)),
            (i0 + 1, 0.5 * (-3 * w3 + 4 * w2 + w)), (np.minimum(i0 + 2, last), 0.5 * (w3 - w2)))
    out = np.take(x, taps[0][0], axis=-1)
    out *= taps[0][1]
    for idx, weight in taps[1:]:  # three more taps
        term = np.take(x, idx, axis=-1)
        term *= weight
        out += term
    return out


def phase_average(x: np.ndarray, time: np.ndarray, period: float, start: float, n_cycles: int,
                  n_phase: int = 100, kind: str = "linear") -> PhaseAverage:
    """Phase average of ``x`` over ``n_cycles`` periods from ``start`` (Brito et al. 2020, Eq. 2).

    ``std`` is the RMS of the fluctuation x - <x> over the cycles at each phase (the
    phase-resolved turbulence intensity for velocities); ``ci95`` the Student-t half-width of the
    95 % confidence interval of the mean, treating cycles as independent. ``kind`` selects the
    interpolation between samples (:func:`resample_cycles`).
    """
    if n_cycles < 2:
        raise ValueError("phase averaging needs at least two cycles")
    cyc = resample_cycles(x, time, period, start, n_cycles, n_phase, kind=kind)
    mean = cyc.mean(axis=-2)
    std = cyc.std(axis=-2, ddof=1)
    from scipy import stats as _stats  # imported here: seconds to import, used only here

    ci = _stats.t.ppf(0.975, n_cycles - 1) * std / np.sqrt(n_cycles)
    return PhaseAverage(phase=np.arange(n_phase) / n_phase, mean=mean, std=std, ci95=ci,
                        n_cycles=n_cycles)


def estimate_time_offset(reference: np.ndarray, reference_time: np.ndarray, other: np.ndarray,
                         other_time: np.ndarray, max_offset: float | None = None) -> float:
    """Clock offset of a second instrument from a signal both record, by cross-correlation.

    The two records are interpolated onto one uniform grid (the finer of their sampling
    intervals), standardised, and cross-correlated by FFT; the peak is refined by a parabola
    through its three samples (sub-sample resolution).

    Parameters
    ----------
    reference : Common signal as recorded by the reference instrument (any unit).
    reference_time : Its time stamps [s], increasing.
    other : The same signal as recorded by the other instrument (any unit, any gain).
    other_time : Its time stamps on its own clock [s], increasing.
    max_offset : Largest offset searched [s]; default half the shorter record.

    Returns
    -------
    The offset [s] to add to ``other_time`` to put it on the reference clock (the value of
    ``[clock] <instrument>`` in run.toml). Only meaningful for a signal both instruments
    record (a trigger pulse, the same probe): between different physical quantities it
    includes their physical phase lag. Reported to the user, never applied by itself.
    """
    tr, to = np.asarray(reference_time, float), np.asarray(other_time, float)
    dt = min(np.median(np.diff(tr)), np.median(np.diff(to)))
    span = min(tr[-1] - tr[0], to[-1] - to[0])
    max_offset = 0.5 * span if max_offset is None else float(max_offset)
    t0, t1 = min(tr[0], to[0]), max(tr[-1], to[-1])
    grid = t0 + dt * np.arange(int(np.floor((t1 - t0) / dt)) + 1)

    def standard(x, t):
        y = np.interp(grid, t, np.asarray(x, float), left=np.nan, right=np.nan)
        ok = np.isfinite(y)
        y = np.where(ok, y - np.nanmean(y), 0.0)
        return y / (np.sqrt(np.sum(y**2)) or 1.0)

    a, b = standard(reference, tr), standard(other, to)
    n = 1 << int(np.ceil(np.log2(2 * grid.size)))
    c = np.fft.irfft(np.fft.rfft(a, n) * np.conj(np.fft.rfft(b, n)), n)
    lags = np.concatenate([np.arange(0, n // 2), np.arange(-n // 2, 0)]) * dt
    c[np.abs(lags) > max_offset] = -np.inf
    k = int(np.argmax(c))
    y0, y1, y2 = c[k - 1], c[k], c[(k + 1) % n]
    denom = y0 - 2 * y1 + y2
    frac = 0.5 * (y0 - y2) / denom if np.isfinite(denom) and denom != 0 else 0.0
    return float(lags[k] + frac * dt)


def cycle_amplitude(x: np.ndarray, time: np.ndarray, period: float, start: float,
                    n_cycles: int, n_phase: int = 100) -> float:
    """Half the difference of the mean per-cycle maximum and minimum of ``x``.

    The amplitude of Brito et al. (2020, §3.2, Fig. 8) over ``n_cycles`` periods from ``start``
    [s], each cycle resampled on ``n_phase`` points (:func:`resample_cycles`); in the unit of
    ``x``.
    """
    cyc = resample_cycles(x, time, period, start, n_cycles, n_phase)
    return float(0.5 * (cyc.max(axis=-1).mean() - cyc.min(axis=-1).mean()))
