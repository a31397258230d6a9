"""Phase-space despiking of velocity records (Goring and Nikora 2002, with Wahl 2003).

Goring, D. G. and Nikora, V. I. (2002), Despiking acoustic Doppler velocimeter data, J. Hydraul.
Eng. 128(1), 117-126; Wahl, T. L. (2003), Discussion, J. Hydraul. Eng. 129(6), 484-487.
"""

from __future__ import annotations

import numpy as np

from flumekit.qc.blocks import by_rows
from flumekit.qc.fill import fill_gaps
from flumekit.qc.qartod import integer_median


def goring_nikora(u: np.ndarray, floor: float | np.ndarray = 0.0, max_iterations: int = 20
                  ) -> np.ndarray:
    """Spikes of velocity records by the phase-space thresholding method, per channel.

    Vectorised over all leading axes (profiles' channels, beams); time along the last axis. Each
    iteration: fluctuation u about the channel's median, its central differences Δu and Δ²u
    (GN 2002, Eqs. 6-7), the universal threshold λ = sqrt(2 ln n) (Eq. 2), and three ellipses
    in the (u, Δu), (Δu, Δ²u) and (u, Δ²u) planes with semi-axes λσ; the third is rotated by
    θ = atan(Σ u Δ²u / Σ u²) (Eq. 9) and its axes solve Eqs. (10)-(11). Points outside any
    ellipse are spikes; they are replaced by linear interpolation and the test repeats until no
    new spike is found (GN 2002 replace by a cubic through 12 neighbours; the flags are what
    this returns, the replacement only serves the next iteration).

    Parameters
    ----------
    u : Velocity [m s-1], time along the last axis; NaN samples are ignored.
    floor : Lower bound of each standard deviation [m s-1] (the velocity resolution of a
        quantised instrument), so a channel in still water is not all spikes.
    max_iterations : Iterations at most.

    Returns
    -------
    Boolean array of u's shape, True at spikes.
    """
    u = np.asarray(u, dtype=float)
    shape = u.shape
    u = u.reshape(-1, shape[-1])
    valid = np.isfinite(u)
    n = int(np.count_nonzero(valid, axis=-1).max()) if u.size else 0
    if n < 5:
        return np.zeros(shape, dtype=bool)
    lam2 = 2.0 * np.log(n)  # squared universal threshold, Eq. (2)
    floor = np.broadcast_to(np.asarray(floor, dtype=float).reshape(-1, 1)
                            if np.ndim(floor) else np.asarray(floor, dtype=float), (u.shape[0], 1))
    # every statistic is per channel (λ aside, from the longest record): a few channels at a time
    return by_rows(lambda *b: _despike(*b, lam2, max_iterations), u, valid, floor
                   ).reshape(shape)


def _despike(u: np.ndarray, valid: np.ndarray, floor: np.ndarray, lam2: float,
             max_iterations: int) -> np.ndarray:
    """The iterations of :func:`goring_nikora` on the (channel, time) block ``u``."""
    spikes = np.zeros(u.shape, dtype=bool)
    all_valid = bool(valid.all())
    work = u if all_valid else fill_gaps(u, valid)
    rows = np.arange(u.shape[0])  # channels still changing: only those are iterated again
    for _ in range(max_iterations):
        w = work if rows.size == work.shape[0] else work[rows]
        out = _outside(w, lam2, floor[rows])
        new = out if all_valid else out & valid[rows]
        new &= ~spikes[rows]
        changed = new.any(axis=-1)
        if not changed.any():
            break
        spikes[rows] |= new
        rows = rows[changed]
        if work is u:
            work = u.copy()
        work[rows] = fill_gaps(u[rows], valid[rows] & ~spikes[rows])
    return spikes


def _median(c: np.ndarray) -> np.ndarray:
    """``np.median(c, axis=-1, keepdims=True)`` of a finite float32 block, bit for bit.

    Rows of whole numbers (a quantised record in units of its step) from their histogram
    (:func:`flumekit.qc.qartod.integer_median`, O(n), exact: their median is a whole or half
    number), the others from one selection: the upper middle value, and the lower one as the
    largest of the values below it (``np.median`` selects both, 20 % slower), averaged as numpy
    does (float32 sum, / 2)."""
    k = c.shape[-1] // 2
    whole = (np.rint(c) == c).all(axis=-1)
    out = np.empty((c.shape[0], 1), dtype=np.float32)
    if whole.any():
        w = c if whole.all() else c[whole]
        out[whole, 0] = integer_median(w.astype(np.int32))
    if whole.all():
        return out
    p = np.partition(c[~whole], k, axis=-1)
    hi = p[:, k:k + 1]
    out[~whole] = hi if c.shape[-1] % 2 else (p[:, :k].max(axis=-1, keepdims=True) + hi
                                                ) / np.float32(2)
    return out


def _central(f: np.ndarray) -> np.ndarray:
    """Central difference along the last axis, one-sided at the ends (as ``np.gradient``)."""
    g = np.empty_like(f)
    np.subtract(f[:, 2:], f[:, :-2], out=g[:, 1:-1])
    g[:, 1:-1] *= 0.5
    g[:, 0] = f[:, 1] - f[:, 0]
    g[:, -1] = f[:, -1] - f[:, -2]
    return g


def _outside(w: np.ndarray, lam2: float, floor: np.ndarray) -> np.ndarray:
    """Samples of the (channel, time) block ``w`` outside any of the three ellipses.

    Each ellipse test is a quadratic form in (u, Δu, Δ²u) with per-channel coefficients, so the
    products u², Δu², (Δ²u)² and u Δ²u are formed once and serve the standard deviations,
    the rotation angle and all three tests (about 20 passes over the block). The block is
    worked in single precision (7 digits, far finer than a velocity record's resolution; the
    sums accumulate in double), which halves the memory traffic that bounds the cost."""
    m = w.shape[-1]
    # in units of the floor where there is one (a quantised record's step: its values become
    # whole numbers, exact in single precision, and their median a histogram's); the test is
    # the same in any unit
    unit = np.where(floor > 0, floor, 1.0)
    c = np.empty(w.shape, dtype=np.float32)
    np.multiply(w, 1.0 / unit, out=c, casting="same_kind")
    floor = floor / unit
    c -= _median(c)
    du = _central(c)  # (u_(i+1) - u_(i-1)) / 2, Eq. (6)
    d2 = _central(du)  # Eq. (7)

    def total(x):
        return x.sum(axis=-1, keepdims=True, dtype=np.float64)

    sums = [total(c), total(du), total(d2)]
    c2 = c * c
    cd = c * d2
    du *= du  # Δu² from here on
    d2 *= d2  # (Δ²u)² from here on
    du2, d22 = du, d2
    sq = [total(c2), total(du2), total(d22)]
    f2 = floor * floor
    # per-channel variances from the sums (no centred copies)
    su2, sdu2, sd22 = (np.maximum(q / m - (s_ / m) ** 2, f2) for s_, q in zip(sums, sq,
                                                                               strict=True))
    theta = np.arctan2(total(cd), sq[0])  # Eq. (9)
    cos2, sin2 = np.cos(theta) ** 2, np.sin(theta) ** 2
    a1, b1 = lam2 * su2, lam2 * sd22
    det = cos2 - sin2
    with np.errstate(divide="ignore", invalid="ignore"):
        a2 = (a1 * cos2 - b1 * sin2) / det  # Eqs. (10)-(11) solved for a², b²
        b2 = (b1 * cos2 - a1 * sin2) / det
    # where the system is singular or a semi-axis would be imaginary, use the unrotated axes
    ok = np.isfinite(a2) & np.isfinite(b2) & (a2 > 0) & (b2 > 0)
    a2, b2 = np.where(ok, a2, a1), np.where(ok, b2, b1)
    # (u, Δu) and (Δu, Δ²u) ellipses with semi-axes λσ; the third rotated by θ:
    # x_r²/a² + y_r²/b² with x_r = u cosθ + Δ²u sinθ, y_r = -u sinθ + Δ²u cosθ, expanded
    sc = np.sin(theta) * np.cos(theta)

    def coef(x):
        return x.astype(np.float32)

    e = c2 * coef(1.0 / a1)
    e += du2 * coef(1.0 / (lam2 * sdu2))
    out = e > 1.0
    np.multiply(du2, coef(1.0 / (lam2 * sdu2)), out=e)
    e += d22 * coef(1.0 / b1)
    out |= e > 1.0
    np.multiply(c2, coef(cos2 / a2 + sin2 / b2), out=e)
    e += d22 * coef(sin2 / a2 + cos2 / b2)
    e += cd * coef(2.0 * sc * (1.0 / a2 - 1.0 / b2))
    out |= e > 1.0
    return out
