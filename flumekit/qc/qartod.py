"""QARTOD-style quality tests, vectorised over channels (time along the last axis).

The tests follow the U.S. IOOS QARTOD manuals (gross range, spike, rate of change, flat line,
gap; IOOS 2020, *QARTOD manual for in-situ surface wave data* and *for currents*) and return one
flag per sample (:mod:`flumekit.qc.flags`). They are written here rather than taken from
``ioos_qc`` (3.0.0), which does not fit flume records:

* ``rate_of_change_test`` and ``flat_line_test`` convert time steps to whole seconds
  (``astype("timedelta64[s]")``): at 25-100 Hz every step is 0 s, the rate test then flags
  nothing (masked division) and the flat-line test raises ``ValueError`` (negative window);
  flat-line durations are whole seconds and ``time_gap_test`` spans are hours;
* ``spike_test`` loops in Python over every sample and flattens N-D input, so it cannot run
  along the time axis of a (probe, time) or (channel, time) block;
* it pulls in shapely, geographiclib, geojson, jsonschema and ruamel.yaml for location tests
  a flume does not need.

Thresholds of the spike, rate-of-change and dropout tests are multiples of a *robust, local*
standard deviation of the tested statistic (1.4826 times its median absolute value, per block
of ``block`` samples and the larger of the neighbouring blocks), so that one set of defaults
suits probe voltages, encoder counts, pressures and velocities alike and is not inflated by the
faults it looks for. A floor (the channel's resolution) keeps a quantised channel at rest from
having a zero scale.
"""

from __future__ import annotations

import numpy as np

from flumekit.docstrings import fill, filler
from flumekit.qc.fill import runs
from flumekit.qc.flags import FAIL, GOOD, MAD_TO_STD, MISSING, NOT_EVALUATED, SUSPECT, choose

_FLAGS = "Returns\n-------\nnumpy.ndarray\n    QARTOD flags (uint8) of x's shape."
#: texts that several docstrings of this module share
_doc = filler(
    # what every test returns; most also cite the manual (the test's name follows)
    returns_flags=_FLAGS,
    flags_per_qartod=_FLAGS + "\n\n" + fill("%(references_qartod)s"),
    block=("block : int\n"
           "    Samples per block of the local scale."),
    floor=("floor : float or numpy.ndarray, optional\n"
           "    Lower bound of the scale [unit of x]; None: the channel's :func:`resolution`."),
    threshold=("threshold : float\n"
               "    Robust standard deviations [-]."))


def resolution(x: np.ndarray) -> np.ndarray:
    """Return the smallest non-zero step between consecutive samples per channel (quantisation).

    Parameters
    ----------
    x : array_like
        Record, time along the last axis [any unit]; integer records are scanned as integers.

    Returns
    -------
    numpy.ndarray
        Resolution per channel [unit of x], 0 for a channel without a non-zero step.

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.qc.qartod import resolution
    >>> resolution(np.array([[0.0, 0.5, 0.5, 1.5], [1.0, 1.0, 1.0, 1.0]])).tolist()
    [0.5, 0.0]
    """
    x = np.asarray(x)
    if x.dtype.kind in "iu":  # integers: no NaN, and a smaller type to scan
        if not x.shape[-1]:
            return np.zeros(x.shape[:-1])
        d = np.diff(x.astype(np.int32), axis=-1)
        np.abs(d, out=d)
        # |step| - 1 as unsigned: a zero step wraps to the largest value, so the minimum is
        # that of the non-zero steps (one pass instead of replacing the zeros)
        u = d.view(np.uint32)
        u -= np.uint32(1)
        r = u.min(axis=-1).astype(np.int64) + 1
        return np.where(r > np.iinfo(np.uint32).max, 0.0, r.astype(float))
    d = np.abs(np.diff(np.asarray(x, dtype=float), axis=-1))
    d = np.where(np.isfinite(d) & (d > 0), d, np.inf)
    r = d.min(axis=-1)
    return np.where(np.isfinite(r), r, 0.0)


def local_scale(stat: np.ndarray, block: int, floor: np.ndarray | float = 0.0) -> np.ndarray:
    """Return the robust local standard deviation of ``stat`` along the last axis, per sample.

    1.4826 x median ``|stat|`` per block of ``block`` samples (NaN ignored), the largest of each
    block and its two neighbours (so a block at the arrival of the waves is judged with the
    scale of the waves), at least ``floor``.

    Parameters
    ----------
    stat : array_like
        The tested statistic, time along the last axis [any unit].
    block : int
        Samples per block.
    floor : float or numpy.ndarray
        Lower bound [unit of stat], scalar or one per channel.

    Returns
    -------
    numpy.ndarray
        Scale per sample, of the shape of ``stat`` [unit of stat].
    """
    s = np.abs(np.asarray(stat, dtype=float))
    n = s.shape[-1]
    block = int(max(1, min(block, n)))
    nb = -(-n // block)
    pad = [(0, 0)] * (s.ndim - 1) + [(0, nb * block - n)]
    blocks = np.pad(s, pad, mode="symmetric").reshape(s.shape[:-1] + (nb, block))
    with np.errstate(all="ignore"):
        if np.isnan(blocks).any():
            import warnings

            with warnings.catch_warnings():
                warnings.simplefilter("ignore", RuntimeWarning)
                med = np.nanmedian(blocks, axis=-1)
        else:
            med = np.median(blocks, axis=-1)
    med = np.nan_to_num(MAD_TO_STD * med, nan=0.0)
    edge = np.pad(med, [(0, 0)] * (med.ndim - 1) + [(1, 1)], mode="edge")
    med = np.maximum(np.maximum(edge[..., :-2], edge[..., 1:-1]), edge[..., 2:])
    med = np.maximum(med, np.asarray(floor, dtype=float)[..., None] if np.ndim(floor) else floor)
    return np.repeat(med, block, axis=-1)[..., :n]


def _empty_flags(x: np.ndarray) -> np.ndarray:
    return choose(np.isfinite(x), GOOD, MISSING)


def _rows(x) -> tuple[np.ndarray, np.ndarray, tuple[int, ...]]:
    """Return a record as (channel, time) rows, their flags (GOOD or MISSING) and its shape."""
    x = np.asarray(x, dtype=float)
    x2 = x.reshape(-1, x.shape[-1])
    return x2, _empty_flags(x2), x.shape


def _local_test_start(x, min_samples: int, floor):
    """Return the values, flags and noise floor of a local test.

    The flags are all NOT_EVALUATED (2) when the record is shorter than the test's stencil
    (the floor is then None).
    """
    x = np.asarray(x, dtype=float)
    f = _empty_flags(x)
    if x.shape[-1] < min_samples:
        f[f == GOOD] = NOT_EVALUATED
        return x, f, None
    return x, f, resolution(x) if floor is None else floor


@_doc
def gross_range_test(x: np.ndarray, fail_span: tuple[float, float] | None,
                     suspect_span: tuple[float, float] | None = None) -> np.ndarray:
    """Flag samples outside the sensor's and the user's limits (QARTOD gross range test).

    FAIL outside ``fail_span`` (sensor limits), SUSPECT outside ``suspect_span`` (user
    limits), MISSING where not finite. Without either span, nothing is evaluated (2).

    Parameters
    ----------
    x : array_like
        Record [any unit].
    fail_span : tuple of float, optional
        (min, max) of the sensor [unit of x]; None: not tested.
    suspect_span : tuple of float, optional
        (min, max) expected by the user [unit of x]; None: not tested.

    %(flags_per_qartod)s (gross range test).

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.qc import gross_range_test
    >>> gross_range_test(np.array([0.0, 0.3, 0.6, np.nan]), (-0.5, 0.5), (-0.2, 0.2)).tolist()
    [1, 3, 4, 9]
    """
    x = np.asarray(x, dtype=float)
    if fail_span is None and suspect_span is None:
        return choose(np.isfinite(x), NOT_EVALUATED, MISSING)
    f = _empty_flags(x)
    finite = f != MISSING
    with np.errstate(invalid="ignore"):
        if suspect_span is not None:
            lo, hi = sorted(suspect_span)
            f[finite & ((x < lo) | (x > hi))] = SUSPECT
        if fail_span is not None:
            lo, hi = sorted(fail_span)
            f[finite & ((x < lo) | (x > hi))] = FAIL
    return f


@_doc
def spike_test(x: np.ndarray, suspect: float = 6.0, fail: float = 8.0, block: int = 250,
               floor: np.ndarray | float | None = None, passes: int = 2) -> np.ndarray:
    """Flag spikes (QARTOD spike test, the "average" method), robust and local.

    The statistic is d_n = x_n - (x_(n-1) + x_(n+1))/2. A sample is a spike where abs(d_n)
    exceeds ``suspect`` (SUSPECT) or ``fail`` (FAIL) robust local standard deviations of d
    (:func:`local_scale`) and is the largest abs(d) of its three neighbours: a spike of size s
    also moves its neighbours' d by s/2, and those neighbours are good data. After each pass the
    FAIL samples are replaced by the mean of their neighbours and the test runs again
    (``passes``), which finds spikes hidden next to larger ones. End samples are not evaluated
    (2).

    Parameters
    ----------
    %(record)s
    suspect : float
        Robust local standard deviations of d beyond which a spike is suspect [-].
    fail : float
        Robust local standard deviations of d beyond which a spike fails [-].
    %(block)s
    %(floor)s
    passes : int
        Passes at most.

    %(flags_per_qartod)s (spike test).

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.qc import spike_test
    >>> x = np.sin(2 * np.pi * np.arange(400) / 40.0)
    >>> x[100] += 1.0
    >>> f = spike_test(x)
    >>> np.flatnonzero(f == 4).tolist(), int(f[0])
    ([100], 2)
    """
    x, f, floor = _local_test_start(x, 3, floor)
    if floor is None:
        return f
    work = x.copy()
    for _ in range(passes):
        d = work[..., 1:-1] - 0.5 * (work[..., :-2] + work[..., 2:])
        ad = np.abs(d)
        r = ad / np.maximum(local_scale(d, block, floor), np.finfo(float).tiny)
        nb = np.pad(ad, [(0, 0)] * (ad.ndim - 1) + [(1, 1)], constant_values=0.0)
        peak = (ad >= nb[..., :-2]) & (ad >= nb[..., 2:])
        inner = f[..., 1:-1]
        with np.errstate(invalid="ignore"):
            sus = peak & (r > suspect) & (inner == GOOD)
            bad = peak & (r > fail) & (inner != MISSING)
        inner[sus] = SUSPECT
        inner[bad] = FAIL
        if not bad.any():
            break
        mid = 0.5 * (work[..., :-2] + work[..., 2:])
        work[..., 1:-1] = np.where(bad, mid, work[..., 1:-1])
    f[..., 0] = np.where(f[..., 0] == MISSING, MISSING, NOT_EVALUATED)
    f[..., -1] = np.where(f[..., -1] == MISSING, MISSING, NOT_EVALUATED)
    return f


@_doc
def rate_of_change_test(x: np.ndarray, threshold: float = 10.0, block: int = 250,
                        floor: np.ndarray | float | None = None) -> np.ndarray:
    """Flag excessive rates of change (QARTOD rate of change test).

    SUSPECT where abs(x_n - x_(n-1)) exceeds ``threshold`` robust local standard deviations of
    the first difference (QARTOD's "N standard deviations" rule, :func:`local_scale`). The
    first sample is not evaluated (2).

    Parameters
    ----------
    %(record)s
    threshold : float
        Robust local standard deviations of the first difference [-].
    %(block)s
    %(floor)s

    %(flags_per_qartod)s (rate of change test).

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.qc import rate_of_change_test
    >>> x = np.sin(2 * np.pi * np.arange(400) / 40.0)
    >>> x[200:] += 2.0
    >>> np.flatnonzero(rate_of_change_test(x) == 3).tolist()
    [200]
    """
    x, f, floor = _local_test_start(x, 2, floor)
    if floor is None:
        return f
    dx = np.diff(x, axis=-1)
    r = np.abs(dx) / np.maximum(local_scale(dx, block, floor), np.finfo(float).tiny)
    rest = f[..., 1:]
    with np.errstate(invalid="ignore"):
        rest[(r > threshold) & (rest == GOOD)] = SUSPECT
    f[..., 0] = np.where(f[..., 0] == MISSING, MISSING, NOT_EVALUATED)
    return f


def _paint(shape: tuple[int, int], row, first, length) -> np.ndarray:
    """Return a boolean (m, n) array, True over the given runs (a cumulative sum)."""
    m, n = shape
    mark = np.zeros((m, n + 1), dtype=np.int64)
    np.add.at(mark, (row, first), 1)
    np.add.at(mark, (row, first + length), -1)
    return np.cumsum(mark, axis=-1)[:, :n] > 0


@_doc
def flat_line_test(x: np.ndarray, sampling_rate: float, suspect_seconds: float = 1.0,
                   fail_seconds: float = 2.0, tolerance: float = 0.0,
                   exempt_leading: bool = True) -> np.ndarray:
    """Flag flat lines (QARTOD flat line test).

    Runs of samples within ``tolerance`` of their predecessor that last at least
    ``suspect_seconds`` (SUSPECT) or ``fail_seconds`` (FAIL); every sample of the run is
    flagged. A run from the first sample that ends before the record does is the instrument at
    rest before the waves arrive (an encoder's count does not change then) and passes when
    ``exempt_leading``; a run over the whole record fails (a dead channel).

    Parameters
    ----------
    %(record)s
    %(sampling_rate)s
    suspect_seconds : float
        Shortest flat line that is suspect [s].
    fail_seconds : float
        Shortest flat line that fails [s].
    tolerance : float
        Largest step that counts as flat [unit of x].
    exempt_leading : bool
        Pass a flat line from the first sample that ends before the record does.

    %(flags_per_qartod)s (flat line test).

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.qc import flat_line_test
    >>> x = np.sin(2 * np.pi * np.arange(200) / 20.0)
    >>> x[50:80] = x[50]
    >>> f = flat_line_test(x, 10.0, suspect_seconds=1.0, fail_seconds=2.0)
    >>> np.flatnonzero(f == 4)[[0, -1]].tolist()
    [50, 79]
    """
    x2, f, shape = _rows(x)
    n = x2.shape[-1]
    if n < 2:
        return f.reshape(shape)
    with np.errstate(invalid="ignore"):
        same = np.abs(np.diff(x2, axis=-1)) <= tolerance
    row, first, length = runs(same)  # runs of equal steps; a run of k steps spans k+1 samples
    dur = length / sampling_rate
    leading = exempt_leading & (first == 0) & (first + length < n - 1)
    for level, seconds in ((SUSPECT, suspect_seconds), (FAIL, fail_seconds)):
        sel = (dur >= seconds) & ~leading
        paint = _paint(x2.shape, row[sel], first[sel], length[sel] + 1)
        f[paint & (f != MISSING)] = level
    return f.reshape(shape)


def robust_median(x: np.ndarray) -> np.ndarray:
    """Return the median along the last axis ignoring NaN, vectorised over the other axes.

    numpy's ``nanmedian`` loops over rows in Python for long rows; this sorts once.

    Parameters
    ----------
    x : array_like
        Values, along the last axis [any unit].

    Returns
    -------
    numpy.ndarray
        Median per row [unit of x]; NaN where a row has no value.

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.qc.qartod import robust_median
    >>> robust_median(np.array([[1.0, np.nan, 3.0, 10.0], [np.nan] * 4])).tolist()
    [3.0, nan]
    """
    x = np.asarray(x, dtype=float)
    nan = np.isnan(x)
    if not nan.any():
        return np.median(x, axis=-1)
    s = np.sort(x, axis=-1)  # NaN sort last
    k = x.shape[-1] - nan.sum(axis=-1)
    lo = np.take_along_axis(s, np.maximum((k - 1) // 2, 0)[..., None], axis=-1)[..., 0]
    hi = np.take_along_axis(s, np.minimum(k // 2, x.shape[-1] - 1)[..., None], axis=-1)[..., 0]
    return np.where(k > 0, 0.5 * (lo + hi), np.nan)


@_doc
def level_test(x: np.ndarray, threshold: float = 6.0) -> np.ndarray:
    """Flag samples far from the record's median (the level form of :func:`dropout_test`).

    FAIL where ``|x - median(x)|`` exceeds ``threshold`` robust standard deviations of x over the
    record (1.4826 MAD, at least the channel's resolution), per channel along the last axis.

    Parameters
    ----------
    x : array_like
        Record, time along the last axis [any unit]; integer records are tested exactly
        (:func:`level_fail`).
    %(threshold)s

    %(returns_flags)s

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.qc.qartod import level_test
    >>> x = np.sin(2 * np.pi * np.arange(200) / 20.0)
    >>> x[120] = -9.0
    >>> np.flatnonzero(level_test(x) == 4).tolist()
    [120]
    """
    x = np.asarray(x)
    if x.dtype.kind in "iu" and x.size:
        return choose(level_fail(x, threshold), FAIL, GOOD)
    return _level(x.reshape(-1, x.shape[-1]), threshold).reshape(x.shape)


@_doc
def level_fail(x: np.ndarray, threshold: float = 6.0) -> np.ndarray:
    """Return where :func:`level_test` fails.

    Integer records (echo amplitudes) are tested exactly, compiled
    (:func:`flumekit.qc.kernels.level_fail_rows`).

    Parameters
    ----------
    %(record)s
    %(threshold)s

    Returns
    -------
    numpy.ndarray
        Boolean, of x's shape: True where the sample fails.
    """
    x = np.asarray(x)
    if x.dtype.kind in "iu" and x.size:
        from flumekit.qc.kernels import level_fail_rows

        return level_fail_rows(x.reshape(-1, x.shape[-1]), float(threshold)).reshape(x.shape)
    return level_test(x, threshold) == FAIL


def _level(x2: np.ndarray, threshold: float) -> np.ndarray:
    """Run :func:`level_test` on the (channel, time) block ``x2`` of real numbers."""
    med = robust_median(x2)[:, None]
    x2 = x2.astype(float)
    f = _empty_flags(x2)
    dev = np.abs(x2 - med)
    scale = np.maximum(MAD_TO_STD * robust_median(dev), resolution(x2))[:, None]
    with np.errstate(invalid="ignore"):
        f[(dev > threshold * scale) & (f != MISSING)] = FAIL
    return f


@_doc
def dropout_test(x: np.ndarray, sampling_rate: float, threshold: float = 6.0,
                 hold_seconds: float = 0.2, hold_factor: float = 4.0) -> np.ndarray:
    """Flag dropouts: a channel that falls away from its signal (FAIL), in either of two forms.

    * Level: samples far outside the record's robust envelope (:func:`level_test`).
    * Hold: a run of identical values (a logger writing 0 or repeating its last value) longer
      than ``hold_seconds`` and than ``hold_factor`` times the channel's own longest runs of
      identical values (but the longest 1 %).

    Parameters
    ----------
    %(record)s
    %(sampling_rate)s
    threshold : float
        Robust standard deviations of the level form [-].
    hold_seconds : float
        Shortest hold that can be a dropout [s].
    hold_factor : float
        Multiple of the channel's typical longest run of identical values [-].

    %(returns_flags)s

    Notes
    -----
    The level form flags ``|x - median(x)|`` above ``threshold`` robust standard deviations of
    x over the record (1.4826 MAD). A sinusoid reaches 0.95 of them, so the default 6 leaves
    room for steep crests and a still-water lead-in of up to about half the record.

    The hold threshold follows the record: a noisy channel never repeats a value for long,
    while a quantised one at rest or at a flap's reversal does. The lead-in (the instrument at
    rest before the waves arrive, until it first leaves its initial level by more than two
    quanta) is exempt, and so is a run that a quantised signal enters and leaves by one quantum
    (slow motion, not a hold).

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.qc.qartod import dropout_test
    >>> x = np.sin(2 * np.pi * np.arange(1000) / 100.0)
    >>> x[400:450] = 0.0  # a logger writing 0 for 0.5 s
    >>> np.flatnonzero(dropout_test(x, 100.0) == 4)[[0, -1]].tolist()
    [400, 449]
    """
    x = np.asarray(x, dtype=float)
    shape = x.shape
    x2 = x.reshape(-1, shape[-1])
    f = level_test(x2, threshold)
    with np.errstate(invalid="ignore"):
        same = np.diff(x2, axis=-1) == 0
    n = x2.shape[-1]
    if n > 2:
        row, first, length = runs(same)
        # the lead-in (the instrument at rest before the waves arrive, flickering between two
        # quantisation levels) lasts until the channel first leaves its initial level by more
        # than two quanta; its runs are exempt unless the channel never leaves it (dead)
        with np.errstate(invalid="ignore"):
            moved = np.abs(x2 - x2[:, :1]) > 2 * resolution(x2)[:, None]
        lead = np.where(moved.any(axis=-1), np.argmax(moved, axis=-1), 0)
        inner = ~((first < lead[row]) | ((first == 0) & (first + length < n - 1)))
        # a quantised signal that moves slowly (small motion, as while the waves ramp up, or
        # a turning point) dwells on each level and steps one quantum in and out; a logger that
        # holds a value while the signal moves on leaves the run with a jump
        res = resolution(x2)[row]
        before, after = first - 1, first + length + 1
        ok = (before >= 0) & (after < n)
        v = x2[row, first]
        dp = v - x2[row, np.clip(before, 0, n - 1)]
        dn = v - x2[row, np.clip(after, 0, n - 1)]
        with np.errstate(invalid="ignore"):
            slow = ok & (np.abs(dp) <= res) & (np.abs(dn) <= res)
        inner &= ~slow
        # each channel's typical longest run: the longest 1 % of its runs (at least the
        # longest one) are left out, since in a noisy channel the few runs there are would
        # otherwise include the dropout itself. All channels at once: the inner runs sorted by
        # (channel, length), and per channel the run ranked (count - left out) from the top
        m = x2.shape[0]
        total = np.bincount(row, minlength=m)
        drop = np.maximum(1, total // 100)
        count = np.bincount(row[inner], minlength=m)
        order = np.lexsort((length[inner], row[inner]))
        ranked = length[inner][order]
        pick = np.cumsum(count) - count + count - drop - 1  # row start + (count - drop - 1)
        typical = np.where(count > drop, ranked[np.clip(pick, 0, max(ranked.size - 1, 0))]
                           if ranked.size else 0, 0).astype(float)
        limit = np.where(total > 0, np.maximum(hold_seconds * sampling_rate,
                                               hold_factor * typical), np.inf)
        sel = inner & (length > limit[row])
        f[_paint(x2.shape, row[sel], first[sel], length[sel] + 1) & (f != MISSING)] = FAIL
    return f.reshape(shape)


@_doc
def gap_test(time: np.ndarray, sampling_rate: float, tolerance: float = 0.5) -> np.ndarray:
    """Flag samples after a gap in time (QARTOD gap, or timing, test).

    FAIL on a sample that follows a time step longer than (1 + ``tolerance``) /
    ``sampling_rate`` (samples are missing before it); MISSING where the time is not finite.

    Parameters
    ----------
    time : array_like
        Sample times [s].
    sampling_rate : float
        Nominal sampling rate [Hz].
    tolerance : float
        Relative excess of a time step over 1 / ``sampling_rate`` that is a gap [-].

    Returns
    -------
    numpy.ndarray
        QARTOD flags (uint8) of time's shape.

    %(references_qartod)s (timing/gap test).

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.qc.qartod import gap_test
    >>> gap_test(np.array([0.0, 0.1, 0.2, 0.5, 0.6]), 10.0).tolist()
    [1, 1, 1, 4, 1]
    """
    t = np.asarray(time, dtype=float)
    f = _empty_flags(t)
    with np.errstate(invalid="ignore"):
        late = np.diff(t) > (1.0 + tolerance) / sampling_rate
    f[1:][late & (f[1:] != MISSING)] = FAIL
    return f


@_doc
def noise_test(x: np.ndarray, block: int, max_autocorrelation: float = 0.5,
               min_share: float = 0.1) -> np.ndarray:
    """Flag blocks of a channel that hold more noise than signal (FAIL).

    A block of ``block`` samples (the last block ends at the record's end) fails when

    * its lag-one autocorrelation r1 is below ``max_autocorrelation``, and
    * its high-frequency energy, half the mean square first difference, exceeds
      ``min_share`` of the channel's variance over the record.

    Parameters
    ----------
    %(record)s
    block : int
        Samples per block (at least 4).
    max_autocorrelation : float
        Lag-one autocorrelation below which a block can be noise [-].
    min_share : float
        Share of the channel's variance its high-frequency energy must exceed [-].

    %(returns_flags)s

    Notes
    -----
    A physical signal sampled far above its band (waves of a period T at a rate fs with
    T fs >> 1) changes little from one sample to the next: its lag-one autocorrelation is
    cos(2 pi / (T fs)), 0.99 for a 2 s wave at 25 Hz, 0.81 for a 0.5 s one. White noise has
    none (0), and spikes alternating in sign (a broken channel, electrical interference at
    the Nyquist frequency) have -1, which the spike test cannot see: every sample is as far
    from its neighbours as the next, so the robust local scale is the spikes'.

    The high-frequency energy is the variance for white noise; for a signal it is the spectrum
    weighted by 2 sin²(pi f / fs), about (2 pi f / fs)² / 2 for a slow one. Requiring it to be
    a share of the variance keeps the quiet still-water lead-in of a probe, which is noise but
    tiny beside the waves, from failing. A channel that is noise from end to end fails
    everywhere (its high-frequency energy is its variance).

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.qc.qartod import noise_test
    >>> wave = np.sin(2 * np.pi * np.arange(1000) / 50.0)
    >>> hiss = np.random.default_rng(0).standard_normal(1000)
    >>> [int((noise_test(x, 100) == 4).sum()) for x in (wave, hiss)]
    [0, 1000]
    """
    x2, f, shape = _rows(x)
    n = x2.shape[-1]
    if n < 4:
        return f.reshape(shape)
    size = min(max(int(block), 4), n)
    starts = np.minimum(np.arange(0, n, size), n - size)  # the last block ends at the end
    xb = x2[:, starts[:, None] + np.arange(size)]  # (channel, block, sample)
    with np.errstate(invalid="ignore", divide="ignore"):
        d = np.nan_to_num(xb - _nanmean(xb))  # a missing sample adds nothing
        var = np.mean(d * d, axis=-1)
        r1 = np.mean(d[..., 1:] * d[..., :-1], axis=-1) / var
        hf = 0.5 * np.mean(np.diff(d, axis=-1) ** 2, axis=-1)
        total = np.nanvar(x2, axis=-1)[:, None]
        noisy = (r1 < max_autocorrelation) & (hf > min_share * total)
    k = np.minimum(np.arange(n) // size, starts.size - 1)
    f[noisy[:, k] & (f != MISSING)] = FAIL
    return f.reshape(shape)


def _nanmean(xb: np.ndarray) -> np.ndarray:
    """Mean over the last axis without the NaNs (0 for an all-NaN block)."""
    ok = np.isfinite(xb)
    return (np.where(ok, xb, 0.0).sum(axis=-1, keepdims=True)
            / np.maximum(ok.sum(axis=-1, keepdims=True), 1))
