"""Phase-resolved turbulence statistics from the beams' fluctuation variances.

For velocity fluctuations (u', w') about the phase average, a beam at angle a sees
v' = u' cos a + w' sin a, so its phase-resolved variance is

    ⟨v'²⟩ = cos²a ⟨u'²⟩ + sin²a ⟨w'²⟩ + 2 sin a cos a ⟨u'w'⟩,

linear in the three Reynolds stresses. With UP2 (a = 0) and UP1/UP3 (a = ∓α) this gives
⟨u'²⟩ = ⟨v₂'²⟩, ⟨u'w'⟩ = (⟨v₃'²⟩ - ⟨v₁'²⟩) / (4 sin α cos α) and
⟨w'²⟩ = (⟨v₁'²⟩ + ⟨v₃'²⟩ - 2 cos²α ⟨u'²⟩) / (2 sin²α) (the "variance method" of multi-beam
Doppler profilers; the cross-correlation between beams is not needed, which matters because the
beams are recorded in different runs). Only u and w are measured, so the turbulent kinetic
energy is taken from the available components, k = (⟨u'²⟩ + ⟨w'²⟩)/2; a 3-D value would need
the transverse component, and no isotropy assumption is made for it.
"""

from __future__ import annotations

import numpy as np

from flumekit.docstrings import doc


@doc
def reynolds_stresses(variance, angles, rcond: float = 1e-6
                      ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """⟨u'²⟩, ⟨w'²⟩, ⟨u'w'⟩ [m² s⁻²] from beam variances, by least squares per point.

    Parameters
    ----------
    variance : array_like
        Phase-resolved along-beam fluctuation variances [m² s⁻²], shape (..., n_beam);
        NaN where a beam does not see the point.
    %(angles)s
    rcond : float
        Relative determinant below which the 3x3 system counts as singular.

    Returns
    -------
    uu, ww, uw : shape (...). Where only horizontal beams see a point, uu is their mean and
    ww, uw are NaN; where the system is otherwise singular, all three are NaN. Sampling noise
    can make ww slightly negative where it is small: values are returned as estimated.

    Examples
    --------
    Known stresses ⟨u'²⟩ = 0.004, ⟨w'²⟩ = 0.001, ⟨u'w'⟩ = -0.0005 m²/s² give the three beams
    at -30°, 0 and +30° the variances cos²a ⟨u'²⟩ + sin²a ⟨w'²⟩ + 2 sin a cos a ⟨u'w'⟩, from
    which the stresses come back exactly:

    >>> import numpy as np
    >>> from flumekit.uvp import reynolds_stresses
    >>> a = np.radians([-30.0, 0.0, 30.0])
    >>> var = np.cos(a) ** 2 * 0.004 + np.sin(a) ** 2 * 0.001 - 2 * np.sin(a) * np.cos(a) * 0.0005
    >>> [round(float(s), 12) for s in reynolds_stresses(var, a)]
    [0.004, 0.001, -0.0005]

    Where only the horizontal beam sees the point, only ⟨u'²⟩ is known:

    >>> [float(s) for s in reynolds_stresses([np.nan, 0.004, np.nan], a)]
    [0.004, nan, nan]
    """
    var = np.asarray(variance, dtype=float)
    a = np.asarray(angles, dtype=float)
    if var.shape[-1] != a.size:
        raise ValueError(f"last axis of variance ({var.shape[-1]}) must match {a.size} angles")
    m = np.isfinite(var)
    rows = np.stack([np.cos(a) ** 2, np.sin(a) ** 2, 2 * np.sin(a) * np.cos(a)], axis=-1)
    A = rows * m[..., None]  # (..., beam, 3)
    vz = np.where(m, var, 0.0)
    N = np.einsum("...bi,...bj->...ij", A, A)
    rhs = np.einsum("...bi,...b->...i", A, vz)
    det = np.linalg.det(N)
    scale = np.trace(N, axis1=-2, axis2=-1) ** 3
    full = det > rcond * np.maximum(scale, 1e-300)
    sol = np.full(var.shape[:-1] + (3,), np.nan)
    if np.any(full):
        sol[full] = np.linalg.solve(N[full], rhs[full][..., None])[..., 0]
    horizontal = np.isclose(np.sin(a), 0.0)
    mh = m & horizontal
    nh = mh.sum(-1)
    only_h = ~full & (nh > 0)
    with np.errstate(invalid="ignore", divide="ignore"):
        uu_h = np.where(mh, var, 0.0).sum(-1) / nh
    uu = np.where(full, sol[..., 0], np.where(only_h, uu_h, np.nan))
    return uu, sol[..., 1], sol[..., 2]


def turbulent_kinetic_energy(uu, ww) -> np.ndarray:
    """K = (⟨u'²⟩ + ⟨w'²⟩) / 2 from the two measured components [m² s⁻²].

    The transverse ⟨v'²⟩ of the full k = (⟨u'²⟩ + ⟨v'²⟩ + ⟨w'²⟩) / 2 is not measured by the
    UVP and is left out (no isotropy assumption adds it).

    Parameters
    ----------
    uu : array_like
        Longitudinal normal stress ⟨u'²⟩ [m² s⁻²].
    ww : array_like
        Vertical normal stress ⟨w'²⟩ [m² s⁻²], broadcastable with ``uu``.

    Returns
    -------
    numpy.ndarray
        K [m² s⁻²].

    Examples
    --------
    Fluctuations u' = 0.1 sin ωt and w' = 0.05 cos ωt m/s have the variances 0.1²/2 and
    0.05²/2 over a period, so K = (0.005 + 0.00125) / 2:

    >>> import numpy as np
    >>> from flumekit.uvp import turbulent_kinetic_energy
    >>> wt = 2 * np.pi * np.arange(100) / 100  # one period
    >>> u, w = 0.1 * np.sin(wt), 0.05 * np.cos(wt)
    >>> round(float(turbulent_kinetic_energy(np.mean(u**2), np.mean(w**2))), 12)
    0.003125
    """
    return 0.5 * (np.asarray(uu, dtype=float) + np.asarray(ww, dtype=float))
