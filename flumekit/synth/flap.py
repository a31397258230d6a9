"""The virtual flume's flap channels: flap motion, PTO forces and torques, encoder and pressure.

The flap motion comes from a linear one-degree-of-freedom model of the Eq. (A1) type, applied
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
* K_p = 1.0e6 Pa s² rad⁻² and I_p = 2.4e4 Pa s² rad⁻¹ (a water column of about 3 m in a 12 mm
  line behind the 50 mm bore: ρ L (A/a) |m| ≈ 2.4e4): the chamber reaches 0.65-4.8 bar in
  compression and cavitates on the suction stroke for the larger heights.

From θ(t) the truth of the PTO follows from flumekit's own models, exactly as the analysis
assumes them: the rod kinematics of :mod:`flumekit.flap.geometry`, the chamber pressure of
Eq. (13) in the signed form with the cavitation clamp (true K_p, I_p), the modified LuGre
friction integrated on a grid ``friction_substeps`` times finer than the record with the exact
(band-limited) rod velocity, and the torques of Eq. (11)-(12). The hydrodynamic torque T_h of
the truth is *defined* by Eq. (11) from these, so that it is what a perfect analysis recovers;
the linear model's own excitation torque is returned as ``torque_excitation`` for reference.

Raw channels: encoder counts (wire shortening of Eq. (1) quantised with the campaign's
counts_per_metre, integers, zero at θ = 0) and the chamber gauge pressure with Gaussian sensor
noise of standard deviation 0.2 % of the rated output (5 bar by default: the chamber reaches
up to 4.8 bar, more than a 1 bar sensor could read).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np
import xarray as xr
from scipy import fft as sfft

from flumekit import conventions
from flumekit.campaign import Campaign
from flumekit.flap.encoder import counts_from_wire, wire_length
from flumekit.flap.friction import LuGre, friction_series
from flumekit.flap.geometry import rod_kinematics
from flumekit.flap.power import flow_rate, pto_power
from flumekit.flap.pressure import chamber_pressure_model, pressure_force
from flumekit.flap.torque import (friction_torque, gravity_torque, inertia_torque,
                                  pressure_torque)
from flumekit.waves.theory import G, wavenumber


@dataclass(frozen=True)
class FlapTruth:
    """Physical parameters of the virtual flap that the campaign metadata does not hold."""

    added_inertia: float = 120.0  # μ [kg m2]
    pto_damping: float = 500.0  # linear-equivalent PTO damping ν_pto [N m s]
    viscous_damping: float = 600.0  # linearised viscous losses ν_visc [N m s]
    excitation_phase: float = 0.0  # lag of the excitation torque behind η(x=0) [rad]
    pressure_loss_coefficient: float = 1.0e6  # K_p [Pa s2 rad-2]
    fluid_inertia: float = 2.4e4  # I_p [Pa s2 rad-1]
    pressure_rated_output: float = 5.0e5  # pressure sensor range [Pa]
    pressure_noise: float = 0.002  # noise std as a fraction of the rated output [-]
    friction_substeps: int = 10  # fine friction steps per record step
    rho: float = 1000.0  # water density [kg m-3]

    def __post_init__(self):
        for f in dataclasses.fields(self):
            v = getattr(self, f.name)
            if f.name == "excitation_phase":
                ok = np.isfinite(v)
            elif f.name in ("pressure_noise", "viscous_damping", "pto_damping", "fluid_inertia"):
                ok = np.isfinite(v) and v >= 0
            else:
                ok = np.isfinite(v) and v > 0
            if not ok:
                raise ValueError(f"FlapTruth.{f.name} = {v} is not allowed")
        if int(self.friction_substeps) != self.friction_substeps:
            raise ValueError("FlapTruth.friction_substeps must be an integer")


def excitation_coefficient(omega, depth: float, hinge_height: float, width: float,
                           rho: float = 1000.0, g: float = G) -> np.ndarray:
    """Excitation torque per unit incident amplitude X(ω) [N m m-1] of a 2-D reflecting flap.

    X = 2 ρ g w [(h − c) tanh(kh)/k − (cosh kh − cosh kc)/(k² cosh kh)], written without
    overflow for large kh; X(0) = ρ g w (h − c)² (long-wave limit).

    Parameters
    ----------
    omega : Angular frequency [rad s-1], ≥ 0.
    depth : Water depth h [m].
    hinge_height : Hinge height above the bed c [m], < h.
    width : Flap width w [m].
    """
    w = np.asarray(omega, dtype=float)
    d = depth - hinge_height
    out = np.full(w.shape, rho * g * width * d**2)
    pos = w > 0
    k = wavenumber(w[pos], depth, g)
    kh, kc = k * depth, k * hinge_height
    # cosh(kc)/cosh(kh) = e^{k(c-h)} (1 + e^{-2kc}) / (1 + e^{-2kh})
    ratio = np.exp(kc - kh) * (1 + np.exp(-2 * kc)) / (1 + np.exp(-2 * kh))
    out[pos] = 2 * rho * g * width * (d * np.tanh(kh) / k - (1.0 - ratio) / k**2)
    return out


def radiation_damping(omega, depth: float, hinge_height: float, width: float,
                      rho: float = 1000.0, g: float = G) -> np.ndarray:
    """Radiation damping ν(ω) = X² / (2 ρ g c_g w) [N m s] from the 2-D Haskind relation."""
    w = np.asarray(omega, dtype=float)
    x = excitation_coefficient(w, depth, hinge_height, width, rho, g)
    cg = np.full(w.shape, np.sqrt(g * depth))
    pos = w > 0
    k = wavenumber(w[pos], depth, g)
    y = 2 * k * depth
    cg[pos] = w[pos] / (2 * k) * (1 + 2 * y * np.exp(-y) / -np.expm1(-2 * y))
    return x**2 / (2 * rho * g * cg * width)


def _uniform(time: np.ndarray) -> float:
    if time.ndim != 1 or time.size < 4 or not np.all(np.isfinite(time)):
        raise ValueError("flap_record needs a finite 1-D time of at least 4 samples")
    dt = (time[-1] - time[0]) / (time.size - 1)
    if not dt > 0 or np.max(np.abs(np.diff(time) - dt)) > 1e-6 * dt + 1e-9:
        raise ValueError("flap_record needs uniformly sampled, increasing time")
    return dt


def flap_motion(time, eta_incident_at_flap, *, campaign: Campaign, truth: FlapTruth = FlapTruth(),
                upsample: int = 1) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """θ, θ̇, θ̈ and the excitation torque of the linear 1-DOF model (module notes).

    Parameters
    ----------
    time : Record times [s], uniform.
    eta_incident_at_flap : Incident surface elevation at x = 0 [m].
    campaign : Campaign (depth, flap inertia, width, hinge height, buoyancy stiffness).
    truth : Model parameters.
    upsample : Return the motion on a grid ``upsample`` times finer than ``time`` (band-limited
        interpolation), of (n − 1)·upsample + 1 points.

    Returns
    -------
    theta [rad], theta_dot [rad s-1], theta_ddot [rad s-2], torque_excitation [N m].
    """
    t = np.asarray(time, dtype=float)
    dt = _uniform(t)
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
    x = excitation_coefficient(omega, depth, flap.hinge_height, flap.width, truth.rho)
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


def flap_record(time, eta_incident_at_flap, *, period: float, campaign: Campaign,
                rng: np.random.Generator, truth: FlapTruth = FlapTruth(),
                height: float | None = None) -> xr.Dataset:
    """Raw flap channels and their truth for one run of the virtual flume.

    Parameters
    ----------
    time : Record times [s], uniform (100 Hz for the campaign's encoder and pressure sensor).
    eta_incident_at_flap : True incident surface elevation at the hinge line x = 0 [m].
    period : Wave period of the run [s] (recorded; the model itself is frequency dependent).
    campaign : Campaign metadata (flap, PTO, encoder, flume).
    rng : Random generator for the pressure sensor noise.
    truth : Parameters of the virtual flap (:class:`FlapTruth`).
    height : Target wave height of the run [m], recorded in the attributes if given.

    Returns
    -------
    xr.Dataset on ``time`` with the raw channels ``encoder_counts`` (int64) and
    ``chamber_pressure`` (noisy, gauge, Pa), and the truth: ``theta``, ``theta_dot``,
    ``theta_ddot``, ``wire_shortening``, rod kinematics, ``chamber_pressure_true``,
    ``cavitating``, forces, LuGre state, torques (resisting convention of
    :mod:`flumekit.flap.torque`), ``torque_excitation``, ``torque_hydrodynamic`` (Eq. 11),
    ``flow_rate``, ``power``; scalars K_p, I_p, μ, C, ν_pto and ν(2π/T).
    """
    t = np.asarray(time, dtype=float)
    dt = _uniform(t)
    if not (np.isfinite(period) and period > 0):
        raise ValueError(f"period must be > 0, got {period}")
    flap, pto, enc = campaign.flap, campaign.pto, campaign.encoder
    m = int(truth.friction_substeps)
    th_f, thd_f, thdd_f, exc_f = flap_motion(t, eta_incident_at_flap, campaign=campaign,
                                             truth=truth, upsample=m)
    theta, theta_dot, theta_ddot, t_exc = th_f[::m], thd_f[::m], thdd_f[::m], exc_f[::m]

    rod = rod_kinematics(theta, theta_dot, pto.bed_anchor, pto.flap_anchor)
    compression = -1 if np.median(rod.lever_arm) > 0 else 1
    p_true = chamber_pressure_model(theta_dot, theta_ddot, truth.pressure_loss_coefficient,
                                    truth.fluid_inertia,
                                    atmospheric_pressure=pto.atmospheric_pressure,
                                    vapour_pressure=pto.vapour_pressure,
                                    compression_sign=compression)
    cav = p_true <= pto.vapour_pressure - pto.atmospheric_pressure
    if pto.friction is not None:
        rod_fine = rod_kinematics(th_f, thd_f, pto.bed_anchor, pto.flap_anchor)
        f_fine, z_fine, h_fine = friction_series(rod_fine.velocity, dt / m,
                                                 LuGre.from_campaign(pto.friction))
        f_f, z_b, h_l = f_fine[::m], z_fine[::m], h_fine[::m]
    else:
        f_f = z_b = h_l = np.zeros_like(t)
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

    omega_run = 2 * np.pi / period
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
            "bristle_deflection": (T, z_b), "film_thickness_parameter": (T, h_l),
            "torque_pressure": (T, t_p), "torque_friction": (T, t_f),
            "torque_pto": (T, t_p + t_f), "torque_gravity": (T, t_g),
            "torque_inertia": (T, t_i), "torque_excitation": (T, t_exc),
            # Eq. (11) in Brito et al. 2020 defines the true hydrodynamic torque
            "torque_hydrodynamic": (T, t_i + t_g + t_p + t_f),
            "flow_rate": (T, q), "power": (T, pto_power(p_true, q)),
            "pressure_loss_coefficient": truth.pressure_loss_coefficient,
            "fluid_inertia": truth.fluid_inertia,
            "added_inertia": truth.added_inertia,
            "hydrostatic_stiffness": flap.buoyancy_stiffness,
            "pto_damping": truth.pto_damping,
            "radiation_damping": float(radiation_damping(
                np.array([omega_run]), campaign.flume.water_depth, flap.hinge_height,
                flap.width, truth.rho)[0]),
        },
        coords={"time": t, "wave_period": float(period)},
        attrs={"source": "flumekit.synth.flap: linear 1-DOF flap model + flumekit PTO models",
               **{f"truth_{k}": v for k, v in dataclasses.asdict(truth).items()},
               **({"wave_height_target": float(height)} if height is not None else {})},
    )
    return conventions.annotate(ds)
