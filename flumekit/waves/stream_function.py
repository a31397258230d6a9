"""Steady nonlinear regular waves by the stream-function (Fourier approximation) method.

The method of Rienecker & Fenton (1981) in the form of Fenton (1988): the stream function in a
frame moving with the wave is a truncated Fourier series that satisfies Laplace's equation and
the bed condition exactly; its N coefficients, the surface elevation at N + 1 points of half a
wavelength, the wavenumber, the mean flow and the Bernoulli constant are found by Newton's
method from the two nonlinear free-surface conditions at those points, the mean depth, the wave
height and the period. It is accurate in every depth up to close to breaking (Fenton 1999; the
error falls geometrically with N), so it covers the whole range of the flume of Brito et al.
(2020): h = 0.825 m, T ≤ 4 s, H ≤ 0.3 m, Ursell numbers H L²/h³ up to about 65, where
second-order Stokes theory (valid to about 26) fails and where cnoidal theory (from about 40)
would only be an approximation of the same solution: no cnoidal theory is needed.

Notation (Fenton 1988, §2), with z measured up from the bed, X = x - c t the coordinate moving
with the wave (crest at X = 0) and the fluid velocities (U, W) in that frame:

    ψ(X, z) = -ū z + Σ_{j=1..N} B_j sinh(jkz) / cosh(jkh) cos(jkX)          (Eq. 2)

    kinematic surface condition  ψ(X, η(X)) = -Q                             (Eq. 3)
    dynamic surface condition    ½ (U² + W²) + g η = R  at z = η(X)          (Eq. 4)
    mean depth                   (1/L) ∫ η dX = h                            (Eq. 5)
    height                       η(0) - η(L/2) = H                           (Eq. 6)
    period                       c = L / T = 2π / (k T)                      (Eq. 7)
    current                      c_E = c - ū  (Stokes' first definition)    (Eq. 8)
                            or   c_S = c - Q / h  (Stokes' second definition)  (Eq. 9)

Equation numbers are those of Fenton (1988). In the fixed frame the horizontal velocity is
u = c - ū + Σ jk B_j cosh(jkz)/cosh(jkh) cos(jkX) and w = Σ jk B_j sinh(jkz)/cosh(jkh) sin(jkX).

The current criterion fixes the otherwise undetermined mean flow. In a closed flume no water
leaves or enters, so the mean mass transport is zero: Stokes' second definition with c_S = 0
(``current="stokes"``, the default here). The mean Eulerian velocity c_E = c - ū is then a
return current, negative (against the waves) of order -E/(ρ c h). Stokes' first definition with
c_E = 0 (``current="euler"``) describes waves on water with no mean current at a fixed point,
e.g. in the open sea, and is what Fenton's program computes by default.

References
----------
Rienecker, M. M. & Fenton, J. D. (1981). A Fourier approximation method for steady water waves.
J. Fluid Mech. 104, 119-137.
Fenton, J. D. (1988). The numerical solution of steady water wave problems. Computers &
Geosciences 14(3), 357-368.
Fenton, J. D. (1990). Nonlinear wave theories. In The Sea, vol. 9A, Ocean Engineering Science,
B. Le Méhauté & D. M. Hanes (eds.), Wiley, 3-25.
Fenton, J. D. (1999). Numerical methods for nonlinear waves. In Advances in Coastal and Ocean
Engineering, vol. 5, P. L.-F. Liu (ed.), World Scientific, 241-324.
"""

from __future__ import annotations

import dataclasses
import functools

import numpy as np

from flumekit.docstrings import doc
from flumekit.waves.theory import G, wavenumber

CURRENTS = ("stokes", "euler")


@doc
def highest_wave(wavelength, depth) -> np.ndarray:
    """Height of the highest steady wave of a given length [m].

    The rational fit of Fenton (1990) to the highest waves computed by Williams (1981),
    with λ = L/h: H_max/h = (0.141063 λ + 0.0095721 λ² + 0.0077829 λ³) /
    (1 + 0.0788340 λ + 0.0317567 λ² + 0.0093407 λ³); it tends to 0.142 L in deep water and to
    0.833 h in shallow water.

    Parameters
    ----------
    wavelength : array_like
        Wavelength L [m].
    %(depth_array)s

    Returns
    -------
    numpy.ndarray
        Maximum crest-to-trough height [m].
    """
    lam = np.asarray(wavelength, dtype=float) / np.asarray(depth, dtype=float)
    num = 0.141063 * lam + 0.0095721 * lam**2 + 0.0077829 * lam**3
    den = 1 + 0.0788340 * lam + 0.0317567 * lam**2 + 0.0093407 * lam**3
    return np.asarray(depth, dtype=float) * num / den


@dataclasses.dataclass(frozen=True)
class StreamFunctionWave:
    """A steady nonlinear regular wave (the solution of :func:`stream_function_wave`).

    Attributes
    ----------
    period, height, depth : T [s], crest-to-trough H [m] and still-water depth h [m].
    g : Gravitational acceleration [m s-2].
    current : ``"stokes"`` (mean mass transport c_S = 0) or ``"euler"`` (c_E = 0).
    wavenumber : k [rad m-1] (nonlinear: smaller than the linear one for a given T).
    celerity : c = ω/k [m s-1].
    eulerian_current : Mean horizontal velocity at a fixed point below the troughs, c_E [m s-1].
    mass_transport : Depth-averaged mean mass-transport velocity c_S = c - Q/h [m s-1].
    elevation_coefficients : E_j, j = 1..N [m]: η - h = Σ E_j cos(j(kx - ωt)); E_1 is the
        first-harmonic amplitude.
    stream_coefficients : B_j, j = 1..N [m2 s-1] of Eq. (2) (dimensional).
    bernoulli : R [m2 s-2] of Eq. (4), z from the bed.
    volume_flux : Q [m2 s-1] of Eq. (3), in the frame of the wave.
    """

    period: float
    height: float
    depth: float
    g: float
    current: str
    wavenumber: float
    celerity: float
    eulerian_current: float
    mass_transport: float
    elevation_coefficients: np.ndarray
    stream_coefficients: np.ndarray
    bernoulli: float
    volume_flux: float

    @property
    def n_modes(self) -> int:
        """Number N of Fourier modes [-]."""
        return int(self.elevation_coefficients.size)

    @property
    def omega(self) -> float:
        """Angular frequency ω = 2π/T [rad s-1]."""
        return 2 * np.pi / self.period

    @property
    def wavelength(self) -> float:
        """Wavelength L = 2π/k [m]."""
        return 2 * np.pi / self.wavenumber

    @property
    def ursell_number(self) -> float:
        """Ursell number H L² / h³ [-]."""
        return self.height * self.wavelength**2 / self.depth**3

    def elevation(self, phase) -> np.ndarray:
        """Free-surface elevation above the still water level η [m] at phase θ = kx - ωt [rad]."""
        phase = np.asarray(phase, dtype=float)
        j = np.arange(1, self.n_modes + 1)
        return np.cos(phase[..., None] * j) @ self.elevation_coefficients

    def depth_functions(self, z):
        """cosh(jkz_b)/cosh(jkh) and sinh(jkz_b)/cosh(jkh) for z_b = z + h [-], shape (..., N).

        ``z`` [m] is measured up from the still water level (z_b from the bed); evaluated in the
        overflow-free exponential form.
        """
        zb = np.asarray(z, dtype=float)[..., None] + self.depth
        jk = self.wavenumber * np.arange(1, self.n_modes + 1)
        return depth_ratios(jk, zb, self.depth)

    def velocity(self, phase, z) -> tuple[np.ndarray, np.ndarray]:
        """Fluid velocity (u, w) [m s-1] in the fixed frame.

        At phase θ = kx - ωt [rad] and elevation ``z`` [m] above the still water level
        (broadcast together), for z ≤ η:
        u = c_E + Σ jk B_j cosh(jkz_b)/cosh(jkh) cos jθ, w = Σ jk B_j sinh(jkz_b)/cosh(jkh) sin jθ
        (Fenton 1988, Eq. 2 differentiated, u = U + c).
        """
        phase, z = np.broadcast_arrays(np.asarray(phase, dtype=float), np.asarray(z, dtype=float))
        ch, sh = self.depth_functions(z)
        j = np.arange(1, self.n_modes + 1)
        amp = j * self.wavenumber * self.stream_coefficients
        arg = phase[..., None] * j
        u = self.eulerian_current + np.sum(amp * ch * np.cos(arg), axis=-1)
        w = np.sum(amp * sh * np.sin(arg), axis=-1)
        return u, w


def nonlinear_wavenumber(period: float, height: float, depth: float, g: float = G) -> float:
    """Wavenumber [rad m-1] of the steady regular wave of a period [s], height [m] and depth [m].

    The stream-function wave with zero mean mass transport (a closed flume); the linear one
    for a height below 1e-4 of the depth (where they agree to 1e-8). A height beyond what a
    steady wave can reach (a breaking or badly separated record) raises ValueError.
    """
    if not height > 1e-4 * depth:
        return float(wavenumber(2 * np.pi / period, depth, g))
    return stream_function_wave(period, height, depth, current="stokes", g=g).wavenumber


def nonlinear_wavenumbers(periods, heights, depths, g: float = G) -> list:
    """:func:`nonlinear_wavenumber` of many waves, solved together where they can be.

    The waves whose nearest grid wave starts the chord iteration are iterated together
    (:func:`_chord_many`); each result is the one :func:`nonlinear_wavenumber` returns for
    that wave alone.

    Parameters
    ----------
    periods, heights, depths : sequence of float
        Period [s], height [m] and depth [m] of each wave.
    g : float
        Gravitational acceleration [m s-2].

    Returns
    -------
    list
        Per wave its wavenumber [rad m-1] (a float) or the ValueError that refuses it.

    Examples
    --------
    >>> from flumekit.waves.stream_function import nonlinear_wavenumbers
    >>> k = nonlinear_wavenumbers([3.5, 3.5], [0.25, 0.05], [0.825, 0.825])
    >>> [round(x, 4) for x in k]
    [0.6399, 0.6599]
    """
    n = 20  # stream_function_wave's default modes
    out: list = [None] * len(heights)
    batch = []  # (wave, its anchor, T (g/h)^½, H/h)
    for i, (period, height, depth) in enumerate(zip(periods, heights, depths, strict=True)):
        try:
            if height > 1e-4 * depth and all(np.isfinite(v) and v > 0
                                             for v in (period, height, depth, g)):
                t_nd, h_nd, _, _ = _dimensionless(period, height, depth, g)
                anchor = _anchor(t_nd, h_nd, n, "stokes")
                if anchor is not None:
                    batch.append((i, anchor, t_nd, h_nd))
                    continue
            out[i] = nonlinear_wavenumber(period, height, depth, g)
        except ValueError as e:
            out[i] = e
    if batch:
        cosm, sinm, weights = _collocation(n)
        v, res = _chord_many(np.stack([b[1][0] for b in batch]),
                             np.stack([b[1][1] for b in batch]), n,
                             np.array([b[3] for b in batch]), np.array([b[2] for b in batch]),
                             ("stokes", cosm, sinm, weights))
        for (i, _, _, _), x, r in zip(batch, v, res, strict=True):
            if np.all(np.isfinite(x)) and r < 1e-10:
                out[i] = float(x[0] / depths[i])
            else:  # the chord does not reach it: the wave's own fallbacks
                try:
                    out[i] = nonlinear_wavenumber(periods[i], heights[i], depths[i], g)
                except ValueError as e:
                    out[i] = e
    return out


@doc
def depth_ratios(jk, zb, depth: float) -> tuple[np.ndarray, np.ndarray]:
    """cosh(jk z_b)/cosh(jk h) and sinh(jk z_b)/cosh(jk h) [-], the depth dependence of mode j.

    Parameters
    ----------
    jk : array_like
        Wavenumbers of the modes, j k [rad m-1].
    zb : array_like
        Elevation above the bed [m], broadcast with ``jk``.
    %(depth)s

    Returns
    -------
    tuple of numpy.ndarray
        The two ratios, in the overflow-free exponential form.
    """
    ep = np.exp(jk * (zb - depth))
    em = np.exp(-jk * (zb + depth))
    den = 1.0 + np.exp(-2.0 * jk * depth)
    return (ep + em) / den, (ep - em) / den


def _residuals(v, n: int, height: float, period: float, current: str, cosm: np.ndarray,
               sinm: np.ndarray, weights: np.ndarray) -> np.ndarray:
    """Eqs. (3)-(6) at the N + 1 surface points, dimensionless with g = h = 1.

    ``v`` (..., 2N + 4) = [k, η_0..η_N, B_1..B_N, ū (stokes) or Q (euler), R], real or complex
    (the complex step of :func:`_newton`); the current criterion with c = 2π/(kT) gives the
    other of ū and Q.
    """
    jk, eta = _modes(v, n)
    ch, sh = depth_ratios(jk, eta[..., None], 1.0)  # (..., N+1, N)
    return _equations(v, n, height, period, current, cosm, sinm, weights, ch, sh)


def _modes(v, n: int):
    """Return j k (..., 1, N) and η_m (..., N + 1) of the unknowns ``v`` (:func:`_residuals`)."""
    return v[..., :1, None] * np.arange(1, n + 1), v[..., 1:n + 2]


def _equations(v, n: int, height: float, period: float, current: str, cosm: np.ndarray,
               sinm: np.ndarray, weights: np.ndarray, ch, sh) -> np.ndarray:
    """Return the residuals of :func:`_residuals` from the depth ratios ``ch``, ``sh``."""
    k = v[..., :1]
    jk, eta = _modes(v, n)
    b = v[..., None, n + 2:2 * n + 2]
    c = 2 * np.pi / (k * period)
    if current == "stokes":  # Eq. (9) with c_S = 0 and h = 1: Q = c
        ubar, q = v[..., 2 * n + 2:2 * n + 3], c
    else:  # Eq. (8) with c_E = 0: ū = c
        ubar, q = c, v[..., 2 * n + 2:2 * n + 3]
    r = v[..., 2 * n + 3:]
    kin = -ubar * eta + np.sum(sh * cosm * b, axis=-1) + q
    uu = -ubar + np.sum(ch * cosm * jk * b, axis=-1)
    ww = np.sum(sh * sinm * jk * b, axis=-1)
    dyn = 0.5 * (uu**2 + ww**2) + eta - r
    mean = np.sum(weights * eta, axis=-1, keepdims=True) - 1.0
    hgt = eta[..., :1] - eta[..., -1:] - height
    return np.concatenate([kin, dyn, mean, hgt], axis=-1)


def _jacobian(v: np.ndarray, n: int, height: float, period: float, current: str,
              cosm: np.ndarray, sinm: np.ndarray, weights: np.ndarray) -> np.ndarray:
    """Jacobian of :func:`_residuals` at ``v`` (2N + 4,) by complex steps of every unknown.

    The residuals of ``v + 1e-30 i e_j`` for all j in one batched evaluation, as
    :func:`_residuals` computes them, except that the depth ratios (most of the cost), which
    only the steps of k and of the η_m change (the latter in the row of point m alone), are
    computed once for the other steps, once for k's and once per point for η_m's.
    """
    vs = v + 1e-30j * np.eye(v.size)  # (M, M): row j steps unknown j
    jk, eta = _modes(vs, n)  # (M, 1, N), (M, N+1)
    other = n + 2  # the step of B_1: neither k nor any η_m moves
    ch = np.empty(vs.shape[:1] + (n + 1, n), complex)
    sh = np.empty_like(ch)
    ch[:], sh[:] = depth_ratios(jk[other], eta[other, :, None], 1.0)
    ch[0], sh[0] = depth_ratios(jk[0], eta[0, :, None], 1.0)
    points = np.arange(n + 1)
    # the step of η_m: point m's row, at the stepped η_m
    ch_m, sh_m = depth_ratios(jk[other], eta[1 + points, points][:, None], 1.0)
    ch[1 + points, points], sh[1 + points, points] = ch_m, sh_m
    return _equations(vs, n, height, period, current, cosm, sinm, weights, ch,
                      sh).imag.T / 1e-30


def _newton(v: np.ndarray, args: tuple, max_iter: int = 40) -> tuple[np.ndarray, float]:
    """Newton's method with the exact Jacobian by complex-step differentiation.

    All unknowns are perturbed at once in one batched evaluation (:func:`_jacobian`); returns
    the root and its residual.
    """
    for _ in range(max_iter):
        f = _residuals(v, *args)
        jac = _jacobian(v, *args)
        step = np.linalg.solve(jac, f)
        v = v - step
        if np.max(np.abs(step)) < 1e-13:
            break
    return v, float(np.max(np.abs(_residuals(v, *args))))


#: spacing of the grid of dimensionless periods T (g/h)^½ and heights H/h whose waves start
#: the Newton iteration of a nearby wave (a few iterations instead of the height continuation)
_ANCHOR_STEP = (0.02, 0.005)


@functools.lru_cache(maxsize=512)
def _grid_wave(tg: int, hg: int, n: int, current: str
               ) -> tuple[np.ndarray, np.ndarray] | None:
    """Solve the grid wave (tg, hg) of :data:`_ANCHOR_STEP` from linear theory.

    Returns its unknowns and the inverse of its Jacobian (for :func:`_chord`), or None beyond
    the highest wave or where it does not converge.
    """
    t_nd, h_nd = tg * _ANCHOR_STEP[0], hg * _ANCHOR_STEP[1]
    k0 = float(wavenumber(2 * np.pi / t_nd, 1.0, 1.0))
    h_max = float(highest_wave(2 * np.pi / k0, 1.0))
    if h_nd >= 0.95 * h_max:
        return None
    try:
        v = _solve(t_nd, h_nd, n, current, 1 + int(np.floor(5 * h_nd / h_max)), k0, h_max,
                   "a grid wave")
    except ValueError:
        return None
    return v, np.linalg.inv(_jacobian(v, n, h_nd, t_nd, current, *_collocation(n)))


def _anchor(t_nd: float, h_nd: float, n: int, current: str
            ) -> tuple[np.ndarray, np.ndarray] | None:
    """Return the grid wave nearest to (T (g/h)^½, H/h) that starts :func:`_solve`'s Newton."""
    hg = round(h_nd / _ANCHOR_STEP[1])
    return _grid_wave(round(t_nd / _ANCHOR_STEP[0]), hg, n, current) if hg >= 1 else None


def _chord(v: np.ndarray, jac_inv: np.ndarray, args: tuple, max_iter: int = 40
           ) -> tuple[np.ndarray, float]:
    """Solve by the chord method: Newton's iteration with the Jacobian of the start fixed.

    From a grid wave within half a grid step the fixed Jacobian contracts the error by about
    the relative distance (a hundredth) per iteration, and each iteration costs a residual
    instead of a Jacobian (the (2N + 4)² complex-step evaluations of :func:`_jacobian`), so it
    reaches a step below 1e-13 several times sooner than :func:`_newton`. Returns the root
    (or the last iterate) and its residual, which the caller checks.
    """
    n, height, period, *fixed = args
    x, res = _chord_many(v[None], jac_inv[None], n, np.array([height]), np.array([period]),
                         tuple(fixed), max_iter)
    return x[0], float(res[0])


def _chord_many(v: np.ndarray, jac_inv: np.ndarray, n: int, height: np.ndarray,
                period: np.ndarray, fixed: tuple, max_iter: int = 40
                ) -> tuple[np.ndarray, np.ndarray]:
    """:func:`_chord` of many waves (rows of ``v``, their heights and periods) at once.

    The residuals of the waves not yet converged are evaluated together; each wave stops as
    :func:`_chord` stops it, and its step is its own matrix-vector product, so that a wave's
    root is the one it has alone.
    """
    v = np.array(v, dtype=float)
    active = np.arange(v.shape[0])
    for _ in range(max_iter):
        if not active.size:
            break
        r = _residuals(v[active], n, height[active, None], period[active, None], *fixed)
        step = np.stack([jac_inv[b] @ r[j] for j, b in enumerate(active)])  # a few waves
        v[active] = v[active] - step
        # converged (or NaN: the caller refuses it)
        active = active[np.max(np.abs(step), axis=-1) >= 1e-13]
    res = np.max(np.abs(_residuals(v, n, height[:, None], period[:, None], *fixed)), axis=-1)
    return v, res


@functools.lru_cache(maxsize=8)
def _collocation(n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """cos(jmπ/N), sin(jmπ/N) (N + 1, N) and the trapezoidal weights (N + 1) of the points."""
    jm = np.outer(np.arange(n + 1), np.arange(1, n + 1)) * np.pi / n  # j k X_m
    weights = np.full(n + 1, 1.0 / n)
    weights[[0, -1]] = 0.5 / n
    return np.cos(jm), np.sin(jm), weights


def _solve(t_nd: float, h_nd: float, n: int, current: str, height_steps: int | None,
           k0: float, h_max: float, label: str) -> np.ndarray:
    """Solve for the unknowns (module notes) of the wave of dimensionless period and height.

    With ``height_steps`` None, Newton's method starts from the nearest wave of a grid
    (:data:`_ANCHOR_STEP`), itself solved from linear theory, so the result depends on the
    inputs only, not on what was solved before; where that fails, and with ``height_steps``
    given, H is raised in steps from linear theory.
    """
    m = np.arange(n + 1)
    cosm, sinm, weights = _collocation(n)
    fixed = (t_nd, current, cosm, sinm, weights)
    if height_steps is None:
        anchor = _anchor(t_nd, h_nd, n, current)
        if anchor is not None:
            x, res = _chord(anchor[0], anchor[1], (n, h_nd) + fixed)
            if not (np.all(np.isfinite(x)) and res < 1e-10):  # too far for a fixed Jacobian
                x, res = _newton(anchor[0].copy(), (n, h_nd) + fixed)
            if np.all(np.isfinite(x)) and res < 1e-10:
                return x
        height_steps = 1 + int(np.floor(5 * h_nd / h_max))

    def linear_guess(hh: float) -> np.ndarray:
        c = 2 * np.pi / (k0 * t_nd)
        v = np.zeros(2 * n + 4)
        v[0] = k0
        v[1:n + 2] = 1.0 + 0.5 * hh * np.cos(m * np.pi / n)
        v[n + 2] = c * 0.5 * hh / np.tanh(k0)
        v[2 * n + 2] = c
        v[2 * n + 3] = 1.0 + 0.5 * c * c
        return v

    previous: list[np.ndarray] = []
    for step in range(1, height_steps + 1):
        hh = h_nd * step / height_steps
        if len(previous) >= 2:
            guess = 2 * previous[-1] - previous[-2]
        elif previous:
            guess = previous[-1]
        else:
            guess = linear_guess(hh)
        x, res = _newton(guess, (n, hh) + fixed)
        if not (np.all(np.isfinite(x)) and res < 1e-10):
            raise ValueError(f"the stream-function solution did not converge for {label} "
                             f"(residual {res:.2e} at height step {step}/{height_steps}); "
                             "raise height_steps")
        previous.append(x)
    return previous[-1]


@functools.lru_cache(maxsize=256)
def _limits(t_nd: float) -> tuple[float, float]:
    """Linear k h and the highest wave's H/h of the dimensionless period T (g/h)^½.

    Cached: the incident and reflected waves of a record, and its passes, share the period.
    """
    k0 = float(wavenumber(2 * np.pi / t_nd, 1.0, 1.0))
    return k0, float(highest_wave(2 * np.pi / k0, 1.0))


def _dimensionless(period: float, height: float, depth: float, g: float
                   ) -> tuple[float, float, float, float]:
    """T (g/h)^½, H/h, the linear k h and the highest wave's H/h; ValueError above 0.95 of it."""
    t_nd = period * np.sqrt(g / depth)
    h_nd = height / depth
    k0, h_max = _limits(float(t_nd))
    if h_nd >= 0.95 * h_max:
        raise ValueError(f"wave height {height} m is too close to or above the highest wave "
                         f"(about {h_max * depth:.3g} m for T = {period} s in h = {depth} m)")
    return t_nd, h_nd, k0, h_max


def stream_function_wave(period: float, height: float, depth: float, *, n_modes: int = 20,
                         current: str = "stokes", height_steps: int | None = None,
                         g: float = G) -> StreamFunctionWave:
    """Solve for the steady nonlinear regular wave of a given period, height and depth.

    Parameters
    ----------
    period : Wave period T [s] (in the frame where the current criterion holds).
    height : Crest-to-trough height H [m], below the highest wave (:func:`highest_wave`).
    depth : Still water depth h [m].
    n_modes : Number N of Fourier modes [-]; 20 is converged to about 1e-6 of H for the
        flume's waves (and far below the Ursell range limits of other theories).
    current : ``"stokes"`` (Stokes' second definition, zero mean mass transport: a closed
        flume) or ``"euler"`` (Stokes' first definition, zero mean Eulerian current).
    height_steps : Number of steps in which H is raised, each started from the extrapolation
        of the previous two solutions (Fenton 1988, §3). Default: Newton's method from the
        nearest wave of a fixed grid in T (g/h)^½ and H/h (steps 0.02 and 0.005), itself
        raised in 1 + ⌊5 H/H_max⌋ steps, so that the result depends on the inputs only;
        that number of steps where no grid wave is close enough.
    g : Gravitational acceleration [m s-2].

    Returns
    -------
    StreamFunctionWave
        The solution, with the Fourier coefficients and the evaluation of η, u and w.

    Raises
    ------
    ValueError
        For non-positive inputs, an unknown ``current``, a height above the highest wave or a
        Newton iteration that does not converge.

    Notes
    -----
    Unknowns (dimensionless, g = h = 1): k, η_m at kX_m = mπ/N (m = 0..N), B_1..B_N, ū or Q, R
    (2N + 4); equations: Eqs. (3) and (4) at the N + 1 points, Eq. (5) by the trapezoidal rule,
    Eq. (6); Eq. (7) with (8) or (9) eliminates c and the other of ū, Q. Solved by Newton's
    method with the exact Jacobian (complex-step derivatives), from linear theory or a grid
    wave (``height_steps``).
    E_j is the discrete cosine transform of the η_m (the trapezoidal rule of Fenton 1988), with
    E_N halved.
    """
    if not all(np.isfinite(v) and v > 0 for v in (period, height, depth, g)):
        raise ValueError("stream_function_wave needs finite period, height, depth and g > 0")
    if current not in CURRENTS:
        raise ValueError(f"current must be one of {CURRENTS}, got {current!r}")
    n = int(n_modes)
    if n < 2:
        raise ValueError(f"n_modes must be at least 2, got {n_modes}")
    t_nd, h_nd, k0, h_max = _dimensionless(period, height, depth, g)
    cosm, _, weights = _collocation(n)
    v = _solve(t_nd, h_nd, n, current, height_steps, k0, h_max,
               f"T = {period} s, H = {height} m, h = {depth} m")
    k = v[0]
    eta = v[1:n + 2]
    b = v[n + 2:2 * n + 2]
    c = 2 * np.pi / (k * t_nd)
    ubar, q = (v[2 * n + 2], c) if current == "stokes" else (c, v[2 * n + 2])
    # DCT-I of the surface points: E_j = (2/N) Σ'' η_m cos(jmπ/N), E_N halved
    e = 2.0 * (weights * (eta - 1.0)) @ cosm
    e[-1] *= 0.5
    vel = np.sqrt(g * depth)
    return StreamFunctionWave(
        period=float(period), height=float(height), depth=float(depth), g=float(g),
        current=current, wavenumber=float(k / depth), celerity=float(c * vel),
        eulerian_current=float((c - ubar) * vel), mass_transport=float((c - q) * vel),
        elevation_coefficients=e * depth, stream_coefficients=b * vel * depth,
        bernoulli=float(v[2 * n + 3] * g * depth), volume_flux=float(q * vel * depth))
