"""The buoy WEC: hydrostatics (Fig. 3), linkage kinematics, inverse/forward dynamics and the
energy balance algorithm (Fig. 4, Eq. (2)) of Senatore & De Simone 2022."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import integrate

from flumekit.ballscrew import buoy
from flumekit.ballscrew import screw as ballscrew
from flumekit.errors import GeometryError

G = buoy.BuoyGeometry()


@settings(max_examples=30, deadline=None)
@given(st.floats(0.0, 2.5))
def test_displaced_volume_and_waterplane(draft):
    r = G.float_radius
    # volume of the submerged cap by slices: ∫ π (R² - (R - y)²) dy from 0 to d
    vol = integrate.quad(lambda y: np.pi * (r**2 - (r - y) ** 2), 0, draft)[0]
    assert buoy.displaced_volume(draft, r) == pytest.approx(vol, rel=1e-10, abs=1e-12)
    # waterplane area is dV/dd (central difference: error h² |V'''|/6 = π h²/3 ≈ 1e-10 m²)
    h = 1e-5
    if h < draft < r - h:
        dv = (buoy.displaced_volume(draft + h, r) - buoy.displaced_volume(draft - h, r)) / (2 * h)
        assert buoy.waterplane_area(draft, r) == pytest.approx(dv, rel=1e-8, abs=2e-10)


def test_hydrostatic_limits_and_mass():
    r = G.float_radius
    assert buoy.displaced_volume([-1.0, r + 1.0], r) == pytest.approx([0.0, 2 * np.pi * r**3 / 3])
    assert buoy.waterplane_area([-0.1, r + 0.1], r) == pytest.approx([0.0, 0.0])
    # at rest the float weighs what it displaces
    assert G.mass == pytest.approx(G.water_density * buoy.displaced_volume(G.static_draft, r))


@settings(max_examples=30, deadline=None)
@given(st.floats(-0.3, 0.3))
def test_actuator_derivatives(theta):
    h = 1e-5
    s, ds, dds = buoy.actuator_length(theta, G)
    sp, dsp, _ = buoy.actuator_length(theta + h, G)
    sm, dsm, _ = buoy.actuator_length(theta - h, G)
    assert ds == pytest.approx((sp - sm) / (2 * h), rel=1e-8, abs=1e-10)
    assert dds == pytest.approx((dsp - dsm) / (2 * h), rel=1e-6, abs=1e-8)


def test_kinematics_chain():
    kin = buoy.kinematics(buoy.reference_motion(1.0, 3.8, 1, 760), G, lead=0.02)
    t, z = kin["time"].values, kin["buoy_heave"].values
    # arm angle reproduces the heave, nut velocity = linkage ratio x heave velocity
    assert G.arm_length * np.sin(kin["arm_angle"].values) == pytest.approx(z, abs=1e-12)
    assert kin["nut_velocity"].values == pytest.approx(
        kin["linkage_ratio"].values * kin["buoy_heave_velocity"].values, rel=1e-12, abs=1e-14)
    # nut acceleration is the derivative of nut velocity (central differences, 1e-3 of peak)
    da = np.gradient(kin["nut_velocity"].values, t)[2:-2]
    assert da == pytest.approx(kin["nut_acceleration"].values[2:-2],
                               abs=1e-3 * float(np.abs(kin["nut_acceleration"]).max()))
    # ω = 2π v / lead
    assert kin["screw_speed"].values == pytest.approx(2 * np.pi * kin["nut_velocity"].values / 0.02)


def test_heave_out_of_reach_raises():
    motion = buoy.reference_motion(7.0, 3.8, 1, 64)
    with pytest.raises(GeometryError, match="out of reach"):
        buoy.kinematics(motion, G)
    with pytest.raises(GeometryError, match="draft"):
        buoy.BuoyGeometry(static_draft=3.0)


def test_inverse_then_forward_dynamics_round_trip():
    # the wave force found by inverse dynamics, fed to the forward model, reproduces z(t)
    period, amp, k_pto, k_inert, f_fr, v_eps = 3.8, 0.8, 4e4, 800.0, 300.0, 0.05
    motion = buoy.reference_motion(amp, period, 2, 4000)
    kin = buoy.kinematics(motion, G)
    v, a = kin["nut_velocity"].values, kin["nut_acceleration"].values
    f_pto = -(k_pto * v + f_fr * np.tanh(v / v_eps) + k_inert * a)
    dyn = buoy.inverse_dynamics(kin, f_pto, G)
    fwd = buoy.forward_dynamics(kin["time"].values, dyn["net_vertical_force"].values, G,
                                damping=k_pto, inertia=k_inert, friction_force=f_fr,
                                friction_velocity=v_eps,
                                initial_velocity=float(motion["buoy_heave_velocity"][0]))
    # error budget: linear interpolation of F_z between samples, O(dt²) ≈ 1e-6 of the force
    assert fwd["buoy_heave"].values == pytest.approx(kin["buoy_heave"].values, abs=1e-3 * amp)


def test_wave_energy_density_eq2():
    assert buoy.wave_energy_density(2.0) == pytest.approx(1025 * 9.81 * 4 / 16)
    with pytest.raises(ValueError):
        buoy.wave_energy_density(-1.0)


def test_energy_balance_small_amplitude_limit():
    # linear damper, small waves: W = π K G² ω h², S_avg → S(d0), so h = sqrt(E S0/(π K G² ω))
    k_pto, period, height = 5e4, 3.8, 0.05

    def damper(v, a):
        return -k_pto * v

    h = buoy.lift_from_energy_balance(height, period, G, damper)
    _, ds, _ = buoy.actuator_length(G.rest_angle, G)
    ratio = ds / G.arm_length
    s0 = buoy.waterplane_area(G.static_draft, G.float_radius)
    expected = np.sqrt(buoy.wave_energy_density(height) * s0
                       / (np.pi * k_pto * ratio**2 * 2 * np.pi / period))
    assert h == pytest.approx(expected, rel=1e-2)  # O(h²) nonlinearity of linkage and float


def test_energy_balance_with_ballscrew_pto_closes():
    force = ballscrew.pto_force_function()
    h = buoy.lift_from_energy_balance(1.5, 3.8, G, force)
    work, s_avg = buoy.nut_work(h, 3.8, G, force)
    assert work == pytest.approx(buoy.wave_energy_density(1.5) * s_avg, rel=1e-8)
    assert 0.2 < h < 1.25
    # a bigger sea lifts the buoy higher
    assert buoy.lift_from_energy_balance(1.8, 3.8, G, force) > h
    with pytest.raises(ValueError, match="range of motion"):  # beyond the float's reach
        buoy.lift_from_energy_balance(2.5, 3.8, G, force)


def test_sea_state_motion_uses_the_energy_balance_lift():
    motion = ballscrew.sea_state_motion(1.5, 3.8, n_periods=1, samples_per_period=64)
    h = buoy.lift_from_energy_balance(1.5, 3.8, G, ballscrew.pto_force_function())
    assert motion.attrs["lift"] == pytest.approx(h, rel=1e-12)
    assert float(motion["buoy_heave"].max()) == pytest.approx(h, rel=1e-12)  # sample at T/4
