"""Vertical eigenmodes of linear water waves in constant depth, projected on a bottom-hinged flap.

The potential is expanded as φ = Σ_n ϕ_n(x, y) Z_n(z) with the depth eigenfunctions of
RD12 Eqs. (2.20)–(2.24) (Renzi & Dias, J. Fluid Mech. 701, 2012), written here in dimensional
form (ω² replaced by ω²/g):

- n = 0 (propagating): Z_0 = √2 cosh k(z+h) / N_0, ω² = g k tanh kh;
- n ≥ 1 (evanescent): Z_n = √2 cos k_n(z+h) / N_n, ω² = -g k_n tan k_n h,
  k_n ∈ ((n - ½)π/h, nπ/h);

with N² = h + sinh(2kh)/(2k) (resp. h + sin(2k_n h)/(2k_n)), so that the Z_n are orthonormal
on [-h, 0]. The plane wavenumbers are returned as κ_n² (k² for n = 0, -k_n² for n ≥ 1), the
form in which they enter the horizontal Helmholtz problems (∇² + κ_n²) ϕ_n = 0.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from flumekit.waves.theory import G, wavenumber


def evanescent_wavenumbers(omega, depth, n_modes: int, g: float = G) -> np.ndarray:
    """Roots k_n of ω² = -g k_n tan(k_n h), n = 1..n_modes [rad m-1].

    Parameters
    ----------
    omega : Angular frequency [rad s-1], array-like, > 0.
    depth : Water depth h [m], broadcastable with ``omega``, > 0.
    n_modes : Number of evanescent modes (≥ 0).
    g : Gravitational acceleration [m s-2].

    Returns
    -------
    Array of shape ``broadcast(omega, depth).shape + (n_modes,)``.

    Notes
    -----
    With k_n h = nπ - δ_n the equation becomes δ = arctan(y / (nπ - δ)), y = ω²h/g, whose
    right-hand side is a contraction (slope below 1/π) on δ ∈ (0, π/2). Two fixed-point steps
    from δ = arctan(y/(nπ)) and four Newton steps on δ - arctan(y/(nπ - δ)) reach machine
    precision for every y > 0 and n ≥ 1 (no tan evaluated near its poles).
    """
    omega = np.asarray(omega, dtype=float)
    depth = np.asarray(depth, dtype=float)
    if np.any(~(omega > 0)) or np.any(~(depth > 0)):
        raise ValueError("evanescent_wavenumbers needs omega > 0 and depth > 0 (finite)")
    if int(n_modes) != n_modes or n_modes < 0:
        raise ValueError(f"n_modes must be a non-negative integer, got {n_modes}")
    y = (omega**2 * depth / g)[..., None]
    npi = np.pi * np.arange(1, int(n_modes) + 1)
    delta = np.arctan(y / npi)
    for _ in range(2):
        delta = np.arctan(y / (npi - delta))
    for _ in range(4):
        a = npi - delta
        f = delta - np.arctan(y / a)
        fp = 1.0 - y / (a * a + y * y)
        delta = delta - f / fp
    return (npi - delta) / np.asarray(depth)[..., None]


class VerticalModes(NamedTuple):
    """Depth modes of one or several frequencies; trailing axis = mode n = 0..n_modes."""

    wavenumber: np.ndarray  # k_0 [rad m-1], shape (...)
    kappa2: np.ndarray  # κ_n² [rad2 m-2]: k_0², -k_1², -k_2², ...; shape (..., n+1)
    f: np.ndarray  # f_n = ∫ (z+h-c) Z_n dz over the flap [m^(3/2)], shape (..., n+1)
    d0: np.ndarray  # d_0 [m^(1/2) s-1]: diffraction forcing per metre of wave amplitude, (...)
    z0_surface: np.ndarray  # Z_0(0) [m^(-1/2)], shape (...)


def vertical_modes(omega, depth: float, hinge_height: float, n_modes: int,
                   g: float = G) -> VerticalModes:
    """Wavenumbers and flap projections of the vertical eigenmodes.

    Parameters
    ----------
    omega : Angular frequency [rad s-1], 1-D or scalar, > 0.
    depth : Water depth h [m].
    hinge_height : Height c of the hinge above the bed [m], 0 ≤ c < h.
    n_modes : Number of evanescent modes kept.
    g : Gravitational acceleration [m s-2].

    Returns
    -------
    :class:`VerticalModes`. The projections are

    - f_n = ∫_{-h+c}^0 (z+h-c) Z_n dz: Eq. (2.29) in RD12,
      f_0 = √2 [k(h-c) sinh kh + cosh kc - cosh kh] / (k² N_0),
      f_n = √2 [k_n(h-c) sin k_n h + cos k_n h - cos k_n c] / (k_n² N_n);
    - d_0 = g k N_0 / (√2 ω cosh kh): Eq. (2.30) in RD12 (d_n = 0 for n ≥ 1), the x-derivative
      of the incident potential projected on Z_0, per metre of wave amplitude.

    Notes
    -----
    cosh a - cosh b is written -2 sinh((a+b)/2) sinh((b-a)/2) (no cancellation in long waves),
    and the hyperbolic functions are scaled by e^{-kh} for kh > 20 (no overflow in deep water).
    """
    omega = np.asarray(omega, dtype=float)
    h, c = float(depth), float(hinge_height)
    if not h > 0 or not 0 <= c < h:
        raise ValueError(f"need depth > 0 and 0 <= hinge_height < depth, got h={h}, c={c}")
    k = wavenumber(omega, h, g)
    X = k * h
    a, b = k * (h + c) / 2, k * (h - c) / 2
    with np.errstate(over="ignore", invalid="ignore"):
        # unscaled, accurate for small and moderate kh
        n0 = np.sqrt((2 * X + np.sinh(2 * X)) / (2 * k))
        num = k * (h - c) * np.sinh(X) - 2 * np.sinh(a) * np.sinh(b)
        f0_small = np.sqrt(2) * num / (k**2 * n0)
        sech_n0_small = n0 / np.cosh(X)  # N_0 / cosh kh
    # scaled by e^{-X}: sinh X e^{-X} = (1 - q)/2 with q = e^{-2X}; sinh a sinh b e^{-X}
    # = (1 - e^{-2b} - e^{-2a} + q)/4 with a + b = X
    q = np.exp(-2 * X)
    n0s = np.sqrt((2 * X * q + (1 - q * q) / 2) / (2 * k))  # N_0 e^{-X}
    nums = k * (h - c) * (1 - q) / 2 - (1 - np.exp(-2 * b) - np.exp(-2 * a) + q) / 2
    big = X > 20
    f0 = np.where(big, np.sqrt(2) * nums / (k**2 * n0s), f0_small)
    ratio = np.where(big, n0s / ((1 + q) / 2), sech_n0_small)  # N_0 / cosh kh
    d0 = g * k * ratio / (np.sqrt(2) * omega)
    z0 = np.sqrt(2) / ratio
    # evanescent modes
    kn = evanescent_wavenumbers(omega, h, n_modes, g)
    nn = np.sqrt((2 * kn * h + np.sin(2 * kn * h)) / (2 * kn))
    an, bn = kn * (h + c) / 2, kn * (h - c) / 2
    fn = np.sqrt(2) * (kn * (h - c) * np.sin(kn * h) - 2 * np.sin(an) * np.sin(bn)) / (kn**2 * nn)
    kappa2 = np.concatenate([(k**2)[..., None], -(kn**2)], axis=-1)
    f = np.concatenate([f0[..., None], fn], axis=-1)
    return VerticalModes(k, kappa2, f, d0, z0)
