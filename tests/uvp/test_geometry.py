"""Beam geometry and the flap face."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from flumekit.uvp.geometry import beam_geometry, channel_positions, flap_face_x, inside_flap


def test_channel_positions_analytic():
    x, z = channel_positions(np.array([0.0, 0.2]), -0.37, 0.5, -np.pi / 6)
    np.testing.assert_allclose(x, [-0.37, -0.37 + 0.2 * np.sqrt(3) / 2], rtol=0, atol=1e-15)
    np.testing.assert_allclose(z, [0.5, 0.4], rtol=0, atol=1e-15)


def test_beam_geometry_of_the_campaign(campaign):
    g = beam_geometry(campaign.uvp, 0.42)
    assert g.sizes == {"beam": 3, "channel": 360}
    up2 = g.sel(beam="UP2")
    np.testing.assert_allclose(up2["z"], 0.42, atol=1e-15)
    # last channel of the horizontal beam: -0.37 + 0.02 + 359 x 0.74 mm (default_campaign.toml)
    assert float(up2["x"][-1]) == pytest.approx(-0.37 + 0.02 + 359 * 0.00074, abs=1e-12)
    up1, up3 = g.sel(beam="UP1"), g.sel(beam="UP3")
    np.testing.assert_allclose(up1["x"], up3["x"], atol=1e-15)  # the pair shares x
    np.testing.assert_allclose(up1["z"] + up3["z"], 2 * 0.42, atol=1e-14)  # symmetric in z
    assert float(g["beam_angle"].sel(beam="UP1")) == pytest.approx(-np.pi / 6, abs=1e-15)


@settings(max_examples=50, deadline=None)
@given(theta=st.floats(-0.6, 0.6), z=st.floats(0.0, 0.8))
def test_flap_face_is_half_a_thickness_from_the_rotated_centre_line(theta, z):
    t = 0.17
    x = flap_face_x(z, theta, t)
    # seaward unit normal of the centre line through the hinge with direction (sin θ, cos θ)
    n = np.array([-np.cos(theta), np.sin(theta)])
    assert float(np.dot([x, z], n)) == pytest.approx(t / 2, abs=1e-12)
    assert inside_flap(x + 1e-6, z, theta, t) and not inside_flap(x - 1e-6, z, theta, t)
    assert inside_flap(x - 0.005, z, theta, t, margin=0.01)


def test_flap_face_upright_and_bad_angle():
    assert flap_face_x(0.5, 0.0, 0.17) == pytest.approx(-0.085, abs=1e-15)
    with pytest.raises(ValueError):
        flap_face_x(0.5, np.pi / 2, 0.17)
