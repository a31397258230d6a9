"""The virtual flume's wave generator against its own analytic truth."""

import numpy as np
import pytest

from flumekit.signal import cycles, quasi_steady_window
from flumekit.synth.waves import (
    first_harmonic_amplitude,
    irregular_wave_field,
    jonswap,
    ramp_envelope,
    regular_wave_field,
)
from flumekit.waves import group_velocity, stokes2_coefficient, wavenumber
from flumekit.waves.stream_function import stream_function_wave

H = 0.825
FS = 25.0


def _harmonic(eta, t, f, n=1):
    """Complex amplitude of harmonic n of a record holding whole periods."""
    return 2 * np.mean(eta * np.exp(-2j * np.pi * n * f * t), axis=-1)


@pytest.mark.parametrize("period, height", [(2.0, 0.15), (3.5, 0.05), (3.5, 0.25), (4.0, 0.3)])
@pytest.mark.parametrize("theory", ["stokes2", "stream"])
def test_steady_incident_crest_to_trough_height_is_the_target(period, height, theory):
    # Stokes 2 includes trough-splitting waves (T = 3.5 s, H = 0.25 m: 4 B k a1 > 1)
    t = 300 * period + np.arange(int(10 * period * 200)) / 200.0  # fine sampling for extrema
    ds = regular_wave_field(t, [-5.0], period=period, height=height, depth=H, theory=theory)
    c = cycles(ds.eta_incident.values[0], t)
    np.testing.assert_allclose(c.height, height, rtol=2e-4)  # 200 Hz sampling of the extrema
    a1 = ds.attrs["incident_amplitude"]
    if theory == "stokes2":
        k = wavenumber(2 * np.pi / period, H)
        assert ds.attrs["bound_amplitude"] == pytest.approx(
            stokes2_coefficient(k, H) * k * a1**2)
        assert ds.attrs["wave_number"] == k
    else:  # the stream-function wave's harmonics down to 1e-4 of the first, its wavenumber
        w = stream_function_wave(period, height, H, current="stokes")
        e = w.elevation_coefficients
        kept = ds.attrs["harmonic_amplitudes"]
        np.testing.assert_array_equal(kept, e[:kept.size])
        assert np.all(np.abs(e[kept.size:]) <= 1e-4 * e[0]) and abs(e[kept.size - 1]) > 1e-4 * e[0]
        assert ds.attrs["wave_number"] == w.wavenumber
    amps = ds.attrs["harmonic_amplitudes"]
    assert amps[0] == a1 and amps[1] == ds.attrs["bound_amplitude"]
    for n in range(1, min(amps.size, 6) + 1):  # every harmonic of the record is the truth's
        zn = _harmonic(ds.eta_incident.values[0], t, 1 / period, n)
        assert abs(zn) == pytest.approx(amps[n - 1], rel=1e-8, abs=1e-12)


def test_stream_function_wave_travels_with_its_nonlinear_wavenumber():
    # harmonic n of the incident wave travels with n k, k the nonlinear wavenumber (3 % below
    # the linear one at T = 3.5 s, H = 0.25 m); the reflected wave with its own
    T = 3.5
    t = 300 * T + np.arange(int(10 * T * FS)) / FS
    ds = regular_wave_field(t, np.array([-4.0, -3.0]), period=T, height=0.25, depth=H,
                            reflection=0.3)
    k, k_r = ds.attrs["wave_number"], ds.attrs["reflected_wave_number"]
    assert k / ds.attrs["linear_wave_number"] == pytest.approx(0.968, abs=0.002)
    assert k < k_r < ds.attrs["linear_wave_number"]
    for n in (1, 2, 3):
        zi = _harmonic(ds.eta_incident.values, t, 1 / T, n)
        zr = _harmonic(ds.eta_reflected.values, t, 1 / T, n)
        assert np.angle(zi[1] / zi[0]) == pytest.approx(np.angle(np.exp(-1j * n * k)), abs=1e-9)
        assert np.angle(zr[1] / zr[0]) == pytest.approx(np.angle(np.exp(1j * n * k_r)), abs=1e-9)
    # Kr is the first-harmonic ratio exactly; the reflected harmonics are those of the
    # stream-function wave of height Kr H, scaled to that first harmonic
    z1 = _harmonic(ds.eta_reflected.values[0], t, 1 / T)
    assert abs(z1) == pytest.approx(0.3 * ds.attrs["incident_amplitude"], rel=1e-9)
    e = stream_function_wave(T, 0.3 * 0.25, H).elevation_coefficients
    z2 = _harmonic(ds.eta_reflected.values[0], t, 1 / T, 2)
    assert abs(z2) == pytest.approx(abs(z1) * e[1] / e[0], rel=1e-8)


def test_first_harmonic_amplitude_branches():
    k = wavenumber(2 * np.pi / 3.5, H)
    assert first_harmonic_amplitude(0.05, k, H, True) == 0.025  # 4 B k a < 1: H = 2 a
    assert first_harmonic_amplitude(0.25, k, H, False) == 0.125
    a = first_harmonic_amplitude(0.25, k, H, True)
    r = stokes2_coefficient(k, H) * k * a
    assert 4 * r > 1 and a * (1 + 2 * r + 1 / (8 * r)) == pytest.approx(0.25, rel=1e-12)


def test_incident_travels_towards_plus_x_with_the_phase_speed_and_reflected_back():
    T = 2.5
    t = 300 * T + np.arange(int(20 * T * FS)) / FS
    x = np.array([-4.0, -3.0])
    ds = regular_wave_field(t, x, period=T, height=0.1, depth=H, reflection=0.3,
                            reflection_phase=0.8, second_order=False)
    k = wavenumber(2 * np.pi / T, H)
    zi = _harmonic(ds.eta_incident.values, t, 1 / T)
    zr = _harmonic(ds.eta_reflected.values, t, 1 / T)
    # phase falls by k Δx along +x for the incident wave, rises for the reflected one
    assert np.angle(zi[1] / zi[0]) == pytest.approx(-k * 1.0, abs=1e-9)
    assert np.angle(zr[1] / zr[0]) == pytest.approx(k * 1.0, abs=1e-9)
    assert abs(zr[0]) / abs(zi[0]) == pytest.approx(0.3, rel=1e-9)
    # at the reflector the reflected wave is Kr × incident shifted by the reflection phase
    at = regular_wave_field(t, [0.0], period=T, height=0.1, depth=H, reflection=0.3,
                            reflection_phase=0.8, second_order=False)
    ratio = (_harmonic(at.eta_reflected.values[0], t, 1 / T)
             / _harmonic(at.eta_incident.values[0], t, 1 / T))
    assert ratio == pytest.approx(0.3 * np.exp(0.8j), abs=1e-9)


def test_reflected_bound_harmonic_is_kr_squared():
    T, kr = 3.0, 0.4
    t = 300 * T + np.arange(int(10 * T * FS)) / FS
    ds = regular_wave_field(t, [-2.0], period=T, height=0.15, depth=H, reflection=kr,
                            theory="stokes2")
    z2 = _harmonic(ds.eta_reflected.values[0], t, 1 / T, 2)
    assert abs(z2) == pytest.approx(kr**2 * ds.attrs["bound_amplitude"], rel=1e-9)


def test_envelope_arrives_with_the_group_velocity():
    T = 3.0
    cg = group_velocity(T, H)
    t = np.arange(0, 40 * T, 1 / FS)
    ds = regular_wave_field(t, [-20.0], period=T, height=0.1, depth=H, x_wavemaker=-32.7)
    arrival = 12.7 / cg
    eta = ds.eta_incident.values[0]
    assert np.all(eta[t <= arrival] == 0) and np.any(eta[t > arrival + T] != 0)
    assert np.all(ds.eta_reflected.values[0][t <= (32.7 + 20.0) / cg] == 0)


def test_ramp_envelope_shape():
    # the paddle's linear ramp: 0 before the start, τ / ramp_time, then exactly 1
    tau = np.array([-1.0, 0.0, 0.25, 0.98, 1.0, 50.0])
    np.testing.assert_allclose(ramp_envelope(tau, 2.0), [0, 0, 0.125, 0.49, 0.5, 1],
                               rtol=1e-12)
    np.testing.assert_allclose(ramp_envelope(2.0 * tau, 2.0), [0, 0, 0.25, 0.98, 1, 1],
                               rtol=1e-12)


@pytest.mark.parametrize("period", [2.5, 3.5, 4.0])
def test_quasi_steady_after_about_35_waves_at_the_flap(period):
    # Brito et al. 2020, §2.5: quasi-steady (2 % criterion) from t/T ≈ 35
    t = np.arange(0, 100 * period, 1 / FS)
    ds = regular_wave_field(t, [0.0], period=period, height=0.2, depth=H)
    w = quasi_steady_window(ds.eta.values[0], t)
    assert 30 <= w.start / period <= 40


def test_regular_field_input_checks():
    t = np.arange(0, 10, 0.04)
    with pytest.raises(ValueError, match="between the wavemaker"):
        regular_wave_field(t, [1.0], period=2.0, height=0.1, depth=H)
    with pytest.raises(ValueError, match="reflection"):
        regular_wave_field(t, [-1.0], period=2.0, height=0.1, depth=H, reflection=1.5)
    with pytest.raises(ValueError, match="period"):
        regular_wave_field(t, [-1.0], period=0.0, height=0.1, depth=H)


def test_irregular_field_truth_and_determinism():
    t = np.arange(0, 300, 1 / FS)
    x = np.array([-5.0, -4.0])
    a = irregular_wave_field(t, x, hm0=0.1, peak_period=2.0, depth=H, reflection=0.3, rng=4)
    b = irregular_wave_field(t, x, hm0=0.1, peak_period=2.0, depth=H, reflection=0.3,
                             rng=np.random.default_rng(4))
    c = irregular_wave_field(t, x, hm0=0.1, peak_period=2.0, depth=H, reflection=0.3, rng=5)
    np.testing.assert_array_equal(a.eta.values, b.eta.values)
    assert not np.allclose(a.eta.values, c.eta.values)
    # Hm0 = 4 sqrt(variance) exactly (whole periods of every component), reflected Kr² of it
    np.testing.assert_allclose(4 * a.eta_incident.std(axis=1), 0.1, rtol=1e-12)
    np.testing.assert_allclose(a.eta_reflected.var(axis=1) / a.eta_incident.var(axis=1), 0.09,
                               rtol=1e-12)
    with pytest.raises(ValueError, match="uniformly"):
        irregular_wave_field(t**1.01, x, hm0=0.1, peak_period=2.0, depth=H)


def test_jonswap_peak_and_variance():
    f = np.linspace(0, 2, 4001)
    s = jonswap(f, 0.2, 2.5)
    assert f[np.argmax(s)] == pytest.approx(0.4, abs=1e-3)
    assert s.sum() * (f[1] - f[0]) == pytest.approx(0.2**2 / 16, rel=1e-12)
    assert s[0] == 0
