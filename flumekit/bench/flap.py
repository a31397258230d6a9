"""Flap benchmarks: run time against error for the derivative filter and the LuGre step.

1. Cut-off of the zero-phase low-pass applied to the encoder angle before differentiation:
   errors of θ, θ̇, θ̈ and T_h of :func:`flumekit.flap.analyse_run` against the virtual flume's
   truth (quantised encoder, 1 kPa pressure noise), and the run time.
2. Step of the modified LuGre integrator: force error against a 1e-5 s reference for a
   flap-like rod velocity (three harmonics, stick-slip at every reversal), steps per second.

Run ``python -m flumekit.bench.flap`` (``--quick`` for a short version).
"""

from __future__ import annotations

import shutil
import sys
import tempfile
import time as _time
from importlib import resources
from pathlib import Path

import numpy as np

from flumekit.campaign import Campaign, load_campaign
from flumekit.flap.analysis import analyse_run
from flumekit.flap.friction import LuGre, friction_series
from flumekit.synth.flap import flap_record
from flumekit.waves.theory import stokes2_coefficient, wavenumber


def _default_campaign() -> Campaign:
    with tempfile.TemporaryDirectory() as tmp:
        src = resources.files("flumekit.data").joinpath("default_campaign.toml")
        with resources.as_file(src) as path:
            shutil.copy(path, Path(tmp) / "campaign.toml")
        return load_campaign(tmp)


def _wave(t: np.ndarray, period: float, height: float, depth: float) -> np.ndarray:
    """Second-order Stokes wave at x = 0 with a half-cosine ramp over 8 periods from t = 5 s."""
    w = 2 * np.pi / period
    k = float(wavenumber(w, depth))
    a = height / 2
    env = 0.5 - 0.5 * np.cos(np.pi * np.clip((t - 5.0) / (8 * period), 0, 1))
    ph = w * (t - 5.0)
    return env * (a * np.cos(ph) + float(stokes2_coefficient(k, depth)) * k * a**2 * np.cos(2 * ph))


def _rms(x) -> float:
    return float(np.sqrt(np.mean(np.square(x))))


def derivative_table(campaign: Campaign, cutoffs, cases, n_waves: int) -> str:
    """Return the errors and run time of the flap analysis against the derivative filter's cut-off.

    Each case (T, H) is synthesised by the virtual flume (quantised encoder, pressure noise) and
    analysed by :func:`flumekit.flap.analyse_run` at every cut-off; errors are RMS away from
    the record ends (the filter's edge effects), relative to the truth's amplitude.

    Parameters
    ----------
    campaign : flumekit.campaign.Campaign
        The campaign (flap, PTO, encoder, water depth).
    cutoffs : sequence of float
        Low-pass cut-off frequencies [Hz].
    cases : sequence of tuple of float
        (period [s], height [m]) of each wave.
    n_waves : int
        Waves per record.

    Returns
    -------
    str
        The table: errors of θ [deg], θ̇, θ̈, T_h [% of amplitude], K_p and I_p [%], time [ms].
    """
    lines = [f"{'T [s]':>5} {'H [m]':>5} {'cutoff':>6} {'theta':>9} {'theta_dot':>9} "
             f"{'theta_ddot':>10} {'T_h':>7} {'K_p':>7} {'I_p':>7} {'time':>7}",
             f"{'':>5} {'':>5} {'[Hz]':>6} {'[deg]':>9} {'[% amp]':>9} {'[% amp]':>10} "
             f"{'[%amp]':>7} {'[%]':>7} {'[%]':>7} {'[ms]':>7}"]
    for period, height in cases:
        t = np.arange(int((5 + n_waves * period) * 100)) / 100.0
        truth = flap_record(t, _wave(t, period, height, campaign.flume.water_depth),
                            period=period, campaign=campaign, rng=np.random.default_rng(1))
        inner = slice(300, -300)  # errors away from the record ends (filter edge effects)
        # once per process, untimed: imports and the compiled kernels loaded from their cache
        analyse_run(t, truth.encoder_counts.values, truth.chamber_pressure.values,
                    flap=campaign.flap, pto=campaign.pto, encoder=campaign.encoder,
                    depth=campaign.flume.water_depth, period=period, incident_height=height,
                    cutoff=cutoffs[0])
        for fc in cutoffs:
            t0 = _time.perf_counter()
            ds = analyse_run(t, truth.encoder_counts.values, truth.chamber_pressure.values,
                             flap=campaign.flap, pto=campaign.pto, encoder=campaign.encoder,
                             depth=campaign.flume.water_depth, period=period,
                             incident_height=height,
                             cutoff=fc)
            el = _time.perf_counter() - t0

            def rel(name, truth=truth, ds=ds, inner=inner):
                ref = truth[name].values
                return 100 * _rms((ds[name].values - ref)[inner]) / np.max(np.abs(ref))

            th = np.degrees(_rms((ds.theta.values - truth.theta.values)[inner]))
            kp = 100 * (float(ds.pressure_loss_coefficient)
                        / float(truth.pressure_loss_coefficient) - 1)
            ip = 100 * (float(ds.fluid_inertia) / float(truth.fluid_inertia) - 1)
            lines.append(f"{period:5.2f} {height:5.3f} {fc:6.1f} {th:9.5f} {rel('theta_dot'):9.4f} "
                         f"{rel('theta_ddot'):10.3f} {rel('torque_hydrodynamic'):7.3f} "
                         f"{kp:7.3f} {ip:7.3f} {1e3 * el:7.1f}")
    return "\n".join(lines)


def friction_table(model: LuGre, steps, duration: float) -> str:
    """Return the force error of the LuGre integrator against a 1e-5 s reference.

    At the coarsest step's instants, for a flap-like rod velocity (three harmonics, stick-slip
    at every reversal) of two amplitudes.

    Parameters
    ----------
    model : flumekit.flap.friction.LuGre
        The friction model.
    steps : sequence of float
        Time steps [s]; the coarsest must be a multiple of the others.
    duration : float
        Duration of the velocity record [s].

    Returns
    -------
    str
        The table: maximum and RMS error [% of amplitude], time [ms], steps per second.
    """
    w = 2 * np.pi / 3.5

    def velocity(t, amp):
        return amp * (np.sin(w * t) + 0.25 * np.sin(2 * w * t + 0.7) + 0.1 * np.sin(3 * w * t))

    lines = [f"{'v_max':>6} {'dt':>8} {'steps':>8} {'max err':>8} {'rms err':>8} {'time':>8} "
             f"{'steps/s':>9}",
             f"{'[m/s]':>6} {'[s]':>8} {'':>8} {'[% amp]':>8} {'[% amp]':>8} {'[ms]':>8} {'':>9}"]
    coarse_dt, ref_dt = max(steps), 1e-5
    for amp in (0.16, 0.03):
        m_ref = int(round(coarse_dt / ref_dt))
        t_ref = np.arange(int(round(duration / ref_dt)) + 1) * ref_dt
        ref = friction_series(velocity(t_ref, amp), ref_dt, model)[0][::m_ref]
        scale = np.max(np.abs(ref))
        for dt in steps:
            m = int(round(coarse_dt / dt))
            t = np.arange(int(round(duration / dt)) + 1) * dt
            v = velocity(t, amp)
            t0 = _time.perf_counter()
            f, _, _ = friction_series(v, dt, model)
            el = _time.perf_counter() - t0
            err = f[::m] - ref
            lines.append(f"{amp:6.2f} {dt:8.0e} {t.size:8d} "
                         f"{100 * np.max(np.abs(err)) / scale:8.3f} {100 * _rms(err) / scale:8.4f} "
                         f"{1e3 * el:8.1f} {t.size / el:9.2e}")
    return "\n".join(lines)


def run(quick: bool = False) -> str:
    """Run both benchmarks and return the printed tables.

    Parameters
    ----------
    quick : bool
        A short version (fewer cut-offs, cases and steps).

    Returns
    -------
    str
        The printed report.
    """
    campaign = _default_campaign()
    model = LuGre.from_campaign(campaign.pto.friction)
    if quick:
        cutoffs, cases, n_waves = (2.0, 4.0, 8.0), ((2.0, 0.3),), 30
        steps, duration = (0.02, 0.01, 0.001), 4.0
    else:
        cutoffs = (1.5, 2.0, 3.0, 4.0, 6.0, 8.0, 12.0, 20.0)
        cases, n_waves = ((2.0, 0.3), (3.5, 0.25)), 60
        steps, duration = (0.02, 0.01, 0.005, 0.002, 0.001, 0.0001), 7.0
    out = ["Derivative filter: zero-phase 4th-order Butterworth on theta, central differences;",
           "errors of analyse_run against the virtual-flume truth (RMS, % of the truth's",
           "amplitude; K_p, I_p relative error; time = whole analyse_run, after a first untimed",
           "call that pays the process's one-off imports and kernel loading)",
           derivative_table(campaign, cutoffs, cases, n_waves), "",
           "Modified LuGre integrator (exact frozen-velocity steps, split at reversals): force",
           "error against a 1e-5 s reference at the coarsest step's instants, default campaign",
           friction_table(model, steps, duration)]
    return "\n".join(out)


if __name__ == "__main__":
    print(run(quick="--quick" in sys.argv[1:]))
