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

Each model is a pair of compiled kernels over its state arrays (:mod:`flumekit.hydro.stepping`),
called once per step by the compiled loop.

References
----------
Cox, S. M., Matthews, P. C. (2002). Exponential time differencing for stiff systems. J. Comput.
Phys. 176, 430-455.
Falnes, J. (2002). Ocean Waves and Oscillating Systems. Cambridge University Press.
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr
from numba import njit

from flumekit.docstrings import filler
from flumekit.hydro.radiation import StateSpace
from flumekit.hydro.stepping import BEGIN, FINISH

#: docstring text that several functions of this module share
_doc = filler(
    step=("step : float\n"
          "    Time step h [s]."))


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
        """Return the seven weights in the order of the constructor."""
        return (self.w21, self.w22, self.w32, self.w33, self.w41, self.w43, self.w44)


class _Memory:
    """A memory integrator: its compiled kernels and state (:mod:`flumekit.hydro.stepping`).

    The state lives in ``c`` (complex) and ``r`` (real) arrays that the kernels advance in
    place; :meth:`begin` and :meth:`finish` call the kernels from Python.
    """

    weights: StageWeights
    c: np.ndarray
    r: np.ndarray

    @property
    def kernels(self):
        """The compiled ``(begin, finish)`` kernels of this model."""
        raise NotImplementedError

    def begin(self, n: int, u1: float) -> tuple[float, float, float]:
        """(M, P_h, P_f) of step ``n`` (module notes) from the state at its start."""
        return self.kernels[0](int(n), float(u1), self.c, self.r)

    def finish(self, u1: float, u2: float, u3: float, u4: float) -> None:
        """Advance the state over the step from the four stage velocities."""
        self.kernels[1](float(u1), float(u2), float(u3), float(u4), self.c, self.r)


class NoMemory(_Memory):
    """No radiation memory: μ = 0 at every stage (a modal model without modes)."""

    def __init__(self):
        self.weights = StageWeights()
        self.c = np.zeros((7, 0), complex)
        self.r = np.zeros(0)

    @property
    def kernels(self):
        """The compiled ``(begin, finish)`` kernels of this model."""
        return _modal_begin, _modal_finish


def phi(z: np.ndarray, k: int) -> np.ndarray:
    """Evaluate the ETD function φ_k(z) = Σ_j z^j/(j+k)! (φ₁ = (e^z − 1)/z, ...).

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


@njit(BEGIN, cache=True)
def _modal_begin(n, u1, c, r):
    # rows of c: e^z, e^{z/2}, the three input weights, the scaled states y, e^z y
    s0 = sh = sf = 0j
    for i in range(c.shape[1]):
        y = c[5, i]
        ey = c[0, i] * y
        c[6, i] = ey
        s0 += y
        sh += c[1, i] * y
        sf += ey
    return s0.real, sh.real, sf.real


@njit(FINISH, cache=True)
def _modal_finish(u1, u2, u3, u4, c, r):
    um = 0.5 * (u2 + u3)
    for i in range(c.shape[1]):
        c[5, i] = c[6, i] + c[2, i] * u1 + c[3, i] * um + c[4, i] * u4
    return 0.0


@_doc
class ModalMemory(_Memory):
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
    %(step)s

    References
    ----------
    Cox, S. M., Matthews, P. C. (2002), Eq. (26)-(29).
    """

    def __init__(self, model: StateSpace, step: float):
        self.model, self.step = model, step
        lam = np.asarray(model.poles, complex)
        c = np.asarray(model.residues, complex)
        h = step
        z, zh = lam * h, lam * h / 2
        p1, p2, p3 = phi(z, 1), phi(z, 2), phi(z, 3)
        q1 = phi(zh, 1)
        eh = np.exp(zh)
        g2 = float(np.real(np.sum(c * h / 2 * q1)))
        g4 = float(np.real(np.sum(c * eh * h / 2 * q1)))
        # μ₂ = P_h + g2 u₁, μ₃ = P_h + g2 u₂, μ₄ = P_f + g4 u₁ + g2 (2 u₃ − u₁)
        self.weights = StageWeights(w21=g2, w32=g2, w41=g4 - g2, w43=2.0 * g2)
        zero = np.zeros(lam.size, complex)
        self.c = np.array([np.exp(z), eh, c * h * (p1 - 3 * p2 + 4 * p3),
                           c * h * (4 * p2 - 8 * p3), c * h * (4 * p3 - p2), zero, zero])
        self.r = np.zeros(0)

    @property
    def kernels(self):
        """The compiled ``(begin, finish)`` kernels of this model."""
        return _modal_begin, _modal_finish


# layout of the convolution's real state: h, M, K(0), K(h/2), the full-step sums of this step
# and the last, then K(m h) and K((m + 1/2) h) for m = 0..M+1, K((m + 1) h) and K((m + 1/2) h)
# for m = M..0 (reversed), and the velocity history
_H, _M, _K0, _KH0, _S1, _S1P, _HEAD = range(7)


@njit(BEGIN, cache=True)
def _convolution_begin(n, u1, c, r):
    h, m, k0, khalf0 = r[_H], int(r[_M]), r[_K0], r[_KH0]
    o_kint = _HEAD
    o_khalf = o_kint + m + 2
    o_k1r = o_khalf + m + 2
    o_khr = o_k1r + m + 1
    o_hist = o_khr + m + 1
    r[o_hist + n] = u1
    w0 = r[o_hist]
    mu1 = h * (r[_S1P] - (0.5 * r[o_kint + n] * w0 if n <= m + 1 else 0.0) + 0.5 * k0 * u1)
    lo = n - m if n > m else 0
    base = m - (n - lo)
    s_half = s1 = 0.0
    for i in range(n - lo + 1):
        w = r[o_hist + lo + i]
        s_half += r[o_khr + base + i] * w
        s1 += r[o_k1r + base + i] * w
    r[_S1] = s1
    p_half = h * (s_half - (0.5 * r[o_khalf + n] * w0 if n <= m else 0.0)
                  - 0.5 * khalf0 * u1) + 0.25 * h * khalf0 * u1
    p_full = h * (s1 - (0.5 * r[o_kint + n + 1] * w0 if n + 1 <= m + 1 else 0.0))
    return mu1, p_half, p_full


@njit(FINISH, cache=True)
def _convolution_finish(u1, u2, u3, u4, c, r):
    r[_S1P] = r[_S1]  # the full-step sum is the next step's memory torque
    return 0.0


@_doc
class ConvolutionMemory(_Memory):
    """The convolution of the impulse response with the velocity history, trapezoidal rule.

    μ at t_n (and the part known at the step's start of μ at t_n + h/2 and t_n + h) is the
    trapezoidal sum of K at the lags m h (or (m + 1/2) h) times the stored velocities, over the
    last M = ⌊T_K / h⌋ steps (T_K the length of K); the stage's own velocity enters with the
    trapezoid's end weight (:attr:`weights`).

    Parameters
    ----------
    irf : xr.DataArray
        K(t) over ``lag`` [s], [N m s rad-1 s-1] (zero beyond its last lag).
    %(step)s
    n_steps : int
        Number of steps of the run (the length of the stored velocity history).

    References
    ----------
    Falnes, J. (2002), Eq. (5.168); Cummins (1962).
    """

    def __init__(self, irf: xr.DataArray, step: float, n_steps: int):
        self.irf, self.step, self.n_steps = irf, step, n_steps
        h = step
        lag = irf["lag"].values
        m = math.floor(float(lag[-1]) / h + 1e-9)
        kk = np.interp(0.5 * h * np.arange(2 * m + 4), lag, irf.values, right=0.0)
        self.weights = StageWeights(w22=0.25 * h * kk[0], w33=0.25 * h * kk[0],
                                    w44=0.5 * h * kk[0])
        self.c = np.zeros((7, 0), complex)
        self.r = np.concatenate([[h, m, kk[0], kk[1], 0.0, 0.0], kk[0::2], kk[1::2],
                                 kk[2::2][: m + 1][::-1], kk[1::2][: m + 1][::-1],
                                 np.zeros(n_steps + 1)])

    @property
    def kernels(self):
        """The compiled ``(begin, finish)`` kernels of this model."""
        return _convolution_begin, _convolution_finish


def memory_integrator(radiation, step: float, n_steps: int):
    """Build the memory integrator of a radiation model.

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
