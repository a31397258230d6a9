"""QC tests on records with a known truth: virtual-flume-like probe, encoder and velocity
records with injected faults. Recall >= 95 % of the faulty samples, no false flag on the clean
records (<= 0.1 %)."""

import numpy as np
import pytest

from flumekit.qc import flags as F
from flumekit.qc import qartod
from flumekit.qc.clock import clock_departures
from flumekit.qc.despike import goring_nikora
from flumekit.qc.fill import fill_gaps
from flumekit.qc.record import Thresholds, check_beam, check_series, clean


def _wave(fs: float, seconds: float, period: float, amplitude: float, noise: float, rng,
          n: int = 1, rest: float = 20.0) -> tuple[np.ndarray, np.ndarray]:
    """Ramped second-order-like regular wave after a still lead-in, ``n`` channels."""
    t = np.arange(int(seconds * fs)) / fs
    env = np.clip((t - rest) / (8 * period), 0, 1)
    env = 0.5 - 0.5 * np.cos(np.pi * env)
    ph = 2 * np.pi * t / period
    x = [env * amplitude * (np.cos(ph + j) + 0.15 * np.cos(2 * (ph + j)))
         + noise * rng.standard_normal(t.size) for j in range(n)]
    return t, np.array(x)


def _flagged(per_test):
    return F.aggregate(*per_test.values()) >= F.SUSPECT


@pytest.mark.parametrize("period", [2.0, 3.5])
def test_clean_probe_records_pass_untouched(period):
    rng = np.random.default_rng(1)
    t, x = _wave(25.0, 220, period, 0.5, 0.005, rng, n=4)
    x += 2.5
    f = _flagged(check_series(x, t, 25.0, Thresholds()))
    assert f.mean() <= 1e-3
    assert f.sum() == 0


def test_spikes_dropout_and_flat_line_are_flagged():
    rng = np.random.default_rng(2)
    t, x = _wave(25.0, 220, 2.0, 0.5, 0.005, rng, n=4)
    x += 2.5
    bad = np.zeros(x.shape, dtype=bool)
    for p in range(4):
        idx = rng.choice(np.arange(5, t.size - 5, 4), 10, replace=False)
        x[p, idx] += rng.choice([-1, 1], 10) * rng.uniform(0.15, 0.4, 10) * 1.0
        bad[p, idx] = True
    x[0, 2500:2525] = 0.0  # 1 s dropout to 0 V
    bad[0, 2500:2525] = True
    x[2, 3000:3200] = x[2, 3000]  # 8 s flat line
    bad[2, 3000:3200] = True
    f = _flagged(check_series(x, t, 25.0, Thresholds()))
    assert f[bad].mean() >= 0.95
    assert f[~bad].mean() <= 1e-3
    # failed samples are masked: spikes interpolated, the dropout and flat line left NaN
    agg = F.aggregate(*check_series(x, t, 25.0, Thresholds()).values())
    c = clean(x, agg, 25.0, 0.2)
    assert np.isnan(c[0, 2505:2520]).all() and np.isnan(c[2, 3010:3190]).all()
    assert np.isfinite(c[1]).all() and np.isfinite(c[3]).all()


def test_quantised_encoder_at_rest_and_at_reversals_passes():
    rng = np.random.default_rng(3)
    t, x = _wave(100.0, 200, 3.5, 1.0, 0.0, rng)
    counts = np.round(600 * x)  # at rest for the first 20 s; a few counts per sample
    f = _flagged(check_series(counts, t, 100.0, Thresholds()))
    assert f.sum() == 0
    stuck = counts.copy()
    stuck[0, 10000:11000] = stuck[0, 10000]  # 10 s stuck while the flap moves
    f = check_series(stuck, t, 100.0, Thresholds())["flat_line"]
    assert (f[0, 10001:11000] == F.FAIL).all()


def test_goring_nikora_finds_spikes_in_velocity_records():
    rng = np.random.default_rng(4)
    t = np.arange(4000) / 11.6
    u = 0.3 * np.sin(2 * np.pi * t / 3.5)[None, :] + 0.02 * rng.standard_normal((50, t.size))
    u = np.round(u / 0.0073) * 0.0073  # quantised like a UVP
    th = Thresholds()

    def spikes(v):
        g = check_beam(v, t, 11.6, th, floor=0.0073)["goring_nikora"]
        return g == F.FAIL

    assert spikes(u).mean() <= 1e-3  # clean record
    assert goring_nikora(u, floor=0.0073).mean() <= 1e-3  # the method on its own too
    bad = np.zeros(u.shape, dtype=bool)
    spaced = np.arange(2, t.size - 2, 5)[None, :] + t.size * np.arange(50)[:, None]
    idx = rng.choice(spaced.ravel(), 500, replace=False)
    bad.flat[idx] = True
    v = u.copy()
    v.flat[idx] += rng.choice([-1, 1], 500) * rng.uniform(0.15, 0.4, 500)
    s = spikes(v)
    assert s[bad].mean() >= 0.95
    # a spike moves the phase-space derivatives of its neighbours too (GN 2002, §4): at most
    # its two neighbours are taken with it
    assert s[~bad].sum() <= 2 * bad.sum()


def test_fill_gaps_only_up_to_the_declared_length():
    x = np.arange(20.0)
    valid = np.ones(20, bool)
    valid[[3, 4]] = False  # 2-sample gap
    valid[10:15] = False  # 5-sample gap
    out = fill_gaps(np.where(valid, x, -99.0), valid, max_gap=2)
    np.testing.assert_allclose(out[:10], x[:10])
    assert np.isnan(out[10:15]).all()
    np.testing.assert_allclose(fill_gaps(np.where(valid, x, -99.0), valid), x)


def test_flags_aggregate_worst_and_cf_attributes():
    a = np.array([1, 2, 3, 1, 2])
    b = np.array([2, 2, 1, 4, 9])
    np.testing.assert_array_equal(F.aggregate(a, b), [1, 2, 3, 4, 9])
    attrs = F.flag_attrs("probe_voltage")
    assert list(attrs["flag_values"]) == [1, 2, 3, 4, 9]
    assert attrs["flag_meanings"].split()[3] == "fail"


def test_gross_range_and_gap_tests():
    x = np.array([0.0, 1.0, 5.0, -3.0, np.nan])
    f = qartod.gross_range_test(x, (-2.0, 4.0), (-1.0, 0.5))
    np.testing.assert_array_equal(f, [1, 3, 4, 4, 9])
    assert (qartod.gross_range_test(x[:4], None) == F.NOT_EVALUATED).all()
    t = np.array([0.0, 0.04, 0.08, 0.2, 0.24])
    np.testing.assert_array_equal(qartod.gap_test(t, 25.0), [1, 1, 1, 4, 1])


def test_clock_departures_same_condition_median_and_wrap_by_the_period():
    lags = np.array([1.35, 1.35, 1.65, 0.4, 0.41])
    periods = np.array([3.5, 3.5, 3.5, 2.0, 2.0])
    heights = np.array([0.25, 0.25, 0.25, 0.15, 0.15])
    d, basis = clock_departures(lags, periods, heights)
    np.testing.assert_allclose(d[:3], [0.0, 0.0, 0.3])
    assert "median of the 3 runs" in basis[0]
    # two runs of T = 2 s and one other period only: no reference (no extrapolation in T)
    assert np.isnan(d[3:]).all() and basis[3].startswith("no reference")
    d, _ = clock_departures(np.array([-1.7, 1.7, 1.7]), np.full(3, 3.5), np.full(3, 0.25))
    np.testing.assert_allclose(d, [0.1, 0.0, 0.0], atol=1e-12)


@pytest.mark.parametrize("length", [3001, 3000])
def test_despiking_and_echo_level_per_channel_whatever_the_block(length):
    """The despiking and the echo-level test are worked a few channels at a time
    (flumekit.qc.blocks): each channel's flags are those of the channel tested on its own
    (every statistic is per channel; the universal threshold's n given, the longest record),
    for odd and even record lengths (the median's two forms), with missing samples."""
    rng = np.random.default_rng(8)
    m = 70  # more than two blocks
    t = np.arange(length) / 11.6
    u = 0.3 * np.sin(2 * np.pi * t / 3.5)[None, :] + 0.02 * rng.standard_normal((m, length))
    u = np.round(u / 0.0073) * 0.0073
    u.flat[rng.choice(u.size, 300, replace=False)] += rng.choice([-1, 1], 300) * 0.3
    u[5, 100:110] = np.nan
    u[:, -1] = np.nan  # every channel one short: n is the longest record, length - 1
    whole = goring_nikora(u, floor=0.0073, max_iterations=3)
    assert whole.sum() >= 250  # the spikes (and, before pruning, their neighbours)
    # one channel with channel 1 (length - 1 valid samples: the same n), outside any block
    for r in (0, 5, 33, 69):
        alone = goring_nikora(u[[r, 1]], floor=0.0073, max_iterations=3)
        np.testing.assert_array_equal(alone[0], whole[r])
    amp = (300 + 40 * rng.standard_normal((m, length))).astype(np.int16)
    amp[7, 2000:2030] = 900  # a boundary echo
    level = qartod.level_test(amp, 6.0)
    assert (level[7, 2000:2030] == F.FAIL).all()
    for r in (0, 7, 40, 69):
        np.testing.assert_array_equal(qartod.level_test(amp[[r]], 6.0)[0], level[r])


def test_echo_level_and_integer_statistics_exact_against_sorting():
    """The echo-level test reads the median and the median absolute deviation of integer
    records from histograms (the deviations' from the values'), and sorts rows spanning more
    values than the histogram has bins (flumekit.qc.kernels): the flags and medians are those
    of the definition computed by sorting (np.median), on records of every kind that reaches
    a different path: small ranges, wide ranges, an echo over half the record, coarse steps,
    a span beyond the bins, a transposed (strided) layout."""
    rng = np.random.default_rng(12)

    def by_sorting(x, threshold):
        med = np.median(x, axis=-1)
        dev2 = np.abs(2 * x.astype(np.int64) - np.rint(2 * med).astype(np.int64)[:, None])
        steps = np.abs(np.diff(x.astype(np.int64), axis=-1))
        res = np.where(steps > 0, steps, np.iinfo(np.int64).max).min(axis=-1)
        res = np.where(res == np.iinfo(np.int64).max, 0, res)
        scale = np.maximum(qartod.MAD_TO_STD * 0.5 * np.median(dev2, axis=-1), res)
        bound = np.floor(2 * threshold * scale)[:, None]
        return np.where(dev2 > bound, F.FAIL, F.GOOD)

    for kind in range(6):
        m, n = 40, 301 + kind
        if kind == 0:
            x = rng.integers(-5, 5, (m, n))
        elif kind == 1:  # echo amplitudes with a boundary echo
            x = (300 + 40 * rng.standard_normal((m, n))).astype(np.int16)
            x[3, 100:130] = 2900
        elif kind == 2:  # a wide range
            x = rng.integers(0, 9000, (m, n)).astype(np.int16)
        elif kind == 3:  # the echo over half the record
            x = (300 + 10 * rng.standard_normal((m, n))).astype(np.int16)
            x[:, : n // 2 + 1] += 3000
        elif kind == 4:  # coarse steps and a far mode
            x = (rng.integers(0, 3, (m, n)) * 8 + rng.choice([0, 2000], (m, n), p=[.7, .3]))
            x = x.astype(np.int32)
        else:  # counts spanning more values than the histogram's bins (sorted), transposed
            x = np.ascontiguousarray(rng.integers(-60000, 60000, (n, m)).astype(np.int32)).T
        for threshold in (6.0, 1.0):
            np.testing.assert_array_equal(qartod.level_test(x, threshold),
                                          by_sorting(x, threshold))
        np.testing.assert_array_equal(qartod.robust_median(x), np.median(x, axis=-1))


def test_runs_of_sparse_and_dense_masks():
    """runs() finds the same runs from a sparse mask's indices as from its edges."""
    from flumekit.qc import fill

    rng = np.random.default_rng(5)
    for density in (0.003, 0.01, 0.3, 0.9):
        mask = rng.random((7, 500)) < density
        mask[2, -3:] = True  # a run at a row's end, next to one at the next row's start
        mask[3, :2] = True
        row, first, length = fill.runs(mask)
        rebuilt = np.zeros_like(mask)
        for r, a, k in zip(row, first, length, strict=True):
            assert not rebuilt[r, a:a + k].any() and mask[r, a:a + k].all()
            rebuilt[r, a:a + k] = True
            assert a == 0 or not mask[r, a - 1]
            assert a + k == mask.shape[1] or not mask[r, a + k]
        np.testing.assert_array_equal(rebuilt, mask)


def _goring_nikora_by_definition(u, floor, lam2, iterations, valid):
    """Goring and Nikora (2002) on one channel, written from the paper with numpy: the
    fluctuation about the median, np.gradient for Δu and Δ²u (Eqs. 6-7), the three ellipses
    with the third rotated by θ (Eq. 9) in rotated coordinates, its axes from Eqs. (10)-(11);
    spikes and invalid samples replaced by linear interpolation (ends held; rounded to the
    record's step when it is quantised) between iterations."""
    t = np.arange(u.size)
    unit = floor if floor > 0 else 1.0
    ok = valid.copy()
    spikes = np.zeros(u.size, dtype=bool)

    def var(a):
        return max(np.mean(a * a) - np.mean(a) ** 2, (floor / unit) ** 2)

    for _ in range(iterations):
        w = np.interp(t, t[ok], u[ok] / unit)
        if np.all(np.abs(w[ok] - np.rint(w[ok])) <= 1e-6):  # quantised: on its grid
            w = np.rint(w)
        c = w - np.median(w)
        du = np.gradient(c)
        d2 = np.gradient(du)
        theta = np.arctan2(np.sum(c * d2), np.sum(c * c))
        a1, b1 = lam2 * var(c), lam2 * var(d2)
        cos2, sin2 = np.cos(theta) ** 2, np.sin(theta) ** 2
        a2 = (a1 * cos2 - b1 * sin2) / (cos2 - sin2)
        b2 = (b1 * cos2 - a1 * sin2) / (cos2 - sin2)
        if not (a2 > 0 and b2 > 0):
            a2, b2 = a1, b1
        xr = c * np.cos(theta) + d2 * np.sin(theta)
        yr = -c * np.sin(theta) + d2 * np.cos(theta)
        out = ((c ** 2 / a1 + du ** 2 / (lam2 * var(du)) > 1)
               | (d2 ** 2 / b1 + du ** 2 / (lam2 * var(du)) > 1)
               | (xr ** 2 / a2 + yr ** 2 / b2 > 1))
        new = out & ok
        if not new.any():
            break
        spikes |= new
        ok &= ~new
    return spikes


@pytest.mark.parametrize("quantised", [True, False])
def test_goring_nikora_equals_its_definition(quantised):
    """The compiled despiking (flumekit.qc.kernels) flags what the paper's definition, written
    independently above, flags: sample for sample, with spikes, missing and excluded samples,
    one and several iterations, quantised (whole numbers in units of the floor: the
    histogram median) and continuous records, in a transposed (strided) layout."""
    rng = np.random.default_rng(21)
    m, n = 24, 2901
    t = np.arange(n) / 11.6
    u = 0.3 * np.sin(2 * np.pi * t / 3.5)[None, :] + 0.02 * rng.standard_normal((m, n))
    idx = rng.choice(u.size, 200, replace=False)
    u.flat[idx] += rng.choice([-1, 1], 200) * rng.uniform(0.1, 0.3, 200)
    floor = 0.0073
    if quantised:
        u = np.round(u / floor) * floor
    u[3, 500:520] = np.nan
    exclude = np.zeros(u.shape, dtype=bool)
    exclude[7, 1000:1010] = True
    u = np.ascontiguousarray(u.T).T  # stored profile by profile, as a UVP beam
    valid = np.isfinite(u) & ~exclude
    lam2 = 2 * np.log(valid.sum(axis=-1).max())
    for iterations in (1, 4):
        got = goring_nikora(u, floor=floor, max_iterations=iterations, exclude=exclude)
        want = np.array([_goring_nikora_by_definition(u[r], floor, lam2, iterations, valid[r])
                         for r in range(m)])
        assert want.sum() >= 200  # the spikes are found (and some of their neighbours)
        np.testing.assert_array_equal(got, want)
