"""Phase-space despiking of velocity records (Goring and Nikora 2002, with Wahl 2003).

Goring, D. G. and Nikora, V. I. (2002), Despiking acoustic Doppler velocimeter data, J. Hydraul.
Eng. 128(1), 117-126; Wahl, T. L. (2003), Discussion, J. Hydraul. Eng. 129(6), 484-487.
"""

from __future__ import annotations

import numpy as np

from flumekit.qc.blocks import by_rows
from flumekit.qc.fill import fill_gaps
from flumekit.qc.qartod import integer_moments


def goring_nikora(u: np.ndarray, floor: float | np.ndarray = 0.0, max_iterations: int = 20,
                  exclude: np.ndarray | None = None) -> np.ndarray:
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
    exclude : Samples ignored as NaN ones are (True), of u's shape; None: none.

    Returns
    -------
    Boolean array of u's shape, True at spikes.
    """
    u = np.asarray(u, dtype=float)
    shape = u.shape
    u = u.reshape(-1, shape[-1])
    valid = np.isfinite(u)
    if exclude is not None:
        valid &= ~np.asarray(exclude, dtype=bool).reshape(u.shape)
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


def _centre(c: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Subtract from the float32 block ``c`` (in place) each row's median, as
    ``np.median(c, axis=-1, keepdims=True)`` gives it bit for bit; return (Σc, Σc², whole)
    after it (float64, exact) and which rows hold whole numbers only.

    Rows of whole numbers (a quantised record in units of its step) take their median and
    sums from their histogram (:func:`flumekit.qc.qartod.integer_moments`, O(n), exact: the
    median is a whole or half number); the others one selection (the upper middle value, and
    the lower one as the largest of the values below it: ``np.median`` selects both, 20 %
    slower), averaged as numpy does (float32 sum, / 2), and sums in double."""
    m = c.shape[-1]
    k = m // 2
    whole = (np.rint(c) == c).all(axis=-1)
    med = np.empty((c.shape[0], 1), dtype=np.float32)
    s1 = np.empty((c.shape[0], 1))
    s2 = np.empty((c.shape[0], 1))
    if whole.any():
        rows = slice(None) if whole.all() else whole
        mk, t1, t2 = integer_moments(c[rows].astype(np.int32))
        med[rows, 0] = mk
        # about the median: Σ(x - M) = Σx - mM, Σ(x - M)² = Σx² - 2MΣx + mM², exact (whole
        # and half numbers far below 2^53)
        s1[rows, 0] = t1 - m * mk
        s2[rows, 0] = t2 - 2.0 * mk * t1 + m * mk * mk
    if not whole.all():
        p = np.partition(c[~whole], k, axis=-1)
        hi = p[:, k:k + 1]
        med[~whole] = hi if m % 2 else (p[:, :k].max(axis=-1, keepdims=True) + hi
                                        ) / np.float32(2)
    c -= med
    if not whole.all():
        s1[~whole] = c[~whole].sum(axis=-1, keepdims=True, dtype=np.float64)
        s2[~whole] = np.square(c[~whole]).sum(axis=-1, keepdims=True, dtype=np.float64)
    return s1, s2, whole


def _central(f: np.ndarray) -> np.ndarray:
    """Central difference along the last axis, one-sided at the ends (as ``np.gradient``)."""
    g = np.empty_like(f)
    np.subtract(f[:, 2:], f[:, :-2], out=g[:, 1:-1])
    g[:, 1:-1] *= 0.5
    g[:, 0] = f[:, 1] - f[:, 0]
    g[:, -1] = f[:, -1] - f[:, -2]
    return g


def _central_sum(f: np.ndarray) -> np.ndarray:
    """Σ of :func:`_central` (f) per row from the end values: the interior differences
    telescope, (f_(n-1) + f_(n-2) - f_0 - f_1)/2, plus the one-sided ends."""
    return (3.0 * f[:, -1:].astype(float) - f[:, -2:-1] - 3.0 * f[:, :1] + f[:, 1:2]) / 2.0


def _square_sum(x: np.ndarray, step: float, exact: np.ndarray) -> np.ndarray:
    """Σx per row of a block of non-negative multiples of ``step`` (float64, (rows, 1)).

    Summed in single precision, which is exact where every partial sum is a multiple of the
    step below 2^24 steps (whatever the order of the additions): there the rows ``exact``
    (whole-number records) keep it, the others are summed in double."""
    s = x.sum(axis=-1, keepdims=True, dtype=np.float32).astype(float)
    redo = ~exact[:, None] | ~(s < step * 2.0 ** 24)
    if redo.any():
        r = redo[:, 0]
        s[r] = x[r].sum(axis=-1, keepdims=True, dtype=np.float64)
    return s


def _outside(w: np.ndarray, lam2: float, floor: np.ndarray) -> np.ndarray:
    """Samples of the (channel, time) block ``w`` outside any of the three ellipses.

    Each ellipse test is a quadratic form in (u, Δu, Δ²u) with per-channel coefficients, so the
    products u², Δu², (Δ²u)² and u Δ²u are formed once and serve the standard deviations,
    the rotation angle and all three tests. The block is worked in single precision, in units
    of the floor where there is one: a quantised record's values are then whole numbers, whose
    medians, sums and products are exact (:func:`_centre`, :func:`_square_sum`); otherwise 7
    digits, far finer than a velocity record's resolution, with the sums in double. That
    halves the memory traffic that bounds the cost."""
    m = w.shape[-1]
    # in units of the floor where there is one; the test is the same in any unit
    unit = np.where(floor > 0, floor, 1.0)
    c = np.empty(w.shape, dtype=np.float32)
    np.multiply(w, 1.0 / unit, out=c, casting="same_kind")
    floor = floor / unit
    sc1, sc2, whole = _centre(c)
    du = _central(c)  # (u_(i+1) - u_(i-1)) / 2, Eq. (6)
    d2 = _central(du)  # Eq. (7)
    # exact values (whole-number rows): the telescoped sums are the sums; the others summed
    sdu, sd2 = _central_sum(c), _central_sum(du)
    if not whole.all():
        sdu[~whole] = du[~whole].sum(axis=-1, keepdims=True, dtype=np.float64)
        sd2[~whole] = d2[~whole].sum(axis=-1, keepdims=True, dtype=np.float64)
    cd = c * d2
    du *= du  # Δu² from here on
    d2 *= d2  # (Δ²u)² from here on
    du2, d22 = du, d2
    # whole-number records: u a whole or half number, Δu a half, Δ²u a quarter: Δu² is a
    # multiple of 1/4, (Δ²u)² of 1/16, u Δ²u of 1/8
    sdu2, sd22 = _square_sum(du2, 0.25, whole), _square_sum(d22, 1 / 16, whole)
    # Σ|u Δ²u| <= sqrt(Σu² Σ(Δ²u)²) bounds its partial sums
    scd = cd.sum(axis=-1, keepdims=True, dtype=np.float32).astype(float)
    redo = ~whole[:, None] | ~(np.sqrt(sc2 * sd22) < 2.0 ** 21)
    if redo.any():
        r = redo[:, 0]
        scd[r] = cd[r].sum(axis=-1, keepdims=True, dtype=np.float64)
    f2 = floor * floor
    # per-channel variances from the sums (no centred copies)
    su2, sdu2, sd22 = (np.maximum(q / m - (s_ / m) ** 2, f2)
                       for s_, q in ((sc1, sc2), (sdu, sdu2), (sd2, sd22)))
    theta = np.arctan2(scd, sc2)  # Eq. (9)
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

    q = du2 * coef(1.0 / (lam2 * sdu2))  # Δu²/(λσ_Δu)², in the first two tests
    c *= c  # u² from here on
    e = c * coef(1.0 / a1)
    e += q
    out = e > 1.0
    np.multiply(d22, coef(1.0 / b1), out=e)
    e += q
    out |= e > 1.0
    np.multiply(c, coef(cos2 / a2 + sin2 / b2), out=e)
    np.multiply(d22, coef(sin2 / a2 + cos2 / b2), out=q)
    e += q
    np.multiply(cd, coef(2.0 * sc * (1.0 / a2 - 1.0 / b2)), out=q)
    e += q
    out |= e > 1.0
    return out
