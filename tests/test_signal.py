"""Shared signal tools: cycles, quasi-steady window, phase averaging, against analytic truths."""

import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import stats

from flumekit.signal import (
    cycles,
    lowpass,
    median_rows,
    nanmedian,
    phase_average,
    quasi_steady_window,
    resample_cycles,
    zero_upcrossings,
)

FS = 100.0


@settings(max_examples=30, deadline=None)
@given(st.floats(0.5, 5.0), st.floats(0.01, 2.0), st.floats(0.0, 2 * np.pi))
def test_cycles_of_a_sine(period, amplitude, phase):
    t = np.arange(0, 20 * period, 1 / FS)
    x = amplitude * np.sin(2 * np.pi * t / period + phase)
    c = cycles(x, t)
    # truth: up-crossings at t = (k - phase/2π) T; linear interpolation of a sine near its zero
    # is exact to O((ω dt)³), periods exact to rounding of the differences
    np.testing.assert_allclose(c.period, period, rtol=1e-5)
    first = (-phase / (2 * np.pi)) % 1.0 * period
    # a crossing at t[0] itself (phase = 0 or 2π) is in the record or not depending on the sign
    # rounding gives x[0] (sin 2π = -2.4e-16): either it or the next one is the first
    expected = [first, first + period] if first <= 1e-9 * period else [first]
    assert min(abs(c.start[0] - e) for e in expected) <= 2e-4 * period
    # sampled extrema lie within A (1 - cos(π dt / T)) of the true ±A
    tol = amplitude * (1 - np.cos(np.pi / (FS * period))) + 1e-12
    assert np.all(np.abs(c.crest - amplitude) <= tol)
    assert np.all(np.abs(c.trough + amplitude) <= tol)
    np.testing.assert_allclose(c.height, 2 * amplitude, atol=2 * tol)
    np.testing.assert_allclose(zero_upcrossings(x, t)[: c.start.size], c.start, atol=1e-12)


def test_cycles_merges_noisy_crossings_closer_than_min_period():
    T = 2.0
    t = np.arange(0, 30 * T, 1 / FS)
    rng = np.random.default_rng(0)
    # the record starts rising from below zero, so its first noisy cluster of up-crossings is
    # a true one. (Merging is anchored at the first crossing: had the record started just
    # before a down-crossing, noise there could make the first kept crossing a spurious one.)
    x = np.sin(2 * np.pi * t / T - 0.5) + rng.normal(0, 0.1, t.size)
    raw = cycles(x, t)
    # noise also makes up-crossings near the down-crossings, T/2 away: merge below 0.75 T
    merged = cycles(x, t, min_period=0.75 * T)
    assert raw.period.size > 29  # noise adds spurious crossings
    assert merged.period.size == 29  # up-crossings near 0.16 + 2k s, k = 0..29: 29 cycles
    # kept crossing: the first of each noisy cluster, within a few noise/slope = 0.03 s
    np.testing.assert_allclose(merged.period, T, atol=0.15)
    assert abs(np.mean(merged.period) - T) < 0.01
    assert cycles(np.ones(10), np.arange(10.0)).period.size == 0


def test_cycles_merge_keeps_the_crossings_of_the_sequential_rule():
    # each kept crossing is the first whose time minus the last kept one's is >= min_period, the
    # difference as computed: on a grid of 0.1 s far from t = 0 a crossing exactly min_period
    # on is kept or not as that difference rounds, not as t + min_period does
    rng = np.random.default_rng(7)
    t = 1000.0 + 0.1 * np.arange(4000)
    x = np.sin(2 * np.pi * t / 1.9) + 0.8 * rng.standard_normal(t.size)
    idx = np.flatnonzero((x[:-1] < 0) & (x[1:] >= 0)) + 1
    tc = t[idx]
    for min_period in (0.3, 0.7, 1.3):
        keep = [0]
        for j in range(1, tc.size):
            if tc[j] - tc[keep[-1]] >= min_period:
                keep.append(j)
        kept = idx[keep]
        expected = t[kept - 1] + (-x[kept - 1] / (x[kept] - x[kept - 1])) * (t[kept] - t[kept - 1])
        got = cycles(x, t, min_period=min_period)
        assert np.array_equal(got.start, expected[:-1])
        assert np.array_equal(got.crest, np.maximum.reduceat(x, kept)[:-1])
    # some of those differences are exactly one of the min_periods but for the rounding
    diffs = tc[None, :] - tc[:, None]
    assert np.any((diffs < 0.3) & (diffs > 0.3 - 1e-9)) or np.any(
        (diffs < 0.7) & (diffs > 0.7 - 1e-9))


def test_nanmedian_and_median_rows_give_numpys_numbers():
    # the same bits as numpy's, signed zeros and NaN included, odd and even counts
    rng = np.random.default_rng(3)
    for trial in range(300):
        n = int(rng.integers(1, 120))
        x = np.round(rng.standard_normal(n), 1 + trial % 3)
        x[rng.random(n) < 0.2] = np.nan
        x[rng.random(n) < 0.2] = -0.0
        with np.errstate(all="ignore"), warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)  # all NaN
            expected = np.float64(np.nanmedian(x))
        assert np.float64(nanmedian(x)).tobytes() == expected.tobytes() or (
            np.isnan(expected) and np.isnan(nanmedian(x)))
        rows = np.round(rng.standard_normal((1 + 2 * (trial % 3), n)), 1)
        rows[rng.random(rows.shape) < 0.1] = np.nan
        rows[rng.random(rows.shape) < 0.2] = -0.0
        got, want = median_rows(rows), np.median(rows, axis=0)
        assert np.array_equal(got, want, equal_nan=True)
        assert np.array_equal(np.signbit(got), np.signbit(want))
    assert np.isnan(nanmedian([np.nan, np.nan]))
    with pytest.raises(ValueError, match="odd number of rows"):
        median_rows(np.zeros((4, 3)))


def test_quasi_steady_window_of_an_exponential_ramp():
    # x = (1 - e^(-t/τ)) sin ωt: cycle n (from nT) has its crest near nT + T/4 with value
    # e(nT + T/4); the 2 % criterion starts at the first n with e >= 0.98 (scale -> 1)
    T, tau = 2.0, 15.0
    t = np.arange(0, 120 * T, 1 / FS)
    x = (1 - np.exp(-t / tau)) * np.sin(2 * np.pi * t / T)
    w = quasi_steady_window(x, t)
    n0 = int(np.ceil((tau * np.log(50) - T / 4) / T))
    assert w.start == pytest.approx(n0 * T, abs=1e-3)
    assert w.amplitude_scale == pytest.approx(1.0, abs=1e-3)
    assert w.period == pytest.approx(T, rel=1e-5)
    assert w.height == pytest.approx(2.0, rel=5e-3)
    assert w.end == pytest.approx(119 * T, abs=1e-3)  # last complete cycle
    assert w.n_cycles == 119 - n0
    # a 5 % criterion starts earlier
    assert quasi_steady_window(x, t, tolerance=0.05).start < w.start


def test_quasi_steady_window_errors():
    t = np.arange(0, 5, 1 / FS)
    with pytest.raises(ValueError, match="fewer than four"):
        quasi_steady_window(np.sin(2 * np.pi * t / 2.0), t)


def test_resample_cycles_is_exact_for_a_linear_signal_and_checks_range():
    t = np.arange(0, 50, 0.1)
    x = np.stack([t, 2 * t])
    out = resample_cycles(x, t, period=3.0, start=5.0, n_cycles=4, n_phase=10)
    truth = 5.0 + (np.arange(4)[:, None] + np.arange(10)[None, :] / 10) * 3.0
    np.testing.assert_allclose(out[0], truth, atol=1e-12)
    np.testing.assert_allclose(out[1], 2 * truth, atol=1e-12)
    with pytest.raises(ValueError, match="beyond the record"):
        resample_cycles(x, t, period=3.0, start=45.0, n_cycles=4)
    with pytest.raises(ValueError, match="uniformly"):
        resample_cycles(x, t**1.1, period=3.0, start=5.0, n_cycles=4)


def test_phase_average_mean_std_and_confidence_interval():
    T, n_cyc, sigma = 2.0, 200, 0.05
    t = np.arange(0, (n_cyc + 2) * T, 1 / FS)
    def wave(ph):
        return np.sin(2 * np.pi * ph) + 0.3 * np.cos(4 * np.pi * ph)

    rng = np.random.default_rng(1)
    clean = wave(t / T)
    x = np.stack([clean + rng.normal(0, sigma, t.size), 3 * clean])
    pa = phase_average(x, t, T, start=T, n_cycles=n_cyc, n_phase=50)
    assert pa.mean.shape == (2, 50) and pa.n_cycles == n_cyc
    truth = wave(pa.phase)
    # noiseless channel: exact up to linear interpolation between samples (dt/T = 0.005)
    np.testing.assert_allclose(pa.mean[1], 3 * truth, atol=3 * (2 * np.pi * 0.005) ** 2 / 8 * 2)
    # noisy channel: std ≈ σ (relative standard error 1/sqrt(2N) = 5 %), CI formula, coverage
    assert np.mean(pa.std[0]) == pytest.approx(sigma, rel=0.03)
    np.testing.assert_allclose(pa.ci95[0], stats.t.ppf(0.975, n_cyc - 1) * pa.std[0]
                               / np.sqrt(n_cyc), rtol=1e-12)
    covered = np.mean(np.abs(pa.mean[0] - truth) <= pa.ci95[0])
    assert 0.85 <= covered <= 1.0
    with pytest.raises(ValueError, match="two cycles"):
        phase_average(x, t, T, start=T, n_cycles=1)


def test_lowpass_keeps_the_band_and_removes_the_rest():
    t = np.arange(0, 100, 1 / FS)
    slow = np.sin(2 * np.pi * 0.3 * t)
    y = lowpass(slow + 0.5 * np.sin(2 * np.pi * 20 * t), FS, cutoff=2.0)
    # Butterworth order 4 run forward-backward: |H|² = 1/(1 + (f/fc)^8)
    gain = 1 / (1 + (0.3 / 2.0) ** 8)
    np.testing.assert_allclose(y[500:-500], gain * slow[500:-500], atol=1e-4)


def test_clock_offset_from_a_common_signal():
    """A band-limited random signal seen by two instruments (25 Hz and 100 Hz, gain 2, noise)
    on clocks 0.3 s apart: the cross-correlation recovers the offset within 1 ms."""
    from scipy.signal import butter, sosfiltfilt

    from flumekit.signal import estimate_time_offset

    rng = np.random.default_rng(0)
    fine = np.arange(0, 120, 1e-3)
    s = sosfiltfilt(butter(4, 2.0, fs=1000, output="sos"), rng.standard_normal(fine.size))
    t_ref, t_other = np.arange(0, 100, 0.04), np.arange(0, 100, 0.01)
    for offset in (0.3, -0.137):
        ref = np.interp(t_ref + 5, fine, s)
        other = 2 * np.interp(t_other + 5 + offset, fine, s)
        other += 0.01 * np.std(other) * rng.standard_normal(t_other.size)
        assert estimate_time_offset(ref, t_ref, other, t_other) == pytest.approx(offset, abs=1e-3)


def test_steady_window_of_a_leaning_signal():
    # a ramped sinusoid that, once steady, stays below zero (a flap leaning to the sea) has no
    # steady zero up-crossings; its cycles are then those about its median. A signal that does
    # cross zero keeps the zero-crossing window exactly.
    from flumekit.signal import quasi_steady_window, steady_window_or_centred

    t = np.arange(0, 200, 0.01)
    env = np.clip(t / 40, 0, 1)
    wave = 0.2 * env * np.sin(2 * np.pi * t / 2.0)
    leaning = wave - 0.25 * env
    with pytest.raises(ValueError):
        quasi_steady_window(leaning, t, min_period=1.0)
    win = steady_window_or_centred(leaning, t, min_period=1.0)
    assert win.period == pytest.approx(2.0, rel=1e-3)
    assert win.n_cycles > 60 and win.start > 35  # the envelope is within 2 % from t = 39 s
    assert steady_window_or_centred(wave, t, min_period=1.0) == quasi_steady_window(
        wave, t, min_period=1.0)
