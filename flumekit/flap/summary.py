"""Per-run summary of the flap, the same for a measured and a simulated run.

The comparison sets the simulated run beside the measured one
(:func:`flumekit.flap.analysis.analyse_run`) and the linear model: both are reduced by
:func:`summary` to the same quantities, computed the same way (Brito et al. 2020, §2.5-§3.3):
the quasi-steady window of θ (crests within 2 % of the amplitude scale), amplitudes as half the
difference of the mean per-cycle maximum and minimum (Fig. 8), the mean PTO power over the
window, W_I of Eq. (A2) from the incident height, C_f = W̄_out / W_I, and phase averages over
the window with cycles starting at a zero up-crossing of θ (Fig. 10).

%(references_brito2020)s.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from flumekit import conventions
from flumekit import signal as sig
from flumekit.docstrings import fill, filler
from flumekit.flap.power import capture_factor, incident_power, window_mean

#: docstring text that several functions of this module share
_doc = filler(
    flap_width_a2=("flap_width : float\n"
                   "    Flap width L [m] (Eq. A2)."),
    n_phase=("n_phase : int, optional\n"
             "    Phase points per cycle."),
    run_period=("period : float\n"
                "    Wave period T of the run [s]."))

__doc__ = fill(__doc__)


@_doc
def steady_window(theta, time, period: float, tolerance: float = 0.02) -> sig.SteadyWindow:
    """Find the quasi-steady window of the flap angle (Brito et al. 2020, §2.5).

    Crests within ``tolerance`` of the amplitude scale
    (:func:`flumekit.signal.quasi_steady_window`), cycle crossings closer than half the wave
    ``period`` ignored; about the median of θ if it leans so far to one side that its zero
    up-crossings give no steady cycles (:func:`flumekit.signal.steady_window_or_centred`).

    Parameters
    ----------
    theta : array_like
        Flap angle θ [rad].
    %(time_uniform)s
    %(period)s
    tolerance : float, optional
        Crest tolerance as a fraction of the amplitude scale [-].

    Returns
    -------
    flumekit.signal.SteadyWindow
        Start and end [s], measured period [s] and number of cycles of the window.

    Raises
    ------
    ValueError
        Fewer than two quasi-steady cycles.

    %(references_brito2020)s, §2.5.

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.flap.summary import steady_window
    >>> t = np.arange(0.0, 40.0, 0.01)
    >>> win = steady_window(0.1 * np.sin(np.pi * t), t, period=2.0)
    >>> round(win.period, 3)
    2.0
    """
    win = sig.steady_window_or_centred(theta, time, tolerance=tolerance,
                                       min_period=0.5 * period)
    if win.n_cycles < 2:
        raise ValueError("the run has fewer than two quasi-steady cycles")
    return win


@_doc
def summary(time, series, window: sig.SteadyWindow, *, period: float, incident_height: float,
            depth: float, flap_width: float, n_phase: int = 100,
            ci95: tuple[str, ...] = (), theta_unfiltered=None) -> xr.Dataset:
    """Summarise a run over its steady window: phase averages, amplitudes, power, W_I, C_f.

    The one summary of a flap run, measured (:func:`flumekit.flap.analysis.analyse_run`) or
    simulated (:func:`summarise_run`).

    Parameters
    ----------
    %(time_uniform)s
    series : dict of str to array_like
        ``{name: values}`` over ``time``, with at least ``theta`` [rad], ``power`` [W] and
        ``torque_hydrodynamic`` [N m]; each gets ``<name>_phase_mean``.
    window : flumekit.signal.SteadyWindow
        The steady window (:func:`steady_window`); phase averages start at its first zero
        up-crossing of θ (t/T = 0, Fig. 10).
    %(run_period)s
    incident_height : float
        Incident wave height H at the flap [m] (separation stage), > 0.
    %(depth)s
    %(flap_width_a2)s
    %(n_phase)s
    ci95 : tuple of str, optional
        Names of ``series`` that also get ``<name>_phase_ci95``.
    theta_unfiltered : array_like, optional
        θ before the derivatives' low-pass [rad], of which ``theta_amplitude`` is taken when
        given: the low-pass rounds the extremes where the flap stops and turns (the PTO's
        friction holds it), lowering the amplitude by ~3.5e-4 of it at 4 Hz on the virtual
        flume, while an encoder's quantisation error (uniform within a count, one draw per
        cycle's extreme) averages out over the cycles' mean maximum and minimum.

    Returns
    -------
    xarray.Dataset
        Over ``phase`` [-], the phase averages (units of each series) and the scalars
        ``theta_amplitude`` [rad], ``torque_amplitude`` [N m] (half the difference of the mean
        per-cycle maximum and minimum, Fig. 8), ``mean_power`` [W] (over the window),
        ``incident_height`` [m], ``incident_power`` [W] (W_I, Eq. A2), ``capture_factor`` [-]
        (C_f = W̄_out / W_I, §3.2), ``steady_start``, ``steady_end``, ``measured_period`` [s]
        and ``steady_cycles``.

    Raises
    ------
    ValueError
        A non-positive or non-finite incident height: without an incident wave there is no
        capture factor, and a zero height means the separation failed.

    %(references_brito2020)s, §2.5-§3.3, Eq. (A2).
    """
    scalars = summary_scalars(time, series, window, period=period,
                              incident_height=incident_height, depth=depth,
                              flap_width=flap_width, n_phase=n_phase,
                              theta_unfiltered=theta_unfiltered)
    t = np.asarray(time, dtype=float)
    cycles = (window.period, window.start, window.n_cycles)
    pa = {n: sig.phase_average(x, t, *cycles, n_phase=n_phase) for n, x in series.items()}
    data = {f"{n}_phase_mean": ("phase", a.mean) for n, a in pa.items()}
    data.update({f"{n}_phase_ci95": ("phase", pa[n].ci95) for n in ci95})
    data.update(scalars)
    return xr.Dataset(data, coords={"phase": pa["theta"].phase, "wave_period": float(period)})


@_doc
def summary_scalars(time, series, window: sig.SteadyWindow, *, period: float,
                    incident_height: float, depth: float, flap_width: float,
                    n_phase: int = 100, theta_unfiltered=None) -> dict:
    """Return the scalars of :func:`summary`: amplitudes, mean power, W_I, C_f and the window.

    Parameters
    ----------
    time, series, window, period, incident_height, depth, flap_width, n_phase
        As in :func:`summary`: time [s], the series (``theta`` [rad], ``power`` [W] and
        ``torque_hydrodynamic`` [N m] are used), the steady window, period [s], incident
        height [m], depth [m], flap width [m], phase points per cycle.
    theta_unfiltered : array_like, optional
        As in :func:`summary`: θ before the derivatives' low-pass [rad].

    Returns
    -------
    dict of str to float
        ``theta_amplitude`` [rad], ``torque_amplitude`` [N m], ``mean_power`` [W],
        ``incident_height`` [m], ``incident_power`` [W], ``capture_factor`` [-],
        ``steady_start``, ``steady_end``, ``measured_period`` [s] and ``steady_cycles``.

    Raises
    ------
    ValueError
        A non-positive or non-finite incident height.

    %(references_brito2020)s, §3.2, Eq. (A2).
    """
    if not (np.isfinite(incident_height) and incident_height > 0):
        raise ValueError(f"incident height must be > 0, got {incident_height}")
    t = np.asarray(time, dtype=float)
    cycles = (window.period, window.start, window.n_cycles)
    mean_w = window_mean(series["power"], t, window.start, window.end)
    w_i = float(incident_power(incident_height, period, depth, flap_width))
    return {
        "theta_amplitude": sig.cycle_amplitude(
            series["theta"] if theta_unfiltered is None else theta_unfiltered, t, *cycles,
            n_phase),
        "torque_amplitude": sig.cycle_amplitude(series["torque_hydrodynamic"], t, *cycles,
                                                n_phase),
        "mean_power": mean_w, "incident_height": float(incident_height),
        "incident_power": w_i, "capture_factor": float(capture_factor(mean_w, w_i)),
        "steady_start": window.start, "steady_end": window.end,
        "measured_period": window.period, "steady_cycles": window.n_cycles}


@_doc
def summarise_run(sim: xr.Dataset, *, period: float, incident_height: float, depth: float,
                  flap_width: float, tolerance: float = 0.02, n_phase: int = 100) -> xr.Dataset:
    """Summarise a simulated run as :func:`summary`, in the experimental analysis's names.

    Parameters
    ----------
    sim : xarray.Dataset
        Output of :func:`flumekit.flap.simulator.simulate_run` (or ``simulate``).
    %(run_period)s
    incident_height : float
        Incident wave height H at the flap [m] (from the separation), for W_I.
    %(depth)s
    %(flap_width_a2)s
    tolerance : float, optional
        Crest tolerance of the quasi-steady window [-] (2 %, §2.5).
    %(n_phase)s

    Returns
    -------
    xarray.Dataset
        :func:`summary` of ``theta``, ``theta_dot``, ``power``, ``torque_hydrodynamic`` (and
        ``chamber_pressure`` for the hydraulic PTO), with the simulator's scalar attributes.

    Raises
    ------
    ValueError
        Fewer than two quasi-steady cycles, or a non-positive incident height.

    %(references_brito2020)s, §2.5-§3.3.

    Examples
    --------
    A flap that spins up over 10 s to θ = 0.1 sin(π t) on a linear damper of 300 N m s: the
    quasi-steady window starts after the ramp, the amplitude is the one put in and the mean
    power is ½ ν ω² Θ² = 14.80 W; C_f divides it by W_I of Eq. (A2):

    >>> import numpy as np, xarray as xr
    >>> from flumekit.flap.summary import summarise_run
    >>> t = np.arange(0.0, 60.0, 0.01)
    >>> sim = xr.Dataset({"theta": ("time", 0.1 * np.minimum(t / 10.0, 1.0) * np.sin(np.pi * t))},
    ...                  coords={"time": t})
    >>> sim["theta_dot"] = sim.theta.differentiate("time")
    >>> sim["power"] = 300.0 * sim.theta_dot**2
    >>> sim["torque_hydrodynamic"] = 50.0 * sim.theta_dot
    >>> s = summarise_run(sim, period=2.0, incident_height=0.1, depth=0.825, flap_width=1.31)
    >>> float(s.steady_start) >= 10.0, round(float(s.theta_amplitude), 4)
    (True, 0.1)
    >>> round(float(s.mean_power), 2), round(float(s.incident_power), 2)
    (14.8, 29.87)
    >>> bool(np.isclose(s.capture_factor, s.mean_power / s.incident_power))
    True
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
