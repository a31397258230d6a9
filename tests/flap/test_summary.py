"""The one flap summary, shared by the measured run and the simulator, against a known motion."""

import numpy as np
import pytest
import xarray as xr

from flumekit.flap.power import incident_power
from flumekit.flap.summary import steady_window, summarise_run, summary

T, AMP, DEPTH, WIDTH, H = 2.5, 0.2, 0.825, 1.31, 0.2


def _run():
    t = np.arange(0, 40 * T, 0.01)
    ramp = np.clip(t / (5 * T), 0, 1)
    theta = AMP * ramp * np.sin(2 * np.pi * t / T)
    theta_dot = np.gradient(theta, t)
    power = 300.0 * theta_dot**2  # a linear damper of 300 N m s
    torque = 500.0 * ramp * np.sin(2 * np.pi * t / T + 0.3)
    return xr.Dataset({"theta": ("time", theta), "theta_dot": ("time", theta_dot),
                       "power": ("time", power), "torque_hydrodynamic": ("time", torque)},
                      coords={"time": t})


def test_summary_of_a_known_motion():
    """Amplitudes to 1e-3 (100 phase points on a sine), mean power of ν (ω a)² / 2 to 1e-3,
    C_f = W̄ / W_I exactly, the phase mean of θ is the sine from its up-crossing."""
    sim = _run()
    s = summarise_run(sim, period=T, incident_height=H, depth=DEPTH, flap_width=WIDTH)
    assert float(s.theta_amplitude) == pytest.approx(AMP, rel=1e-3)
    assert float(s.torque_amplitude) == pytest.approx(500.0, rel=1e-3)
    mean_power = 300.0 * (2 * np.pi / T * AMP) ** 2 / 2
    assert float(s.mean_power) == pytest.approx(mean_power, rel=1e-3)
    w_i = float(incident_power(H, T, DEPTH, WIDTH))
    assert float(s.capture_factor) == float(s.mean_power) / w_i
    np.testing.assert_allclose(s.theta_phase_mean, AMP * np.sin(2 * np.pi * s.phase),
                               atol=2e-3 * AMP)
    assert float(s.steady_start) >= 5 * T  # not before the end of the ramp


def test_no_incident_wave_is_an_error_for_both_callers():
    """W_I ≤ 0 (incident height 0 or NaN): an error, measured or simulated, never a silent
    NaN or inf capture factor."""
    sim = _run()
    t = sim.time.values
    win = steady_window(sim.theta.values, t, T)
    series = {n: sim[n].values for n in sim.data_vars}
    for h in (0.0, -0.1, np.nan):
        with pytest.raises(ValueError, match="incident height"):
            summary(t, series, win, period=T, incident_height=h, depth=DEPTH, flap_width=WIDTH)
        with pytest.raises(ValueError, match="incident height"):
            summarise_run(sim, period=T, incident_height=h, depth=DEPTH, flap_width=WIDTH)
