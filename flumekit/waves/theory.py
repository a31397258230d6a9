"""Linear wave theory: dispersion relation, wavelength, celerities, energy flux."""

from __future__ import annotations

import numpy as np

from flumekit.docstrings import doc

G = 9.81  # gravitational acceleration used throughout the flume paper [m s-2]


# The (period, depth, g) parameters of the celerity functions, documented once
_PERIOD_DEPTH_G = """Parameters
    ----------
    period : array_like
        Wave period [s], > 0.
    depth : array_like
        Water depth [m], broadcastable with ``period``, > 0.
    g : float
        Gravitational acceleration [m s-2]."""


def _shared_parameters(func):
    func.__doc__ = func.__doc__.replace("{period_depth_g}", _PERIOD_DEPTH_G)
    return func


def _sech2(y: np.ndarray) -> np.ndarray:
    e = np.exp(-2.0 * np.abs(y))
    return 4.0 * e / (1.0 + e) ** 2


@doc
def wavenumber(omega, depth, g: float = G) -> np.ndarray:
    """Wave number k solving the linear dispersion relation ω² = g k tanh(k h).

    Parameters
    ----------
    omega : array_like
        Angular frequency [rad s-1], > 0.
    depth : array_like
        Water depth h [m], broadcastable with ``omega``, > 0.
    %(g)s

    Returns
    -------
    numpy.ndarray
        Wave number [rad m-1], relative accuracy better than 1e-12 for 1e-4 ≤ kh ≤ 1e3.

    Raises
    ------
    ValueError
        For a non-finite or non-positive ``omega`` or ``depth``.

    Notes
    -----
    Solves y tanh y = x with x = ω²h/g, y = kh, from the explicit start of Fenton & McKee (1990),
    y0 = x / tanh(x^(3/4))^(2/3) (error below 1.5 %), by Newton steps written with sech² in the
    overflow-free exponential form.

    References
    ----------
    Fenton, J. D. & McKee, W. D. (1990). On calculating the lengths of water waves. Coastal
    Engineering 14, 499-513.

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.waves import wavenumber
    >>> k = wavenumber(2 * np.pi / 3.5, 0.825)  # T = 3.5 s in the paper's 0.825 m
    >>> round(float(2 * np.pi / k), 2)  # wavelength [m]
    9.51
    """
    omega = np.asarray(omega, dtype=float)
    depth = np.asarray(depth, dtype=float)
    if not (np.all(np.isfinite(omega) & (omega > 0)) and np.all(np.isfinite(depth) & (depth > 0))):
        raise ValueError("wavenumber needs finite omega > 0 and finite depth > 0")
    x = omega**2 * depth / g
    y = x / np.tanh(x**0.75) ** (2.0 / 3.0)
    for _ in range(6):
        t = np.tanh(y)
        f = y * t - x
        y = y - f / (t + y * _sech2(y))
    return y / depth


@_shared_parameters
def wavelength(period, depth, g: float = G) -> np.ndarray:
    """Wavelength L = 2π/k [m] of a wave of ``period`` [s] in ``depth`` [m].

    {period_depth_g}

    Returns
    -------
    numpy.ndarray
        Wavelength [m] from the linear dispersion relation (:func:`wavenumber`).

    Examples
    --------
    The deep-water and shallow-water limits, and a flume wave between them:

    >>> import numpy as np
    >>> from flumekit.waves import wavelength
    >>> round(float(wavelength(1.0, 10.0)), 4)  # deep (kh = 40): g T² / 2π
    1.5613
    >>> round(float(9.81 * 1.0**2 / (2 * np.pi)), 4)
    1.5613
    >>> round(float(wavelength(20.0, 0.1)), 2)  # shallow (kh = 0.03): T sqrt(g h) = 19.81
    19.81
    >>> np.round(wavelength([2.0, 3.0, 4.0], 0.825), 2).tolist()  # in the 0.825 m flume
    [4.9, 8.01, 10.98]
    """
    return 2 * np.pi / wavenumber(2 * np.pi / np.asarray(period, dtype=float), depth, g)


def _two_kh_over_sinh(y: np.ndarray) -> np.ndarray:
    """Evaluate 2kh / sinh(2kh) as 2y e^(-y) / (1 - e^(-2y)) with y = 2kh.

    No overflow, and no cancellation at small y (``expm1``).
    """
    return 2.0 * y * np.exp(-y) / -np.expm1(-2.0 * y)


@_shared_parameters
def phase_velocity(period, depth, g: float = G) -> np.ndarray:
    """Phase velocity c = ω/k = L/T [m s-1] of a wave of ``period`` [s] in ``depth`` [m].

    {period_depth_g}

    Returns
    -------
    numpy.ndarray
        Phase velocity [m s-1], the wavelength over the period.

    Examples
    --------
    c obeys the dispersion relation ω² = g k tanh(kh) with k = ω / c, and tends to
    sqrt(g h) in shallow water:

    >>> import numpy as np
    >>> from flumekit.waves import phase_velocity
    >>> c = float(phase_velocity(2.0, 0.825))
    >>> round(c, 3)
    2.451
    >>> omega = 2 * np.pi / 2.0
    >>> k = omega / c
    >>> bool(np.isclose(omega**2, 9.81 * k * np.tanh(k * 0.825), rtol=1e-12))
    True
    >>> round(float(phase_velocity(30.0, 0.5)), 3), round(float(np.sqrt(9.81 * 0.5)), 3)
    (2.214, 2.215)
    """
    return wavelength(period, depth, g) / np.asarray(period, dtype=float)


@_shared_parameters
def group_velocity(period, depth, g: float = G) -> np.ndarray:
    """Group velocity c_g = (ω / 2k) (1 + 2kh / sinh 2kh) [m s-1].

    {period_depth_g}

    Returns
    -------
    numpy.ndarray
        Group velocity [m s-1], n c with n = (1 + 2kh / sinh 2kh) / 2: the speed at which
        the wave energy travels.

    Examples
    --------
    The ratio n = c_g / c goes from 1/2 in deep water to 1 in shallow water:

    >>> import numpy as np
    >>> from flumekit.waves import group_velocity, phase_velocity
    >>> period = np.array([1.0, 2.0, 30.0])  # deep, the flume, shallow
    >>> depth = np.array([10.0, 0.825, 0.5])
    >>> n = group_velocity(period, depth) / phase_velocity(period, depth)
    >>> np.round(n, 3).tolist()
    [0.5, 0.759, 0.999]
    """
    omega = 2 * np.pi / np.asarray(period, dtype=float)
    depth = np.asarray(depth, dtype=float)
    k = wavenumber(omega, depth, g)
    return omega / (2 * k) * (1 + _two_kh_over_sinh(2 * k * depth))


@doc
def energy_flux(height, period, depth, rho: float = 1000.0, g: float = G) -> np.ndarray:
    """Period-averaged energy flux of a linear wave per unit crest width [W m-1].

    Eq. (A2) in Brito et al. 2020 without the flap width:
    P = (1/8) ρ g H² (ω / 2k) (1 + 2kh / sinh 2kh) = E c_g.

    Parameters
    ----------
    height : array_like
        Wave height H (crest to trough) [m], ≥ 0.
    %(period_array)s
    %(depth_array)s
    %(rho)s
    %(g)s

    Returns
    -------
    numpy.ndarray
        Energy flux [W m-1].

    References
    ----------
    Brito, M. et al. (2020). Experimental investigation of the flow field in the vicinity of
    an oscillating wave surge converter. J. Mar. Sci. Eng. 8, Eq. (A2).

    Examples
    --------
    The flux is the energy density E = ρ g H² / 8 carried at c_g; in deep water
    P = ρ g² H² T / (32 π):

    >>> import numpy as np
    >>> from flumekit.waves import energy_flux, group_velocity
    >>> round(float(energy_flux(0.1, 2.0, 0.825)), 2)  # H = 0.1 m, T = 2 s in 0.825 m
    22.8
    >>> round(float(1000.0 * 9.81 * 0.1**2 / 8 * group_velocity(2.0, 0.825)), 2)  # E c_g
    22.8
    >>> round(float(energy_flux(0.1, 1.0, 10.0)), 3)  # deep water
    9.573
    >>> round(1000.0 * 9.81**2 * 0.1**2 * 1.0 / (32 * np.pi), 3)
    9.573
    """
    height = np.asarray(height, dtype=float)
    if np.any(~(height >= 0)):
        raise ValueError("energy_flux needs a finite wave height >= 0")
    # Eq. (A2) in Brito et al. 2020 (divided by the flap width L)
    return rho * g * height**2 / 8.0 * group_velocity(period, depth, g)


@doc
def stokes2_coefficient(k, depth) -> np.ndarray:
    """Second-order Stokes coefficient B with η₂ = B k a² cos 2θ for η₁ = a cos θ [-].

    B = cosh kh (2 + cosh 2kh) / (4 sinh³ kh) (Dean & Dalrymple 1991, Eq. 11.33, written with
    a = H/2), evaluated overflow-free as (1 + q)(1 + 4q + q²) / (2 (1 - q)³), q = e^(-2kh);
    B → 1/2 in deep water. The second-order crest-to-trough height equals 2a exactly.

    Parameters
    ----------
    k : array_like
        Wave number of the first harmonic [rad m-1].
    %(depth_array)s

    Returns
    -------
    numpy.ndarray
        B [-].

    References
    ----------
    Dean, R. G. & Dalrymple, R. A. (1991). Water wave mechanics for engineers and scientists.
    World Scientific, Eq. (11.33).

    Examples
    --------
    B against the textbook form at kh = 1, its deep-water limit, and the second-order crest
    and trough of a 0.1 m, 2 s wave in 0.825 m: the crest rises higher above the still water
    level than the trough falls below it, and the height stays 2a:

    >>> import numpy as np
    >>> from flumekit.waves import stokes2_coefficient, wavenumber
    >>> round(float(stokes2_coefficient(1.0, 1.0)), 4)
    1.3696
    >>> round(float(np.cosh(1) * (2 + np.cosh(2)) / (4 * np.sinh(1) ** 3)), 4)
    1.3696
    >>> float(stokes2_coefficient(20.0, 1.0))  # deep water: 1/2
    0.5
    >>> a, k = 0.05, float(wavenumber(2 * np.pi / 2.0, 0.825))
    >>> b = float(stokes2_coefficient(k, 0.825))
    >>> round(a + b * k * a**2, 4), round(a - b * k * a**2, 4)  # crest, trough depth [m]
    (0.054, 0.046)
    """
    kh = np.asarray(k, dtype=float) * np.asarray(depth, dtype=float)
    q = np.exp(-2.0 * kh)
    return (1 + q) * (1 + 4 * q + q * q) / (2.0 * (-np.expm1(-2.0 * kh)) ** 3)
