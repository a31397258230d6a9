"""Per-run flap analysis: encoder and chamber pressure -> motion, PTO forces, torques and power.

One pure function, :func:`analyse_run`, that the pipeline's flap stage calls for each run.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from flumekit import conventions
from flumekit import signal as sig
from flumekit.campaign import PTO, Encoder, Flap
from flumekit.errors import InputError
from flumekit.flap.encoder import angle_from_wire, wire_from_counts
from flumekit.flap.friction import LuGre, friction_series
from flumekit.flap.geometry import rod_kinematics
from flumekit.flap.power import flow_rate, pto_power
from flumekit.flap.pressure import chamber_pressure_model, fit_pressure_model, pressure_force
from flumekit.flap.summary import steady_window, summary
from flumekit.flap.torque import (
    friction_torque,
    gravity_torque,
    hydrodynamic_torque,
    inertia_torque,
    pressure_torque,
)

#: default cut-off of the zero-phase 4th-order Butterworth low-pass applied to θ before
#: differentiation [Hz]. It passes the first 8 harmonics of the shortest period (2 s) with at
#: most 0.4 % loss (forward-backward |H|² = 1/(1 + (f/fc)^8)), while the quantisation noise of
#: θ̈ grows as fc^2.5. Against the virtual flume (flumekit.bench.flap, T = 2 and 3.5 s): θ̇
#: within 0.02 % and θ̈ within 0.13-0.19 % RMS of their amplitudes; 2-3 Hz would be marginally
#: better for these linear motions, 12-20 Hz lets the quantisation noise through (θ̈ 2-7 %).
DEFAULT_CUTOFF = 4.0


def _fill_flagged(theta: np.ndarray, flag: np.ndarray, time: np.ndarray,
                  max_fraction: float) -> np.ndarray:
    n_bad = int(flag.sum())
    if n_bad == 0:
        return theta
    frac = n_bad / flag.size
    if frac > max_fraction:
        first = float(time[np.argmax(flag)])
        raise InputError(None, f"{n_bad} encoder samples ({frac:.2%}, first at t = {first:.3f} s) "
                         "lie outside the domain of Eq. (1): the wire length is impossible for "
                         "the encoder geometry (check L5, L7, counts_per_metre and the zero "
                         f"count); at most {max_fraction:.2%} may be interpolated")
    good = ~flag
    out = theta.copy()
    out[flag] = np.interp(time[flag], time[good], theta[good])
    return out


def analyse_run(time, encoder_counts, chamber_pressure, *, flap: Flap, pto: PTO,
                encoder: Encoder, depth: float, period: float,
                incident_height: float, cutoff: float = DEFAULT_CUTOFF,
                zero_count: float = 0.0, tolerance: float = 0.02, n_phase: int = 100,
                max_flagged_fraction: float = 0.0) -> xr.Dataset:
    """Analyse one run's flap channels (Brito et al. 2020, §2.3, §3.1-3.3).

    Parameters
    ----------
    time : array_like
        Sample times [s], uniform (100 Hz in the campaign).
    encoder_counts : array_like
        Wire-encoder counts, increasing as the wire is reeled in [-].
    chamber_pressure : array_like
        Measured gauge pressure in the cylinder chamber [Pa].
    flap : Flap
        The flap (inertia, buoyancy stiffness C, width).
    pto : PTO
        The PTO (anchors, bore, atmospheric and vapour pressures, LuGre friction or None).
    encoder : Encoder
        The wire encoder of Eq. (1) (L5, L7, counts per metre).
    depth : float
        Water depth h [m] (for W_I, Eq. A2).
    period : float
        Wave period of the run [s] (the quasi-steady window's cycle detection ignores
        crossings closer than half of it).
    incident_height : float
        Incident wave height at the flap from the wave separation [m]; used for
        W_I (Eq. A2) and C_f.
    cutoff : float
        Cut-off of the zero-phase 4th-order Butterworth low-pass applied to θ before
        differentiation [Hz].
    zero_count : float
        Encoder count at θ = 0.
    tolerance : float
        Relative crest tolerance of the quasi-steady window (2 %, §2.5).
    n_phase : int
        Phase points per cycle of the phase averages.
    max_flagged_fraction : float
        Largest fraction of encoder samples outside the domain of Eq. (1)
        that may be replaced by interpolation; more is an :class:`InputError`.

    Returns
    -------
    xarray.Dataset
        Dims ``time`` and ``phase``: θ, θ̇, θ̈, rod kinematics, measured and fitted pressure,
        forces, torques (Eq. 11-12, resisting-torque convention of
        :mod:`flumekit.flap.torque`), T_h, flow and power time series; phase averages over
        the quasi-steady window of θ; scalars K_p, I_p, R², θ and T_h amplitudes, mean power,
        W_I, C_f and the window. Every name is in :mod:`flumekit.conventions`.
    """
    t = np.asarray(time, dtype=float)
    fs = 1.0 / sig.uniform_step(t, "flap analysis", min_samples=16)
    counts = np.asarray(encoder_counts)
    p = np.asarray(chamber_pressure, dtype=float)
    if counts.shape != t.shape or p.shape != t.shape:
        raise ValueError(f"flap analysis: time {t.shape}, encoder counts {counts.shape} and "
                         f"chamber pressure {p.shape} must have the same length")
    if not np.all(np.isfinite(p)):
        raise InputError(None, f"{int((~np.isfinite(p)).sum())} chamber pressure samples are "
                         "not finite")
    if not (np.isfinite(period) and period > 0):
        raise ValueError(f"period must be > 0, got {period}")
    # Eq. (1): encoder -> wire -> angle
    wire = wire_from_counts(counts, encoder.counts_per_metre, zero_count)
    wa = angle_from_wire(wire, encoder.L5, encoder.L7)
    theta_raw = _fill_flagged(wa.theta, wa.out_of_domain, t, max_flagged_fraction)
    theta, theta_dot, theta_ddot = sig.smooth_derivatives(theta_raw, fs, cutoff)

    # PTO kinematics and forces
    rod = rod_kinematics(theta, theta_dot, pto.bed_anchor, pto.flap_anchor)
    compression = -1 if np.median(rod.lever_arm) > 0 else 1  # θ̇ > 0 shortens the rod if m < 0
    f_p = pressure_force(p, pto.bore_area)
    if pto.friction is not None:
        f_f, z_b, h_l = friction_series(rod.velocity, 1.0 / fs, LuGre.from_campaign(pto.friction))
    else:
        f_f = z_b = h_l = np.zeros_like(t)
    t_p = pressure_torque(f_p, rod.lever_arm)
    t_f = friction_torque(f_f, rod.lever_arm)
    t_pto = t_p + t_f
    t_h = hydrodynamic_torque(theta, theta_ddot, t_pto, inertia=flap.inertia,
                              buoyancy_stiffness=flap.buoyancy_stiffness)
    q = flow_rate(rod.velocity, pto.bore_area)
    w_out = pto_power(p, q)

    # quasi-steady window on θ (§2.5), pressure fit (Eqs. 13-14) inside it
    win = steady_window(theta, t, period, tolerance)
    inside = (t >= win.start) & (t <= win.end)
    fit = fit_pressure_model(p[inside], theta_dot[inside], theta_ddot[inside],
                             atmospheric_pressure=pto.atmospheric_pressure,
                             vapour_pressure=pto.vapour_pressure, compression_sign=compression)
    kw = dict(atmospheric_pressure=pto.atmospheric_pressure, vapour_pressure=pto.vapour_pressure,
              compression_sign=compression)
    p_fit = chamber_pressure_model(theta_dot, theta_ddot, fit.pressure_loss_coefficient,
                                   fit.fluid_inertia, **kw)
    cav = p_fit <= pto.vapour_pressure - pto.atmospheric_pressure
    t_p_fit = pressure_torque(pressure_force(p_fit, pto.bore_area), rod.lever_arm)

    # phase averages, amplitudes, power capture over the window (§3.2, Eq. A2; Fig. 10)
    summ = summary(t, {"theta": theta, "theta_dot": theta_dot, "power": w_out,
                       "chamber_pressure": p, "torque_hydrodynamic": t_h}, win,
                   period=period, incident_height=incident_height, depth=depth,
                   flap_width=flap.width, n_phase=n_phase,
                   ci95=("theta", "torque_hydrodynamic"))

    T = ("time",)
    ds = xr.Dataset(
        {
            "encoder_counts": (T, counts),
            "wire_shortening": (T, wire),
            "domain_flag": (T, wa.out_of_domain.astype(np.int8)),
            "theta": (T, theta), "theta_dot": (T, theta_dot), "theta_ddot": (T, theta_ddot),
            "rod_length": (T, rod.length), "rod_velocity": (T, rod.velocity),
            "beta": (T, rod.beta), "lever_arm": (T, rod.lever_arm),
            "chamber_pressure": (T, p), "chamber_pressure_fitted": (T, p_fit),
            "cavitating": (T, cav.astype(np.int8)),
            "force_pressure": (T, f_p), "force_friction": (T, f_f),
            "bristle_deflection": (T, z_b), "film_thickness_parameter": (T, h_l),
            "torque_pressure": (T, t_p), "torque_pressure_fitted": (T, t_p_fit),
            "torque_friction": (T, t_f), "torque_pto": (T, t_pto),
            "torque_gravity": (T, gravity_torque(theta, flap.buoyancy_stiffness)),
            "torque_inertia": (T, inertia_torque(theta_ddot, flap.inertia)),
            "torque_hydrodynamic": (T, t_h), "flow_rate": (T, q), "power": (T, w_out),
            "pressure_loss_coefficient": fit.pressure_loss_coefficient,
            "fluid_inertia": fit.fluid_inertia, "pressure_fit_r2": fit.r2,
            "domain_flagged_fraction": float(wa.out_of_domain.mean()),
        },
        coords={"time": t},
        attrs={"derivative_cutoff_hz": float(cutoff), "derivative_filter":
               "zero-phase 4th-order Butterworth low-pass, central differences",
               "friction_model": "modified LuGre (Appendix B)" if pto.friction is not None
               else "none (no [pto.friction] in the campaign)",
               "torque_sign_convention": "T_h positive towards the beach; T_g, T_PTO, T_p, T_f "
               "resisting (positive when opposing theta > 0), Eq. (11)"},
    )
    ds = conventions.annotate(ds.merge(summ))
    if fit.bounded:  # said in the product: Eq. (13) misses part of this PTO's pressure
        ds.attrs["pressure_fit_bounded"] = (
            "a coefficient of the Eq. (13) fit is held at its bound 0: the free least-squares "
            "fit gave a negative (unphysical) value, so the pressure lags the motion in a way "
            "Eq. (13) cannot represent")
    return ds
