"""Filling flagged or missing samples: linear interpolation, only across short gaps."""

from __future__ import annotations

import numpy as np


def fill_gaps(values: np.ndarray, valid: np.ndarray, max_gap: int | None = None) -> np.ndarray:
    """Replace invalid samples by linear interpolation between the valid ones around them.

    Vectorised over channels (time along the last axis). Before the first or after the last
    valid sample the nearest valid value is held. With ``max_gap`` (samples), only gaps of at
    most that many consecutive invalid samples are filled; longer ones (and held ends longer than
    that) become NaN. Without it every gap is filled and a channel with no valid sample
    becomes 0.
    """
    values = np.asarray(values, dtype=float)
    valid = np.asarray(valid, dtype=bool) & np.isfinite(values)
    n = values.shape[-1]
    idx = np.arange(n)
    prev = np.maximum.accumulate(np.where(valid, idx, -1), axis=-1)
    nxt = np.minimum.accumulate(np.where(valid, idx, n)[..., ::-1], axis=-1)[..., ::-1]
    has_prev, has_next = prev >= 0, nxt < n
    p = np.where(has_prev, prev, np.where(has_next, nxt, 0))
    q = np.where(has_next, nxt, p)
    vp = np.take_along_axis(values, p, axis=-1)
    vq = np.take_along_axis(values, q, axis=-1)
    with np.errstate(invalid="ignore", divide="ignore"):
        f = np.where(q > p, (idx - p) / (q - p), 0.0)
    filled = vp + f * (vq - vp)
    if max_gap is None:
        filled = np.where(has_prev | has_next, filled, 0.0)
    else:
        # length of the gap each invalid sample belongs to (ends: distance to the record edge)
        length = np.where(has_prev & has_next, nxt - prev - 1,
                          np.where(has_prev, n - 1 - prev, np.where(has_next, nxt, n)))
        filled = np.where((has_prev | has_next) & (length <= max_gap), filled, np.nan)
    return np.where(valid, values, filled)


def gap_spans(invalid: np.ndarray, time: np.ndarray) -> list[tuple[int, float, float]]:
    """Runs of invalid samples along the last axis of a 1-D or 2-D mask:
    (row, first time, last time) [s], in order."""
    m = np.atleast_2d(np.asarray(invalid, dtype=bool))
    n = m.shape[-1]
    padded = np.zeros((m.shape[0], n + 2), dtype=bool)
    padded[:, 1:-1] = m
    edges = np.flatnonzero(np.diff(padded.ravel().astype(np.int8)))
    starts, ends = edges[::2], edges[1::2]
    row = starts // (n + 2)
    first = starts - row * (n + 2)
    last = ends - row * (n + 2) - 1
    return [(int(r), float(time[a]), float(time[b])) for r, a, b in zip(row, first, last,
                                                                       strict=True)]
