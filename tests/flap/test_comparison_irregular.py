"""The comparison of an irregular run: the spectral sum of the linear model against the
regular-wave model and a time-domain linear flap, the mirrored extension, the simulator."""

import numpy as np
import pytest
import xarray as xr

from flumekit.flap import comparison as cmp
from flumekit.hydro.response import response
from flumekit.waves.theory import G, group_velocity

#: the default flap's inertia [kg m2], buoyancy stiffness [N m rad-1] and the depth [m] of the
#: ``hydro`` fixture (tests/flap/conftest.py)
INERTIA, C, DEPTH = 14.74, 605.0, 0.825


def _spectrum(f, s):
    return xr.DataArray(s, dims="frequency", coords={"frequency": f}, name="spectrum_incident")


@pytest.mark.parametrize("f0, a, nu", [(0.3, 0.05, 300.0), (0.45, 0.02, 80.0)])
def test_single_frequency_spectrum_is_the_regular_wave_model(hydro, f0, a, nu):
    f = np.arange(1, 201) * 0.005
    s = np.where(np.isclose(f, f0), a**2 / 2 / 0.005, 0.0)  # one bin holding a^2 / 2
    out = cmp.spectral_response(hydro, _spectrum(f, s), INERTIA, C, nu)
    reg = response(cmp.coefficients_at(hydro, 1 / f0), a, INERTIA, C, nu).isel(period=0)
    assert out["mean_power"] == pytest.approx(float(reg.mean_power), rel=1e-12)
    # a sine's significant amplitude 2 sqrt(m0) is sqrt(2) times its amplitude
    assert out["theta_significant_amplitude"] == pytest.approx(
        np.sqrt(2) * float(reg.theta_amplitude), rel=1e-12)
    assert out["torque_significant_amplitude"] == pytest.approx(
        np.sqrt(2) * float(reg.torque_amplitude), rel=1e-12)
    assert out["variance_outside"] == 0.0


def test_frequencies_outside_the_coefficients_are_left_out_and_said(hydro):
    f = np.array([0.01, 0.3, 0.6])  # 0.01 Hz = 0.063 rad/s is below the grid's 0.4 rad/s
    out = cmp.spectral_response(hydro, _spectrum(f, np.array([1.0, 1.0, 2.0]) * 1e-3), INERTIA, C,
                                100.0)
    # the bins reach halfway to their neighbours: widths 0.29, 0.295, 0.3 Hz
    assert out["variance_outside"] == pytest.approx(0.29 / (0.29 + 0.295 + 0.6), rel=1e-12)
    assert out["nan_bins"] == 0
    # a bin masked by the separation (NaN) is empty, and counted
    masked = cmp.spectral_response(hydro, _spectrum(f, np.array([1.0, np.nan, 2.0]) * 1e-3),
                                   INERTIA, C, 100.0)
    assert masked["nan_bins"] == 1 and masked["mean_power"] < out["mean_power"]


@pytest.fixture(scope="module")
def linear_flap(hydro):
    """A flap that is exactly the linear model (nu = 250 N m s) in a 20-component sea over a
    400 s span (whole cycles), its waves product, and its truth."""
    nu, span, start = 250.0, 400.0, 50.0
    rng = np.random.default_rng(5)
    k = np.arange(100, 281, 9)  # 0.25-0.70 Hz on the span's frequency grid k / span
    f = k / span
    a = 0.015 * np.exp(-(((f - 0.4) / 0.12) ** 2))  # component amplitudes [m]
    ph = rng.uniform(0, 2 * np.pi, k.size)
    r = response(cmp.coefficients_at(hydro, 1 / f), 1.0, INERTIA, C, nu)
    theta_c = (r.theta_real.values + 1j * r.theta_imag.values) * a  # Θ_j, e^{-iωt} convention
    t = np.arange(0, start + span + 30.0, 0.04)
    w = 2 * np.pi * f[:, None]
    eta = (a[:, None] * np.cos(w * t - ph[:, None])).sum(0)  # Re(a e^{-i(ωt - φ)})
    e = np.exp(-1j * (w * t - ph[:, None]))
    theta = np.real((theta_c[:, None] * e).sum(0))
    theta_dot = np.real((-1j * w * theta_c[:, None] * e).sum(0))
    power = float(np.sum(0.5 * nu * (2 * np.pi * f) ** 2 * np.abs(theta_c) ** 2))
    flux = float(np.sum(1000.0 * G * a**2 / 2 * group_velocity(1 / f, DEPTH)))
    fg = np.arange(1, 400) / span  # the spectrum on the span's grid: a_j^2 / 2 = S df
    s = np.zeros_like(fg)
    s[k - 1] = a**2 / 2 * span
    T = ("time",)
    in_span = (t >= start) & (t <= start + span)
    flap = xr.Dataset({"theta": (T, theta), "theta_dot": (T, theta_dot),
                       "mean_power": power, "analysis_start": start,
                       "analysis_end": start + span, "capture_width": power / flux,
                       "capture_width_ratio": power / flux / 1.31,
                       "theta_significant_amplitude": 2 * np.std(theta[in_span]),
                       "torque_significant_amplitude": 1.0,
                       "pressure_loss_coefficient": 2e5, "fluid_inertia": 500.0},
                      coords={"time": t})
    waves = xr.Dataset({"eta_incident": (T, eta), "energy_flux": flux, "te": 2.5,
                        "spectrum_incident": ("frequency", s)}, coords={"time": t,
                                                                         "frequency": fg})
    return flap, waves, nu, power


def test_energy_equivalent_linear_model_recovers_a_linear_flap(hydro, linear_flap):
    flap, waves, nu, power = linear_flap
    # mean(theta_dot^2) over the span of whole cycles is sum w^2 |Theta|^2 / 2: nu exactly
    # (to the sampling of the span's ends, 1e-4)
    assert cmp.span_equivalent_damping(flap) == pytest.approx(nu, rel=1e-3)
    out, extra = cmp.linear_model_irregular(flap, waves, hydro, INERTIA, C)
    # the spectral sum against the time-domain flap: within 0.2 % (measured 1e-5 on the power,
    # 3e-5 on the significant amplitude; the cubic interpolation of the coefficients)
    assert out["mean_power"] == pytest.approx(power, rel=2e-3)
    assert out["capture_width_ratio"] == pytest.approx(float(flap.capture_width_ratio),
                                                       rel=2e-3)
    assert out["theta_significant_amplitude"] == pytest.approx(
        float(flap.theta_significant_amplitude), rel=2e-3)
    assert float(extra.pto_damping) == pytest.approx(nu, rel=1e-3)


def test_optimal_damping_maximises_the_spectral_power(hydro, linear_flap):
    flap, waves, nu, _ = linear_flap
    out, extra = cmp.linear_model_irregular(flap, waves, hydro, INERTIA, C, "optimal")
    best = float(extra.pto_damping)
    spec = waves.spectrum_incident
    for other in (0.8 * best, 1.25 * best, nu):
        assert out["mean_power"] >= cmp.spectral_response(hydro, spec, INERTIA, C,
                                                          other)["mean_power"]


def test_mirrored_extension():
    t = np.arange(0, 50, 0.1)
    v = np.where(t >= 10, np.sin(t) + 0.3 * np.cos(2.7 * t), np.nan)
    ext = cmp.mirrored_extension(xr.DataArray(v, dims="time", coords={"time": t}), 5.0, 3.0)
    tt, e = ext.time.values, ext.values
    assert np.allclose(np.diff(tt), 0.1) and tt[0] == pytest.approx(5.0) and tt[-1] == \
        pytest.approx(52.9)
    ok = np.isfinite(v)
    # the record unchanged, its mirror after it, the ramped mirror before it
    np.testing.assert_array_equal(e[(tt >= 10 - 1e-9) & (tt <= 49.9 + 1e-9)], v[ok])
    after = tt > 49.95
    np.testing.assert_allclose(e[after], np.interp(2 * 49.9 - tt[after], t[ok], v[ok]))
    before = tt < 9.95
    mirror = np.interp(2 * 10.0 - tt[before], t[ok], v[ok])
    assert np.all(np.abs(e[before]) <= np.abs(mirror) + 1e-12) and e[before][0] == 0.0


def test_the_simulator_beside_the_models(hydro, linear_flap, campaign):
    flap, waves, _, _ = linear_flap
    assert (campaign.flap.inertia, campaign.flap.width) == (INERTIA, 1.31)
    ds = cmp.compare_irregular_run(flap, waves, hydro, flap_params=campaign.flap,
                                   pto=campaign.pto, spin_up=40.0)
    assert list(ds.source.values) == ["experiment", "analytical", "simulator"]
    sim = ds.sel(source="simulator")
    # what the simulator absorbs is bounded by the channel: CWR < b / (2 w) = 0.573 (RD13a)
    assert 0 < float(sim.capture_width_ratio) < 1.5 / (2 * 1.31)
    assert float(sim.capture_width) == pytest.approx(float(sim.mean_power / ds.energy_flux),
                                                     rel=1e-12)
    assert np.isfinite(float(ds.theta_relative_rms_difference))
    for name in cmp.IRREGULAR_SCALARS:
        assert "units" in ds[name].attrs
    # the scalar coordinates of a regular run's comparison (the summary stacks both kinds)
    assert float(ds.incident_power) == pytest.approx(float(ds.energy_flux) * 1.31, rel=1e-12)
    assert np.isnan(float(ds.incident_height)) and np.isnan(float(ds.measured_period))
    # the experiment's row is the flap product's
    assert float(ds.mean_power.sel(source="experiment")) == float(flap.mean_power)
