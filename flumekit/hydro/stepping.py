"""The simulator's time-stepping loop, compiled (numba), and the kernel signatures it calls.

:func:`flumekit.hydro.simulation.integrate` runs the fixed-step Runge-Kutta loop of the Cummins
equation here. The loop is sequential by nature (each step needs the last), so it is compiled
rather than vectorised; it calls its parts through numba's first-class function types with the
fixed signatures below, so that one compiled loop serves every radiation model, PTO and extra
torque, and is cached on disk like the package's other kernels (numba's cache in the package's
``__pycache__``; a process pays the import of numba and the loading of the cache once).

Kernels (every argument a float64 scalar or array unless said):

* memory (:mod:`flumekit.hydro.memory`): ``begin(n: int64, u1, c: complex128[:, :],
  r: float64[:]) -> (M, P_h, P_f)`` and ``finish(u1, u2, u3, u4, c, r) -> 0.0``, the model's
  state in ``c`` and ``r`` (advanced in place);
* PTO (:class:`flumekit.hydro.simulation.PTOKernel`): ``accel(t, θ, θ̇, rest, s0, s1,
  params) -> (θ̈, out0, out1)``, ``predict(s0, s1, θ, θ̇, θ̈, params) -> (s0, s1, s0', s1')``
  and ``advance(s0, s1, θ, θ̇, θ_new, θ̇_new, params) -> (s0, s1)``; a non-finite θ̈ stops
  the run (a PTO signals a state outside its range that way);
* extra torque: ``torque(j: int64, θ, θ̇, params, state, record: float64[:, :]) -> T`` with j
  the half-step index, its mutable state in ``state`` and what it records per step in row
  ``j // 2`` of ``record``.

A part given as a Python function instead runs the same loop uncompiled (``py_func``): every
Runge-Kutta stage is written once.
"""

from __future__ import annotations

import math

from numba import njit, types

from flumekit.docstrings import filler

#: docstring text that several functions of this module share
_doc = filler(
    params=("params : ndarray\n"
            "    The PTO's parameters (unused)."))

__all__ = ["ACCEL", "ADVANCE", "BEGIN", "EXTRA", "FINISH", "PREDICT", "is_compiled", "linear_accel",
           "no_extra", "no_predict", "no_advance", "steps"]

f8, i8 = types.float64, types.int64
_vec, _mat, _cmat = types.float64[:], types.float64[:, :], types.complex128[:, :]

#: signature of a memory model's ``begin``
BEGIN = types.UniTuple(f8, 3)(i8, f8, _cmat, _vec)
#: signature of a memory model's ``finish``
FINISH = f8(f8, f8, f8, f8, _cmat, _vec)
#: signature of a PTO's ``accel``
ACCEL = types.UniTuple(f8, 3)(f8, f8, f8, f8, f8, f8, _vec)
#: signature of a PTO's ``predict``
PREDICT = types.UniTuple(f8, 4)(f8, f8, f8, f8, f8, _vec)
#: signature of a PTO's ``advance``
ADVANCE = types.UniTuple(f8, 2)(f8, f8, f8, f8, f8, f8, _vec)
#: signature of an extra torque
EXTRA = f8(i8, f8, f8, _vec, _vec, _mat)


@_doc
@njit(PREDICT, cache=True)
def no_predict(s0, s1, th, om, acc, params):
    """Keep the states of a PTO without internal states (signature ``PREDICT``).

    Parameters
    ----------
    s0, s1 : float
        The PTO's states (unused).
    th, om, acc : float
        θ [rad], θ̇ [rad s-1] and θ̈ [rad s-2] of the first stage (unused).
    %(params)s

    Returns
    -------
    tuple of float
        Four zeros: the states at mid-step and at the step's end.
    """
    return 0.0, 0.0, 0.0, 0.0


@_doc
@njit(ADVANCE, cache=True)
def no_advance(s0, s1, th, om, th_new, om_new, params):
    """Keep the states of a PTO without internal states (signature ``ADVANCE``).

    Parameters
    ----------
    s0, s1 : float
        The PTO's states.
    th, om, th_new, om_new : float
        θ [rad] and θ̇ [rad s-1] at the step's start and end (unused).
    %(params)s

    Returns
    -------
    s0, s1 : float
        The states, unchanged.
    """
    return s0, s1


@njit(EXTRA, cache=True)
def no_extra(j, th, om, params, state, record):
    """Return no extra torque (signature ``EXTRA``).

    Parameters
    ----------
    j : int
        Half-step index (unused).
    th, om : float
        θ [rad] and θ̇ [rad s-1] (unused).
    params, state : ndarray
        Parameters and mutable state (unused).
    record : ndarray
        Per-step record (unused).

    Returns
    -------
    float
        0 [N m].
    """
    return 0.0


def is_compiled(*functions) -> bool:
    """Tell whether every function is a numba-compiled kernel the compiled loop can call.

    Parameters
    ----------
    *functions : callable
        The parts of a run (memory model, PTO and extra-torque kernels).

    Returns
    -------
    bool
        True when each is a numba dispatcher; else the loop runs uncompiled (``py_func``).
    """
    from numba.core.registry import CPUDispatcher

    return all(isinstance(f, CPUDispatcher) for f in functions)


_SIG = types.Tuple((i8, i8, f8))(
    i8, i8, _vec, _vec, _vec, types.boolean,
    types.FunctionType(BEGIN), types.FunctionType(FINISH), _cmat, _vec,
    types.FunctionType(ACCEL), types.FunctionType(PREDICT), types.FunctionType(ADVANCE), _vec,
    types.FunctionType(EXTRA), _vec, _vec, _mat, types.boolean, _mat)


@njit(_SIG, cache=True)
def steps(first, last, exc, state, body, final, begin, finish, mem_c, mem_r, accel, predict,
          advance, pto_params, extra, extra_params, extra_state, extra_record, has_extra, out):
    """Integrate steps ``first`` to ``last`` of a run.

    Classical RK4 for (θ, θ̇) with the memory torque at the four stages (module notes of
    :mod:`flumekit.hydro.memory`).

    Parameters
    ----------
    first, last : int
        Step indices of the chunk (``last`` excluded).
    exc : ndarray
        Excitation torque [N m] at the chunk's half steps, ``2 (last - first) + 1`` values
        (one fewer in the final chunk).
    state : ndarray
        (θ [rad], θ̇ [rad s-1], s0, s1) at step ``first``; advanced in place.
    body : ndarray
        (h [s], C [N m rad-1], c_d [N m s2], 1 for C sin θ else 0, the seven stage weights
        w21, w22, w32, w33, w41, w43, w44 [N m s rad-1] of the memory).
    final : bool
        The chunk ends the run (its last step has no later stages).
    begin, finish : function
        Kernels of the memory model (signatures ``BEGIN``, ``FINISH``).
    mem_c, mem_r : ndarray
        State of the memory model (complex and real), advanced in place.
    accel, predict, advance : function
        Kernels of the PTO (signatures ``ACCEL``, ``PREDICT``, ``ADVANCE``).
    pto_params : ndarray
        Parameters of the PTO kernels.
    extra : function
        Extra torque kernel (signature ``EXTRA``).
    extra_params, extra_state, extra_record : ndarray
        Its parameters, mutable state and per-step record.
    has_extra : bool
        Whether to call ``extra``.
    out : ndarray
        (9, last - first) output: θ, θ̇, θ̈, μ, out0, out1, s0, s1, extra torque per step.

    Returns
    -------
    status : int
        0, or 1 if a state or stage acceleration became non-finite.
    step : int
        The step at which it did (``last`` if none).
    theta : float
        The angle [rad] of the failed evaluation.
    """
    h, cc, cd, sine = body[0], body[1], body[2], body[3] != 0.0
    w21, w22, w32, w33, w41, w43, w44 = (body[4], body[5], body[6], body[7], body[8],
                                         body[9], body[10])
    th, om, z, hl = state[0], state[1], state[2], state[3]
    n1 = last - first
    hh, h6 = 0.5 * h, h / 6.0
    xt = 0.0

    def stage(t, th, om, torque, s0, s1):
        # θ̈ at a later stage: ``torque`` is the excitation (and extra torque) minus the
        # memory torque there; the restoring and drag torques of θ, θ̇ are subtracted here
        return accel(t, th, om, torque - (cc * math.sin(th) if sine else cc * th)
                     - cd * om * abs(om), s0, s1, pto_params)[0]

    for n in range(first, last):
        k = n - first
        t = n * h
        # memory torque now, and the parts of the later stages' memory known at the start
        mu1, p_half, p_full = begin(n, om, mem_c, mem_r)
        if has_extra:  # frozen over the step (operator splitting)
            xt = extra(2 * n, th, om, extra_params, extra_state, extra_record)
        rest = exc[2 * k] - mu1 - (cc * math.sin(th) if sine else cc * th) - cd * om * abs(om)
        a1, p1, f1 = accel(t, th, om, rest + xt, z, hl, pto_params)
        out[0, k], out[1, k], out[2, k], out[3, k] = th, om, a1, mu1
        out[4, k], out[5, k], out[6, k], out[7, k], out[8, k] = p1, f1, z, hl, xt
        if not (math.isfinite(th) and math.isfinite(om) and math.isfinite(a1)):
            return 1, n, th
        if final and k == n1 - 1:
            break
        te_h, te_f = exc[2 * k + 1] + xt, exc[2 * k + 2] + xt
        zm, hm, ze, he = predict(z, hl, th, om, a1, pto_params)
        # stages 2 and 3 at t + h/2, 4 at t + h
        om2 = om + hh * a1
        th2 = th + hh * om
        a2 = stage(t + hh, th2, om2, te_h - (p_half + w21 * om + w22 * om2), zm, hm)
        om3 = om + hh * a2
        th3 = th + hh * om2
        a3 = stage(t + hh, th3, om3, te_h - (p_half + w32 * om2 + w33 * om3), zm, hm)
        om4 = om + h * a3
        th4 = th + h * om3
        a4 = stage(t + h, th4, om4, te_f - (p_full + w41 * om + w43 * om3 + w44 * om4), ze, he)
        if not (math.isfinite(a2) and math.isfinite(a3) and math.isfinite(a4)):
            # the first stage that failed names its angle (a NaN carries to the later ones)
            return 1, n, th2 if not math.isfinite(a2) else (th3 if not math.isfinite(a3)
                                                            else th4)
        finish(om, om2, om3, om4, mem_c, mem_r)
        th_new = th + h6 * (om + 2.0 * (om2 + om3) + om4)
        om_new = om + h6 * (a1 + 2.0 * (a2 + a3) + a4)
        z, hl = advance(z, hl, th, om, th_new, om_new, pto_params)
        th, om = th_new, om_new
    state[0], state[1], state[2], state[3] = th, om, z, hl
    return 0, last, 0.0


@njit(ACCEL, cache=True)
def linear_accel(t, th, om, rest, s0, s1, params):
    """Return θ̈ with a linear PTO damper (signature ``ACCEL``).

    Parameters
    ----------
    t : float
        Time [s] (unused).
    th : float
        θ [rad] (unused: the restoring torque is in ``rest``).
    om : float
        θ̇ [rad s-1].
    rest : float
        The torques other than the PTO's [N m].
    s0, s1 : float
        The PTO's states (unused).
    params : ndarray
        (ν [N m s], 1/(I + A∞) [kg-1 m-2]).

    Returns
    -------
    acc : float
        θ̈ = (rest − ν θ̇)/(I + A∞) [rad s-2].
    out0, out1 : float
        Zeros (no PTO outputs).
    """
    return (rest - params[0] * om) * params[1], 0.0, 0.0
