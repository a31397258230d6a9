"""Elastohydrodynamic lubrication of elliptical (ball-on-groove) contacts.

Hertz contact of a ball on the screw and on the nut groove, Hamrock–Dowson film thickness, the
film parameter λ = h_min/σ, the lubrication regime and a Stribeck friction coefficient. All
functions are vectorised over numpy arrays (time along any axis) and use SI units.

Conventions (Hamrock, *Fundamentals of Fluid Film Lubrication*, NASA RP-1255, 1991):

- x is the rolling (entrainment) direction, y the transverse direction; radii of curvature are
  positive for convex and negative for concave surfaces; 1/R_x = 1/r_ax + 1/r_bx etc.
- E' = 2 / [(1 - ν_a²)/E_a + (1 - ν_b²)/E_b] (twice the "contact modulus" E* of Johnson).
- Ellipticity k = D_y / D_x ≥ 1 (transverse over rolling diameter of the contact ellipse) for
  R_y ≥ R_x.
- Dimensionless groups: U = η0 u / (E' R_x), G = α E', W = w / (E' R_x²), u the mean
  (entrainment) velocity.

References
----------
Hamrock B.J. (1991) Fundamentals of Fluid Film Lubrication, NASA RP-1255.
Hamrock B.J., Brewe D.E. (1983) Simplified solution for stresses and deformations,
    J. Lubr. Technol. 105, 171-177.
Hamrock B.J., Dowson D. (1977) Isothermal elastohydrodynamic lubrication of point contacts,
    part III, J. Lubr. Technol. 99, 264-276.
Senatore A., De Simone A. (2022) Energies 15, 9358 (Fig. 8: Stribeck curve).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import special

from flumekit.errors import GeometryError

#: lubrication regimes returned by :func:`lubrication_regime`
BOUNDARY, MIXED, FULL_FILM = 0, 1, 2
#: film-parameter limits of the regimes: λ < 1 boundary, 1 ≤ λ < 3 mixed, λ ≥ 3 full film
REGIME_LIMITS = (1.0, 3.0)


def _positive(name: str, value) -> np.ndarray:
    arr = np.asarray(value, dtype=float)
    if not np.all(np.isfinite(arr)) or np.any(arr <= 0):
        raise ValueError(f"{name} must be positive and finite, got {value!r}")
    return arr


def reduced_modulus(young_a: float, poisson_a: float, young_b: float | None = None,
                    poisson_b: float | None = None) -> float:
    """Effective elastic modulus E' of two bodies in contact (Hamrock's convention).

    Parameters
    ----------
    young_a, poisson_a : Young's modulus [Pa] and Poisson's ratio [1] of body a.
    young_b, poisson_b : The same for body b (defaults: equal to body a).

    Returns
    -------
    E' = 2 / [(1 - ν_a²)/E_a + (1 - ν_b²)/E_b] [Pa].
    """
    young_b = young_a if young_b is None else young_b
    poisson_b = poisson_a if poisson_b is None else poisson_b
    _positive("Young's modulus", [young_a, young_b])
    if not (-1 < poisson_a < 0.5 and -1 < poisson_b < 0.5):
        raise ValueError(f"Poisson's ratio must lie in (-1, 0.5), got {poisson_a}, {poisson_b}")
    return 2.0 / ((1 - poisson_a**2) / young_a + (1 - poisson_b**2) / young_b)


def curvature_sum(r_ax, r_ay, r_bx, r_by) -> tuple[np.ndarray, np.ndarray]:
    """Effective radii R_x, R_y of two bodies (convex > 0, concave < 0, plane = inf).

    Returns
    -------
    (R_x, R_y) [m] with 1/R_x = 1/r_ax + 1/r_bx, 1/R_y = 1/r_ay + 1/r_by.

    Raises
    ------
    GeometryError if a curvature sum is not positive (the surfaces would be conformal or
    interpenetrating, no Hertz contact).
    """
    cx = 1.0 / np.asarray(r_ax, float) + 1.0 / np.asarray(r_bx, float)
    cy = 1.0 / np.asarray(r_ay, float) + 1.0 / np.asarray(r_by, float)
    if np.any(cx <= 0) or np.any(cy <= 0):
        raise GeometryError("curvature sums must be positive (non-conformal contact); "
                            f"got 1/Rx = {cx}, 1/Ry = {cy}")
    return 1.0 / cx, 1.0 / cy


def ball_groove_radii(ball_diameter: float, pitch_diameter: float, contact_angle: float,
                      conformity: float, race: str) -> tuple[float, float]:
    """Effective radii R_x, R_y of a ball on the screw ('inner') or nut ('outer') groove.

    The ball screw is treated like a ball bearing (screw = inner race, nut = outer race): the
    race curvature in the rolling direction is cos β over the distance of the contact point
    from the axis, the groove radius r_g = f d is concave. The helix (lead angle α) is
    neglected in the curvature: it mixes the groove curvature into the rolling direction by
    sin²α, an error of order sin²α · d/(2 r_g) ≈ 4 % in 1/R_x for α ≈ 4.5°.

    Parameters
    ----------
    ball_diameter : Ball diameter d [m].
    pitch_diameter : Pitch (ball-centre) diameter d_m of the screw [m].
    contact_angle : Contact angle β [rad].
    conformity : Groove conformity f = r_g / d [1], > 0.5.
    race : 'inner' (screw) or 'outer' (nut).

    Returns
    -------
    (R_x, R_y) [m].
    """
    d, dm = float(ball_diameter), float(pitch_diameter)
    if d <= 0 or dm <= d:
        raise GeometryError(f"need 0 < ball diameter < pitch diameter, got d={d}, dm={dm}")
    if not conformity > 0.5:
        raise GeometryError(f"groove conformity must exceed 0.5 (groove wider than ball), "
                            f"got {conformity}")
    cb = np.cos(contact_angle)
    if race == "inner":
        r_bx = (dm - d * cb) / (2 * cb)
    elif race == "outer":
        r_bx = -(dm + d * cb) / (2 * cb)
    else:
        raise ValueError(f"race must be 'inner' (screw) or 'outer' (nut), got {race!r}")
    rx, ry = curvature_sum(d / 2, d / 2, r_bx, -conformity * d)
    return float(rx), float(ry)


@dataclass(frozen=True)
class HertzContact:
    """Hertz elliptical contact (arrays broadcast like the load)."""

    ellipticity: np.ndarray  # k = a/b [1]
    elliptic_first: np.ndarray  # F = K(e), complete elliptic integral of the first kind [1]
    elliptic_second: np.ndarray  # E = E(e), complete elliptic integral of the second kind [1]
    semi_axis_transverse: np.ndarray  # a = D_y / 2 [m]
    semi_axis_rolling: np.ndarray  # b = D_x / 2 [m]
    max_pressure: np.ndarray  # p_max [Pa]
    approach: np.ndarray  # mutual approach δ [m]


def _curvature_ratio(k: np.ndarray) -> np.ndarray:
    """R_y/R_x of an elliptical Hertz contact of ellipticity k = a/b ≥ 1 (exact)."""
    m = 1.0 - 1.0 / k**2  # e²
    kk, ee = special.ellipk(m), special.ellipe(m)
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = (k**2 * ee - kk) / (kk - ee)
    return np.where(m < 1e-12, 1.0, ratio)


def ellipticity(radius_ratio, method: str = "exact") -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Ellipticity k and complete elliptic integrals F, E for a curvature ratio α_r = R_y/R_x.

    Parameters
    ----------
    radius_ratio : α_r = R_y / R_x ≥ 1 [1].
    method : 'exact' solves Hertz's transcendental relation
        α_r = (k² E(e) - K(e)) / (K(e) - E(e)), e² = 1 - 1/k², with scipy.special.ellipk/ellipe
        (vectorised bisection on ln k to machine precision); 'hamrock' uses the curve fits of
        Hamrock & Brewe (1983): k ≈ 1.0339 α_r^0.6360, E ≈ 1.0003 + 0.5968/α_r,
        F ≈ 1.5277 + 0.6023 ln α_r.

    Returns
    -------
    (k, F, E) [1].
    """
    ar = np.asarray(radius_ratio, dtype=float)
    if np.any(~np.isfinite(ar)) or np.any(ar < 1):
        raise ValueError("radius ratio Ry/Rx must be >= 1 (choose x as the direction of the "
                         f"smaller radius), got {radius_ratio!r}")
    if method == "hamrock":
        return 1.0339 * ar**0.6360, 1.5277 + 0.6023 * np.log(ar), 1.0003 + 0.5968 / ar
    if method != "exact":
        raise ValueError(f"method must be 'exact' or 'hamrock', got {method!r}")
    # k < α_r for α_r > 1 (k ~ α_r^(2/π)); the ratio is monotonic in k
    lo = np.zeros_like(ar)
    hi = np.log(ar)  # ratio(k = α_r) > α_r for α_r > 1; α_r = 1 gives k = 1 exactly
    for _ in range(60):  # bisection iterations, not a loop over samples
        mid = 0.5 * (lo + hi)
        above = _curvature_ratio(np.exp(mid)) > ar
        hi = np.where(above, mid, hi)
        lo = np.where(above, lo, mid)
    k = np.exp(0.5 * (lo + hi))
    m = 1.0 - 1.0 / k**2
    return k, special.ellipk(m), special.ellipe(m)


def hertz_contact(load, r_x: float, r_y: float, modulus: float,
                  method: str = "exact") -> HertzContact:
    """Hertz elliptical contact under a normal load.

    Parameters
    ----------
    load : Normal load w [N], array.
    r_x, r_y : Effective radii in the rolling and transverse directions [m], R_y ≥ R_x.
    modulus : Effective modulus E' [Pa] (see :func:`reduced_modulus`).
    method : 'exact' (elliptic integrals) or 'hamrock' (Hamrock–Brewe fits).

    Returns
    -------
    HertzContact with D_y = 2 (6 k² E w R / (π E'))^(1/3), D_x = 2 (6 E w R / (π k E'))^(1/3),
    p_max = 6 w / (π D_x D_y), δ = F [9/(2 E R) (w/(π k E'))²]^(1/3), 1/R = 1/R_x + 1/R_y
    (Hamrock 1991, Ch. 17/18).
    """
    w = np.asarray(load, dtype=float)
    if np.any(~np.isfinite(w)) or np.any(w < 0):
        raise ValueError("contact load must be finite and >= 0")
    _positive("effective radius", [r_x, r_y])
    _positive("effective modulus", modulus)
    k, ff, ee = ellipticity(r_y / r_x, method)
    r = 1.0 / (1.0 / r_x + 1.0 / r_y)
    dy = 2.0 * (6.0 * k**2 * ee * w * r / (np.pi * modulus)) ** (1 / 3)
    dx = 2.0 * (6.0 * ee * w * r / (np.pi * k * modulus)) ** (1 / 3)
    with np.errstate(invalid="ignore", divide="ignore"):
        pmax = np.where(w > 0, 6.0 * w / (np.pi * dx * dy), 0.0)
    delta = ff * (9.0 / (2.0 * ee * r) * (w / (np.pi * k * modulus)) ** 2) ** (1 / 3)
    b = np.broadcast_to
    shape = w.shape
    return HertzContact(b(k, shape), b(ff, shape), b(ee, shape), dy / 2, dx / 2, pmax, delta)


def dimensionless_groups(speed, load, r_x: float, modulus: float, viscosity: float,
                         pressure_viscosity: float) -> tuple[np.ndarray, float, np.ndarray]:
    """Speed, materials and load parameters U, G, W of Hamrock & Dowson.

    Parameters
    ----------
    speed : Mean entrainment velocity u = (u_a + u_b)/2 [m s-1] (magnitude is used).
    load : Normal load w [N].
    r_x : Effective radius in the rolling direction [m].
    modulus : Effective modulus E' [Pa].
    viscosity : Dynamic viscosity at ambient pressure η0 [Pa s].
    pressure_viscosity : Barus pressure-viscosity coefficient α [Pa-1].
    """
    return (viscosity * np.abs(np.asarray(speed, float)) / (modulus * r_x),
            pressure_viscosity * modulus,
            np.asarray(load, float) / (modulus * r_x**2))


def film_thickness(speed, load, r_x: float, r_y: float, modulus: float, viscosity: float,
                   pressure_viscosity: float) -> tuple[np.ndarray, np.ndarray]:
    """Hamrock–Dowson minimum and central film thickness of an elliptical EHL contact.

    H_min = 3.63 U^0.68 G^0.49 W^-0.073 (1 - e^(-0.68 k)),
    H_c = 2.69 U^0.67 G^0.53 W^-0.067 (1 - 0.61 e^(-0.73 k)), h = H R_x,
    with k from the exact Hertz relation (Hamrock & Dowson 1977; Hamrock 1991, Ch. 22).

    Parameters
    ----------
    speed : Mean entrainment velocity [m s-1]; zero speed gives zero film.
    load : Normal load per contact [N], > 0 (a preload keeps it positive in a ball screw).
    r_x, r_y : Effective radii [m].
    modulus : Effective modulus E' [Pa].
    viscosity : η0 [Pa s].
    pressure_viscosity : α [Pa-1].

    Returns
    -------
    (h_min, h_c) [m].
    """
    _positive("viscosity", viscosity)
    _positive("pressure-viscosity coefficient", pressure_viscosity)
    w = np.asarray(load, float)
    if np.any(~np.isfinite(w)) or np.any(w <= 0):
        raise ValueError("film thickness needs a positive contact load (add the preload)")
    u = np.asarray(speed, float)
    if np.any(~np.isfinite(u)):
        raise ValueError("entrainment speed must be finite")
    k, _, _ = ellipticity(r_y / r_x)
    uu, g, ww = dimensionless_groups(u, w, r_x, modulus, viscosity, pressure_viscosity)
    hmin = 3.63 * uu**0.68 * g**0.49 * ww**-0.073 * (1 - np.exp(-0.68 * k))
    hc = 2.69 * uu**0.67 * g**0.53 * ww**-0.067 * (1 - 0.61 * np.exp(-0.73 * k))
    return hmin * r_x, hc * r_x


def composite_roughness(*rms_roughness: float) -> float:
    """Composite RMS roughness σ = sqrt(Σ σ_i²) of the contacting surfaces [m]."""
    arr = np.asarray(rms_roughness, float)
    if arr.size == 0 or np.any(arr < 0) or not np.any(arr > 0):
        raise ValueError(f"RMS roughness must be >= 0 and not all zero, got {rms_roughness}")
    return float(np.sqrt(np.sum(arr**2)))


def film_parameter(min_film_thickness, roughness: float) -> np.ndarray:
    """Film parameter λ = h_min / σ [1] (Eq. (7) in Senatore & De Simone 2022)."""
    _positive("composite roughness", roughness)
    return np.asarray(min_film_thickness, float) / roughness


def lubrication_regime(lam) -> np.ndarray:
    """Lubrication regime from the film parameter: 0 boundary (λ < 1), 1 mixed (1 ≤ λ < 3),
    2 full film (λ ≥ 3).

    The limits follow the usual reading of the Stribeck curve (Hamrock 1991, Ch. 1; Fig. 8 of
    Senatore & De Simone 2022); Hamrock's own bands overlap (partial 1 ≤ Λ < 5, EHL 3 ≤ Λ < 10),
    so we state ours: full film from λ = 3.
    """
    lam = np.asarray(lam, float)
    return np.digitize(lam, REGIME_LIMITS).astype(np.int8)


def asperity_load_fraction(lam, lam_half: float = np.sqrt(3.0), sharpness: float = 4.0):
    """Fraction of the load carried by asperities, φ(λ) = 1 / (1 + (λ/λ_½)^n).

    A smooth load-sharing law (model choice, in the spirit of Johnson's load sharing): with the
    defaults λ_½ = √3 (geometric mean of the regime limits 1 and 3) and n = 4, asperities carry
    90 % of the load at λ = 1 and 10 % at λ = 3, so the mixed band of
    :func:`lubrication_regime` is where the load passes from the asperities to the film.
    """
    lam = np.maximum(np.asarray(lam, float), 0.0)
    return 1.0 / (1.0 + (lam / lam_half) ** sharpness)


def stribeck_friction(lam, boundary: float = 0.1, full_film: float = 0.01,
                      lam_half: float = np.sqrt(3.0), sharpness: float = 4.0) -> np.ndarray:
    """Friction coefficient along the Stribeck curve (Fig. 8 in Senatore & De Simone 2022).

    f = φ f_boundary + (1 - φ) f_full_film with φ the asperity load fraction
    (:func:`asperity_load_fraction`). f decreases monotonically with λ, i.e. with speed in the
    mixed regime ("right-hand range of the Stribeck curve"). The hydrodynamic rise of f at very
    large λ is not modelled (the ball screw never gets there).

    Parameters
    ----------
    lam : Film parameter λ [1].
    boundary : Friction coefficient of boundary lubrication [1] (0.1, lubricated steel).
    full_film : Friction (traction) coefficient of a full EHL film [1].
    """
    if not 0 <= full_film <= boundary:
        raise ValueError(f"need 0 <= full-film friction <= boundary friction, got "
                         f"{full_film}, {boundary}")
    phi = asperity_load_fraction(lam, lam_half, sharpness)
    return phi * boundary + (1.0 - phi) * full_film
