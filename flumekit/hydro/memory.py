"""Radiation-memory integrators for the time-domain simulator, one per radiation model.

The memory torque μ(t) = ∫₀ᵗ K(t − τ) θ̇(τ) dτ of the Cummins equation enters each of the four
stages of the Runge-Kutta step of :mod:`flumekit.hydro.simulation`. Over one step of length h
from t_n, every model here gives μ at the stages as an affine function of the stage velocities
u₁ = θ̇_n, u₂, u₃ (at t_n + h/2) and u₄ (at t_n + h):

    μ₁ = M,   μ₂ = P_h + w₂₁ u₁ + w₂₂ u₂,   μ₃ = P_h + w₃₂ u₂ + w₃₃ u₃,
    μ₄ = P_f + w₄₁ u₁ + w₄₃ u₃ + w₄₄ u₄,

where (M, P_h, P_f) depend on the history before t_n (:meth:`begin`) and the weights w are
constants of the model and step (:attr:`weights`). After the stage velocities are known,
:meth:`finish` advances the model's own state over the step. The Runge-Kutta step is written
once, in the simulator, for all three models:

* :class:`NoMemory`: μ = 0;
* :class:`ModalMemory`: the state-space model K(t) ≈ Re Σ c_k e^{λ_k t} of
  :class:`flumekit.hydro.radiation.StateSpace`, advanced by exponential time differencing
  (ETDRK4, Cox & Matthews 2002), exact for the fast modes whatever the step;
* :class:`ConvolutionMemory`: the impulse response K(t) sampled every h/2, the convolution by the
  trapezoidal rule on the step grid (Falnes 2002, Sec. 5.9).

The methods work on Python floats: they run once per time step, where a numpy call costs more
than the arithmetic (the convolution's dot product over the kernel's length excepted).

References
----------
Cox, S. M., Matthews, P. C. (2002). Exponential time differencing for stiff systems. J. Comput.
Phys. 176, 430-455.
Falnes, J. (2002). Ocean Waves and Oscillating Systems. Cambridge University Press.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from operator import mul

import numpy as np
import xarray as xr

from flumekit.hydro.radiation import StateSpace


class StageWeights:
    """Weights of the stage velocities in the memory torque (module notes).

    Parameters
    ----------
    w21, w22, w32, w33, w41, w43, w44 : float
        Weights [N m s rad-1] of the stage velocities u_j in μ at stage i.
    """

    __slots__ = ("w21", "w22", "w32", "w33", "w41", "w43", "w44")

    def __init__(self, w21=0.0, w22=0.0, w32=0.0, w33=0.0, w41=0.0, w43=0.0, w44=0.0):
        self.w21, self.w22, self.w32, self.w33 = float(w21), float(w22), float(w32), float(w33)
        self.w41, self.w43, self.w44 = float(w41), float(w43), float(w44)

    def astuple(self) -> tuple[float, ...]:
        """The seven weights in the order of the constructor."""
        return (self.w21, self.w22, self.w32, self.w33, self.w41, self.w43, self.w44)


class NoMemory:
    """No radiation memory: μ = 0 at every stage."""

    weights = StageWeights()

    def begin(self, n: int, u1: float) -> tuple[float, float, float]:
        """(M, P_h, P_f) of step ``n`` (module notes): all zero."""
        return 0.0, 0.0, 0.0

    def finish(self, u1: float, u2: float, u3: float, u4: float) -> None:
        """Nothing to advance."""


def phi(z: np.ndarray, k: int) -> np.ndarray:
    """The ETD function φ_k(z) = Σ_j z^j/(j+k)! (φ₁ = (e^z − 1)/z, ...).

    Parameters
    ----------
    z : array of complex
        Argument (a pole times a step, dimensionless).
    k : int
        Order, ≥ 1.

    Returns
    -------
    ndarray of complex
        φ_k(z), by its Taylor series for |z| < 1 (where the closed form cancels) and the closed
        form elsewhere.

    References
    ----------
    Cox, S. M., Matthews, P. C. (2002), Eq. (4)-(6).

    Examples
    --------
    >>> complex(phi(np.array([0.0]), 1)[0])
    (1+0j)
    """
    z = np.asarray(z, dtype=complex)
    out = np.empty_like(z)
    small = np.abs(z) < 1.0
    zs = z[small]
    acc = np.zeros_like(zs)
    term = np.full_like(zs, 1.0 / math.factorial(k))
    for j in range(30):
        acc += term
        term = term * zs / (j + k + 1)
    out[small] = acc
    zl = z[~small]
    e = np.exp(zl)
    poly = sum(zl**j / math.factorial(j) for j in range(k))
    out[~small] = (e - poly) / zl**k
    return out


@dataclass
class ModalMemory:
    """Exponential (ETDRK4) update of the radiation modes of a state-space model.

    The modal states are scaled, y_k = c_k x_k, so that μ = Re Σ y_k. Over a step,
    x(h) = e^z x + h[(φ₁ − 3φ₂ + 4φ₃) u₁ + (4φ₂ − 8φ₃) u_m + (4φ₃ − φ₂) u₄] (z = λh) is exact
    for the quadratic θ̇ through u₁, u_m = (u₂ + u₃)/2 and u₄ (the final step of ETDRK4); the
    stages x₂ = e^{z/2} x + (h/2) φ₁(z/2) u₁, x₃ likewise with u₂ and
    x₄ = e^{z/2} x₂ + (h/2) φ₁(z/2)(2 u₃ − u₁) make μ at the stages Re Σ c e^{z/2} x (or
    c e^z x) plus scalar multiples of the stage velocities.

    Parameters
    ----------
    model : StateSpace
        Poles λ_k [s-1] and residues c_k [N m s rad-1 s-1] of K(t).
    step : float
        Time step h [s].

    References
    ----------
    Cox, S. M., Matthews, P. C. (2002), Eq. (26)-(29).
    """

    model: StateSpace
    step: float
    y: list = field(init=False)
    weights: StageWeights = field(init=False)

    def __post_init__(self):
        lam = np.asarray(self.model.poles, complex)
        c = np.asarray(self.model.residues, complex)
        h = self.step
        z, zh = lam * h, lam * h / 2
        p1, p2, p3 = phi(z, 1), phi(z, 2), phi(z, 3)
        q1 = phi(zh, 1)
        eh = np.exp(zh)
        self._e = np.exp(z).tolist()
        self._eh = eh.tolist()
        self._qa = (c * h * (p1 - 3 * p2 + 4 * p3)).tolist()
        self._qm = (c * h * (4 * p2 - 8 * p3)).tolist()
        self._qb = (c * h * (4 * p3 - p2)).tolist()
        g2 = float(np.real(np.sum(c * h / 2 * q1)))
        g4 = float(np.real(np.sum(c * eh * h / 2 * q1)))
        # μ₂ = P_h + g2 u₁, μ₃ = P_h + g2 u₂, μ₄ = P_f + g4 u₁ + g2 (2 u₃ − u₁)
        self.weights = StageWeights(w21=g2, w32=g2, w41=g4 - g2, w43=2.0 * g2)
        self.y = [0j] * lam.size
        self._ey = self.y

    def begin(self, n: int, u1: float) -> tuple[float, float, float]:
        """(M, P_h, P_f) of step ``n`` (module notes) from the modal states at its start."""
        y = self.y
        self._ey = ey = list(map(mul, self._e, y))
        return sum(y).real, sum(map(mul, self._eh, y)).real, sum(ey).real

    def finish(self, u1: float, u2: float, u3: float, u4: float) -> None:
        """Advance the modal states over the step."""
        um = 0.5 * (u2 + u3)
        self.y = [e + a * u1 + b * um + c * u4
                  for e, a, b, c in zip(self._ey, self._qa, self._qm, self._qb)]


@dataclass
class ConvolutionMemory:
    """The convolution of the impulse response with the velocity history, trapezoidal rule.

    μ at t_n (and the part known at the step's start of μ at t_n + h/2 and t_n + h) is the
    trapezoidal sum of K at the lags m h (or (m + 1/2) h) times the stored velocities, over the
    last M = ⌊T_K / h⌋ steps (T_K the length of K); the stage's own velocity enters with the
    trapezoid's end weight (:attr:`weights`).

    Parameters
    ----------
    irf : xr.DataArray
        K(t) over ``lag`` [s], [N m s rad-1 s-1] (zero beyond its last lag).
    step : float
        Time step h [s].
    n_steps : int
        Number of steps of the run (the length of the stored velocity history).

    References
    ----------
    Falnes, J. (2002), Eq. (5.168); Cummins (1962).
    """

    irf: xr.DataArray
    step: float
    n_steps: int
    history: np.ndarray = field(init=False)
    weights: StageWeights = field(init=False)

    def __post_init__(self):
        h = self.step
        lag = self.irf["lag"].values
        m = math.floor(float(lag[-1]) / h + 1e-9)
        kk = np.interp(0.5 * h * np.arange(2 * m + 4), lag, self.irf.values, right=0.0)
        self._m = m
        self._k0, self._khalf0 = float(kk[0]), float(kk[1])
        self._kint = kk[0::2].tolist()  # K(m h), m = 0..M+1
        self._khalf = kk[1::2].tolist()  # K((m + 1/2) h)
        self._k1r = kk[2::2][: m + 1][::-1].copy()  # K((m + 1) h), reversed
        self._khr = kk[1::2][: m + 1][::-1].copy()  # K((m + 1/2) h), reversed
        self.history = np.zeros(self.n_steps + 1)
        self._s1 = self._s1_prev = 0.0
        self.weights = StageWeights(w22=0.25 * h * self._k0, w33=0.25 * h * self._k0,
                                    w44=0.5 * h * self._k0)

    def begin(self, n: int, u1: float) -> tuple[float, float, float]:
        """(M, P_h, P_f) of step ``n`` (module notes); stores θ̇_n in the history."""
        h, m, hist = self.step, self._m, self.history
        hist[n] = u1
        w0 = hist[0]
        mu1 = h * (self._s1_prev - (0.5 * self._kint[n] * w0 if n <= m + 1 else 0.0)
                   + 0.5 * self._k0 * u1)
        lo = n - m if n > m else 0
        win = hist[lo:n + 1]
        s_half = float(np.dot(self._khr[m - (n - lo):], win))
        self._s1 = float(np.dot(self._k1r[m - (n - lo):], win))
        p_half = h * (s_half - (0.5 * self._khalf[n] * w0 if n <= m else 0.0)
                      - 0.5 * self._khalf0 * u1) + 0.25 * h * self._khalf0 * u1
        p_full = h * (self._s1 - (0.5 * self._kint[n + 1] * w0 if n + 1 <= m + 1 else 0.0))
        return mu1, p_half, p_full

    def finish(self, u1: float, u2: float, u3: float, u4: float) -> None:
        """Keep the full-step sum for the next step's memory torque."""
        self._s1_prev = self._s1


def memory_integrator(radiation, step: float, n_steps: int):
    """The memory integrator of a radiation model.

    Parameters
    ----------
    radiation : StateSpace, xr.DataArray or None
        A state-space model, an impulse response over ``lag``, or None (no memory).
    step : float
        Time step [s].
    n_steps : int
        Number of steps of the run.

    Returns
    -------
    ModalMemory, ConvolutionMemory or NoMemory

    Raises
    ------
    TypeError
        If ``radiation`` is none of these.

    Examples
    --------
    >>> memory_integrator(None, 0.1, 10).begin(0, 0.0)
    (0.0, 0.0, 0.0)
    """
    if radiation is None:
        return NoMemory()
    if isinstance(radiation, StateSpace):
        return ModalMemory(radiation, step)
    if isinstance(radiation, xr.DataArray):
        return ConvolutionMemory(radiation, step, n_steps)
    raise TypeError("radiation must be a StateSpace, an impulse response over 'lag', or None")


__all__ = ["ConvolutionMemory", "ModalMemory", "NoMemory", "StageWeights", "memory_integrator",
           "phi"]
