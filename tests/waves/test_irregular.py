"""The irregular-run analysis against linear random-phase records of known incident spectrum
and reflection function: three probes, a wavemaker ramp, probe noise."""

import numpy as np
import pytest
import xarray as xr

from flumekit.waves import LowFrequencyWarning, analyse_irregular_run, wavenumber

DEPTH = 0.825
RATE = 25.0
X = np.array([-3.0, -2.55, -2.0])  # a Mansard-Funke-like spacing for fp = 0.5 Hz


def jonswap(f, hm0, tp, gamma=3.3):
    """JONSWAP variance density [m2 s] scaled to Hm0 (written here, not the package's)."""
    fp = 1.0 / tp
    sigma = np.where(f <= fp, 0.07, 0.09)
    shape = (f ** -5 * np.exp(-1.25 * (fp / f) ** 4)
             * gamma ** np.exp(-((f - fp) ** 2) / (2 * sigma ** 2 * fp ** 2)))
    df = f[1] - f[0]
    return shape * (hm0 / 4) ** 2 / (shape.sum() * df)


def kr_truth(f):
    """A smooth reflection function: 0.35 at 0.3 Hz falling to 0.1 at 1.5 Hz."""
    return np.clip(0.35 - 0.25 * (f - 0.3) / 1.2, 0.1, 0.35)


def record(seed=1, duration=900.0, hm0=0.10, tp=2.0, ramp=30.0, noise=0.0005, seiche=0.0):
    rng = np.random.default_rng(seed)
    n = int(duration * RATE)
    t = np.arange(n) / RATE
    f = np.fft.rfftfreq(n, 1 / RATE)[1:]
    s = np.where(f > 0.2, jonswap(f, hm0, tp), 0.0)
    a = np.sqrt(2 * s * (f[1] - f[0]))
    k = wavenumber(2 * np.pi * f, DEPTH)
    phase = rng.uniform(0, 2 * np.pi, f.size)
    psi = rng.uniform(0, 2 * np.pi, f.size)  # the reflection's phase at x = 0
    eta = []
    for x in X:
        spec = np.zeros(n // 2 + 1, complex)
        spec[1:] = (a * np.exp(1j * (phase - k * x))
                    + kr_truth(f) * a * np.exp(1j * (phase + psi + k * x)))
        eta.append(np.fft.irfft(spec, n) * n / 2)
    eta = np.array(eta) * np.clip(t / ramp, 0, 1)
    eta += seiche * np.sin(2 * np.pi * 0.04 * t) + noise * rng.standard_normal(eta.shape)
    m0 = float(np.sum(s * (f[1] - f[0])))
    truth = {"hm0": 4 * np.sqrt(m0), "te": float(np.sum(s / f) / np.sum(s)),
             "tp": float(1 / f[np.argmax(s)]),
             "kr": float(np.sqrt(np.sum(kr_truth(f) ** 2 * s) / np.sum(s)))}
    da = xr.DataArray(eta, dims=("probe", "time"),
                      coords={"probe": ["WP1", "WP2", "WP3"], "x": ("probe", X), "time": t})
    return da, truth


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_sea_state_and_reflection_against_the_truth(seed):
    """Hm0 and Te within 2 %, Tp within 5 %, bulk Kr within 0.02, Kr(f) within 0.05 over the
    bands holding 90 % of the incident energy (the acceptance of the irregular-seas issue)."""
    eta, truth = record(seed)
    ds = analyse_irregular_run(eta, DEPTH)
    assert float(ds.hm0) == pytest.approx(truth["hm0"], rel=0.02)
    assert float(ds.te) == pytest.approx(truth["te"], rel=0.02)
    assert float(ds.tp) == pytest.approx(truth["tp"], rel=0.05)
    assert float(ds.reflection_coefficient) == pytest.approx(truth["kr"], abs=0.02)
    s = ds.spectrum_incident.values
    energy = np.cumsum(np.nan_to_num(s)) / np.nansum(s)
    held = (energy > 0.05) & (energy < 0.95)
    err = np.abs(ds.reflection_coefficient_spectrum.values[held]
                 - kr_truth(ds.frequency.values[held]))
    assert held.sum() >= 5 and err.max() < 0.05
    # the ramp and the reflection's travel to the farthest probe are left out
    assert 30.0 < float(ds.analysis_start) < 60.0
    assert float(ds.analysis_end) == pytest.approx(900.0 - 1 / RATE)
    assert ds.attrs["span"] == "start detected, end detected"
    assert float(ds.low_frequency_energy_fraction) < 0.01


def test_incident_wave_statistics_at_the_device():
    """Zero up-crossing heights of the separated incident wave: H1/3 and Hmax against the
    Rayleigh expectations for the number of waves of a JONSWAP sea."""
    eta, truth = record(4)
    ds = analyse_irregular_run(eta, DEPTH)
    n = int(ds.number_of_waves)
    span = float(ds.analysis_end) - float(ds.analysis_start)
    assert n == pytest.approx(span / float(ds.tz), rel=0.01)
    assert 0.90 < float(ds.h1_3) / float(ds.hm0) < 1.0
    # the most probable maximum of n Rayleigh heights: sqrt(ln n / 2) Hm0
    assert 0.8 < float(ds.hmax) / (np.sqrt(np.log(n) / 2) * float(ds.hm0)) < 1.4
    assert float(ds.energy_flux) > 0


def test_long_waves_are_flagged():
    """A seiche at 0.04 Hz holding a quarter of the variance: flagged (the target peak period
    keeps the analysis on the sea state, whose own peak the seiche would hide)."""
    eta, _ = record(5, seiche=0.02)
    with pytest.warns(LowFrequencyWarning, match="below fp/2"):
        ds = analyse_irregular_run(eta, DEPTH, peak_period=2.0)
    assert float(ds.low_frequency_energy_fraction) > 0.05
    assert ds.low_frequency_energy_fraction.attrs["flag"] == 1


def test_declared_span_and_gauge_weights():
    """A declared span is used as given; down-weighting a noisy probe brings its noise out of
    the separated waves."""
    eta, truth = record(6)
    noisy = eta.copy(data=eta.values + np.array([0, 0.01, 0])[:, None]
                     * np.random.default_rng(0).standard_normal(eta.shape))
    equal = analyse_irregular_run(noisy, DEPTH, span=(100.0, 800.0))
    weighted = analyse_irregular_run(noisy, DEPTH, span=(100.0, 800.0),
                                     gauge_weights=[1.0, 0.01, 1.0])
    assert equal.attrs["span"] == "start given, end given"
    assert float(weighted.analysis_start) == pytest.approx(100.0, abs=0.05)
    assert (abs(float(weighted.hm0) - truth["hm0"])
            < abs(float(equal.hm0) - truth["hm0"]))


def test_declared_start_with_a_detected_end():
    eta, _ = record(8)
    ds = analyse_irregular_run(eta, DEPTH, span=(120.0, None))
    assert float(ds.analysis_start) == pytest.approx(120.0)
    assert float(ds.analysis_end) == pytest.approx(900.0 - 1 / RATE)
    assert ds.attrs["span"] == "start given, end detected"


def test_too_short_a_record_is_an_error():
    eta, _ = record(7, duration=60.0, ramp=5.0)
    with pytest.raises(ValueError, match="fewer than 20 peak periods"):
        analyse_irregular_run(eta, DEPTH)


def test_active_span_example_holds():
    """The example of active_span's docstring holds as written: a unit sine ramped over 50 s,
    40 s windows; the first window whose mean variance reaches a quarter of the established
    0.5 m2 ends at 42.3 s, before the ramp's end (the threshold allows a wave group's lull)."""
    import doctest

    from flumekit.waves import irregular

    test, = doctest.DocTestFinder().find(irregular.active_span, "active_span",
                                         globs=dict(vars(irregular)))
    result = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS, verbose=False).run(test)
    assert result.attempted == 5 and result.failed == 0
