"""The comparison's pieces: coefficient container, interpolation, spin-up, PTO damping."""

import numpy as np
import pytest
import xarray as xr

from flumekit.flap import comparison as cmp
from flumekit.flap.renzi_dias import model as rd
from flumekit.hydro.coefficients import split_complex
from flumekit.io.netcdf import read_dataset
from flumekit.stages import models as stage


def test_the_stage_writes_the_one_channel_container(hydro):
    """The virtual flume and the stage share rd.channel_container: the file holds it exactly."""
    direct = split_complex(rd.channel_container(0.825, 1.31, 0.10, 1.5, 605.0))
    for name in ("added_inertia", "radiation_damping", "excitation_torque_real",
                 "excitation_torque_imag", "added_inertia_infinite"):
        np.testing.assert_array_equal(hydro[name].values, direct[name].values)


def test_radiation_model_fitted_once_in_the_container(hydro):
    """models/hydro stores the simulator's state-space model; every run reads it back."""
    from flumekit.hydro.radiation import impulse_response, state_space_from_dataset

    ss = state_space_from_dataset(hydro)
    assert ss.order >= 2 and ss.fit_error_time <= 0.01
    irf = impulse_response(_container(hydro), 30.0, 0.01)
    k = irf.values
    assert np.sqrt(np.mean((ss.impulse(irf["lag"].values) - k) ** 2) / np.mean(k**2)) < 0.011


def _container(hydro):
    from flumekit.hydro.coefficients import merge_complex

    return merge_complex(hydro.drop_dims("radiation_mode"))


@pytest.mark.parametrize("period", [2.0, 2.6, 3.5, 4.0])
def test_container_at_a_period_matches_the_model_there(hydro, period):
    """Cubic interpolation over the 400-point grid: 1e-4 relative on every coefficient."""
    at = cmp.coefficients_at(hydro, period)
    direct = rd.coefficients([period], 0.825, 1.31, 0.10, channel_width=1.5)
    for name in ("added_inertia", "radiation_damping"):
        np.testing.assert_allclose(at[name], direct[name], rtol=1e-4)
    np.testing.assert_allclose(np.abs(at.excitation_torque_real + 1j * at.excitation_torque_imag),
                               np.abs(rd.excitation(direct)), rtol=1e-4)


def test_periodic_extension_continues_the_steady_wave():
    t = np.arange(0, 100, 0.04)
    eta = np.where((t > 30) & (t < 80), np.sin(2 * np.pi * t / 2.5), np.nan)
    ext = cmp.periodic_extension(xr.DataArray(eta, dims="time", coords={"time": t}), 2.5,
                                   before=10, after=4)
    tt = ext.time.values
    assert tt[0] == pytest.approx(30.04 - 25.0, abs=0.05) and tt[-1] > 79.9 + 9.9
    wave = np.sin(2 * np.pi * tt / 2.5)
    steady = tt > 30  # the window and the unramped continuation after it: the same sine
    np.testing.assert_allclose(ext.values[steady], wave[steady], atol=2e-3)
    # before it: the same sine under a half-cosine ramp from rest
    ramp = 0.5 * (1 - np.cos(np.pi * (tt[~steady] - tt[0]) / (30.04 - tt[0])))
    np.testing.assert_allclose(ext.values[~steady], ramp * wave[~steady], atol=2e-3)


def test_energy_equivalent_damping_reproduces_the_mean_power():
    t = np.arange(0, 200, 0.01)
    theta_dot = 0.3 * np.cos(2 * np.pi * t / 3.0)
    nu = 400.0
    flap = xr.Dataset({"theta_dot": ("time", theta_dot),
                       "mean_power": nu * np.mean(theta_dot[(t >= 50) & (t <= 150)] ** 2),
                       "steady_start": 50.0, "steady_end": 150.0}, coords={"time": t})
    assert cmp.energy_equivalent_damping(flap) == pytest.approx(nu, rel=1e-12)


def test_bem_container(tmp_path, geometry):
    pytest.importorskip("capytaine")
    out = tmp_path / "bem.nc"
    params = {**geometry, "coefficients": "bem", "bem_omega_min": 1.5, "bem_omega_max": 4.0,
              "bem_n_omega": 6, "bem_panel_size": 0.1}
    stage.hydro({}, {"dataset": out}, params)
    h = read_dataset(out)
    assert h.sizes["angular_frequency"] == 6 and np.all(h.radiation_damping > 0)
    at = cmp.coefficients_at(h, 3.0)
    assert at.added_inertia.item() > 0


@pytest.mark.parametrize("period", [2.5, 3.5])
def test_optimal_pto_damping_maximises_the_linear_power(hydro, period):
    """RD12 Eq. (2.40): P(ν_pto) = ½ ν_pto ω² |X A|² / [R² + ω²(ν + ν_pto)²] is largest at
    ν_pto² = R²/ω² + ν² (dP/dν_pto = 0). Checked against the Eq. (A1) power on a 0.1 % grid of
    ν_pto: the grid's best is the closed form's neighbour, within one step (0.1 %)."""
    from flumekit.hydro.response import optimal_pto_damping, response

    at = cmp.coefficients_at(hydro, period)
    nu_opt = float(optimal_pto_damping(at, 14.74, 605.0).values[0])
    grid = nu_opt * np.exp(np.linspace(-0.5, 0.5, 1001))  # steps of 0.1 %
    power = np.array([float(response(at, 0.125, 14.74, 605.0, nu).mean_power.values[0])
                      for nu in grid])
    assert grid[np.argmax(power)] == pytest.approx(nu_opt, rel=1.1e-3)
    assert power[np.argmax(power)] == pytest.approx(
        float(response(at, 0.125, 14.74, 605.0, nu_opt).mean_power.values[0]), rel=1e-6)


def _run_datasets(period=3.5, height=0.25, nu=400.0):
    t = np.arange(0, 200, 0.01)
    theta_dot = 0.3 * np.cos(2 * np.pi * t / period)
    flap = xr.Dataset({"theta_dot": ("time", theta_dot),
                       "mean_power": nu * np.mean(theta_dot[(t >= 50) & (t <= 150)] ** 2),
                       "steady_start": 50.0, "steady_end": 150.0},
                      coords={"time": t, "phase": np.arange(100) / 100})
    waves = xr.Dataset({"measured_period": period, "incident_height": height})
    return flap, waves


@pytest.mark.parametrize("method", ["energy_equivalent", "optimal"])
def test_linear_model_pto_damping_method(hydro, method):
    """The linear model uses the chosen ν_pto, records how, and its power is ν_pto ω² Θ² / 2."""
    from flumekit.hydro.response import optimal_pto_damping

    flap, waves = _run_datasets()
    out, extra = cmp.linear_model(flap, waves, hydro, 14.74, 605.0, pto_damping=method)
    nu = float(extra["pto_damping"])
    expected = (400.0 if method == "energy_equivalent" else
                float(optimal_pto_damping(cmp.coefficients_at(hydro, 3.5), 14.74, 605.0)[0]))
    assert nu == pytest.approx(expected, rel=1e-9)
    assert extra["pto_damping"].attrs["method"] == method
    omega = 2 * np.pi / 3.5
    assert out["mean_power"] == pytest.approx(0.5 * nu * omega**2 * out["theta_amplitude"]**2,
                                              rel=1e-9)
    with pytest.raises(ValueError, match="linear_pto_damping"):
        cmp.linear_model(flap, waves, hydro, 14.74, 605.0, pto_damping="Lorentz")
