"""Clock check between instruments: the lag between a probe and the flap, compared across runs.

Instruments on separate clocks (probes, flap, UVP) can be offset by a fraction of a second, and
nothing in one run tells an offset from the physical lag between the wave at a probe and the
flap's response. Runs of the same wave condition share that physical lag, though: the
cross-correlation lag (:func:`flumekit.signal.estimate_time_offset`) between the probe nearest
the flap and the encoder is the same in each of them, up to noise, so a run whose lag departs
from the median of its condition by more than a tolerance has a clock offset of about that
departure. The check reports it (never applies it): the user declares the offset in run.toml.
"""

from __future__ import annotations

import numpy as np

from flumekit.signal import estimate_time_offset


def probe_flap_lag(eta: np.ndarray, eta_time: np.ndarray, flap: np.ndarray,
                   flap_time: np.ndarray, period: float) -> float:
    """Cross-correlation lag of a flap channel behind a probe record, within ±T/2 [s].

    Parameters
    ----------
    eta, eta_time : Probe record (any unit) and its times [s].
    flap, flap_time : Flap channel (encoder counts or angle) and its times [s].
    period : Wave period [s]; a regular wave's correlation repeats every period, so the lag is
        sought within half of it.
    """
    ok_e, ok_f = np.isfinite(eta), np.isfinite(flap)
    return estimate_time_offset(eta[ok_e], eta_time[ok_e], flap[ok_f], flap_time[ok_f],
                                max_offset=0.5 * period)


def clock_departures(lags: np.ndarray, periods: np.ndarray, groups: list) -> np.ndarray:
    """Departure of each run's lag from the median lag of the runs of its group [s].

    Departures are wrapped into ±T/2 (the lag of a regular wave is known modulo a period); NaN
    for a group of fewer than three runs, where two runs cannot tell which one is off.
    """
    lags = np.asarray(lags, dtype=float)
    periods = np.asarray(periods, dtype=float)
    out = np.full(lags.shape, np.nan)
    for key in dict.fromkeys(groups):  # a handful of wave conditions
        idx = np.array([i for i, g in enumerate(groups) if g == key])
        if idx.size >= 3:
            d = lags[idx] - np.median(lags[idx])
            out[idx] = (d + 0.5 * periods[idx]) % periods[idx] - 0.5 * periods[idx]
    return out
