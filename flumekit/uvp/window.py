"""Where a UVP run's phase average lies: N steady waves that the instruments it reads saw cleanly.

Brito et al. (2020, §2.5-2.6) average N = 50 waves of the quasi-steady part of a run from a
phase reference, the zero up-crossing of the incident wave at the flap. Two things decide where
those waves may lie, and they are kept apart here:

* the wave field must be quasi-steady there, a property of the flow that every probe sees.
  A probe fault that quality control masked (a dropout, a flat line: NaN in the elevation) says
  nothing about the flow, so the cycles it holds neither count as steady nor break the steady
  part (:func:`steady_span`); the probes' analysis window (the waves stage), which needs every
  separation probe clean, is not the UVP's;
* the instruments the UVP average reads, the UVP beams and the flap angle (its phase average
  masks the channels inside the flap), must be clean over the waves averaged and the filter's
  pad on either side (:func:`averaging_start`).

The phase reference repeats every period in the steady part, so the average may start at any
whole number of periods from it; the earliest clean start is taken (with clean records, the
first up-crossing of the steady part, as before).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from flumekit.qc.fill import runs
from flumekit.signal import cycles


def steady_span(eta: np.ndarray, time: np.ndarray, amplitude_scale: np.ndarray,
                tolerance: np.ndarray, min_period: float) -> tuple[float, float]:
    """Return the quasi-steady part of the wave field seen by all probes [s].

    Per probe, the cycles between zero up-crossings whose crest lies within ``tolerance`` of the
    probe's amplitude scale (Brito et al. 2020, §2.5) are steady; a cycle holding masked samples
    (NaN: a fault quality control removed) is unknown and bridged, so that a probe fault does
    not cut the steady part in two. The probe's steady part is the longest run (in time) of
    steady and unknown cycles that begins and ends with a steady one; the span returned is the
    part common to all probes.

    Parameters
    ----------
    eta : Elevation (probe, time) [m], NaN where masked.
    time : Sample times [s].
    amplitude_scale, tolerance : Per probe, the crest scale [m] and relative tolerance [-] of
        the waves stage's quasi-steady test (``amplitude_scale``, ``steady_tolerance``).
    min_period : Up-crossings closer than this are merged [s].

    Raises
    ------
    ValueError
        A probe without a steady cycle, or probes whose steady parts do not overlap.
    """
    eta = np.atleast_2d(np.asarray(eta, dtype=float))
    starts, ends = [], []
    for p in range(eta.shape[0]):  # a handful of probes
        c = cycles(eta[p], time, min_period=min_period)
        scale = float(amplitude_scale[p])
        with np.errstate(invalid="ignore"):
            ok = np.abs(c.crest - scale) <= float(tolerance[p]) * abs(scale)
        unknown = np.isnan(c.crest)
        if not ok.any():
            raise ValueError(f"probe {p}: no cycle is quasi-steady")
        row, first, length = runs((ok | unknown)[None, :])
        # trim the unknown cycles at either end of each run: only steady ones bound it
        idx = np.flatnonzero(ok)
        pos = np.searchsorted(idx, first)
        a = idx[np.minimum(pos, idx.size - 1)]  # first steady cycle at or after each run start
        b = idx[np.searchsorted(idx, first + length, side="left") - 1]  # last before its end
        keep = (pos < idx.size) & (a < first + length)
        a, b = a[keep], b[keep]
        t0 = c.start[a]
        t1 = c.start[b] + c.period[b]
        k = int(np.argmax(t1 - t0))
        starts.append(float(t0[k]))
        ends.append(float(t1[k]))
    start, end = max(starts), min(ends)
    if end <= start:
        raise ValueError("the probes' quasi-steady parts do not overlap ("
                         + ", ".join(f"{a:.1f}-{b:.1f} s" for a, b in zip(starts, ends,
                                                                            strict=True)) + ")")
    return start, end


@dataclass(frozen=True)
class Flagged:
    """Profiles (times) at which an instrument failed quality control, per instrument name."""

    time: np.ndarray  # [s], the instrument's sample times
    bad: np.ndarray  # bool, True where the sample is unusable (masked and not interpolated)


def bad_spans(record: Flagged, max_gap: float) -> list[tuple[float, float]]:
    """Return the runs of bad samples longer than ``max_gap`` seconds [s].

    Shorter runs are interpolated. Each run is (first time, last time).
    """
    if not record.bad.any():
        return []
    _, first, length = runs(np.asarray(record.bad, dtype=bool)[None, :])
    dt = (record.time[-1] - record.time[0]) / max(record.time.size - 1, 1)
    long_ = length * dt > max_gap + 1e-9
    return [(float(record.time[a]), float(record.time[a + n - 1]))
            for a, n in zip(first[long_], length[long_], strict=True)]


def blocking(records: Mapping[str, Flagged], lo: np.ndarray, hi: np.ndarray,
             max_gap: float) -> list[list[str]]:
    """Return, per window [lo, hi] [s], what rules it out (empty: clean).

    An instrument of ``records`` that does not cover the window, or holds a run of bad samples
    longer than ``max_gap`` [s] in it.
    """
    lo, hi = np.atleast_1d(lo), np.atleast_1d(hi)
    blocked: list[list[str]] = [[] for _ in lo]
    for name, rec in records.items():  # a handful of instruments
        t = rec.time
        cover = (lo >= t[0] - 1e-9) & (hi <= t[-1] + 1e-9)
        for i in np.flatnonzero(~cover):
            blocked[i].append(f"{name} records {t[0]:.1f}-{t[-1]:.1f} s only")
        for a, b in bad_spans(rec, max_gap):
            for i in np.flatnonzero((lo <= b) & (hi >= a)):
                blocked[i].append(f"{name} flagged over {a:.2f}-{b:.2f} s")
    return blocked


def averaging_start(reference: float | np.ndarray, period: float, n_cycles: int, pad: float,
                    span: tuple[float, float], records: Mapping[str, Flagged],
                    max_gap: float, run: str = "") -> float:
    """Return the start of the phase average [s].

    The earliest whole number of periods from the phase reference at which ``n_cycles``
    periods lie in the quasi-steady ``span`` and every instrument of ``records`` covers them,
    with ``pad`` seconds either side, without a run of bad samples longer than ``max_gap``.

    Parameters
    ----------
    reference : Time(s) of the phase reference [s] (up-crossings of the incident wave at the
        flap); the one nearest each candidate start is extrapolated by whole periods.
    period : Wave period [s].
    n_cycles : Waves averaged.
    pad : Seconds each instrument must hold before and after the waves averaged [s].
    span : Quasi-steady part of the wave field (:func:`steady_span`) [s].
    records : Per instrument name (for the message), its :class:`Flagged` samples.
    max_gap : Longest run of bad samples that is interpolated [s].
    run : Run name, for the message.

    Raises
    ------
    ValueError
        Naming the run and, for each candidate start, the instrument and flagged span that
        rule it out, when no candidate is clean.
    """
    ref = np.atleast_1d(np.asarray(reference, dtype=float))
    anchor = float(ref[0])
    eps = 1e-6 * period
    k0 = int(np.ceil((span[0] - anchor) / period - eps))
    k1 = int(np.floor((span[1] - n_cycles * period - anchor) / period + eps))
    who = f"run {run}: " if run else ""
    if k1 < k0:
        raise ValueError(f"{who}the quasi-steady part of the waves, {span[0]:.1f}-{span[1]:.1f} s, "
                         f"holds fewer than the {n_cycles} periods of {period:.4g} s the UVP "
                         "average needs ([stages.uvp] n_cycles)")
    starts = anchor + np.arange(k0, k1 + 1) * period
    # extrapolate from the reference nearest each start (the period's error grows with k)
    near = ref[np.argmin(np.abs(starts[:, None] - ref[None, :]), axis=1)]
    starts = near + np.round((starts - near) / period) * period
    blocked = blocking(records, starts - pad, starts + n_cycles * period + pad, max_gap)
    ok = np.array([not b for b in blocked])
    if ok.any():
        return float(starts[np.argmax(ok)])
    reasons = list(dict.fromkeys(r for b in blocked for r in b))
    raise ValueError(f"{who}no clean window of {n_cycles} periods of {period:.4g} s (+ {pad:g} s "
                     f"pad) in the quasi-steady part {span[0]:.1f}-{span[1]:.1f} s: "
                     + "; ".join(reasons[:6]) + (" ..." if len(reasons) > 6 else ""))
