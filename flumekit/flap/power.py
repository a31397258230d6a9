"""Power captured by the PTO and the capture factor (Brito et al. 2020, §3.2 and Eq. A2).

W_out = P_int Q, with P_int the chamber gauge pressure and Q = −A ℓ̇ the flow rate out of the
chamber (positive while the rod is pushed in). On the compression stroke P_int > 0 and Q > 0;
on the suction stroke both are negative: W_out ≥ 0 whenever the chamber pressure opposes the
motion, as it does for a dissipative PTO.

%(references_brito2020)s.
"""

from __future__ import annotations

import numpy as np

from flumekit.docstrings import doc, fill
from flumekit.waves.theory import G, energy_flux

__doc__ = fill(__doc__)


@doc
def flow_rate(rod_velocity, bore_area: float) -> np.ndarray:
    """Compute the flow rate out of the chamber, Q = −A ℓ̇.

    Parameters
    ----------
    rod_velocity : array_like
        Rod extension rate ℓ̇ [m s-1].
    %(bore_area)s

    Returns
    -------
    numpy.ndarray
        Q [m3 s-1], positive while the rod is pushed in.

    %(raises_bore_area)s

    %(references_brito2020)s, §3.2.

    Examples
    --------
    >>> from flumekit.flap.power import flow_rate
    >>> flow_rate([-0.1, 0.2], 0.002)
    array([ 0.0002, -0.0004])
    """
    if not bore_area > 0:
        raise ValueError(f"bore area must be > 0, got {bore_area}")
    return -bore_area * np.asarray(rod_velocity, dtype=float)


@doc
def pto_power(chamber_pressure, flow) -> np.ndarray:
    """Compute the instantaneous PTO power W_out = P_int Q (§3.2).

    Parameters
    ----------
    %(chamber_pressure)s
    flow : array_like
        Flow rate out of the chamber Q [m3 s-1] (:func:`flow_rate`).

    Returns
    -------
    numpy.ndarray
        W_out [W].

    %(references_brito2020)s, §3.2.

    Examples
    --------
    >>> from flumekit.flap.power import pto_power
    >>> pto_power([1.0e5, -2.0e4], [2.0e-4, -1.0e-4])
    array([20.,  2.])
    """
    return np.asarray(chamber_pressure, dtype=float) * np.asarray(flow, dtype=float)


def window_mean(values, time, start: float, end: float) -> float:
    """Average ``values`` over the time window [start, end] by the trapezoidal rule.

    Used for the mean power over the quasi-steady window, which spans whole cycles. The ends
    of the window are interpolated linearly between samples.

    Parameters
    ----------
    values : array_like
        Samples (any unit).
    time : array_like
        Sample times [s], increasing.
    start : float
        Start of the window [s], inside the record.
    end : float
        End of the window [s], inside the record and after ``start``.

    Returns
    -------
    float
        The time average (unit of ``values``).

    Raises
    ------
    ValueError
        The window is empty or not inside the record.

    Examples
    --------
    >>> from flumekit.flap.power import window_mean
    >>> window_mean([0.0, 2.0, 4.0], [0.0, 1.0, 2.0], 0.5, 1.5)
    2.0
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


@doc
def incident_power(height, period, depth, width: float, rho: float = 1000.0,
                   g: float = G) -> np.ndarray:
    """Compute the incident power W_I, the period-averaged energy flux times the flap width.

    W_I = (1/8) ρ g H² c_g L, Eq. (A2).

    Parameters
    ----------
    height : array_like
        Incident wave height H [m] (from the incident/reflected separation).
    %(period_array)s
    %(depth_array)s
    width : float
        Flap width L [m] (1.31 m).
    %(rho)s
    %(g)s

    Returns
    -------
    numpy.ndarray
        W_I [W].

    Raises
    ------
    ValueError
        A non-positive flap width.

    %(references_brito2020)s, Eq. (A2).

    Examples
    --------
    >>> from flumekit.flap.power import incident_power
    >>> round(float(incident_power(0.1, 2.0, 0.825, 1.31)), 2)
    29.87
    """
    if not width > 0:
        raise ValueError(f"flap width must be > 0, got {width}")
    # Eq. (A2) in Brito et al. 2020: per-metre flux E c_g times the flap width L
    return energy_flux(height, period, depth, rho=rho, g=g) * width


@doc
def capture_factor(mean_power, incident_power_value) -> np.ndarray:
    """Compute the power capture factor C_f = mean W_out / W_I (§3.2).

    Parameters
    ----------
    mean_power : array_like
        Mean PTO power W̄_out [W].
    incident_power_value : array_like
        Incident power W_I [W], > 0 (:func:`incident_power`).

    Returns
    -------
    numpy.ndarray
        C_f [-].

    Raises
    ------
    ValueError
        A non-positive incident power.

    %(references_brito2020)s, §3.2.

    Examples
    --------
    >>> from flumekit.flap.power import capture_factor
    >>> float(capture_factor(5.0, 20.0))
    0.25
    """
    wi = np.asarray(incident_power_value, dtype=float)
    if np.any(~(wi > 0)):
        raise ValueError("capture factor needs a positive incident power")
    return np.asarray(mean_power, dtype=float) / wi
