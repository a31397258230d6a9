"""Flap angle from the wire encoder (Brito et al. 2020, §2.3, Eq. 1).

Geometry (our coordinates: x = 0 at the hinge, positive towards the beach; z = 0 at the hinge
axis; θ > 0 when the flap leans towards the beach). The encoder sits on the wavemaker side at
(−L7, L5) = (−1.48, 1.53) m; its wire runs horizontally to an anchor on the flap's vertical frame
at height L5 above the hinge, (0, L5) at θ = 0 and (L5 sin θ, L5 cos θ) at θ. The wire length is

    L(θ)² = (L7 + L5 sin θ)² + (L5 cos θ − L5)² = L7² + [2 L5 sin(θ/2)]² + 2 L7 L5 sin θ.

Eq. (1) as printed has −2 L7 L5 sin θ: that is the same geometry with θ positive towards the
wavemaker (the encoder's side), or with ΔL7 an extension rather than a shortening. With θ > 0
towards the beach the anchor moves away from the encoder and the wire pays out, so the plain
geometry above (+2 L7 L5 sin θ) is the consistent form for our conventions; it is what we
implement, with the wire shortening ΔL7 = L7 − L(θ) (negative when the flap leans to the beach).

Closed form: with 2 L5²(1 − cos θ) = [2 L5 sin(θ/2)]²,

    2 L7 L5 sin θ − 2 L5² cos θ = L² − L7² − 2 L5²,   i.e.   R cos(θ − φ) = c,

with R = 2 L5 √(L7² + L5²), φ = atan2(2 L7 L5, −2 L5²) ∈ (π/2, π) and c = L² − L7² − 2 L5².
θ = 0 lies on the branch θ − φ ∈ (−π, 0), on which L(θ) increases monotonically, so

    θ = φ − arccos(c / R),   valid for θ ∈ (φ − π, φ) = (−atan(L7/L5), π − atan(L7/L5)),

which covers any physical flap motion. Samples with |c/R| > 1 have no solution (a wire shorter
or longer than the geometry allows: glitch, wrong zero or wrong L5/L7); they are flagged.

%(references_brito2020)s, §2.3, Eq. (1).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from flumekit.docstrings import doc, fill
from flumekit.errors import GeometryError

__doc__ = fill(__doc__)


class WireAngle(NamedTuple):
    """Flap angle from the wire and the flag of samples outside the domain of Eq. (1).

    What :func:`angle_from_wire` returns.

    Attributes
    ----------
    theta : numpy.ndarray
        Flap angle θ [rad], positive towards the beach; the flagged samples hold the nearest
        end of the branch (never NaN).
    out_of_domain : numpy.ndarray of bool
        True where the wire length has no flap angle (abs(c/R) > 1 in Eq. (1)).

    Examples
    --------
    0.1 m of wire reeled in (the flap leans towards the wavemaker, θ < 0), then a glitch of
    2 m, more than the 1.48 m of wire there is: its angle is clipped, and flagged:

    >>> from flumekit.flap.encoder import angle_from_wire
    >>> theta, flagged = angle_from_wire([0.1, 2.0], 1.53, 1.48)
    >>> theta.round(4).tolist(), flagged.tolist()
    ([-0.0654, -0.7688], [False, True])
    """

    theta: np.ndarray  # flap angle [rad]; flagged samples hold the nearest end of the branch
    out_of_domain: np.ndarray  # bool, True where |c/R| > 1


def _check_lengths(L5: float, L7: float) -> None:
    for name, value in (("L5", L5), ("L7", L7)):
        if not (np.isfinite(value) and value > 0):
            raise GeometryError(f"encoder length {name} must be finite and > 0, got {value} m")


@doc
def wire_length(theta, L5: float, L7: float) -> np.ndarray:
    """Compute the wire length L(θ) between the encoder and the flap frame.

    Eq. (1) of Brito et al. (2020), with the sign for θ > 0 towards the beach.

    Parameters
    ----------
    %(theta)s
    L5 : float
        Height of the wire anchor above the hinge [m].
    L7 : float
        Wire length at θ = 0 (horizontal distance from the encoder to the flap frame) [m].

    Returns
    -------
    numpy.ndarray
        L(θ) [m].

    Raises
    ------
    flumekit.errors.GeometryError
        L5 or L7 not finite and positive.

    %(references_brito2020)s, Eq. (1).

    Examples
    --------
    >>> from flumekit.flap.encoder import wire_length
    >>> wire_length([0.0, 0.1], 1.53, 1.48).round(4)
    array([1.48  , 1.6328])
    """
    _check_lengths(L5, L7)
    th = np.asarray(theta, dtype=float)
    # Eq. (1) in Brito et al. 2020, with +2 L7 L5 sin θ (see the module notes)
    return np.sqrt(L7**2 + (2 * L5 * np.sin(th / 2)) ** 2 + 2 * L7 * L5 * np.sin(th))


@doc
def angle_from_wire(wire_shortening, L5: float, L7: float) -> WireAngle:
    """Compute the flap angle θ from the wire shortening ΔL7, Eq. (1) in closed form.

    Parameters
    ----------
    wire_shortening : array_like
        ΔL7 = L7 − L, shortening of the measuring wire [m] (positive when the
        wire is reeled in, i.e. the flap leans towards the encoder and the wavemaker).
    L5 : float
        Height of the wire anchor above the hinge [m], > 0.
    L7 : float
        Wire length at θ = 0 [m], > 0.

    Returns
    -------
    WireAngle
        ``theta``: θ [rad] (positive towards the beach); ``out_of_domain``: boolean flag of
        the samples whose argument c/R leaves [−1, 1]; there θ is clipped to the end of the
        branch (never NaN), so callers must look at the flag.

    Raises
    ------
    flumekit.errors.GeometryError
        L5 or L7 not finite and positive.
    ValueError
        Non-finite samples of the wire shortening.

    %(references_brito2020)s, Eq. (1).

    Examples
    --------
    The inverse of :func:`wire_length`:

    >>> from flumekit.flap.encoder import angle_from_wire, wire_length
    >>> shortening = 1.48 - wire_length([-0.05, 0.1], 1.53, 1.48)
    >>> angle_from_wire(shortening, 1.53, 1.48).theta.round(12)
    array([-0.05,  0.1 ])
    """
    _check_lengths(L5, L7)
    s = np.asarray(wire_shortening, dtype=float)
    if not np.all(np.isfinite(s)):
        raise ValueError("angle_from_wire: the wire shortening has non-finite samples")
    length = L7 - s
    # R cos(θ − φ) = c, from Eq. (1) in Brito et al. 2020 (sign corrected, see module notes)
    R = 2.0 * L5 * np.hypot(L7, L5)
    phi = np.arctan2(2.0 * L7 * L5, -2.0 * L5**2)
    arg = (length**2 - L7**2 - 2.0 * L5**2) / R
    bad = (np.abs(arg) > 1.0) | (length < 0)
    theta = phi - np.arccos(np.clip(arg, -1.0, 1.0))
    return WireAngle(theta, bad)


def wire_from_counts(counts, counts_per_metre: float, zero_count: float = 0.0) -> np.ndarray:
    """Convert encoder counts to the wire shortening ΔL7.

    Parameters
    ----------
    counts : array_like
        Encoder counts, increasing as the wire is reeled in [-].
    counts_per_metre : float
        Counts per metre of wire [m-1], > 0 (e.g. 600 pulses per revolution on
        a drum of 0.1 m circumference: 6000 m-1).
    zero_count : float
        Count at θ = 0 (the flap at rest, usually the start of the record) [-].

    Returns
    -------
    numpy.ndarray
        ΔL7 [m], positive when the wire is reeled in.

    Raises
    ------
    ValueError
        A non-positive ``counts_per_metre`` or non-numeric counts.

    Examples
    --------
    >>> from flumekit.flap.encoder import wire_from_counts
    >>> wire_from_counts([100, 160, 40], 6000.0, zero_count=100)
    array([ 0.  ,  0.01, -0.01])
    """
    if not (np.isfinite(counts_per_metre) and counts_per_metre > 0):
        raise ValueError(f"counts_per_metre must be > 0, got {counts_per_metre}")
    c = np.asarray(counts)
    if c.dtype.kind not in "iuf":
        raise ValueError(f"encoder counts must be numeric, got dtype {c.dtype}")
    return (c.astype(float) - zero_count) / counts_per_metre


def counts_from_wire(wire_shortening, counts_per_metre: float, zero_count: int = 0) -> np.ndarray:
    """Convert a wire shortening to integer encoder counts (quantised to the nearest count).

    The inverse of :func:`wire_from_counts`, used to synthesise encoder records.

    Parameters
    ----------
    wire_shortening : array_like
        ΔL7 [m].
    counts_per_metre : float
        Counts per metre of wire [m-1], > 0.
    zero_count : int, optional
        Count at θ = 0 [-].

    Returns
    -------
    numpy.ndarray of int64
        Encoder counts [-].

    Raises
    ------
    ValueError
        A non-positive ``counts_per_metre``.

    Examples
    --------
    >>> from flumekit.flap.encoder import counts_from_wire
    >>> counts_from_wire([0.0, 0.01, -0.0101], 6000.0, zero_count=100).tolist()
    [100, 160, 39]
    """
    if not (np.isfinite(counts_per_metre) and counts_per_metre > 0):
        raise ValueError(f"counts_per_metre must be > 0, got {counts_per_metre}")
    s = np.asarray(wire_shortening, dtype=float)
    return np.rint(s * counts_per_metre).astype(np.int64) + int(zero_count)
