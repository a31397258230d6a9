"""PTO geometry: rod length, rate, beta, lever arm (Eq. 12 with the lever arm); bad geometry."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from flumekit.errors import GeometryError
from flumekit.flap.geometry import (
    angle_from_rod_length,
    flap_point,
    rod_kinematics,
    rod_length_limits,
)
from flumekit.flap.torque import friction_torque, pressure_torque

BED, FLAP = (1.04, 0.0), (0.09, 0.47)  # §2.2


def test_values_at_rest_from_the_paper_geometry():
    k = rod_kinematics(0.0, 1.0, BED, FLAP)
    # rod from (1.04, 0) to (0.09, 0.47); perpendicular distance hinge-rod line = |b x p| / l
    length = np.hypot(0.95, 0.47)
    assert float(k.length) == pytest.approx(length, rel=1e-14)
    assert float(k.lever_arm) == pytest.approx(-(1.04 * 0.47) / length, rel=1e-14)
    r = np.hypot(0.09, 0.47)
    assert r * np.sin(float(k.beta)) == pytest.approx(1.04 * 0.47 / length, rel=1e-13)
    # leaning to the beach shortens the rod: compression
    assert float(k.velocity) < 0


points = st.tuples(st.floats(-2, 2), st.floats(-1, 2))


@settings(max_examples=50, deadline=None)
@given(bed=points, flap=points, theta=st.floats(-0.6, 0.6))
def test_rate_lever_and_torque_against_independent_formulas(bed, flap, theta):
    b, p0 = np.array(bed), np.array(flap)
    if min(np.hypot(*p0), np.hypot(*b), np.hypot(*(p0 - b))) < 0.05:
        return
    px, pz = flap_point(p0, theta)
    rod = np.array([px - b[0], pz - b[1]])
    ell = np.hypot(*rod)
    perp = abs(b[0] * pz - b[1] * px) / ell  # distance from the hinge to the rod line
    if ell < 0.05 or perp < 1e-3:
        return
    k = rod_kinematics(theta, 0.7, b, p0)
    # rod length rate = d(length)/d(theta) * theta_dot, by a central difference (h = 1e-6)
    h = 1e-6
    dl = (rod_kinematics(theta + h, 0, b, p0).length
          - rod_kinematics(theta - h, 0, b, p0).length) / (2 * h)
    assert float(k.velocity) == pytest.approx(0.7 * float(dl), rel=1e-6, abs=1e-9)
    # |lever| = r sin(beta) = perpendicular distance of the rod line from the hinge
    assert abs(float(k.lever_arm)) == pytest.approx(perp, rel=1e-10)
    assert np.hypot(*p0) * np.sin(float(k.beta)) == pytest.approx(perp, rel=1e-8, abs=1e-12)
    # torque of an extending force F on the flap, by the 2-D cross product p x (F u)
    F = 123.0
    u = rod / ell
    torque_on_flap = pz * F * u[0] - px * F * u[1]  # positive towards +x (the beach)
    assert -float(pressure_torque(F, k.lever_arm)) == pytest.approx(torque_on_flap, rel=1e-10)
    assert float(friction_torque(F, k.lever_arm)) == pytest.approx(torque_on_flap, rel=1e-10)


def test_pressure_resists_leaning_to_the_beach():
    k = rod_kinematics(0.1, 0.5, BED, FLAP)
    assert float(pressure_torque(500.0, k.lever_arm)) > 0  # resisting torque in Eq. (11)


def test_angle_from_rod_length_round_trip_and_limits():
    theta = np.linspace(-0.5, 0.5, 11)
    k = rod_kinematics(theta, 0, BED, FLAP)
    assert np.allclose(angle_from_rod_length(k.length, BED, FLAP), theta, atol=1e-12)
    lo, hi = rod_length_limits(BED, FLAP)
    assert lo == pytest.approx(1.04 - np.hypot(0.09, 0.47))
    with pytest.raises(GeometryError, match="rod length outside"):
        angle_from_rod_length(lo * 0.99, BED, FLAP)  # rod shorter than the anchors allow
    with pytest.raises(GeometryError, match="rod length outside"):
        angle_from_rod_length(hi * 1.01, BED, FLAP)


@pytest.mark.parametrize("bed, flap, match", [
    ((0.5, 0.2), (0.5, 0.2), "coincide"),
    ((1.04, 0.0), (0.0, 0.0), "flap anchor .* hinge"),
    ((0.0, 0.0), (0.09, 0.47), "bed anchor .* hinge"),
    ((1.04, np.nan), (0.09, 0.47), "finite"),
    ((1.04, 0.0, 1.0), (0.09, 0.47), "pair"),
])
def test_bad_anchors_are_geometry_errors(bed, flap, match):
    with pytest.raises(GeometryError, match=match):
        rod_kinematics(np.zeros(3), np.zeros(3), bed, flap)


def test_rod_through_the_hinge_is_a_geometry_error():
    # at theta = atan2(0.47, 0.09) the flap anchor lies on the x axis, in line with the hinge
    # and the bed anchor: the rod has no lever arm
    singular = np.arctan2(0.47, 0.09)
    with pytest.raises(GeometryError, match="passes through the hinge"):
        rod_kinematics(np.array([0.0, singular]), np.zeros(2), BED, FLAP)
