"""From along-beam velocities to the longitudinal and vertical components ⟨u⟩, ⟨w⟩.

A beam at angle a above the horizontal, positive away from its transducer, measures
v = u cos a + w sin a (Eqs. (4)-(6) in Brito et al. 2020, with UP1 at a = -α, UP2 at 0 and UP3
at +α). Two decompositions are offered (numpy kernels; :mod:`flumekit.uvp.field` applies them):

* :func:`paired_velocity`: Eqs. (9)-(10) of the paper, from the inclined beams of one run at the
  same channel. The two channels lie at the same x but 2 r sin α apart in z, and the equations
  assume the flow uniform between them (their "statistically uniform" assumption below Eq. 8):
  the error grows with the distance r from the transducer.
* :func:`least_squares_velocity`: using the runs at many elevations, each beam's phase-averaged
  velocity is first interpolated to common (x, z) points; there, (u, w) solve
  v_b = u cos a_b + w sin a_b in the least-squares sense over the beams that see the point
  (3 equations for 2 unknowns where all beams see it). No uniformity assumption.

Both are linear in the beam velocities; the returned coefficients propagate confidence
intervals of independent beams: ci_u = sqrt(Σ c_b² ci_b²).
"""

from __future__ import annotations

import numpy as np

from flumekit.docstrings import doc


@doc
def paired_velocity(v_lower, v_upper, alpha: float) -> tuple[np.ndarray, np.ndarray]:
    """⟨u⟩, ⟨w⟩ from the downward (UP1) and upward (UP3) beams, Eqs. (9)-(10).

    Parameters
    ----------
    v_lower : array_like
        Phase-averaged velocity of the beam at -α (UP1), positive away from the
        transducer [m s-1].
    v_upper : array_like
        Same for the beam at +α (UP3) [m s-1].
    alpha : float
        Beam inclination α [rad] (π/6 in Brito et al. 2020).

    Returns
    -------
    tuple[numpy.ndarray, numpy.ndarray]
        u, w [m s-1].

    References
    ----------
    %(brito2020)s, Eqs. (9)-(10).

    Examples
    --------
    A uniform flow u = 0.3, w = -0.1 m/s seen by the beams at ∓30° (each measures
    u cos a + w sin a) is recovered exactly:

    >>> import numpy as np
    >>> from flumekit.uvp import paired_velocity
    >>> alpha, u, w = np.pi / 6, 0.3, -0.1
    >>> v1 = u * np.cos(-alpha) + w * np.sin(-alpha)  # UP1, pointing down
    >>> v3 = u * np.cos(alpha) + w * np.sin(alpha)  # UP3, pointing up
    >>> [round(float(c), 12) for c in paired_velocity(v1, v3, alpha)]
    [0.3, -0.1]
    """
    if not 0 < alpha < np.pi / 2:
        raise ValueError(f"alpha must lie in (0, pi/2), got {alpha}")
    v1, v3 = np.asarray(v_lower, dtype=float), np.asarray(v_upper, dtype=float)
    u = (v1 + v3) / (2 * np.cos(alpha))  # Eq. (9) in Brito et al. 2020
    w = (v3 - v1) / (2 * np.sin(alpha))  # Eq. (10) in Brito et al. 2020
    return u, w


@doc
def least_squares_velocity(v, angles, rcond: float = 1e-6
                           ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Least-squares (u, w) from any beams, per point, ignoring beams whose value is NaN.

    Parameters
    ----------
    v : array_like
        Along-beam velocities [m s-1], shape (..., n_beam); NaN where a beam does not see
        the point.
    %(angles)s
    rcond : float
        Points whose normal matrix has det / trace² below this are rank-deficient.

    Returns
    -------
    u, w : shape (...) [m s-1]. Where the valid beams only determine u (horizontal beams
        only), w is NaN; where they determine neither, both are NaN.
    cu, cw : Coefficients, shape (..., n_beam), with u = Σ cu_b v_b and w = Σ cw_b v_b
        (0 for missing beams; NaN rows where the component is undetermined).

    Examples
    --------
    The three beams at -30°, 0 and +30° see the uniform flow u = 0.3, w = -0.1 m/s at three
    points: at the first all beams see it, at the second UP3 does not, at the third only the
    horizontal UP2 does, which gives u but not w.

    >>> import numpy as np
    >>> from flumekit.uvp import least_squares_velocity
    >>> angles = np.radians([-30.0, 0.0, 30.0])
    >>> v = 0.3 * np.cos(angles) - 0.1 * np.sin(angles)
    >>> points = np.array([v, [v[0], v[1], np.nan], [np.nan, v[1], np.nan]])
    >>> u, w, cu, cw = least_squares_velocity(points, angles)
    >>> u.round(12).tolist(), w.round(12).tolist()
    ([0.3, 0.3, 0.3], [-0.1, -0.1, nan])

    With all three beams, w = v_UP3 - v_UP1 (2 sin 30° = 1) and UP2 does not enter it:

    >>> cw[0].round(12).tolist()
    [-1.0, 0.0, 1.0]
    """
    v = np.asarray(v, dtype=float)
    a = np.asarray(angles, dtype=float)
    if v.shape[-1] != a.size:
        raise ValueError(f"last axis of v ({v.shape[-1]}) must match the {a.size} angles")
    m = np.isfinite(v)
    c, s = np.cos(a) * m, np.sin(a) * m
    vz = np.where(m, v, 0.0)
    # normal equations [[Σc², Σcs], [Σcs, Σs²]] [u, w] = [Σ c v, Σ s v]
    scc, sss, scs = (c * c).sum(-1), (s * s).sum(-1), (c * s).sum(-1)
    det = scc * sss - scs**2
    full = det > rcond * np.maximum((scc + sss) ** 2, 1e-300)
    only_u = ~full & (scc > rcond) & (sss <= rcond * np.maximum(scc, 1e-300))
    with np.errstate(divide="ignore", invalid="ignore"):
        inv = np.where(full, 1.0 / det, np.nan)
        cu = np.where(full[..., None], (sss[..., None] * c - scs[..., None] * s) * inv[..., None],
                      np.where(only_u[..., None], c / scc[..., None], np.nan))
        cw = np.where(full[..., None], (scc[..., None] * s - scs[..., None] * c) * inv[..., None],
                      np.nan)
    u = (cu * vz).sum(-1)
    w = (cw * vz).sum(-1)
    return u, w, cu, cw


def combine_ci(coefficients, ci) -> np.ndarray:
    """Half-width of the CI of Σ c_b v_b for independent beams: sqrt(Σ c_b² ci_b²).

    Parameters
    ----------
    coefficients : array_like
        Coefficients c_b of the beams, shape (..., n_beam), e.g. ``cu`` or ``cw`` of
        :func:`least_squares_velocity`.
    ci : array_like
        CI half-widths of the beam velocities [m s-1], broadcastable with ``coefficients``;
        ignored (may be NaN) where the coefficient is 0.

    Returns
    -------
    numpy.ndarray
        CI half-width [m s-1], shape (...).

    Examples
    --------
    With the beams at ∓30°, w = v_UP3 - v_UP1 (coefficients -1, 0, 1), so beam CIs of 3 and
    4 cm/s give 5 cm/s for w; the missing (NaN) value of the horizontal beam does not enter.

    >>> import numpy as np
    >>> from flumekit.uvp import combine_ci
    >>> round(float(combine_ci([-1.0, 0.0, 1.0], [0.03, np.nan, 0.04])), 12)  # √(3² + 4²)
    0.05
    """
    c = np.asarray(coefficients, dtype=float)
    e = np.where(c == 0, 0.0, np.asarray(ci, dtype=float))
    return np.sqrt(np.sum((c * e) ** 2, axis=-1))
