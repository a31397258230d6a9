"""Per-run summary of a simulation, in the names of the experimental flap analysis.

The comparison stage sets the simulated run beside the measured one
(:func:`flumekit.flap.analysis.analyse_run`) and the linear model: this module reduces a
simulator output to the same quantities, computed the same way (Brito et al. 2020, §2.5-§3.3):
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
from flumekit.flap.power import incident_power, window_mean


def _half_range(x, time, period, start, n_cycles, n_phase) -> float:
    cyc = sig.resample_cycles(x, time, period, start, n_cycles, n_phase)
    return float(0.5 * (cyc.max(axis=-1).mean() - cyc.min(axis=-1).mean()))


def summarise_run(sim: xr.Dataset, *, period: float, incident_height: float, depth: float,
                  flap_width: float, tolerance: float = 0.02, n_phase: int = 100) -> xr.Dataset:
    """Amplitudes, mean power, capture factor and phase averages of a simulated run.

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
    Dataset over ``phase`` with ``theta_phase_mean``, ``theta_dot_phase_mean``,
    ``power_phase_mean``, ``torque_hydrodynamic_phase_mean`` (and
    ``chamber_pressure_phase_mean`` for the hydraulic PTO) and the scalars
    ``theta_amplitude``, ``torque_amplitude``, ``mean_power``, ``incident_height``,
    ``incident_power``, ``capture_factor``, ``steady_start``, ``steady_end``,
    ``measured_period``, ``steady_cycles`` (the names of the experimental analysis).
    """
    t = sim["time"].values
    theta = sim["theta"].values
    win = sig.steady_window_or_centred(theta, t, tolerance=tolerance, min_period=0.5 * period)
    if win.n_cycles < 2:
        raise ValueError("the simulated run has fewer than two quasi-steady cycles")
    mean_w = window_mean(sim["power"].values, t, win.start, win.end)
    w_i = float(incident_power(incident_height, period, depth, flap_width))
    names = ["theta", "theta_dot", "power", "torque_hydrodynamic"]
    if "chamber_pressure" in sim:
        names.append("chamber_pressure")
    pa = {n: sig.phase_average(sim[n].values, t, win.period, win.start, win.n_cycles,
                               n_phase=n_phase) for n in names}
    args = (t, win.period, win.start, win.n_cycles, n_phase)
    out = xr.Dataset(
        {**{f"{n}_phase_mean": ("phase", pa[n].mean) for n in names},
         "theta_amplitude": _half_range(theta, *args),
         "torque_amplitude": _half_range(sim["torque_hydrodynamic"].values, *args),
         "mean_power": mean_w, "incident_height": float(incident_height),
         "incident_power": w_i, "capture_factor": mean_w / w_i if w_i > 0 else np.nan,
         "steady_start": win.start, "steady_end": win.end, "measured_period": win.period,
         "steady_cycles": win.n_cycles},
        coords={"phase": pa["theta"].phase, "wave_period": float(period)},
        attrs={"source": "flumekit.flap.summary",
               **{k: v for k, v in sim.attrs.items() if isinstance(v, (int, float, str))}})
    return conventions.annotate(out)
