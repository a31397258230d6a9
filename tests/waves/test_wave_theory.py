"""Linear wave theory against analytic limits, the dispersion relation itself and Table 1."""

import warnings

import numpy as np
import pytest

from flumekit.waves import (
    energy_flux,
    group_velocity,
    phase_velocity,
    probe_spacing,
    stokes2_coefficient,
    wavelength,
    wavenumber,
)

G = 9.81


def test_wavenumber_relative_accuracy_1e12_over_kh_1e4_to_1e3_without_warnings():
    # truth: pick kh, compute ω exactly from the dispersion relation, recover k
    kh = np.logspace(-4, 3, 3001)
    depth = np.array([0.05, 0.825, 40.0])[:, None]
    k_true = kh / depth
    omega = np.sqrt(G * k_true * np.tanh(kh))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        k = wavenumber(omega, depth)
    assert k.shape == (3, kh.size)
    assert np.max(np.abs(k / k_true - 1)) < 1e-12


def test_wavenumber_limits_and_broadcasting():
    h = 0.825
    # shallow: k -> ω / sqrt(g h) (relative correction (kh)²/6 = 1.7e-9 at kh = 1e-4)
    kh = 1e-4
    omega = kh / h * np.sqrt(G * h)
    assert wavenumber(omega, h) == pytest.approx(kh / h, rel=2e-9)
    # deep: k -> ω²/g (tanh(kh) = 1 to 1e-300 at kh = 1e3)
    omega = np.sqrt(G * 1e3 / h)
    assert wavenumber(omega, h) == pytest.approx(omega**2 / G, rel=1e-14)
    out = wavenumber(np.array([[1.0], [2.0]]), np.array([0.5, 1.0, 2.0]))
    assert out.shape == (2, 3)


@pytest.mark.parametrize("omega, depth", [(0.0, 1.0), (-1.0, 1.0), (1.0, 0.0), (np.nan, 1.0),
                                          (1.0, np.inf)])
def test_wavenumber_rejects_bad_input(omega, depth):
    with pytest.raises(ValueError):
        wavenumber(omega, depth)


def test_group_velocity_equals_dω_dk_and_limits():
    h = 0.825
    period = np.array([0.5, 1.0, 2.0, 3.5, 10.0, 60.0])
    k = wavenumber(2 * np.pi / period, h)
    # truth: central difference of ω(k) = sqrt(g k tanh kh), step 1e-6 k (error ~1e-12)
    dk = 1e-6 * k
    def w(kk):
        return np.sqrt(G * kk * np.tanh(kk * h))

    cg_fd = (w(k + dk) - w(k - dk)) / (2 * dk)
    np.testing.assert_allclose(group_velocity(period, h), cg_fd, rtol=1e-8)
    # deep water c/2, shallow water sqrt(g h)
    assert group_velocity(1.0, 1e3) == pytest.approx(G / (4 * np.pi), rel=1e-12)
    assert group_velocity(1e4, 1.0) == pytest.approx(np.sqrt(G), rel=1e-6)
    assert phase_velocity(1.0, 1e3) == pytest.approx(G / (2 * np.pi), rel=1e-12)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert np.isfinite(group_velocity(0.05, 1e3))  # kh ~ 1.6e6: no overflow


def test_energy_flux_limits_and_value():
    rho = 1000.0
    # deep water: P = E c_g = (ρ g H² / 8)(g T / 4π) = ρ g² H² T / (32 π)
    H, T = 0.1, 1.0
    assert energy_flux(H, T, 1e3) == pytest.approx(rho * G**2 * H**2 * T / (32 * np.pi), rel=1e-12)
    # shallow water: P = ρ g H² sqrt(g h) / 8 (relative correction ~ (kh)² ~ 1e-6 here)
    h = 0.1
    assert energy_flux(H, 300.0, h) == pytest.approx(rho * G * H**2 / 8 * np.sqrt(G * h), rel=1e-5)
    # Eq. (A2) in Brito et al. 2020 for T = 3.5 s, H = 0.25 m, h = 0.825 m, written out directly
    k = wavenumber(2 * np.pi / 3.5, 0.825)
    direct = rho * G * 0.25**2 / 8 * (2 * np.pi / 3.5) / (2 * k) * (
        1 + 2 * k * 0.825 / np.sinh(2 * k * 0.825))
    assert energy_flux(0.25, 3.5, 0.825) == pytest.approx(direct, rel=1e-13)
    with pytest.raises(ValueError):
        energy_flux(-0.1, 3.5, 0.825)


def test_stokes2_coefficient_against_dean_dalrymple_form():
    kh = np.array([0.3, 0.5, 1.0, 2.0, 5.0])
    direct = np.cosh(kh) * (2 + np.cosh(2 * kh)) / (4 * np.sinh(kh) ** 3)
    np.testing.assert_allclose(stokes2_coefficient(kh, 1.0), direct, rtol=1e-13)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert stokes2_coefficient(1e3, 1.0) == 0.5  # deep water, no overflow


def test_probe_spacing_reproduces_table_1_of_brito_2020():
    # Table 1 (values rounded to 0.01 m in the paper)
    T = np.array([2, 2.25, 2.5, 2.75, 3, 3.25, 3.5, 3.75, 4])
    x12 = np.array([0.49, 0.57, 0.65, 0.72, 0.8, 0.88, 0.95, 1.02, 1.1])
    x23 = np.array([1.23, 1.42, 1.62, 1.81, 2.0, 2.19, 2.38, 2.56, 2.75])
    a, b = probe_spacing(T, 0.825)
    np.testing.assert_allclose(a, x12, atol=0.0051)
    np.testing.assert_allclose(b, x23, atol=0.0051)
    np.testing.assert_allclose(wavelength(T, 0.825), 10 * a, rtol=1e-14)
