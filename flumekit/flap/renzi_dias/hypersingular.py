"""Chebyshev collocation of the hypersingular plate equation of the Renzi–Dias flap model.

For one vertical mode with plane wavenumber κ (κ² > 0 propagating, κ² < 0 evanescent), the
potential jump Δ(η) = ϕ(-0, η) - ϕ(+0, η) across a thin plate |η| < w/2 on x = 0 produces the
normal velocity on the plate (RD12 Eqs. B7–B11, from the double-layer representation
ϕ = ∫ Δ ∂G/∂ξ dη)

    ϕ_x(0, y) = ⨍ Δ(η) K(y - η) dη,   K(s) = ∂²G/∂x∂ξ |_{x=ξ=0} = -(iκ/4) H₁⁽¹⁾(κ|s|)/|s|

(finite part; G = -(i/4) H₀⁽¹⁾(κR) in open water, plus the image lattice η + m b in the channel).
With η = w u / 2, y = w v / 2 and the ansatz Δ = Σ_p a_p (1-u²)^{1/2} U_p(u) (RD12 Eq. B18),
this module returns the collocation matrix A[j, p] = ϕ_x(0, y_j) produced by the p-th basis
function, at the zeros v_j of T_{P+1} (RD12 Eqs. B20–B23). The kernel is split into

- the static hypersingular part -1/(2πs²), integrated exactly by the Parsons & Martin (1992)
  identity ⨍ (1-u²)^{1/2} U_p(u)/(v-u)² du = -π(p+1) U_p(v) (RD12 Eq. B19);
- the logarithmic part (κ²/4π) ln|s|, integrated exactly with
  ∫ (1-u²)^{1/2} U_p(u) ln|v-u| du = (π/2)[T_{p+2}(v)/(p+2) - T_p(v)/p] (p ≥ 1),
  (π/2)[T_2(v)/2 - ln 2] (p = 0);
- a remainder that is either O(s² ln s) (open water: split, graded Gauss–Legendre quadrature)
  or smooth, or a rapidly convergent modal series (channel, see :func:`channel_matrix`).

This replaces the numerical integration of RD12's remainder R_n (their Eq. B15) and their direct
image sum (which converges like m^{-3/2}) by exact integrals and a Kummer-accelerated modal sum.
All functions are vectorised over leading axes of ``kappa2`` (periods × vertical modes).
"""

from __future__ import annotations

import numpy as np
from scipy.special import hankel1, jv, k1

EULER = 0.5772156649015329


def collocation_points(n_terms: int) -> np.ndarray:
    """Zeros v_j = cos((2j+1)π/(2P+2)) of T_{P+1}, j = 0..P, with P + 1 = ``n_terms`` [-]."""
    j = np.arange(n_terms)
    return np.cos((2 * j + 1) * np.pi / (2 * n_terms))


def chebyshev_u(n_terms: int, v: np.ndarray) -> np.ndarray:
    """U_p(v) for p = 0..n_terms-1, shape v.shape + (n_terms,), by the three-term recurrence."""
    v = np.asarray(v, dtype=float)
    out = np.empty(v.shape + (n_terms,))
    out[..., 0] = 1.0
    if n_terms > 1:
        out[..., 1] = 2 * v
    for p in range(2, n_terms):
        out[..., p] = 2 * v * out[..., p - 1] - out[..., p - 2]
    return out


def _chebyshev_t(n_max: int, v: np.ndarray) -> np.ndarray:
    v = np.asarray(v, dtype=float)
    out = np.empty(v.shape + (n_max + 1,))
    out[..., 0] = 1.0
    out[..., 1] = v
    for n in range(2, n_max + 1):
        out[..., n] = 2 * v * out[..., n - 1] - out[..., n - 2]
    return out


def static_matrix(n_terms: int, width: float) -> np.ndarray:
    """Free-space static hypersingular part: (p+1) U_p(v_j) / w [m-1] (RD12 Eq. B19)."""
    v = collocation_points(n_terms)
    return (np.arange(1, n_terms + 1) * chebyshev_u(n_terms, v)) / width


def log_matrix(n_terms: int) -> np.ndarray:
    """L[j, p] = ∫_{-1}^{1} (1-u²)^{1/2} U_p(u) ln|v_j - u| du [-], exact."""
    v = collocation_points(n_terms)
    t = _chebyshev_t(n_terms + 2, v)
    p = np.arange(n_terms)
    out = np.empty((n_terms, n_terms))
    out[:, 0] = np.pi / 2 * (t[:, 2] / 2 - np.log(2.0))
    pp = p[1:]
    out[:, 1:] = np.pi / 2 * (t[:, pp + 2] / (pp + 2) - t[:, pp] / pp)
    return out


def _psi_coefficients(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Series coefficients 1/(k!(k+1)!) and (ψ(k+1)+ψ(k+2))/(k!(k+1)!), k = 0..n-1."""
    k = np.arange(n)
    fact = np.cumprod(np.concatenate([[1.0], np.arange(1, n, dtype=float)]))  # k!
    e = 1.0 / (fact * fact * (k + 1))
    harm = np.concatenate([[0.0], np.cumsum(1.0 / np.arange(1, n + 1))])  # H_0..H_n
    c = (harm[k] + harm[k + 1] - 2 * EULER) * e
    return e, c


_E_COEF, _C_COEF = _psi_coefficients(24)


def regular_kernel(s: np.ndarray, kappa2: np.ndarray) -> np.ndarray:
    """K(s) + 1/(2πs²) - (κ²/4π) ln s: the O(s² ln s) remainder of the free-space kernel [m-2].

    Parameters
    ----------
    s : Distance |y - η| > 0 [m].
    kappa2 : κ² [m-2], broadcastable with ``s``; > 0 for the propagating mode (kernel
        -(iκ/4) H₁⁽¹⁾(κs)/s), < 0 for evanescent modes (kernel -(|κ|/2π) K₁(|κ|s)/s).

    Notes
    -----
    For |κ| s ≤ 3 the ascending series of Y₁ (A&S 9.1.11) and K₁ (A&S 9.6.11) are used with the
    singular terms removed analytically; with t = -κ²s²/4, E = Σ t^k/(k!(k+1)!) (= 2J₁(z)/z or
    2I₁(z)/z) and C = Σ (ψ(k+1)+ψ(k+2)) t^k/(k!(k+1)!),

        K_r = (κ²/4π)[ln(|κ|/2) E + ln s (E - 1)] - (κ²/8π) C - i [κ² > 0] (κ²/8) E.

    Beyond, the closed forms are used (no cancellation there).
    """
    s = np.asarray(s, dtype=float)
    kappa2 = np.asarray(kappa2, dtype=float)
    s, kappa2 = np.broadcast_arrays(s, kappa2)
    kabs = np.sqrt(np.abs(kappa2))
    z = kabs * s
    out = np.empty(s.shape, dtype=complex)
    small = z <= 3.0
    if np.any(small):
        ss, k2, ka = s[small], kappa2[small], kabs[small]
        t = -k2 * ss * ss / 4
        em1 = np.zeros_like(t)  # Horner: E - 1 = t (e_1 + t (e_2 + ...)), C likewise
        c = np.zeros_like(t)
        for j in range(_E_COEF.size - 1, 0, -1):
            em1 = (em1 + _E_COEF[j]) * t
            c = c * t + _C_COEF[j]
        e = em1 + 1.0
        c = c * t + _C_COEF[0]
        with np.errstate(divide="ignore", invalid="ignore"):
            lnterm = np.where(ss > 0, np.log(ss) * em1, 0.0)
        val = k2 / (4 * np.pi) * (np.log(ka / 2) * e + lnterm) - k2 / (8 * np.pi) * c
        out[small] = val - 1j * np.where(k2 > 0, k2 / 8 * e, 0.0)
    big = ~small
    if np.any(big):
        sb, k2 = s[big], kappa2[big]
        out[big] = (full_kernel(sb, k2) + 1 / (2 * np.pi * sb**2)
                    - k2 / (4 * np.pi) * np.log(sb))
    return out


def full_kernel(s: np.ndarray, kappa2: np.ndarray) -> np.ndarray:
    """K(s) = -(iκ/4) H₁⁽¹⁾(κ|s|)/|s| (κ² > 0) or -(|κ|/2π) K₁(|κ||s|)/|s| (κ² < 0) [m-2]."""
    s = np.abs(np.asarray(s, dtype=float))
    kappa2 = np.asarray(kappa2, dtype=float)
    s, kappa2 = np.broadcast_arrays(s, kappa2)
    ka = np.sqrt(np.abs(kappa2))
    prop = kappa2 > 0
    out = np.empty(s.shape, dtype=complex)
    x, kp = ka[prop] * s[prop], ka[prop]
    out[prop] = -0.25j * kp * hankel1(1, x) / s[prop]
    ke = ka[~prop]
    out[~prop] = -ke / (2 * np.pi) * k1(ke * s[~prop]) / s[~prop]
    return out


def _graded_nodes(n_terms: int, n_nodes: int) -> tuple[np.ndarray, np.ndarray]:
    """θ nodes and weights on [0, θ_j] ∪ [θ_j, π] graded (θ - θ_j ∝ τ²) toward θ_j = arccos v_j."""
    tau, wt = np.polynomial.legendre.leggauss(n_nodes)
    tau, wt = (tau + 1) / 2, wt / 2
    th_j = np.arccos(collocation_points(n_terms))[:, None]
    left = th_j * (1 - tau**2)
    right = th_j + (np.pi - th_j) * tau**2
    theta = np.concatenate([left, right], axis=1)
    weight = np.concatenate([2 * th_j * tau * wt, 2 * (np.pi - th_j) * tau * wt], axis=1)
    return theta, weight


def _graded_integrals(kernel_values: np.ndarray, theta: np.ndarray, weight: np.ndarray,
                      n_terms: int) -> np.ndarray:
    """∫ (1-u²)^{1/2} U_p(u) F(v_j, u) du, with u = cos θ.

    (1-u²)^{1/2} U_p(u) du = sin θ sin((p+1)θ) dθ.
    """
    basis = np.sin(theta)[..., None] * np.sin(np.arange(1, n_terms + 1) * theta[..., None])
    return np.einsum("...jk,jkp->...jp", kernel_values, weight[..., None] * basis)


def open_water_matrix(kappa2: np.ndarray, width: float, n_terms: int,
                      quadrature_nodes: int = 24, channel_width: float | None = None,
                      images: int = 0) -> np.ndarray:
    """Collocation matrix A[..., j, p] [m-1] in open water (RD13o), optionally + direct images.

    Parameters
    ----------
    kappa2 : κ_n² [m-2], any shape (e.g. periods × modes).
    width : Flap width w [m].
    n_terms : Number of Chebyshev terms P + 1 (= number of collocation points).
    quadrature_nodes : Gauss–Legendre nodes on each side of the collocation point.
    channel_width, images : When given, add the images at η + m b, 0 < |m| ≤ ``images`` summed
        directly (the RD12 method; converges like images^{-1/2}, see :func:`channel_matrix`).
        Evanescent modes use at most ⌈40/(|κ| b)⌉ images (the rest is below e^{-40}).
    """
    kappa2 = np.asarray(kappa2, dtype=float)
    theta, weight = _graded_nodes(n_terms, quadrature_nodes)
    v = collocation_points(n_terms)[:, None]
    sdiff = width * (v - np.cos(theta)) / 2  # signed y - η [m], shape (j, k)
    k2 = kappa2[..., None, None]
    kern = regular_kernel(np.abs(sdiff), k2)
    if channel_width is not None and images > 0:
        b = float(channel_width)
        kabs = np.sqrt(np.abs(kappa2))
        kmin_ev = np.min(kabs[kappa2 < 0]) if np.any(kappa2 < 0) else np.inf
        m_ev = int(min(images, np.ceil(40 / (kmin_ev * b)))) if np.isfinite(kmin_ev) else 0
        prop = kappa2 > 0
        if np.any(prop):
            kp = k2[prop]  # (n_prop, 1, 1)
            acc = np.zeros(kp.shape[:1] + sdiff.shape, dtype=complex)
            for m in range(1, images + 1):  # few hundred lattice terms; each is vectorised
                acc += full_kernel(sdiff - m * b, kp) + full_kernel(sdiff + m * b, kp)
            kern[prop] += acc
        if m_ev > 0 and np.any(~prop):
            ke = k2[~prop]
            acc = np.zeros(ke.shape[:1] + sdiff.shape, dtype=complex)
            for m in range(1, m_ev + 1):
                acc += full_kernel(sdiff - m * b, ke) + full_kernel(sdiff + m * b, ke)
            kern[~prop] += acc
    a = static_matrix(n_terms, width) + (kappa2[..., None, None] * width / (8 * np.pi)) * (
        log_matrix(n_terms) + np.log(width / 2) * _delta0(n_terms))
    return a + width / 2 * _graded_integrals(kern, theta, weight, n_terms)


def _delta0(n_terms: int) -> np.ndarray:
    """∫ (1-u²)^{1/2} U_p du = (π/2) δ_p0, as a (1, P+1) row."""
    d = np.zeros((1, n_terms))
    d[0, 0] = np.pi / 2
    return d


def _gauss_u_nodes(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Gauss quadrature for the weight (1-u²)^{1/2}: nodes cos(kπ/(n+1)), weights π/(n+1) sin²."""
    t = np.arange(1, n + 1) * np.pi / (n + 1)
    return np.cos(t), np.pi / (n + 1) * np.sin(t) ** 2


def channel_quadrature_nodes(width: float, channel_width: float, tol: float = 1e-14) -> int:
    """Nodes of the (1-u²)^{1/2}-weighted Gauss rule needed for the smooth channel kernels.

    The kernels are analytic for |s| < b, i.e. for u within 2b/w - 2 of [-1, 1] from the worst
    collocation point; Gauss converges like ρ^{-2N} with ρ the Bernstein-ellipse parameter.
    """
    d = 2 * channel_width / width - 2
    rho = 1 + d + np.sqrt(d * d + 2 * d)
    return int(np.clip(np.ceil(np.log(1 / tol) / (2 * np.log(rho))) + 4, 16, 4096))


def kummer_remainder(beta: np.ndarray, kappa2: np.ndarray) -> np.ndarray:
    """r(β) = γ - i|β| + iκ²/(2|β|) = -iκ⁴ / (2|β| (S + |β|)²) with γ = iS, S = √(β² - κ²).

    S is the principal root for β² ≥ κ² and -i√(κ² - β²) otherwise (outgoing waves). The
    closed form has no cancellation; r = O(κ⁴/|β|³).
    """
    beta = np.abs(beta)
    d = beta**2 - kappa2
    root = np.where(d >= 0, np.sqrt(np.abs(d)) + 0j, -1j * np.sqrt(np.abs(d)))
    return -0.5j * kappa2**2 / (beta * (root + beta) ** 2)


def channel_matrix(kappa2: np.ndarray, width: float, channel_width: float, n_terms: int,
                   lattice_modes: np.ndarray | int, quadrature_nodes: int | None = None
                   ) -> np.ndarray:
    """Collocation matrix A[..., j, p] [m-1] in a channel of width b (RD12), spectral lattice.

    The centred flap in the channel is an in-phase array of period b (RD12 §2.1), whose Green's
    function is the modal series (2/b) Σ_q e^{iβ_q y} e^{iγ_q|x|}/γ_q, β_q = 2πq/b,
    γ_q = √(κ² - β_q²). On the plate it gives

        ϕ_x(0, y) = -(i/2b) Σ_q γ_q e^{iβ_q y} Δ̂(β_q),  Δ̂(β) = ∫ Δ(η) e^{-iβη} dη,

    with ∫(1-u²)^{1/2}U_p(u) e^{-iλu} du = π(p+1)(-i)^p J_{p+1}(λ)/λ. Kummer's transformation
    γ_q = i|β_q| - iκ²/(2|β_q|) + r_q (q ≠ 0) splits it into

    - the static periodic hypersingular kernel -(1/2π)(π/b)²/sin²(πs/b) = free static part
      (exact) + smooth static images (Gauss quadrature);
    - the periodic log kernel (κ²/4π) ln|2 sin(πs/b)| = ln|v-u| (exact) + ln(πw/b) +
      ln|sinc(πs/b)| (smooth, Gauss quadrature);
    - the q = 0 term -(i/2b) γ_0 Δ̂(0) and the rapidly convergent remainder
      -(i/2b) Σ_{q≠0} r_q e^{iβ_q y} Δ̂(β_q), whose terms decay like q^{-9/2}.

    The γ_q appear in the numerator, so the operator is continuous through the sloshing cut-offs
    κb = 2πq (where the direct image sum of RD12 stalls).

    Parameters
    ----------
    kappa2 : κ_n² [m-2], shape (..., n_modes).
    width, channel_width : Flap width w and channel width b [m], w < b.
    n_terms : Number of Chebyshev terms P + 1.
    lattice_modes : Number Q of transverse modes q = 1..Q kept in the remainder series; an int or
        an array broadcastable with ``kappa2`` (per vertical mode).
    quadrature_nodes : Nodes of the Gauss rule for the smooth kernels (default from
        :func:`channel_quadrature_nodes`).
    """
    kappa2 = np.asarray(kappa2, dtype=float)
    w, b = float(width), float(channel_width)
    v = collocation_points(n_terms)
    if quadrature_nodes is None:
        quadrature_nodes = channel_quadrature_nodes(w, b)
    uq, wq = _gauss_u_nodes(quadrature_nodes)
    x = np.pi * w * (v[:, None] - uq[None, :]) / (2 * b)  # π s / b, shape (j, k)
    with np.errstate(divide="ignore", invalid="ignore"):
        s_st = np.where(np.abs(x) < 1e-2, 1 / 3 + x**2 / 15 + 2 * x**4 / 189,
                        1 / np.sin(x) ** 2 - 1 / x**2) * (np.pi / b) ** 2
    ln_sinc = np.log(np.sinc(x / np.pi))
    uk = chebyshev_u(n_terms, uq) * wq[:, None]  # (k, p)
    # static images: -(1/2π) ∫ Δ(η) Σ_{m≠0} (s - m b)^{-2} dη = -(1/2π)(w/2) ∫ P(u) S(s) du
    static_images = -(w / (4 * np.pi)) * (s_st @ uk)
    log_part = log_matrix(n_terms) + np.log(np.pi * w / b) * _delta0(n_terms) + ln_sinc @ uk
    a = static_matrix(n_terms, w) + static_images + (
        kappa2[..., None, None] * w / (8 * np.pi)) * log_part
    # modal remainder
    q_all = np.asarray(lattice_modes)
    q_max = int(np.max(q_all))
    q = np.arange(1, q_max + 1)
    beta = 2 * np.pi * q / b
    lam = beta * w / 2
    p = np.arange(n_terms)
    jfac = (w / 2) * np.pi * (p + 1) * jv(p[None, :] + 1, lam[:, None]) / lam[:, None]  # (q, p)
    by = beta[:, None] * (w * v / 2)[None, :]  # (q, j)
    sign = (-1.0) ** (p // 2)
    trig = np.where(p % 2 == 0, np.cos(by)[..., None], np.sin(by)[..., None])  # (q, j, p)
    e = 2 * sign * trig * jfac[:, None, :]  # (q, j, p)
    r = kummer_remainder(beta, kappa2[..., None])  # (..., q)
    r = np.where(q <= np.asarray(lattice_modes)[..., None], r, 0.0)
    rem = -(0.5j / b) * np.einsum("...q,qjp->...jp", r, e)
    d0 = 0.0 - kappa2
    gamma0 = 1j * np.where(d0 >= 0, np.sqrt(np.abs(d0)) + 0j, -1j * np.sqrt(np.abs(d0)))
    q0 = -(0.5j / b) * gamma0[..., None, None] * (w / 2) * _delta0(n_terms)
    return a + rem + q0
