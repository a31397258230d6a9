"""Per-run summary of the flap, the same for a measured and a simulated run.

The comparison sets the simulated run beside the measured one
(:func:`flumekit.flap.analysis.analyse_run`) and the linear model: both are reduced by
:func:`summary` to the same quantities, computed the same way (Brito et al. 2020, §2.5-§3.3):
the quasi-steady window of θ (crests within 2 % of the amplitude scale), amplitudes as half the
difference of the mean per-cycle maximum and minimum (Fig. 8), the mean PTO power over the
window, W_I of Eq. (A2) from the incident height, C_f = W̄_out / W_I, and phase averages over
the window with cycles starting at a zero up-crossing of θ (Fig. 10).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from flumekit import conventions
from flumekit import signal as sig
from flumekit.flap.power import capture_factor, incident_power, window_mean


def steady_window(theta, time, period: float, tolerance: float = 0.02) -> sig.SteadyWindow:
    """Quasi-steady window of the flap angle (Brito et al. 2020, §2.5).

    Crests within ``tolerance`` of the amplitude scale (:func:`flumekit.signal.
    quasi_steady_window`), cycle crossings closer than half the wave ``period`` [s] ignored;
    about the median of θ if it leans so far to one side that its zero up-crossings give no
    steady cycles (:func:`flumekit.signal.steady_window_or_centred`); at least two cycles, else
    ``ValueError``.
    """
    win = sig.steady_window_or_centred(theta, time, tolerance=tolerance,
                                       min_period=0.5 * period)
    if win.n_cycles < 2:
        raise ValueError("the run has fewer than two quasi-steady cycles")
    return win


def summary(time, series, window: sig.SteadyWindow, *, period: float, incident_height: float,
            depth: float, flap_width: float, n_phase: int = 100,
            ci95: tuple[str, ...] = ()) -> xr.Dataset:
    """Phase averages, amplitudes, mean power, W_I and C_f of a run over its steady window.

    The one summary of a flap run, measured (:func:`flumekit.flap.analysis.analyse_run`) or
    simulated (:func:`summarise_run`).

    Parameters
    ----------
    time : Sample times [s], uniform.
    series : ``{name: values}`` over ``time``, with at least ``theta`` [rad], ``power`` [W] and
        ``torque_hydrodynamic`` [N m]; each gets ``<name>_phase_mean``.
    window : The steady window (:func:`steady_window`); phase averages start at its first
        zero up-crossing of θ (t/T = 0, Fig. 10).
    period : Wave period T of the run [s].
    incident_height : Incident wave height H at the flap [m] (separation stage), > 0.
    depth : Water depth h [m].
    flap_width : Flap width L [m] (Eq. A2).
    n_phase : Phase points per cycle.
    ci95 : Names of ``series`` that also get ``<name>_phase_ci95``.

    Returns
    -------
    Dataset over ``phase`` with the phase averages and the scalars ``theta_amplitude``,
    ``torque_amplitude`` (half the difference of the mean per-cycle maximum and minimum,
    Fig. 8), ``mean_power`` (over the window), ``incident_height``, ``incident_power`` (W_I,
    Eq. A2), ``capture_factor`` (C_f = W̄_out / W_I, §3.2), ``steady_start``, ``steady_end``,
    ``measured_period``, ``steady_cycles``.

    Raises
    ------
    ValueError : a non-positive or non-finite incident height: without an incident wave there
        is no capture factor, and a zero height means the separation failed.
    """
    if not (np.isfinite(incident_height) and incident_height > 0):
        raise ValueError(f"incident height must be > 0, got {incident_height}")
    t = np.asarray(time, dtype=float)
    cycles = (window.period, window.start, window.n_cycles)
    pa = {n: sig.phase_average(x, t, *cycles, n_phase=n_phase) for n, x in series.items()}
    mean_w = window_mean(series["power"], t, window.start, window.end)
    w_i = float(incident_power(incident_height, period, depth, flap_width))
    data = {f"{n}_phase_mean": ("phase", a.mean) for n, a in pa.items()}
    data.update({f"{n}_phase_ci95": ("phase", pa[n].ci95) for n in ci95})
    data.update({
        "theta_amplitude": sig.cycle_amplitude(series["theta"], t, *cycles, n_phase),
        "torque_amplitude": sig.cycle_amplitude(series["torque_hydrodynamic"], t, *cycles,
                                                n_phase),
        "mean_power": mean_w, "incident_height": float(incident_height),
        "incident_power": w_i, "capture_factor": float(capture_factor(mean_w, w_i)),
        "steady_start": window.start, "steady_end": window.end,
        "measured_period": window.period, "steady_cycles": window.n_cycles})
    return xr.Dataset(data, coords={"phase": pa["theta"].phase, "wave_period": float(period)})


def summarise_run(sim: xr.Dataset, *, period: float, incident_height: float, depth: float,
                  flap_width: float, tolerance: float = 0.02, n_phase: int = 100) -> xr.Dataset:
    """:func:`summary` of a simulated run, in the names of the experimental flap analysis.

    Parameters
    ----------
    sim : Output of :func:`flumekit.flap.simulator.simulate_run` (or ``simulate``).
    period : Wave period T of the run [s].
    incident_height : Incident wave height H at the flap [m] (from the separation), for W_I.
    depth : Water depth h [m].
    flap_width : Flap width L [m] (Eq. A2).
    tolerance : Crest tolerance of the quasi-steady window (2 %, §2.5).
    n_phase : Phase points per cycle.

    Returns
    -------
    :func:`summary` of ``theta``, ``theta_dot``, ``power``, ``torque_hydrodynamic`` (and
    ``chamber_pressure`` for the hydraulic PTO), with the simulator's scalar attributes.
    """
    t = sim["time"].values
    win = steady_window(sim["theta"].values, t, period, tolerance)
    names = ["theta", "theta_dot", "power", "torque_hydrodynamic"]
    if "chamber_pressure" in sim:
        names.append("chamber_pressure")
    out = summary(t, {n: sim[n].values for n in names}, win, period=period,
                  incident_height=incident_height, depth=depth, flap_width=flap_width,
                  n_phase=n_phase)
    out.attrs = {"source": "flumekit.flap.summary",
                 **{k: v for k, v in sim.attrs.items() if isinstance(v, (int, float, str))}}
    return conventions.annotate(out)
