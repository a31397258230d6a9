"""Ball-screw efficiency Eqs. (4)-(6), PTO force Eq. (3) and the reference scenario of
Senatore & De Simone 2022 (sinusoidal z(t), A = 1 m, T = 3.8 s)."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from flumekit import conventions
from flumekit.ballscrew import buoy
from flumekit.ballscrew import screw as ballscrew
from flumekit.errors import GeometryError
from flumekit.io.netcdf import read_dataset, write_dataset

angles = st.floats(np.radians(1.0), np.radians(30.0))
contact = st.floats(np.radians(20.0), np.radians(80.0))
slip = st.floats(0.0, np.radians(10.0))
friction = st.floats(0.0, 0.15)


@settings(max_examples=40, deadline=None)
@given(angles, contact, slip)
def test_zero_friction_is_lossless(alpha, beta, gamma):
    eta = ballscrew.indirect_efficiency(alpha, beta, 0.0, 0.0, 0.0, gamma)
    eta_d = ballscrew.direct_efficiency(alpha, beta, 0.0, 0.0, 0.0, gamma)
    assert eta == pytest.approx(1.0, abs=1e-12) and eta_d == pytest.approx(1.0, abs=1e-12)


@settings(max_examples=40, deadline=None)
@given(angles, contact, slip, friction, friction, st.floats(0.0, 0.005), st.floats(1e-4, 0.05),
       st.sampled_from(["nut", "screw", "rho"]))
def test_efficiency_falls_as_friction_rises(alpha, beta, gamma, fn, fs, tr, df, which):
    base = dict(friction_nut=fn, friction_screw=fs, rho=np.arctan(tr))
    more = dict(base)
    key = {"nut": "friction_nut", "screw": "friction_screw", "rho": "rho"}[which]
    more[key] = base[key] + (np.arctan(tr + df) - np.arctan(tr) if which == "rho" else df)
    e1 = ballscrew.indirect_efficiency(alpha, beta, slip_angle=gamma, **base)
    e2 = ballscrew.indirect_efficiency(alpha, beta, slip_angle=gamma, **more)
    assert e2 <= e1 + 1e-15 and e1 <= 1.0 + 1e-12
    if e1 > 0:
        assert e2 < e1


@settings(max_examples=30, deadline=None)
@given(angles, st.floats(0.0, np.radians(25.0)))
def test_classic_screw_efficiencies(alpha, rho):
    # β = 90°, no groove friction: Eqs. (5)-(6) reduce to the classic power-screw results
    eta = ballscrew.indirect_efficiency(alpha, np.pi / 2 - 1e-12, 0.0, 0.0, rho)
    expected = max(np.tan(alpha - rho) / np.tan(alpha), 0.0)
    assert eta == pytest.approx(expected, abs=1e-9)
    eta_d = ballscrew.direct_efficiency(alpha, np.pi / 2 - 1e-12, 0.0, 0.0, rho)
    assert eta_d == pytest.approx(np.tan(alpha) / np.tan(alpha + rho), abs=1e-9)


def test_self_locking_when_lead_angle_below_friction_angle():
    alpha = np.radians(3.0)
    rho = np.radians([2.0, 3.5, 6.0])  # below, above, far above the lead angle
    eta = ballscrew.indirect_efficiency(alpha, np.pi / 2, 0.0, 0.0, rho)
    assert eta[0] > 0 and eta[1] == 0.0 and eta[2] == 0.0
    with pytest.raises(ValueError, match="self-locking"):
        ballscrew.indirect_efficiency(alpha, np.pi / 2, 0.0, 0.0, rho, strict=True)
    # the full model refuses a motion the screw cannot back-drive
    screw = ballscrew.BallScrew(lead=0.002, rolling_resistance=0.02)
    with pytest.raises(ValueError, match="self-locks"):
        ballscrew.pto_state(np.array([0.1, 0.2]), np.zeros(2), screw)


def test_pto_force_eq3():
    v = np.array([-0.4, -0.1, 0.0, 0.2, 0.5])
    a = np.array([1.0, -2.0, 0.5, 0.0, 3.0])
    f = ballscrew.pto_force(v, a, 100.0, 5e4, 500.0, 1000.0)
    assert f == pytest.approx(-5e4 * v - 100.0 * np.sign(v) - 500.0 * v - 1000.0 * a)
    assert np.all(ballscrew.pto_force(v, 0 * v, 100.0, 5e4, 500.0, 1000.0) * v <= 0)  # resists
    with pytest.raises(ValueError):
        ballscrew.pto_force(v, a, -1.0, 5e4, 500.0, 1000.0)


@pytest.fixture(scope="module")
def reference():
    kin = buoy.kinematics(buoy.reference_motion(1.0, 3.8, 1, 760))
    return kin, ballscrew.efficiency(kin)


def test_power_balance_and_eq4_at_every_step(reference):
    _, eff = reference
    v = eff["nut_velocity"].values
    pin, pout = eff["input_power"].values, eff["output_power"].values
    loss = eff["friction_force"].values * np.abs(v)
    assert pin == pytest.approx(pout + loss, rel=1e-12, abs=1e-9)  # energy conservation
    ind = (eff["power_flow_direction"].values > 0) & (np.abs(v) > 1e-3)
    # Eq. (4): the efficiency of the contact state equals P_out/P_in of the motion
    assert (pout / pin)[ind] == pytest.approx(eff["ballscrew_efficiency"].values[ind], rel=1e-9)
    omega = 2 * np.pi * v / 0.02
    assert eff["screw_speed"].values == pytest.approx(omega, rel=1e-12)


def test_reference_scenario_matches_paper(reference):
    kin, eff = reference
    eta = eff["ballscrew_efficiency"].values
    # paper: indirect efficiency between 73 % and 97 %
    assert eta.min() >= 0.73 and eta.max() <= 0.97
    assert eta.min() < 0.80 and eta.max() > 0.94  # and it spans most of that range
    # paper: "largely under mixed-mode lubrication"
    for side in ("screw", "nut"):
        regime = eff[f"lubrication_regime_{side}"].values
        assert np.mean(regime == 1) > 0.5
    # mixed regime, right-hand branch of the Stribeck curve: f falls as the speed rises
    mixed = eff["lubrication_regime_screw"].values == 1
    speed = np.abs(eff["screw_speed"].values[mixed])
    f = eff["friction_coefficient_screw"].values[mixed]
    assert np.corrcoef(speed, f)[0, 1] < -0.9
    # nut velocity is the time derivative of the nut travel (linkage kinematics)
    t = kin["time"].values
    dv = np.gradient(kin["nut_travel"].values, t)[2:-2]
    assert dv == pytest.approx(kin["nut_velocity"].values[2:-2], abs=2e-3 * 0.39)


def test_efficiency_dataset_is_writable(reference, tmp_path):
    kin, eff = reference
    for ds in (kin, eff):
        conventions.check(conventions.annotate(ds))
    path = write_dataset(eff, tmp_path / "eff.nc")
    back = read_dataset(path)
    assert back["ballscrew_efficiency"].values == pytest.approx(eff["ballscrew_efficiency"].values)


def test_bad_parameters_raise(reference):
    kin, _ = reference
    with pytest.raises(ValueError, match="lead"):
        ballscrew.efficiency(kin, ballscrew.BallScrew(lead=0.025))
    with pytest.raises(GeometryError, match="contact angle"):
        ballscrew.BallScrew(contact_angle=np.pi / 2)
    with pytest.raises(GeometryError, match="preload"):
        ballscrew.BallScrew(preload_per_ball=0.0)
    with pytest.raises(ValueError, match="friction"):
        ballscrew.Lubricant(friction_full_film=0.2, friction_boundary=0.1)
    # a lead angle outside (0, 90°) is refused in both directions of power flow, never
    # answered with a clipped efficiency
    for efficiency in (ballscrew.direct_efficiency, ballscrew.indirect_efficiency):
        for angle in (0.0, -0.1, np.pi / 2, 2.0):
            with pytest.raises(GeometryError, match="lead angle"):
                efficiency(angle, np.pi / 2, 0.0, 0.0, 0.01)


def test_figures_11_to_15(reference):
    from matplotlib.figure import Figure

    from flumekit.figures import ballscrew as figures

    _, eff = reference
    for number in (11, 12, 13, 14, 15):
        fig = figures.FIGURES[number](eff)
        assert isinstance(fig, Figure) and len(fig.axes) >= 1
    line = figures.figure_15(eff).axes[0].lines[0]
    assert line.get_ydata() == pytest.approx(100 * eff["ballscrew_efficiency"].values)
