"""Chamber pressure of the single-acting PTO cylinder (Brito et al. 2020, Eqs. 13-14).

The cylinder's lower (full-bore) chamber is connected to the hydraulic circuit; its upper
chamber is open to the atmosphere, so the net pressure force pushing the rod out is
F_p = A P_int with P_int the chamber's gauge pressure and A the bore area.

Eq. (13) models the chamber pressure as K_p θ̇² + I_p θ̈ (pressure loss in the circuit plus the
inertia of the fluid), clamped at the vapour pressure when the Thoma coefficient
σ = (P_atm + P_int − P_v)/P_atm (Eq. 14) falls below σ_c = 0. As printed, K_p θ̇² has the same
sign whichever way the flap moves. For a single-acting cylinder that is not physical: when the
rod is pushed in (compression; θ̇ > 0 for our anchors, the flap leaning to the beach) the fluid
is driven out through the circuit and the chamber pressure rises above the atmosphere; when the
rod is pulled out (extension) the chamber sucks fluid in and its pressure falls below the
atmosphere, towards the vapour pressure. The loss term therefore takes the sign of the flow:
we implement

    P_int = K_p θ̇ |θ̇| + I_p θ̈                    (σ ≥ 0, no cavitation)
    P_int = P_v − P_atm                            (σ < 0, cavitation)

with P_int a gauge pressure and θ̇ > 0 the compression direction (pass ``compression_sign=-1``
for a cylinder mounted the other way). The cavitation branch as printed, P_v + I_p θ̈, adds the
fluid inertia to an absolute vapour pressure: while the chamber cavitates its vapour cavity
decouples the piston from the fluid column, so the chamber pressure is the vapour pressure
(P_v − P_atm in gauge terms) and the inertia term does not act on the piston.

%(references_brito2020)s, Eqs. (13)-(14).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from flumekit.docstrings import fill, filler

#: docstring text that several functions of this module share
_doc = filler(
    vapour_pressure=("vapour_pressure : float, optional\n"
                     "    P_v, absolute [Pa]."))

__doc__ = fill(__doc__)

#: water vapour pressure at 20 °C [Pa] and standard atmosphere [Pa]
VAPOUR_PRESSURE = 2339.0
ATMOSPHERIC_PRESSURE = 101325.0


@_doc
def thoma_coefficient(chamber_pressure, atmospheric_pressure: float = ATMOSPHERIC_PRESSURE,
                      vapour_pressure: float = VAPOUR_PRESSURE) -> np.ndarray:
    """Compute the Thoma coefficient σ = (P_atm + P_int − P_v)/P_atm (Eq. 14).

    Parameters
    ----------
    %(chamber_pressure)s
    atmospheric_pressure : float, optional
        P_atm [Pa], > 0.
    %(vapour_pressure)s

    Returns
    -------
    numpy.ndarray
        σ [-]; the chamber cavitates where σ < 0.

    Raises
    ------
    ValueError
        A non-positive atmospheric pressure.

    %(references_brito2020)s, Eq. (14).

    Examples
    --------
    >>> from flumekit.flap.pressure import thoma_coefficient
    >>> thoma_coefficient([0.0, -98986.0]).round(6)
    array([0.976916, 0.      ])
    """
    if not atmospheric_pressure > 0:
        raise ValueError(f"atmospheric pressure must be > 0, got {atmospheric_pressure}")
    return (atmospheric_pressure + np.asarray(chamber_pressure, dtype=float)
            - vapour_pressure) / atmospheric_pressure


@_doc
def chamber_pressure_model(theta_dot, theta_ddot, pressure_loss_coefficient: float,
                           fluid_inertia: float, *,
                           atmospheric_pressure: float = ATMOSPHERIC_PRESSURE,
                           vapour_pressure: float = VAPOUR_PRESSURE,
                           compression_sign: int = 1) -> np.ndarray:
    """Compute the chamber gauge pressure from the flap motion (Eq. 13 signed, σ_c = 0).

    Parameters
    ----------
    %(theta_dot)s
    theta_ddot : array_like
        Flap angular acceleration [rad s-2].
    pressure_loss_coefficient : float
        K_p [Pa s2 rad-2], ≥ 0.
    %(fluid_inertia)s
    atmospheric_pressure : float
        P_atm [Pa].
    vapour_pressure : float
        P_v, absolute [Pa].
    compression_sign : int
        +1 if θ̇ > 0 compresses the chamber (the default anchors), −1 otherwise.

    Returns
    -------
    numpy.ndarray
        P_int [Pa], K_p θ̇ abs(θ̇) + I_p θ̈ clamped below at P_v − P_atm.

    %(references_brito2020)s, Eqs. (13)-(14).

    Examples
    --------
    Compression, then suction strong enough to cavitate:

    >>> from flumekit.flap.pressure import chamber_pressure_model
    >>> chamber_pressure_model([0.5, -2.0], [0.0, 0.0], 1.0e5, 0.0)
    array([ 25000., -98986.])
    """
    w = compression_sign * np.asarray(theta_dot, dtype=float)
    a = compression_sign * np.asarray(theta_ddot, dtype=float)
    p = pressure_loss_coefficient * w * np.abs(w) + fluid_inertia * a
    # Eq. (14) with σ_c = 0: σ < 0  <=>  P_int < P_v − P_atm
    return np.maximum(p, vapour_pressure - atmospheric_pressure)


class PressureFit(NamedTuple):
    """Least-squares fit of Eq. (13).

    What :func:`fit_pressure_model` returns.

    Attributes
    ----------
    pressure_loss_coefficient : float
        K_p [Pa s2 rad-2].
    fluid_inertia : float
        I_p [Pa s2 rad-1].
    r2 : float
        Coefficient of determination over all samples used [-].
    cavitating : numpy.ndarray of bool
        The samples on the cavitation branch of the fitted model.
    fitted : numpy.ndarray
        Fitted chamber (gauge) pressure [Pa].
    bounded : bool
        True when a coefficient is held at its bound 0 (the free fit was unphysical).

    Examples
    --------
    One cycle of a flap swinging at 0.8 rad/s: on the suction stroke K_p θ̇² exceeds the
    99 kPa between the atmosphere and the vapour pressure, and the chamber cavitates. A
    record made by the model is fitted exactly, cavitation included:

    >>> import numpy as np
    >>> from flumekit.flap.pressure import chamber_pressure_model, fit_pressure_model
    >>> t = np.linspace(0.0, 2.0, 201)  # [s]
    >>> w, a = 0.8 * np.sin(np.pi * t), 0.8 * np.pi * np.cos(np.pi * t)
    >>> record = chamber_pressure_model(w, a, 2.0e5, 300.0)
    >>> fit = fit_pressure_model(record, w, a)
    >>> round(fit.pressure_loss_coefficient), round(fit.fluid_inertia, 6), fit.bounded
    (200000, 300.0, False)
    >>> int(fit.cavitating.sum()), bool(np.allclose(fit.fitted, record))  # samples of 201
    (31, True)
    """

    pressure_loss_coefficient: float  # K_p [Pa s2 rad-2]
    fluid_inertia: float  # I_p [Pa s2 rad-1]
    r2: float  # coefficient of determination over all samples used
    cavitating: np.ndarray  # bool, samples on the cavitation branch of the fitted model
    fitted: np.ndarray  # fitted chamber pressure [Pa]
    bounded: bool = False  # a coefficient is held at its bound 0 (the free fit was unphysical)


@_doc
def fit_pressure_model(chamber_pressure, theta_dot, theta_ddot, *,
                       atmospheric_pressure: float = ATMOSPHERIC_PRESSURE,
                       vapour_pressure: float = VAPOUR_PRESSURE, compression_sign: int = 1,
                       max_iterations: int = 20) -> PressureFit:
    """Fit K_p and I_p of Eq. (13) to a measured chamber pressure by least squares.

    The model is linear in (K_p, I_p) off the cavitation branch and constant on it, so the fit
    alternates a linear least-squares solve on the samples where the current model is above the
    vapour clamp with a re-classification of the samples (an active-set iteration), starting
    from the samples whose measured pressure is above the clamp. The iteration stops when the
    set no longer changes. R² is that of the full piecewise model over all samples. Both
    coefficients are bounded below by 0 (a solve whose free optimum has one negative is
    replaced by the non-negative least-squares one; ``bounded`` says so).

    Parameters
    ----------
    chamber_pressure : array_like
        Measured gauge pressure [Pa].
    theta_dot : array_like
        Flap angular velocity θ̇ [rad s-1].
    theta_ddot : array_like
        Flap angular acceleration θ̈ [rad s-2].
    atmospheric_pressure : float, optional
        P_atm [Pa].
    %(vapour_pressure)s
    compression_sign : int, optional
        +1 if θ̇ > 0 compresses the chamber, −1 otherwise.
    max_iterations : int, optional
        Largest number of active-set iterations.

    Returns
    -------
    PressureFit
        K_p [Pa s2 rad-2], I_p [Pa s2 rad-1], R² [-], the cavitating samples, the fitted
        pressure [Pa] and whether a coefficient is held at its bound 0.

    Raises
    ------
    ValueError
        Non-finite input, mismatched shapes, too few non-cavitating samples, or a constant
        pressure.

    %(references_brito2020)s, Eqs. (13)-(14).
    Lawson, C. L. & Hanson, R. J. (1974). Solving Least Squares Problems. Prentice-Hall,
    Chapter 23 (non-negative least squares).

    Examples
    --------
    A pressure made by the model itself is fitted exactly:

    >>> import numpy as np
    >>> from flumekit.flap.pressure import chamber_pressure_model, fit_pressure_model
    >>> t = np.linspace(0.0, 4.0, 401)
    >>> w, a = 0.3 * np.cos(np.pi * t), -0.3 * np.pi * np.sin(np.pi * t)
    >>> fit = fit_pressure_model(chamber_pressure_model(w, a, 2.0e5, 300.0), w, a)
    >>> round(fit.pressure_loss_coefficient), round(fit.fluid_inertia, 6), round(fit.r2, 9)
    (200000, 300.0, 1.0)
    """
    p = np.asarray(chamber_pressure, dtype=float).ravel()
    w = compression_sign * np.asarray(theta_dot, dtype=float).ravel()
    a = compression_sign * np.asarray(theta_ddot, dtype=float).ravel()
    if not (p.shape == w.shape == a.shape):
        raise ValueError(f"pressure fit: shapes differ ({p.shape}, {w.shape}, {a.shape})")
    if not (np.all(np.isfinite(p)) and np.all(np.isfinite(w)) and np.all(np.isfinite(a))):
        raise ValueError("pressure fit: non-finite samples in the pressure or the motion")
    clamp = vapour_pressure - atmospheric_pressure
    design = np.column_stack([w * np.abs(w), a])
    # start from the samples clearly above the clamp (noise scale from the data)
    spread = np.std(p) if p.size > 1 else 0.0
    active = p > clamp + 1e-3 * spread
    coef = np.zeros(2)
    for _ in range(max_iterations):
        if active.sum() < 3:
            raise ValueError("pressure fit: fewer than three samples off the cavitation branch")
        coef, *_ = np.linalg.lstsq(design[active], p[active], rcond=None)
        if np.any(coef < 0):
            # K_p (a loss) and I_p (the inertia of the fluid column) cannot be negative. A
            # pressure that lags the motion (air in the chamber, a valve; not in Eq. 13) makes
            # the free fit trade inertia for lag and return I_p < 0, which no fluid has and
            # which the simulator rightly refuses: bounded least squares (Lawson-Hanson NNLS)
            # keeps the fitted model physical, at a lower R². (scipy.optimize is imported here:
            # a large import that only this branch needs.)
            from scipy.optimize import nnls

            coef, _ = nnls(design[active], p[active])
        new = design @ coef > clamp
        if np.array_equal(new, active):
            break
        active = new
    fitted = np.maximum(design @ coef, clamp)
    ss_res = float(np.sum((p - fitted) ** 2))
    ss_tot = float(np.sum((p - p.mean()) ** 2))
    if not ss_tot > 0:
        raise ValueError("pressure fit: the measured chamber pressure is constant (R² undefined)")
    r2 = 1.0 - ss_res / ss_tot
    return PressureFit(float(coef[0]), float(coef[1]), r2, ~active, fitted,
                       bool(np.any(coef == 0)))


@_doc
def pressure_force(chamber_pressure, bore_area: float) -> np.ndarray:
    """Compute the pressure force pushing the rod out, F_p = A P_int.

    P_int is the gauge pressure of the chamber that pushes the rod out; a suction (P_int < 0)
    pulls the rod in.

    Parameters
    ----------
    %(chamber_pressure)s
    %(bore_area)s

    Returns
    -------
    numpy.ndarray
        F_p [N].

    %(raises_bore_area)s

    %(references_brito2020)s, §2.2.

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.flap.pressure import pressure_force
    >>> area = np.pi * 0.05**2 / 4  # a 50 mm bore [m2]
    >>> pressure_force([2.0e5, -500.0], area).round(2)
    array([392.7 ,  -0.98])
    """
    if not bore_area > 0:
        raise ValueError(f"bore area must be > 0, got {bore_area}")
    return bore_area * np.asarray(chamber_pressure, dtype=float)
