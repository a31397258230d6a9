"""Metadata checked against the records: declared period and height, calibration quality,
dead channels. Each check raises :class:`~flumekit.errors.InputError` naming the file and the
key or channel, or returns a warning (text) where a user may knowingly proceed."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from flumekit.errors import InputError


def dominant_period(x: np.ndarray, sampling_rate: float) -> float:
    """Period of the spectral peak of a (channel, time) record, channels' spectra averaged [s].

    Each channel is detrended (mean removed) and Hann-windowed; the peak of the mean periodogram
    (bins above the lowest two) is refined by a parabola through the logarithm of the three
    bins around it (exact for a Gaussian peak, the Hann window's main lobe nearly is).
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


def check_period(declared: float, measured: float, tolerance: float, run_file: Path,
                 record: Path) -> None:
    """Error when the declared period differs from the record's by more than ``tolerance``
    (relative). The period steers the analysis (cycle detection, separation band), so a wrong
    one gives wrong results silently (3.5 s declared on a 2 s record: Kr 0.82 instead of 0.2)."""
    rel = abs(measured / declared - 1.0)
    if not rel <= tolerance:
        raise InputError(run_file, f"declared period {declared:g} s disagrees with the record: "
                         f"the dominant period of {record} is {measured:.3f} s "
                         f"({rel:.0%} off, tolerance {tolerance:.0%} "
                         "[stages.qc] period_tolerance)", field="run.period")


def check_record_period(declared: float, periods: dict[str, float], tolerance: float,
                        record: Path, run_file: Path) -> None:
    """Error naming ``record`` when the dominant period of any of its channels (``periods``:
    channel -> period [s], :func:`dominant_period`) differs from the run's declared period by
    more than ``tolerance`` (relative), as :func:`check_period` does for the probes: a record
    of another run (a copied file, a [files] entry pointing into another run folder) would be
    analysed as this run's (a 3.5 s flap record in a 2.0 s run: capture factor 0.43 instead of
    0.22)."""
    off = {k: p for k, p in periods.items() if not abs(p / declared - 1.0) <= tolerance}
    if off:
        raise InputError(record, "dominant period " + ", ".join(
            f"{p:.3f} s ({k})" for k, p in off.items()) + f", but {run_file} declares period "
            f"{declared:g} s, as the probes' records must (tolerance {tolerance:.0%}, "
            "[stages.qc] period_tolerance): a record of another run?")


def check_durations(durations: dict[str, float], files: dict[str, object], tolerance: float
                    ) -> None:
    """Error naming the shorter record when a run's records (``durations``: instrument ->
    duration [s], ``files``: instrument -> its file, for the message) differ in duration by more
    than ``tolerance`` of the longer one: one run's instruments record the same waves, so a
    record much shorter than the others was cut (a TDMS file truncated at a segment boundary
    reads without complaint) or is another run's."""
    longest = max(durations.values())
    short = {k: d for k, d in durations.items() if d < (1.0 - tolerance) * longest}
    if short:
        k, d = min(short.items(), key=lambda kv: kv[1])
        other = ", ".join(f"{n} {v:.1f} s" for n, v in durations.items() if n != k)
        raise InputError(files[k], f"the {k} record lasts {d:.1f} s, the run's other records "
                         f"{other}: more than {tolerance:.0%} shorter (a file cut short, or "
                         "another run's record?)")


def check_height(declared: float, measured: float, tolerance: float, warning: float,
                 run_file: Path, what: str) -> str | None:
    """Error beyond ``tolerance``, warning text beyond ``warning`` (relative differences of the
    declared height and the measured one)."""
    return check_declared("height", declared, measured, "m", tolerance, warning, run_file,
                          what, "height_tolerance")


def check_declared(key: str, declared: float, measured: float, unit: str, tolerance: float,
                   warning: float, run_file: Path, what: str, parameter: str) -> str | None:
    """A declared run value against the measured one: an error beyond ``tolerance``, a
    warning (returned text) beyond ``warning`` (relative differences).

    Parameters
    ----------
    key : str
        The key of ``[run]`` in run.toml (``height``, ``hm0``, ``tp``, ``te``).
    declared, measured : float
        The declared and the measured value [``unit``].
    unit : str
        Their unit, for the message.
    tolerance, warning : float
        Relative differences beyond which the run is refused, or a warning recorded [-].
    run_file : pathlib.Path
        The run.toml, named in the message.
    what : str
        What was measured (e.g. "incident height at the flap").
    parameter : str
        The ``[stages.waves]`` parameter holding ``tolerance``.

    Returns
    -------
    str or None
        The warning, or None.
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


def check_kind(kind: str, peak_frequency: float, share: float, regular_fraction: float,
               run_file: Path, record: Path) -> None:
    """Error when the records contradict the run's declared kind: a regular run whose records
    are an irregular sea, or an irregular run whose records are a regular wave train.

    The detection is the one :func:`flumekit.waves.separate` uses: a record holding at least
    ``regular_fraction`` of its variance at its peak frequency and the harmonics of it
    (:func:`flumekit.waves.harmonic_energy_fraction`) is regular. Analysed as the other kind,
    a record gives a confident wrong answer (an irregular sea read as a regular wave: the
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
    run_file, record : pathlib.Path
        The run.toml and the probe file, named in the message.
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
    """Errors for probes whose calibration fit has R² below ``min_r2`` or is not monotonic over
    the calibrated voltages; warnings (returned) for R² below ``warn_r2``."""
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
    """Error naming the file and channel(s) that are dead (constant over the whole record),
    stuck (flat lines over more than ``max_flat_fraction`` of the record) or noise (failing
    the noise test, :func:`flumekit.qc.qartod.noise_test`, over more than that fraction)."""
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
