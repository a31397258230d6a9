"""Statistics of a motion or load record in irregular seas.

The record is a flap's angle, a buoy's heave or a hinge torque; the statistics are the spectral
significant amplitude and the zero-crossing amplitudes.

Amplitudes are half heights, the way a wave's amplitude is half its height: the significant
amplitude 2 √m0 is half of the spectral Hm0 = 4 √m0 of the record, the zero-crossing
significant amplitude half of its H1/3. Both are taken about the record's mean (a flap leaning
on its PTO oscillates about a non-zero angle).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from flumekit import conventions
from flumekit import signal as sig
from flumekit.waves.statistics import wave_statistics

#: the statistics of :func:`motion_statistics`, suffixes of ``<name>_``
STATISTICS = ("mean", "rms", "significant_amplitude", "significant_amplitude_zero_crossing",
              "maximum_amplitude")


def motion_statistics(series, sampling_rate: float | None = None, *, time=None,
                      name: str = "theta") -> xr.Dataset:
    """Mean, RMS, significant and maximum amplitudes of a record about its mean.

    Parameters
    ----------
    series : array_like or xarray.DataArray
        The record, 1-D (an angle [rad], a displacement [m], a torque [N m], ...).
    sampling_rate : float, optional
        Sampling rate [Hz]; or give ``time``.
    time : array_like, optional
        Uniform sample times [s] (the DataArray's ``time`` coordinate when ``series`` is one).
    name : str
        Prefix of the variables (``theta`` gives ``theta_significant_amplitude`` ...); the units
        come from the registry (:mod:`flumekit.conventions`) when ``<name>_<statistic>`` is
        registered.

    Returns
    -------
    xarray.Dataset
        Scalars ``<name>_mean``; ``<name>_rms``, the standard deviation √m0 about the mean;
        ``<name>_significant_amplitude`` 2 √m0; ``<name>_significant_amplitude_zero_crossing``,
        half the mean height of the highest third of the zero up-crossing cycles (H1/3 / 2);
        ``<name>_maximum_amplitude``, half the largest zero up-crossing height (Hmax / 2);
        and ``<name>_cycles``, the number of zero up-crossing cycles.

    Raises
    ------
    ValueError
        Non-finite samples, a non-uniform time axis, or fewer than three zero up-crossing
        cycles (no zero-crossing statistic).

    Notes
    -----
    For a narrow-banded Gaussian record the two significant amplitudes agree (H1/3 ≈ Hm0,
    Longuet-Higgins 1952); a broad spectrum gives a zero-crossing amplitude a few per cent
    below the spectral one. The zero-crossing cycles are those of
    :func:`flumekit.signal.cycles` about the mean; the partial cycles before the first and
    after the last up-crossing are left out.

    References
    ----------
    IEC TS 62600-103:2018, Guidelines for the early stage development of wave energy
    converters (statistics of the device's motions and loads in irregular waves).
    ITTC (2021). Recommended procedure 7.5-02-07-03.7, Wave energy converter model test
    experiments.
    Longuet-Higgins, M. S. (1952). On the statistical distribution of the heights of sea
    waves. J. Mar. Res. 11, 245-266.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(0, 200, 0.01)
    >>> ds = motion_statistics(0.1 + 0.2 * np.sin(2 * np.pi * 0.5 * t), 100.0)
    >>> round(float(ds.theta_significant_amplitude), 4)  # 2 sqrt(0.02) for a sine
    0.2828
    >>> round(float(ds.theta_significant_amplitude_zero_crossing), 4)
    0.2
    """
    x = np.asarray(series, dtype=float)
    if time is None and isinstance(series, xr.DataArray) and "time" in series.coords:
        time = series["time"].values
    if time is not None:
        t = np.asarray(time, dtype=float)
        sig.uniform_step(t, f"{name} statistics", min_samples=16)
        if t.shape != x.shape:
            raise ValueError(f"{name} statistics: time {t.shape} and record {x.shape} differ")
    elif sampling_rate is not None and sampling_rate > 0:
        t = np.arange(x.size) / float(sampling_rate)
    else:
        raise ValueError(f"{name} statistics need a positive sampling_rate or the time axis")
    if x.ndim != 1 or not np.all(np.isfinite(x)):
        raise ValueError(f"{name} statistics need a finite 1-D record")
    mean = float(np.mean(x))
    dev = x - mean
    m0 = float(np.mean(dev**2))
    try:
        waves = wave_statistics(xr.DataArray(dev, dims="time", coords={"time": t}))
    except ValueError:
        waves = None
    n = 0 if waves is None else int(waves["number_of_waves"])
    if n < 3:
        raise ValueError(f"{name} statistics: {n} zero up-crossing cycles about the mean, at "
                         "least 3 needed")
    out = xr.Dataset({
        f"{name}_mean": mean,
        f"{name}_rms": np.sqrt(m0),
        f"{name}_significant_amplitude": 2.0 * np.sqrt(m0),
        f"{name}_significant_amplitude_zero_crossing": 0.5 * float(waves["h1_3"]),
        f"{name}_maximum_amplitude": 0.5 * float(waves["hmax"]),
        f"{name}_cycles": n,
    })
    return conventions.annotate(out)
