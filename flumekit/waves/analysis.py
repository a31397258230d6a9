"""Wave statistics of one regular-wave run: quasi-steady window, separation at the flap, Kr, H_I, T.

This is the pure function behind the pipeline's per-run waves stage.
"""

from __future__ import annotations

import warnings
from typing import NamedTuple

import numpy as np
import xarray as xr

from flumekit import conventions
from flumekit.docstrings import doc
from flumekit.signal import cycles, quasi_steady_window
from flumekit.waves.layout import MAX_CONDITION
from flumekit.waves.records import probe_record
from flumekit.waves.separation import (
    SeparationWarning,
    check_probe_arrays,
    check_separation_arrays,
    prepare_separation,
    separate_prepared,
    separation_dataset,
    unpack_probe_time,
)
from flumekit.waves.steady import reflection_settling
from flumekit.waves.stream_function import nonlinear_wavenumbers
from flumekit.waves.theory import G, energy_flux


@doc
def analyse_run(eta, depth: float, period: float, x_ref: float = 0.0, *,
                x=None, sampling_rate: float | None = None, method: str = "mansard_funke",
                separation_probes=None, n_harmonics: int = 8,
                bound_harmonics: bool = True, amplitude_dispersion: bool = True,
                tolerance: float = 0.02, min_cycles: int = 10,
                noise_factor: float = 4.0, reflection_tolerance: float = 0.002,
                max_condition: float = MAX_CONDITION, g: float = G) -> xr.Dataset:
    """Analyse the probe records of one regular-wave run.

    Parameters
    ----------
    eta : xarray.DataArray, pandas.DataFrame or array_like
        Calibrated surface elevation [m], dims ("probe", "time"), coordinate ``x`` [m] on
        ``probe``, ``time`` [s] since the start of the record (uniform sampling); or a
        DataFrame (one column per probe) or an array (probe, time) with ``x`` and
        ``sampling_rate`` (:func:`flumekit.waves.probe_record`).
    %(depth)s
    period : float
        Target wave period [s] (used to merge noisy zero crossings closer than 0.75 T and as
        the starting guess; the analysis uses the measured period).
    x_ref : float
        Position where the incident and reflected waves are returned [m] (the flap hinge,
        x = 0, for the comparison with the flap).
    %(probe_positions)s
    %(sampling_rate_eta)s
    method : str
        Separation method (see :func:`flumekit.waves.separate`).
    separation_probes : sequence of str, optional
        Names of the probes used for the separation; default all.
    n_harmonics : int
        Harmonics of the measured frequency included in the analysis band [-]. The crest-to-
        trough height of the flume's steepest waves needs about 8: at T = 3.5 s, H = 0.25 m in
        0.825 m the harmonics beyond the 4th still hold 1.5 % of H (stream-function theory).
    bound_harmonics : bool
        Solve harmonics n ≥ 2 as bound waves (wavenumber n k1).
    amplitude_dispersion : bool
        With ``bound_harmonics``: separate again with the nonlinear wavenumbers of the incident
        and the reflected wave, each the stream-function wave
        (:func:`flumekit.waves.stream_function.stream_function_wave`, zero mean mass transport
        as in a closed flume) of the height and period just separated (two passes). A steep
        wave is longer than linear theory says (3 % at T = 3.5 s, H = 0.25 m), which the
        linear wavenumber turns into an error of Kr (0.18 instead of 0.20 there).
    tolerance : float
        Quasi-steady criterion: relative deviation of each cycle's crest from the
        amplitude scale (Brito et al. 2020, §2.5: 2 %).
    min_cycles : int
        Fewest whole periods the common quasi-steady window must hold [-].
    noise_factor : float
        The noise-aware criterion: each probe's tolerance raised to ``noise_factor`` times the
        robust relative scatter of its crests (:func:`flumekit.signal.quasi_steady_window`).
        It replaces the paper's when that keeps fewer than ``min_cycles`` common periods or
        fewer than 80 % of the noise-aware window's (on a noisy record the paper's 2 % is the
        noise level and rejects steady cycles at random); 0 applies the paper's alone [-].
        The criterion kept is the ``steady_criterion`` attribute, the tolerance applied
        ``steady_tolerance``; a window holding fewer than half of the periods that follow its
        start is a :class:`~flumekit.waves.SeparationWarning`.
    reflection_tolerance : float
        Within the crests' window, the separated first-harmonic reflection must have settled
        too: the analysis window is the longest run of blocks of whole periods whose complex
        reflection coefficient lies within this tolerance (or ``noise_factor`` times the blocks'
        scatter, if larger) of its settled value (:func:`flumekit.waves.steady.
        reflection_settling`; a beach's wave returning through the device after the crests
        have settled is what it catches). Where fewer than ``min_cycles`` settled periods
        remain, or R still changes by more than 5 times this across them (a drift that widens
        the scatter), the crests' window is kept with a
        :class:`~flumekit.waves.SeparationWarning` that states the change. 0 skips the test [-].
    max_condition : float
        Largest condition number of the separation accepted per bin [-].
    %(g)s

    Returns
    -------
    xarray.Dataset
        ``eta`` (probe, time): the input records (for figures 5a and 6a);
        ``eta_incident``, ``eta_reflected`` (time): separated at ``x_ref`` from the steady
        window cut to a whole number of periods; NaN (documented fill) outside that window,
        where a regular-wave separation is not defined (ramp-up, reflections still arriving);
        ``amplitude_scale``, ``measured_height`` (probe): per-probe quasi-steady statistics;
        scalars ``steady_start``, ``steady_end`` [s] (the analysis window: every probe
        quasi-steady and the reflection settled), ``crest_steady_start`` [s] (where every
        probe's crests are quasi-steady, the paper's criterion), ``reflection_drift`` [-]
        (the largest change of the reflection outside the window), ``steady_cycles``,
        ``measured_period`` [s] and, from the separation of that window cut to a whole number
        of periods, ``reflection_coefficient`` (first
        harmonic), ``incident_height`` / ``reflected_height`` (crest-to-trough of the separated
        harmonic waves), ``incident_amplitude``, ``incident_phase``, ``energy_flux`` (Eq. A2 per
        metre of crest with H = 2 a1), ``masked_energy_fraction``; harmonic-resolved amplitudes
        and spectra over ``harmonic`` and ``frequency``.

    Raises
    ------
    ValueError
        A non-positive period, no harmonics, or quasi-steady windows of the probes that overlap
        over fewer than ``min_cycles`` periods (the message lists each probe's window).

    Examples
    --------
    A 2 s wave of height 0.08 m in 0.825 m, reflected with Kr = 0.3, recorded for 60 s at
    20 Hz by three probes at the spacings of :func:`~flumekit.waves.probe_spacing`, 4 m in
    front of the flap; the energy flux is E c_g of the separated incident height:

    >>> import numpy as np
    >>> from flumekit.waves import analyse_run, energy_flux, probe_spacing, wavenumber
    >>> x12, x23 = probe_spacing(2.0, 0.825)
    >>> x = np.array([-4.0, -4.0 + x12, -4.0 + x12 + x23])  # [m]
    >>> omega = 2 * np.pi / 2.0
    >>> k, t = float(wavenumber(omega, 0.825)), np.arange(1200) / 20.0
    >>> eta = (0.04 * np.cos(omega * t - k * x[:, None])
    ...        + 0.012 * np.cos(omega * t + k * x[:, None]))
    >>> ds = analyse_run(eta, 0.825, 2.0, x=x, sampling_rate=20.0)
    >>> round(float(ds.reflection_coefficient), 3), round(float(ds.incident_height), 3)
    (0.3, 0.08)
    >>> float(ds.measured_period), int(ds.steady_cycles)
    (2.0, 27)
    >>> round(float(ds.energy_flux), 1), round(float(energy_flux(0.08, 2.0, 0.825)), 1)
    (14.6, 14.6)
    >>> ds.eta_incident.dims, ds.incident_harmonic_amplitude.dims
    (('time',), ('harmonic',))
    """
    if x is not None or sampling_rate is not None or not isinstance(eta, xr.DataArray):
        eta = probe_record(eta, x=x, sampling_rate=sampling_rate)
    rec = _steady_record(ProbeArrays(*unpack_probe_time(eta)), depth, period,
                         separation_probes=separation_probes, n_harmonics=n_harmonics,
                         tolerance=tolerance, min_cycles=min_cycles,
                         noise_factor=noise_factor, reflection_tolerance=reflection_tolerance,
                         g=g)
    v, t, x = rec.values, rec.time, rec.x
    windows, criterion, t_meas, n_per = rec.windows, rec.criterion, rec.period, rec.cycles
    i0, n, dt = rec.start, rec.samples, rec.step
    crest_start, settling = rec.crest_start, rec.settling
    parts = _separation_passes([rec], [depth], method=method, x_ref=x_ref,
                               bound_harmonics=bound_harmonics,
                               amplitude_dispersion=amplitude_dispersion,
                               max_condition=max_condition, g=g)[0]
    if isinstance(parts, ValueError):
        raise parts
    steady = separation_dataset(parts)
    # separated series on the full time axis, defined (not NaN) over the steady window only
    inc = np.full(t.size, np.nan)
    ref = np.full(t.size, np.nan)
    inc[i0:i0 + n] = steady.eta_incident.values
    ref[i0:i0 + n] = steady.eta_reflected.values
    fill = {"comment": "NaN outside the quasi-steady window [steady_start, steady_end), where "
                       "the regular-wave separation is not defined"}

    h_lin = 2.0 * float(steady.incident_amplitude)
    ds = xr.Dataset(
        {"eta": (("probe", "time"), v),
         "eta_incident": ("time", inc, fill), "eta_reflected": ("time", ref, fill),
         "amplitude_scale": ("probe", [w.amplitude_scale for w in windows]),
         "steady_tolerance": ("probe", [w.tolerance for w in windows],
                              {"criterion": criterion}),
         "measured_height": ("probe", [w.height for w in windows]),
         "steady_start": ((), float(t[i0])), "steady_end": ((), float(t[i0 + n - 1] + dt)),
         "crest_steady_start": ((), float(crest_start)),
         "reflection_drift": ((), settling.drift, {"tolerance": settling.tolerance}),
         "steady_cycles": ((), n_per), "measured_period": ((), t_meas),
         "energy_flux": ((), float(energy_flux(h_lin, t_meas, depth, g=g)),
                         {"definition": "Eq. (A2) of Brito et al. 2020 per unit crest width, "
                                        "H = 2 a1 (first-harmonic incident height)"}),
         **{name: steady[name] for name in (
             "reflection_coefficient", "incident_height", "reflected_height",
             "incident_amplitude", "incident_phase", "masked_energy_fraction",
             "incident_harmonic_amplitude", "reflected_harmonic_amplitude",
             "harmonic_reflection_coefficient", "spectrum_incident", "spectrum_reflected",
             "condition_number", "masked")}},
        coords={"probe": eta.probe.values, "x": ("probe", x), "time": t,
                "frequency": steady.frequency.values, "harmonic": steady.harmonic.values},
        attrs={"method": method, "x_ref": float(x_ref), "depth": float(depth),
               "wave_period": float(period), "separation_probes": steady.attrs["probes"],
               "n_harmonics": n_harmonics, "bound_harmonics": int(bound_harmonics),
               "amplitude_dispersion": int(amplitude_dispersion and bound_harmonics),
               "fundamental_wavenumbers": steady.attrs["fundamental_wavenumbers"],
               "tolerance": tolerance, "min_cycles": min_cycles,
               "noise_factor": noise_factor, "steady_criterion": criterion,
               "reflection_tolerance": reflection_tolerance,
               "band": steady.attrs["band"],
               "max_condition": max_condition})
    return conventions.annotate(ds)


#: the scalar results of :func:`variant_results`
VARIANT_RESULTS = ("incident_height", "reflected_height", "reflection_coefficient",
                   "incident_amplitude", "measured_period", "energy_flux")


@doc
def variant_results(etas, depths, period: float, x_ref: float = 0.0, *,
                    method: str = "mansard_funke", separation_probes=None,
                    n_harmonics: int = 8, bound_harmonics: bool = True,
                    amplitude_dispersion: bool = True, tolerance: float = 0.02,
                    min_cycles: int = 10, noise_factor: float = 4.0,
                    reflection_tolerance: float = 0.002,
                    max_condition: float = MAX_CONDITION, g: float = G) -> dict:
    """Return the scalar results of :func:`analyse_run` for many variants of one run at once.

    Each variant (a Monte Carlo draw of the run's records, probe positions and depth) is
    analysed exactly as :func:`analyse_run` analyses a run (its own quasi-steady window, the
    same separation passes), without the datasets: the reruns of an uncertainty propagation
    need these numbers only.

    Parameters
    ----------
    etas : sequence of xarray.DataArray or ProbeArrays
        The variants' calibrated surface elevations [m] (probe, time) with ``x`` [m], as
        DataArrays or as their arrays (:class:`ProbeArrays`, what a caller that perturbs the
        values of one record passes without building a DataArray per variant).
    depths : sequence of float
        Still water depth of each variant [m].
    %(target_period)s
    x_ref : float
        Position where the incident and reflected waves are returned [m].
    method, separation_probes, n_harmonics, bound_harmonics, amplitude_dispersion
        As in :func:`analyse_run`.
    tolerance, min_cycles, noise_factor, reflection_tolerance, max_condition
        As in :func:`analyse_run` ([-]).
    %(g)s

    Returns
    -------
    dict of str to numpy.ndarray
        :data:`VARIANT_RESULTS` -> one value per variant (units of :func:`analyse_run`), NaN
        for a variant the analysis refuses (a ValueError of :func:`analyse_run`).

    Examples
    --------
    >>> import numpy as np
    >>> import xarray as xr
    >>> from flumekit.waves.analysis import variant_results
    >>> from flumekit.waves.theory import wavenumber
    >>> t = np.arange(4000) / 20.0
    >>> x = np.array([-3.0, -2.4, -2.1])
    >>> k = wavenumber(2 * np.pi / 2.0, 0.5)
    >>> v = 0.05 * np.cos(np.pi * t - k * x[:, None])
    >>> eta = xr.DataArray(v, dims=("probe", "time"),
    ...                    coords={"probe": ["a", "b", "c"], "x": ("probe", x), "time": t})
    >>> r = variant_results([eta, 1.01 * eta], [0.5, 0.5], 2.0)
    >>> np.round(r["incident_height"], 3).tolist()
    [0.1, 0.101]
    """
    recs, ok = [], []
    shared: dict = {}  # the probes' windows of records that several variants share
    for eta, depth in zip(etas, depths, strict=True):
        if not isinstance(eta, ProbeArrays):
            eta = ProbeArrays(*unpack_probe_time(eta if isinstance(eta, xr.DataArray)
                                                 else probe_record(eta)))
        try:
            recs.append(_steady_record(eta, depth, period,
                                       separation_probes=separation_probes,
                                       n_harmonics=n_harmonics, tolerance=tolerance,
                                       min_cycles=min_cycles, noise_factor=noise_factor,
                                       reflection_tolerance=reflection_tolerance, g=g,
                                       probe_windows=shared))
            ok.append(True)
        except ValueError:
            recs.append(None)
            ok.append(False)
    idx = [i for i in range(len(recs)) if ok[i]]
    parts = _separation_passes([recs[i] for i in idx], [depths[i] for i in idx], method=method,
                               x_ref=x_ref, bound_harmonics=bound_harmonics,
                               amplitude_dispersion=amplitude_dispersion,
                               max_condition=max_condition, g=g, elevations=False)
    out = {k: np.full(len(recs), np.nan) for k in VARIANT_RESULTS}
    for i, part in zip(idx, parts, strict=True):
        if isinstance(part, ValueError):
            continue
        data, t_meas, depth = part[0], recs[i].period, depths[i]
        for k in ("incident_height", "reflected_height", "reflection_coefficient",
                  "incident_amplitude"):
            out[k][i] = float(data[k][1])
        out["measured_period"][i] = t_meas
        out["energy_flux"][i] = float(energy_flux(2.0 * float(data["incident_amplitude"][1]),
                                                  t_meas, depth, g=g))
    return out


class ProbeArrays(NamedTuple):
    """A run's probe records as arrays: what the waves analysis reads of their DataArray.

    ``values`` (probe, time) [m], NaN where quality control masked; ``time`` [s]; ``x`` the
    probe positions [m]; ``probes`` the probe labels
    (:func:`flumekit.waves.separation.unpack_probe_time`).

    Parameters
    ----------
    values : numpy.ndarray
        Elevation [m], shape (probe, time).
    time : numpy.ndarray
        Time [s], uniform.
    x : numpy.ndarray
        Probe positions [m].
    probes : list
        Probe labels.
    """

    values: np.ndarray
    time: np.ndarray
    x: np.ndarray
    probes: list


class _SteadyRecord(NamedTuple):
    """A run's records checked, and the quasi-steady window the separation analyses."""

    values: np.ndarray  # the records (probe, time) [m], NaN where quality control masked
    time: np.ndarray  # [s]
    x: np.ndarray  # probe positions [m]
    windows: list  # each probe's quasi-steady window (signal.quasi_steady_window)
    criterion: str  # the criterion kept
    period: float  # measured period [s]
    cycles: int  # whole periods of the window
    start: int  # first sample of the window
    samples: int  # samples of the window
    step: float  # sampling step [s]
    steady: ProbeArrays  # the separation probes' records over the window [m]
    band: tuple  # the separation's band [Hz]
    crest_start: float  # where every probe's crests are quasi-steady [s]
    settling: object  # the reflection's settling (waves.steady.reflection_settling)


def _steady_record(rec: ProbeArrays, depth: float, period: float, *, separation_probes=None,
                   n_harmonics: int = 8, tolerance: float = 0.02, min_cycles: int = 10,
                   noise_factor: float = 4.0, reflection_tolerance: float = 0.002,
                   g: float = G, probe_windows: dict | None = None) -> _SteadyRecord:
    """Check a run's records and find the window the separation analyses (:func:`analyse_run`).

    ``probe_windows``: a dict that keeps :func:`_probe_windows` of each records' arrays (by
    identity) for the next variant of the same records (other probe positions, another depth).
    """
    v, t, x, probes = rec
    # samples masked by quality control (NaN) may remain: the cycles holding them fail the
    # quasi-steady test below, so the window avoids them, and `separate` checks the window
    check_probe_arrays(v, t, x, probes, masked=True)
    if not period > 0:
        raise ValueError(f"period must be positive, got {period}")
    if n_harmonics < 1:
        raise ValueError(f"n_harmonics must be at least 1, got {n_harmonics}")
    if separation_probes is None:
        sep = rec
    else:
        index = {p: i for i, p in enumerate(probes)}
        missing = [p for p in separation_probes if p not in index]
        if missing:
            raise KeyError(f"separation probes {missing} are not among the probes {probes}")
        rows = [index[p] for p in separation_probes]
        sep = ProbeArrays(v[rows], t, x[rows], list(separation_probes))
    known = None
    if probe_windows is not None:
        key = (id(v), id(t), tuple(probes))
        if key not in probe_windows:  # the arrays kept with them: their ids stay theirs
            probe_windows[key] = (v, t, _probe_windows(v, t, probes, period, tolerance,
                                                       noise_factor))
        known = probe_windows[key][2]
    found = _steady_window(v, t, probes, period, tolerance, min_cycles, noise_factor, sep,
                           depth, reflection_tolerance, g, probe_windows=known)
    windows, criterion, t_meas, n_per, i0, n, dt, crest_start, settling = found
    f1 = 1.0 / t_meas
    band = (0.5 * f1, min((n_harmonics + 0.5) * f1, 0.5 / dt * (1 - 1e-9)))
    steady = ProbeArrays(sep.values[:, i0:i0 + n], t[i0:i0 + n], sep.x, sep.probes)
    return _SteadyRecord(v, t, x, windows, criterion, t_meas, n_per, i0, n, dt, steady, band,
                         crest_start, settling)


def _probe_windows(v: np.ndarray, t: np.ndarray, probes: list, period: float,
                   tolerance: float, noise_factor: float) -> tuple[dict, ValueError | None]:
    """Return each probe's quasi-steady window under each criterion (:func:`_steady_window`).

    What the records alone and the period determine (not the probe positions nor the depth):
    criterion -> (the windows, their common start and end [s], the mean period [s], the whole
    periods between), and the last criterion's failure (a ValueError naming the probe).
    """
    criteria = [("tolerance", 0.0)] + ([("crest noise", noise_factor)] if noise_factor > 0
                                       else [])
    found: dict[str, tuple] = {}
    failure = None
    # each probe's cycles, the same for both criteria
    split = [cycles(v[p], t, min_period=0.75 * period) for p in range(v.shape[0])]
    for criterion, factor in criteria:
        try:
            windows = []
            for p in range(v.shape[0]):  # a handful of probes
                try:
                    windows.append(quasi_steady_window(v[p], t, tolerance=tolerance,
                                                       min_period=0.75 * period,
                                                       noise_factor=factor,
                                                       zero_cycles=split[p]))
                except ValueError as e:  # name the probe (a dead probe, a short record)
                    raise ValueError(f"probe {probes[p]}: {e}") from None
        except ValueError as e:
            failure = e
            continue
        start = max(w.start for w in windows)
        end = min(w.end for w in windows)
        t_meas = float(np.mean([w.period for w in windows]))
        n_per = int(np.floor((end - start) / t_meas + 1e-9))
        found[criterion] = (windows, start, end, t_meas, n_per)
    return found, failure


def _steady_window(v: np.ndarray, t: np.ndarray, probes: list, period: float,
                   tolerance: float, min_cycles: int, noise_factor: float, sep: ProbeArrays,
                   depth: float, reflection_tolerance: float, g: float,
                   probe_windows: tuple | None = None):
    """Return the common quasi-steady window of the probes (see :func:`analyse_run`).

    The probes' windows, the criterion kept, the measured period [s], the whole periods, the
    first sample and the samples of the window cut to them, the sampling step [s], where the
    crests' window starts [s] and the reflection's settling. ``probe_windows``: those of
    :func:`_probe_windows` when the caller has them (variants that share the records).
    """
    # quasi-steady window of every probe (Brito et al. 2020, §2.5): the paper's criterion first;
    # where the crest noise defeats it, the noise-aware tolerance (signal.quasi_steady_window)
    # The noise-aware criterion is also the measure of what follows the ramp: the paper's is
    # kept unless it keeps fewer than 80 % of those cycles (its 2 % is then the noise level
    # and it rejects steady cycles at random).
    if probe_windows is None:
        probe_windows = _probe_windows(v, t, probes, period, tolerance, noise_factor)
    found, failure = probe_windows
    if not found:
        raise failure
    enough = max(min_cycles, 2)
    paper, noisy = found.get("tolerance"), found.get("crest noise")
    if paper is not None and paper[4] >= enough and (noisy is None
                                                      or paper[4] >= 0.8 * noisy[4]):
        criterion = "tolerance"
    elif noisy is not None and noisy[4] >= enough:
        criterion = "crest noise"
    else:
        criterion = "tolerance" if noisy is None else "crest noise"
    windows, start, end, t_meas, n_per = found[criterion]
    # what follows the ramp: whole periods from the first cycle every probe has within the
    # tolerance (the end of the ramp) to the end of the record
    # the separated reflection settled too (waves.steady): a wave returning from behind the
    # device after the crests have settled changes Kr but no crest by the tolerance
    crest_start = start
    settling = reflection_settling(sep.values, t, sep.x, t_meas, depth, start, end,
                                   tolerance=reflection_tolerance, noise_factor=noise_factor,
                                   g=g)
    n_settled = int(np.floor((settling.end - settling.start) / t_meas + 1e-9))
    if n_settled >= enough and not settling.trend > 5.0 * reflection_tolerance:
        start, end, n_per = settling.start, min(end, settling.end), n_settled
    elif reflection_tolerance > 0:
        change = max(settling.drift, 0.0 if np.isnan(settling.trend) else settling.trend)
        warnings.warn(f"the separated reflection does not settle within the quasi-steady window "
                      f"({start:.1f}-{end:.1f} s): it changes by {change:.3f} (tolerance "
                      f"{settling.tolerance:.3f}; {n_settled} settled periods, {enough} needed, "
                      f"a trend of at most {5.0 * reflection_tolerance:.3f} across them); Kr is "
                      "the mean of a changing reflection (a wave still returning from behind "
                      "the device, a seiche): check the record or lengthen it",
                      SeparationWarning, stacklevel=4)
    settled = max(w.settled for w in windows)
    following = int(np.floor((t[-1] - settled) / t_meas + 1e-9))
    if n_per >= enough and 2 * n_per < following:
        warnings.warn(f"the quasi-steady window ({criterion} criterion) keeps {n_per} of the "
                      f"{following} periods that follow the ramp ({settled:.1f} s to the end of "
                      "the record): crests scatter beyond the tolerance after it (a disturbance, "
                      "a dropout, re-reflection); check the record or the window",
                      SeparationWarning, stacklevel=4)
    if n_per < enough:
        raise ValueError(
            f"the probes' quasi-steady windows overlap over {max(end - start, 0):.3g} s, fewer "
            f"than {max(min_cycles, 2)} periods of {t_meas:.3g} s (windows: "
            + ", ".join(f"{p}: {w.start:.1f}-{w.end:.1f} s"
                        for p, w in zip(probes, windows, strict=True))
            + (f"; crest tolerance up to {max(w.tolerance for w in windows):.1%}"
               f" with noise_factor = {noise_factor:g}" if noise_factor > 0 else "")
            + ")")
    dt = (t[-1] - t[0]) / (t.size - 1)
    i0 = int(np.ceil((start - t[0]) / dt - 1e-9))
    # whole number of periods spanning (nearly) a whole number of samples: of the last ten
    # candidate counts keep the one with the smallest sample misfit (less spectral leakage)
    cand = np.arange(max(2, n_per - 9), n_per + 1)
    misfit = np.abs(cand * t_meas / dt - np.rint(cand * t_meas / dt))
    n_per = int(cand[misfit <= misfit.min() + 0.02][-1])  # the longest of the best
    n = min(int(round(n_per * t_meas / dt)), t.size - i0)
    return windows, criterion, t_meas, n_per, i0, n, dt, crest_start, settling


def _separation_passes(records: list, depths: list, *, method: str, x_ref: float,
                       bound_harmonics: bool, amplitude_dispersion: bool,
                       max_condition: float, g: float, elevations: bool = True) -> list:
    """Separate the steady windows of runs (or of draws of one run) as :func:`analyse_run` does.

    The first pass with the linear wavenumbers; with ``amplitude_dispersion`` and
    ``bound_harmonics`` two more with the nonlinear wavenumbers of the heights just separated.
    The record's Fourier coefficients and harmonic fit are shared by the passes.

    Parameters
    ----------
    records : list of _SteadyRecord
        The runs' steady windows (:func:`_steady_record`).
    depths : list of float
        Still water depth of each [m].
    method, x_ref, bound_harmonics, amplitude_dispersion, max_condition, g
        As in :func:`analyse_run`.
    elevations : bool
        Whether the separated elevations are synthesised (the scalar results need them not).

    Returns
    -------
    list
        Per record the parts of its separation's dataset
        (:func:`flumekit.waves.separation.separate_prepared`), or the ValueError that refused
        it.
    """
    kw = dict(regular=True, bound_harmonics=bound_harmonics, window=None,
              max_condition=max_condition, warn_fraction=0.01, gauge_weights=None, g=g,
              detection="given", elevations=elevations)
    prepared, out = [], []
    for rec, depth in zip(records, depths, strict=True):
        try:
            v, t, x, probes = rec.steady
            check_separation_arrays(v, t, x, probes, depth, method, max_condition)
            p = prepare_separation(v, t, rec.band, None, True, rec.period)
            prepared.append((p, x, probes))
            out.append(separate_prepared(p, x, probes, depth, method, x_ref, wavenumbers=None,
                                          **kw))
        except ValueError as e:
            prepared.append(None)
            out.append(e)
    if not (amplitude_dispersion and bound_harmonics):
        return out
    active = [i for i, o in enumerate(out) if not isinstance(o, ValueError)]
    for _ in range(2):  # the heights move k by < 1e-3 after the first pass
        still = []
        # the incident and reflected waves of every record, solved together
        waves = [(records[i].period, float(out[i][0][h][1]), depths[i])
                 for i in active for h in ("incident_height", "reflected_height")]
        solved = nonlinear_wavenumbers(*zip(*waves), g=g) if waves else []
        for j, i in enumerate(active):
            ks = solved[2 * j:2 * j + 2]
            refused = [k for k in ks if isinstance(k, ValueError)]
            if refused:  # beyond the highest steady wave: keep the linear k
                warnings.warn(f"separation with the linear wavenumber: {refused[0]}",
                              SeparationWarning, stacklevel=3)
                continue
            p, x, probes = prepared[i]
            try:
                out[i] = separate_prepared(p, x, probes, depths[i], method, x_ref,
                                            wavenumbers=ks, **kw)
                still.append(i)
            except ValueError as e:
                out[i] = e
        active = still
    return out
