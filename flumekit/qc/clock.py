"""Clock check between instruments: the probe-to-flap lag against the campaign's other runs.

Instruments on separate clocks (probes, flap, UVP) can be offset by a fraction of a second, and
nothing in one run tells an offset from the physical lag between the wave at a probe and the
flap's response. That lag is a smooth function of the wave condition, though (the propagation
from the probe to the flap and the flap's response phase): runs of the same condition share it
up to noise (3 ms between repeats of the virtual flume), and across conditions it varies
with period and height smoothly enough for a low-order fit: the single-run conditions of the
virtual flume's campaigns are predicted from their neighbouring conditions within 0.057 s
(paper size, 141 runs) and 0.072 s (default size, at T = 3.75 s), the flap's nonlinear
response (vapour cavity, vortex drag) bending the lag between neighbouring periods, so the
default tolerance is 0.1 s, a third of the 0.3 s offset the benchmark injects. So each run's
cross-correlation lag (:func:`flumekit.signal.estimate_time_offset`) between the probe nearest
the flap and the encoder is compared with a reference: the median of its condition where it
has three runs or more, else a low-order fit in (period, height) to the runs of the
neighbouring conditions, which a run alone in its condition (every wave run of the paper
campaign) has. A departure beyond a tolerance is a clock offset of about that size. The check
reports it (never applies it): the user declares the offset in run.toml. A campaign with no
neighbouring conditions (one period only, or a single run) has no reference: the departure is
NaN and the reason is said.
"""

from __future__ import annotations

import numpy as np

from flumekit.signal import estimate_time_offset


def probe_flap_lag(eta: np.ndarray, eta_time: np.ndarray, flap: np.ndarray,
                   flap_time: np.ndarray, period: float) -> float:
    """Return the cross-correlation offset of a flap channel from a probe record, within ±T/2.

    The offset to add to the flap's time stamps that best aligns the flap channel with the
    probe record (:func:`flumekit.signal.estimate_time_offset`): minus the physical lag of the
    flap behind the wave at the probe, modulo a period, plus any clock offset of the flap.
    Non-finite samples are left out.

    Parameters
    ----------
    eta : numpy.ndarray
        Probe record [any unit].
    eta_time : numpy.ndarray
        Its times [s].
    flap : numpy.ndarray
        Flap channel (encoder counts or angle) [any unit].
    flap_time : numpy.ndarray
        Its times [s].
    period : float
        Wave period [s]; a regular wave's correlation repeats every period, so the offset is
        sought within half of it.

    Returns
    -------
    float
        Offset [s].

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.qc import probe_flap_lag
    >>> t = np.arange(0.0, 40.0, 0.02)
    >>> eta = np.sin(2 * np.pi * t / 2.0)
    >>> round(probe_flap_lag(eta, t, np.sin(2 * np.pi * (t - 0.3) / 2.0), t, 2.0), 2)
    -0.3
    """
    ok_e, ok_f = np.isfinite(eta), np.isfinite(flap)
    return estimate_time_offset(eta[ok_e], eta_time[ok_e], flap[ok_f], flap_time[ok_f],
                                max_offset=0.5 * period)


#: distinct periods on either side of a run's whose conditions serve its fit
NEIGHBOURS = 1


def clock_departures(lags: np.ndarray, periods: np.ndarray, heights: np.ndarray
                     ) -> tuple[np.ndarray, list[str]]:
    """Return each run's departure from the lag its wave condition should have, and its basis.

    * Three runs or more of the same (period, height): the median lag of those runs.
    * Otherwise the runs of the other conditions whose period is the nearest distinct period
      on either side of the run's (``NEIGHBOURS``), or its own at other heights, give a
      least-squares fit lag(T, H) = a + b T + H (c + d T) (terms as the distinct periods and
      heights allow) to the median lag of each condition, evaluated at the run's condition.
      The run's period must lie within the periods fitted (no extrapolation in period), and
      three conditions more than the fit's terms are needed. A condition carrying another run's
      clock offset is found by leaving each out in turn and dropped (see ``_fit_reference``).

    Departures are wrapped into ±T/2 (the lag of a regular wave is known modulo a period);
    NaN where there is no reference.

    Parameters
    ----------
    lags : numpy.ndarray
        Probe-to-flap lag of each run (:func:`probe_flap_lag`) [s].
    periods : numpy.ndarray
        Wave period of each run [s].
    heights : numpy.ndarray
        Wave height of each run [m].

    Returns
    -------
    departures : numpy.ndarray
        Departure of each run's lag from its reference [s], NaN without a reference.
    basis : list of str
        How each run's reference was found (or why there is none).

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.qc.clock import clock_departures
    >>> d, basis = clock_departures(np.array([0.50, 0.52, 0.81]), np.full(3, 2.0), np.full(3, 0.1))
    >>> np.round(d, 2).tolist(), basis[0]
    ([-0.02, 0.0, 0.29], 'median of the 3 runs of its condition')
    """
    lags = np.asarray(lags, dtype=float)
    periods = np.asarray(periods, dtype=float)
    heights = np.asarray(heights, dtype=float)
    out = np.full(lags.shape, np.nan)
    basis = ["no reference: fewer than three runs of its condition, and too few neighbouring "
             "conditions (on both sides in period, three more than the fit's terms)"] * lags.size
    same = (periods[:, None] == periods[None, :]) & (heights[:, None] == heights[None, :])
    for i in range(lags.size):  # runs of a campaign: a few hundred at most
        group = np.flatnonzero(same[i])
        if group.size >= 3:
            ref = float(np.median(lags[group]))
            basis[i] = f"median of the {group.size} runs of its condition"
        else:
            ref, n = _fit_reference(i, lags, periods, heights, ~same[i])
            if ref is None:
                continue
            basis[i] = f"fit over {n} neighbouring conditions"
        d = lags[i] - ref
        out[i] = (d + 0.5 * periods[i]) % periods[i] - 0.5 * periods[i]
    return out, basis


def _design(t: np.ndarray, h: np.ndarray, deg_t: int, deg_h: int) -> np.ndarray:
    cols = [np.ones_like(t)] + [t ** k for k in range(1, deg_t + 1)]
    if deg_h:
        cols += [h] + ([t * h] if deg_t else [])
    return np.column_stack(cols)


def _fit_reference(i: int, lags, periods, heights, other) -> tuple[float | None, int]:
    """Lag of run i's condition from the fit over the neighbouring conditions (or None)."""
    distinct = np.unique(periods[other])
    below = distinct[distinct < periods[i]][-NEIGHBOURS:]
    above = distinct[distinct > periods[i]][:NEIGHBOURS]
    own = distinct[distinct == periods[i]]
    if not (below.size and above.size) and not own.size:
        return None, 0  # no extrapolation in period
    use = other & np.isin(periods, np.concatenate([below, own, above]))
    # one point per condition (the median of its runs): repeats of one condition must not
    # outweigh the others, nor set the scale of the residuals
    cond, inv = np.unique(np.column_stack([periods[use], heights[use]]), axis=0,
                          return_inverse=True)
    inv = inv.ravel()
    t, h = cond[:, 0], cond[:, 1]
    y = np.array([np.median(lags[use][inv == k]) for k in range(cond.shape[0])])
    deg_t = min(1, np.unique(t).size - 1)
    deg_h = min(1, np.unique(h).size - 1)
    at = _design(np.array([periods[i]]), np.array([heights[i]]), deg_t, deg_h)
    npar = _design(t, h, deg_t, deg_h).shape[1]
    # a lag is known modulo its period: each condition's lag on the branch nearest a first fit
    coef, *_ = np.linalg.lstsq(_design(t, h, deg_t, deg_h), y, rcond=None)
    y = y - np.round((y - _design(t, h, deg_t, deg_h) @ coef) / t) * t
    keep = np.ones(y.size, dtype=bool)
    # another run's clock offset: with a handful of conditions a least-squares fit bends
    # towards it, so each condition in turn is left out, and the one whose removal leaves the
    # best fit is dropped when the fit without it misses it by far. That takes two spare
    # conditions once one is left out (with one, leaving out a good condition at the edge
    # can fit the rest as well), so fewer conditions give no reference.
    if y.size < npar + 3:
        return None, 0
    while keep.sum() >= npar + 3:
        idx = np.flatnonzero(keep)
        best = None
        for j in idx:  # a dozen conditions
            rest = idx[idx != j]
            a = _design(t[rest], h[rest], deg_t, deg_h)
            c, *_ = np.linalg.lstsq(a, y[rest], rcond=None)
            rms = float(np.sqrt(np.mean((y[rest] - a @ c) ** 2)))
            miss = abs(float(y[j] - (_design(t[j:j + 1], h[j:j + 1], deg_t, deg_h) @ c)[0]))
            if best is None or rms < best[0]:
                best = (rms, miss, j)
        rms, miss, j = best
        if miss <= 5 * rms + 0.01:
            break
        keep[j] = False
    if keep.sum() < npar + 2:
        return None, 0
    coef, *_ = np.linalg.lstsq(_design(t[keep], h[keep], deg_t, deg_h), y[keep], rcond=None)
    return float((at @ coef)[0]), int(keep.sum())
