"""The phase-averaging window of one UVP run, from the run's datasets.

:mod:`flumekit.uvp.window` decides on arrays where N waves may be averaged; this module reads
what it needs from the datasets of a run (the waves analysis, the flap angle, the beams and
their quality-control flags) and checks the beams where the average reads them:
:func:`checked_window` finds the earliest window of N waves that the waves and the flap angle
allow, has the beams checked over the samples that window reads and, only when a beam is not
clean there, over the whole quasi-steady part, where the window may then move (Brito et al.
2020, §2.5-2.6). With clean beams, the usual case, the beams are checked once, over 70 % of
the quasi-steady part at the paper's 50 waves of 3.5 s.

References
----------
Brito, M., Ferreira, R. M. L., Teixeira, L., Neves, M. G. and Canhoto, P. (2020). Experimental
investigation on the power capture of an oscillating wave surge converter in unidirectional
waves. Renewable Energy 151, 975-992.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np
import xarray as xr

from flumekit.conventions import MAX_GAP
from flumekit.qc.flags import FAIL, MISSING
from flumekit.qc.record import clean
from flumekit.signal import zero_upcrossings
from flumekit.uvp.phase import default_pad
from flumekit.uvp.window import Flagged, averaging_start, blocking, steady_span

#: a profile with more than this fraction of its channels failed quality control (or missing)
#: is a dropout of the instrument [-]
DROPOUT_FRACTION = 0.5
#: up-crossings closer than this fraction of the wave period are merged when the quasi-steady
#: part is sought: a cycle of a regular wave is never that short, a noise crossing is [-]
MIN_CYCLE_FRACTION = 0.75
#: the average reads the profile beyond each end of its padded window
#: (:func:`flumekit.uvp.phase.phase_average_beams`): the records checked extend this many
#: profile intervals beyond it [-]
PROFILE_MARGIN = 1.5


def phase_reference(waves: xr.Dataset) -> tuple[np.ndarray, float]:
    """Return the phase reference of a run: up-crossings [s] and the measured period [s].

    The zero up-crossings of the separated incident wave at the flap (``eta_incident``) in the
    waves' analysis window (``steady_start``-``steady_end``, where the separation is defined),
    placed on the least-squares line through them (t_n = t_0 + n T'), which removes the
    jitter of single crossings.

    Parameters
    ----------
    waves : The waves stage's dataset of a regular run.

    Returns
    -------
    ups : numpy.ndarray
        The up-crossing times [s].
    period : float
        ``measured_period`` [s].

    Raises
    ------
    ValueError
        No up-crossing in the window.
    """
    t = waves["time"].values
    # steady_end is the end of the last sample's interval: the sample there is outside (NaN)
    inside = (t >= float(waves["steady_start"])) & (t < float(waves["steady_end"]))
    eta = waves["eta_incident"].values[inside]
    if not np.all(np.isfinite(eta)):
        eta = np.nan_to_num(eta)
    ups = zero_upcrossings(eta, t[inside])
    if ups.size == 0:
        raise ValueError("no zero up-crossing of the incident wave in the quasi-steady window")
    period = float(waves["measured_period"])
    if ups.size >= 3:
        # one crossing jitters by a millisecond or two (the harmonics and the noise left in
        # the separated wave), which a reference extrapolated to a window elsewhere carries
        # whole: the crossings on the least-squares line through all of them instead
        n = np.rint((ups - ups[0]) / period)
        slope, intercept = np.polyfit(n, ups, 1)
        ups = intercept + slope * n
    return ups, period


def waves_span(waves: xr.Dataset) -> tuple[float, float]:
    """Return the quasi-steady part of a run's wave field, probe faults bridged [s].

    :func:`flumekit.uvp.window.steady_span` on the elevations of the waves stage's dataset,
    with its per-probe crest scale and tolerance; up-crossings closer than
    :data:`MIN_CYCLE_FRACTION` of the wave period are merged.

    Parameters
    ----------
    waves : The waves stage's dataset (``eta`` (probe, time) [m], ``amplitude_scale`` [m],
        ``steady_tolerance`` [-], attribute ``wave_period`` [s]).

    Returns
    -------
    tuple of float
        (start, end) [s].
    """
    return steady_span(waves["eta"].transpose("probe", "time").values, waves["time"].values,
                       waves["amplitude_scale"].values, waves["steady_tolerance"].values,
                       MIN_CYCLE_FRACTION * float(waves.attrs["wave_period"]))


def qc_span(span: tuple[float, float], period: float, cutoff: float) -> tuple[float, float]:
    """Return the span of the UVP records checked when the first window is not clean [s].

    The quasi-steady part ``span`` [s] (:func:`waves_span`) and, on each side, the low-pass
    filter's pad (:func:`flumekit.uvp.phase.default_pad` of ``cutoff`` [Hz]) and one
    ``period`` [s] more (the average starts on an up-crossing near the span's edge): every
    sample the average may read.
    """
    margin = default_pad(cutoff) + period
    return span[0] - margin, span[1] + margin


def records_span(beams: dict[str, xr.Dataset], start: float, end: float,
                 pad: float) -> tuple[float, float]:
    """Return the span of the UVP records that the average of the waves ``start``-``end`` reads.

    ``pad`` [s] either side and :data:`PROFILE_MARGIN` profile intervals (of the beam with the
    longest) beyond each end, on the probes' clock [s].
    """
    dt = max(float(b["time"][-1] - b["time"][0]) / max(b.sizes["time"] - 1, 1)
             for b in beams.values())
    return start - pad - PROFILE_MARGIN * dt, end + pad + PROFILE_MARGIN * dt


def beam_records(flags: xr.Dataset, names: Sequence[str], offset: float = 0.0
                 ) -> dict[str, Flagged]:
    """Return, per beam, the profiles at which the instrument dropped out.

    A profile with more than :data:`DROPOUT_FRACTION` of its channels failed or missing in the
    flags (:func:`flumekit.qc.record.beam_flags`) is bad; times on the probes' clock (beam time
    + ``offset`` [s]), keyed ``"UVP beam <name>"`` for messages.
    """
    out = {}
    for name in names:
        f = flags[f"beam_velocity_qc_{name}"].transpose("channel", ...).values
        bad = ((f == FAIL) | (f == MISSING)).mean(axis=0) > DROPOUT_FRACTION
        out[f"UVP beam {name}"] = Flagged(flags[f"time_{name}"].values + offset, bad)
    return out


def averaging_window(waves: xr.Dataset, flags: xr.Dataset | None, theta: xr.DataArray,
                     names: Sequence[str], *, n_cycles: int, pad: float, max_gap: float,
                     time_offset: float = 0.0, span: tuple[float, float] | None = None,
                     run: str = "") -> tuple[float, float]:
    """Return (start [s], period [s]) of a run's phase average.

    :func:`flumekit.uvp.window.averaging_start`: ``n_cycles`` periods from the phase reference
    (:func:`phase_reference`) in the quasi-steady ``span`` [s] (default :func:`waves_span`)
    with the flap angle ``theta`` (NaN where unusable) and the beams ``names`` clean (their QC
    ``flags``; None: the beams not considered), ``pad`` [s] either side, runs of bad samples up
    to ``max_gap`` [s] interpolated. ``time_offset``: the UVP's clock offset [s].

    Raises
    ------
    ValueError
        Naming the run and, for each candidate, the instrument and flagged span that rule it
        out.
    """
    ups, period = phase_reference(waves)
    records = {} if flags is None else beam_records(flags, names, time_offset)
    records["flap angle"] = Flagged(theta["time"].values, ~np.isfinite(theta.values))
    span = waves_span(waves) if span is None else span
    return averaging_start(ups, period, n_cycles, pad, span, records, max_gap, run=run), period


def checked_window(waves: xr.Dataset, theta: xr.DataArray, beams: dict[str, xr.Dataset],
                   check: Callable[[tuple[float, float]], xr.Dataset], *, n_cycles: int,
                   cutoff: float, max_gap: float, span: tuple[float, float],
                   time_offset: float = 0.0, run: str = "") -> tuple[float, float, xr.Dataset]:
    """Return (start [s], period [s], flags) of a run's phase average, its beams checked.

    The earliest window that the waves and the flap angle allow (:func:`averaging_window`
    without the beams) is taken; the beams are checked over the samples it reads
    (:func:`records_span`); when one holds a dropout longer than ``max_gap`` there, they are
    checked over the whole quasi-steady part (:func:`qc_span`) and the window is sought again
    with their flags.

    Parameters
    ----------
    waves : The waves stage's dataset of the run.
    theta : Flap angle [rad] on its ``time`` [s], NaN where unusable.
    beams : Beam name -> beam record as read (``time`` [s] on the UVP's clock).
    check : Quality control of the beams over a span [s] of the probes' clock: their flags
        (:func:`flumekit.qc.record.beam_flags` with the run's thresholds). Pure.
    n_cycles : Waves averaged.
    cutoff : Low-pass cut-off [Hz] (its pad, :func:`flumekit.uvp.phase.default_pad`).
    max_gap : Longest run of bad samples that is interpolated [s].
    span : Quasi-steady part of the waves [s] (:func:`waves_span`).
    time_offset : The UVP's clock offset: beam time + offset is on the probes' clock [s].
    run : Run name, for messages.

    Returns
    -------
    start, period : float
        Start of the average and the period [s].
    flags : xarray.Dataset
        The flags of the last check, with attribute ``max_gap`` [s].

    Raises
    ------
    ValueError
        No clean window (:func:`flumekit.uvp.window.averaging_start`).
    """
    pad = default_pad(cutoff)
    kw = {"n_cycles": n_cycles, "pad": pad, "max_gap": max_gap, "time_offset": time_offset,
          "span": span, "run": run}
    names = list(beams)
    start, period = averaging_window(waves, None, theta, names, **kw)
    end = start + n_cycles * period
    flags = check(records_span(beams, start, end, pad))
    if blocking(beam_records(flags, names, time_offset), start - pad, end + pad, max_gap)[0]:
        flags = check(qc_span(span, period, cutoff))
        start, period = averaging_window(waves, flags, theta, names, **kw)
    flags.attrs[MAX_GAP] = float(max_gap)
    return start, period, flags


def clean_beam(beam: xr.Dataset, flags: xr.Dataset, name: str, copy: bool = True
               ) -> xr.Dataset:
    """Return the beam with the samples that failed quality control masked and short gaps filled.

    :func:`flumekit.qc.record.clean` with the flags of beam ``name`` (``beam_velocity_qc_<name>``
    over the profiles checked, ``time_<name>``) and their attribute ``max_gap`` [s]; the
    profiles outside the checked span as read.

    Parameters
    ----------
    beam : The beam record (``beam_velocity`` [m s-1], ``time`` [s]).
    flags : Its QC flags (:func:`flumekit.qc.record.beam_flags`).
    name : The beam's name.
    copy : False: the beam's own velocity array is cleaned (a beam read for the caller).

    Raises
    ------
    ValueError
        The flags are not of this record's profiles.
    """
    f = flags[f"beam_velocity_qc_{name}"].transpose("channel", ...).values
    t = beam["time"].values
    checked = flags[f"time_{name}"].values
    i0 = int(np.searchsorted(t, checked[0])) if checked.size else 0
    span = slice(i0, i0 + checked.size)
    if not np.array_equal(t[span], checked):
        raise ValueError(f"beam {name}: the QC flags are not of this record's profiles")
    v = beam["beam_velocity"].transpose("channel", "time").values
    out = np.array(v) if copy else v
    fs = (t.size - 1) / (t[-1] - t[0])
    cleaned = clean(out[:, span], f, fs, float(flags.attrs[MAX_GAP]), copy=False)
    if not np.may_share_memory(cleaned, out):  # cleaned in place, as a rule
        out[:, span] = cleaned
    return beam.assign(beam_velocity=beam["beam_velocity"].copy(
        data=out.T if beam["beam_velocity"].dims[0] == "time" else out))
