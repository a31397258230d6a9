"""Time-domain flap dynamics: the Cummins equation with a nonlinear hydraulic PTO.

The device-agnostic integrator, waves, energy balance and stability guards are
:mod:`flumekit.hydro.simulation`; this module adds the flap's hydraulic cylinder with LuGre
friction as a PTO object (:class:`HydraulicCylinder`, its scalar kernels below) and the
campaign-level entry :func:`simulate_run`.

Equation of motion about the hinge (Cummins 1962; Eq. (11)-(13) in Brito et al. 2020):

    (I + A∞) θ̈ = T_exc(t) − μ(t) − T_g(θ) − c_d θ̇|θ̇| − T_PTO

* μ(t) = ∫₀ᵗ K(t − τ) θ̇(τ) dτ, the radiation memory, by convolution with K(t) or by the modal
  state-space model of :mod:`flumekit.hydro.radiation`; A∞ stays on the left-hand side.
* T_g = C θ (``restoring="linear"``, as in Eq. A1) or C sin θ (``"sine"``, exact for a rigid
  submerged flap, :func:`flumekit.flap.torque.gravity_torque`).
* c_d θ̇|θ̇|: optional quadratic viscous drag torque [N m s2].
* T_x(t, θ, θ̇): optional further torque acting on the flap (``extra_torque`` of
  :func:`simulate`), for physics beyond this model's (the virtual flume's losses,
  :mod:`flumekit.synth.flume`), which records its own parts.
* PTO: :class:`LinearDamper` (T_PTO = ν_pto θ̇) or :class:`HydraulicCylinder`: Eq. (13) in the
  signed form of :mod:`flumekit.flap.pressure`, P = s (K_p θ̇|θ̇| + I_p θ̈) clamped at the vapour
  pressure, torque T_p = −m A P with the signed lever arm m(θ) of
  :func:`flumekit.flap.geometry.rod_kinematics`, plus the modified LuGre friction of
  Appendix B (:func:`flumekit.flap.friction.friction_step`), T_f = m F_f.

The fluid inertia I_p θ̈ makes the pressure depend on the acceleration; off cavitation it adds
g I_p (g = −m s A > 0) to the inertia, so each evaluation solves for θ̈ with the effective
inertia, checks the pressure against the vapour clamp and, when it cavitates, solves again
with the clamped pressure (the unique consistent branch, since the pressure is decreasing in
the clamped value).

Integrator
----------
Fixed step h, the exponential fourth-order Runge-Kutta scheme ETDRK4 of Cox & Matthews (2002)
with the linear part diag(0, 0, λ_k): classical RK4 for (θ, θ̇), and for the radiation modes
ẋ_k = λ_k x_k + θ̇ the exact exponential propagation of each stage's input, with the
φ-functions of λ_k h precomputed. The modal update is therefore stable for any pole (no step
limit from fast radiation modes), the scheme is fourth order (measured: the error falls 16x
per halving of h), and the memory torque at every stage reduces to three dot products per step
(at the step start) plus scalar multiples of the stage velocities. The convolution
variant evaluates μ at the stage times by the trapezoidal rule on the step grid with K sampled
at half steps (history sums reused between stages; O(L/h) per step).

The LuGre state is stiff (relaxation rate σ0|v|/g, thousands per second); it is never
integrated by the RK stages. Its state at the stage times comes from exact frozen-velocity
exponential steps (:func:`flumekit.flap.friction.friction_step`) at the rod velocities
predicted at h/4 and 3h/4 from the first stage, the force at each stage is Eq. (A3) with the
stage's own rod velocity, and the state at the end of the step is advanced from the actual
start and end velocities, split at a reversal (:func:`flumekit.flap.friction.friction_advance`).
Every update is an exact exponential relaxation, stable for any h (operator splitting, first
order in the friction's coupling; measured < 0.05 % on θ at h = 0.04 s).

Torque signs in the output follow Eq. (11): T_h = I θ̈ + T_g + T_PTO, with ``torque_gravity``,
``torque_pto``, ``torque_pressure`` and ``torque_friction`` resisting (positive when they oppose
a positive θ, as in :mod:`flumekit.flap.torque`) and ``torque_excitation``,
``torque_radiation`` (−A∞θ̈ − μ), ``torque_drag`` and ``torque_hydrodynamic`` (their sum)
acting on the flap.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import xarray as xr

from flumekit.docstrings import filler
from flumekit.flap import friction as _friction
from flumekit.flap.friction import LuGre
from flumekit.flap.geometry import rod_kinematics
from flumekit.hydro import simulation as _sim
from flumekit.hydro.radiation import StateSpace
from flumekit.hydro.simulation import BadParameterError, DivergenceError, PTOKernel, SimulationError

#: docstring text that several functions of this module share
_doc = filler(
    pressure_loss_coefficient=("pressure_loss_coefficient : float\n"
                               "    K_p [Pa s2 rad-2]."))

#: rigid-body properties of the flap about its hinge (hydro.simulation.BodyDynamics)
FlapDynamics = _sim.BodyDynamics
#: linear PTO T = ν θ̇ (:class:`flumekit.hydro.simulation.LinearPTO`)
LinearDamper = _sim.LinearPTO

__all__ = ["BadParameterError", "DivergenceError", "FlapDynamics", "HydraulicCylinder",
           "LinearDamper", "SimulationError", "drag_torque_coefficient", "simulate",
           "simulate_run"]


def drag_torque_coefficient(drag_coefficient: float, flap_width: float, submerged_height: float,
                            rho: float = 1000.0) -> float:
    """Compute c_d of the quadratic drag torque c_d θ̇|θ̇| of a flat flap (Morison-type drag).

    Each strip at a distance r above the hinge moves at r θ̇ and resists with
    ½ ρ C_d w (r θ̇)|r θ̇| dr, so c_d = ½ ρ C_d w ∫₀^d r³ dr = ρ C_d w d⁴ / 8, with d the wetted
    height above the hinge (h − c for a surface-piercing flap). The water's own motion is
    neglected (drag on the absolute flap velocity), which is what makes it a damping.

    Parameters
    ----------
    drag_coefficient : float
        C_d of the plate [-] (about 2 for a flat plate normal to the flow), ≥ 0.
    flap_width : float
        w [m], > 0.
    submerged_height : float
        d [m], > 0.
    rho : float, default 1000
        Water density [kg m-3].

    Returns
    -------
    float
        c_d [N m s2].

    Raises
    ------
    ValueError
        If C_d < 0 or the width or height is not positive.

    References
    ----------
    Morison, J. R., O'Brien, M. P., Johnson, J. W. & Schaaf, S. A. (1950). The force exerted by
    surface waves on piles. Petroleum Transactions, AIME 189, 149-154.

    Examples
    --------
    >>> drag_torque_coefficient(2.0, 1.0, 0.5)
    15.625
    """
    if not (drag_coefficient >= 0 and flap_width > 0 and submerged_height > 0):
        raise ValueError("drag_torque_coefficient needs C_d >= 0, width > 0, height > 0")
    return rho * drag_coefficient * flap_width * submerged_height**4 / 8.0


def _lever_table(cyl: HydraulicCylinder, span: float = 1.2, n: int = 4001):
    """Signed lever arm m(θ) [m] on a uniform θ grid from flumekit.flap.geometry."""
    th = np.linspace(-span, span, n)
    m = rod_kinematics(th, np.zeros_like(th), cyl.bed_anchor, cyl.flap_anchor).lever_arm
    return float(th[0]), float(th[1] - th[0]), m


@_doc
@dataclass(frozen=True)
class HydraulicCylinder:
    """Single-acting cylinder of Brito et al. (2020), §2.2 and Eqs. (12)-(14), App. B.

    A PTO object of :mod:`flumekit.hydro.simulation` (methods ``kernel``, ``outputs``,
    ``describe``): its two internal states are the LuGre bristle deflection z [m] and film
    thickness parameter h [-]; its recorded outputs the chamber pressure and friction force.

    Parameters
    ----------
    bore_area : float
        A [m2].
    %(pressure_loss_coefficient)s
    %(fluid_inertia)s
    bed_anchor, flap_anchor : tuple of float
        Rod anchors (x, z) [m] (flap anchor at θ = 0).
    atmospheric_pressure, vapour_pressure : float
        P_atm and absolute P_v [Pa].
    friction : flumekit.flap.friction.LuGre or None
        Modified LuGre model, or None.

    Raises
    ------
    BadParameterError
        If a parameter is negative or not finite.

    References
    ----------
    Brito, M. et al. (2020). Experimental investigation on the power capture of an oscillating
    wave surge converter in unidirectional waves. Energies 13, 5417 (§2.2, Eqs. 12-14,
    Appendix B).
    """

    bore_area: float
    pressure_loss_coefficient: float
    fluid_inertia: float
    bed_anchor: tuple[float, float]
    flap_anchor: tuple[float, float]
    atmospheric_pressure: float = 101325.0
    vapour_pressure: float = 2339.0
    friction: LuGre | None = None

    def __post_init__(self):
        """Check every parameter (:class:`BadParameterError` names a bad one)."""
        for name in ("bore_area", "pressure_loss_coefficient", "fluid_inertia",
                     "atmospheric_pressure", "vapour_pressure"):
            _sim.check_parameter(name, getattr(self, name), 0.0)
        for name in ("bed_anchor", "flap_anchor"):
            for v in getattr(self, name):
                _sim.check_parameter(name, v)

    @_doc
    @classmethod
    def from_campaign(cls, pto, pressure_loss_coefficient: float, fluid_inertia: float,
                      friction: bool = True) -> HydraulicCylinder:
        """Build the cylinder from :class:`flumekit.campaign.PTO` and the fitted (or true) K_p, I_p.

        Parameters
        ----------
        pto : flumekit.campaign.PTO
            The campaign's PTO: bore, anchors, pressures and friction.
        %(pressure_loss_coefficient)s
        %(fluid_inertia)s
        friction : bool, default True
            Include the campaign's LuGre friction (if it has one).

        Returns
        -------
        HydraulicCylinder
        """
        fr = LuGre.from_campaign(pto.friction) if (friction and pto.friction) else None
        return cls(pto.bore_area, float(pressure_loss_coefficient), float(fluid_inertia),
                   tuple(pto.bed_anchor), tuple(pto.flap_anchor), pto.atmospheric_pressure,
                   pto.vapour_pressure, fr)

    @_doc
    def kernel(self, inertia: float, dt: float) -> PTOKernel:
        """Return the compiled kernels of :mod:`flumekit.flap.kernels`.

        They give θ̈ with the fluid inertia and the vapour clamp, and the LuGre states at the
        stage times and at the end of the step (:class:`flumekit.hydro.simulation.PTO`).

        Parameters
        ----------
        inertia : float
            Effective inertia I + A∞ [kg m2].
        %(dt)s

        Returns
        -------
        flumekit.hydro.simulation.PTOKernel
        """
        from flumekit.flap import kernels

        th_lo, dth, mtab = _lever_table(self)
        fr = self.friction
        params = kernels.cylinder_params(
            th_lo, dth, mtab, self.bore_area, self.pressure_loss_coefficient,
            self.fluid_inertia, inertia, self.vapour_pressure - self.atmospheric_pressure,
            None if fr is None else _friction.kernel_constants(fr), dt)

        def explain(theta: float) -> str | None:
            if th_lo <= theta < th_lo + dth * (len(mtab) - 1):
                return None
            return (f"flap angle {theta:.4g} rad is outside the PTO geometry table "
                    f"[{th_lo:.3g}, {-th_lo:.3g}] rad")

        if fr is None:
            return PTOKernel(kernels.cylinder_accel, params=params, explain=explain)
        return PTOKernel(kernels.cylinder_accel, kernels.cylinder_predict,
                         kernels.cylinder_advance, params, explain)

    def outputs(self, time, theta, theta_dot, theta_ddot, pressure, friction, z, h) -> dict:
        """Return pressure, forces, torques, flow, power, lever arm, cavitation, LuGre state.

        Units: pressure [Pa] (gauge), forces [N], torques [N m], flow [m3 s-1], power [W],
        lever arm [m] (:class:`flumekit.hydro.simulation.PTO`).
        """
        rod = rod_kinematics(theta, theta_dot, self.bed_anchor, self.flap_anchor)
        m = rod.lever_arm
        fp = self.bore_area * pressure
        q = -self.bore_area * rod.velocity  # flow out of the chamber (flumekit.flap.power)
        out = {"chamber_pressure": pressure, "force_pressure": fp, "force_friction": friction,
               "torque_pressure": -m * fp, "torque_friction": m * friction,
               "torque_pto": -m * fp + m * friction, "flow_rate": q, "power": pressure * q,
               "rod_velocity": rod.velocity, "lever_arm": m,
               "cavitating": (pressure <= self.vapour_pressure - self.atmospheric_pressure
                              ).astype(np.int8)}
        if self.friction is not None:
            out.update(bristle_deflection=z, film_thickness_parameter=h)
        return out

    def describe(self) -> dict:
        """Return the attributes naming the cylinder and its K_p, I_p and bore."""
        return {"pto": "hydraulic cylinder, Eq. (13) signed form with vapour clamp"
                       + (" + modified LuGre friction (App. B)" if self.friction else ""),
                "pressure_loss_coefficient": self.pressure_loss_coefficient,
                "fluid_inertia": self.fluid_inertia, "bore_area": self.bore_area}


@_doc
def simulate(excitation: xr.DataArray | None, flap: FlapDynamics,
             radiation: StateSpace | xr.DataArray | None,
             pto: LinearDamper | HydraulicCylinder | None, *, dt: float,
             duration: float | None = None, theta0: float = 0.0,
             theta_dot0: float = 0.0, output_step: float | None = None,
             extra_torque=None) -> xr.Dataset:
    """Integrate the flap's equation of motion (module notes) with a fixed step.

    Parameters
    ----------
    excitation : xarray.DataArray or None
        Excitation torque T_exc over ``time`` [N m] (cubic-spline interpolated to the half
        steps), or None for a free response.
    flap : FlapDynamics
        Inertia, A∞, stiffness, restoring law, drag and angle limit.
    radiation : StateSpace, xarray.DataArray or None
        :class:`flumekit.hydro.radiation.StateSpace`, an impulse response K(t) (DataArray over
        ``lag``, convolution), or None (no memory term).
    pto : LinearDamper, HydraulicCylinder or None
        The power take-off.
    dt : float
        Time step h [s].
    duration : float, optional
        Simulated time [s]; default the excitation record.
    theta0, theta_dot0 : float, default 0
        Initial angle [rad] and angular velocity [rad s-1].
    %(output_step)s
    extra_torque : callable, optional
        ``(j, theta, theta_dot) -> torque`` [N m] acting on the flap, with j the half-step
        index (time t0 + j dt/2, j = 0, 2, .. 2 n_steps). It is called once per step, in
        order, at the step's start, and held over the step (operator splitting, first order
        in the term: for slowly varying losses).

    Returns
    -------
    xarray.Dataset
        Over ``time``: θ [rad], θ̇ [rad s-1], θ̈ [rad s-2], every torque [N m] (signs in the
        module notes), the energy balance of :mod:`flumekit.hydro.simulation` [J], and for
        the hydraulic PTO the chamber pressure [Pa], flow rate [m3 s-1], power [W], forces
        [N], lever arm [m], cavitation flag and LuGre state.

    Raises
    ------
    BadParameterError
        If a parameter is not finite or out of range, a free response has no duration, the
        excitation does not cover the run or ``output_step`` is not a multiple of ``dt``.
    DivergenceError
        If the run diverges (:mod:`flumekit.hydro.simulation`).

    References
    ----------
    Cummins, W. E. (1962). The impulse response function and ship motions. Schiffstechnik 9.
    Cox, S. M., Matthews, P. C. (2002). Exponential time differencing for stiff systems.
    J. Comput. Phys. 176, 430-455.
    Brito, M. et al. (2020). Experimental investigation on the power capture of an oscillating
    wave surge converter in unidirectional waves. Energies 13, 5417 (Eqs. 11-13, Appendix B).

    Examples
    --------
    Free decay of an undamped flap from 0.1 rad: after one natural period
    2π √((I + A∞)/C) it is back at 0.1 rad.

    >>> import numpy as np
    >>> flap = FlapDynamics(inertia=2.0, added_inertia_infinite=0.5, hydrostatic_stiffness=60.0)
    >>> period = 2 * np.pi * np.sqrt(2.5 / 60.0)
    >>> run = simulate(None, flap, None, None, dt=period / 200, duration=period, theta0=0.1)
    >>> round(float(run.theta[-1]), 6)
    0.1
    """
    dt = _sim.check_parameter("dt", dt, 0.0, strict=True)
    if excitation is not None:
        f, (t0, t1) = _sim.excitation_series(excitation)
    else:
        f, t0, t1 = None, 0.0, None
    if duration is None:
        if excitation is None:
            raise BadParameterError("a free response needs a duration")
        duration = t1 - t0
    n_steps = math.floor(duration / dt + 1e-9)
    if n_steps < 1:
        raise BadParameterError("duration shorter than one step")
    if t1 is not None and t0 + n_steps * dt > t1 + 1e-9 * max(1.0, abs(t1)):
        raise BadParameterError(f"the excitation covers [{t0}, {t1}] s, the run "
                                f"[{t0}, {t0 + n_steps * dt}] s")
    every = _output_every(output_step, dt)
    out = _sim.integrate(f, flap, radiation, pto, dt=dt, n_steps=n_steps, t0=t0,
                         theta0=theta0, theta_dot0=theta_dot0, output_every=every,
                         extra_torque=extra_torque)
    time = t0 + dt * np.arange(0, n_steps + 1, every)
    attrs = {"output_step": every * dt}
    if extra_torque is not None:
        attrs["extra_torque"] = getattr(extra_torque, "description", repr(extra_torque))
    return _sim.to_dataset(out, time, flap, radiation, pto, dt, attrs)


def _output_every(output_step, dt) -> int:
    if output_step is None:
        return 1
    every = round(output_step / dt)
    if every < 1 or abs(every * dt - output_step) > 1e-9 * max(1.0, output_step):
        raise BadParameterError(f"bad parameter: output_step = {output_step} s must be a "
                                f"multiple of dt = {dt} s")
    return every


def _pto_model(pto: str, pto_damping, pressure_loss_coefficient, fluid_inertia, friction,
               campaign):
    if pto == "linear":
        if pto_damping is None:
            raise BadParameterError("pto='linear' needs pto_damping")
        return LinearDamper(float(pto_damping))
    if pto == "hydraulic":
        if pressure_loss_coefficient is None or fluid_inertia is None:
            raise BadParameterError("pto='hydraulic' needs pressure_loss_coefficient and "
                                    "fluid_inertia")
        if campaign is None:
            raise BadParameterError("pto='hydraulic' needs the campaign's PTO geometry")
        return HydraulicCylinder.from_campaign(campaign.pto, pressure_loss_coefficient,
                                               fluid_inertia, friction=friction)
    if pto == "none":
        return None
    raise BadParameterError(f"pto must be 'hydraulic', 'linear' or 'none', got {pto!r}")


def simulate_run(hydro: xr.Dataset, eta_incident_at_flap: xr.DataArray, campaign=None, *,
                 pto: str = "hydraulic", pto_damping: float | None = None,
                 pressure_loss_coefficient: float | None = None,
                 fluid_inertia: float | None = None, friction: bool = True,
                 drag_coefficient: float = 0.0, restoring: str = "linear", dt: float = 0.02,
                 radiation: str | StateSpace | xr.DataArray = "state_space",
                 irf_duration: float = 30.0,
                 order: int | None = None, match_frequency: float | None = None,
                 max_spread: float | None = None, taper: float = 2.0,
                 inertia: float | None = None, output_step: float | None = None,
                 extra_torque=None) -> xr.Dataset:
    """Simulate one flume run from its incident elevation at the flap (pure; for the stages).

    Parameters
    ----------
    hydro : xarray.Dataset
        Coefficient container (:mod:`flumekit.hydro.coefficients`); passivity is always
        checked. Its ``added_inertia_infinite`` is used if present, else it is estimated by the
        Ogilvie relation (median, or at ``match_frequency``; ``max_spread`` checks the spread).
    eta_incident_at_flap : xarray.DataArray
        Incident elevation at x = 0 over ``time`` [m] (separation stage).
    campaign : flumekit.campaign.Campaign, optional
        Flap inertia, PTO geometry and friction; needed for the hydraulic PTO, and for the
        inertia unless ``inertia`` is given.
    pto : str, default "hydraulic"
        "hydraulic", "linear" or "none".
    pto_damping : float, optional
        ν_pto [N m s] for ``pto="linear"``.
    pressure_loss_coefficient, fluid_inertia : float, optional
        K_p [Pa s2 rad-2] and I_p [Pa s2 rad-1] of Eq. (13) for ``pto="hydraulic"`` (fitted
        by the flap stage, or the virtual flume's truth).
    friction : bool, default True
        Include the LuGre friction of ``campaign.pto.friction``.
    drag_coefficient : float, default 0
        Quadratic drag torque coefficient c_d [N m s2].
    restoring : str, default "linear"
        "linear" (C θ, as Eq. A1) or "sine" (C sin θ).
    dt : float, default 0.02
        Time step [s].
    radiation : str, StateSpace or xarray.DataArray, default "state_space"
        "state_space", "convolution" or "none", or a precomputed model
        (:class:`~flumekit.hydro.radiation.StateSpace` or an impulse response over ``lag``),
        fitted once per campaign and shared by its runs.
    irf_duration : float, default 30
        Length of K(t) [s].
    order : int, optional
        State-space order (default: smallest with 1 % error on K(t)).
    match_frequency : float, optional
        Angular frequency [rad s-1] at which A∞ makes the time-domain model reproduce A(ω)
        exactly (e.g. 2π/T of a regular-wave run); default the median estimate.
    max_spread : float, optional
        Largest accepted spread of the Ogilvie estimates (None: report only).
    taper : float, default 2
        End tapers of the excitation filter [s]
        (:func:`flumekit.hydro.excitation.excitation_torque`); the result's ``valid_end``
        attribute says where the filter's end effect starts.
    inertia : float, optional
        Flap inertia about the hinge [kg m2]; default ``campaign.flap.inertia``.
    output_step : float, optional
        Output interval [s], a multiple of ``dt``.
    extra_torque : callable, optional
        Further torque on the flap, passed to :func:`simulate` (its half steps are those of
        the elevation's time grid at step ``dt``).

    Returns
    -------
    xarray.Dataset
        As :func:`flumekit.hydro.simulation.simulate`, on the elevation's time grid spacing
        ``dt``, with ``eta_incident`` [m] at the simulation times; attrs name the options.

    Raises
    ------
    BadParameterError
        If neither ``inertia`` nor ``campaign`` is given, the PTO's parameters are missing, or
        a parameter is out of range.

    References
    ----------
    Brito, M. et al. (2020). Experimental investigation on the power capture of an oscillating
    wave surge converter in unidirectional waves. Energies 13, 5417 (Eqs. 11-13).
    Ogilvie, T. F. (1964). Recent progress toward the understanding and prediction of ship
    motions. Proc. 5th Symp. Naval Hydrodynamics, 3-128.
    """
    if inertia is None:
        if campaign is None:
            raise BadParameterError("simulate_run needs inertia= or a campaign")
        inertia = campaign.flap.inertia
    model = _pto_model(pto, pto_damping, pressure_loss_coefficient, fluid_inertia, friction,
                       campaign)
    return _sim.simulate(hydro, inertia, model, _sim.MeasuredWave(eta_incident_at_flap, taper),
                         dt=dt, radiation=radiation, irf_duration=irf_duration, order=order,
                         match_frequency=match_frequency, max_spread=max_spread,
                         restoring=restoring, drag_coefficient=drag_coefficient,
                         output_step=output_step, extra_torque=extra_torque)
