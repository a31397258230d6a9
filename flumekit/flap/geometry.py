"""Geometry of the PTO cylinder between the bed and the flap (Brito et al. 2020, §2.2, Eq. 12).

Coordinates: hinge at the origin, x towards the beach, z up; θ > 0 leans the flap towards the
beach, so a point (x0, z0) of the flap at θ = 0 moves to

    p(θ) = (x0 cos θ + z0 sin θ, −x0 sin θ + z0 cos θ).

The cylinder joins the fixed bed anchor b = (1.04, 0) m to the flap anchor p(θ), p(0) =
(0.09, 0.47) m. With u = (p − b)/ℓ the unit vector along the rod (bed to flap), ℓ the rod
length, an extending rod force F (pushing the flap away from the bed anchor) exerts about the
hinge the torque (positive towards the beach)

    T = m F,   m = p_z u_x − p_x u_z,   |m| = r sin β,

where r = |p| is the distance from the hinge to the flap anchor and β the angle between the rod
and the hinge-to-anchor line. Eq. (12) as printed, T_p = F_p sin β, omits the lever arm r: a
torque is a force times a lever arm. The figure's β is drawn between the rod and the flap; the
anchor sits 0.09 m off the flap's centre plane (on its beach face), so the exact lever is the
hinge-to-anchor line, which differs from the flap plane by the constant angle atan(0.09/0.47) =
10.8°; we define β against the hinge-to-anchor line so that |m| = r sin β holds exactly.
The signed lever arm m is also the rod's kinematic ratio (virtual work): ℓ̇ = m θ̇.
For the default campaign m ≈ −0.46 m: leaning to the beach shortens the rod (compression).

%(references_brito2020)s, §2.2, Eq. (12).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from flumekit.docstrings import fill, filler
from flumekit.errors import GeometryError

#: docstring text that several functions of this module share
_doc = filler(
    parameters_anchors=("Parameters\n"
                        "----------\n"
                        "%(bed_anchor)s\n"
                        "%(flap_anchor)s"),
    bed_anchor=("bed_anchor : array_like\n"
                "    Fixed rod anchor (x, z) [m]."),
    flap_anchor=("flap_anchor : array_like\n"
                 "    Rod anchor on the flap at θ = 0, (x, z) [m]."))

__doc__ = fill(__doc__)

#: smallest |lever arm| [m] accepted: below this the rod line passes (almost) through the hinge
_MIN_LEVER = 1e-6


def _point(name: str, p) -> np.ndarray:
    a = np.asarray(p, dtype=float)
    if a.shape != (2,) or not np.all(np.isfinite(a)):
        raise GeometryError(f"{name} must be a finite (x, z) pair in metres, got {p!r}")
    return a


@_doc
def check_anchors(bed_anchor, flap_anchor) -> tuple[np.ndarray, np.ndarray]:
    """Validate the anchors of the PTO cylinder.

    %(parameters_anchors)s

    Returns
    -------
    bed_anchor, flap_anchor : numpy.ndarray
        The anchors as float arrays of shape (2,) [m].

    Raises
    ------
    flumekit.errors.GeometryError
        An impossible cylinder: an anchor not a finite (x, z) pair or at the hinge, or the two
        anchors coinciding.

    Examples
    --------
    >>> from flumekit.flap.geometry import check_anchors
    >>> check_anchors((1.04, 0.0), (0.09, 0.47))[1].tolist()
    [0.09, 0.47]
    """
    b = _point("bed anchor", bed_anchor)
    p = _point("flap anchor", flap_anchor)
    if np.hypot(*p) <= _MIN_LEVER:
        raise GeometryError("the flap anchor of the PTO rod is at the hinge: the rod has no "
                            "lever arm")
    if np.hypot(*b) <= _MIN_LEVER:
        raise GeometryError("the bed anchor of the PTO rod is at the hinge: the rod line "
                            "always passes through the hinge and exerts no torque")
    if np.hypot(*(p - b)) <= _MIN_LEVER:
        raise GeometryError(f"the PTO anchors coincide at ({b[0]:g}, {b[1]:g}) m: the rod has no "
                            "length")
    return b, p


def flap_point(point, theta) -> tuple[np.ndarray, np.ndarray]:
    """Rotate a flap point to the flap angle θ about the hinge.

    Parameters
    ----------
    point : array_like
        The point (x0, z0) at θ = 0 [m].
    theta : array_like
        Flap angle θ [rad], positive towards the beach.

    Returns
    -------
    x, z : numpy.ndarray
        Position at θ [m].

    Raises
    ------
    flumekit.errors.GeometryError
        ``point`` is not a finite (x, z) pair.

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.flap.geometry import flap_point
    >>> x, z = flap_point((0.0, 1.0), np.pi / 2)  # the top of the flap, laid towards the beach
    >>> round(float(x), 12), round(float(z), 12)
    (1.0, 0.0)
    """
    from flumekit.flap.kernels import rotate

    x0, z0 = _point("flap point", point)
    th = np.asarray(theta, dtype=float)
    x, z = np.empty(th.shape), np.empty(th.shape)
    rotate(float(x0), float(z0), np.ascontiguousarray(th).reshape(-1), x.reshape(-1),
           z.reshape(-1))
    return x[()], z[()]


@dataclass(frozen=True)
class RodKinematics:
    """Rod length, extension rate, angle to the lever and signed lever arm (numpy arrays).

    What :func:`rod_kinematics` returns.

    Attributes
    ----------
    length : numpy.ndarray
        Rod length ℓ [m].
    velocity : numpy.ndarray
        Extension rate ℓ̇ = m θ̇ [m s-1], positive when the rod extends.
    beta : numpy.ndarray
        Angle β between the rod and the hinge-to-anchor line, in (0, π) [rad].
    lever_arm : numpy.ndarray
        Signed lever arm m [m]: the torque towards the beach per newton of extending force,
        abs(m) = r sin β.

    Examples
    --------
    A right-angled layout: the bed anchor 1 m towards the beach, the flap anchor 1 m above
    the hinge. The rod is the hypotenuse √2 m at 45° to the flap; the lever arm is
    r sin β = 1/√2 m, negative as an extending rod pushes the flap towards the wavemaker;
    leaning to the beach at 0.2 rad/s shortens the rod at m θ̇:

    >>> import numpy as np
    >>> from flumekit.flap.geometry import rod_kinematics
    >>> rod = rod_kinematics(0.0, 0.2, (1.0, 0.0), (0.0, 1.0))
    >>> round(float(rod.length), 4), round(float(np.degrees(rod.beta)), 6)
    (1.4142, 45.0)
    >>> round(float(rod.lever_arm), 4), round(float(rod.velocity), 4)
    (-0.7071, -0.1414)
    """

    length: np.ndarray  # ℓ [m]
    velocity: np.ndarray  # ℓ̇, positive when the rod extends [m s-1]
    beta: np.ndarray  # angle between the rod and the hinge-to-anchor line, in (0, π) [rad]
    lever_arm: np.ndarray  # signed m: torque towards the beach per newton of extending force [m]


@_doc
def rod_kinematics(theta, theta_dot, bed_anchor, flap_anchor) -> RodKinematics:
    """Rod kinematics for a flap motion (see the module notes for the conventions).

    Parameters
    ----------
    %(theta)s
    %(theta_dot)s
    %(bed_anchor)s
    %(flap_anchor)s

    Returns
    -------
    RodKinematics
        Rod length ℓ [m], extension rate ℓ̇ [m s-1], angle β to the hinge-to-anchor line [rad]
        and signed lever arm m [m], each the shape of ``theta``.

    Raises
    ------
    flumekit.errors.GeometryError
        Coinciding anchors, an anchor at the hinge, or a flap angle at which the anchors
        coincide or the rod line passes through the hinge (no torque can be transmitted, and
        the torque inversion would divide by zero).

    %(references_brito2020)s, §2.2, Eq. (12).

    Examples
    --------
    >>> from flumekit.flap.geometry import rod_kinematics
    >>> k = rod_kinematics(0.0, 1.0, (1.04, 0.0), (0.09, 0.47))
    >>> round(float(k.length), 4), round(float(k.lever_arm), 4)
    (1.0599, -0.4612)
    """
    b, p0 = check_anchors(bed_anchor, flap_anchor)
    th = np.asarray(theta, dtype=float)
    px, pz = flap_point(p0, th)
    dx, dz = px - b[0], pz - b[1]
    length = np.hypot(dx, dz)
    if np.any(length <= _MIN_LEVER):
        raise GeometryError("the PTO anchors coincide at some flap angle: rod length zero at "
                            f"theta = {float(th.flat[np.argmin(length)]):.4g} rad")
    ux, uz = dx / length, dz / length
    lever = pz * ux - px * uz
    if np.any(np.abs(lever) <= _MIN_LEVER):
        raise GeometryError("the PTO rod line passes through the hinge at theta = "
                            f"{float(th.flat[np.argmin(np.abs(lever))]):.4g} rad: no lever arm")
    r = np.hypot(*p0)
    # angle between the rod (direction u) and the hinge-to-anchor line (direction p/r)
    beta = np.arccos(np.clip((px * ux + pz * uz) / r, -1.0, 1.0))
    return RodKinematics(length=length, velocity=lever * np.asarray(theta_dot, dtype=float),
                         beta=beta, lever_arm=lever)


@_doc
def rod_length_limits(bed_anchor, flap_anchor) -> tuple[float, float]:
    """Return the shortest and longest rod lengths that the anchors allow over a full turn.

    %(parameters_anchors)s

    Returns
    -------
    shortest, longest : float
        abs(d − r) and d + r [m], with d and r the anchors' distances from the hinge.

    Raises
    ------
    flumekit.errors.GeometryError
        Impossible anchors (:func:`check_anchors`).

    Examples
    --------
    >>> from flumekit.flap.geometry import rod_length_limits
    >>> [float(v) for v in rod_length_limits((1.0, 0.0), (0.0, 0.5))]
    [0.5, 1.5]
    """
    b, p0 = check_anchors(bed_anchor, flap_anchor)
    d, r = np.hypot(*b), np.hypot(*p0)
    return abs(d - r), d + r


@_doc
def angle_from_rod_length(rod_length, bed_anchor, flap_anchor) -> np.ndarray:
    """Compute the flap angle θ on the branch through θ = 0 for a given rod length ℓ.

    The anchors lie on circles of radius d = abs(b) and r = abs(p) about the hinge, so
    ℓ² = d² + r² − 2 d r cos(α − α_b) with α the polar angle of the flap anchor; the branch is
    the one containing θ = 0.

    Parameters
    ----------
    rod_length : array_like
        Rod length ℓ [m].
    %(bed_anchor)s
    %(flap_anchor)s

    Returns
    -------
    numpy.ndarray
        θ [rad], positive towards the beach.

    Raises
    ------
    flumekit.errors.GeometryError
        A rod shorter than abs(d − r) or longer than d + r (no configuration of the anchors
        gives that length), impossible anchors, or a flap anchor on the line through the hinge
        and the bed anchor at θ = 0 (the sign of θ is undetermined).

    Examples
    --------
    The inverse of :func:`rod_kinematics`' length:

    >>> from flumekit.flap.geometry import angle_from_rod_length, rod_kinematics
    >>> ell = rod_kinematics([-0.1, 0.2], 0.0, (1.04, 0.0), (0.09, 0.47)).length
    >>> angle_from_rod_length(ell, (1.04, 0.0), (0.09, 0.47)).round(12)
    array([-0.1,  0.2])
    """
    b, p0 = check_anchors(bed_anchor, flap_anchor)
    ell = np.asarray(rod_length, dtype=float)
    lo, hi = rod_length_limits(b, p0)
    if (np.any(~np.isfinite(ell)) or np.any(ell < lo * (1 - 1e-12))
            or np.any(ell > hi * (1 + 1e-12))):
        raise GeometryError(f"rod length outside [{lo:.6g}, {hi:.6g}] m allowed by the anchors "
                            f"(got {np.nanmin(ell):.6g} to {np.nanmax(ell):.6g} m)")
    d, r = np.hypot(*b), np.hypot(*p0)
    # polar angle of the flap anchor relative to the bed anchor's, at θ = 0, in (−π, π]
    rel0 = float(np.angle(np.exp(1j * (np.arctan2(p0[1], p0[0]) - np.arctan2(b[1], b[0])))))
    if rel0 == 0.0 or abs(rel0) == np.pi:
        raise GeometryError("the flap anchor is on the line through the hinge and the bed anchor "
                            "at theta = 0: the rod length does not determine the sign of theta")
    cos_rel = np.clip((d**2 + r**2 - ell**2) / (2 * d * r), -1.0, 1.0)
    # the relative angle falls by θ (rotation towards +x is clockwise in the x-z plane); the
    # branch through θ = 0 keeps the sign of rel0
    return rel0 - np.sign(rel0) * np.arccos(cos_rel)
