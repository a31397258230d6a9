"""Per-run flap analysis: encoder and chamber pressure -> motion, PTO forces, torques and power.

Two pure functions that the pipeline's flap stage calls for each run, sharing the measured
chain (encoder → θ and its derivatives, rod kinematics, pressure and LuGre friction forces,
torques, T_h, flow and power): :func:`analyse_run` for a regular-wave run (quasi-steady window,
phase averages, capture factor) and :func:`analyse_irregular_run` for an irregular sea state
(mean power over the analysed span, motion statistics, capture width and its ratio).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import xarray as xr

from flumekit import conventions
from flumekit import signal as sig
from flumekit.campaign import PTO, Encoder, Flap
from flumekit.docstrings import filler
from flumekit.errors import InputError
from flumekit.flap.encoder import angle_from_wire, wire_from_counts
from flumekit.flap.friction import LuGre, friction_series
from flumekit.flap.geometry import rod_kinematics
from flumekit.flap.power import flow_rate, pto_power, window_mean
from flumekit.flap.pressure import chamber_pressure_model, fit_pressure_model, pressure_force
from flumekit.flap.summary import steady_window, summary, summary_scalars
from flumekit.flap.torque import (
    friction_torque,
    gravity_torque,
    hydrodynamic_torque,
    inertia_torque,
    pressure_torque,
)
from flumekit.performance import capture_width, capture_width_ratio, motion_statistics

#: docstring text that several functions of this module share
_doc = filler(
    measured_pressure=("chamber_pressure : array_like\n"
                       "    Measured gauge pressure in the cylinder chamber [Pa]."),
    cutoff=("cutoff : float\n"
            "    Cut-off of the low-pass applied to θ before differentiation [Hz]."),
    max_flagged_fraction=("max_flagged_fraction : float\n"
                          "    Largest fraction of encoder samples outside the domain of Eq. (1) "
                          "that may be\n"
                          "    interpolated."),
    zero_count=("zero_count : float\n"
                "    Encoder count at θ = 0."))

#: how far the waves' analysed span may end past the flap's record, which it then ends with
#: [s]: one step of a probe record sampled at 10 Hz or faster
SPAN_OVERHANG = 0.1

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


class _Measured(NamedTuple):
    """The measured chain of a run over its whole record (one home for both run kinds)."""

    time: np.ndarray
    sampling_rate: float
    series: dict  # name -> time series, in the order the product stores them
    compression: int  # sign of θ̇ that compresses the chamber (Eq. 13)


class Kinematics(NamedTuple):
    """The part of the measured chain that the encoder and the sampling alone determine.

    θ from the encoder (Eq. 1), its low-passed derivatives, the rod kinematics and the LuGre
    friction of the rod's motion: what a rerun that perturbs only the chamber pressure or the
    flap's inertia shares with the run (:func:`encoder_kinematics`).
    """

    counts: np.ndarray  # encoder counts [-]
    time: np.ndarray  # sample times [s]
    sampling_rate: float  # [Hz]
    wire: np.ndarray  # wire shortening [m]
    out_of_domain: np.ndarray  # samples outside the domain of Eq. (1)
    theta_raw: np.ndarray  # θ before the low-pass [rad]
    theta: np.ndarray  # [rad]
    theta_dot: np.ndarray  # [rad s-1]
    theta_ddot: np.ndarray  # [rad s-2]
    rod: object  # flumekit.flap.geometry.RodKinematics
    friction: tuple  # force [N], bristle deflection [m], film thickness [-]


def _sampling(time) -> tuple[np.ndarray, float]:
    t = np.asarray(time, dtype=float)
    return t, 1.0 / sig.uniform_step(t, "flap analysis", min_samples=16)


@_doc
def encoder_kinematics(time, encoder_counts, *, pto: PTO, encoder: Encoder,
                       cutoff: float = DEFAULT_CUTOFF, zero_count: float = 0.0,
                       max_flagged_fraction: float = 0.0) -> Kinematics:
    """Return the encoder's part of the measured chain: θ, its derivatives, rod and friction.

    What :func:`steady_measured` computes from the encoder and the sampling alone, before the
    chamber pressure and the flap's inertia enter: the reruns of an uncertainty propagation
    that perturb only those pass it back (``kinematics``) instead of recomputing it.

    Parameters
    ----------
    time : array_like
        Sample times [s], uniform.
    encoder_counts : array_like
        Wire-encoder counts [-].
    pto : PTO
        The PTO (anchors, LuGre friction or None).
    encoder : Encoder
        The wire encoder of Eq. (1).
    %(cutoff)s
    %(zero_count)s
    %(max_flagged_fraction)s

    Returns
    -------
    Kinematics
        θ [rad], θ̇ [rad s-1], θ̈ [rad s-2], the rod kinematics and the friction force [N]
        with its states, and the counts and times they were computed from.

    Raises
    ------
    flumekit.errors.InputError
        More encoder samples outside the domain of Eq. (1) than ``max_flagged_fraction``.

    %(references_brito2020)s, §2.3, Eq. (1), Appendix B.

    Examples
    --------
    >>> from flumekit.flap.analysis import encoder_kinematics
    >>> k = encoder_kinematics(t, counts, pto=c.pto, encoder=c.encoder)  # doctest: +SKIP
    >>> k.theta_dot.max()  # doctest: +SKIP
    """
    t, fs = _sampling(time)
    counts = np.asarray(encoder_counts)
    if counts.shape != t.shape:
        raise ValueError(f"flap analysis: time {t.shape} and encoder counts {counts.shape} "
                         "must have the same length")
    # Eq. (1): encoder -> wire -> angle
    wire = wire_from_counts(counts, encoder.counts_per_metre, zero_count)
    wa = angle_from_wire(wire, encoder.L5, encoder.L7)
    theta_raw = _fill_flagged(wa.theta, wa.out_of_domain, t, max_flagged_fraction)
    theta, theta_dot, theta_ddot = sig.smooth_derivatives(theta_raw, fs, cutoff)
    # PTO kinematics and friction
    rod = rod_kinematics(theta, theta_dot, pto.bed_anchor, pto.flap_anchor)
    if pto.friction is not None:
        friction = friction_series(rod.velocity, 1.0 / fs, LuGre.from_campaign(pto.friction))
    else:
        friction = (np.zeros_like(t),) * 3
    return Kinematics(counts, t, fs, wire, wa.out_of_domain, theta_raw, theta, theta_dot,
                      theta_ddot, rod, friction)


def _measured(time, encoder_counts, chamber_pressure, *, flap: Flap, pto: PTO,
              encoder: Encoder, cutoff: float, zero_count: float,
              max_flagged_fraction: float, kinematics: Kinematics | None = None) -> _Measured:
    t, fs = _sampling(time)
    counts = np.asarray(encoder_counts)
    p = np.asarray(chamber_pressure, dtype=float)
    if counts.shape != t.shape or p.shape != t.shape:
        raise ValueError(f"flap analysis: time {t.shape}, encoder counts {counts.shape} and "
                         f"chamber pressure {p.shape} must have the same length")
    if not np.all(np.isfinite(p)):
        raise InputError(None, f"{int((~np.isfinite(p)).sum())} chamber pressure samples are "
                         "not finite")
    k = kinematics
    if k is None:
        k = encoder_kinematics(t, counts, pto=pto, encoder=encoder, cutoff=cutoff,
                               zero_count=zero_count, max_flagged_fraction=max_flagged_fraction)
    # given, it must be of these counts and this sampling (and these times where it filled in)
    elif not (k.sampling_rate == fs and np.array_equal(k.counts, counts)
              and (not k.out_of_domain.any() or np.array_equal(k.time, t))):
        raise ValueError("flap analysis: the kinematics passed are of other encoder counts or "
                         "another sampling")
    theta, theta_ddot, rod = k.theta, k.theta_ddot, k.rod
    f_f, z_b, h_l = k.friction
    compression = -1 if np.median(rod.lever_arm) > 0 else 1  # θ̇ > 0 shortens the rod if m < 0
    f_p = pressure_force(p, pto.bore_area)
    t_p = pressure_torque(f_p, rod.lever_arm)
    t_f = friction_torque(f_f, rod.lever_arm)
    t_pto = t_p + t_f
    t_g = gravity_torque(theta, flap.buoyancy_stiffness)
    t_h = hydrodynamic_torque(theta, theta_ddot, t_pto, inertia=flap.inertia,
                              buoyancy_stiffness=flap.buoyancy_stiffness, torque_gravity=t_g)
    q = flow_rate(rod.velocity, pto.bore_area)
    w_out = pto_power(p, q)
    series = {
        "encoder_counts": counts, "wire_shortening": k.wire,
        "domain_flag": k.out_of_domain.astype(np.int8),
        "theta": theta, "theta_dot": k.theta_dot, "theta_ddot": theta_ddot,
        "theta_unfiltered": k.theta_raw, "rod_length": rod.length,
        "rod_velocity": rod.velocity, "beta": rod.beta,
        "lever_arm": rod.lever_arm, "chamber_pressure": p,
        "force_pressure": f_p, "force_friction": f_f,
        "bristle_deflection": z_b, "film_thickness_parameter": h_l,
        "torque_pressure": t_p, "torque_friction": t_f, "torque_pto": t_pto,
        "torque_gravity": t_g,
        "torque_inertia": inertia_torque(theta_ddot, flap.inertia),
        "torque_hydrodynamic": t_h, "flow_rate": q, "power": w_out}
    return _Measured(t, fs, series, compression)


def _fitted_pressure(m: _Measured, inside: np.ndarray, pto: PTO):
    """Eq. (13-14) fitted over the samples ``inside``, and the fitted model over the record."""
    s = m.series
    kw = dict(atmospheric_pressure=pto.atmospheric_pressure, vapour_pressure=pto.vapour_pressure,
              compression_sign=m.compression)
    fit = fit_pressure_model(s["chamber_pressure"][inside], s["theta_dot"][inside],
                             s["theta_ddot"][inside], **kw)
    p_fit = chamber_pressure_model(s["theta_dot"], s["theta_ddot"],
                                   fit.pressure_loss_coefficient, fit.fluid_inertia, **kw)
    cav = p_fit <= pto.vapour_pressure - pto.atmospheric_pressure
    t_p_fit = pressure_torque(pressure_force(p_fit, pto.bore_area), s["lever_arm"])
    return fit, p_fit, cav, t_p_fit


def _dataset(m: _Measured, fit, p_fit, cav, t_p_fit, *, pto: PTO, cutoff: float) -> xr.Dataset:
    """Assemble the time series and the pressure fit of a run as the product stores them."""
    s = m.series
    order = ["encoder_counts", "wire_shortening", "domain_flag", "theta", "theta_dot",
             "theta_ddot", "rod_length", "rod_velocity", "beta", "lever_arm",
             "chamber_pressure", "chamber_pressure_fitted", "cavitating", "force_pressure",
             "force_friction", "bristle_deflection", "film_thickness_parameter",
             "torque_pressure", "torque_pressure_fitted", "torque_friction", "torque_pto",
             "torque_gravity", "torque_inertia", "torque_hydrodynamic", "flow_rate", "power"]
    fitted = {"chamber_pressure_fitted": p_fit, "cavitating": cav.astype(np.int8),
              "torque_pressure_fitted": t_p_fit}
    T = ("time",)
    data = {n: (T, fitted[n] if n in fitted else s[n]) for n in order}
    data.update({
        "pressure_loss_coefficient": fit.pressure_loss_coefficient,
        "fluid_inertia": fit.fluid_inertia, "pressure_fit_r2": fit.r2,
        "domain_flagged_fraction": float(s["domain_flag"].astype(bool).mean())})
    return xr.Dataset(
        data, coords={"time": m.time},
        attrs={"derivative_cutoff_hz": float(cutoff), "derivative_filter":
               "zero-phase 4th-order Butterworth low-pass, central differences",
               "friction_model": "modified LuGre (Appendix B)" if pto.friction is not None
               else "none (no [pto.friction] in the campaign)",
               "torque_sign_convention": "T_h positive towards the beach; T_g, T_PTO, T_p, T_f "
               "resisting (positive when opposing theta > 0), Eq. (11)"},
    )


def _bounded(ds: xr.Dataset, fit) -> xr.Dataset:
    if fit.bounded:  # said in the product: Eq. (13) misses part of this PTO's pressure
        ds.attrs["pressure_fit_bounded"] = (
            "a coefficient of the Eq. (13) fit is held at its bound 0: the free least-squares "
            "fit gave a negative (unphysical) value, so the pressure lags the motion in a way "
            "Eq. (13) cannot represent")
    return ds


@_doc
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
    %(measured_pressure)s
    flap : Flap
        The flap (inertia, buoyancy stiffness C, width).
    pto : PTO
        The PTO (anchors, bore, atmospheric and vapour pressures, LuGre friction or None).
    encoder : Encoder
        The wire encoder of Eq. (1) (L5, L7, counts per metre).
    depth : float
        Water depth h [m] (for W_I, Eq. A2).
    period : float
        Wave period of the run [s]: the incident wave's measured period (the waves stage's
        ``measured_period``), with which W_I's group velocity is taken (Eq. A2); the
        quasi-steady window's cycle detection ignores crossings closer than half of it.
    incident_height : float
        Incident wave height at the flap from the wave separation [m]; used for
        W_I (Eq. A2) and C_f.
    cutoff : float
        Cut-off of the zero-phase 4th-order Butterworth low-pass applied to θ before
        differentiation [Hz].
    %(zero_count)s
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

    Raises
    ------
    flumekit.errors.InputError
        More encoder samples outside the domain of Eq. (1) than ``max_flagged_fraction``.
    ValueError
        A non-positive period or incident height, fewer than two quasi-steady cycles, or a
        pressure record the Eq. (13) fit cannot use.

    %(references_brito2020)s, §2.3, §2.5, §3.1-3.3, Eqs. (1), (11)-(14), (A2).

    Examples
    --------
    A run made from a known motion, θ = 0.2 sin(π t) for 40 s at 100 Hz: the encoder counts
    from Eq. (1), the chamber pressure from Eq. (13) with K_p = 2e5 Pa s2 rad-2 and
    I_p = 300 Pa s2 rad-1 (the flume's device, a PTO without friction). The analysis finds the
    motion's amplitude and period in the counts and fits back the K_p and I_p of the pressure:

    >>> import numpy as np
    >>> from flumekit.campaign import PTO, Encoder, Flap
    >>> from flumekit.flap.analysis import analyse_run
    >>> from flumekit.flap.encoder import counts_from_wire, wire_length
    >>> from flumekit.flap.pressure import chamber_pressure_model
    >>> flap = Flap(width=1.31, thickness=0.17, inertia=14.74, hinge_height=0.1,
    ...             buoyancy_stiffness=605.0)
    >>> pto = PTO(bed_anchor=(1.04, 0.0), flap_anchor=(0.09, 0.47), bore_diameter=0.05,
    ...           atmospheric_pressure=101325.0, vapour_pressure=2339.0)
    >>> encoder = Encoder(L5=1.53, L7=1.48, counts_per_metre=6000.0, sampling_rate=100.0)
    >>> t = np.arange(0.0, 40.0, 0.01)
    >>> theta = 0.2 * np.sin(np.pi * t)
    >>> wire = encoder.L7 - wire_length(theta, encoder.L5, encoder.L7)  # shortening
    >>> counts = counts_from_wire(wire, encoder.counts_per_metre)
    >>> pressure = chamber_pressure_model(0.2 * np.pi * np.cos(np.pi * t),
    ...                                   -0.2 * np.pi**2 * np.sin(np.pi * t), 2.0e5, 300.0)
    >>> ds = analyse_run(t, counts, pressure, flap=flap, pto=pto, encoder=encoder,
    ...                  depth=0.825, period=2.0, incident_height=0.1)
    >>> round(float(ds.theta_amplitude), 3), round(float(ds.measured_period), 3)
    (0.2, 2.0)
    >>> round(float(ds.pressure_loss_coefficient), -3), round(float(ds.fluid_inertia), -1)
    (200000.0, 300.0)
    >>> round(float(ds.pressure_fit_r2), 4), int(ds.steady_cycles)
    (1.0, 19)
    """
    m, win = steady_measured(time, encoder_counts, chamber_pressure, flap=flap, pto=pto,
                             encoder=encoder, period=period, cutoff=cutoff,
                             zero_count=zero_count, tolerance=tolerance,
                             max_flagged_fraction=max_flagged_fraction)
    t, s = m.time, m.series

    # pressure fit (Eqs. 13-14) inside the quasi-steady window
    inside = (t >= win.start) & (t <= win.end)
    fit, p_fit, cav, t_p_fit = _fitted_pressure(m, inside, pto)

    # phase averages, amplitudes, power capture over the window (§3.2, Eq. A2; Fig. 10)
    summ = summary(t, {n: s[n] for n in ("theta", "theta_dot", "power", "chamber_pressure",
                                        "torque_hydrodynamic")}, win,
                   period=period, incident_height=incident_height, depth=depth,
                   flap_width=flap.width, n_phase=n_phase,
                   ci95=("theta", "torque_hydrodynamic"),
                   theta_unfiltered=s["theta_unfiltered"])
    ds = _dataset(m, fit, p_fit, cav, t_p_fit, pto=pto, cutoff=cutoff)
    return _bounded(conventions.annotate(ds.merge(summ)), fit)


@_doc
def steady_measured(time, encoder_counts, chamber_pressure, *, flap: Flap, pto: PTO,
                    encoder: Encoder, period: float, cutoff: float = DEFAULT_CUTOFF,
                    zero_count: float = 0.0, tolerance: float = 0.02,
                    max_flagged_fraction: float = 0.0,
                    kinematics: Kinematics | None = None, chain: _Measured | None = None
                    ) -> tuple:
    """Return the measured chain of a regular run and the quasi-steady window of θ (§2.5).

    What :func:`analyse_run` and :func:`run_results` compute first; it depends neither on the
    depth nor on the incident height.

    Parameters
    ----------
    time, encoder_counts, chamber_pressure, flap, pto, encoder, period
        As in :func:`analyse_run` (time [s], counts [-], pressure [Pa], period [s]).
    %(cutoff)s
    %(zero_count)s
    tolerance : float
        Relative crest tolerance of the quasi-steady window [-].
    %(max_flagged_fraction)s
    kinematics : Kinematics, optional
        :func:`encoder_kinematics` of these times and counts with these ``pto``, ``encoder``,
        ``cutoff``, ``zero_count`` and ``max_flagged_fraction``, when the caller has it (the
        reruns that perturb only the pressure or the flap's inertia).
    chain : tuple, optional
        The measured chain (the first element of the result) of an earlier call on these same
        records and parameters, when the caller has it: the chain depends neither on the
        period nor on the tolerance, so only the window is searched (the reruns that change
        only the period).

    Returns
    -------
    tuple
        The measured chain (time [s], sampling rate [Hz], the series by name, the compression
        sign) and the window (:class:`flumekit.signal.SteadyWindow`).

    Raises
    ------
    flumekit.errors.InputError
        More encoder samples outside the domain of Eq. (1) than ``max_flagged_fraction``.
    ValueError
        A non-positive period, fewer than two quasi-steady cycles; ``kinematics`` of other
        counts or another sampling.
    """
    m = chain
    if m is None:
        m = _measured(time, encoder_counts, chamber_pressure, flap=flap, pto=pto,
                      encoder=encoder, cutoff=cutoff, zero_count=zero_count,
                      max_flagged_fraction=max_flagged_fraction, kinematics=kinematics)
    if not (np.isfinite(period) and period > 0):
        raise ValueError(f"period must be > 0, got {period}")
    return m, steady_window(m.series["theta"], m.time, period, tolerance)


@_doc
def run_results(time, encoder_counts, chamber_pressure, *, flap: Flap, pto: PTO,
                encoder: Encoder, depth: float, period: float, incident_height: float,
                cutoff: float = DEFAULT_CUTOFF, zero_count: float = 0.0,
                tolerance: float = 0.02, n_phase: int = 100,
                max_flagged_fraction: float = 0.0, measured: tuple | None = None
                ) -> dict[str, float]:
    """Return the scalar results of :func:`analyse_run` alone, as it computes them.

    The measured chain, the quasi-steady window and the amplitudes, mean power, W_I and C_f
    of :func:`flumekit.flap.summary.summary_scalars`, without what none of them reads (the
    time series dataset, the Eq. (13) pressure fit and the phase averages): the many reruns of
    an uncertainty propagation need these numbers only.

    Parameters
    ----------
    time, encoder_counts, chamber_pressure, flap, pto, encoder, depth, period, incident_height
        As in :func:`analyse_run`: time [s], counts [-], pressure [Pa], the flap, PTO and
        encoder, depth [m], period [s], incident height [m].
    cutoff, zero_count, tolerance, n_phase, max_flagged_fraction
        As in :func:`analyse_run`: cut-off [Hz], zero count [-], crest tolerance [-], phase
        points per cycle, largest interpolated fraction [-].
    measured : tuple, optional
        :func:`steady_measured` of these same records and parameters, when the caller has it
        (the reruns that change only the depth or the incident height).

    Returns
    -------
    dict of str to float
        ``theta_amplitude`` [rad], ``torque_amplitude`` [N m], ``mean_power`` [W],
        ``incident_power`` [W], ``capture_factor`` [-] and the window
        (:func:`flumekit.flap.summary.summary_scalars`), equal to those of
        :func:`analyse_run`.

    Raises
    ------
    flumekit.errors.InputError
        More encoder samples outside the domain of Eq. (1) than ``max_flagged_fraction``.
    ValueError
        A non-positive period or incident height, fewer than two quasi-steady cycles.

    %(references_brito2020)s, §2.3, §2.5, §3.2, Eq. (A2).

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.flap.analysis import run_results
    >>> r = run_results(t, counts, pressure, flap=c.flap, pto=c.pto,  # doctest: +SKIP
    ...                 encoder=c.encoder, depth=0.825, period=3.5, incident_height=0.25)
    >>> r["capture_factor"]  # doctest: +SKIP
    """
    if measured is None:
        measured = steady_measured(time, encoder_counts, chamber_pressure, flap=flap, pto=pto,
                                   encoder=encoder, period=period, cutoff=cutoff,
                                   zero_count=zero_count, tolerance=tolerance,
                                   max_flagged_fraction=max_flagged_fraction)
    m, win = measured
    return summary_scalars(m.time, m.series, win, period=period,
                           incident_height=incident_height, depth=depth,
                           flap_width=flap.width, n_phase=n_phase,
                           theta_unfiltered=m.series["theta_unfiltered"])


@_doc
def analyse_irregular_run(time, encoder_counts, chamber_pressure, *, flap: Flap, pto: PTO,
                          encoder: Encoder, analysis_start: float, analysis_end: float,
                          energy_flux: float, cutoff: float = DEFAULT_CUTOFF,
                          zero_count: float = 0.0,
                          max_flagged_fraction: float = 0.0) -> xr.Dataset:
    """Analyse one irregular-sea run's flap channels: mean power, motion statistics, capture.

    The measured chain of :func:`analyse_run` (Brito et al. 2020, §2.3, §3.1-3.3: θ from the
    encoder, its derivatives, the rod kinematics, the pressure and LuGre friction forces, the
    torques, T_h, the flow and the power W_out = P_int Q) over the whole record; over the span
    the wave separation analysed (after the wavemaker's ramp), the mean absorbed power P̄, the
    statistics of θ and T_h (:func:`flumekit.performance.motion_statistics`), the capture
    width P̄/J and the capture width ratio P̄/(J w). An irregular sea has no quasi-steady
    window and no phase: there are no phase averages and no capture factor C_f. The pressure
    model of Eq. (13) is fitted over the span (for the simulator; its R² says how well).

    Parameters
    ----------
    %(time_uniform)s
    encoder_counts : array_like
        Wire-encoder counts [-].
    %(measured_pressure)s
    flap : Flap
        The flap (inertia, buoyancy stiffness C, width w of the capture width ratio).
    pto : PTO
        The PTO (anchors, bore, pressures, LuGre friction or None).
    encoder : Encoder
        The wire encoder of Eq. (1).
    analysis_start, analysis_end : float
        The analysed span of the waves stage [s] (the same span gives J).
    energy_flux : float
        Spectral energy flux J = ρ g ∫ S_I(f) c_g(f, h) df of the incident wave at the flap
        over the span [W m-1] (the waves product's ``energy_flux``).
    %(cutoff)s
    %(zero_count)s
    %(max_flagged_fraction)s

    Returns
    -------
    xarray.Dataset
        The time series of :func:`analyse_run` (dim ``time``), and the scalars
        ``analysis_start``, ``analysis_end``, ``mean_power`` (over the span, trapezoidal rule),
        ``energy_flux``, ``capture_width``, ``capture_width_ratio``, the ``theta_*`` and
        ``torque_*`` statistics of :func:`flumekit.performance.motion_statistics` (T_h under
        the ``torque`` prefix), and the Eq. (13) fit K_p, I_p, R².

    Raises
    ------
    ValueError
        A span outside the record, a non-positive flux, a motion with fewer than three
        zero-crossing cycles in the span.

    References
    ----------
    Brito, M. et al. (2020). Experimental investigation of the flow field in the vicinity of an
    oscillating wave surge converter. J. Mar. Sci. Eng. 8.
    Babarit, A. (2015). A database of capture width ratio of wave energy converters. Renewable
    Energy 80, 610-628.
    IEC TS 62600-103:2018, Guidelines for the early stage development of wave energy
    converters.

    Examples
    --------
    >>> from flumekit.campaign import load_campaign  # doctest: +SKIP
    >>> c = load_campaign("raw/default")  # doctest: +SKIP
    >>> ds = analyse_irregular_run(t, counts, pressure, flap=c.flap, pto=c.pto,  # doctest: +SKIP
    ...                            encoder=c.encoder, analysis_start=40.0, analysis_end=640.0,
    ...                            energy_flux=24.5)
    >>> float(ds.capture_width_ratio)  # doctest: +SKIP
    """
    m = _measured(time, encoder_counts, chamber_pressure, flap=flap, pto=pto, encoder=encoder,
                  cutoff=cutoff, zero_count=zero_count,
                  max_flagged_fraction=max_flagged_fraction)
    t, s = m.time, m.series
    start, end = float(analysis_start), float(analysis_end)
    # the probes' last sample may lie up to one of their steps past the flap's last one
    # (records of one duration sampled at 25 and 100 Hz): the span ends with the record
    if 0 < end - t[-1] <= SPAN_OVERHANG:
        end = float(t[-1])
    mean_w = window_mean(s["power"], t, start, end)  # ValueError for a span outside the record
    inside = (t >= start) & (t <= end)
    fit, p_fit, cav, t_p_fit = _fitted_pressure(m, inside, pto)
    stats = xr.merge([motion_statistics(s["theta"][inside], time=t[inside], name="theta"),
                      motion_statistics(s["torque_hydrodynamic"][inside], time=t[inside],
                                        name="torque")])
    ds = _dataset(m, fit, p_fit, cav, t_p_fit, pto=pto, cutoff=cutoff).merge(stats)
    ds["analysis_start"] = start
    ds["analysis_end"] = end
    ds["mean_power"] = ((), mean_w, {"long_name": "mean PTO power over the analysed span"})
    ds["energy_flux"] = ((), float(energy_flux), {
        "long_name": "spectral energy flux of the incident wave per unit crest width, "
                     "rho g int S_I(f) c_g(f, h) df"})
    ds["capture_width"] = float(capture_width(mean_w, energy_flux))
    ds["capture_width_ratio"] = float(capture_width_ratio(mean_w, energy_flux, flap.width))
    ds.attrs["flap_width"] = float(flap.width)
    return _bounded(conventions.annotate(ds), fit)
