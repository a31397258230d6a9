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

from flumekit.docstrings import filler
from flumekit.errors import GeometryError

#: docstring text that several functions of this module share
_doc = filler(
    lam=("lam : float or array_like\n"
         "    Film parameter λ [-]."),
    modulus=("modulus : float\n"
             "    Effective modulus E' [Pa]."),
    r_x=("r_x : float\n"
         "    Effective radius in the rolling direction [m]."),
    r_y=("r_y : float\n"
         "    Effective radius in the transverse direction [m]."),
    viscosity=("viscosity : float\n"
               "    Dynamic viscosity at ambient pressure η0 [Pa s]."))

#: lubrication regimes returned by :func:`lubrication_regime`
BOUNDARY, MIXED, FULL_FILM = 0, 1, 2
#: film-parameter limits of the regimes: λ < 1 boundary, 1 ≤ λ < 3 mixed, λ ≥ 3 full film
REGIME_LIMITS = (1.0, 3.0)


def _positive(name: str, value) -> np.ndarray:
    arr = np.asarray(value, dtype=float)
    if not np.all(np.isfinite(arr)) or np.any(arr <= 0):
        raise ValueError(f"{name} must be positive and finite, got {value!r}")
    return arr


@_doc
def reduced_modulus(young_a: float, poisson_a: float, young_b: float | None = None,
                    poisson_b: float | None = None) -> float:
    """Return the effective elastic modulus E' of two bodies in contact (Hamrock's convention).

    E' = 2 / [(1 - ν_a²)/E_a + (1 - ν_b²)/E_b], twice the contact modulus E* of Johnson.

    Parameters
    ----------
    young_a : float
        Young's modulus of body a [Pa].
    poisson_a : float
        Poisson's ratio of body a [-].
    young_b : float, optional
        Young's modulus of body b [Pa]; default that of body a.
    poisson_b : float, optional
        Poisson's ratio of body b [-]; default that of body a.

    Returns
    -------
    float
        E' [Pa].

    Raises
    ------
    ValueError
        For a non-positive modulus or a Poisson's ratio outside (-1, 0.5).

    %(references_hamrock1991)s, Ch. 17.

    Examples
    --------
    >>> from flumekit.ballscrew.ehl import reduced_modulus
    >>> round(reduced_modulus(208e9, 0.3) / 1e9, 2)  # bearing steel on bearing steel [GPa]
    228.57
    """
    young_b = young_a if young_b is None else young_b
    poisson_b = poisson_a if poisson_b is None else poisson_b
    _positive("Young's modulus", [young_a, young_b])
    if not (-1 < poisson_a < 0.5 and -1 < poisson_b < 0.5):
        raise ValueError(f"Poisson's ratio must lie in (-1, 0.5), got {poisson_a}, {poisson_b}")
    return 2.0 / ((1 - poisson_a**2) / young_a + (1 - poisson_b**2) / young_b)


@_doc
def curvature_sum(r_ax, r_ay, r_bx, r_by) -> tuple[np.ndarray, np.ndarray]:
    """Return the effective radii R_x, R_y of two bodies in contact.

    1/R_x = 1/r_ax + 1/r_bx, 1/R_y = 1/r_ay + 1/r_by; radii positive for convex and negative for
    concave surfaces, infinite for a plane.

    Parameters
    ----------
    r_ax : float or array_like
        Radius of body a in the rolling direction x [m].
    r_ay : float or array_like
        Radius of body a in the transverse direction y [m].
    r_bx : float or array_like
        Radius of body b in x [m].
    r_by : float or array_like
        Radius of body b in y [m].

    Returns
    -------
    r_x : numpy.ndarray
        Effective radius in x [m].
    r_y : numpy.ndarray
        Effective radius in y [m].

    Raises
    ------
    flumekit.errors.GeometryError
        If a curvature sum is not positive (the surfaces would be conformal or interpenetrating:
        no Hertz contact).

    %(references_hamrock1991)s, Ch. 17.

    Examples
    --------
    >>> from flumekit.ballscrew.ehl import curvature_sum
    >>> [round(float(r), 6) for r in curvature_sum(0.005, 0.005, 0.02, -0.0055)]
    [0.004, 0.055]
    """
    cx = 1.0 / np.asarray(r_ax, float) + 1.0 / np.asarray(r_bx, float)
    cy = 1.0 / np.asarray(r_ay, float) + 1.0 / np.asarray(r_by, float)
    if np.any(cx <= 0) or np.any(cy <= 0):
        raise GeometryError("curvature sums must be positive (non-conformal contact); "
                            f"got 1/Rx = {cx}, 1/Ry = {cy}")
    return 1.0 / cx, 1.0 / cy


@_doc
def ball_groove_radii(ball_diameter: float, pitch_diameter: float, contact_angle: float,
                      conformity: float, race: str) -> tuple[float, float]:
    """Return the effective radii R_x, R_y of a ball on the screw ('inner') or nut ('outer') groove.

    The ball screw is treated like a ball bearing (screw = inner race, nut = outer race): the
    race curvature in the rolling direction is cos β over the distance of the contact point
    from the axis, the groove radius r_g = f d is concave. The helix (lead angle α) is
    neglected in the curvature: it mixes the groove curvature into the rolling direction by
    sin²α, an error of order sin²α · d/(2 r_g) ≈ 4 % in 1/R_x for α ≈ 4.5°.

    Parameters
    ----------
    ball_diameter : float
        Ball diameter d [m].
    pitch_diameter : float
        Pitch (ball-centre) diameter d_m of the screw [m].
    %(contact_angle)s
    conformity : float
        Groove conformity f = r_g / d [-], > 0.5.
    race : {"inner", "outer"}
        'inner' (screw) or 'outer' (nut).

    Returns
    -------
    %(r_x)s
    %(r_y)s

    Raises
    ------
    flumekit.errors.GeometryError
        For a ball not smaller than the pitch diameter or a conformity of 0.5 or less.
    ValueError
        For an unknown ``race``.

    %(references_hamrock1991)s, Ch. 17.

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.ballscrew.ehl import ball_groove_radii
    >>> [round(r, 6) for r in ball_groove_radii(0.0127, 0.080, np.pi / 4, 0.54, "inner")]
    [0.005637, 0.085725]
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
    """Hertz elliptical contact (arrays broadcast like the load), as :func:`hertz_contact` returns.

    Parameters
    ----------
    ellipticity : numpy.ndarray
        k = a/b [-].
    elliptic_first : numpy.ndarray
        F = K(e), complete elliptic integral of the first kind [-].
    elliptic_second : numpy.ndarray
        E = E(e), complete elliptic integral of the second kind [-].
    semi_axis_transverse : numpy.ndarray
        a = D_y / 2 [m].
    semi_axis_rolling : numpy.ndarray
        b = D_x / 2 [m].
    max_pressure : numpy.ndarray
        Maximum contact pressure p_max [Pa].
    approach : numpy.ndarray
        Mutual approach δ [m].
    """

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
    """Return the ellipticity k and complete elliptic integrals F, E for a curvature ratio.

    Parameters
    ----------
    radius_ratio : float or array_like
        α_r = R_y / R_x ≥ 1 [-].
    method : {"exact", "hamrock"}
        'exact' solves Hertz's transcendental relation
        α_r = (k² E(e) - K(e)) / (K(e) - E(e)), e² = 1 - 1/k², with scipy.special.ellipk/ellipe
        (vectorised bisection on ln k to machine precision); 'hamrock' uses the curve fits of
        Hamrock & Brewe (1983): k ≈ 1.0339 α_r^0.6360, E ≈ 1.0003 + 0.5968/α_r,
        F ≈ 1.5277 + 0.6023 ln α_r.

    Returns
    -------
    k : numpy.ndarray
        Ellipticity D_y / D_x [-].
    F : numpy.ndarray
        Complete elliptic integral of the first kind [-].
    E : numpy.ndarray
        Complete elliptic integral of the second kind [-].

    Raises
    ------
    ValueError
        For a ratio below 1 or not finite, or an unknown ``method``.

    References
    ----------
    Hamrock, B. J. and Brewe, D. E. (1983). Simplified solution for stresses and deformations.
    J. Lubr. Technol. 105, 171-177.

    Examples
    --------
    >>> from flumekit.ballscrew.ehl import ellipticity
    >>> [round(float(v), 4) for v in ellipticity(4.0)]
    [2.5007, 2.3595, 1.1506]
    >>> [round(float(v), 4) for v in ellipticity(4.0, "hamrock")]
    [2.4968, 2.3627, 1.1495]
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


@_doc
def hertz_contact(load, r_x: float, r_y: float, modulus: float,
                  method: str = "exact") -> HertzContact:
    """Compute the Hertz elliptical contact under a normal load.

    D_y = 2 (6 k² E w R / (π E'))^(1/3), D_x = 2 (6 E w R / (π k E'))^(1/3),
    p_max = 6 w / (π D_x D_y), δ = F [9/(2 E R) (w/(π k E'))²]^(1/3), 1/R = 1/R_x + 1/R_y.

    Parameters
    ----------
    load : float or array_like
        Normal load w [N], ≥ 0.
    %(r_x)s
    r_y : float
        Effective radius in the transverse direction [m], R_y ≥ R_x.
    modulus : float
        Effective modulus E' [Pa] (see :func:`reduced_modulus`).
    method : {"exact", "hamrock"}
        Elliptic integrals exact or by the Hamrock-Brewe fits (:func:`ellipticity`).

    Returns
    -------
    HertzContact
        Ellipticity, elliptic integrals, semi-axes [m], maximum pressure [Pa] and approach [m],
        of the load's shape.

    Raises
    ------
    ValueError
        For a negative or non-finite load, or a non-positive radius or modulus.

    %(references_hamrock1991)s, Ch. 17-18.

    Examples
    --------
    >>> from flumekit.ballscrew.ehl import hertz_contact
    >>> c = hertz_contact(1000.0, 0.01, 0.01, 228.57e9)  # two 2 cm steel balls
    >>> round(float(c.semi_axis_rolling) * 1e3, 4), round(float(c.max_pressure) / 1e9, 3)
    (0.4034, 2.935)
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


@_doc
def dimensionless_groups(speed, load, r_x: float, modulus: float, viscosity: float,
                         pressure_viscosity: float) -> tuple[np.ndarray, float, np.ndarray]:
    """Return the speed, materials and load parameters U, G, W of Hamrock & Dowson.

    U = η0 u / (E' R_x), G = α E', W = w / (E' R_x²).

    Parameters
    ----------
    speed : float or array_like
        Mean entrainment velocity u = (u_a + u_b)/2 [m s-1] (its magnitude is used).
    load : float or array_like
        Normal load w [N].
    %(r_x)s
    %(modulus)s
    %(viscosity)s
    pressure_viscosity : float
        Barus pressure-viscosity coefficient α [Pa-1].

    Returns
    -------
    U : numpy.ndarray
        Speed parameter [-].
    G : float
        Materials parameter [-].
    W : numpy.ndarray
        Load parameter [-].

    References
    ----------
    Hamrock, B. J. and Dowson, D. (1977). Isothermal elastohydrodynamic lubrication of point
    contacts, part III. J. Lubr. Technol. 99, 264-276.

    Examples
    --------
    >>> from flumekit.ballscrew.ehl import dimensionless_groups
    >>> u, g, w = dimensionless_groups(1.0, 100.0, 0.005, 228.57e9, 0.07, 2e-8)
    >>> round(g, 1), float(f"{float(w):.4g}")
    (4571.4, 1.75e-05)
    """
    return (viscosity * np.abs(np.asarray(speed, float)) / (modulus * r_x),
            pressure_viscosity * modulus,
            np.asarray(load, float) / (modulus * r_x**2))


@_doc
def film_thickness(speed, load, r_x: float, r_y: float, modulus: float, viscosity: float,
                   pressure_viscosity: float) -> tuple[np.ndarray, np.ndarray]:
    """Return the Hamrock-Dowson minimum and central film thickness of an elliptical EHL contact.

    H_min = 3.63 U^0.68 G^0.49 W^-0.073 (1 - e^(-0.68 k)),
    H_c = 2.69 U^0.67 G^0.53 W^-0.067 (1 - 0.61 e^(-0.73 k)), h = H R_x,
    with k from the exact Hertz relation (:func:`ellipticity`).

    Parameters
    ----------
    speed : float or array_like
        Mean entrainment velocity [m s-1]; zero speed gives zero film.
    load : float or array_like
        Normal load per contact [N], > 0 (a preload keeps it positive in a ball screw).
    %(r_x)s
    %(r_y)s
    %(modulus)s
    %(viscosity)s
    pressure_viscosity : float
        Pressure-viscosity coefficient α [Pa-1].

    Returns
    -------
    h_min : numpy.ndarray
        Minimum film thickness [m].
    h_c : numpy.ndarray
        Central film thickness [m].

    Raises
    ------
    ValueError
        For a non-positive viscosity, pressure-viscosity coefficient or load, or a non-finite
        speed.

    References
    ----------
    Hamrock, B. J. and Dowson, D. (1977). Isothermal elastohydrodynamic lubrication of point
    contacts, part III. J. Lubr. Technol. 99, 264-276.

    %(hamrock1991)s, Ch. 22.

    Examples
    --------
    >>> from flumekit.ballscrew.ehl import film_thickness
    >>> h_min, h_c = film_thickness(1.0, 100.0, 0.005637, 0.085725, 228.57e9, 0.07, 2e-8)
    >>> round(float(h_min) * 1e6, 3), round(float(h_c) * 1e6, 3)  # [µm]
    (0.296, 0.367)
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
    """Return the composite RMS roughness σ = sqrt(Σ σ_i²) of the contacting surfaces.

    Parameters
    ----------
    *rms_roughness : float
        RMS roughness of each surface [m].

    Returns
    -------
    float
        Composite roughness [m].

    Raises
    ------
    ValueError
        For a negative roughness, or none that is positive.

    Examples
    --------
    >>> from flumekit.ballscrew.ehl import composite_roughness
    >>> round(composite_roughness(0.05e-6, 0.15e-6) * 1e6, 4)  # [µm]
    0.1581
    """
    arr = np.asarray(rms_roughness, float)
    if arr.size == 0 or np.any(arr < 0) or not np.any(arr > 0):
        raise ValueError(f"RMS roughness must be >= 0 and not all zero, got {rms_roughness}")
    return float(np.sqrt(np.sum(arr**2)))


@_doc
def film_parameter(min_film_thickness, roughness: float) -> np.ndarray:
    """Return the film parameter λ = h_min / σ (Eq. (7) in Senatore & De Simone 2022).

    Parameters
    ----------
    min_film_thickness : float or array_like
        Minimum film thickness h_min [m].
    roughness : float
        Composite RMS roughness σ [m] (:func:`composite_roughness`).

    Returns
    -------
    numpy.ndarray
        λ [-].

    Raises
    ------
    ValueError
        For a non-positive roughness.

    %(references_senatore2022)s, Eq. (7).

    Examples
    --------
    >>> from flumekit.ballscrew.ehl import film_parameter
    >>> round(float(film_parameter(0.3e-6, 0.1e-6)), 6)
    3.0
    """
    _positive("composite roughness", roughness)
    return np.asarray(min_film_thickness, float) / roughness


@_doc
def lubrication_regime(lam) -> np.ndarray:
    """Return the lubrication regime from the film parameter.

    0 boundary (λ < 1), 1 mixed (1 ≤ λ < 3), 2 full film (λ ≥ 3). The limits follow the usual
    reading of the Stribeck curve (Hamrock 1991, Ch. 1; Fig. 8 of Senatore & De Simone 2022);
    Hamrock's own bands overlap (partial 1 ≤ Λ < 5, EHL 3 ≤ Λ < 10), so the limits are stated
    here: full film from λ = 3.

    Parameters
    ----------
    %(lam)s

    Returns
    -------
    numpy.ndarray
        Regime (int8): ``BOUNDARY``, ``MIXED`` or ``FULL_FILM``.

    %(references_hamrock1991)s, Ch. 1.

    Examples
    --------
    >>> from flumekit.ballscrew.ehl import lubrication_regime
    >>> lubrication_regime([0.5, 1.0, 2.9, 3.0]).tolist()
    [0, 1, 1, 2]
    """
    lam = np.asarray(lam, float)
    return np.digitize(lam, REGIME_LIMITS).astype(np.int8)


def asperity_load_fraction(lam, lam_half: float = np.sqrt(3.0), sharpness: float = 4.0):
    """Return the fraction of the load carried by asperities, φ(λ) = 1 / (1 + (λ/λ_½)^n).

    A smooth load-sharing law (a model choice, in the spirit of Johnson's load sharing): with
    the defaults λ_½ = √3 (geometric mean of the regime limits 1 and 3) and n = 4, asperities
    carry 90 % of the load at λ = 1 and 10 % at λ = 3, so the mixed band of
    :func:`lubrication_regime` is where the load passes from the asperities to the film.

    Parameters
    ----------
    lam : float or array_like
        Film parameter λ [-] (negative values count as 0).
    lam_half : float
        λ at which asperities and film share the load equally [-].
    sharpness : float
        Exponent n [-].

    Returns
    -------
    numpy.ndarray
        φ [-].

    Examples
    --------
    >>> from flumekit.ballscrew.ehl import asperity_load_fraction
    >>> asperity_load_fraction([1.0, 3.0]).round(6).tolist()
    [0.9, 0.1]
    """
    lam = np.maximum(np.asarray(lam, float), 0.0)
    return 1.0 / (1.0 + (lam / lam_half) ** sharpness)


@_doc
def stribeck_friction(lam, boundary: float = 0.1, full_film: float = 0.01,
                      lam_half: float = np.sqrt(3.0), sharpness: float = 4.0) -> np.ndarray:
    """Return the friction coefficient along the Stribeck curve.

    The curve of Fig. 8 in Senatore & De Simone 2022: f = φ f_boundary + (1 - φ) f_full_film
    with φ the asperity load fraction (:func:`asperity_load_fraction`). f decreases
    monotonically with λ, i.e. with speed in the mixed regime ("right-hand range of the
    Stribeck curve"). The hydrodynamic rise of f at very large λ is not modelled (the ball
    screw never gets there).

    Parameters
    ----------
    %(lam)s
    boundary : float
        Friction coefficient of boundary lubrication [-] (0.1, lubricated steel).
    full_film : float
        Friction (traction) coefficient of a full EHL film [-].
    lam_half : float
        λ of equal load sharing [-] (:func:`asperity_load_fraction`).
    sharpness : float
        Exponent of the load-sharing law [-].

    Returns
    -------
    numpy.ndarray
        Friction coefficient [-].

    Raises
    ------
    ValueError
        Unless 0 ≤ ``full_film`` ≤ ``boundary``.

    %(references_senatore2022)s, Fig. 8.

    Examples
    --------
    >>> from flumekit.ballscrew.ehl import stribeck_friction
    >>> stribeck_friction([0.0, 1.0, 3.0], 0.13, 0.002).round(4).tolist()
    [0.13, 0.1172, 0.0148]
    """
    if not 0 <= full_film <= boundary:
        raise ValueError(f"need 0 <= full-film friction <= boundary friction, got "
                         f"{full_film}, {boundary}")
    phi = asperity_load_fraction(lam, lam_half, sharpness)
    return phi * boundary + (1.0 - phi) * full_film
