"""Compiled scalar kernels of the flap PTO: the modified LuGre friction and the hydraulic cylinder.

The friction's state equations are integrated sample by sample (each step needs the last), and
the simulator evaluates the cylinder four times per Runge-Kutta step, so these loops and kernels
are compiled (numba, cached on disk). The physics and its corrections to the paper's equations
are documented where the models are defined: :mod:`flumekit.flap.friction` (Brito et al. 2020,
Appendix B) and :mod:`flumekit.flap.simulator` (Eqs. 12-14). The PTO kernels have the
signatures of :mod:`flumekit.hydro.stepping` and take their parameters as one float array
(:func:`cylinder_params`).

This module imports numba; :mod:`flumekit.flap` imports it only inside the functions that run
a loop.

%(references_brito2020)s, Eqs. (12)-(14) and Appendix B.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from flumekit.docstrings import fill, filler
from flumekit.hydro.stepping import ACCEL, ADVANCE, PREDICT

#: docstring text that several functions of this module share
_doc = filler(
    c=("c : ndarray\n"
       "    Parameters from :func:`flumekit.flap.friction.kernel_constants`."),
    step=("dt : float\n"
          "    Step [s]."),
    h=("h : float\n"
       "    Film thickness parameter [-]."),
    z=("z : float\n"
       "    Bristle deflection [m]."))

__doc__ = fill(__doc__)

#: the friction kernels divide only by validated positive parameters (σ0, the film time
#: constants, g ≥ F_c > 0) and by v0 − v1 across a reversal: IEEE division without numba's
#: zero-division checks (about 12 % of the friction loop), the same numbers
_FRICTION_ERRORS = "numpy"

__all__ = ["cylinder_accel", "cylinder_advance", "cylinder_params", "cylinder_predict",
           "film_factors", "friction_loop", "lugre_advance", "lugre_force", "lugre_step", "rotate"]


#: film factors not known in advance: each step computes its own (:func:`film_factors`)
_FILM_PER_STEP = (math.nan, math.nan, math.nan)


@_doc
@njit(cache=True, error_model=_FRICTION_ERRORS)
def lugre_step(z, h, v, dt, c):
    """Take one exact frozen-velocity step of Eqs. (A4) and (A6).

    Parameters
    ----------
    %(z)s
    %(h)s
    v : float
        Rod velocity, frozen over the step [m s-1].
    %(step)s
    %(c)s

    Returns
    -------
    z, h : float
        The state at the end of the step.
    """
    return _lugre_step(z, h, v, dt, c, _FILM_PER_STEP)


@njit(cache=True, error_model=_FRICTION_ERRORS)
def film_factors(dt, c):
    """Return the film's decay over half a step, exp(-dt / (2 τ)), for τ_hp, τ_hm and τ_h0.

    What :func:`lugre_step` computes at every step: a loop of steps of one ``dt`` [s] computes
    them once (``c`` the parameters of :func:`flumekit.flap.friction.kernel_constants`).
    """
    return (math.exp(-0.5 * dt / c[10]), math.exp(-0.5 * dt / c[11]),
            math.exp(-0.5 * dt / c[12]))


@njit(cache=True, error_model=_FRICTION_ERRORS)
def _lugre_step(z, h, v, dt, c, film):
    """:func:`lugre_step` with the film factors of ``dt`` (:func:`film_factors`), NaN: not known."""
    s0, fc, fs, ivs, n = c[0], c[3], c[4], c[5], c[6]
    vb, kf, hmax, thp, thm, th0 = c[7], c[8], c[9], c[10], c[11], c[12]
    a = abs(v)
    # film state, Eqs. (A6)-(A8): exact exponential towards h_ss for frozen v
    if a == 0.0:
        hss, tau, j = 0.0, th0, 2
    else:
        hss = kf * a ** (2.0 / 3.0) if a < vb else hmax
        tau, j = (thp, 0) if h <= hss else (thm, 1)
    eh = film[j]
    if eh != eh:  # not known in advance
        eh = math.exp(-0.5 * dt / tau)
    if a == 0.0:  # dwell: the bristles hold their deflection
        return z, hss + (h - hss) * eh * eh
    hmid = hss + (h - hss) * eh
    x = a * ivs
    g = fc + ((1.0 - hmid) * fs - fc) * math.exp(-(x if n == 1.0 else x ** n))
    zss = g / s0 if v > 0 else -g / s0  # steady deflection for this v
    # Eq. (A4) for frozen v: dz/dt = r (z_ss - z), r = s0 |v| / g
    return zss + (z - zss) * math.exp(-s0 * a / g * dt), hss + (h - hss) * eh * eh


@_doc
@njit(cache=True, error_model=_FRICTION_ERRORS)
def lugre_advance(z, h, v0, v1, dt, c):
    """Advance the state for a velocity linear from ``v0`` to ``v1`` over ``dt``.

    The step is split at a velocity reversal, else taken at the mid-step velocity
    (:func:`lugre_step`).

    Parameters
    ----------
    %(z)s
    %(h)s
    v0, v1 : float
        Rod velocity at the start and end of the step [m s-1].
    %(step)s
    %(c)s

    Returns
    -------
    z, h : float
        The state at the end of the step ([m], [-]).
    """
    return _lugre_advance(z, h, v0, v1, dt, c, _FILM_PER_STEP)


@njit(cache=True, error_model=_FRICTION_ERRORS)
def _lugre_advance(z, h, v0, v1, dt, c, film):
    """:func:`lugre_advance` with the film factors of ``dt`` (:func:`film_factors`)."""
    if v0 * v1 < 0.0:  # steps of other lengths: their film factors are their own
        s = v0 / (v0 - v1)
        z, h = lugre_step(z, h, 0.5 * v0, s * dt, c)
        return lugre_step(z, h, 0.5 * v1, (1.0 - s) * dt, c)
    return _lugre_step(z, h, 0.5 * (v0 + v1), dt, c, film)


@njit(cache=True, error_model=_FRICTION_ERRORS)
def lugre_force(z, h, v, c):
    """Compute the friction force F = σ0 z + σ1 ż + σ2 v [N] (Eq. A3, corrected Eq. A5).

    At the state (z [m], h [-]) and rod velocity v [m s-1]; ``c`` the parameters of
    :func:`flumekit.flap.friction.kernel_constants`.
    """
    s0, s1, s2, fc, fs, ivs, n = c[0], c[1], c[2], c[3], c[4], c[5], c[6]
    x = abs(v) * ivs
    g = fc + ((1.0 - h) * fs - fc) * math.exp(-(x if n == 1.0 else x ** n))  # Eq. (A5)
    return s0 * z + s1 * (v - s0 * abs(v) * z / g) + s2 * v  # Eqs. (A3)-(A4)


@njit(cache=True, error_model=_FRICTION_ERRORS)
def friction_loop(v, dt, z, h, substeps, c, zs, hs):
    """Integrate the state over a velocity series (:func:`flumekit.flap.friction.friction_series`).

    ``substeps`` steps of :func:`lugre_advance` per sampling interval ``dt`` [s] from the
    initial state (z [m], h [-]); the state at every sample is written into ``zs`` and ``hs``.
    """
    zs[0], hs[0] = z, h
    hsub = dt / substeps
    film = film_factors(hsub, c)  # every step but the split ones at reversals is hsub long
    for k in range(1, v.size):
        v0, dv = v[k - 1], (v[k] - v[k - 1]) / substeps
        if substeps == 1:
            z, h = _lugre_advance(z, h, v0, v[k], dt, c, film)
        else:
            for j in range(substeps):
                z, h = _lugre_advance(z, h, v0 + j * dv, v0 + (j + 1) * dv, hsub, c, film)
        zs[k], hs[k] = z, h


@njit(cache=True)
def rotate(x0, z0, theta, x, z):
    """Rotate the point (x0, z0) [m] about the origin by each angle of ``theta`` [rad].

    Writes x0 cos θ + z0 sin θ into ``x`` and −x0 sin θ + z0 cos θ into ``z`` (1-D arrays of
    the size of ``theta``): the sine and cosine of one angle computed together, which costs
    less than two passes of numpy's, with the same numbers
    (:func:`flumekit.flap.geometry.flap_point`).
    """
    for i in range(theta.size):
        c, s = math.cos(theta[i]), math.sin(theta[i])
        x[i] = x0 * c + z0 * s
        z[i] = -x0 * s + z0 * c


# --- the hydraulic cylinder (flumekit.flap.simulator.HydraulicCylinder) ----------------------
# layout of the parameter array: scalars, the 13 friction constants, the lever-arm table
_TH_LO, _INV_DTH, _N_TAB, _S_COMP, _AREA, _KP, _IP, _J0, _PCAV, _FRICTION, _DT = range(11)
_C = 11  # friction constants
_TAB = _C + 13  # lever arms m(θ) at the table's nodes, then their differences


def cylinder_params(theta_lo: float, dtheta: float, lever: np.ndarray, bore_area: float,
                    pressure_loss_coefficient: float, fluid_inertia: float, inertia: float,
                    cavitation_pressure: float, friction: np.ndarray | None,
                    dt: float) -> np.ndarray:
    """Pack the parameters of the cylinder's kernels into one array.

    Parameters
    ----------
    theta_lo, dtheta : float
        First node and spacing of the lever-arm table [rad].
    lever : ndarray
        Signed lever arm m(θ) [m] at the table's nodes.
    bore_area : float
        A [m2].
    pressure_loss_coefficient, fluid_inertia : float
        K_p [Pa s2 rad-2] and I_p [Pa s2 rad-1] of Eq. (13).
    inertia : float
        I + A∞ [kg m2].
    cavitation_pressure : float
        P_v − P_atm [Pa] (the gauge pressure of the vapour clamp, Eq. 14).
    friction : ndarray or None
        :func:`flumekit.flap.friction.kernel_constants`, or None without friction.
    dt : float
        Simulator step [s].

    Returns
    -------
    ndarray
        The parameters in the layout of this module.
    """
    lever = np.asarray(lever, dtype=float)
    n_tab = lever.size - 1
    # Eq. (13) sign: +1 if θ̇ > 0 compresses the chamber (lever arm m < 0)
    s_comp = -1.0 if lever[n_tab // 2] > 0 else 1.0
    head = [theta_lo, 1.0 / dtheta, n_tab, s_comp, bore_area, pressure_loss_coefficient,
            fluid_inertia, inertia, cavitation_pressure, friction is not None, dt]
    fr = np.zeros(13) if friction is None else np.asarray(friction, dtype=float)
    return np.concatenate([np.array(head, dtype=float), fr, lever, np.diff(lever)])


@njit(cache=True)
def _lever(th, p):
    """m(θ) [m], linear in the table; NaN outside it."""
    u = (th - p[_TH_LO]) * p[_INV_DTH]
    n_tab = int(p[_N_TAB])
    if not (u > -1.0 and u < n_tab):  # int() truncates towards zero, as the table's index
        return math.nan
    i = int(u)
    return p[_TAB + i] + (u - i) * p[_TAB + n_tab + 1 + i]


@njit(ACCEL, cache=True)
def cylinder_accel(t, th, om, rest, z, hl, p):
    """Compute θ̈ [rad s-2] with the fluid inertia and the vapour clamp (Eqs. 12-14).

    Returns (θ̈, the chamber pressure [Pa], the friction force [N]); NaN outside the lever-arm
    table.
    """
    m = _lever(th, p)
    if m != m:
        return math.nan, math.nan, math.nan
    ff = 0.0
    if p[_FRICTION] != 0.0:
        ff = lugre_force(z, hl, m * om, p[_C:_TAB])  # Eq. (A3), resisting the rod rate m θ̇
        rest -= m * ff  # resisting friction torque T_f = m F_f
    s_comp, area, kp, ip, j0 = p[_S_COMP], p[_AREA], p[_KP], p[_IP], p[_J0]
    g = -m * s_comp * area  # > 0
    q = om * abs(om)
    a = (rest - g * kp * q) / (j0 + g * ip)
    pr = s_comp * (kp * q + ip * a)  # Eq. (13), signed form, no cavitation
    if pr < p[_PCAV]:  # Eq. (14) with σ_c = 0: clamp at the vapour pressure
        pr = p[_PCAV]
        a = (rest + m * area * pr) / j0
    return a, pr, ff


@njit(PREDICT, cache=True)
def cylinder_predict(z, hl, th, om, a1, p):
    """Predict the LuGre state at the stage times (middle and end of the step).

    Exact frozen-velocity steps at the rod velocities predicted at h/4 and 3h/4 from the first
    stage.
    """
    dt = p[_DT]
    hh, hq = 0.5 * dt, 0.25 * dt
    c = p[_C:_TAB]
    zm, hm = lugre_step(z, hl, _lever(th + hq * om, p) * (om + hq * a1), hh, c)
    ze, he = lugre_step(zm, hm, _lever(th + 3 * hq * om, p) * (om + 3 * hq * a1), hh, c)
    return zm, hm, ze, he


@njit(ADVANCE, cache=True)
def cylinder_advance(z, hl, th, om, th_new, om_new, p):
    """Advance the LuGre state over the step from the rod velocities (split at a reversal)."""
    return lugre_advance(z, hl, _lever(th, p) * om, _lever(th_new, p) * om_new, p[_DT],
                         p[_C:_TAB])
