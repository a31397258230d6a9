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
    """Half-width of the CI of Σ c_b v_b for independent beams: sqrt(Σ c_b² ci_b²)."""
    c = np.asarray(coefficients, dtype=float)
    e = np.where(c == 0, 0.0, np.asarray(ci, dtype=float))
    return np.sqrt(np.sum((c * e) ** 2, axis=-1))
