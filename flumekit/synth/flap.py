"""The virtual flume's flap channels: flap motion, PTO forces and torques, encoder and pressure.

Three flap models (``FlapTruth.model``):

``"flume"`` (default): the simulator below plus the losses that the pipeline's models lack
(:mod:`flumekit.synth.flume`: KC-dependent vortex drag, wetted length, overtopping, bearing
friction, a check valve in the PTO line, the chamber's compliance and the vapour cavity of the
single-acting cylinder), calibrated to what Brito et al. (2020) state of their flume
(:mod:`flumekit.bench.flume`). The comparison stage's simulator and linear model then differ
from the "experiment" as the paper's do. Every extra term is recorded in the truth, the
valve's, the compliance's and the cavity's pressures in ``chamber_pressure_valve``,
``chamber_pressure_compliance`` and ``chamber_pressure_cavity``; since Eq. (13) cannot
represent them, the truth's attributes also hold the best Eq. (13) fit to the true pressure
over the true quasi-steady window (``eq13_pressure_loss_coefficient``,
``eq13_fluid_inertia``, ``eq13_r2``), the target of the flap stage's fit.

``"simulator"``: the time-domain simulator :func:`flumekit.flap.simulator.
simulate_run` (Cummins equation, Brito et al. 2020 Eqs. 11-13 and Appendix B) driven from rest
by the true incident elevation at the hinge line over the whole record (and an optional
lead-out, see :func:`flap_record`), with the Renzi & Dias (2012) coefficients of the flap in
the flume's channel (:func:`flume_hydrodynamics`, built as the pipeline's ``models/hydro``
stage builds them), the true K_p and I_p of ``FlapTruth``, the campaign's modified LuGre
friction and T_g = C sin θ (``restoring="sine"``, as :func:`flumekit.flap.torque.gravity_torque`
that the analysis inverts Eq. (11) with). The hydraulic PTO (signed quadratic loss, fluid
inertia, cavitation at the vapour pressure) and the friction therefore feed back into the
motion. The simulator steps ``simulator_substeps`` times per record step (default 1: h = 0.01 s
at 100 Hz; the states, pressure and LuGre state are the simulator's own at every record sample,
nothing is resampled). Against 4 steps per sample: θ within 5e-5, θ̇ 2e-4, pressure 3e-4, T_h
8e-4 and the friction force 9e-3 of their largest values (30 s, T = 2.5 s, cavitating). An
optional quadratic drag on the flat flap (``drag_coefficient`` C_d,
:func:`flumekit.flap.simulator.drag_torque_coefficient`) is off by default.

With potential-flow radiation as the only loss besides the PTO (and K_p = 1e6), this flap moves
more than the paper's: at T = 3.5 s, H = 0.25 m the steady θ swings from −0.62 to +0.34 rad
(amplitude 0.45-0.48 rad; the single-acting cylinder resists compression only, so the flap
leans to the sea), against 0.19 rad measured; C_f ≈ 0.36-0.42; 0.13 rad and C_f ≈ 0.36 at T = 2
s, H = 0.15 m; up to 0.61 rad at T = 4 s, H = 0.3 m. The chamber reaches 1.8-6.9 bar over the
paper's conditions and cavitates 17-35 % of the time. A drag coefficient C_d = 20 brings the
3.5 s amplitude to 0.25 rad only: the paper's smaller motion needs losses this model lacks.

``"linear"``: the linear one-degree-of-freedom model of the Eq. (A1) type, applied
in the frequency domain to the incident surface elevation at the hinge line (so a ramped wave
ramps the flap), per unit incident amplitude

    Θ(ω) = X(ω) / [C − (I + μ) ω² + i ω (ν(ω) + ν_pto + ν_visc)]

(numpy's e^{+iωt} convention), with

* X(ω): excitation torque per unit amplitude of a thin, fully reflecting flap in two dimensions:
  twice the incident dynamic pressure ρ g cosh k(z+h)/cosh kh integrated over the wetted flap
  (hinge at c = 0.10 m above the bed) with the lever arm about the hinge,
  X = 2 ρ g w [(h − c) tanh(kh)/k − (cosh kh − cosh kc)/(k² cosh kh)] (Renzi & Dias 2012,
  Eq. 3.1, 2-D reference); long-wave limit ρ g w (h − c)². About 6.3 kN m per metre of
  amplitude at T = 3.5 s. The torque is in phase with the incident elevation at x = 0
  (``excitation_phase`` shifts it).
* ν(ω) = X² / (2 ρ g c_g w): radiation damping from the 2-D Haskind relation (a body radiating
  equally to both sides absorbs at most half the incident power); about 630 N m s at 3.5 s.
* μ = 120 kg m² (``added_inertia``): constant added inertia, which puts the natural period
  2π √((I + μ)/C) at 3.0 s, inside the tested 2-4 s as Renzi & Dias predict for this flap.
* ν_pto = 500 N m s: linear damping equivalent to the mean power of the hydraulic PTO;
  ν_visc = 600 N m s: linearised viscous and vortex losses, which the paper finds important.
  With these θ reaches 0.08-0.19 rad for H = 0.15 m and 0.16-0.34 rad for H = 0.3 m over
  T = 2-4 s (the paper measured 0.19 rad at T = 3.5 s, H = 0.25 m), and C_f of the nonlinear
  PTO below is 0.075-0.16.
* K_p = 1.0e6 Pa s² rad⁻² (the flume model's default is 3.0e6) and I_p = 2.4e4 Pa s² rad⁻¹
  (a water column of about 3 m in a 12 mm line behind the 50 mm bore: ρ L (A/a) |m| ≈ 2.4e4):
  the chamber reaches 0.65-4.8 bar in compression and cavitates on the suction stroke for the
  larger heights (with K_p = 1.0e6).

For the linear model, the truth of the PTO follows from θ(t) through flumekit's own models,
exactly as the analysis assumes them: the rod kinematics of :mod:`flumekit.flap.geometry`, the
chamber pressure of Eq. (13) in the signed form with the cavitation clamp (true K_p, I_p), the
modified LuGre friction integrated on a grid ``friction_substeps`` times finer than the record
with the exact (band-limited) rod velocity, and the torques of Eq. (11)-(12). The hydrodynamic
torque T_h of the truth is *defined* by Eq. (11) from these, so that it is what a perfect
analysis recovers; the linear model's own excitation torque is returned as
``torque_excitation`` for reference.
With the simulator the same variables are the simulator's (rod kinematics recomputed exactly
from θ, θ̇), T_h is again defined by Eq. (11), and it equals the simulator's excitation +
radiation + drag torque to the lever-arm table's interpolation error (~1e-7 relative);
``torque_radiation`` and ``torque_drag`` are added.

Raw channels: encoder counts (wire shortening of Eq. (1) quantised with the campaign's
counts_per_metre, integers, zero at θ = 0) and the chamber gauge pressure with Gaussian sensor
noise of standard deviation 0.2 % of the rated output (10 bar by default: the linear model's
chamber reaches up to 4.8 bar, more than a 1 bar sensor could read; the flume's 4.5 bar at
H = 0.3 m, the simulator's more than 5 bar in the larger waves; the sensor is not clipped).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
import xarray as xr
from scipy import fft as sfft

from flumekit import conventions
from flumekit.campaign import Campaign
from flumekit.docstrings import doc
from flumekit.flap.encoder import counts_from_wire, wire_length
from flumekit.flap.friction import LuGre, friction_series
from flumekit.flap.geometry import rod_kinematics
from flumekit.flap.power import flow_rate, pto_power
from flumekit.flap.pressure import chamber_pressure_model, pressure_force
from flumekit.flap.renzi_dias.model import channel_container, two_dimensional_excitation
from flumekit.flap.torque import friction_torque, gravity_torque, inertia_torque, pressure_torque
from flumekit.signal import uniform_step
from flumekit.synth.flume import ExtraTorque, FlumeLosses
from flumekit.waves.theory import G, group_velocity

MODELS = ("flume", "simulator", "linear")


@dataclass(frozen=True)
class FlapTruth:
    """Physical parameters of the virtual flap that the campaign metadata does not hold.

    ``model`` selects the flap motion (module notes). The linear model uses ``added_inertia``,
    ``pto_damping``, ``viscous_damping``, ``excitation_phase`` and ``friction_substeps``; the
    simulator uses ``simulator_substeps``, ``drag_coefficient`` and ``irf_duration``; the
    flume is the simulator plus ``losses`` (:mod:`flumekit.synth.flume`). All use K_p, I_p,
    the pressure sensor and ``rho``.
    """

    model: str = "flume"  # "flume", "simulator" or "linear"
    losses: FlumeLosses = FlumeLosses()  # the flume's extra losses (model "flume")
    added_inertia: float = 120.0  # μ [kg m2]
    pto_damping: float = 500.0  # linear-equivalent PTO damping ν_pto [N m s]
    viscous_damping: float = 600.0  # linearised viscous losses ν_visc [N m s]
    excitation_phase: float = 0.0  # lag of the excitation torque behind η(x=0) [rad]
    pressure_loss_coefficient: float = 3.0e6  # K_p [Pa s2 rad-2] (flume calibration)
    fluid_inertia: float = 2.4e4  # I_p [Pa s2 rad-1]
    pressure_rated_output: float = 1.0e6  # sensor range [Pa]: the flume's chamber ~4.5 bar
    pressure_noise: float = 0.002  # noise std as a fraction of the rated output [-]
    friction_substeps: int = 10  # fine friction steps per record step (linear model)
    simulator_substeps: int = 1  # simulator steps per record step
    drag_coefficient: float = 0.0  # C_d of the flat flap's quadratic drag [-] (simulator)
    irf_duration: float = 30.0  # length of the radiation impulse response [s] (simulator)
    rho: float = 1000.0  # water density [kg m-3]

    def __post_init__(self):
        """Refuse an unknown model and a non-finite, negative or non-integer parameter."""
        if self.model not in MODELS:
            raise ValueError(f"FlapTruth.model = {self.model!r} is not allowed: {MODELS}")
        for f in dataclasses.fields(self):
            v = getattr(self, f.name)
            if f.name in ("model", "losses"):
                continue
            if f.name == "excitation_phase":
                ok = np.isfinite(v)
            elif f.name in ("pressure_noise", "viscous_damping", "pto_damping", "fluid_inertia",
                            "drag_coefficient"):
                ok = np.isfinite(v) and v >= 0
            else:
                ok = np.isfinite(v) and v > 0
            if not ok:
                raise ValueError(f"FlapTruth.{f.name} = {v} is not allowed")
        for name in ("friction_substeps", "simulator_substeps"):
            if int(getattr(self, name)) != getattr(self, name):
                raise ValueError(f"FlapTruth.{name} must be an integer")


class FlumeHydrodynamics(NamedTuple):
    """What the simulator needs of the flap in the flume, the same for every run of a campaign."""

    hydro: xr.Dataset  # coefficient container with A∞ (flumekit.hydro.coefficients)
    radiation: object  # flumekit.hydro.radiation.StateSpace of the radiation kernel


@doc
def flume_hydrodynamics(campaign: Campaign, truth: FlapTruth = FlapTruth(), *,
                        irf_step: float = 0.005, rtol: float = 1e-3) -> FlumeHydrodynamics:
    """Build the Renzi-Dias coefficients of the flap in the flume and their radiation model.

    The container is the pipeline's ``models/hydro`` one
    (:func:`flumekit.flap.renzi_dias.model.channel_container`, channel width = flume width), and
    the radiation kernel K(t) over ``truth.irf_duration`` is fitted by the state-space model of
    :func:`flumekit.hydro.radiation.fit_state_space` (build it once per campaign and pass it
    to :func:`flap_record`). The fit is tighter than the simulator's
    default (``rtol`` 1e-3 reaches order 17 and 0.28 % on K(t), against order 11 and 0.8 % at
    1e-2): measured against Eq. (A1) at small amplitude without PTO, the flap's steady
    amplitude and phase are then within 0.5 % and 0.35° at T = 2-4 s (1.0 % and 1.0° at T = 4 s
    with the default fit; 0.3 % and 0.4° by direct convolution).

    Parameters
    ----------
    campaign : flumekit.campaign.Campaign
        Depth, flume width, flap width, hinge height and stiffness C.
    truth : FlapTruth, optional
        Density ``rho`` [kg m-3] and ``irf_duration`` [s].
    irf_step : float, default 0.005
        Sampling step of K(t) for the fit [s].
    rtol : float, default 1e-3
        Target relative error of the state-space fit of K(t) [-].

    Returns
    -------
    FlumeHydrodynamics
        The coefficient container (with A∞) and the state-space radiation model.

    %(references_renzi_dias2012)s.
    """
    from flumekit.hydro.radiation import fit_state_space, impulse_response

    flap = campaign.flap
    hydro = channel_container(campaign.flume.water_depth, flap.width, flap.hinge_height,
                              campaign.flume.width, flap.buoyancy_stiffness, rho=truth.rho)
    radiation = fit_state_space(impulse_response(hydro, truth.irf_duration, irf_step),
                                rtol=rtol)
    return FlumeHydrodynamics(hydro, radiation)


@doc
def radiation_damping(omega, depth: float, hinge_height: float, width: float,
                      rho: float = 1000.0, g: float = G) -> np.ndarray:
    """Compute the radiation damping ν(ω) = X² / (2 ρ g c_g w) from the 2-D Haskind relation.

    Parameters
    ----------
    omega : array_like
        Angular frequencies [rad s-1].
    depth : float
        Water depth h [m].
    hinge_height : float
        Hinge height c above the bed [m].
    width : float
        Flap width w [m].
    %(rho)s
    %(g)s

    Returns
    -------
    numpy.ndarray
        ν(ω) [N m s], shaped as ``omega``.
    """
    w = np.asarray(omega, dtype=float)
    x = two_dimensional_excitation(w, depth, hinge_height, width, rho, g)
    cg = np.full(w.shape, np.sqrt(g * depth))
    pos = w > 0
    cg[pos] = group_velocity(2 * np.pi / w[pos], depth, g)
    return x**2 / (2 * rho * g * cg * width)


@doc
def flap_scattering(frequency, campaign: Campaign, loss_damping: float,
                    truth: FlapTruth = FlapTruth()) -> tuple[np.ndarray, np.ndarray]:
    """Compute the complex reflection R(f) and transmission T(f) of the flap in two dimensions.

    The flap's linear one-degree-of-freedom model (module notes, model "linear": inertia
    I + μ, stiffness C, 2-D radiation damping ν(ω) of the Haskind relation) with a linear loss
    damping ν_L standing for the PTO and the flume's losses. A fixed thin flap reflects the
    whole wave (R = 1, T = 0: the excitation X(ω) is that of a fully reflecting wall); its
    motion radiates antisymmetric waves, −u to the sea and +u to the lee, so R = 1 − u, T = u.
    The energy balance |R|² + |T|² = 1 − 2 ν ν_L / |Z|² (the share absorbed by ν_L) for every
    inertia fixes the phase of u, and

        u = ν / Z,  Z = ν + ν_L + i (ω (I + μ) − C/ω),

    in the convention η = Re Σ c e^{+iωt} of numpy's FFT (R and T multiply the incident
    wave's coefficient at x = 0). Without losses the free flap is transparent at resonance
    (T = 1) and reflects like a wall at high frequency (R → 1); with ν_L = 110 N m s it
    absorbs a quarter of the incident flux at T = 3.5 s (the flume's D = 0.25,
    :mod:`flumekit.synth.flume`), reflects 19 % there, 32 % at 2 s and 79 % at 1 s.

    Parameters
    ----------
    frequency : array_like
        Frequencies [Hz], > 0.
    campaign : Campaign
        Depth, flap inertia, width, hinge height and stiffness C.
    loss_damping : float
        ν_L [N m s].
    truth : FlapTruth
        Added inertia μ [kg m2] and density [kg m-3].

    Returns
    -------
    R, T : numpy.ndarray
        Complex reflection and transmission coefficients [-].

    References
    ----------
    Newman, J. N. (1976). The interaction of stationary vessels with regular waves. Proc. 11th
    Symp. Naval Hydrodynamics, 491-501 (2-D energy relations of a body radiating to both sides).
    %(renzi_dias2012)s, Eq. (3.1).

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.synth import virtual_campaign
    >>> campaign = virtual_campaign("raw/default", "default", 2020)
    >>> r, t = flap_scattering(np.array([0.5, 1.0]), campaign, 110.0)
    >>> np.abs(r).round(2).tolist()
    [0.32, 0.79]
    """
    f = np.asarray(frequency, dtype=float)
    if np.any(f <= 0) or not (np.isfinite(loss_damping) and loss_damping >= 0):
        raise ValueError("frequencies must be > 0 and the loss damping >= 0")
    flap = campaign.flap
    omega = 2 * np.pi * f
    nu = radiation_damping(omega, campaign.flume.water_depth, flap.hinge_height, flap.width,
                           truth.rho)
    z = nu + loss_damping + 1j * (omega * (flap.inertia + truth.added_inertia)
                                  - flap.buoyancy_stiffness / omega)
    u = nu / z
    return 1.0 - u, u


def flap_motion(time, eta_incident_at_flap, *, campaign: Campaign, truth: FlapTruth = FlapTruth(),
                upsample: int = 1) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Compute θ, θ̇, θ̈ and the excitation torque of the linear 1-DOF model (module notes).

    Parameters
    ----------
    time : array_like
        Record times [s], uniform.
    eta_incident_at_flap : array_like
        Incident surface elevation at x = 0 [m], on ``time``.
    campaign : flumekit.campaign.Campaign
        Depth, flap inertia, width, hinge height and buoyancy stiffness.
    truth : FlapTruth, optional
        Model parameters.
    upsample : int, default 1
        Return the motion on a grid ``upsample`` times finer than ``time`` (band-limited
        interpolation), of (n − 1)·upsample + 1 points.

    Returns
    -------
    theta : numpy.ndarray
        Flap angle [rad].
    theta_dot : numpy.ndarray
        Angular velocity [rad s-1].
    theta_ddot : numpy.ndarray
        Angular acceleration [rad s-2].
    torque_excitation : numpy.ndarray
        Excitation torque [N m].

    Raises
    ------
    ValueError
        If ``time`` is not uniform or the elevation is not finite or does not match it.
    """
    t = np.asarray(time, dtype=float)
    dt = uniform_step(t, "flap_record", min_samples=4)
    eta = np.asarray(eta_incident_at_flap, dtype=float)
    if eta.shape != t.shape or not np.all(np.isfinite(eta)):
        raise ValueError("eta_incident_at_flap must be finite and match time")
    flap, depth = campaign.flap, campaign.flume.water_depth
    n = t.size
    # zero padding: the response to the end of the record decays (time constant
    # 2(I+μ)/ν ≈ 0.2 s) long before it could wrap round to the start
    nfft = sfft.next_fast_len(2 * n + int(np.ceil(20.0 / dt)))
    spec = sfft.rfft(eta, nfft)
    omega = 2 * np.pi * sfft.rfftfreq(nfft, dt)
    x = two_dimensional_excitation(omega, depth, flap.hinge_height, flap.width, truth.rho)
    nu = radiation_damping(omega, depth, flap.hinge_height, flap.width, truth.rho)
    z = (flap.buoyancy_stiffness - (flap.inertia + truth.added_inertia) * omega**2
         + 1j * omega * (nu + truth.pto_damping + truth.viscous_damping))
    lag = np.exp(-1j * truth.excitation_phase * np.sign(omega))
    torque = x * lag * spec
    if nfft % 2 == 0:
        torque[-1] = 0.0  # Nyquist bin: no derivative can be represented there
    theta_hat = torque / z
    m = int(upsample)
    if m < 1:
        raise ValueError("upsample must be >= 1")
    n_out = (n - 1) * m + 1

    def back(hat):
        return sfft.irfft(hat, nfft * m)[:n_out] * m

    return (back(theta_hat), back(1j * omega * theta_hat), back(-omega**2 * theta_hat),
            back(torque))


def _linear_truth(t, dt, eta, campaign: Campaign, truth: FlapTruth) -> dict:
    """Motion, chamber pressure and LuGre friction of the linear model (module notes)."""
    pto = campaign.pto
    m = int(truth.friction_substeps)
    th_f, thd_f, thdd_f, exc_f = flap_motion(t, eta, campaign=campaign, truth=truth, upsample=m)
    theta, theta_dot, theta_ddot = th_f[::m], thd_f[::m], thdd_f[::m]
    rod = rod_kinematics(theta, theta_dot, pto.bed_anchor, pto.flap_anchor)
    compression = -1 if np.median(rod.lever_arm) > 0 else 1
    p_true = chamber_pressure_model(theta_dot, theta_ddot, truth.pressure_loss_coefficient,
                                    truth.fluid_inertia,
                                    atmospheric_pressure=pto.atmospheric_pressure,
                                    vapour_pressure=pto.vapour_pressure,
                                    compression_sign=compression)
    if pto.friction is not None:
        rod_fine = rod_kinematics(th_f, thd_f, pto.bed_anchor, pto.flap_anchor)
        f_fine, z_fine, h_fine = friction_series(rod_fine.velocity, dt / m,
                                                 LuGre.from_campaign(pto.friction))
        f_f, z_b, h_l = f_fine[::m], z_fine[::m], h_fine[::m]
    else:
        f_f = z_b = h_l = np.zeros_like(t)
    flap = campaign.flap
    return {"theta": theta, "theta_dot": theta_dot, "theta_ddot": theta_ddot,
            "p_true": p_true, "f_f": f_f, "z_b": z_b, "h_l": h_l,
            "series": {"torque_excitation": exc_f[::m]},
            "scalars": {
                "added_inertia": truth.added_inertia, "pto_damping": truth.pto_damping,
                "radiation_damping": lambda w: float(radiation_damping(
                    np.array([w]), campaign.flume.water_depth, flap.hinge_height, flap.width,
                    truth.rho)[0])},
            "source": "flumekit.synth.flap: linear 1-DOF flap model + flumekit PTO models",
            "attrs": {}}


def _simulator_truth(t, dt, eta, campaign: Campaign, truth: FlapTruth,
                     hydro: FlumeHydrodynamics | xr.Dataset | None, *, period: float,
                     eta_front=None) -> dict:
    """Simulate the motion, pressure and friction with the time-domain simulator (module notes).

    The flume's extra losses are added for ``truth.model == "flume"``
    (:mod:`flumekit.synth.flume`).
    """
    from flumekit.flap.simulator import drag_torque_coefficient, simulate_run
    from flumekit.hydro.radiation import fit_state_space, impulse_response

    if hydro is None:
        hydro = flume_hydrodynamics(campaign, truth)
    elif isinstance(hydro, xr.Dataset):
        hydro = FlumeHydrodynamics(
            hydro, fit_state_space(impulse_response(hydro, truth.irf_duration, 0.005),
                                   rtol=1e-3))
    flap = campaign.flap
    m = int(truth.simulator_substeps)
    c_d = (drag_torque_coefficient(truth.drag_coefficient, flap.width,
                                   campaign.flume.water_depth - flap.hinge_height, truth.rho)
           if truth.drag_coefficient > 0 else 0.0)
    extra = None
    if truth.model == "flume":
        h = dt / m
        n_half = 2 * int(np.floor((t[-1] - t[0]) / h + 1e-9)) + 1
        front = eta if eta_front is None else eta_front
        omega = 2 * np.pi / period
        x_w = hydro.hydro["angular_frequency"].values
        excitation = float(np.interp(omega, x_w, np.abs(hydro.hydro["excitation_torque"].values)))
        m0 = rod_kinematics(np.zeros(1), np.zeros(1), campaign.pto.bed_anchor,
                            campaign.pto.flap_anchor).lever_arm[0]
        extra = ExtraTorque(np.interp(t[0] + 0.5 * h * np.arange(n_half), t, front),
                            omega=omega, amplitude=float(np.sqrt(2) * np.std(eta[eta.size // 2:])),
                            excitation=excitation, campaign=campaign, losses=truth.losses,
                            compression_sign=-1 if m0 > 0 else 1,
                            pressure_loss_coefficient=truth.pressure_loss_coefficient,
                            time_step=h, rho=truth.rho)
    sim = simulate_run(hydro.hydro, xr.DataArray(eta, dims="time", coords={"time": t}),
                       campaign, pto="hydraulic",
                       pressure_loss_coefficient=truth.pressure_loss_coefficient,
                       fluid_inertia=truth.fluid_inertia, friction=True,
                       drag_coefficient=c_d, restoring="sine", dt=dt / m,
                       radiation=hydro.radiation, extra_torque=extra)
    sim = sim.isel(time=slice(None, None, m))
    if sim.sizes["time"] != t.size:
        raise RuntimeError(f"the simulator returned {sim.sizes['time']} samples for the "
                           f"record's {t.size}")

    def get(name):
        return sim[name].values if name in sim else np.zeros_like(t)

    series = {n: get(n) for n in ("torque_excitation", "torque_radiation", "torque_drag")}
    p_true = get("chamber_pressure")
    if extra is not None:
        series.update(extra.record(step=m))
        # the valve's, the compliance's and the cavity's pressures add to Eq. (13)'s in the
        # chamber (their torques m A ΔP acted on the flap through the simulator's extra torque)
        p_true = (p_true + series["chamber_pressure_valve"]
                  + series["chamber_pressure_compliance"] + series["chamber_pressure_cavity"])

    h = hydro.hydro
    w_grid = h["angular_frequency"].values

    def at(name):
        return lambda w: float(np.interp(w, w_grid, h[name].values))

    return {"theta": get("theta"), "theta_dot": get("theta_dot"),
            "theta_ddot": get("theta_ddot"), "p_true": p_true,
            "f_f": get("force_friction"),
            "z_b": get("bristle_deflection"), "h_l": get("film_thickness_parameter"),
            "series": series,
            "scalars": {"added_inertia": at("added_inertia"),
                        "added_inertia_infinite": float(h["added_inertia_infinite"]),
                        "radiation_damping": at("radiation_damping")},
            "source": ("flumekit.synth.flap: time-domain simulator (flumekit.flap.simulator, "
                       "Renzi-Dias coefficients, hydraulic PTO with cavitation and fluid "
                       "inertia, modified LuGre friction, T_g = C sin theta)"
                       + (" + " + extra.description if extra is not None else "")),
            "attrs": {"simulator_time_step": dt / m,
                      "simulator_drag_torque_coefficient": c_d,
                      "simulator_radiation": sim.attrs.get("radiation", ""),
                      "simulator_radiation_order": int(sim.attrs.get("radiation_order", 0)),
                      "simulator_radiation_fit_error_time":
                          float(sim.attrs.get("radiation_fit_error_time", np.nan)),
                      "simulator_added_inertia_infinite_spread":
                          float(sim.attrs.get("added_inertia_infinite_spread", np.nan))}}


def _eq13_reference(t, theta, theta_dot, theta_ddot, p_true, period: float, pto,
                    span: tuple[float, float] | None = None) -> dict:
    """Fit Eq. (13) to the true chamber pressure over the true quasi-steady window or ``span``.

    ``span`` [s] is the analysed span of an irregular run.

    What a perfect flap stage can recover: with the flume's check valve the chamber pressure
    holds a term Eq. (13) cannot represent, so the true K_p, I_p are no longer the fit's
    target; this least-squares optimum on the noise-free truth is. The regressors are θ̇ and θ̈
    of the true θ band-limited as the flap stage does (4 Hz zero-phase Butterworth,
    :data:`flumekit.flap.analysis.DEFAULT_CUTOFF`): with the valve's residual in the pressure,
    the fitted I_p depends on the band of θ̈ by a few per cent (3 % at T = 3.5 s, H = 0.25 m,
    against the exact θ̈), which is the model's misfit, not the stage's error.
    """
    from flumekit.flap.analysis import DEFAULT_CUTOFF
    from flumekit.flap.pressure import fit_pressure_model
    from flumekit.signal import quasi_steady_window, smooth_derivatives

    dt = (t[-1] - t[0]) / (t.size - 1)
    _, theta_dot, theta_ddot = smooth_derivatives(theta, 1.0 / dt, DEFAULT_CUTOFF)

    if span is not None:
        inside = (t >= span[0]) & (t <= span[1])
    else:
        try:
            win = quasi_steady_window(theta, t, tolerance=0.02, min_period=0.5 * period)
        except ValueError:
            return {}
        inside = (t >= win.start) & (t <= win.end)
    m0 = rod_kinematics(np.zeros(1), np.zeros(1), pto.bed_anchor, pto.flap_anchor).lever_arm[0]
    fit = fit_pressure_model(p_true[inside], theta_dot[inside], theta_ddot[inside],
                             atmospheric_pressure=pto.atmospheric_pressure,
                             vapour_pressure=pto.vapour_pressure,
                             compression_sign=-1 if m0 > 0 else 1)
    return {"eq13_pressure_loss_coefficient": fit.pressure_loss_coefficient,
            "eq13_fluid_inertia": fit.fluid_inertia, "eq13_r2": fit.r2}


def _flat_attrs(prefix: str, d: dict) -> dict:
    """Nested truth parameters as flat netCDF attributes (prefix_name, prefix_group_name)."""
    out = {}
    for k, v in d.items():
        out.update(_flat_attrs(f"{prefix}_{k}", v) if isinstance(v, dict)
                   else {f"{prefix}_{k}": v})
    return out


def flap_record(time, eta_incident_at_flap, *, period: float, campaign: Campaign,
                rng: np.random.Generator, truth: FlapTruth = FlapTruth(),
                height: float | None = None,
                hydro: FlumeHydrodynamics | xr.Dataset | None = None,
                eta_lead_out=None, eta_front=None,
                span: tuple[float, float] | None = None) -> xr.Dataset:
    """Synthesise the raw flap channels and their truth for one run of the virtual flume.

    Parameters
    ----------
    time : array_like
        Record times [s], uniform (100 Hz for the campaign's encoder and pressure sensor).
    eta_incident_at_flap : array_like
        True incident surface elevation at the hinge line x = 0 [m], over the whole record
        (the flap starts from rest at its first sample).
    period : float
        Wave period of the run [s] (recorded; the models are frequency dependent); the peak
        period of an irregular run.
    campaign : flumekit.campaign.Campaign
        Campaign metadata (flap, PTO, encoder, flume).
    rng : numpy.random.Generator
        Random generator for the pressure sensor noise.
    truth : FlapTruth, optional
        Parameters of the virtual flap, among them ``model``.
    height : float, optional
        Target wave height of the run [m], recorded in the attributes if given.
    hydro : FlumeHydrodynamics or xarray.Dataset, optional
        For the simulator: :class:`FlumeHydrodynamics` of the campaign (build it once with
        :func:`flume_hydrodynamics`), or a coefficient container alone (its radiation model is
        then fitted here), or None (both built here). Ignored by the linear model.
    eta_lead_out : array_like, optional
        Incident elevation at x = 0 that follows the record [m], at the record's step. The
        flap is driven over the record and this lead-out, then cut to
        ``time``, so that the end of the truth sees the wave that goes on: the excitation
        filter is non-causal and the simulator tapers its last 2 s (without a lead-out, θ of
        the last 1-2 s differs from that of a continuing wave by up to 30 % of its amplitude;
        with 20 s of lead-out the whole record is within 0.11 % of that of a record 60 s
        longer, the rest being a near-constant offset: the excitation filter removes the
        record's mean elevation, :func:`flumekit.hydro.excitation.excitation_torque`).
    eta_front : array_like, optional
        True local elevation in front of the flap (incident + reflected at x = 0) [m] over
        the record and the lead-out, for the flume's wetted length and overtopping (model
        "flume"); default the incident elevation.
    span : tuple of float, optional
        (start, end) [s] over which the truth's best Eq. (13) fit is made (an irregular run's
        analysed span); default the true quasi-steady window of θ.

    Returns
    -------
    xarray.Dataset
        On ``time``: the raw channels ``encoder_counts`` (int64) and ``chamber_pressure``
        (noisy, gauge) [Pa], and the truth: ``theta`` [rad], ``theta_dot`` [rad s-1],
        ``theta_ddot`` [rad s-2], ``wire_shortening`` [m], rod kinematics,
        ``chamber_pressure_true`` [Pa], ``cavitating``, forces [N], LuGre state, torques
        [N m] (resisting convention of :mod:`flumekit.flap.torque`), ``torque_excitation``,
        ``torque_hydrodynamic`` (Eq. 11), ``flow_rate`` [m3 s-1], ``power`` [W]; with the
        simulator also ``torque_radiation`` and ``torque_drag`` (acting on the flap).
        Scalar attributes: K_p, I_p, C, the added inertia and radiation damping at 2π/T (the
        linear model's constant μ), and A∞ (simulator) or ν_pto (linear).

    Raises
    ------
    ValueError
        If ``time`` is not uniform, ``period`` is not positive or the elevation is not finite
        or does not match ``time``.

    References
    ----------
    Brito, M. et al. (2020). Experimental investigation on the power capture of an oscillating
    wave surge converter in unidirectional waves. Energies 13, 5417 (Eqs. 1, 11-13,
    Appendix B).

    Examples
    --------
    20 s of a 2.5 s wave ramped up over 10 s, with the linear model (the quickest) and the
    flap, PTO and encoder of the virtual campaign. The raw encoder channel is the true wire
    shortening to within half a count, and the true torques close Eq. (11).

    >>> from flumekit.synth.campaign import virtual_campaign
    >>> campaign = virtual_campaign("raw/small", "small", 2020)
    >>> t = np.arange(0, 20, 0.01)
    >>> eta = 0.05 * np.clip(t / 10, 0, 1) * np.cos(2 * np.pi * t / 2.5)
    >>> rec = flap_record(t, eta, period=2.5, campaign=campaign, rng=np.random.default_rng(0),
    ...                   truth=FlapTruth(model="linear"))
    >>> step = 1 / campaign.encoder.counts_per_metre  # one count [m]
    >>> float(abs(rec.encoder_counts * step - rec.wire_shortening).max()) <= step / 2
    True
    >>> balance = rec.torque_inertia + rec.torque_gravity + rec.torque_pto
    >>> bool(np.allclose(rec.torque_hydrodynamic, balance))  # Eq. (11)
    True
    """
    t = np.asarray(time, dtype=float)
    dt = uniform_step(t, "flap_record", min_samples=4)
    if not (np.isfinite(period) and period > 0):
        raise ValueError(f"period must be > 0, got {period}")
    eta = np.asarray(eta_incident_at_flap, dtype=float)
    if eta.shape != t.shape or not np.all(np.isfinite(eta)):
        raise ValueError("eta_incident_at_flap must be finite and match time")
    lead = np.empty(0) if eta_lead_out is None else np.asarray(eta_lead_out, dtype=float)
    if lead.ndim != 1 or not np.all(np.isfinite(lead)):
        raise ValueError("eta_lead_out must be a finite 1-D array")
    flap, pto, enc = campaign.flap, campaign.pto, campaign.encoder
    n = t.size
    t_run = t[0] + dt * np.arange(n + lead.size) if lead.size else t
    eta_run = np.concatenate([eta, lead])
    if truth.model == "linear":
        mo = _linear_truth(t_run, dt, eta_run, campaign, truth)
    else:
        front = None if eta_front is None else np.asarray(eta_front, dtype=float)
        if front is not None and front.shape != eta_run.shape:
            raise ValueError("eta_front must cover the record and the lead-out")
        mo = _simulator_truth(t_run, dt, eta_run, campaign, truth, hydro, period=period,
                              eta_front=front)
    theta, theta_dot, theta_ddot = mo["theta"][:n], mo["theta_dot"][:n], mo["theta_ddot"][:n]
    p_true, f_f = mo["p_true"][:n], mo["f_f"][:n]
    rod = rod_kinematics(theta, theta_dot, pto.bed_anchor, pto.flap_anchor)

    cav = p_true <= pto.vapour_pressure - pto.atmospheric_pressure
    f_p = pressure_force(p_true, pto.bore_area)
    t_p = pressure_torque(f_p, rod.lever_arm)
    t_f = friction_torque(f_f, rod.lever_arm)
    t_g = gravity_torque(theta, flap.buoyancy_stiffness)
    t_i = inertia_torque(theta_ddot, flap.inertia)
    q = flow_rate(rod.velocity, pto.bore_area)

    wire = enc.L7 - wire_length(theta, enc.L5, enc.L7)
    counts = counts_from_wire(wire, enc.counts_per_metre)
    noise = truth.pressure_noise * truth.pressure_rated_output
    p_meas = p_true + rng.normal(0.0, noise, t.size) if noise > 0 else p_true.copy()

    eq13 = _eq13_reference(t, theta, theta_dot, theta_ddot, p_true, period, pto, span)
    omega_run = 2 * np.pi / period
    scalars = {k: (v(omega_run) if callable(v) else v) for k, v in mo["scalars"].items()}
    T = ("time",)
    ds = xr.Dataset(
        {
            "encoder_counts": (T, counts), "chamber_pressure": (T, p_meas),
            "theta": (T, theta), "theta_dot": (T, theta_dot), "theta_ddot": (T, theta_ddot),
            "wire_shortening": (T, wire),
            "rod_length": (T, rod.length), "rod_velocity": (T, rod.velocity),
            "beta": (T, rod.beta), "lever_arm": (T, rod.lever_arm),
            "chamber_pressure_true": (T, p_true), "cavitating": (T, cav.astype(np.int8)),
            "force_pressure": (T, f_p), "force_friction": (T, f_f),
            "bristle_deflection": (T, mo["z_b"][:n]),
            "film_thickness_parameter": (T, mo["h_l"][:n]),
            "torque_pressure": (T, t_p), "torque_friction": (T, t_f),
            "torque_pto": (T, t_p + t_f), "torque_gravity": (T, t_g),
            "torque_inertia": (T, t_i),
            **{k: (T, v[:n]) for k, v in mo["series"].items()},
            # Eq. (11) in Brito et al. 2020 defines the true hydrodynamic torque
            "torque_hydrodynamic": (T, t_i + t_g + t_p + t_f),
            "flow_rate": (T, q), "power": (T, pto_power(p_true, q)),
            "pressure_loss_coefficient": truth.pressure_loss_coefficient,
            "fluid_inertia": truth.fluid_inertia,
            "hydrostatic_stiffness": flap.buoyancy_stiffness,
            **scalars,
        },
        coords={"time": t, "wave_period": float(period)},
        attrs={"source": mo["source"],
               **_flat_attrs("truth", dataclasses.asdict(truth)),
               **mo["attrs"], **eq13, "lead_out_duration": lead.size * dt,
               **({"wave_height_target": float(height)} if height is not None else {})},
    )
    return conventions.annotate(ds)
