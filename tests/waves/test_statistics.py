"""Zero-crossing wave statistics against exact waves and the Rayleigh expectations.

Truths: a sampled cosine whose crests, troughs lie on samples (exact H and T), the
up-crossings of -η (the down-crossing option), and linear random-phase Gaussian seas
synthesised here, whose heights follow the Rayleigh distribution when the spectrum is
narrow (Longuet-Higgins 1952) and Rice's mean crossing period sqrt(m0/m2) at any width.
"""

import numpy as np
import pytest
import xarray as xr

from flumekit.synth.waves import jonswap
from flumekit.waves import spectral_parameters, spectrum, wave_statistics


def gaussian_sea(duration, fs, variance_density, seed):
    """Linear random-phase Gaussian record [m] of a variance density S(f) [m2 s]."""
    n = int(round(duration * fs))
    f = np.fft.rfftfreq(n, 1.0 / fs)
    s = variance_density(f)
    rng = np.random.default_rng(seed)
    c = np.sqrt(s * f[1]) * (rng.standard_normal(f.size) + 1j * rng.standard_normal(f.size))
    return np.fft.irfft(c * n / 2, n)


def narrow(f, f0=0.5, width=0.025, m0=1e-3):
    s = np.exp(-0.5 * ((f - f0) / width) ** 2)
    return s * m0 / (s.sum() * (f[1] - f[0]))


def test_a_cosine_gives_its_exact_height_and_period_both_ways():
    fs, period, a = 20.0, 2.0, 0.05
    t = np.arange(int(61 * fs)) / fs  # 30.5 periods; crests at t = 0, 2, ..., troughs at odd t
    eta = 0.01 + a * np.cos(2 * np.pi * t / period)  # an offset: the mean is removed
    for crossing in ("up", "down"):
        w = wave_statistics(eta, fs, crossing=crossing)
        n = int(w.number_of_waves)
        # up-crossings at t = 1.5, 3.5, ..., 59.5 (30), down-crossings at 0.5, ..., 60.5 (31)
        assert n == (29 if crossing == "up" else 30)
        h = w.individual_wave_height.values
        tw = w.individual_wave_period.values
        # the mean of 30.5 periods is off zero by a/(61 π) · sin: the crossing times move
        # together, so periods stay exact; heights are crest minus trough samples
        np.testing.assert_allclose(h, 2 * a, rtol=1e-12)
        np.testing.assert_allclose(tw, period, rtol=1e-9)
        for name in ("hrms", "h1_3", "h1_10", "hmax"):
            assert float(w[name]) == pytest.approx(2 * a, rel=1e-12), name
        for name in ("t1_3", "tz"):
            assert float(w[name]) == pytest.approx(period, rel=1e-9), name
        # up-crossings of a cos at t = 1.5 + 2j, down-crossings at 0.5 + 2j (mean-shifted)
        first = 1.5 if crossing == "up" else 0.5
        mean = float(np.mean(eta)) - 0.01
        shift = np.arcsin(mean / a) * period / (2 * np.pi) * (1 if crossing == "up" else -1)
        np.testing.assert_allclose(w.individual_wave_start.values,
                                   first + shift + period * np.arange(n), atol=2e-5)
    assert w.attrs["crossing"] == "down"


def test_down_crossing_is_the_up_crossing_of_the_reversed_sign():
    eta = gaussian_sea(600, 25.0, lambda f: jonswap(f, 0.1, 2.0), seed=5)
    down = wave_statistics(eta, 25.0, crossing="down")
    up_of_minus = wave_statistics(-eta, 25.0, crossing="up")
    up = wave_statistics(eta, 25.0)
    for name in ("individual_wave_height", "individual_wave_period", "individual_wave_start",
                 "h1_3", "hmax", "tz"):
        np.testing.assert_array_equal(down[name].values, up_of_minus[name].values)
    # and it is another set of waves than the up-crossing one
    assert not np.allclose(down.individual_wave_start[:10], up.individual_wave_start[:10])
    starts = down.individual_wave_start.values
    i = np.searchsorted(np.arange(eta.size) / 25.0, starts)
    e = eta - eta.mean()
    assert np.all(e[i - 1] > 0) and np.all(e[i] <= 0)  # each wave starts going down


def test_narrow_band_heights_follow_rayleigh():
    # narrow Gaussian spectrum (σ_f = 0.05 f0), 1 h at 10 Hz, ~1800 waves, normalised by the
    # record's own variance. Rayleigh: H1/3 = 4.004 sqrt(m0), Hrms = sqrt(8 m0),
    # H1/10 = 1.271 H1/3. Over 30 seeds: H1/3/sqrt(m0) = 3.974 ± 0.026 (finite width lowers it
    # slightly), Hrms/sqrt(8 m0) = 0.994 ± 0.001, H1/10/H1/3 = 1.271 ± 0.020.
    # Tolerances: 3 %, 2 % and 5 %; Hmax between the 0.1 % and 99.9 % quantiles of the maximum
    # of N Rayleigh heights, P(Hmax/Hs < x) = (1 - exp(-2 x²))^N with Hs = 4 sqrt(m0)
    for seed in range(3):
        eta = gaussian_sea(3600, 10.0, narrow, seed=seed)
        w = wave_statistics(eta, 10.0)
        rms = eta.std()
        n = int(w.number_of_waves)
        assert 1700 < n < 1900  # 3600 s / 2 s
        assert float(w.h1_3) / rms == pytest.approx(4.004, rel=0.03)
        assert float(w.hrms) / (np.sqrt(8) * rms) == pytest.approx(1.0, rel=0.02)
        assert float(w.h1_10) / float(w.h1_3) == pytest.approx(1.271, rel=0.05)
        lo, hi = (np.sqrt(-np.log(1 - q ** (1 / n)) / 2) for q in (0.001, 0.999))
        assert lo < float(w.hmax) / (4 * rms) < hi, (lo, float(w.hmax) / (4 * rms), hi)
        # the most probable maximum sqrt(ln N / 2) lies inside that band
        assert lo < np.sqrt(np.log(n) / 2) < hi


def test_jonswap_h13_over_hm0_and_rice_mean_period():
    # broad JONSWAP (γ 3.3): H1/3 ≈ 0.95 Hm0 (Goda 2010); over 30 seeds of 30 min,
    # H1/3/(4 σ) = 0.967 ± 0.005 (0.958 to 0.976); tolerance 0.93 to 1.0.
    # Rice: the mean zero-crossing period is sqrt(m0/m2) of the record's spectrum; the 25-Hz
    # sampling resolves every crossing of the f^-5 tail (tolerance 3 %)
    for seed in range(3):
        eta = gaussian_sea(1800, 25.0, lambda f: jonswap(f, 0.1, 2.0), seed=30 + seed)
        w = wave_statistics(eta, 25.0)
        assert 0.93 < float(w.h1_3) / (4 * eta.std()) < 1.0
        p = spectral_parameters(spectrum(eta, 25.0).variance_density)
        assert float(w.tz) == pytest.approx(float(p.tm02), rel=0.03)
        # T1/3 of a JONSWAP sea lies a little below Tp (Goda 2010, Chapter 2: about 0.9 Tp)
        assert 0.85 < float(w.t1_3) / 2.0 < 1.0


def test_records_along_other_dims_each_get_their_waves():
    fs = 25.0
    eta = np.stack([gaussian_sea(300, fs, lambda f, h=h: jonswap(f, h, 2.0), seed=40)
                    for h in (0.05, 0.1, 0.2)])
    eta[2] = gaussian_sea(300, fs, lambda f: jonswap(f, 0.1, 1.5), seed=41)
    da = xr.DataArray(eta.T, dims=("time", "probe"),
                      coords={"probe": ["a", "b", "c"], "x": ("probe", [0.0, 0.6, 0.9]),
                              "time": np.arange(eta.shape[1]) / fs})
    w = wave_statistics(da)
    assert w.hmax.dims == ("probe",) and w.individual_wave_height.dims == ("probe", "wave")
    assert list(w.x.values) == [0.0, 0.6, 0.9]
    counts = w.number_of_waves.values
    assert counts[2] > counts[0]  # the shorter period has more waves: NaN pads the others
    for i in range(3):
        one = wave_statistics(eta[i], fs)
        n = int(one.number_of_waves)
        assert counts[i] == n
        np.testing.assert_array_equal(w.individual_wave_height[i, :n], one.individual_wave_height)
        assert np.all(np.isnan(w.individual_wave_height[i, n:]))
        for name in ("hrms", "h1_3", "t1_3", "h1_10", "hmax", "tz"):
            assert float(w[name][i]) == float(one[name])
    # scaling the sea scales the heights, not the periods
    assert float(w.h1_3[1]) == pytest.approx(2 * float(w.h1_3[0]), rel=1e-12)
    assert float(w.tz[1]) == pytest.approx(float(w.tz[0]), rel=1e-12)
    assert w.h1_3.attrs["units"] == "m" and w.tz.attrs["units"] == "s"
    assert w.hmax.attrs["standard_name"] == "sea_surface_wave_maximum_height"


def test_wave_statistics_refuses_what_it_cannot_analyse():
    t = np.arange(500) / 10.0
    with pytest.raises(ValueError, match="crossing"):
        wave_statistics(np.sin(t), 10.0, crossing="both")
    with pytest.raises(ValueError, match="non-finite"):
        wave_statistics(np.where(t > 20, np.nan, np.sin(t)), 10.0)
    with pytest.raises(ValueError, match="no complete"):
        wave_statistics(np.sin(2 * np.pi * t / 80.0), 10.0)  # half a wave


def test_outputs_carry_the_registry_attributes():
    from flumekit import conventions

    eta = gaussian_sea(300, 10.0, narrow, seed=7)
    up = wave_statistics(eta, 10.0)
    conventions.check(up)
    for name in up.data_vars:
        assert up[name].attrs == conventions.attrs(name), name
    down = wave_statistics(eta, 10.0, crossing="down")
    assert down.tz.attrs["long_name"] == "mean zero down-crossing period"
    assert down.tz.attrs["standard_name"] == "sea_surface_wave_mean_period"
