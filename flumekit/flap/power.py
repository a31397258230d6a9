"""Power captured by the PTO and the capture factor (Brito et al. 2020, §3.2 and Eq. A2).

W_out = P_int Q, with P_int the chamber gauge pressure and Q = −A ℓ̇ the flow rate out of the
chamber (positive while the rod is pushed in). On the compression stroke P_int > 0 and Q > 0;
on the suction stroke both are negative: W_out ≥ 0 whenever the chamber pressure opposes the
motion, as it does for a dissipative PTO.
"""

from __future__ import annotations

import numpy as np

from flumekit.waves.theory import G, energy_flux


def flow_rate(rod_velocity, bore_area: float) -> np.ndarray:
    """Flow rate out of the chamber Q = −A ℓ̇ [m3 s-1]; ℓ̇ rod extension rate [m s-1], A [m2]."""
    if not bore_area > 0:
        raise ValueError(f"bore area must be > 0, got {bore_area}")
    return -bore_area * np.asarray(rod_velocity, dtype=float)


def pto_power(chamber_pressure, flow) -> np.ndarray:
    """Instantaneous PTO power W_out = P_int Q [W] (§3.2); P_int gauge [Pa], Q [m3 s-1]."""
    return np.asarray(chamber_pressure, dtype=float) * np.asarray(flow, dtype=float)


def window_mean(values, time, start: float, end: float) -> float:
    """Time average of ``values`` over [start, end] [s] by the trapezoidal rule.

    Used for the mean power over the quasi-steady window, which spans whole cycles.
    """
    t = np.asarray(time, dtype=float)
    y = np.asarray(values, dtype=float)
    if not (t[0] <= start < end <= t[-1]):
        raise ValueError(f"window [{start}, {end}] s is not inside the record "
                         f"[{t[0]}, {t[-1]}] s")
    inner = (t > start) & (t < end)
    tt = np.concatenate([[start], t[inner], [end]])
    yy = np.concatenate([[np.interp(start, t, y)], y[inner], [np.interp(end, t, y)]])
    return float(np.sum(0.5 * (yy[1:] + yy[:-1]) * np.diff(tt)) / (end - start))


def incident_power(height, period, depth, width: float, rho: float = 1000.0,
                   g: float = G) -> np.ndarray:
    """Period-averaged incident energy flux times the flap width, W_I [W] (Eq. A2).

    Parameters
    ----------
    height : array_like
        Incident wave height H [m] (from the incident/reflected separation).
    period : array_like
        Wave period T [s].
    depth : array_like
        Water depth h [m].
    width : float
        Flap width L [m] (1.31 m).
    rho : float
        Water density [kg m-3].
    g : float
        Gravitational acceleration [m s-2].
    """
    if not width > 0:
        raise ValueError(f"flap width must be > 0, got {width}")
    # Eq. (A2) in Brito et al. 2020: per-metre flux E c_g times the flap width L
    return energy_flux(height, period, depth, rho=rho, g=g) * width


def capture_factor(mean_power, incident_power_value) -> np.ndarray:
    """Power capture factor C_f = mean W_out / W_I [-] (§3.2)."""
    wi = np.asarray(incident_power_value, dtype=float)
    if np.any(~(wi > 0)):
        raise ValueError("capture factor needs a positive incident power")
    return np.asarray(mean_power, dtype=float) / wi
