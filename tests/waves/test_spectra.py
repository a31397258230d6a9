"""Welch spectrum, spectral parameters and spectral energy flux against their definitions.

Truths: the analytic JONSWAP and Pierson-Moskowitz spectra (moments by numpy's trapezoid rule
or in closed form with the Gamma function, not by the code under test), the exact Parseval
identities of Welch's estimate, and linear random-phase records synthesised here from a
JONSWAP spectrum (complex Gaussian Fourier coefficients: a Gaussian sea, so that the
chi-squared interval applies).
"""

import math

import numpy as np
import pytest
import xarray as xr

from flumekit.waves import spectral_energy_flux, spectral_parameters, spectrum, theory
from flumekit.waves.spectra import energy_flux

G = 9.81


def jonswap_shape(f, tp, gamma=3.3):
    """Unscaled JONSWAP shape (Hasselmann et al. 1973), zero at f = 0."""
    f = np.asarray(f, dtype=float)
    fp = 1.0 / tp
    fs = np.where(f > 0, f, fp)
    sigma = np.where(fs <= fp, 0.07, 0.09)
    s = fs**-5 * np.exp(-1.25 * (fp / fs) ** 4) * gamma ** np.exp(
        -((fs - fp) ** 2) / (2 * sigma**2 * fp**2))
    return np.where(f > 0, s, 0.0)


def jonswap(f, hm0, tp, gamma=3.3):
    """JONSWAP variance density [m2 s] with ∫ S df = Hm0²/16 over (0, 20/Tp]."""
    ff = np.linspace(0.0, 20.0 / tp, 400_001)
    scale = hm0**2 / 16 / np.trapezoid(jonswap_shape(ff, tp, gamma), ff)
    return scale * jonswap_shape(f, tp, gamma)


def gaussian_sea(duration, fs, hm0, tp, gamma=3.3, seed=0):
    """Linear random-phase record [m] of a JONSWAP sea, complex Gaussian coefficients."""
    n = int(round(duration * fs))
    f = np.fft.rfftfreq(n, 1.0 / fs)
    s = jonswap(f, hm0, tp, gamma)
    rng = np.random.default_rng(seed)
    c = np.sqrt(s * f[1]) * (rng.standard_normal(f.size) + 1j * rng.standard_normal(f.size))
    return np.fft.irfft(c * n / 2, n)


def as_da(s, f):
    return xr.DataArray(s, dims="frequency", coords={"frequency": f})


# --- spectrum --------------------------------------------------------------------------------

def test_welch_box_segments_tiling_the_record_hold_exactly_its_mean_square():
    # rectangular window, no overlap, no detrending, segments tiling the record: Parseval makes
    # Σ S Δf the record's mean square exactly (checks the density scaling and the one-sided
    # doubling, with the zero and Nyquist bins counted once)
    eta = gaussian_sea(640, 10.0, 0.1, 2.0, seed=1) + 0.01
    s = spectrum(eta, 10.0, segment_duration=64, overlap=0.0, window="boxcar", detrend=False)
    assert s.segments == 10 and s.equivalent_degrees_of_freedom == pytest.approx(20, rel=1e-12)
    total = float(s.variance_density.sum()) * s.frequency_resolution
    assert total == pytest.approx(np.mean(eta**2), rel=1e-12)


def test_welch_default_equals_the_mean_tapered_segment_variance_computed_here():
    # the estimate integrates to the average over segments of Σ (w (x - mean))² / Σ w²:
    # computed here with strides, independently of scipy
    fs = 25.0
    eta = gaussian_sea(600, fs, 0.1, 2.0, seed=2)
    s = spectrum(eta, fs)
    n = eta.size
    nseg = 2 * (n // 16)
    assert s.segments == 15 and s.segment_duration == pytest.approx(nseg / fs)
    w = 0.5 - 0.5 * np.cos(2 * np.pi * np.arange(nseg) / nseg)  # periodic Hann
    seg = np.lib.stride_tricks.sliding_window_view(eta, nseg)[:: nseg // 2][:15]
    seg = seg - seg.mean(axis=1, keepdims=True)
    expected = np.mean(np.sum((w * seg) ** 2, axis=1) / np.sum(w**2))
    total = float(s.variance_density.sum()) * s.frequency_resolution
    assert total == pytest.approx(expected, rel=1e-10)


def test_welch_integrates_to_the_record_variance_within_the_taper_weighting():
    # against the plain variance, the tapers weight the record's first and last 1/16 less:
    # over 30 seeds the difference had a standard deviation of 1.6 % (extremes -3.4, +2.4 %);
    # tolerance 5 % per record, and 1 % on the mean over 8 records
    errors = []
    for seed in range(8):
        eta = gaussian_sea(1800, 25.0, 0.1, 2.0, seed=seed)
        s = spectrum(eta, 25.0)
        errors.append(float(s.variance_density.sum()) * s.frequency_resolution / eta.var() - 1)
    errors = np.array(errors)
    assert np.max(np.abs(errors)) < 0.05, errors
    assert abs(errors.mean()) < 0.01, errors


def test_equivalent_degrees_of_freedom_follow_percival_walden_for_overlapping_hann():
    # Hann segments overlapping by half: ρ(S) = 1/6 exactly for the periodic Hann taper, ρ = 0
    # beyond one shift, so ν = 2K / (1 + 2 (1 - 1/K) / 36) (Percival & Walden 1993, Eq. 292b);
    # without overlap ν = 2K
    eta = gaussian_sea(1024, 8.0, 0.1, 2.0, seed=3)
    s = spectrum(eta, 8.0, segment_duration=64.0)
    k = s.segments
    assert k == (8192 - 256) // 256
    assert s.equivalent_degrees_of_freedom == pytest.approx(2 * k / (1 + 2 * (1 - 1 / k) / 36),
                                                            rel=1e-9)
    assert s.equivalent_degrees_of_freedom < 1.9 * k  # not 2K
    assert float(s.degrees_of_freedom[0]) == pytest.approx(s.equivalent_degrees_of_freedom / 2)
    s0 = spectrum(eta, 8.0, segment_duration=64.0, overlap=0.0)
    assert s0.equivalent_degrees_of_freedom == pytest.approx(2 * s0.segments, rel=1e-12)


def test_chi_squared_interval_covers_the_true_spectrum_in_90_percent_of_bins():
    # bins holding more than 1 % of the peak density, four 30-min records pooled (844 bins);
    # over 30 single records the coverage was 0.90 ± 0.024 (0.84 to 0.97), so the pooled
    # coverage must lie within 0.85 to 0.95
    covered = []
    for seed in range(4):
        eta = gaussian_sea(1800, 25.0, 0.1, 2.0, seed=10 + seed)
        s = spectrum(eta, 25.0, confidence=0.9)
        true = jonswap(s.frequency.values, 0.1, 2.0)
        band = true > 0.01 * true.max()
        inside = ((s.variance_density_lower.values <= true)
                  & (true <= s.variance_density_upper.values))
        covered.append(inside[band])
    coverage = np.concatenate(covered).mean()
    assert 0.85 <= coverage <= 0.95, coverage


def test_spectrum_keeps_the_other_dims_and_their_coordinates():
    fs = 10.0
    eta = np.stack([gaussian_sea(300, fs, h, 2.0, seed=4) for h in (0.05, 0.1, 0.2)])
    da = xr.DataArray(eta, dims=("probe", "time"),
                      coords={"probe": ["p1", "p2", "p3"], "x": ("probe", [0.0, 0.6, 0.9]),
                              "time": 5.0 + np.arange(eta.shape[1]) / fs})
    s = spectrum(da.transpose("time", "probe"))
    assert s.variance_density.dims == ("probe", "frequency")
    assert list(s.x.values) == [0.0, 0.6, 0.9] and s.attrs["sampling_rate"] == fs
    # each probe as its own record
    for i in range(3):
        one = spectrum(eta[i], fs)
        np.testing.assert_allclose(s.variance_density[i], one.variance_density, rtol=1e-12)
    assert s.variance_density.attrs["units"] == "m2 s"
    assert s.variance_density.attrs["standard_name"] == "sea_surface_wave_variance_spectral_density"


def test_spectrum_refuses_what_it_cannot_analyse():
    t = np.arange(1000) / 10.0
    with pytest.raises(ValueError, match="non-finite"):
        spectrum(np.where(t > 50, np.nan, 0.0), 10.0)
    with pytest.raises(ValueError, match="sampled uniformly"):
        spectrum(xr.DataArray(np.zeros(1000), dims="time", coords={"time": t**1.01}))
    with pytest.raises(ValueError, match="contradicts"):
        spectrum(xr.DataArray(np.zeros(1000), dims="time", coords={"time": t}), 20.0)
    with pytest.raises(ValueError, match="sampling_rate"):
        spectrum(np.zeros(1000))
    with pytest.raises(ValueError, match="segment_duration"):
        spectrum(np.zeros(1000), 10.0, segment_duration=200.0)


# --- spectral parameters ---------------------------------------------------------------------

def test_each_parameter_equals_its_definition_on_the_analytic_jonswap():
    # truth: numpy's trapezoid rule on the analytic spectrum, written out here; the code sums
    # S Δf over whole bins, which is the trapezoid rule plus half of each end bin
    f = np.linspace(0.0, 10.0, 20_001)
    df = f[1] - f[0]
    hm0, tp = 0.1, 2.0
    s = jonswap(f, hm0, tp)
    p = spectral_parameters(as_da(s, f))
    g = f > 0

    def integral(y):
        return np.trapezoid(y, f[g]) + 0.5 * df * (y[0] + y[-1])

    def m(n):
        return integral(s[g] * f[g] ** n)

    m_1, m0, m1, m2, m4 = m(-1), m(0), m(1), m(2), m(4)
    expected = {
        "m_minus1": m_1, "m0": m0, "m1": m1, "m2": m2, "m4": m4,
        "hm0": 4 * np.sqrt(m0), "tm01": m0 / m1, "tm02": np.sqrt(m0 / m2), "tm_10": m_1 / m0,
        "spectral_width": np.sqrt(1 - m2**2 / (m0 * m4)),
        "spectral_narrowness": np.sqrt(m0 * m2 / m1**2 - 1),
        "peakedness": 2 / m0**2 * integral(f[g] * s[g] ** 2),
        "tp_smoothed": integral(s[g] ** 4) / integral(f[g] * s[g] ** 4),
    }
    for name, value in expected.items():
        assert float(p[name]) == pytest.approx(value, rel=1e-10), name
    assert float(p.hm0) == pytest.approx(hm0, rel=1e-8)
    assert float(p.tp) == tp  # the peak lies on a bin (0.5 Hz)
    # a sanity bound besides the definition: Qp = 2 for Pierson-Moskowitz, higher for a
    # peaked JONSWAP (3.3 here)
    assert 2.7 < float(p.peakedness) < 4.2


def test_mean_periods_of_pierson_moskowitz_against_their_closed_forms():
    # S = A f^-5 exp(-B f^-4): m_n = (A/4) B^((n-4)/4) Γ((4-n)/4), so
    # Tm01 = B^(-1/4)/Γ(3/4), Tm02 = B^(-1/4)/sqrt(Γ(1/2)), Te = B^(-1/4) Γ(5/4)
    fp = 0.5
    b = 1.25 * fp**4
    f = np.linspace(0.0, 40.0, 400_001)
    s = np.zeros_like(f)
    s[1:] = f[1:] ** -5 * np.exp(-b * f[1:] ** -4)
    p = spectral_parameters(as_da(s, f))
    # truncation at 40 Hz misses (A/2) 40^-2 of m2, 2.0e-4 of it (1.0e-4 of Tm02), and
    # 1e-5 of m1; Δf = 1e-4 Hz resolves the low-frequency edge
    assert float(p.tm01) == pytest.approx(b**-0.25 / math.gamma(0.75), rel=2e-5)
    assert float(p.tm02) == pytest.approx(b**-0.25 / math.sqrt(math.gamma(0.5)), rel=1.2e-4)
    assert float(p.tm_10) == pytest.approx(b**-0.25 * math.gamma(1.25), rel=2e-5)
    assert float(p.m0) == pytest.approx(1 / (4 * b), rel=1e-6)
    # Goda's Qp: 2/m0² ∫ f S² df = 2 (A²/(16 B²)) / (A/(4B))² = 2 exactly
    assert float(p.peakedness) == pytest.approx(2.0, rel=1e-5)


def test_band_limits_the_moments_and_parabolic_peak_is_exact_for_a_parabola():
    f = np.linspace(0.0, 2.0, 201)  # Δf = 0.01 Hz
    s = np.clip(1.0 - ((f - 0.503) / 0.05) ** 2, 0.0, None)  # a parabola peaking off-bin
    p = spectral_parameters(as_da(s, f), method="parabolic")
    assert 1 / float(p.tp_smoothed) == pytest.approx(0.503, abs=1e-12)
    assert float(p.tp) == pytest.approx(1 / 0.50)
    assert p.attrs["tp_smoothed_method"] == "parabolic"
    # band: only the bins inside count, each with its full width
    pb = spectral_parameters(as_da(s, f), band=(0.5, 0.52))
    sel = (f >= 0.5 - 1e-12) & (f <= 0.52 + 1e-12)
    assert float(pb.m0) == pytest.approx(np.sum(s[sel]) * 0.01, rel=1e-12)
    assert pb.attrs["band"] == pytest.approx([0.5, 0.52])


def test_parameters_are_vectorised_over_other_dims():
    f = np.linspace(0.0, 3.0, 3001)
    hm0 = xr.DataArray([0.05, 0.1], dims="run")
    tp = xr.DataArray([1.5, 2.0, 2.5], dims="probe")
    s = xr.apply_ufunc(lambda h, t: jonswap(f, h, t), hm0, tp, output_core_dims=[["frequency"]],
                       vectorize=True).assign_coords(frequency=f)
    p = spectral_parameters(s, method="parabolic")
    assert p.hm0.dims == ("run", "probe")
    for i in range(2):
        for j in range(3):
            one = spectral_parameters(s.isel(run=i, probe=j), method="parabolic")
            for name in ("hm0", "tp", "tp_smoothed", "tm_10", "peakedness"):
                assert float(p[name][i, j]) == pytest.approx(float(one[name]), rel=1e-12)
    # the discrete peak: the bin nearest 1/Tp (Δf = 1 mHz)
    np.testing.assert_array_less(np.abs(1 / p.tp.values - 1 / tp.values), 0.5e-3 + 1e-12)
    assert p.tm01.attrs["standard_name"] == ("sea_surface_wave_mean_period_from_variance_"
                                             "spectral_density_first_frequency_moment")


def test_parameters_of_a_record_against_the_analytic_spectrum():
    # a 30-min Gaussian sea: Hm0 and the mean periods of the Welch estimate within sampling
    # error of the analytic ones (ν ≈ 28.5 per bin, ~300 independent bins in the band: 2 %
    # on Hm0, 1.5 % on the periods); Tp within one bin of 64-s segments (30 of 30 seeds,
    # |error| ≤ 1 bin) and the smoothed Tp within 1.5 bins (worst of 30 seeds: 1.23 bins, the
    # S⁴ centroid of the asymmetric peak lies above fp)
    hm0, tp = 0.1, 2.0
    fa = np.linspace(0.0, 12.5, 250_001)
    truth = spectral_parameters(as_da(jonswap(fa, hm0, tp), fa))
    for seed in range(3):
        eta = gaussian_sea(1800, 25.0, hm0, tp, seed=20 + seed)
        p = spectral_parameters(spectrum(eta, 25.0).variance_density)
        assert float(p.hm0) == pytest.approx(hm0, rel=0.04)
        for name in ("tm01", "tm02", "tm_10"):
            assert float(p[name]) == pytest.approx(float(truth[name]), rel=0.03), name
        s64 = spectrum(eta, 25.0, segment_duration=64.0)
        df = s64.frequency_resolution
        p64 = spectral_parameters(s64.variance_density)
        assert abs(1 / float(p64.tp) - 1 / tp) <= df * (1 + 1e-9)
        assert abs(1 / float(p64.tp_smoothed) - 1 / tp) <= 1.5 * df


def test_spectral_parameters_refuse_nan_and_unknown_method():
    f = np.linspace(0, 1, 11)
    with pytest.raises(ValueError, match="non-finite"):
        spectral_parameters(as_da(np.where(f > 0.5, np.nan, 1.0), f))
    with pytest.raises(ValueError, match="method"):
        spectral_parameters(as_da(np.ones(11), f), method="spline")
    with pytest.raises(ValueError, match="no frequency bin"):
        spectral_parameters(as_da(np.ones(11), f), band=(2.0, 3.0))


def test_against_mhkit_when_available():
    resource = pytest.importorskip("mhkit.wave.resource")
    pd = pytest.importorskip("pandas")
    f = np.linspace(0.01, 5.0, 5000)
    s = jonswap(f, 0.1, 2.0)
    p = spectral_parameters(as_da(s, f))
    spec = pd.Series(s, index=pd.Index(f, name="frequency"))
    # mhkit sums S Δf over the same bins with f > 0 (IEC TS 62600-101 Eq. 8)
    assert float(np.squeeze(resource.significant_wave_height(spec))) == pytest.approx(
        float(p.hm0), rel=1e-4)
    assert float(np.squeeze(resource.energy_period(spec))) == pytest.approx(float(p.tm_10),
                                                                            rel=1e-4)
    assert float(np.squeeze(resource.peak_period(spec))) == pytest.approx(float(p.tp),
                                                                          rel=1e-9)


# --- energy flux -----------------------------------------------------------------------------

def test_narrow_spectrum_flux_is_the_regular_wave_flux_of_hm0_over_root_two():
    f = np.linspace(0.0, 3.0, 30_001)
    for tp, depth in ((1.5, 0.825), (3.5, 0.825), (2.0, 0.3)):
        s = np.exp(-0.5 * ((f - 1 / tp) / 0.002) ** 2)
        hm0 = 0.08
        s *= hm0**2 / 16 / (s.sum() * (f[1] - f[0]))
        j = float(energy_flux(as_da(s, f), depth))
        regular = float(theory.energy_flux(hm0 / np.sqrt(2), tp, depth))
        # the group velocity varies over the ±3σ = ±0.006 Hz peak: second order, < 1e-4
        assert j == pytest.approx(regular, rel=1e-4), (tp, depth)


def test_deep_water_flux_is_rho_g2_hm0_squared_te_over_64_pi():
    f = np.linspace(0.0, 6.0, 60_001)
    s = jonswap(f, 0.1, 1.0)
    # in 20 m of water every frequency of the band (≥ 0.5 Hz) has kh ≥ 20: c_g = g/(4πf)
    # to 1e-15, so J = ρ g² m_-1/(4π) = ρ g² Hm0² Te/(64π) over the same band
    band = (0.5, 6.0)
    p = spectral_parameters(as_da(s, f), band=band)
    j = float(spectral_energy_flux(as_da(s, f), 20.0, band=band))
    expected = 1000.0 * G**2 / (64 * np.pi) * float(p.hm0) ** 2 * float(p.tm_10)
    assert j == pytest.approx(expected, rel=1e-12)
    # and ρ is a parameter, fresh water by default
    assert float(energy_flux(as_da(s, f), 20.0, rho=1025.0, band=band)) == pytest.approx(
        1.025 * j, rel=1e-12)


def test_energy_flux_broadcasts_depth():
    f = np.linspace(0.0, 3.0, 3001)
    s = as_da(jonswap(f, 0.1, 2.0), f)
    depth = xr.DataArray([0.3, 0.825], dims="run")
    j = energy_flux(s, depth)
    assert j.dims == ("run",) and j.name == "spectral_energy_flux"
    assert j.attrs["units"] == "W m-1"
    assert float(j[1]) == pytest.approx(float(energy_flux(s, 0.825)), rel=1e-12)
    with pytest.raises(ValueError, match="depth"):
        energy_flux(s, 0.0)


def test_outputs_carry_exactly_the_registry_attributes():
    from flumekit import conventions

    eta = xr.DataArray(gaussian_sea(300, 10.0, 0.1, 2.0, seed=6), dims="time",
                       coords={"time": np.arange(3000) / 10.0})
    eta.attrs = {"units": "m", "long_name": "surface elevation"}
    s = spectrum(eta)
    p = spectral_parameters(s.variance_density)
    j = energy_flux(s.variance_density, 0.5)
    for ds in (s, p, j.to_dataset()):
        conventions.check(ds)
        for name in ds.data_vars:
            assert ds[name].attrs == conventions.attrs(name), name
    assert s.frequency.attrs == conventions.attrs("frequency")


def test_standard_names_are_in_the_cf_table():
    # the table compliance-checker ships (the one the netCDF checks use), when installed
    resources = pytest.importorskip("importlib.resources")
    pytest.importorskip("compliance_checker")
    from flumekit import conventions

    table = (resources.files("compliance_checker") / "data"
             / "cf-standard-name-table.xml").read_text(encoding="utf-8")
    names = ["variance_density", "hm0", "tp", "tm01", "tm02", "tm_10", "spectral_energy_flux",
             "h1_3", "t1_3", "h1_10", "hmax", "tz"]
    for name in names:
        var = conventions.VARIABLES[name]
        assert f'<entry id="{var.standard_name}">' in table, name
