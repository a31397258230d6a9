"""Metadata checked against the records.

The declared period and height, the calibration quality and dead channels. Each check raises
:class:`~flumekit.errors.InputError` naming the file and the key or channel, or returns a
warning (text) where a user may knowingly proceed.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from flumekit.docstrings import filler
from flumekit.errors import InputError

#: docstring text that several functions of this module share
_doc = filler(
    returns_warning=("Returns\n"
                     "-------\n"
                     "str or None\n"
                     "    The warning, or None."),
    run_file=("run_file : pathlib.Path\n"
              "    The run.toml, named in the message."),
    tolerance=("tolerance : float\n"
               "    Largest relative difference accepted [-]."),
    refuse_tolerance=("tolerance : float\n"
                      "    Relative difference beyond which the run is refused [-]."),
    warning=("warning : float\n"
             "    Relative difference beyond which a warning is returned [-]."),
    what=("what : str\n"
          "    What was measured (e.g. \"incident height at the flap\")."))


@_doc
def dominant_period(x: np.ndarray, sampling_rate: float) -> float:
    """Return the period of the spectral peak of a record, its channels' spectra averaged.

    Each channel is detrended (mean removed) and Hann-windowed; the peak of the mean periodogram
    (bins above the lowest two) is refined by a parabola through the logarithm of the three
    bins around it (exact for a Gaussian peak, the Hann window's main lobe nearly is).
    Non-finite samples count as the channel's mean.

    Parameters
    ----------
    x : array_like
        Record, time along the last axis; 1-D (one channel) or (channel, time) [any unit].
    %(sampling_rate)s

    Returns
    -------
    float
        Period of the peak [s].

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.qc.checks import dominant_period
    >>> t = np.arange(2000) / 50.0
    >>> round(dominant_period(np.sin(2 * np.pi * t / 2.0), 50.0), 2)
    2.0
    """
    x = np.atleast_2d(np.asarray(x, dtype=float))
    x = np.where(np.isfinite(x), x, np.nan)
    x = x - np.nanmean(x, axis=-1, keepdims=True)
    x = np.nan_to_num(x)
    n = x.shape[-1]
    p = np.mean(np.abs(np.fft.rfft(x * np.hanning(n), axis=-1)) ** 2, axis=0)
    k = 2 + int(np.argmax(p[2:-1]))
    a, b, c = np.log(p[k - 1:k + 2] + 1e-300)
    den = a - 2 * b + c
    shift = 0.5 * (a - c) / den if den < 0 else 0.0
    f = (k + shift) * sampling_rate / n
    return float(1.0 / f)


@_doc
def check_period(declared: float, measured: float, tolerance: float, run_file: Path,
                 record: Path) -> None:
    """Refuse a run whose declared period differs from its record's dominant period.

    The period steers the analysis (cycle detection, separation band), so a wrong one gives
    wrong results silently (3.5 s declared on a 2 s record: Kr 0.82 instead of 0.2).

    Parameters
    ----------
    declared : float
        The period declared in run.toml [s].
    measured : float
        The dominant period of the record (:func:`dominant_period`) [s].
    %(tolerance)s
    %(run_file)s
    record : pathlib.Path
        The record the period was measured on, named in the message.

    Raises
    ------
    flumekit.errors.InputError
        When ``|measured / declared - 1|`` exceeds ``tolerance`` (or is NaN), on ``run.period``.
    """
    rel = abs(measured / declared - 1.0)
    if not rel <= tolerance:
        raise InputError(run_file, f"declared period {declared:g} s disagrees with the record: "
                         f"the dominant period of {record} is {measured:.3f} s "
                         f"({rel:.0%} off, tolerance {tolerance:.0%} "
                         "[stages.qc] period_tolerance)", field="run.period")


@_doc
def check_record_period(declared: float, periods: dict[str, float], tolerance: float,
                        record: Path, run_file: Path) -> None:
    """Refuse a record whose channels' dominant period is not the run's declared one.

    As :func:`check_period` does for the probes: a record of another run (a copied file, a
    ``[files]`` entry pointing into another run folder) would be analysed as this run's (a 3.5 s
    flap record in a 2.0 s run: capture factor 0.43 instead of 0.22).

    Parameters
    ----------
    declared : float
        The run's declared period [s].
    periods : dict of str to float
        Channel -> its dominant period (:func:`dominant_period`) [s].
    %(tolerance)s
    record : pathlib.Path
        The record, named as the file at fault.
    %(run_file)s

    Raises
    ------
    flumekit.errors.InputError
        Naming ``record`` and the channels whose period is off by more than ``tolerance``.
    """
    off = {k: p for k, p in periods.items() if not abs(p / declared - 1.0) <= tolerance}
    if off:
        raise InputError(record, "dominant period " + ", ".join(
            f"{p:.3f} s ({k})" for k, p in off.items()) + f", but {run_file} declares period "
            f"{declared:g} s, as the probes' records must (tolerance {tolerance:.0%}, "
            "[stages.qc] period_tolerance): a record of another run?")


def check_durations(durations: dict[str, float], files: dict[str, object], tolerance: float
                    ) -> None:
    """Refuse a run whose records differ in duration by more than ``tolerance``.

    One run's instruments record the same waves, so a record much shorter than the others was
    cut (a TDMS file truncated at a segment boundary reads without complaint) or is another
    run's.

    Parameters
    ----------
    durations : dict of str to float
        Instrument -> duration of its record [s].
    files : dict of str to object
        Instrument -> its file, named in the message.
    tolerance : float
        Largest shortfall accepted, as a fraction of the longest record [-].

    Raises
    ------
    flumekit.errors.InputError
        Naming the file of the shortest record among those more than ``tolerance`` shorter
        than the longest.
    """
    longest = max(durations.values())
    short = {k: d for k, d in durations.items() if d < (1.0 - tolerance) * longest}
    if short:
        k, d = min(short.items(), key=lambda kv: kv[1])
        other = ", ".join(f"{n} {v:.1f} s" for n, v in durations.items() if n != k)
        raise InputError(files[k], f"the {k} record lasts {d:.1f} s, the run's other records "
                         f"{other}: more than {tolerance:.0%} shorter (a file cut short, or "
                         "another run's record?)")


@_doc
def check_height(declared: float, measured: float, tolerance: float, warning: float,
                 run_file: Path, what: str) -> str | None:
    """Check a declared wave height against the measured one.

    :func:`check_declared` for the key ``height`` [m], tolerance from the ``[stages.waves]``
    parameter ``height_tolerance``.

    Parameters
    ----------
    declared : float
        The height declared in run.toml [m].
    measured : float
        The measured height [m].
    %(refuse_tolerance)s
    %(warning)s
    %(run_file)s
    %(what)s

    %(returns_warning)s

    Raises
    ------
    flumekit.errors.InputError
        Beyond ``tolerance``, on ``run.height``.
    """
    return check_declared("height", declared, measured, "m", tolerance, warning, run_file,
                          what, "height_tolerance")


@_doc
def check_declared(key: str, declared: float, measured: float, unit: str, tolerance: float,
                   warning: float, run_file: Path, what: str, parameter: str) -> str | None:
    """Check a declared run value against the measured one.

    An error beyond ``tolerance``, a warning (returned text) beyond ``warning`` (relative
    differences ``|measured / declared - 1|``).

    Parameters
    ----------
    key : str
        The key of ``[run]`` in run.toml (``height``, ``hm0``, ``tp``, ``te``).
    declared : float
        The declared value [``unit``].
    measured : float
        The measured value [``unit``].
    unit : str
        Their unit, for the message.
    %(refuse_tolerance)s
    %(warning)s
    %(run_file)s
    %(what)s
    parameter : str
        The ``[stages.waves]`` parameter holding ``tolerance``.

    %(returns_warning)s

    Raises
    ------
    flumekit.errors.InputError
        Beyond ``tolerance`` (or for a NaN difference), on ``run.<key>``.

    Examples
    --------
    >>> from pathlib import Path
    >>> from flumekit.qc.checks import check_declared
    >>> check_declared("height", 0.10, 0.104, "m", 0.25, 0.10, Path("run.toml"), "height", "t")
    >>> check_declared("height", 0.10, 0.115, "m", 0.25, 0.10, Path("run.toml"), "height", "t")
    'run.toml: run.height: declared height 0.1 m differs from the measured height 0.115 m by 15%'
    """
    rel = abs(measured / declared - 1.0)
    msg = (f"declared {key} {declared:g} {unit} differs from the measured {what} "
           f"{measured:.4g} {unit} by {rel:.0%}")
    if not rel <= tolerance:
        raise InputError(run_file, f"{msg}, more than the tolerance {tolerance:.0%} "
                         f"([stages.waves] {parameter})", field=f"run.{key}")
    if rel > warning:
        return f"{run_file}: run.{key}: {msg}"
    return None


@_doc
def check_kind(kind: str, peak_frequency: float, share: float, regular_fraction: float,
               run_file: Path, record: Path) -> None:
    """Refuse records that contradict the run's declared kind.

    A regular run whose records are an irregular sea, or an irregular run whose records are a
    regular wave train. The detection is the one :func:`flumekit.waves.separate` uses: a record
    holding at least ``regular_fraction`` of its variance at its peak frequency and the harmonics
    of it (:func:`flumekit.waves.harmonic_energy_fraction`) is regular. Analysed as the other
    kind, a record gives a confident wrong answer (an irregular sea read as a regular wave: the
    first-harmonic Kr of one random bin).

    Parameters
    ----------
    kind : str
        The declared kind ("waves", "uvp": regular; "irregular").
    peak_frequency : float
        The records' peak frequency [Hz].
    share : float
        Their share of variance at the peak and its harmonics [-].
    regular_fraction : float
        The share from which a record is regular [-]
        (:data:`flumekit.waves.REGULAR_FRACTION`).
    %(run_file)s
    record : pathlib.Path
        The probe file, named in the message.

    Raises
    ------
    flumekit.errors.InputError
        On ``run.kind`` when the declared kind and the records disagree.
    """
    regular = share >= regular_fraction
    looks = (f"{share:.1%} of the variance of {record} lies at its peak {peak_frequency:.4g} Hz "
             f"(T = {1 / peak_frequency:.4g} s) and the harmonics of it (a regular wave train "
             f"holds {regular_fraction:.0%} or more)")
    if kind == "irregular" and regular:
        raise InputError(run_file, f"the run is declared irregular, but its record is a "
                         f"regular wave train: {looks}. Declare kind = \"waves\" with its "
                         "period (and height), or check the probe file", field="run.kind")
    if kind != "irregular" and not regular:
        raise InputError(run_file, f"the run is declared regular (kind = \"{kind}\"), but its "
                         f"record is an irregular sea: only {looks}. Declare kind = "
                         "\"irregular\" with hm0 and tp (or te) instead of period, or check the "
                         "probe file", field="run.kind")


def check_calibration(r2: np.ndarray, monotonic: np.ndarray, probes, path: Path,
                      min_r2: float, warn_r2: float) -> list[str]:
    """Refuse a probe calibration that does not describe the probes; warn about a poor one.

    Parameters
    ----------
    r2 : numpy.ndarray
        Coefficient of determination of each probe's calibration fit [-].
    monotonic : numpy.ndarray
        Whether each probe's fitted polynomial is monotonic over the calibrated voltages (bool).
    probes : sequence of str
        Probe names, in the order of ``r2``.
    path : pathlib.Path
        The calibration file, named in the message.
    min_r2 : float
        R² below which a fit is refused [-] (``[stages.calibration] min_r2``).
    warn_r2 : float
        R² below which a warning is returned [-].

    Returns
    -------
    list of str
        One warning per probe whose R² is below ``warn_r2``.

    Raises
    ------
    flumekit.errors.InputError
        Naming ``path`` and every probe whose R² is below ``min_r2`` or whose polynomial is not
        monotonic (a voltage would map to two levels).
    """
    errors = [f"probe {p}: calibration R² = {r:.4f} is below {min_r2:g} "
              "([stages.calibration] min_r2): the fit does not describe the probe"
              for p, r in zip(probes, r2, strict=True) if not r >= min_r2]
    errors += [f"probe {p}: calibration polynomial is not monotonic over the calibrated "
               "voltages (a voltage would map to two levels)"
               for p, m in zip(probes, monotonic, strict=True) if not m]
    if errors:
        raise InputError(path, "; ".join(errors))
    return [f"{path}: probe {p}: calibration R² = {r:.5f} < {warn_r2:g}"
            for p, r in zip(probes, r2, strict=True) if r < warn_r2]


def check_alive(x: np.ndarray, channels, path: Path, flat_fraction: np.ndarray | None = None,
                max_flat_fraction: float = 0.5, unit: str = "",
                noise_fraction: np.ndarray | None = None) -> None:
    """Refuse a record with dead, stuck or noise channels.

    Dead: constant over the whole record (or without a finite sample); stuck: flat lines over
    more than ``max_flat_fraction`` of the record; noise: failing the noise test
    (:func:`flumekit.qc.qartod.noise_test`) over more than that fraction.

    Parameters
    ----------
    x : array_like
        Record, (channel, time) or 1-D [any unit].
    channels : sequence of str
        Channel names, in the order of ``x``.
    path : pathlib.Path
        The record's file, named in the message.
    flat_fraction : numpy.ndarray, optional
        Fraction of each channel's record in flat lines [-]; None: not checked.
    max_flat_fraction : float
        Largest fraction of flat line or noise accepted [-].
    unit : str
        Unit of ``x``, for the message.
    noise_fraction : numpy.ndarray, optional
        Fraction of each channel's record failing the noise test [-]; None: not checked.

    Raises
    ------
    flumekit.errors.InputError
        Naming ``path`` and every channel at fault.
    """
    x = np.atleast_2d(np.asarray(x, dtype=float))
    problems = []
    for i, name in enumerate(channels):
        v = x[i][np.isfinite(x[i])]
        if v.size == 0:
            problems.append(f"channel '{name}' has no finite sample")
        elif np.ptp(v) == 0:
            problems.append(f"channel '{name}' is dead: constant at {v[0]:g}{unit} over the "
                            "whole record")
        elif flat_fraction is not None and flat_fraction[i] > max_flat_fraction:
            problems.append(f"channel '{name}' is stuck: flat lines over "
                            f"{flat_fraction[i]:.0%} of the record")
        elif noise_fraction is not None and noise_fraction[i] > max_flat_fraction:
            v = v - v.mean()
            r1 = float(np.dot(v[1:], v[:-1]) / np.dot(v, v))
            problems.append(f"channel '{name}' is noise, not a signal: {noise_fraction[i]:.0%}"
                            f" of the record fails the noise test (lag-one autocorrelation "
                            f"{r1:.2f} over the record; a wave record sampled far above its "
                            "band has nearly 1): a broken or disconnected sensor, or "
                            "interference?")
    if problems:
        raise InputError(path, "; ".join(problems))
