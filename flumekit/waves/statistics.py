"""Sea-state analysis in the time domain: the zero-crossing waves of a record and their statistics.

:func:`wave_statistics` cuts a surface-elevation record into its zero up-crossing (or
down-crossing) waves and gives the individual heights and periods with the statistics of the
IAHR/PIANC (1986) list: N, Hrms, H1/3, T1/3, H1/10, Hmax and Tz.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from flumekit import conventions
from flumekit.docstrings import doc
from flumekit.signal import cycles
from flumekit.waves.spectra import as_time_series

__all__ = ["wave_statistics"]

#: crossings :func:`wave_statistics` knows
CROSSINGS = ("up", "down")


def _top_mean(height: np.ndarray, period: np.ndarray, fraction: int) -> tuple[float, float]:
    """Mean height and period of the highest 1/``fraction`` of the waves (at least one)."""
    n = max(1, height.size // fraction)
    top = np.argsort(height, kind="stable")[::-1][:n]
    return float(height[top].mean()), float(period[top].mean())


@doc
def wave_statistics(eta, sampling_rate: float | None = None, *,
                    crossing: str = "up") -> xr.Dataset:
    """Zero-crossing waves of a surface-elevation record and their statistics.

    The mean of each record is removed; a wave runs from one zero up-crossing to the next
    (``crossing="down"``: from one down-crossing to the next), the crossing times linearly
    interpolated between samples; its height is the highest minus the lowest sample between
    the two crossings and its period the time between them (:func:`flumekit.signal.cycles`:
    crossings from the sign changes, extremes by ``reduceat``, no loop over waves or samples).
    The part of the record before the first crossing and after the last is not a wave.

    Parameters
    ----------
    %(eta)s
    %(sampling_rate_array)s
    crossing : {"up", "down"}
        Zero up-crossing (default, the IAHR recommendation) or down-crossing waves.

    Returns
    -------
    xarray.Dataset
        The individual waves along ``wave`` (..., wave), in time order:
        ``individual_wave_height`` [m], ``individual_wave_period`` [s] and
        ``individual_wave_start`` [s] (the time of the crossing that starts the wave), NaN
        beyond a record's last wave when records of several have different counts; and over
        the other dimensions: ``number_of_waves`` N, ``hrms`` = sqrt(mean H²), ``h1_3`` (H1/3,
        the mean height of the highest N/3 waves), ``t1_3`` (their mean period), ``h1_10``
        (the mean of the highest N/10), ``hmax`` [m] and ``tz`` (the mean period) [s]. The
        highest 1/3 and 1/10 are the int(N/3) and int(N/10) highest waves, at least one.
        Attribute ``crossing``.

    Raises
    ------
    ValueError
        For an unknown ``crossing``, a record with no complete wave, or an input
        :func:`~flumekit.waves.spectra.as_time_series` refuses.

    Notes
    -----
    For a narrow-band linear sea the heights follow the Rayleigh distribution with
    Hrms = sqrt(8 m0), so H1/3 ≈ 4.004 sqrt(m0) ≈ Hm0 and H1/10 ≈ 1.27 H1/3 (Longuet-Higgins
    1952); for a broad JONSWAP spectrum H1/3 ≈ 0.95 Hm0 (Goda 2010). The most probable Hmax of
    N Rayleigh waves is Hm0 sqrt(ln N / 2).

    References
    ----------
    Goda, Y. (2010). Random seas and design of maritime structures, 3rd ed. World Scientific,
    Chapter 2 (zero-crossing method and wave height statistics).

    %(holthuijsen2007)s, Chapter 4.

    IAHR/PIANC (1986). List of sea-state parameters. Supplement to PIANC Bulletin 52.

    Longuet-Higgins, M. S. (1952). On the statistical distribution of the heights of sea
    waves. J. Marine Research 11(3), 245-266.

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.waves import wave_statistics
    >>> fs = 20.0
    >>> t = np.arange(int(60 * fs)) / fs
    >>> eta = 0.05 * np.cos(2 * np.pi * t / 2.0)  # H = 0.1 m, T = 2 s, crests on samples
    >>> w = wave_statistics(eta, sampling_rate=fs)
    >>> int(w.number_of_waves), round(float(w.h1_3), 6), round(float(w.tz), 6)
    (29, 0.1, 2.0)
    """
    if crossing not in CROSSINGS:
        raise ValueError(f"wave_statistics: crossing must be one of {CROSSINGS}, "
                         f"got {crossing!r}")
    da, _ = as_time_series(eta, sampling_rate, "wave_statistics: eta")
    time = np.asarray(da["time"].values, dtype=float)
    x = np.asarray(da.values, dtype=float)
    other = x.shape[:-1]
    rows = x.reshape(-1, x.shape[-1])
    rows = rows - rows.mean(axis=-1, keepdims=True)
    # a down-crossing of η is an up-crossing of -η, and the heights of -η are those of η
    sign = 1.0 if crossing == "up" else -1.0
    waves = []
    scalars = []
    # one pass per record (probe, run, ...), never per wave or sample
    for j, row in enumerate(rows):
        c = cycles(sign * row, time)
        if c.period.size == 0:
            where = "" if not other else f" (record {np.unravel_index(j, other)})"
            raise ValueError(f"wave_statistics: the record{where} holds no complete "
                             f"zero-{crossing}-crossing wave")
        h, per = c.height, c.period
        h3, t3 = _top_mean(h, per, 3)
        h10, _ = _top_mean(h, per, 10)
        scalars.append((h.size, np.sqrt(np.mean(h**2)), h3, t3, h10, h.max(), per.mean()))
        waves.append((h, per, c.start))
    n_max = max(w[0].size for w in waves)
    ind = np.full((3, rows.shape[0], n_max), np.nan)
    for j, w in enumerate(waves):
        ind[:, j, : w[0].size] = w
    ind = ind.reshape(3, *other, n_max)
    sc = np.asarray(scalars, dtype=float).T.reshape(7, *other)
    dims = da.dims[:-1]
    coords = {k: v for k, v in da.coords.items() if "time" not in v.dims}
    names = ("number_of_waves", "hrms", "h1_3", "t1_3", "h1_10", "hmax", "tz")
    data = {name: (dims, sc[i]) for i, name in enumerate(names)}
    data["number_of_waves"] = (dims, sc[0].astype(np.int64))
    for i, name in enumerate(("individual_wave_height", "individual_wave_period",
                              "individual_wave_start")):
        data[name] = ((*dims, "wave"), ind[i])
    coords["wave"] = np.arange(n_max)
    ds = xr.Dataset(data, coords=coords,
                    attrs={"crossing": crossing,
                           "method": f"zero {crossing}-crossing analysis of the record with its "
                                     "mean removed; crossing times interpolated linearly"})
    ds = conventions.annotate(ds)
    if crossing == "down":
        ds["tz"].attrs["long_name"] = "mean zero down-crossing period"
    return ds
