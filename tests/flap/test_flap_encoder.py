"""Eq. (1): wire length <-> flap angle, counts <-> wire, domain flags, derivative filter."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import brentq

from flumekit import signal as sig
from flumekit.errors import GeometryError
from flumekit.flap.encoder import angle_from_wire, counts_from_wire, wire_from_counts, wire_length

L5, L7 = 1.53, 1.48  # §2.3


def _anchor_distance(theta, L5, L7):
    """Independent truth: distance from the encoder (-L7, L5) to the rotated anchor."""
    return np.hypot(L5 * np.sin(theta) + L7, L5 * np.cos(theta) - L5)


def test_closed_form_matches_numerical_root_of_eq1():
    # Eq. (1) with +2 L7 L5 sin(theta), solved by Brent's method to 1e-14 rad; tolerance 1e-9 rad
    theta_true = np.linspace(-0.6, 0.6, 241)  # ±34°, beyond any physical flap motion
    shortening = L7 - _anchor_distance(theta_true, L5, L7)

    def eq1(th, s):
        return L7**2 + (2 * L5 * np.sin(th / 2)) ** 2 + 2 * L7 * L5 * np.sin(th) - (L7 - s) ** 2

    roots = np.array([brentq(eq1, -0.7, 0.7, args=(s,), xtol=1e-14) for s in shortening])
    got = angle_from_wire(shortening, L5, L7)
    assert not got.out_of_domain.any()
    assert np.max(np.abs(got.theta - roots)) < 1e-9
    assert np.max(np.abs(got.theta - theta_true)) < 1e-9


@settings(max_examples=50, deadline=None)
@given(L5=st.floats(0.2, 3.0), L7=st.floats(0.2, 3.0), frac=st.floats(-0.95, 0.95))
def test_round_trip_over_the_branch(L5, L7, frac):
    # any angle on the branch (phi - pi, phi) comes back to 1e-9 rad (away from its ends,
    # where d(theta)/dL is unbounded)
    lo = -np.arctan(L7 / L5)
    hi = np.pi - np.arctan(L7 / L5)
    theta = 0.5 * (lo + hi) + frac * 0.5 * (hi - lo)
    s = L7 - _anchor_distance(theta, L5, L7)
    got = angle_from_wire(s, L5, L7)
    assert not got.out_of_domain
    assert abs(float(got.theta) - theta) < 1e-9 * max(1.0, 1.0 / np.cos(0.5 * np.pi * frac))


def test_sign_convention_theta_to_the_beach_pays_out_wire():
    # the anchor moves away from the encoder (wavemaker side) when the flap leans to the beach
    assert wire_length(0.1, L5, L7) > L7 > wire_length(-0.1, L5, L7)
    assert float(angle_from_wire(-0.01, L5, L7).theta) > 0  # negative shortening: beach


def test_printed_eq1_is_the_mirror_image():
    # Eq. (1) as printed (-2 L7 L5 sin theta) gives the wire length of the mirrored angle:
    # feeding its length to our (physical) inversion returns -theta
    theta = np.linspace(-0.3, 0.3, 13)
    printed = np.sqrt(L7**2 + (2 * L5 * np.sin(theta / 2)) ** 2 - 2 * L7 * L5 * np.sin(theta))
    assert np.allclose(angle_from_wire(L7 - printed, L5, L7).theta, -theta, atol=1e-12)


def test_out_of_domain_samples_are_flagged_not_nan():
    # the wire can be neither shorter than |encoder - hinge| - L5 nor longer than that + L5
    d = np.hypot(L5, L7)
    s = np.array([0.0, L7 - (d - L5) + 0.01, L7 - (d + L5) - 0.01, 0.05])
    got = angle_from_wire(s, L5, L7)
    assert got.out_of_domain.tolist() == [False, True, True, False]
    assert np.all(np.isfinite(got.theta))


@pytest.mark.parametrize("L5_, L7_", [(0.0, 1.48), (-1.0, 1.48), (1.53, 0.0), (np.nan, 1.0)])
def test_bad_encoder_geometry_is_an_error(L5_, L7_):
    with pytest.raises(GeometryError, match="L5|L7"):
        angle_from_wire(np.zeros(3), L5_, L7_)


def test_non_finite_wire_is_an_error():
    with pytest.raises(ValueError, match="non-finite"):
        angle_from_wire(np.array([0.0, np.nan]), L5, L7)


def test_counts_round_trip_within_half_a_count():
    cpm = 6000.0
    s = np.linspace(-0.4, 0.3, 1001)
    counts = counts_from_wire(s, cpm)
    assert counts.dtype.kind == "i"
    assert np.max(np.abs(wire_from_counts(counts, cpm) - s)) <= 0.5 / cpm + 1e-15
    with pytest.raises(ValueError):
        wire_from_counts(counts, 0.0)


def test_derivative_filter_error_against_truth():
    # quantised encoder signal of a two-harmonic flap motion; truth analytic. Cut-off 4 Hz:
    # measured 0.0004 deg, 0.02 % and 0.11 % (RMS, % of amplitude) for theta, theta_dot and
    # theta_ddot away from the record ends; asserted below 0.01 deg, 0.2 % and 1.5 %
    fs, T = 100.0, 2.0
    t = np.arange(0, 60, 1 / fs)
    w = 2 * np.pi / T
    th = 0.15 * np.sin(w * t) + 0.02 * np.sin(2 * w * t + 0.5)
    thd = 0.15 * w * np.cos(w * t) + 0.04 * w * np.cos(2 * w * t + 0.5)
    thdd = -0.15 * w**2 * np.sin(w * t) - 0.08 * w**2 * np.sin(2 * w * t + 0.5)
    counts = counts_from_wire(L7 - wire_length(th, L5, L7), 6000.0)
    theta = angle_from_wire(wire_from_counts(counts, 6000.0), L5, L7).theta
    xs, v, a = sig.smooth_derivatives(theta, fs, 4.0)
    inner = slice(500, -500)

    def rel(e, ref):
        return np.sqrt(np.mean(e[inner] ** 2)) / np.max(np.abs(ref))

    assert np.degrees(np.sqrt(np.mean((xs - th)[inner] ** 2))) < 0.01
    assert rel(v - thd, thd) < 0.002
    assert rel(a - thdd, thdd) < 0.015
