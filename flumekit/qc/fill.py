"""Filling flagged or missing samples: linear interpolation, only across short gaps."""

from __future__ import annotations

import numpy as np

#: fraction of True below which :func:`runs` works from the True samples' indices
SPARSE = 0.02


def runs(mask: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Find the runs of True along the last axis of a 2-D mask.

    O(n) in the mask and vectorised: the edges of the runs in the flattened mask padded with a
    False column on each side; or, for a sparse mask (flagged samples, fewer than ``SPARSE`` of
    the mask), the flat indices of its True samples split where they stop following each other
    or change rows, so that the work after one pass over the mask is on those samples only.

    Parameters
    ----------
    mask : numpy.ndarray
        Boolean (row, sample) array.

    Returns
    -------
    row : numpy.ndarray
        Row of each run.
    first : numpy.ndarray
        Index of its first sample.
    length : numpy.ndarray
        Its number of samples; runs in row-major order.

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.qc.fill import runs
    >>> [a.tolist() for a in runs(np.array([[0, 1, 1, 0, 1], [1, 0, 0, 0, 0]], dtype=bool))]
    [[0, 0, 1], [1, 4, 0], [2, 1, 1]]
    """
    m, n = mask.shape
    if np.count_nonzero(mask) < SPARSE * mask.size:
        idx = np.flatnonzero(np.ascontiguousarray(mask))
        row = idx // max(n, 1)
        start = np.ones(idx.size, dtype=bool)
        start[1:] = (np.diff(idx) != 1) | (row[1:] != row[:-1])
        first = np.flatnonzero(start)
        length = np.diff(np.append(first, idx.size))
        return row[first], idx[first] - row[first] * n, length
    padded = np.zeros((m, n + 2), dtype=bool)
    padded[:, 1:-1] = mask
    edges = np.flatnonzero(padded[:, 1:].ravel() != padded[:, :-1].ravel())
    # edges index the (m, n + 1) differences; a run never spans two rows (False pads)
    starts, ends = edges[::2], edges[1::2]
    row = starts // (n + 1)
    return row, starts - row * (n + 1), ends - starts


def fill_gaps(values: np.ndarray, valid: np.ndarray, max_gap: int | None = None, *,
              copy: bool = True) -> np.ndarray:
    """Replace invalid samples by linear interpolation between the valid ones around them.

    Vectorised over channels (time along the last axis). Before the first or after the last
    valid sample the nearest valid value is held. With ``max_gap``, only gaps of at most that
    many consecutive invalid samples are filled; longer ones (and held ends longer than that)
    become NaN. Without it every gap is filled and a channel with no valid sample becomes 0.
    Non-finite values count as invalid.

    The work is per run of invalid samples (found in O(n), :func:`runs`), so a record with a few
    flagged samples costs little more than a copy.

    Parameters
    ----------
    values : array_like
        Record, time along the last axis [any unit].
    valid : array_like
        Boolean, of the shape of ``values``: True where a sample is valid.
    max_gap : int, optional
        Longest run of invalid samples filled [samples]; None: every run.
    copy : bool
        False: ``values`` may be overwritten (the result may share its memory).

    Returns
    -------
    numpy.ndarray
        The record with its invalid samples filled, of the shape of ``values`` [unit of values].

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.qc import fill_gaps
    >>> x = np.array([0.0, 9.0, 2.0, 9.0, 9.0, 9.0, 6.0])
    >>> fill_gaps(x, x != 9.0).tolist()
    [0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0]
    >>> fill_gaps(x, x != 9.0, max_gap=2).tolist()
    [0.0, 1.0, 2.0, nan, nan, nan, 6.0]
    """
    values = np.asarray(values, dtype=float)
    valid = np.asarray(valid, dtype=bool)
    finite = np.isfinite(values)  # in the layout of values (a transposed view: fast)
    if not finite.all():
        valid = valid & finite
    shape = values.shape
    n = shape[-1]
    # copied in the layout it has (a transposed view stays one: a copy in the other order
    # would cost twice as much), then filled in place
    out = np.array(values, order="K") if copy else values
    out = out.reshape(-1, n) if values.ndim else out
    if values.ndim == 0 or valid.all():
        return out.reshape(shape)
    row, first, length = runs(~valid.reshape(-1, n))
    last = first + length - 1
    has_prev, has_next = first > 0, last < n - 1
    vp = out[row, np.maximum(first - 1, 0)]
    vq = out[row, np.minimum(last + 1, n - 1)]
    # every invalid sample: its run, and its offset in the run
    k = np.repeat(np.arange(row.size), length)
    pos = np.arange(k.size) - np.repeat(np.cumsum(length) - length, length)
    both = has_prev & has_next
    with np.errstate(invalid="ignore"):
        frac = (pos + 1) / (length + 1)[k]
        filled = np.where(both[k], vp[k] + frac * (vq[k] - vp[k]),
                          np.where(has_prev[k], vp[k], vq[k]))
    lonely = ~has_prev & ~has_next  # a channel without a valid sample
    if max_gap is None:
        filled = np.where(lonely[k], 0.0, filled)
    else:
        filled = np.where(lonely[k] | (length[k] > max_gap), np.nan, filled)
    out[row[k], first[k] + pos] = filled
    return out.reshape(shape)


def gap_spans(invalid: np.ndarray, time: np.ndarray) -> list[tuple[int, float, float]]:
    """Return the runs of invalid samples along the last axis of a 1-D or 2-D mask, as times.

    Parameters
    ----------
    invalid : array_like
        Boolean mask, (row, sample) or 1-D: True where a sample is invalid.
    time : numpy.ndarray
        Time of each sample [s].

    Returns
    -------
    list of tuple of (int, float, float)
        (row, time of the first sample, time of the last sample) [s] of each run, in order.

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.qc.fill import gap_spans
    >>> gap_spans(np.array([False, True, True, False]), np.array([0.0, 0.1, 0.2, 0.3]))
    [(0, 0.1, 0.2)]
    """
    m = np.atleast_2d(np.asarray(invalid, dtype=bool))
    row, first, length = runs(m)
    last = first + length - 1
    return [(int(r), float(time[a]), float(time[b])) for r, a, b in zip(row, first, last,
                                                                       strict=True)]
