"""Time-domain simulator of any one-degree-of-freedom body in waves (Cummins equation).

Equation of motion of the body's coordinate θ (an angle about a hinge [rad], or a
displacement [m] with masses in place of inertias) (Cummins 1962; Falnes 2002, Eq. 5.167):

    (I + A∞) θ̈ = T_exc(t) − μ(t) − T_g(θ) − c_d θ̇|θ̇| − T_PTO

* μ(t) = ∫₀ᵗ K(t − τ) θ̇(τ) dτ, the radiation memory, by convolution with the impulse
  response K(t) or by the modal state-space model of :mod:`flumekit.hydro.radiation`;
* T_g = C θ (``restoring="linear"``) or C sin θ (``"sine"``, a rigid flap turning about its
  hinge);
* c_d θ̇|θ̇|: optional quadratic drag [N m s2];
* T_PTO from a PTO object (:class:`LinearPTO`, :class:`CallablePTO`, or a device's own model such
  as :class:`flumekit.flap.simulator.HydraulicCylinder`: anything with the
  :class:`PTO` methods ``kernel`` and ``outputs``).

The wave enters through the excitation torque T_exc(t): :class:`RegularWave`,
:class:`IrregularWave` (random phases from a seed) or :class:`MeasuredWave` (a recorded incident
elevation through the FFT filter of :mod:`flumekit.hydro.excitation`), or any DataArray of
T_exc over ``time``.

Integrator: fixed-step exponential Runge-Kutta ETDRK4 (Cox & Matthews 2002): classical RK4 for
(θ, θ̇) and the exact exponential propagation of the radiation modes, so fast radiation poles
set no step limit (module notes of :mod:`flumekit.flap.simulator` for the PTO's own stiff
states). The Runge-Kutta step is written once; each radiation model is its own memory
integrator (:mod:`flumekit.hydro.memory`) that gives the memory torque at the four stages. The
loop over steps is compiled (:mod:`flumekit.hydro.stepping`), sequential by nature;
everything else is vectorised per chunk of steps.

Energy balance. With the stored energy E = ½ (I + A∞) θ̇² + V(θ) (V = ½ C θ², or
C (1 − cos θ) for the sine law) the equation of motion gives

    E(t) − E(0) = W_exc (+ W_extra) − W_rad − W_pto − W_fric − W_drag,

W_x = ∫₀ᵗ P_x dt with P_exc = T_exc θ̇, P_rad = μ θ̇ (radiated, including the energy held by the
memory), P_pto the PTO's useful absorption, P_fric its friction loss and P_drag = c_d |θ̇|³.
The works (trapezoidal rule on every step) and E are returned with their residual
``energy_balance_residual`` (a measure of the time-step error).

Stability guards. Before the first step: every parameter finite (:class:`BadParameterError`
names it). During the run: a non-finite state, |θ| beyond ``angle_limit`` (the physical range,
π/2 by default for a hinged body) or energy created from nothing (E + losses − W_exc above
``energy_growth`` times the input) stop the run with a :class:`DivergenceError` naming the
step, the time and the largest stable step estimated from the linear system.

Memory: the run is integrated in chunks; ``output_step`` keeps one sample in every
``output_step/dt`` (works and energies are integrated on every step before thinning), so a
1e5 s run at 0.02 s with 1 s output holds about 100 000 samples per variable.

References
----------
Cummins, W. E. (1962). The impulse response function and ship motions. Schiffstechnik 9.
Cox, S. M., Matthews, P. C. (2002). Exponential time differencing for stiff systems. J. Comput.
Phys. 176, 430-455.
Falnes, J. (2002). Ocean Waves and Oscillating Systems. Cambridge University Press.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import NamedTuple, Protocol

import numpy as np
import xarray as xr
from scipy.interpolate import CubicSpline

from flumekit import conventions
from flumekit.docstrings import filler
from flumekit.errors import FlumekitError
from flumekit.hydro.coefficients import check_passive
from flumekit.hydro.excitation import excitation_torque, transfer_function
from flumekit.hydro.radiation import StateSpace

#: docstring text that several functions of this module share
_doc = filler(
    order=("order : int, optional\n"
           "    State-space order (default: 1 % on K(t))."),
    ramp=("ramp : float, default 0\n"
          "    Ramp duration [s]."))


class SimulationError(FlumekitError, RuntimeError):
    """The integration failed (non-finite state, a PTO's geometry left, ...)."""


class DivergenceError(SimulationError):
    """The integration diverged (bound exceeded or energy created); says where and what to do."""


class BadParameterError(SimulationError, ValueError):
    """A simulation parameter is not finite or out of its range (named in the message)."""


def check_parameter(name: str, value, minimum: float | None = None,
                    strict: bool = False) -> float:
    """Return ``value`` as a float, checked to be finite and not below ``minimum``.

    Parameters
    ----------
    name : str
        The parameter's name, for the message.
    value : float
        The value to check.
    minimum : float, optional
        Smallest allowed value.
    strict : bool, default False
        Refuse ``value`` equal to ``minimum`` too.

    Returns
    -------
    float
        ``value``.

    Raises
    ------
    BadParameterError
        Naming the parameter, if ``value`` is not finite or below ``minimum`` (``strict``: at
        or below).

    Examples
    --------
    >>> check_parameter("dt", 0.01, 0.0, strict=True)
    0.01
    """
    v = float(value)
    if not math.isfinite(v):
        raise BadParameterError(f"bad parameter: {name} = {value} is not finite")
    if minimum is not None and (v <= minimum if strict else v < minimum):
        raise BadParameterError(f"bad parameter: {name} = {value} must be "
                                f"{'>' if strict else '>='} {minimum}")
    return v


@dataclass(frozen=True)
class BodyDynamics:
    """Rigid-body and hydrostatic properties of a one-dof body.

    Parameters
    ----------
    inertia : float
        Inertia I about the dof's axis [kg m2] (a mass [kg] for a translation).
    added_inertia_infinite : float
        A∞ [kg m2].
    hydrostatic_stiffness : float
        C [N m rad-1], > 0 (the restoring of gravity and buoyancy).
    restoring : str, default "linear"
        "linear" (C θ) or "sine" (C sin θ).
    drag_coefficient : float, default 0
        c_d of the quadratic drag c_d θ̇|θ̇| [N m s2], ≥ 0.
    angle_limit : float, default π/2
        Physical range |θ| ≤ angle_limit [rad]; beyond it the run is declared diverged
        (π/2: a hinged body lying flat).

    Raises
    ------
    BadParameterError
        If a parameter is not finite or out of its range, or I + A∞ ≤ 0.
    """

    inertia: float
    added_inertia_infinite: float
    hydrostatic_stiffness: float
    restoring: str = "linear"
    drag_coefficient: float = 0.0
    angle_limit: float = math.pi / 2

    def __post_init__(self):
        """Check every parameter (:class:`BadParameterError` names a bad one)."""
        check_parameter("inertia", self.inertia)
        check_parameter("added_inertia_infinite", self.added_inertia_infinite)
        check_parameter("hydrostatic_stiffness", self.hydrostatic_stiffness)
        check_parameter("drag_coefficient", self.drag_coefficient, 0.0)
        check_parameter("angle_limit", self.angle_limit, 0.0, strict=True)
        if not self.inertia + self.added_inertia_infinite > 0:
            raise BadParameterError("bad parameter: I + A_inf must be > 0")
        if self.restoring not in ("linear", "sine"):
            raise BadParameterError(f"restoring must be 'linear' or 'sine', got "
                                    f"{self.restoring!r}")


# --- PTOs ------------------------------------------------------------------------------------

class PTOKernel(NamedTuple):
    """Scalar kernels of a PTO for the time-stepping loop (:mod:`flumekit.hydro.stepping`).

    ``accel(t, θ, θ̇, rest, s0, s1, params) -> (θ̈, out0, out1)``: the acceleration given the
    sum ``rest`` of every other torque and the PTO's two internal states (s0, s1); out0 and out1
    are recorded at every step (e.g. a chamber pressure and a friction force); a non-finite θ̈
    stops the run. ``predict(s0, s1, θ, θ̇, θ̈, params) -> (s0, s1, s0', s1')``: internal
    states at the middle and the end of the step, predicted from its start (None for a PTO
    without states). ``advance(s0, s1, θ, θ̇, θ_new, θ̇_new, params) -> (s0, s1)``: states at
    the end of the step. ``params``: the float array the kernels take. ``explain(θ)``: why the
    PTO gave no finite θ̈ at θ (None if it cannot say). Compiled kernels (numba, with the
    signatures of :mod:`flumekit.hydro.stepping`) run in the compiled loop; Python functions run
    the same loop uncompiled.
    """

    accel: Callable
    predict: Callable | None = None
    advance: Callable | None = None
    params: np.ndarray | None = None
    explain: Callable | None = None


class PTO(Protocol):
    """What the simulator needs from a PTO model."""

    def kernel(self, inertia: float, dt: float) -> PTOKernel:
        """Return the scalar kernels for the effective inertia I + A∞ [kg m2] and step dt [s]."""

    def outputs(self, time, theta, theta_dot, theta_ddot, out0, out1, s0, s1) -> dict:
        """Return the PTO's variables over the steps.

        At least ``torque_pto`` (total, resisting) [N m], ``torque_friction`` (its friction
        part) [N m] and ``power`` (useful absorbed power) [W], plus any other variable.
        """

    def describe(self) -> dict:
        """Return the attributes of the result naming the PTO and its parameters."""


@dataclass(frozen=True)
class LinearPTO:
    """Linear damper T_PTO = ν θ̇ with ``damping`` ν [N m s] ≥ 0."""

    damping: float

    def __post_init__(self):
        """Refuse a negative or non-finite damping."""
        check_parameter("pto damping", self.damping, 0.0)

    def kernel(self, inertia, dt):
        """Return the compiled kernel of the damper (:class:`PTO`)."""
        from flumekit.hydro.stepping import linear_accel

        return PTOKernel(linear_accel, params=np.array([self.damping, 1.0 / inertia]))

    def outputs(self, time, theta, theta_dot, theta_ddot, out0, out1, s0, s1):
        """Return the damper's torque [N m], no friction, and its power [W] (:class:`PTO`)."""
        t = self.damping * theta_dot
        return {"torque_pto": t, "torque_friction": np.zeros_like(t), "power": t * theta_dot}

    def describe(self):
        """Return the attributes naming the damper (:class:`PTO`)."""
        return {"pto": "linear damper", "pto_damping": self.damping}


@dataclass(frozen=True)
class CallablePTO:
    """A user's PTO law T_PTO = torque(t, θ, θ̇) [N m] (resisting positive θ̇ when positive).

    ``torque`` is called with floats at every Runge-Kutta stage; it must not depend on θ̈.
    ``name`` describes it in the result's attributes.
    """

    torque: Callable[[float, float, float], float]
    name: str = "user callable"

    def kernel(self, inertia, dt):
        """Return an uncompiled kernel calling ``torque`` (:class:`PTO`)."""
        f, inv = self.torque, 1.0 / inertia
        return PTOKernel(lambda t, th, om, rest, s0, s1, p: ((rest - f(t, th, om)) * inv, 0.0,
                                                             0.0))

    def outputs(self, time, theta, theta_dot, theta_ddot, out0, out1, s0, s1):
        """Return the law's torque [N m], no friction, and its power [W] (:class:`PTO`)."""
        t = np.array([self.torque(a, b, c) for a, b, c in zip(time, theta, theta_dot)])
        return {"torque_pto": t, "torque_friction": np.zeros_like(t), "power": t * theta_dot}

    def describe(self):
        """Return the attributes naming the law (:class:`PTO`)."""
        return {"pto": f"callable: {self.name}"}


# --- waves -----------------------------------------------------------------------------------

def _ramp(t: np.ndarray, ramp: float) -> np.ndarray:
    if ramp <= 0:
        return np.ones_like(t)
    x = np.clip(t / ramp, 0.0, 1.0)
    return 0.5 * (1 - np.cos(np.pi * x))


@_doc
@dataclass(frozen=True)
class RegularWave:
    """A regular wave η(0, t) = Re{a e^{-iωt}} at the reference line, a = H/2.

    The wave rises under a half-cosine ``ramp`` [s] from t = 0. The excitation is exact:
    T_exc = Re{F(ω) a e^{-iωt}} (F interpolated in the container).

    Parameters
    ----------
    height : float
        Wave height H [m], ≥ 0.
    period : float
        Wave period T [s], > 0.
    %(ramp)s
    """

    height: float
    period: float
    ramp: float = 0.0

    def __post_init__(self):
        """Check the height, period and ramp (:class:`BadParameterError`)."""
        check_parameter("wave height", self.height, 0.0)
        check_parameter("wave period", self.period, 0.0, strict=True)
        check_parameter("ramp", self.ramp, 0.0)

    @_doc
    def excitation(self, hydro):
        """Return T_exc(t), η(t), no time span and the attributes of the wave.

        Parameters
        ----------
        %(hydro)s

        Returns
        -------
        torque : callable
            t [s] -> T_exc [N m].
        eta : callable
            t [s] -> η [m] at the reference line.
        span : None
            A synthetic wave covers every time.
        attrs : dict
            Attributes of the result describing the wave.
        """
        w = 2 * np.pi / self.period
        f = complex(transfer_function(hydro, [w])[0]) * self.height / 2

        def torque(t):
            return np.real(f * np.exp(-1j * w * t)) * _ramp(t, self.ramp)

        def eta(t):
            return self.height / 2 * np.cos(w * t) * _ramp(t, self.ramp)

        return torque, eta, None, {"wave": "regular", "wave_height": self.height,
                                   "wave_period": self.period, "ramp": self.ramp}


@_doc
@dataclass(frozen=True)
class IrregularWave:
    """An irregular wave by the random-phase sum η = Re Σ a_j e^{-i(ω_j t − φ_j)}.

    a_j = √(2 S(ω_j) Δω_j), φ_j uniform from ``seed`` (numpy's default generator), under a
    half-cosine ``ramp`` [s].

    Parameters
    ----------
    angular_frequency : numpy.ndarray
        ω_j [rad s-1], increasing, > 0.
    spectral_density : numpy.ndarray
        S(ω_j) [m2 s rad-1] ≥ 0.
    seed : int
        Seed of the phases.
    %(ramp)s

    References
    ----------
    %(tucker1984)s.
    """

    angular_frequency: np.ndarray
    spectral_density: np.ndarray
    seed: int
    ramp: float = 0.0

    def excitation(self, hydro):
        """Return T_exc(t), η(t), no time span and the attributes (as :class:`RegularWave`).

        Raises
        ------
        BadParameterError
            If the frequencies are not increasing and > 0 or S is not finite and ≥ 0.
        """
        w = np.asarray(self.angular_frequency, dtype=float)
        s = np.asarray(self.spectral_density, dtype=float)
        if w.shape != s.shape or w.ndim != 1 or w.size < 2 or not np.all(np.diff(w) > 0) \
                or w[0] <= 0 or np.any(~np.isfinite(s)) or np.any(s < 0):
            raise BadParameterError("bad parameter: the wave spectrum needs increasing "
                                    "angular frequencies > 0 and finite S >= 0 of one shape")
        dw = np.gradient(w)
        phase = np.random.default_rng(self.seed).uniform(0, 2 * np.pi, w.size)
        a = np.sqrt(2 * s * dw) * np.exp(1j * phase)
        fa = transfer_function(hydro, w) * a

        def series(coef):
            def f(t):
                out = np.empty(t.shape)
                for i in range(0, t.size, 2048):  # bounded memory: 2048 x n_freq at a time
                    tt = t[i:i + 2048]
                    out[i:i + 2048] = np.real(np.exp(-1j * np.outer(tt, w)) @ coef)
                return out * _ramp(t, self.ramp)
            return f

        hs = 4 * float(np.sqrt(np.sum(s * dw)))
        return series(fa), series(a), None, {"wave": "irregular (random phases)",
                                             "wave_seed": int(self.seed),
                                             "significant_wave_height": hs, "ramp": self.ramp}


@dataclass(frozen=True)
class MeasuredWave:
    """A recorded incident elevation at the reference line, through the FFT excitation filter.

    The filter is :func:`flumekit.hydro.excitation.excitation_torque`; the result's
    ``valid_end`` says where the filter's end effect starts.

    Parameters
    ----------
    eta : xarray.DataArray
        Incident elevation [m] over ``time`` [s].
    taper : float, default 2
        Length of the filter's end taper [s].
    """

    eta: xr.DataArray
    taper: float = 2.0

    def excitation(self, hydro):
        """Return T_exc(t), η(t) (cubic splines), the record's time span and the attributes."""
        exc = excitation_torque(self.eta, hydro, taper=self.taper)
        t = exc["time"].values
        f = CubicSpline(t, exc.values)
        e = CubicSpline(t, self.eta.values.astype(float))
        attrs = {"wave": "measured elevation", "taper": self.taper,
                 "excitation_variance_outside_band": exc.attrs["variance_below_band"]
                 + exc.attrs["variance_above_band"]}
        for k in ("valid_start", "valid_end"):
            if k in exc.attrs:
                attrs[k] = exc.attrs[k]
        return f, e, (float(t[0]), float(t[-1])), attrs


def excitation_series(excitation: xr.DataArray):
    """Return a callable T_exc(t) (cubic spline) and the time span of an excitation torque.

    Parameters
    ----------
    excitation : xarray.DataArray
        Excitation torque [N m] over ``time`` [s].

    Returns
    -------
    torque : scipy.interpolate.CubicSpline
        t [s] -> T_exc [N m].
    span : tuple of float
        First and last time of the record [s].
    """
    t = excitation["time"].values.astype(float)
    return CubicSpline(t, excitation.values.astype(float)), (float(t[0]), float(t[-1]))


# --- the integrator --------------------------------------------------------------------------

def stable_step(body: BodyDynamics, damping: float = 0.0) -> float:
    """Return the largest step [s] of classical RK4 for the body's linear part without memory.

    The eigenvalues λ of J θ̈ + ν θ̇ + C θ = 0 (J = I + A∞) must satisfy |λ| h ≲ 2.8 (RK4's
    stability region reaches −2.79 on the real axis and ±2.83 on the imaginary one). The
    memory and a nonlinear PTO change the limit; it is a hint for error messages.

    Parameters
    ----------
    body : BodyDynamics
        Inertias I, A∞ and stiffness C.
    damping : float, default 0
        Linear damping ν [N m s].

    Returns
    -------
    float
        The step limit [s] (inf for a body without stiffness or damping).

    Examples
    --------
    >>> round(stable_step(BodyDynamics(2.0, 0.0, 200.0)), 4)
    0.28
    """
    j = body.inertia + body.added_inertia_infinite
    c, nu = abs(body.hydrostatic_stiffness), abs(damping)
    disc = complex(nu * nu - 4 * j * c) ** 0.5
    lam = max(abs((-nu + disc) / (2 * j)), abs((-nu - disc) / (2 * j)))
    return 2.8 / lam if lam > 0 else math.inf


@_doc
def integrate(excitation: Callable | None, body: BodyDynamics, radiation, pto, *, dt: float,
              n_steps: int, t0: float = 0.0, theta0: float = 0.0, theta_dot0: float = 0.0,
              output_every: int = 1, chunk: int = 20000, energy_growth: float = 1.0,
              eta: Callable | None = None, extra_torque: Callable | None = None) -> dict:
    """Integrate the equation of motion from rest (or θ0, θ̇0) over ``n_steps`` steps of ``dt``.

    The scheme and the guards are those of the module notes; arrays are kept every
    ``output_every`` steps.

    Parameters
    ----------
    excitation : callable or None
        t [s] (an array) -> T_exc [N m]; None: free response.
    body : BodyDynamics
        Inertia, A∞, restoring, drag and angle limit.
    radiation : StateSpace, xarray.DataArray or None
        Radiation memory model (:func:`radiation_model`).
    pto : PTO or None
        The power take-off (:class:`PTO` protocol).
    %(dt)s
    n_steps : int
        Number of steps.
    t0 : float, default 0
        Start time [s].
    theta0, theta_dot0 : float, default 0
        Initial state [rad], [rad s-1].
    output_every : int, default 1
        Keep one sample in every ``output_every`` steps.
    chunk : int, default 20000
        Steps integrated per compiled call (bounds the memory).
    energy_growth : float, default 1
        Largest accepted energy created from nothing, as a multiple of the energy supplied.
    eta : callable, optional
        t [s] -> incident elevation [m], recorded as ``eta_incident``.
    extra_torque : callable, optional
        ``extra_torque(j, θ, θ̇)`` [N m], a further torque acting on the body (j the
        half-step index from the start: time t0 + j dt/2), called once per step in order at
        the step's start and held over the step (operator splitting, first order in the term:
        for slowly varying losses beyond the model, e.g. the virtual flume's); its work is
        ``work_extra``. An object with a ``kernel()`` method gives a compiled kernel.

    Returns
    -------
    dict of str to numpy.ndarray
        The arrays of :func:`to_dataset`.

    Raises
    ------
    BadParameterError
        If a parameter or the excitation is not finite or out of range.
    DivergenceError
        If the run diverges (non-finite state, angle limit or energy created).
    """
    from flumekit.hydro.memory import memory_integrator

    dt = check_parameter("dt", dt, 0.0, strict=True)
    theta0 = check_parameter("theta0", theta0)
    theta_dot0 = check_parameter("theta_dot0", theta_dot0)
    if output_every < 1 or int(output_every) != output_every:
        raise BadParameterError(f"bad parameter: output_every = {output_every} must be a "
                                "positive integer")
    j0 = body.inertia + body.added_inertia_infinite
    kern = (pto if pto is not None else LinearPTO(0.0)).kernel(j0, dt)
    try:
        memory = memory_integrator(radiation, dt, n_steps)
    except TypeError as e:
        raise BadParameterError(str(e)) from None
    guard = _Guard(body, dt, getattr(pto, "damping", 0.0), energy_growth)
    state = np.array([theta0, theta_dot0, 0.0, 0.0])
    body_vec = np.array([dt, body.hydrostatic_stiffness, body.drag_coefficient,
                         1.0 if body.restoring == "sine" else 0.0, *memory.weights.astuple()])
    extra = _Extra.of(extra_torque)
    keep: dict[str, list] = {}
    carry = None
    for first in range(0, n_steps + 1, chunk):
        last = min(first + chunk, n_steps + 1)
        final = last == n_steps + 1
        t = t0 + dt * np.arange(first, last)
        # half-step times of the chunk's steps (the final step needs no later stage)
        half = t0 + 0.5 * dt * np.arange(2 * first, 2 * last - 1 if final else 2 * last + 1)
        exc = np.asarray(excitation(half), dtype=float) if excitation is not None \
            else np.zeros(half.size)
        if not np.all(np.isfinite(exc)):
            raise BadParameterError("bad parameter: the excitation torque is not finite")
        try:
            raw = _run_chunk(first, last, exc, state, memory, final, body_vec, kern, extra)
        except _StepFailure as e:
            guard.check_angle(e.theta[: e.step - first], first, t0)  # the earlier symptom
            raise guard.diverged(e.step, t0 + e.step * dt, e.what) from None
        guard.check_angle(raw[0], first, t0)
        arrays = _post(raw, t, exc[::2][: last - first], body, pto)
        carry = _energies(arrays, dt, carry)
        guard.check_energy(arrays, first, t0)
        if extra_torque is None:
            del arrays["torque_extra"], arrays["work_extra"]
        sel = slice((-first) % output_every, None, output_every)
        # copies: a strided view would keep the whole chunk alive (memory of every step)
        arrays = {k: v[sel].copy() for k, v in arrays.items()}
        if eta is not None:
            arrays["eta_incident"] = np.asarray(eta(t[sel]), dtype=float)
        for k, v in arrays.items():
            keep.setdefault(k, []).append(v)
    return {k: np.concatenate(v) for k, v in keep.items()}


class _StepFailure(Exception):
    def __init__(self, step: int, what: str, theta: list):
        self.step, self.what, self.theta = step, what, theta


class _Guard:
    """Divergence checks on each chunk: |θ| bound and energy created from nothing."""

    def __init__(self, body, dt, damping, energy_growth):
        self.body, self.dt, self.growth = body, dt, energy_growth
        self.hint = stable_step(body, damping)
        self.scale = 0.0

    def diverged(self, step: int, t: float, what: str) -> DivergenceError:
        return DivergenceError(
            f"the simulation diverged at step {step} (t = {t:.6g} s): {what}. The time step "
            f"dt = {self.dt:g} s is too long for this body and PTO (fixed-step RK4 without the "
            f"radiation memory is stable below about {self.hint:.3g} s; the memory and a "
            f"nonlinear PTO lower that): reduce dt, e.g. to {self.dt / 4:.3g} s; if a smaller "
            "step diverges too, check the parameters")

    def check_angle(self, theta: list, first: int, t0: float) -> None:
        th = np.abs(np.asarray(theta))
        lim = self.body.angle_limit
        if th.size and not th.max() <= lim:
            i = int(np.argmax(th > lim))
            raise self.diverged(first + i, t0 + (first + i) * self.dt,
                                f"|theta| = {th[i]:.4g} is beyond the physical range "
                                f"{lim:.4g} (angle_limit)")

    def check_energy(self, a: dict, first: int, t0: float) -> None:
        # the residual of the energy balance is an integration error: energy created from
        # nothing; compared with the energy put in so far (initial + supplied by the waves)
        created = a["energy_balance_residual"]
        # the largest energy put in so far, this chunk included: a diverging run creates
        # energy exponentially, orders of magnitude above it by the end of the chunk
        supplied = (float(a["energy_stored"][0]) if first == 0 else 0.0) + float(
            np.max(np.abs(a["work_excitation"]) + np.abs(a["work_extra"])))
        self.scale = supplied = max(self.scale, supplied)
        bad = np.flatnonzero(created > self.growth * supplied + 1e-9)
        if bad.size:
            i = int(bad[0])
            raise self.diverged(first + i, t0 + (first + i) * self.dt,
                                f"{created[i]:.4g} J of energy created from nothing (stored + "
                                f"dissipated - supplied), more than {self.growth:g} times the "
                                f"{supplied:.4g} J supplied")


def _post(raw: np.ndarray, t, exc, body: BodyDynamics, pto) -> dict:
    """Torques and powers of a chunk (vectorised) from its record (:func:`_run_chunk`)."""
    th, om, acc, mu, out0, out1, s0, s1, xt = raw
    sine = body.restoring == "sine"
    a = {"theta": th, "theta_dot": om, "theta_ddot": acc,
         "torque_excitation": exc,
         "torque_radiation": -body.added_inertia_infinite * acc - mu,
         "torque_drag": -body.drag_coefficient * om * np.abs(om),
         "torque_gravity": body.hydrostatic_stiffness * (np.sin(th) if sine else th),
         "torque_inertia": body.inertia * acc}
    a["torque_hydrodynamic"] = exc + a["torque_radiation"] + a["torque_drag"]
    a["torque_extra"] = xt
    p = (pto if pto is not None else LinearPTO(0.0)).outputs(
        t, th, om, acc, out0, out1, s0, s1)
    a.update(p)
    c = body.hydrostatic_stiffness
    a["energy_stored"] = (0.5 * (body.inertia + body.added_inertia_infinite) * om**2
                          + (c * (1 - np.cos(th)) if sine else 0.5 * c * th**2))
    a["_p_exc"] = exc * om
    a["_p_rad"] = mu * om
    a["_p_pto"] = (p["torque_pto"] - p["torque_friction"]) * om
    a["_p_fric"] = p["torque_friction"] * om
    a["_p_drag"] = body.drag_coefficient * np.abs(om) ** 3
    a["_p_extra"] = xt * om
    return a


_WORKS = (("work_excitation", "_p_exc"), ("work_radiation", "_p_rad"), ("work_pto", "_p_pto"),
          ("work_friction", "_p_fric"), ("work_drag", "_p_drag"), ("work_extra", "_p_extra"))


def _energies(a: dict, dt: float, carry):
    """Cumulative works (trapezoidal rule on every step, carried across chunks)."""
    carry = carry or {}
    new = {}
    for name, p in _WORKS:
        pw = a.pop(p)
        prev_w, prev_p = carry.get(name, (0.0, None))
        inc = 0.5 * dt * (pw[1:] + pw[:-1])
        start = prev_w + (0.5 * dt * (prev_p + pw[0]) if prev_p is not None else 0.0)
        w = start + np.concatenate([[0.0], np.cumsum(inc)])
        a[name] = w
        new[name] = (float(w[-1]), float(pw[-1]))
    if "e0" not in carry:
        new["e0"] = float(a["energy_stored"][0])
    else:
        new["e0"] = carry["e0"]
    a["energy_balance_residual"] = (a["energy_stored"] - new["e0"] - a["work_excitation"]
                                    - a["work_extra"] + a["work_radiation"] + a["work_pto"]
                                    + a["work_friction"] + a["work_drag"])
    return new


def _run_chunk(first: int, last: int, exc: np.ndarray, state: np.ndarray, memory, final: bool,
               body: np.ndarray, kern: PTOKernel, extra: _Extra) -> np.ndarray:
    """Integrate steps ``first`` to ``last`` of the run (:func:`flumekit.hydro.stepping.steps`).

    The loop is compiled when every part is, else the same loop runs in Python; ``state`` and
    ``memory`` are advanced in place. Returns the (9, last - first) record of the steps.
    """
    from flumekit.hydro import stepping

    begin, finish = memory.kernels
    predict = kern.predict if kern.predict is not None else stepping.no_predict
    advance = kern.advance if kern.advance is not None else stepping.no_advance
    params = kern.params if kern.params is not None else np.zeros(0)
    parts = (begin, finish, kern.accel, predict, advance, extra.function)
    loop = stepping.steps if stepping.is_compiled(*parts) else stepping.steps.py_func
    out = np.zeros((9, last - first))
    status, step, theta = loop(first, last, exc, state, body, final, begin, finish, memory.c,
                               memory.r, kern.accel, predict, advance, params, extra.function,
                               extra.params, extra.state, extra.record, extra.active, out)
    if status:
        why = kern.explain(theta) if kern.explain is not None else None
        raise _StepFailure(step, why or "the state became non-finite", out[0])
    return out


class _Extra(NamedTuple):
    """An extra torque on the body as the stepping loop takes it (:func:`integrate`)."""

    function: Callable
    params: np.ndarray
    state: np.ndarray
    record: np.ndarray
    active: bool

    @classmethod
    def of(cls, extra: Callable | None) -> _Extra:
        from flumekit.hydro import stepping

        empty, none = np.zeros(0), np.zeros((0, 0))
        if extra is None:
            return cls(stepping.no_extra, empty, empty, none, False)
        if hasattr(extra, "kernel"):  # compiled: (function, params, state, record)
            return cls(*extra.kernel(), True)
        return cls(lambda j, th, om, p, s, r: extra(j, th, om), empty, empty, none, True)


_ATTRS = {
    "work_excitation": ("J", "work of the excitation torque since the start"),
    "work_radiation": ("J", "energy radiated (memory torque times velocity, integrated)"),
    "work_pto": ("J", "energy absorbed by the PTO (friction excluded)"),
    "work_friction": ("J", "energy dissipated by PTO friction"),
    "work_drag": ("J", "energy dissipated by quadratic drag"),
    "work_extra": ("J", "work of the extra torque on the body"),
    "torque_extra": ("N m", "extra torque acting on the body (held over each step)"),
    "energy_stored": ("J", "kinetic (with A_inf) plus potential energy of the body"),
    "energy_balance_residual": ("J", "E - E0 - (W_exc + W_extra - W_rad - W_pto - W_fric "
                                     "- W_drag)"),
    "eta_incident": ("m", "incident wave elevation at the reference line"),
}


@_doc
def to_dataset(out: dict, time: np.ndarray, body: BodyDynamics, radiation, pto,
               dt: float, extra_attrs: dict | None = None) -> xr.Dataset:
    """Return the result as a dataset over ``time`` with the attributes of the run.

    Parameters
    ----------
    out : dict of str to numpy.ndarray
        The arrays of :func:`integrate`.
    time : numpy.ndarray
        Output times [s].
    body : BodyDynamics
        The body simulated.
    radiation : StateSpace, xarray.DataArray or None
        The radiation memory model used.
    pto : PTO or None
        The power take-off used.
    %(dt)s
    extra_attrs : dict, optional
        Further attributes (wave, output step, ...).

    Returns
    -------
    xarray.Dataset
        One variable per array, with units and long names.
    """
    attrs = {"integrator": ("fixed-step RK4 for (theta, theta_dot); exponential (ETD) update "
                            "of the radiation modes; PTO states by the PTO's own kernels"),
             "time_step": float(dt), "inertia": body.inertia,
             "added_inertia_infinite": body.added_inertia_infinite,
             "hydrostatic_stiffness": body.hydrostatic_stiffness, "restoring": body.restoring,
             "drag_coefficient": body.drag_coefficient, "angle_limit": body.angle_limit,
             "torque_sign_convention": ("torque_gravity, torque_pto, torque_pressure, "
                                        "torque_friction resist; torque_excitation, "
                                        "torque_radiation, torque_drag, torque_hydrodynamic act")}
    if isinstance(radiation, StateSpace):
        attrs.update(radiation="state space", radiation_order=radiation.order,
                     radiation_fit_error_time=radiation.fit_error_time,
                     radiation_fit_error_frequency=radiation.fit_error_frequency)
    elif isinstance(radiation, xr.DataArray):
        attrs.update(radiation="convolution", radiation_irf_duration=float(radiation["lag"][-1]))
    else:
        attrs.update(radiation="none")
    attrs.update(pto.describe() if pto is not None else {"pto": "none"})
    attrs.update(extra_attrs or {})
    ds = xr.Dataset({k: ("time", v) for k, v in out.items()}, coords={"time": time}, attrs=attrs)
    for k, (u, ln) in _ATTRS.items():
        if k in ds:
            ds[k].attrs.update(units=u, long_name=ln)
    return conventions.annotate(ds)


@_doc
def simulate(hydro: xr.Dataset, inertia: float, pto, wave, *, dt: float,
             duration: float | None = None, stiffness: float | None = None,
             radiation: str | StateSpace | xr.DataArray = "state_space",
             irf_duration: float = 60.0, order: int | None = None,
             match_frequency: float | None = None, restoring: str = "linear",
             drag_coefficient: float = 0.0, angle_limit: float = math.pi / 2,
             output_step: float | None = None, t_start: float | None = None,
             energy_growth: float = 1.0, max_spread: float | None = None,
             extra_torque: Callable | None = None) -> xr.Dataset:
    """Simulate a one-dof body described by a coefficient container in a wave.

    Parameters
    ----------
    hydro : xarray.Dataset
        Coefficient container (:mod:`flumekit.hydro.coefficients`); passivity is always
        checked (:func:`~flumekit.hydro.coefficients.check_passive`). Its
        ``added_inertia_infinite`` is used if present (and ``match_frequency`` is None), else
        the Ogilvie (1964) estimate (median over frequencies, or at ``match_frequency``).
    inertia : float
        Body inertia about the dof's axis I [kg m2].
    pto : PTO or None
        :class:`LinearPTO`, :class:`CallablePTO`, a device's PTO (:class:`PTO` protocol) or
        None.
    wave : RegularWave, IrregularWave, MeasuredWave or xarray.DataArray
        The wave, or an excitation torque [N m] over ``time``.
    %(dt)s
    duration : float, optional
        Simulated time [s]; default the record of a measured wave or torque.
    stiffness : float, optional
        C [N m rad-1]; default the container's ``hydrostatic_stiffness``.
    radiation : str, StateSpace or xarray.DataArray, default "state_space"
        "state_space", "convolution", "none", or a precomputed model (a
        :class:`~flumekit.hydro.radiation.StateSpace` or an impulse response over ``lag``) to
        share across runs.
    irf_duration : float, default 60
        Length of the impulse response K(t) [s].
    %(order)s
    match_frequency : float, optional
        Frequency of the A∞ estimate [rad s-1] (see ``hydro``).
    restoring, drag_coefficient, angle_limit
        As in :class:`BodyDynamics` ([-], [N m s2], [rad]).
    %(output_step)s
    t_start : float, optional
        Start time [s] (default 0, or the record's start).
    energy_growth : float, default 1
        Largest accepted energy created from nothing, as a multiple of the energy supplied,
        before the run is declared diverged.
    max_spread : float, optional
        Largest accepted spread of the Ogilvie estimates of A∞ (None: report only).
    extra_torque : callable, optional
        Further torque ``(j, θ, θ̇) -> T`` [N m] on the body (:func:`integrate`); its
        ``description`` attribute, if any, goes into the result's attributes.

    Returns
    -------
    xarray.Dataset
        Over ``time``: θ [rad], θ̇ [rad s-1], θ̈ [rad s-2], the torques [N m], the PTO's
        outputs, the works and stored energy of the energy balance [J] (module notes),
        ``eta_incident`` [m] for a wave input.

    Raises
    ------
    BadParameterError
        If a parameter is not finite or out of range, the wave record does not cover the run
        or ``output_step`` is not a multiple of ``dt``.
    DivergenceError
        If the run diverges (module notes).

    References
    ----------
    Cummins, W. E. (1962). The impulse response function and ship motions. Schiffstechnik 9.
    Ogilvie, T. F. (1964). Recent progress toward the understanding and prediction of ship
    motions. Proc. 5th Symp. Naval Hydrodynamics, 3-128.
    Cox, S. M., Matthews, P. C. (2002). Exponential time differencing for stiff systems.
    J. Comput. Phys. 176, 430-455.

    Examples
    --------
    A body without radiation damping behind a linear damper reaches the steady amplitude
    ``|F a| / |C − (I + A) ω² − i ω ν|`` of the linear equation:

    >>> import numpy as np
    >>> from flumekit.hydro import hydro_dataset
    >>> w = np.linspace(0.5, 10.0, 50)
    >>> hy = hydro_dataset(w, np.full(50, 5.0), np.zeros(50), np.full(50, 100.0 + 0j), 200.0)
    >>> run = simulate(hy, 15.0, LinearPTO(20.0), RegularWave(height=0.1, period=2.0),
    ...                dt=0.01, duration=120.0, radiation="none")
    >>> exact = 100.0 * 0.05 / abs(200.0 - 20.0 * np.pi**2 - 1j * np.pi * 20.0)
    >>> round(float(abs(run.theta.sel(time=slice(100, None))).max()), 4), round(exact, 4)
    (0.0795, 0.0795)
    """
    from flumekit.hydro.coefficients import with_infinite_frequency_inertia

    check_passive(hydro)
    dt = check_parameter("dt", dt, 0.0, strict=True)
    c = float(hydro["hydrostatic_stiffness"]) if stiffness is None else check_parameter("stiffness",
                                                                               stiffness)
    if "added_inertia_infinite" in hydro and match_frequency is None:
        a_inf = float(hydro["added_inertia_infinite"])
        spread = float(hydro.attrs.get("added_inertia_infinite_spread", np.nan))
    else:
        h2 = with_infinite_frequency_inertia(hydro, max_spread=max_spread,
                                             at_frequency=match_frequency, duration=irf_duration)
        a_inf = float(h2["added_inertia_infinite"])
        spread = float(h2.attrs["added_inertia_infinite_spread"])
    body = BodyDynamics(check_parameter("inertia", inertia, 0.0, strict=True), a_inf, c, restoring,
                        drag_coefficient, angle_limit)
    rad = radiation_model(hydro, radiation, dt, irf_duration, order)
    if isinstance(wave, xr.DataArray):
        f, span = excitation_series(wave)
        eta, attrs = None, {"wave": "excitation torque series"}
    else:
        f, eta, span, attrs = wave.excitation(hydro)
    t0 = (span[0] if span else 0.0) if t_start is None else float(t_start)
    if duration is None:
        if span is None:
            raise BadParameterError("bad parameter: a synthetic wave needs a duration")
        duration = span[1] - t0
    duration = check_parameter("duration", duration, 0.0, strict=True)
    n_steps = math.floor(duration / dt + 1e-9)
    if n_steps < 1:
        raise BadParameterError("bad parameter: duration shorter than one step")
    if span is not None and (t0 < span[0] - 1e-9 or t0 + n_steps * dt > span[1] + 1e-9):
        raise BadParameterError(f"bad parameter: the wave record covers [{span[0]}, {span[1]}]"
                                f" s, the run [{t0}, {t0 + n_steps * dt}] s")
    every = 1 if output_step is None else round(output_step / dt)
    if every < 1 or abs(every * dt - (output_step or dt)) > 1e-9 * max(1.0, every * dt):
        raise BadParameterError(f"bad parameter: output_step = {output_step} s must be a "
                                f"multiple of dt = {dt} s")
    out = integrate(f, body, rad, pto, dt=dt, n_steps=n_steps, t0=t0, output_every=every,
                    energy_growth=energy_growth, eta=eta, extra_torque=extra_torque)
    if extra_torque is not None:
        attrs["extra_torque"] = getattr(extra_torque, "description", repr(extra_torque))
    time = t0 + dt * np.arange(0, n_steps + 1, every)
    return to_dataset(out, time, body, rad, pto, dt, {**attrs, "output_step": every * dt,
                                                      "added_inertia_infinite_spread": spread})


@_doc
def radiation_model(hydro: xr.Dataset, radiation, dt: float, irf_duration: float = 60.0,
                    order: int | None = None):
    """Return the radiation memory model: a given one, None, or one fitted from the container.

    Parameters
    ----------
    hydro : xarray.Dataset
        Coefficient container.
    radiation : str, StateSpace, xarray.DataArray or None
        "state_space", "convolution", "none", or a model (returned as is).
    dt : float
        Time step of the run [s]; K(t) is sampled at min(dt/2, 0.01 s).
    irf_duration : float, default 60
        Length of K(t) [s].
    %(order)s

    Returns
    -------
    StateSpace, xarray.DataArray or None
        The state-space model, the impulse response over ``lag``, or None.

    Raises
    ------
    BadParameterError
        If ``radiation`` is an unknown name.
    """
    from flumekit.hydro.radiation import fit_state_space, impulse_response

    if isinstance(radiation, (StateSpace, xr.DataArray)) or radiation is None:
        return radiation
    if radiation == "none":
        return None
    if radiation not in ("convolution", "state_space"):
        raise BadParameterError(f"radiation must be 'state_space', 'convolution' or 'none', "
                                f"got {radiation!r}")
    irf = impulse_response(hydro, irf_duration, min(dt / 2, 0.01))
    return irf if radiation == "convolution" else fit_state_space(irf, order)


__all__ = ["BadParameterError", "BodyDynamics", "CallablePTO", "DivergenceError",
           "IrregularWave", "LinearPTO", "MeasuredWave", "PTO", "PTOKernel",
           "RegularWave", "SimulationError", "integrate", "radiation_model", "simulate",
           "stable_step", "to_dataset", "check_parameter"]
