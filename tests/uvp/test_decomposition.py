"""Eqs. (9)-(10), least-squares decomposition, CI propagation, Reynolds stresses."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from flumekit.uvp.decomposition import combine_ci, least_squares_velocity, paired_velocity
from flumekit.uvp.turbulence import reynolds_stresses, turbulent_kinetic_energy

A = np.array([-np.pi / 6, 0.0, np.pi / 6])  # UP1, UP2, UP3
vel = st.floats(-2.0, 2.0)


def _beams(u, w, angles):
    return u * np.cos(angles) + w * np.sin(angles)  # Eqs. (4)-(6)


@settings(max_examples=50, deadline=None)
@given(u=vel, w=vel, alpha=st.floats(0.1, 1.4))
def test_paired_exact_for_uniform_flow(u, w, alpha):
    v1, _, v3 = _beams(u, w, np.array([-alpha, 0.0, alpha]))
    uu, ww = paired_velocity(v1, v3, alpha)
    assert uu == pytest.approx(u, abs=1e-12) and ww == pytest.approx(w, abs=1e-12)


@settings(max_examples=50, deadline=None)
@given(u=vel, w=vel, angles=st.lists(st.floats(-1.3, 1.3), min_size=2, max_size=5),
       drop=st.integers(0, 4))
def test_least_squares_exact_and_ignores_missing_beams(u, w, angles, drop):
    a = np.array(angles)
    v = _beams(u, w, a)
    keep = np.ones(a.size, bool)
    if a.size > 2:
        keep[drop % a.size] = False
        v[~keep] = np.nan
    ak = a[keep]
    if abs(np.sin(ak.max() - ak.min())) < 0.05:  # (nearly) parallel beams: not a test of LS
        return
    uu, ww, cu, cw = least_squares_velocity(v, a)
    assert uu == pytest.approx(u, abs=1e-9) and ww == pytest.approx(w, abs=1e-9)
    assert np.all(cu[~keep] == 0) and np.all(cw[~keep] == 0)
    np.testing.assert_allclose(np.nansum(cu * v), uu, atol=1e-12)


def test_least_squares_rank_deficient_cases():
    v = np.array([[np.nan, 0.3, np.nan],    # horizontal beam only: u, not w
                  [0.2, np.nan, np.nan],     # one inclined beam: nothing
                  [np.nan, np.nan, np.nan]])
    u, w, cu, _ = least_squares_velocity(v, A)
    assert u[0] == pytest.approx(0.3) and np.isnan(w[0])
    assert np.isnan(u[1]) and np.isnan(w[1]) and np.isnan(u[2])


def test_paired_ci_propagation_matches_coefficients():
    alpha = np.pi / 6
    v = np.array([0.1, np.nan, 0.4])  # UP1 and UP3 only: LS reduces to Eqs. (9)-(10)
    u, w, cu, cw = least_squares_velocity(v, A)
    pu, pw = paired_velocity(v[0], v[2], alpha)
    assert u == pytest.approx(pu, abs=1e-14) and w == pytest.approx(pw, abs=1e-14)
    ci = np.array([0.01, np.nan, 0.02])
    assert combine_ci(cu, ci) == pytest.approx(np.hypot(0.01, 0.02) / (2 * np.cos(alpha)))
    assert combine_ci(cw, ci) == pytest.approx(np.hypot(0.01, 0.02) / (2 * np.sin(alpha)))


@settings(max_examples=50, deadline=None)
@given(su=st.floats(0.0, 0.1), sw=st.floats(0.0, 0.1), rho=st.floats(-1, 1))
def test_reynolds_stresses_exact(su, sw, rho):
    uu, ww, uw = su**2, sw**2, rho * su * sw
    var = np.cos(A) ** 2 * uu + np.sin(A) ** 2 * ww + 2 * np.sin(A) * np.cos(A) * uw
    a, b, c = reynolds_stresses(var, A)
    assert a == pytest.approx(uu, abs=1e-14)
    assert b == pytest.approx(ww, abs=1e-14)
    assert c == pytest.approx(uw, abs=1e-14)
    assert turbulent_kinetic_energy(a, b) == pytest.approx(0.5 * (uu + ww), abs=1e-14)


def test_reynolds_stresses_horizontal_only():
    a, b, c = reynolds_stresses(np.array([np.nan, 0.004, np.nan]), A)
    assert a == pytest.approx(0.004) and np.isnan(b) and np.isnan(c)
