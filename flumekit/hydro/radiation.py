"""Radiation memory of the Cummins (1962) equation: impulse response and state-space model.

Cummins (1962) writes the radiation torque on a body as

    T_rad(t) = −A∞ θ̈(t) − ∫₀ᵗ K(t − τ) θ̇(τ) dτ,

K(t) = (2/π) ∫₀^∞ B(ω) cos(ωt) dω            (Ogilvie 1964; Cummins 1962)

with A∞ the infinite-frequency added inertia, kept on the left-hand side of the equation of
motion by the simulator (implicit: the effective inertia is I + A∞). The memory term has the
frequency response (time factor e^{-iωt} of :mod:`flumekit.hydro.coefficients`)

    K̂(ω) = ∫₀^∞ K(t) e^{iωt} dt = C(ω) + i S(ω),
    C(ω) = ∫ K cos ωt dt = B(ω),   S(ω) = ∫ K sin ωt dt = ω (A∞ − A(ω))   (Ogilvie 1964),

so that the memory torque of a motion θ̇ = Re{V e^{-iωt}} is Re{K̂ V e^{-iωt}}.

Numerics
--------
* Cosine/sine transforms of piecewise-linear data are evaluated exactly on each interval
  (Filon-type rule), so K(t) at long lags does not alias however coarse the frequency grid.
* High-frequency tail: beyond the last frequency ω_N the damping is continued as
  B(ω) = B(ω_N)(ω_N/ω)^p, p fitted to the last points on a log-log scale (clipped to
  [1.5, 8]; p = 3 is the usual decay of a surface-piercing body's damping), up to
  ``tail_factor``·ω_N; the part of ∫B dω beyond that is reported as ``tail_truncation``
  (a fraction of the whole). Below the first frequency B is held at B(ω₁) (``low="hold"``) or
  ramped linearly to zero (``low="zero"``).
* State space: Kung's (1978) SVD realisation of the sampled K(t) (the eigensystem realisation
  algorithm) gives a discrete system K(kΔ) = C A_dᵏ B; its eigen-decomposition
  A_d = V diag(μ) V⁻¹ gives continuous poles λ = ln μ / Δ and residues, so that
  K(t) ≈ Re Σ c_k e^{λ_k t} with one state per complex-conjugate pair (c_k doubled) or real pole.
  The order is the smallest that meets the requested relative L2 error on K(t); the fitting
  errors in time and in frequency are stored on the model. Unstable poles are reflected into
  the left half-plane (reported).

References
----------
Cummins, W. E. (1962). The impulse response function and ship motions. Schiffstechnik 9,
101-109.
%(ogilvie1964)s.
Kung, S.-Y. (1978). A new identification and model reduction algorithm via singular value
decomposition. Proc. 12th Asilomar Conference on Circuits, Systems and Computers, 705-714.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import xarray as xr

from flumekit import conventions
from flumekit.docstrings import fill, filler

#: docstring text that several functions of this module share
_doc = filler(
    parameters_transform=("Parameters\n"
                          "----------\n"
                          "%(irf)s\n"
                          "%(omega)s"),
    irf=("irf : xarray.DataArray\n"
         "    K(t) [N m] over ``lag`` [s] (:func:`impulse_response`)."),
    omega=("omega : array_like\n"
           "    Angular frequencies [rad s-1]."))

__doc__ = fill(__doc__)

DIM = "angular_frequency"


def _sinc(d: np.ndarray) -> np.ndarray:
    return np.sinc(d / np.pi)


def _g(d: np.ndarray) -> np.ndarray:
    """(sin d − d cos d)/(2 d²), series below |d| = 1e-2 (value ≈ d/6)."""
    d = np.asarray(d, dtype=float)
    out = np.empty_like(d)
    small = np.abs(d) < 1e-2
    ds = d[small]
    out[small] = ds / 6 - ds**3 / 60
    dl = d[~small]
    out[~small] = (np.sin(dl) - dl * np.cos(dl)) / (2 * dl * dl)
    return out


def filon(x, f, y, kind: str) -> np.ndarray:
    """Integrate f(x) cos(y x) or f(x) sin(y x) over [x₀, x_N], exactly for piecewise-linear f.

    On [x_j, x_{j+1}] with centre x̄, half-width Δ/2, mean f̄ and increment Δf, c = y x̄ and
    d = yΔ/2:  ∫ f cos = Δ[f̄ cos c sinc d − Δf sin c g(d)],  ∫ f sin = Δ[f̄ sin c sinc d +
    Δf cos c g(d)], g(d) = (sin d − d cos d)/(2d²).

    Parameters
    ----------
    x : array_like
        Nodes, increasing, shape (N+1,) (units of x).
    f : array_like
        Values at the nodes, shape (N+1,) (units of f).
    y : array_like
        Transform variable(s), any shape (units of 1/x).
    kind : {"cos", "sin"}
        Which transform.

    Returns
    -------
    numpy.ndarray
        The integral for every ``y`` [units of f times x], shape of ``y``.

    Raises
    ------
    ValueError
        ``kind`` is neither "cos" nor "sin".

    References
    ----------
    Filon, L. N. G. (1928). On a quadrature formula for trigonometric integrals. Proc. Roy.
    Soc. Edinburgh 49, 38-47.

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.hydro.radiation import filon
    >>> x = np.linspace(0.0, np.pi / 2, 3)  # f = 1: exact however coarse the grid
    >>> round(float(filon(x, np.ones(3), 1.0, "cos")), 12)
    1.0
    """
    x = np.asarray(x, dtype=float)
    f = np.asarray(f, dtype=float)
    y = np.asarray(y, dtype=float)
    dx = np.diff(x)
    xm = 0.5 * (x[1:] + x[:-1])
    fm = 0.5 * (f[1:] + f[:-1])
    df = np.diff(f)
    yy = y.reshape(-1, 1)
    c = yy * xm
    d = 0.5 * yy * dx
    s, g = _sinc(d), _g(d)
    if kind == "cos":
        val = dx * (fm * np.cos(c) * s - df * np.sin(c) * g)
    elif kind == "sin":
        val = dx * (fm * np.sin(c) * s + df * np.cos(c) * g)
    else:
        raise ValueError(f"kind must be 'cos' or 'sin', got {kind!r}")
    return val.sum(axis=1).reshape(y.shape)


def _tail_exponent(w: np.ndarray, b: np.ndarray, n_fit: int = 5) -> float:
    ww, bb = w[-n_fit:], b[-n_fit:]
    ok = bb > 0
    if ok.sum() < 2:
        return 3.0
    slope = np.polyfit(np.log(ww[ok]), np.log(bb[ok]), 1)[0]
    return float(np.clip(-slope, 1.5, 8.0))


@_doc
def extended_damping(hydro: xr.Dataset, *, tail: str = "power", tail_exponent: float | None = None,
                     tail_factor: float = 20.0, low: str = "hold",
                     n_tail: int = 400) -> tuple[np.ndarray, np.ndarray, dict]:
    """Extend the damping to [0, tail_factor·ω_N] at low and high frequencies (module notes).

    Parameters
    ----------
    %(hydro)s
    tail : {"power", "none"}, optional
        High-frequency continuation: B(ω_N)(ω_N/ω)^p, or none.
    tail_exponent : float, optional
        The exponent p [-], > 1; by default fitted to the last points (clipped to [1.5, 8]).
    tail_factor : float, optional
        Upper end of the continuation as a multiple of ω_N [-].
    low : {"hold", "zero"}, optional
        Below ω₁: B held at B(ω₁), or ramped linearly to zero at ω = 0.
    n_tail : int, optional
        Number of geometrically spaced nodes of the continuation.

    Returns
    -------
    omega : numpy.ndarray
        Nodes [rad s-1], from 0.
    damping : numpy.ndarray
        B at the nodes [N m s].
    info : dict
        What was done: ``omega_min``, ``omega_max`` [rad s-1], ``tail_exponent`` [-] and the
        fractions [-] ``tail_fraction`` and ``tail_truncation`` of ∫B dω.

    Raises
    ------
    ValueError
        An unknown ``tail`` or ``low``, or a tail exponent ≤ 1 (K(0) would be infinite).
    """
    w = hydro[DIM].values.astype(float)
    b = hydro["radiation_damping"].values.astype(float)
    if low == "hold":
        w0, b0 = [0.0], [b[0]]
    elif low == "zero":
        w0, b0 = [0.0], [0.0]
    else:
        raise ValueError(f"low must be 'hold' or 'zero', got {low!r}")
    ww, bb = np.concatenate([w0, w]), np.concatenate([b0, b])
    info = {"omega_min": float(w[0]), "omega_max": float(w[-1]), "low": low, "tail": tail}
    total_data = float(np.trapezoid(bb, ww))
    if tail == "none" or b[-1] <= 0:
        info.update(tail_exponent=np.nan, tail_fraction=0.0,
                    tail_truncation=float(max(b[-1], 0) * w[-1] / max(abs(total_data), 1e-300)))
        return ww, bb, info
    if tail != "power":
        raise ValueError(f"tail must be 'power' or 'none', got {tail!r}")
    p = _tail_exponent(w, b) if tail_exponent is None else float(tail_exponent)
    if not p > 1:
        raise ValueError(f"the tail exponent must be > 1 for a finite K(0), got {p}")
    wt = w[-1] * np.geomspace(1.0, tail_factor, n_tail + 1)[1:]
    bt = b[-1] * (w[-1] / wt) ** p
    tail_int = b[-1] * w[-1] / (p - 1) * (1 - tail_factor ** (1 - p))
    beyond = b[-1] * w[-1] / (p - 1) * tail_factor ** (1 - p)
    total = total_data + tail_int + beyond
    info.update(tail_exponent=p, tail_fraction=float(tail_int / total),
                tail_truncation=float(beyond / total))
    return np.concatenate([ww, wt]), np.concatenate([bb, bt]), info


@_doc
def impulse_response(hydro: xr.Dataset, duration: float | None = None, dt: float | None = None, *,
                     tail: str = "power", tail_exponent: float | None = None,
                     tail_factor: float = 20.0, low: str = "hold") -> xr.DataArray:
    """Compute the radiation impulse response K(t) = (2/π) ∫₀^∞ B(ω) cos(ωt) dω.

    Parameters
    ----------
    %(hydro)s
    duration : float, optional
        Longest lag [s]; default 30 s.
    dt : float, optional
        Lag step [s]; default π/(8 ω_N) capped at 0.05 s.
    tail, tail_exponent, tail_factor, low : optional
        High- and low-frequency extension of B, as in :func:`extended_damping`.

    Returns
    -------
    xarray.DataArray
        ``radiation_irf`` K(t) [N m] over ``lag`` [s]; attrs describe the extension
        (``tail_exponent``, ``tail_fraction``, ``tail_truncation``, ``omega_min``,
        ``omega_max``).

    Raises
    ------
    ValueError
        ``duration`` or ``dt`` not positive, or an invalid extension (:func:`extended_damping`).

    References
    ----------
    Cummins, W. E. (1962). The impulse response function and ship motions. Schiffstechnik 9,
    101-109.
    %(ogilvie1964)s.

    Examples
    --------
    Constant damping without a tail is a sinc: K(0) = (2/π) B ω_N.

    >>> import numpy as np
    >>> from flumekit.hydro.coefficients import hydro_dataset
    >>> from flumekit.hydro.radiation import impulse_response
    >>> hydro = hydro_dataset([1.0, 4.0], [5.0, 5.0], [2.0, 2.0], [1, 1], 10.0)
    >>> k = impulse_response(hydro, duration=1.0, tail="none")
    >>> round(float(k[0]) * np.pi / 2, 9)  # B ω_N = 8 N m
    8.0
    """
    w_n = float(hydro[DIM].values[-1])
    duration = 30.0 if duration is None else float(duration)
    dt = min(0.05, np.pi / (8 * w_n)) if dt is None else float(dt)
    if not (duration > 0 and dt > 0):
        raise ValueError("impulse_response needs duration > 0 and dt > 0")
    n = round(duration / dt)
    t = np.arange(n + 1) * dt
    ww, bb, info = extended_damping(hydro, tail=tail, tail_exponent=tail_exponent,
                                    tail_factor=tail_factor, low=low)
    k = 2.0 / np.pi * filon(ww, bb, t, "cos")
    da = xr.DataArray(k, dims="lag", coords={"lag": t}, name="radiation_irf",
                      attrs={k_: v for k_, v in info.items()})
    return conventions.annotate(da)


@_doc
def sine_transform(irf: xr.DataArray, omega) -> np.ndarray:
    """Compute S(ω) = ∫₀^L K(t) sin(ωt) dt (equals ω(A∞ − A(ω)) for an exact K).

    %(parameters_transform)s

    Returns
    -------
    numpy.ndarray
        S(ω) [N m s], shape of ``omega``.

    %(references_ogilvie1964)s.
    """
    return filon(irf["lag"].values, irf.values, omega, "sin")


@_doc
def memory_response(irf: xr.DataArray, omega) -> np.ndarray:
    """Compute K̂(ω) = C(ω) + i S(ω), the memory torque per unit θ̇ amplitude.

    C(ω) = ∫₀^L K(t) cos(ωt) dt and S(ω) = ∫₀^L K(t) sin(ωt) dt (:func:`sine_transform`).

    %(parameters_transform)s

    Returns
    -------
    numpy.ndarray of complex
        K̂(ω) [N m s] (time factor e^{-iωt}), shape of ``omega``.

    Notes
    -----
    For an exact K, C(ω) is the radiation damping B(ω) and S(ω) is ω (A∞ − A(ω)), so K̂ tells
    how well a truncated impulse response, or a state-space fit of it, keeps the coefficients
    it came from.
    """
    return filon(irf["lag"].values, irf.values, omega, "cos") + 1j * sine_transform(irf, omega)


# --- state space -----------------------------------------------------------------------------

@dataclass(frozen=True)
class StateSpace:
    """Modal state-space model of the radiation memory.

    States x_k (complex, one per pole kept): ẋ_k = λ_k x_k + θ̇; memory torque
    μ(t) = Re Σ c_k x_k, so that K(t) ≈ Re Σ c_k e^{λ_k t}. Conjugate pairs are represented by
    the member with Im λ > 0 and a doubled residue; real poles by themselves.
    """

    poles: np.ndarray  # λ_k [s-1], complex, Re λ < 0
    residues: np.ndarray  # c_k [N m], complex
    fit_error_time: float = np.nan  # relative L2 error on K(t) over the fitted lags
    fit_error_frequency: float = np.nan  # max |K̂_ss − K̂| / max |K̂| over the hydro band
    fit_dt: float = np.nan  # sampling interval of the realisation [s]
    n_reflected: int = 0  # unstable poles reflected into the left half-plane
    hankel_singular_values: np.ndarray = field(default_factory=lambda: np.empty(0))

    @property
    def order(self) -> int:
        """Number of real states (2 per complex pair, 1 per real pole)."""
        return int(sum(2 if abs(p.imag) > 0 else 1 for p in self.poles))

    def impulse(self, t) -> np.ndarray:
        """Return the model's impulse response K_ss(t) [N m] at lags ``t`` [s]."""
        t = np.asarray(t, dtype=float)
        return np.real(np.exp(np.multiply.outer(t, self.poles)) @ self.residues)

    def frequency_response(self, omega) -> np.ndarray:
        """Return K̂_ss(ω) [N m s] at ``omega`` [rad s-1], as :func:`memory_response` defines it."""
        w = np.asarray(omega, dtype=float)
        out = np.zeros(w.shape, dtype=complex)
        iw = 1j * w
        # ∫₀^∞ r e^{λt} e^{iωt} dt = r / (−iω − λ), Re λ < 0
        for lam, c in zip(self.poles, self.residues):
            if abs(lam.imag) > 0:  # pair: c/2 at λ and at its conjugate
                out += 0.5 * c / (-iw - lam) + 0.5 * np.conj(c) / (-iw - np.conj(lam))
            else:
                out += c.real / (-iw - lam.real)
        return out

    def matrices(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Return real (A, B, C) with ẋ = A x + B θ̇, μ = C x (2×2 blocks for pairs)."""
        n = self.order
        a, b, c = np.zeros((n, n)), np.zeros(n), np.zeros(n)
        i = 0
        for lam, res in zip(self.poles, self.residues):
            if abs(lam.imag) > 0:
                # x = u + i v: u' = σu − ωv + θ̇, v' = ωu + σv; μ = Re(c x) = c_r u − c_i v
                a[i:i + 2, i:i + 2] = [[lam.real, -lam.imag], [lam.imag, lam.real]]
                b[i] = 1.0
                c[i], c[i + 1] = res.real, -res.imag
                i += 2
            else:
                a[i, i], b[i], c[i] = lam.real, 1.0, res.real
                i += 1
        return a, b, c


def _realise(k: np.ndarray, dt: float, u: np.ndarray, s: np.ndarray, vt: np.ndarray,
             h1: np.ndarray, n: int):
    sq = np.sqrt(s[:n])
    ad = (u[:, :n].T @ h1 @ vt[:n].T) / np.outer(sq, sq)
    bd = sq * vt[:n, 0]
    cd = u[0, :n] * sq
    mu, v = np.linalg.eig(ad)
    res = (cd @ v) * np.linalg.solve(v, bd.astype(complex))
    lam = np.log(mu.astype(complex)) / dt
    n_refl = int(np.sum(lam.real >= 0))
    lam = np.where(lam.real >= 0, -np.abs(lam.real) - 1e-9 / dt + 1j * lam.imag, lam)
    keep_p, keep_c = [], []
    for lm, r in zip(lam, res):
        if lm.imag > 1e-9 / dt:
            keep_p.append(lm)
            keep_c.append(2 * r)
        elif abs(lm.imag) <= 1e-9 / dt:
            keep_p.append(complex(lm.real, 0.0))
            keep_c.append(complex(r.real, 0.0))
    return np.array(keep_p, dtype=complex), np.array(keep_c, dtype=complex), n_refl


def fit_state_space(irf: xr.DataArray, order: int | None = None, *, rtol: float = 0.01,
                    max_order: int = 24, fit_dt: float | None = None,
                    omega=None) -> StateSpace:
    """Fit a state-space model to K(t) by Kung's (1978) SVD realisation (module notes).

    Parameters
    ----------
    irf : xarray.DataArray
        K(t) [N m] over ``lag`` [s] from :func:`impulse_response`.
    order : int, optional
        Number of Hankel singular values kept (real state dimension); by default the
        smallest that reaches ``rtol``.
    rtol : float, optional
        Target relative L2 error [-] of K_ss(t) against K(t) over the IRF lags.
    max_order : int, optional
        Largest order tried.
    fit_dt : float, optional
        Sampling interval used for the realisation [s] (a multiple of the IRF step); default
        the multiple nearest to π/(4 ω_max) of the coefficients, at least the IRF step.
    omega : array_like, optional
        Angular frequencies [rad s-1] for the frequency-domain error; default 200 points over
        the coefficients' band (``omega_min``/``omega_max`` attrs of ``irf``).

    Returns
    -------
    StateSpace
        The model with ``fit_error_time`` and ``fit_error_frequency`` [-]; when no order up to
        ``max_order`` reaches ``rtol``, the one with the smallest error in time.

    Raises
    ------
    ValueError
        Fewer than 8 samples at ``fit_dt``, or ``order`` out of range.

    References
    ----------
    Kung, S.-Y. (1978). A new identification and model reduction algorithm via singular value
    decomposition. Proc. 12th Asilomar Conference on Circuits, Systems and Computers, 705-714.

    Examples
    --------
    A kernel of one damped cosine needs one complex pole pair:

    >>> from flumekit.hydro.coefficients import from_kernel
    >>> from flumekit.hydro.radiation import fit_state_space, impulse_response
    >>> import numpy as np
    >>> w = np.linspace(0.2, 20.0, 200)
    >>> hydro = from_kernel(w, 50.0, 1.0, 3.0, added_inertia_infinite=10.0,
    ...                     excitation_torque=np.ones(w.size), hydrostatic_stiffness=100.0)
    >>> fit_state_space(impulse_response(hydro)).order
    2
    """
    t = irf["lag"].values
    k = irf.values.astype(float)
    dt0 = float(t[1] - t[0])
    w_max = float(irf.attrs.get("omega_max", np.pi / (4 * dt0)))
    if fit_dt is None:
        fit_dt = max(dt0, np.pi / (4 * w_max))
    step = max(1, round(fit_dt / dt0))
    ks = k[::step]
    d = dt0 * step
    n_s = ks.size
    if n_s < 8:
        raise ValueError("the impulse response is too short for a realisation (< 8 samples)")
    # a wide Hankel matrix with at most 120 block rows: every sample is used, the SVD stays
    # cheap (O(rows² cols)) and 120 rows leave room for any order tried
    rows = min((n_s - 1) // 2, 120)
    cols = n_s - 1 - rows
    idx = np.arange(rows)[:, None] + np.arange(cols)[None, :]
    h0, h1 = ks[idx], ks[idx + 1]
    u, s, vt = np.linalg.svd(h0, full_matrices=False)
    if omega is None:
        omega = np.linspace(float(irf.attrs.get("omega_min", w_max / 20)), w_max, 200)
    ref = memory_response(irf, omega)
    norm_t = float(np.sqrt(np.sum(k**2)))
    norm_f = float(np.max(np.abs(ref)))

    def build(n):
        poles, res, nr = _realise(ks, d, u, s, vt, h1, n)
        ss = StateSpace(poles, res, fit_dt=d, n_reflected=nr, hankel_singular_values=s[:n])
        e_t = float(np.sqrt(np.sum((ss.impulse(t) - k) ** 2)) / norm_t)
        e_f = float(np.max(np.abs(ss.frequency_response(omega) - ref)) / norm_f)
        return StateSpace(poles, res, e_t, e_f, d, nr, s[:n])

    if order is not None:
        if not 1 <= order <= min(rows, cols):
            raise ValueError(f"order must be between 1 and {min(rows, cols)}, got {order}")
        return build(int(order))
    best = None
    for n in range(1, min(max_order, rows, cols) + 1):
        ss = build(n)
        if best is None or ss.fit_error_time < best.fit_error_time:
            best = ss
        if ss.fit_error_time <= rtol:
            return ss
    return best


def state_space_dataset(ss: StateSpace) -> xr.Dataset:
    """Return the model as netCDF-ready variables over ``radiation_mode``.

    The model is fitted once per campaign and shared through this dataset
    (:func:`state_space_from_dataset` reads it back).

    Parameters
    ----------
    ss : StateSpace
        The model (:func:`fit_state_space`).

    Returns
    -------
    xarray.Dataset
        Real and imaginary parts of the poles [s-1] and residues [N m], with the fit errors
        [-], the realisation step [s] and the number of reflected poles in ``attrs``.

    Examples
    --------
    The kernel K(t) = 50 e^{−t} cos 3t is one pole pair λ = −1 ± 3i with residue 50 N m:

    >>> import numpy as np
    >>> from flumekit.hydro.radiation import StateSpace, state_space_dataset
    >>> ds = state_space_dataset(StateSpace(np.array([-1 + 3j]), np.array([50 + 0j])))
    >>> dict(ds.sizes), ds["radiation_residue_real"].values.tolist()
    ({'radiation_mode': 1}, [50.0])
    >>> ds["radiation_pole_real"].values.tolist(), ds["radiation_pole_imag"].values.tolist()
    ([-1.0], [3.0])
    """
    p, r = np.asarray(ss.poles, complex), np.asarray(ss.residues, complex)
    dim = "radiation_mode"
    ds = xr.Dataset({
        "radiation_pole_real": (dim, p.real, {"units": "s-1",
                                              "long_name": "radiation state-space pole (real)"}),
        "radiation_pole_imag": (dim, p.imag, {"units": "s-1",
                                              "long_name": "radiation state-space pole (imag)"}),
        "radiation_residue_real": (dim, r.real, {"units": "N m", "long_name":
                                                 "radiation state-space residue (real)"}),
        "radiation_residue_imag": (dim, r.imag, {"units": "N m", "long_name":
                                                 "radiation state-space residue (imag)"})})
    ds.attrs.update(radiation_fit_error_time=float(ss.fit_error_time),
                    radiation_fit_error_frequency=float(ss.fit_error_frequency),
                    radiation_fit_dt=float(ss.fit_dt), radiation_n_reflected=int(ss.n_reflected))
    return ds


def state_space_from_dataset(ds: xr.Dataset) -> StateSpace:
    """Rebuild the model from :func:`state_space_dataset`'s variables.

    Also accepts the parts merged into complex ``radiation_pole``/``radiation_residue`` by
    :func:`flumekit.hydro.coefficients.merge_complex`.

    Parameters
    ----------
    ds : xarray.Dataset
        Poles [s-1] and residues [N m] over ``radiation_mode``, fit information in ``attrs``.

    Returns
    -------
    StateSpace
        The model.

    Examples
    --------
    A model through a netCDF file and back, K(0) = 50 N m before and after:

    >>> import tempfile
    >>> from pathlib import Path
    >>> import numpy as np
    >>> import xarray as xr
    >>> from flumekit.hydro.radiation import (StateSpace, state_space_dataset,
    ...                                       state_space_from_dataset)
    >>> model = StateSpace(np.array([-1 + 3j, -0.5]), np.array([40 + 10j, 10 + 0j]))
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     path = Path(tmp) / "radiation.nc"
    ...     state_space_dataset(model).to_netcdf(path)
    ...     back = state_space_from_dataset(xr.load_dataset(path))
    >>> back.order, back.poles.tolist(), float(back.impulse(0.0))
    (3, [(-1+3j), (-0.5+0j)], 50.0)

    The complex form that :func:`~flumekit.hydro.coefficients.merge_complex` makes reads alike:

    >>> from flumekit.hydro.coefficients import merge_complex
    >>> state_space_from_dataset(merge_complex(state_space_dataset(model))).residues.tolist()
    [(40+10j), (10+0j)]
    """

    def get(name):
        if name in ds:
            return np.asarray(ds[name].values, dtype=complex)
        return ds[f"{name}_real"].values + 1j * ds[f"{name}_imag"].values

    a = ds.attrs
    return StateSpace(get("radiation_pole"), get("radiation_residue"),
                      float(a.get("radiation_fit_error_time", np.nan)),
                      float(a.get("radiation_fit_error_frequency", np.nan)),
                      float(a.get("radiation_fit_dt", np.nan)),
                      int(a.get("radiation_n_reflected", 0)))
