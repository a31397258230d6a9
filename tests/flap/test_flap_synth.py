"""The virtual flume's flap channels against analytic truths."""

import numpy as np
import pytest
from scipy.integrate import quad

from flumekit import conventions
from flumekit.flap.encoder import wire_length
from flumekit.synth.flap import (FlapTruth, excitation_coefficient, flap_motion,
                                 radiation_damping)
from flumekit.waves.theory import group_velocity, wavenumber

H_DEPTH, C_HINGE, WIDTH = 0.825, 0.10, 1.31


@pytest.mark.parametrize("period", [1.0, 2.0, 3.5, 8.0])
def test_excitation_is_the_pressure_integral(period):
    # independent truth: twice the incident dynamic pressure over the wetted flap, by quadrature
    omega = 2 * np.pi / period
    k = float(wavenumber(omega, H_DEPTH))
    integral, _ = quad(lambda s: s * np.cosh(k * (s + C_HINGE)) / np.cosh(k * H_DEPTH),
                       0.0, H_DEPTH - C_HINGE, epsabs=0, epsrel=1e-13)
    expected = 2 * 1000.0 * 9.81 * WIDTH * integral
    got = excitation_coefficient(np.array([omega]), H_DEPTH, C_HINGE, WIDTH)[0]
    assert got == pytest.approx(expected, rel=1e-10)
    # Haskind: nu = X^2 / (2 rho g c_g w)
    nu = radiation_damping(np.array([omega]), H_DEPTH, C_HINGE, WIDTH)[0]
    assert nu == pytest.approx(expected**2 / (2 * 9810.0 * float(group_velocity(period, H_DEPTH)) * WIDTH),
                               rel=1e-10)


def test_excitation_limits():
    # long waves: rho g w (h - c)^2, continuous from omega = 0; short waves: no overflow
    x = excitation_coefficient(np.array([0.0, 1e-4, 300.0]), H_DEPTH, C_HINGE, WIDTH)
    assert x[0] == pytest.approx(9810.0 * WIDTH * (H_DEPTH - C_HINGE) ** 2, rel=1e-12)
    assert x[1] == pytest.approx(x[0], rel=1e-6)
    assert np.isfinite(x[2]) and 0 < x[2] < 1e-3 * x[0]


def test_steady_response_is_the_transfer_function(campaign):
    # a pure sinusoid switched on smoothly: once steady, theta = Re{X a e^{i w t} / Z(w)}
    truth = FlapTruth()
    period, a = 3.0, 0.1
    omega = 2 * np.pi / period
    t = np.arange(0, 120, 0.01)
    env = np.clip(t / 20.0, 0, 1)
    theta, theta_dot, theta_ddot, _ = flap_motion(t, env * a * np.cos(omega * t),
                                                  campaign=campaign, truth=truth)
    fl = campaign.flap
    X = excitation_coefficient(np.array([omega]), H_DEPTH, fl.hinge_height, fl.width)[0]
    nu = radiation_damping(np.array([omega]), H_DEPTH, fl.hinge_height, fl.width)[0]
    Z = (fl.buoyancy_stiffness - (fl.inertia + truth.added_inertia) * omega**2
         + 1j * omega * (nu + truth.pto_damping + truth.viscous_damping))
    expected = np.real(X * a / Z * np.exp(1j * omega * t))
    steady = (t > 60) & (t < 100)  # the ramp kink at 20 s leaves a 4e-6 tail at 40 s
    amp = abs(X * a / Z)
    assert np.max(np.abs(theta[steady] - expected[steady])) < 1e-6 * amp
    assert np.max(np.abs(theta_dot[steady] + omega * np.imag(X * a / Z * np.exp(1j * omega * t))[steady])) < 1e-6 * amp * omega
    assert np.max(np.abs(theta_ddot[steady] + omega**2 * expected[steady])) < 1e-6 * amp * omega**2


def test_ramped_wave_ramps_the_flap(record):
    t, eta, ds = record(3.5, 0.25)
    # before the wave arrives (5 s) the flap is (almost) at rest; the excitation kernel is
    # non-causal, so allow a precursor of 1e-3 of the amplitude
    amp = np.max(np.abs(ds.theta.values))
    assert np.max(np.abs(ds.theta.values[t < 4.0])) < 1e-3 * amp
    assert np.max(np.abs(ds.theta.values[(t > 5) & (t < 12)])) < 0.5 * amp


def test_raw_channels(record, campaign):
    t, eta, ds = record(3.5, 0.25)
    enc, pto = campaign.encoder, campaign.pto
    counts = ds.encoder_counts.values
    assert counts.dtype.kind == "i"
    # quantisation: within half a count of the true wire shortening
    wire = enc.L7 - wire_length(ds.theta.values, enc.L5, enc.L7)
    assert np.max(np.abs(counts / enc.counts_per_metre - wire)) <= 0.5 / enc.counts_per_metre
    # sensor noise: std 0.2 % of the 5 bar rated output = 1 kPa (within 5 % for 17 000 samples)
    noise = ds.chamber_pressure.values - ds.chamber_pressure_true.values
    assert np.std(noise) == pytest.approx(1000.0, rel=0.05)
    # the cavitation clamp is reached and never crossed (Eq. 14, sigma_c = 0)
    clamp = pto.vapour_pressure - pto.atmospheric_pressure
    assert ds.chamber_pressure_true.min() == clamp and ds.cavitating.sum() > 0
    # the truth satisfies Eq. (11)
    lhs = ds.torque_hydrodynamic
    rhs = ds.torque_inertia + ds.torque_gravity + ds.torque_pressure + ds.torque_friction
    assert np.max(np.abs(lhs - rhs)) < 1e-9 * np.max(np.abs(lhs))


def test_every_variable_is_registered(record):
    _, _, ds = record(3.5, 0.25)
    for name in ds.variables:
        assert name in conventions.VARIABLES, name
    conventions.check(ds)


def test_truth_friction_is_converged(campaign):
    # the friction truth at 10 steps per sample agrees with 40 steps per sample to 0.1 %
    t = np.arange(0, 30, 0.01)
    eta = 0.1 * np.clip(t / 10, 0, 1) * np.cos(2 * np.pi * t / 2.5)
    from flumekit.synth.flap import flap_record

    a = flap_record(t, eta, period=2.5, campaign=campaign, rng=np.random.default_rng(0))
    b = flap_record(t, eta, period=2.5, campaign=campaign, rng=np.random.default_rng(0),
                    truth=FlapTruth(friction_substeps=40))
    scale = float(np.max(np.abs(b.force_friction)))
    assert float(np.max(np.abs(a.force_friction - b.force_friction))) < 1e-3 * scale


def test_bad_input(campaign):
    from flumekit.synth.flap import flap_record

    t = np.arange(0, 10, 0.01)
    with pytest.raises(ValueError, match="uniform"):
        flap_record(t**1.01, np.zeros_like(t), period=2.0, campaign=campaign,
                    rng=np.random.default_rng(0))
    with pytest.raises(ValueError, match="eta"):
        flap_record(t, np.zeros(5), period=2.0, campaign=campaign, rng=np.random.default_rng(0))
    with pytest.raises(ValueError, match="FlapTruth"):
        FlapTruth(added_inertia=-1.0)
