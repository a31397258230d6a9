"""Modified LuGre friction of the PTO cylinder (Brito et al. 2020, Appendix B, Eqs. A3-A9).

The model (Yanada & Sekikawa 2008; Tran, Hafizah & Yanada 2012) adds a dimensionless lubricant
film state h to the LuGre bristle state z:

    F   = σ0 z + σ1 ż + σ2 v                                  Eq. (A3)
    ż   = v − σ0 |v| z / g(v, h)                              Eq. (A4), corrected
    g   = F_c + [(1 − h) F_s − F_c] exp(−(|v|/v_s)^n)         Eq. (A5), corrected  [N]
    ḣ   = (h_ss − h) / τ_h                                    Eq. (A6)
    τ_h = τ_hp (v ≠ 0, h ≤ h_ss), τ_hm (v ≠ 0, h > h_ss), τ_h0 (v = 0)   Eq. (A7)
    h_ss = K_f min(|v|, v_b)^(2/3)                            Eq. (A8)
    K_f = (1 − F_c/F_s) / v_b^(2/3)                           Eq. (A9), corrected

with v the rod extension rate (ẋ in the paper) and F the friction force acting against it
(F > 0 resists extension).

Corrections to the equations as printed in Brito et al. (2020):

* (A4) prints ẋ z / g_s; with ẋ instead of |ẋ| the steady bristle deflection would be +g_s/σ0
  for both directions of motion and the friction would not change sign with the velocity. The
  standard LuGre form (Canudas de Wit et al. 1995) and Yanada & Sekikawa (2008) use |ẋ|.
* (A5) prints g_s = (1/σ0)[(1 − h)F_c + (F_s − F_c)] exp(−(|ẋ|/ẋ_s)^n), which makes the whole
  Stribeck curve decay to zero at high speed (no Coulomb friction, and an infinite bristle
  relaxation rate). We use the form above, with the exponential on the static excess only. It
  is the form that makes Eq. (A9) meaningful: at the largest film thickness
  h_max = 1 − F_c/F_s the static excess (1 − h)F_s − F_c vanishes, so a fully developed film
  removes the Stribeck peak and g = F_c. Here g is a force; the paper's g_s = g/σ0 is a length.
* (A9) prints K_f = (1 − F_c/F_s)|ẋ_b|^(2/3); h must be dimensionless and reach h_max at ẋ_b,
  which needs the exponent −2/3.

Integration
-----------
The bristle equation is stiff: it relaxes with the rate r = σ0|v|/g, about 4000 s⁻¹ at 0.16 m/s
for the default campaign, 40 times the pipeline's sampling rate. For a frozen velocity both
state equations are linear in their state, so each step uses their exact exponential solution:

    z(t + Δt) = z_ss + (z − z_ss) exp(−r Δt),   z_ss = v g/(σ0|v|)
    h(t + Δt) = h_ss + (h − h_ss) exp(−Δt/τ_h)

(for frozen v, h moves monotonically towards h_ss without crossing it, so τ_h is constant over
the step). The update is unconditionally stable: |z| never exceeds max(|z₀|, F_s/σ0) and h
stays between its start and h_ss, whatever the step. For sampled velocities,
:func:`friction_series` freezes the velocity at the mid-step value and uses the film state at
the middle of the step in g, which makes the scheme second order in Δt where v is smooth, and
splits a step at a velocity reversal (:func:`friction_advance`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from flumekit.campaign import Friction
from flumekit.docstrings import filler

#: docstring text that several functions of this module share
_doc = filler(
    step=("dt : float\n"
          "    Step [s], > 0."),
    model=("model : LuGre\n"
           "    Friction parameters."),
    # a function of the velocity alone
    parameters_velocity=("Parameters\n"
                         "----------\n"
                         "%(velocity)s\n"
                         "%(model)s"),
    raises_step=("Raises\n"
                 "------\n"
                 "ValueError\n"
                 "    A step that is not > 0."),
    velocity=("velocity : float or array_like\n"
              "    Rod extension rate v [m s-1]."),
    references_lugre=("References\n"
                      "----------\n"
                      "%(brito2020)s, Appendix B, Eqs. (A3)-(A9).\n"
                      "Canudas de Wit, C., Olsson, H., Åström, K. J. & Lischinsky, P. (1995). A "
                      "new model for\ncontrol of systems with friction. IEEE Trans. Autom. "
                      "Control 40(3), 419-425.\n"
                      "Yanada, H. & Sekikawa, Y. (2008). Modeling of dynamic behaviors of "
                      "friction. Mechatronics\n18(7), 330-339."),
    # the parameters of the default campaign's cylinder (flumekit/data/default_campaign.toml)
    model_example=(">>> from flumekit.flap.friction import LuGre\n"
                   ">>> model = LuGre(sigma0=1.0e6, sigma1=2.0e3, sigma2=150.0, "
                   "coulomb_force=40.0,\n"
                   "...               static_force=70.0, stribeck_velocity=0.01, "
                   "stribeck_exponent=1.0,\n"
                   "...               minimum_friction_velocity=0.05, tau_hp=0.02, "
                   "tau_hm=0.2, tau_h0=20.0)"))


@_doc
class FrictionState(NamedTuple):
    """State of the modified LuGre model.

    The default is the state at rest: straight bristles, no film.

    Attributes
    ----------
    z : float or numpy.ndarray
        Mean bristle deflection z [m].
    h : float or numpy.ndarray
        Dimensionless lubricant film thickness h [-].

    Examples
    --------
    The state carries a record's friction across its chunks: a series resumed from the state
    at the last sample of the first half is the series of the whole record:

    >>> import numpy as np
    %(model_example)s
    >>> from flumekit.flap.friction import FrictionState, friction_series
    >>> FrictionState()
    FrictionState(z=0.0, h=0.0)
    >>> v = 0.16 * np.sin(np.linspace(0.0, 4 * np.pi, 401))  # two cycles at 100 Hz [m s-1]
    >>> whole = friction_series(v, 0.01, model)[0]
    >>> first, z, h = friction_series(v[:201], 0.01, model)
    >>> second = friction_series(v[200:], 0.01, model, state=FrictionState(z[-1], h[-1]))[0]
    >>> bool(np.array_equal(np.concatenate([first, second[1:]]), whole))
    True
    """

    z: float = 0.0  # mean bristle deflection [m]
    h: float = 0.0  # dimensionless lubricant film thickness [-]


@dataclass(frozen=True)
class LuGre:
    """Modified LuGre model with the parameters of :class:`flumekit.campaign.Friction`.

    Parameters
    ----------
    sigma0 : float
        Bristle stiffness σ0 [N m-1].
    sigma1 : float
        Bristle micro-damping σ1 [N s m-1].
    sigma2 : float
        Viscous friction coefficient σ2 [N s m-1].
    coulomb_force : float
        Coulomb friction force F_c [N], > 0.
    static_force : float
        Maximum static friction force F_s [N], ≥ F_c.
    stribeck_velocity : float
        Stribeck velocity v_s [m s-1], > 0.
    stribeck_exponent : float
        Exponent n of the Stribeck curve [-], > 0.
    minimum_friction_velocity : float
        Velocity v_b of the minimum steady friction [m s-1], > 0.
    tau_hp, tau_hm, tau_h0 : float
        Film time constants for acceleration, deceleration and dwell [s].

    Examples
    --------
    The model of the default campaign's cylinder, from its ``[pto.friction]`` table, and the
    largest film it builds, h_max = 1 − F_c/F_s = 1 − 40/70:

    >>> import pathlib, tempfile
    >>> from flumekit.campaign import load_campaign
    >>> from flumekit.flap.friction import LuGre
    >>> from flumekit.synth.campaign import campaign_toml
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     _ = (pathlib.Path(folder) / "campaign.toml").write_text(campaign_toml("demo"))
    ...     campaign = load_campaign(folder, runs=False)
    >>> model = LuGre.from_campaign(campaign.pto.friction)
    >>> model.coulomb_force, model.static_force, round(model.film_max, 4)
    (40.0, 70.0, 0.4286)
    """

    sigma0: float
    sigma1: float
    sigma2: float
    coulomb_force: float
    static_force: float
    stribeck_velocity: float
    stribeck_exponent: float
    minimum_friction_velocity: float
    tau_hp: float
    tau_hm: float
    tau_h0: float

    def __post_init__(self):
        """Check that every parameter is physical (positive rates, forces and times)."""
        positive = ("sigma0", "coulomb_force", "stribeck_velocity", "stribeck_exponent",
                    "minimum_friction_velocity", "tau_hp", "tau_hm", "tau_h0")
        for name in positive:
            v = getattr(self, name)
            if not (math.isfinite(v) and v > 0):
                raise ValueError(f"LuGre friction: {name} must be finite and > 0, got {v}")
        for name in ("sigma1", "sigma2"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v >= 0):
                raise ValueError(f"LuGre friction: {name} must be finite and >= 0, got {v}")
        if not self.static_force >= self.coulomb_force:
            raise ValueError(f"LuGre friction: static force {self.static_force} N is below the "
                             f"Coulomb force {self.coulomb_force} N")

    @classmethod
    def from_campaign(cls, friction: Friction) -> LuGre:
        """Model from the campaign's ``[pto.friction]`` table."""
        return cls(**{k: getattr(friction, k) for k in Friction.__dataclass_fields__})

    @property
    def film_max(self) -> float:
        """Largest film thickness h_max = 1 − F_c/F_s [-] (Eqs. A8-A9)."""
        return 1.0 - self.coulomb_force / self.static_force

    @property
    def film_gain(self) -> float:
        """K_f = (1 − F_c/F_s) / v_b^(2/3) [(m s-1)^(-2/3)] (Eq. A9, corrected exponent)."""
        return self.film_max / self.minimum_friction_velocity ** (2.0 / 3.0)


@_doc
def film_steady_state(velocity, model: LuGre) -> np.ndarray:
    """Steady film thickness h_ss(v) [-] (Eqs. A8-A9).

    h_ss = K_f min(abs(v), v_b)^(2/3): the film grows with the speed up to v_b, where it
    reaches its largest thickness h_max = 1 − F_c/F_s (:attr:`LuGre.film_max`).

    %(parameters_velocity)s

    Returns
    -------
    numpy.ndarray
        h_ss [-], in [0, h_max].

    %(references_lugre)s

    Examples
    --------
    At rest there is no film; from v_b = 0.05 m/s on it is h_max = 1 − 40/70 = 3/7:

    %(model_example)s
    >>> from flumekit.flap.friction import film_steady_state
    >>> film_steady_state([0.0, -0.05, 0.5], model).round(4).tolist()
    [0.0, 0.4286, 0.4286]
    """
    a = np.minimum(np.abs(np.asarray(velocity, dtype=float)), model.minimum_friction_velocity)
    return model.film_gain * a ** (2.0 / 3.0)


@_doc
def stribeck(velocity, film, model: LuGre) -> np.ndarray:
    """Stribeck function g(v, h) [N] (Eq. A5 in the corrected form, see the module notes).

    g = F_c + [(1 − h) F_s − F_c] exp(−(abs(v)/v_s)^n): the friction the bristles carry
    when sliding steadily at v on a film h, from the breakaway force F_s (at rest, no film)
    down to the Coulomb force F_c.

    Parameters
    ----------
    %(velocity)s
    film : float or array_like
        Film thickness h [-].
    %(model)s

    Returns
    -------
    numpy.ndarray
        g [N], broadcast over ``velocity`` and ``film``.

    %(references_lugre)s

    Examples
    --------
    Breakaway at rest without a film, Coulomb friction on a full film, and one Stribeck
    velocity into the decay, F_c + (F_s − F_c)/e:

    %(model_example)s
    >>> from flumekit.flap.friction import stribeck
    >>> stribeck([0.0, 1.0, 0.01], [0.0, model.film_max, 0.0], model).round(3).tolist()
    [70.0, 40.0, 51.036]
    """
    v = np.abs(np.asarray(velocity, dtype=float))
    h = np.asarray(film, dtype=float)
    fc, fs = model.coulomb_force, model.static_force
    return fc + ((1.0 - h) * fs - fc) * np.exp(-(v / model.stribeck_velocity)
                                               ** model.stribeck_exponent)


@_doc
def steady_friction(velocity, model: LuGre) -> np.ndarray:
    """Steady-state friction force F_ss(v) = sign(v) g(v, h_ss(v)) + σ2 v [N].

    The limit of the dynamic model at constant velocity (ż = 0, h = h_ss): the Stribeck curve
    of the cylinder, odd in v.

    %(parameters_velocity)s

    Returns
    -------
    numpy.ndarray
        F_ss [N], positive when it resists extension (v > 0); 0 at v = 0.

    %(references_lugre)s

    Examples
    --------
    Above v_b = 0.05 m/s the full film removes the Stribeck peak, F_ss = F_c + σ2 v
    (40 + 150 × 0.16 = 64 N); at low speed the friction first falls with v, then rises:

    %(model_example)s
    >>> from flumekit.flap.friction import steady_friction
    >>> steady_friction([-0.16, 0.16], model).round(6).tolist()
    [-64.0, 64.0]
    >>> steady_friction([0.001, 0.02, 0.05], model).round(1).tolist()
    [65.3, 44.9, 47.5]
    """
    v = np.asarray(velocity, dtype=float)
    return np.sign(v) * stribeck(v, film_steady_state(v, model), model) + model.sigma2 * v


@_doc
def friction_step(state: FrictionState, velocity: float, dt: float,
                  model: LuGre) -> FrictionState:
    """Advance the friction state by ``dt`` at a frozen rod velocity (exact for frozen v).

    This is the stepping interface for time-domain simulators: pass the velocity at the middle
    of the step for second-order accuracy (or use :func:`friction_advance`, which also splits
    the step at a velocity reversal), then :func:`friction_force` with the velocity at the end
    of the step.

    Parameters
    ----------
    state : FrictionState
        Bristle deflection [m] and film thickness [-] at the start of the step.
    velocity : float
        Rod extension rate held over the step [m s-1].
    %(step)s
    %(model)s

    Returns
    -------
    FrictionState
        State at the end of the step. The film thickness used in g over the step is the exact
        film at the middle of the step.

    %(raises_step)s

    %(references_lugre)s

    Examples
    --------
    The step is exact for a frozen velocity, so one long step from rest lands on the steady
    state: z = g/σ0 = F_c/σ0 on the full film, and the force of :func:`steady_friction`,
    F_c + σ2 v = 64 N at 0.16 m/s:

    %(model_example)s
    >>> from flumekit.flap.friction import FrictionState, friction_force, friction_step
    >>> state = friction_step(FrictionState(), 0.16, 1.0, model)
    >>> round(state.z * 1e6, 6), round(state.h / model.film_max, 6)  # 40 µm, h = h_max
    (40.0, 1.0)
    >>> round(float(friction_force(state, 0.16, model)), 6)
    64.0
    """
    if not dt > 0:
        raise ValueError(f"friction step must be > 0, got {dt}")
    from flumekit.flap.kernels import lugre_step

    z, h = lugre_step(float(state[0]), float(state[1]), float(velocity), float(dt),
                      kernel_constants(model))
    return FrictionState(z, h)


@_doc
def friction_advance(state: FrictionState, velocity_start: float, velocity_end: float,
                     dt: float, model: LuGre) -> FrictionState:
    """Advance the state over a step in which the velocity varies linearly.

    The step is taken at the mid-step velocity, or, when the velocity changes sign inside the
    step, as two frozen-velocity steps split at the interpolated zero crossing, each at its own
    mid velocity. A single frozen velocity across a reversal keeps the old direction and misses
    the displacement after the crossing, which the bristles feel in full (at 100 Hz this was an
    error of 4.5 % of the force amplitude at the reversals of a 0.16 m/s motion).

    Parameters
    ----------
    state : FrictionState
        State at the start of the step.
    velocity_start, velocity_end : float
        Rod extension rate at the start and end of the step [m s-1].
    %(step)s
    %(model)s

    Returns
    -------
    FrictionState
        State at the end of the step.

    %(raises_step)s

    %(references_lugre)s

    Examples
    --------
    A reversal from −0.1 to 0.1 m/s is two frozen half steps of :func:`friction_step`, each at
    its own mid velocity ∓0.05 m/s; the same step is what :func:`friction_series` takes
    between two samples:

    %(model_example)s
    >>> from flumekit.flap.friction import (FrictionState, friction_advance, friction_series,
    ...                                     friction_step)
    >>> start = FrictionState(z=-4.0e-5, h=0.2)
    >>> state = friction_advance(start, -0.1, 0.1, 0.01, model)
    >>> halves = friction_step(friction_step(start, -0.05, 0.005, model), 0.05, 0.005, model)
    >>> state == halves
    True
    >>> _, z, h = friction_series([-0.1, 0.1], 0.01, model, state=start)
    >>> bool(np.isclose(z[1], state.z, rtol=1e-12) and np.isclose(h[1], state.h, rtol=1e-12))
    True
    """
    if not dt > 0:
        raise ValueError(f"friction step must be > 0, got {dt}")
    from flumekit.flap.kernels import lugre_advance

    z, h = lugre_advance(float(state[0]), float(state[1]), float(velocity_start),
                          float(velocity_end), float(dt), kernel_constants(model))
    return FrictionState(z, h)


@_doc
def friction_force(state: FrictionState, velocity, model: LuGre):
    """Friction force F = σ0 z + σ1 ż + σ2 v [N] (Eq. A3) for a state and a rod velocity.

    ż is the right-hand side of Eq. (A4) at this state and velocity. Evaluated at the end of a
    step with the end velocity (rather than as the mean rate (z₁ − z₀)/Δt over the step, which
    lags by half a step), the micro-damping term σ1 ż stays right at velocity reversals: for a
    0.16 m/s sine at the 100 Hz step the largest force error falls from 5.5 % to 0.5 % of the
    amplitude (flumekit.bench.flap). Vectorised over ``velocity`` and the state arrays.

    Parameters
    ----------
    state : FrictionState or tuple of array_like
        Bristle deflection z [m] and film thickness h [-].
    %(velocity)s
    %(model)s

    Returns
    -------
    numpy.ndarray
        F [N], positive when it resists extension.

    %(references_lugre)s

    Examples
    --------
    Bristles bent by F_c/σ0 = 40 µm on the full film: at rest they hold σ0 z = 40 N; sliding
    at 0.16 m/s they are in their steady state (ż = 0) and the viscous σ2 v = 24 N adds on:

    %(model_example)s
    >>> from flumekit.flap.friction import FrictionState, friction_force
    >>> state = FrictionState(z=4.0e-5, h=model.film_max)
    >>> friction_force(state, [0.0, 0.16], model).round(6).tolist()
    [40.0, 64.0]
    """
    z = np.asarray(state[0], dtype=float)
    h = np.asarray(state[1], dtype=float)
    v = np.asarray(velocity, dtype=float)
    g = stribeck(v, h, model)
    zdot = v - model.sigma0 * np.abs(v) * z / g
    return model.sigma0 * z + model.sigma1 * zdot + model.sigma2 * v


def kernel_constants(m: LuGre) -> np.ndarray:
    """Return the parameters as the float array the compiled kernels take.

    Parameters
    ----------
    m : LuGre
        Friction parameters.

    Returns
    -------
    ndarray
        σ0, σ1, σ2, F_c, F_s, 1/v_s, n, v_b, K_f, h_max, τ_hp, τ_hm, τ_h0
        (:mod:`flumekit.flap.kernels`).
    """
    return np.array([m.sigma0, m.sigma1, m.sigma2, m.coulomb_force, m.static_force,
                     1.0 / m.stribeck_velocity, m.stribeck_exponent,
                     m.minimum_friction_velocity, m.film_gain, m.film_max, m.tau_hp, m.tau_hm,
                     m.tau_h0], dtype=float)


@_doc
def friction_series(velocity, dt: float, model: LuGre, state: FrictionState = FrictionState(),
                    substeps: int = 1) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Friction force for a uniformly sampled rod velocity.

    Each sampling interval is split into ``substeps`` steps of :func:`friction_advance` on the
    linear interpolant of the velocity (mid-step velocity, split at reversals); the force at
    each sample is :func:`friction_force` of the state there with the sampled velocity.

    Parameters
    ----------
    velocity : array_like
        Rod extension rate at the samples [m s-1], 1-D.
    %(dt_sampling)s
    %(model)s
    state : FrictionState
        State at the first sample.
    substeps : int
        Steps per sampling interval.

    Returns
    -------
    force, z, h : numpy.ndarray
        Friction force [N], bristle deflection [m] and film thickness [-] at the samples.

    Raises
    ------
    ValueError
        A velocity that is not a non-empty 1-D finite series, a step that is not > 0, or
        ``substeps`` not an integer ≥ 1.

    %(references_lugre)s

    Examples
    --------
    Starting from rest at a constant 0.02 m/s (below v_b, on the falling branch of the
    Stribeck curve): at the first sample the bristles are straight (z = 0, ż = v) and only
    the damping acts, (σ1 + σ2) v = 43 N; the force then settles on :func:`steady_friction`:

    %(model_example)s
    >>> from flumekit.flap.friction import friction_series, steady_friction
    >>> force, z, h = friction_series(np.full(300, 0.02), 0.01, model)  # 3 s at 100 Hz
    >>> round(float(force[0]), 3), round(float(force[-1]), 3)
    (43.0, 44.856)
    >>> round(float(steady_friction(0.02, model)), 3)
    44.856
    """
    v = np.asarray(velocity, dtype=float)
    if v.ndim != 1 or v.size == 0:
        raise ValueError("friction_series needs a non-empty 1-D velocity series")
    if not np.all(np.isfinite(v)):
        raise ValueError("friction_series: the velocity has non-finite samples")
    if not (math.isfinite(dt) and dt > 0):
        raise ValueError(f"friction_series: dt must be > 0, got {dt}")
    if int(substeps) != substeps or substeps < 1:
        raise ValueError(f"substeps must be an integer >= 1, got {substeps}")
    from flumekit.flap.kernels import friction_loop

    zs, hs = np.empty(v.size), np.empty(v.size)
    # sequential by nature (each state needs the last): a compiled loop
    friction_loop(np.ascontiguousarray(v), float(dt), float(state[0]), float(state[1]),
                  int(substeps), kernel_constants(model), zs, hs)
    return friction_force((zs, hs), v, model), zs, hs
