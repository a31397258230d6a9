"""Torque balance about the hinge (Brito et al. 2020, Eqs. 11-12).

    T_h = I θ̈ + T_g + T_PTO,     T_PTO = T_p + T_f                    Eqs. (11)-(12)

All torques are about the hinge axis. T_h is the hydrodynamic torque acting on the flap
(positive towards the beach); T_g and T_PTO are *resisting* torques, positive when they oppose a
positive θ (that is how they enter Eq. 11, I θ̈ = T_h − T_g − T_PTO).

Gravity and buoyancy. The flap's weight m g at the centre of mass (height z_g = 0.33 m above the
hinge) and the buoyancy ρ g V at the centre of buoyancy (height z_b) rotate rigidly with the
flap, so for a rigid, fully submerged body both torques are exactly proportional to sin θ:

    T_g = (ρ g V z_b − m g z_g) sin θ = C sin θ,

with C the net buoyancy stiffness, C = 605 N m rad-1 for this flap (Appendix A; with
m g z_g = 234 N m the buoyancy moment ρ g V z_b is 839 N m). The flap pierces the surface, so its
submerged volume and z_b change with θ; that correction is of relative order θ²/2 on the
buoyancy part (under 2 % at 0.2 rad) and is neglected, as in the linear model of Appendix A.

PTO torques. F_p = A P_int pushes the rod out, the LuGre friction force F_f resists the rod's
extension rate, so the net extending force is F_p − F_f and its torque on the flap is
m (F_p − F_f) with m the signed lever arm of :mod:`flumekit.flap.geometry` (|m| = r sin β,
the lever arm that Eq. 12 omits). As resisting torques: T_p = −m F_p, T_f = +m F_f.

%(references_brito2020)s, Eqs. (11)-(12) and Appendix A.
"""

from __future__ import annotations

import numpy as np

from flumekit.docstrings import fill, filler

#: docstring text that several functions of this module share
_doc = filler(
    raises_inertia=("Raises\n"
                    "------\n"
                    "ValueError\n"
                    "    A non-positive moment of inertia."),
    flap_angle=("theta : array_like\n"
                "    Flap angle [rad]."),
    lever_arm=("lever_arm : array_like\n"
               "    Signed lever arm m of the rod about the hinge [m], abs(m) = r sin β "
               "(:mod:`flumekit.flap.geometry`)."))

__doc__ = fill(__doc__)


@_doc
def gravity_torque(theta, buoyancy_stiffness: float) -> np.ndarray:
    """Compute the net gravity-buoyancy resisting torque T_g = C sin θ.

    Parameters
    ----------
    %(flap_angle)s
    buoyancy_stiffness : float
        Net buoyancy stiffness C = ρ g V z_b − m g z_g [N m rad-1].

    Returns
    -------
    numpy.ndarray
        T_g [N m], positive when it opposes a positive θ.

    %(references_brito2020)s, Eq. (11) and Appendix A.

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.flap.torque import gravity_torque
    >>> float(gravity_torque(np.pi / 6, 605.0))
    302.4...
    """
    return buoyancy_stiffness * np.sin(np.asarray(theta, dtype=float))


@_doc
def inertia_torque(theta_ddot, inertia: float) -> np.ndarray:
    """Compute the inertia torque I θ̈ of the flap.

    Parameters
    ----------
    theta_ddot : array_like
        Angular acceleration θ̈ [rad s-2].
    inertia : float
        The flap's moment of inertia about the hinge I [kg m2], > 0.

    Returns
    -------
    numpy.ndarray
        I θ̈ [N m].

    %(raises_inertia)s

    %(references_brito2020)s, Eq. (11).

    Examples
    --------
    >>> from flumekit.flap.torque import inertia_torque
    >>> inertia_torque([0.5, -1.0], 14.74)
    array([  7.37, -14.74])
    """
    if not inertia > 0:
        raise ValueError(f"moment of inertia must be > 0, got {inertia}")
    return inertia * np.asarray(theta_ddot, dtype=float)


@_doc
def pressure_torque(force_pressure, lever_arm) -> np.ndarray:
    """Compute the resisting torque of the cylinder pressure force, T_p = −m F_p.

    Eq. (12) with the lever arm that the paper leaves out. Where m < 0, a chamber pressure that
    pushes the rod out resists a positive θ.

    Parameters
    ----------
    force_pressure : array_like
        Pressure force pushing the rod out, A P_int [N].
    %(lever_arm)s

    Returns
    -------
    numpy.ndarray
        T_p [N m], positive when it opposes a positive θ.

    See Also
    --------
    flumekit.flap.pressure.pressure_force : F_p from the chamber pressure.
    flumekit.flap.geometry.rod_kinematics : The signed lever arm m along θ.

    %(references_brito2020)s, Eq. (12).

    Examples
    --------
    >>> from flumekit.flap.torque import pressure_torque
    >>> float(pressure_torque(100.0, -0.2))
    20.0
    """
    return -np.asarray(lever_arm, dtype=float) * np.asarray(force_pressure, dtype=float)


@_doc
def friction_torque(force_friction, lever_arm) -> np.ndarray:
    """Compute the resisting torque of the cylinder friction force, T_f = m F_f.

    Eq. (12) with the lever arm that the paper leaves out. Sliding friction opposes the rod's
    motion, so T_f opposes θ̇ whatever the sign of m.

    Parameters
    ----------
    force_friction : array_like
        Friction force resisting the rod's extension (> 0 while extending) [N].
    %(lever_arm)s

    Returns
    -------
    numpy.ndarray
        T_f [N m], positive when it opposes a positive θ; its power T_f θ̇ is a loss over a cycle.

    See Also
    --------
    flumekit.flap.friction.friction_series : F_f of the LuGre model along a rod velocity.

    %(references_brito2020)s, Eq. (12).

    Examples
    --------
    With m < 0, a positive θ̇ shortens the rod, so friction pushes it out (F_f < 0); the
    second value is the return stroke:

    >>> from flumekit.flap.torque import friction_torque
    >>> friction_torque([-30.0, 30.0], -0.2)
    array([ 6., -6.])
    """
    return np.asarray(lever_arm, dtype=float) * np.asarray(force_friction, dtype=float)


@_doc
def hydrodynamic_torque(theta, theta_ddot, torque_pto, *, inertia: float,
                        buoyancy_stiffness: float,
                        torque_gravity=None) -> np.ndarray:
    """Compute the hydrodynamic torque on the flap, T_h = I θ̈ + T_g + T_PTO (Eq. 11).

    Parameters
    ----------
    %(flap_angle)s
    theta_ddot : array_like
        Angular acceleration [rad s-2].
    torque_pto : array_like
        Resisting PTO torque T_p + T_f [N m].
    inertia : float
        Moment of inertia about the hinge [kg m2].
    buoyancy_stiffness : float
        Net buoyancy stiffness C [N m rad-1].
    torque_gravity : array_like, optional
        :func:`gravity_torque` of ``theta`` and ``buoyancy_stiffness`` [N m], when the caller
        has it (the flap analysis stores it as a series of its own).

    Returns
    -------
    numpy.ndarray
        T_h [N m], positive towards the beach.

    %(raises_inertia)s

    %(references_brito2020)s, Eq. (11).

    Examples
    --------
    >>> from flumekit.flap.torque import hydrodynamic_torque
    >>> float(hydrodynamic_torque(0.0, 2.0, 5.0, inertia=10.0, buoyancy_stiffness=605.0))
    25.0
    """
    # Eq. (11) in Brito et al. 2020
    if torque_gravity is None:
        torque_gravity = gravity_torque(theta, buoyancy_stiffness)
    return (inertia_torque(theta_ddot, inertia) + np.asarray(torque_gravity, dtype=float)
            + np.asarray(torque_pto, dtype=float))
