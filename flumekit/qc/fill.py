"""Filling flagged or missing samples: linear interpolation, only across short gaps."""

from __future__ import annotations

import numpy as np


def runs(mask: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Runs of True along the last axis of a 2-D mask: (row, first index, length), in order.

    O(n) in the mask and vectorised: the edges of the runs in the flattened mask padded with a
    False column on each side."""
    m, n = mask.shape
    padded = np.zeros((m, n + 2), dtype=bool)
    padded[:, 1:-1] = mask
    edges = np.flatnonzero(padded[:, 1:].ravel() != padded[:, :-1].ravel())
    # edges index the (m, n + 1) differences; a run never spans two rows (False pads)
    starts, ends = edges[::2], edges[1::2]
    row = starts // (n + 1)
    return row, starts - row * (n + 1), ends - starts


def fill_gaps(values: np.ndarray, valid: np.ndarray, max_gap: int | None = None) -> np.ndarray:
    """Replace invalid samples by linear interpolation between the valid ones around them.

    Vectorised over channels (time along the last axis). Before the first or after the last
    valid sample the nearest valid value is held. With ``max_gap`` (samples), only gaps of at
    most that many consecutive invalid samples are filled; longer ones (and held ends longer than
    that) become NaN. Without it every gap is filled and a channel with no valid sample
    becomes 0.

    The work is per run of invalid samples (found in O(n)), so a record with a few flagged
    samples costs little more than a copy.
    """
    values = np.asarray(values, dtype=float)
    valid = np.asarray(valid, dtype=bool) & np.isfinite(values)
    shape = values.shape
    n = shape[-1]
    # copied in the layout it has (a transposed view stays one: a copy in the other order
    # would cost twice as much), then filled in place
    out = np.array(values, order="K")
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
    """Runs of invalid samples along the last axis of a 1-D or 2-D mask:
    (row, first time, last time) [s], in order."""
    m = np.atleast_2d(np.asarray(invalid, dtype=bool))
    row, first, length = runs(m)
    last = first + length - 1
    return [(int(r), float(time[a]), float(time[b])) for r, a, b in zip(row, first, last,
                                                                       strict=True)]
