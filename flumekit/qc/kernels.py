"""The per-sample loops of the UVP tests, compiled (numba): despiking and the echo-level test.

Goring-Nikora despiking and the echo-level test, channel by channel. Both make a handful of
passes over each channel's record and keep per-channel statistics (medians, sums); written
with numpy, every pass is a temporary array. Compiled, one channel's record stays in the
CPU's cache through all passes, and a quantised record is worked in integers
(``flumekit bench qc`` measures them). The definitions they must equal, written with numpy,
are in tests/qc/test_qartod.py.

Imported only by the UVP tests, so that the probe and flap QC and the other stages do not
load numba (its import and the loading of the cached kernels cost a process a noticeable
fraction of a second). ``cache=True``: compiled once per installation into this package's
``__pycache__`` (numba falls back to a user cache directory when that is not writable); no
generic ``np.median`` or ``np.sort``, whose compilation is slow: :func:`_middle` selects
instead.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from flumekit.docstrings import doc
from flumekit.qc.flags import FAIL, GOOD, MAD_TO_STD, MISSING, NOT_EVALUATED

#: bins of the histogram median of whole-number records (values spanning more are sorted)
HIST_BINS = 1 << 14

#: whole-number records worked in integers (:func:`_outside`): values of at most 2^16 steps,
#: rows of at most 2^20 samples, so that no sum exceeds 2^62
_WHOLE_MAX = 1 << 16
_WHOLE_N = 1 << 20

#: no non-zero step (the start of a channel's resolution)
_NO_STEP = np.int64(2) ** 62


@njit(cache=True)
def _ranked(hist, span, n):
    """Return the bins of the values of ranks (n - 1) // 2 and n // 2 in a histogram.

    (a, b), 0-based ranks, in the histogram ``hist[:span]`` of n values; their mean is the
    median.
    """
    r1, r2 = (n - 1) // 2, n // 2
    cum = 0
    a = -1
    for k in range(span):
        cum += hist[k]
        if a < 0 and cum > r1:
            a = k
        if cum > r2:
            return a, k
    return a, span - 1


@njit(cache=True)
def _middle(x):
    """Return the values of ranks (n - 1) // 2 and n // 2 (0-based) of ``x``.

    ``x`` is reordered in place; the mean of the two is the median. Quickselect (Hoare partition
    about the middle element, which keeps sorted and constant records linear), then the least
    value above rank (n - 1) // 2. Written out rather than ``np.median`` or ``np.sort``, whose
    generic implementations are slow to compile on each fresh installation's first run.
    """
    n = x.size
    k = (n - 1) // 2
    lo, hi = 0, n - 1
    while lo < hi:
        pivot = x[(lo + hi) // 2]
        i, j = lo, hi
        while i <= j:
            while x[i] < pivot:
                i += 1
            while x[j] > pivot:
                j -= 1
            if i <= j:
                x[i], x[j] = x[j], x[i]
                i += 1
                j -= 1
        # x[lo:j + 1] <= pivot <= x[i:hi + 1], and x[j + 1:i] == pivot
        if k <= j:
            hi = j
        elif k >= i:
            lo = i
        else:
            break
    a = x[k]
    if n % 2:
        return a, a
    b = x[k + 1]
    for i in range(k + 2, n):  # every value above rank k is at least x[k]
        b = min(b, x[i])
    return a, b


# -- Goring-Nikora phase-space despiking (flumekit.qc.despike) ---------------------------------

@njit(cache=True)
def _fill(src, ok, unit, w):
    """Set w = src / unit, the samples not ``ok`` linearly interpolated between the ok ones.

    The nearest ok value is held before the first and after the last, 0 where none is ok
    (:func:`flumekit.qc.fill.fill_gaps` without a limit).
    """
    n = src.size
    prev = -1
    for i in range(n):
        if ok[i]:
            v = src[i] / unit
            w[i] = v
            if prev < i - 1:
                if prev < 0:
                    w[:i] = v
                else:
                    a, k = w[prev], i - prev
                    for j in range(prev + 1, i):
                        w[j] = a + (j - prev) / k * (v - a)
            prev = i
    if prev < 0:
        w[:] = 0.0
    else:
        w[prev + 1:] = w[prev]


@njit(cache=True)
def _fill_quantised(src, ok, unit, w):
    """Run :func:`_fill`, the filled samples rounded to whole numbers where the ok ones are whole.

    For a quantised record in units of its step: the placeholders stay on the instrument's grid,
    and the record is worked in integers (:func:`_outside`).
    """
    _fill(src, ok, unit, w)
    for i in range(w.size):
        if ok[i] and abs(w[i] - np.rint(w[i])) > 1e-6:
            return
    for i in range(w.size):
        w[i] = np.rint(w[i])  # halves to even, as numpy rounds


@njit(cache=True)
def _whole(w, k):
    """Test whether every value of ``w`` lies within 1e-6 of a whole number of at most 2^30.

    A quantised record in units of its step, up to the rounding of the division; those numbers
    are written in ``k`` (int32) and returned with their extremes.
    """
    bad = False
    lo = hi = np.int32(0)
    for i in range(w.size):
        r = np.floor(w[i] + 0.5)
        bad |= (abs(w[i] - r) > 1e-6) | (abs(r) > 2.0 ** 30)
        k[i] = np.int32(r) if abs(r) <= 2.0 ** 30 else 0
        lo = min(lo, k[i]) if i else k[i]
        hi = max(hi, k[i]) if i else k[i]
    return not bad, lo, hi


@njit(cache=True)
def _differences(C, D, E):
    """Set D = 4Δu and E = 8Δ²u from C = 2u (any numeric type).

    Central differences, one-sided at the ends as np.gradient's (GN 2002, Eqs. 6-7), in units
    where each is an integer when u is a whole or half number.
    """
    n = C.size
    D[0], D[n - 1] = 2 * (C[1] - C[0]), 2 * (C[n - 1] - C[n - 2])
    for i in range(1, n - 1):
        D[i] = C[i + 1] - C[i - 1]
    E[0], E[n - 1] = 2 * (D[1] - D[0]), 2 * (D[n - 1] - D[n - 2])
    for i in range(1, n - 1):
        E[i] = D[i + 1] - D[i - 1]


@njit(cache=True)
def _sums(X, D, E, zero):
    """Return (ΣX, ΣX², ΣD, ΣD², ΣE, ΣE², ΣXE), accumulated from ``zero``.

    int64 ``zero``: exact, whatever the order; float64: in order, no reassociation, the same
    bits on every CPU.
    """
    s1 = s2 = t1 = t2 = q1 = q2 = sxe = zero
    for i in range(X.size):
        x, y, z = X[i] + zero, D[i] + zero, E[i] + zero
        s1 += x
        s2 += x * x
        t1 += y
        t2 += y * y
        q1 += z
        q2 += z * z
        sxe += x * z
    return s1, s2, t1, t2, q1, q2, sxe


@njit(cache=True)
def _coefficients(n, s1, s2, t1, t2, q1, q2, sce, lam2, fl):
    """Return the coefficients of the three ellipse tests (GN 2002, Eqs. 2, 9-11).

    From the sums of C = 2u, D = 4Δu, E = 8Δ²u, of their squares and of C E; ``fl``: floor of
    the standard deviations, in the units of u.
    """
    f2 = fl * fl
    su2 = max(s2 / (4.0 * n) - (s1 / (2.0 * n)) ** 2, f2)
    sdu2 = max(t2 / (16.0 * n) - (t1 / (4.0 * n)) ** 2, f2)
    sd22 = max(q2 / (64.0 * n) - (q1 / (8.0 * n)) ** 2, f2)
    theta = np.arctan2(sce / 16.0, s2 / 4.0)  # Eq. (9)
    cs, sn = np.cos(theta), np.sin(theta)
    cos2, sin2 = cs * cs, sn * sn
    a1, b1 = lam2 * su2, lam2 * sd22
    # Eqs. (10)-(11) solved for a², b²; where the system is singular or a semi-axis would be
    # imaginary, the unrotated axes
    a2, b2 = a1, b1
    det = cos2 - sin2
    if det != 0.0:
        x2 = (a1 * cos2 - b1 * sin2) / det
        y2 = (b1 * cos2 - a1 * sin2) / det
        if np.isfinite(x2) and np.isfinite(y2) and x2 > 0.0 and y2 > 0.0:
            a2, b2 = x2, y2
    # (u, Δu) and (Δu, Δ²u) ellipses with semi-axes λσ; the third rotated by θ:
    # x_r²/a² + y_r²/b² with x_r = u cosθ + Δ²u sinθ, y_r = -u sinθ + Δ²u cosθ, expanded
    return (1.0 / (lam2 * sdu2), 1.0 / a1, 1.0 / b1, cos2 / a2 + sin2 / b2,
            sin2 / a2 + cos2 / b2, 2.0 * sn * cs * (1.0 / a2 - 1.0 / b2))


@njit(cache=True)
def _test(X, xs, shift, D, ds, E, es, coefficients, out):
    """Set out[i]: sample i lies outside one of the three ellipses.

    u = xs X - shift, Δu = ds D, Δ²u = es E (each exact: whole and half numbers, scaled by
    powers of 2).
    """
    k_du, k_u1, k_d1, k_u3, k_d3, k_c3 = coefficients
    for i in range(X.size):
        x, y, z = xs * X[i] - shift, ds * D[i], es * E[i]
        q = y * y * k_du
        xx, zz = x * x, z * z
        # bitwise |: no branch, the loop vectorises
        out[i] = ((xx * k_u1 + q > 1.0) | (zz * k_d1 + q > 1.0)
                  | (xx * k_u3 + zz * k_d3 + x * z * k_c3 > 1.0))


@njit(cache=True)
def _outside(w, lam2, fl, work, out):
    """Set out[i]: sample i of the record ``w`` lies outside one of the three ellipses.

    Goring and Nikora (2002), see :func:`flumekit.qc.despike.goring_nikora`; ``w`` in units of
    the floor, about its median.

    A record of whole numbers (a quantised one) of modest size is worked in integers: its
    median from its histogram (O(n)), C = 2u, D = 4Δu, E = 8Δ²u and their sums exact, those
    of C from those of the record itself (C = 2k - 2M: D and E do not depend on the median,
    so no pass waits for it). Other records: the median by selection, the sums in double
    precision, in order (no reassociation: the same bits on every CPU). Both forms give a
    whole-number record the same statistics and flags bit for bit (scaling by a power of 2 is
    exact in floating point).
    """
    k, D, E, hist, Cf, Df, Ef = work
    n = w.size
    whole, lo, hi = _whole(w, k)
    if whole and hi - lo < HIST_BINS and n <= _WHOLE_N and max(-lo, hi) <= _WHOLE_MAX:
        span = hi - lo + 1
        hist[:span] = 0
        for i in range(n):
            hist[k[i] - lo] += 1
        # D and E of k: halves of those of C = 2k - 2M (the median cancels)
        _differences(k, D, E)
        sk, skk, sd, sdd, se, see, ske = _sums(k, D, E, np.int64(0))
        a, b = _ranked(hist, span, n)
        twice = 2 * lo + a + b  # 2M, an integer
        # the sums of C = 2k - 2M, D_C = 2D and E_C = 2E from those of k, D and E
        c = _coefficients(n, 2 * sk - n * twice, 4 * skk - 4 * twice * sk + n * twice * twice,
                          2 * sd, 4 * sdd, 2 * se, 4 * see, 4 * ske - 2 * twice * se, lam2, fl)
        _test(k, 1.0, 0.5 * twice, D, 0.5, E, 0.25, c, out)
        return
    if whole:  # too wide for the integers: snapped all the same
        for i in range(n):
            w[i] = np.floor(w[i] + 0.5)
    Df[:] = w  # a copy to select in
    a, b = _middle(Df)
    med = a if n % 2 else (a + b) / 2  # as np.median
    for i in range(n):
        Cf[i] = 2.0 * (w[i] - med)
    _differences(Cf, Df, Ef)
    c = _coefficients(n, *_sums(Cf, Df, Ef, 0.0), lam2, fl)
    _test(Cf, 0.5, 0.0, Df, 0.25, Ef, 0.125, c, out)


@njit(cache=True)
def _buffers(n):
    """Return the work arrays of one row of n samples.

    (record as read, record worked, outside, ok) and those of :func:`_outside`.
    """
    return (np.empty(n), np.empty(n), np.empty(n, dtype=np.bool_), np.empty(n, dtype=np.bool_),
            (np.empty(n, dtype=np.int32), np.empty(n, dtype=np.int32),
             np.empty(n, dtype=np.int32), np.empty(HIST_BINS, dtype=np.int64),
             np.empty(n), np.empty(n), np.empty(n)))


@njit(cache=True)
def _spikes_row(src, ok, every, floor, lam2, max_iterations, sp, buffers):
    """Run Goring-Nikora on one row ``src``, iterated, setting its spikes in ``sp``.

    ``ok``: its valid samples (all valid: ``every``; updated: the spikes leave it). A spike is
    replaced by linear interpolation (on the record's grid when it is quantised) and the row
    tested again until no new spike is found, ``max_iterations`` at most. The row is worked in
    units of its ``floor`` (the velocity resolution), where a quantised record's values are
    whole numbers; ``buffers[1]`` holds it so when ``every`` (the caller's copy).
    """
    _, w, out, _, work = buffers
    n = src.size
    unit = floor if floor > 0.0 else 1.0
    fl = floor / unit
    if not every:
        _fill_quantised(src, ok, unit, w)
    for it in range(max_iterations):
        _outside(w, lam2, fl, work, out)
        changed = False
        for i in range(n):
            new = out[i] & ok[i]
            sp[i] |= new
            ok[i] &= ~new
            changed |= new
        if not changed or it == max_iterations - 1:
            break
        _fill_quantised(src, ok, unit, w)


@njit(cache=True)
def _universal(u, exclude):
    """Return λ² = 2 ln n (Goring and Nikora 2002, Eq. 2) of the longest row of samples tested.

    The finite samples of ``u`` not ``exclude``-d (channel x time) count; the same λ serves
    every row; 0 below 5 samples (nothing is evaluated). A row tested whole ends the search
    (the usual case: the first).
    """
    m, n = u.shape
    longest = 0
    for r in range(m):
        count = 0
        for i in range(n):
            count += np.isfinite(u[r, i]) & ~exclude[r, i]
        longest = max(longest, count)
        if longest == n:
            break
    return 2.0 * np.log(longest) if longest >= 5 else 0.0


@njit(cache=True)
def _departure(x, k):
    """Return ``|x_k - (x_(k-1) + x_(k+1))/2|``, 0 at the first and last samples."""
    if k < 1 or k > x.size - 2:
        return 0.0
    return abs(x[k] - 0.5 * (x[k - 1] + x[k + 1]))


@doc
@njit(cache=True)
def despike_flags_rows(u, exclude, floor, max_iterations, peaks):
    """Return the QARTOD flags of the Goring-Nikora despiking of each row of ``u``.

    Only the finite samples not ``exclude``-d are tested (λ of :func:`_universal`; per-row
    ``floor``): FAIL at the spikes (``peaks``: at those only whose departure from their
    neighbours' mean is the local largest, since a spike moves the derivatives of its two
    neighbours, which the method then flags with it), MISSING where not finite, NOT_EVALUATED
    where finite and excluded, else GOOD. The others are interpolated over
    (:func:`_spikes_row`).

    Parameters
    ----------
    u : numpy.ndarray
        Velocity [m s-1], (channel, time), any memory layout.
    exclude : numpy.ndarray
        Boolean, of u's shape: samples not evaluated.
    floor : numpy.ndarray
        Lower bound of the standard deviations of each row [m s-1] (its velocity resolution).
    %(max_iterations)s
    peaks : bool
        Flag only the spikes that are the local largest departure.

    Returns
    -------
    numpy.ndarray
        QARTOD flags (uint8) of u's shape.

    References
    ----------
    Goring, D. G. and Nikora, V. I. (2002). Despiking acoustic Doppler velocimeter data.
    J. Hydraul. Eng. 128(1), 117-126.
    """
    m, n = u.shape
    lam2 = _universal(u, exclude)
    flags = np.empty((m, n), dtype=np.uint8)
    buffers = _buffers(n)
    src, w, _, ok, _ = buffers
    sp = np.empty(n, dtype=np.bool_)
    for r in range(m):
        unit = floor[r] if floor[r] > 0.0 else 1.0
        # a bool computed, not the constant True: numba would compile _spikes_row and its
        # callees twice, once for the literal True of an empty row and once for a bool
        every = n >= 0
        f = flags[r]
        for i in range(n):  # the row copied once: a transposed view is strided
            v = u[r, i]
            src[i] = v
            w[i] = v / unit
            ok[i] = np.isfinite(v) & ~exclude[r, i]
            every &= ok[i]
            f[i] = GOOD if ok[i] else (NOT_EVALUATED if np.isfinite(v) else MISSING)
        if lam2 == 0.0:
            continue
        sp[:] = False
        _spikes_row(src, ok, every, floor[r], lam2, max_iterations, sp, buffers)
        for j in range(n):
            if sp[j]:
                d = _departure(src, j)
                if not peaks or (d >= _departure(src, j - 1) and d >= _departure(src, j + 1)):
                    f[j] = FAIL
    return flags


# -- echo-level test (flumekit.qc.qartod.level_test, integer records) -------------------------

@njit(cache=True)
def level_fail_rows(x, threshold):
    """Return where ``|x - median(x)|`` exceeds ``threshold`` robust standard deviations, per row.

    The robust standard deviation is 1.4826 MAD, at least the channel's resolution (its
    smallest non-zero step); exact: in half steps, ``|2x - 2M|`` against the floor of twice the
    bound. The median and the MAD are read from the row's histogram (the deviations' histogram
    from the values'), O(n); a row spanning more values than ``HIST_BINS`` by selection instead
    (:func:`_middle`).

    Parameters
    ----------
    x : numpy.ndarray
        Integer record (channel, time), any memory layout (echo amplitudes [counts]).
    threshold : float
        Robust standard deviations beyond which a sample fails [-].

    Returns
    -------
    numpy.ndarray
        Boolean, of x's shape: True where the sample fails.
    """
    m, n = x.shape
    fail = np.empty((m, n), dtype=np.bool_)
    row = np.empty(n, dtype=np.int64)
    hist = np.empty(HIST_BINS, dtype=np.int64)
    dhist = np.empty(2 * HIST_BINS + 1, dtype=np.int64)
    for r in range(m):
        for i in range(n):  # the row copied once (a transposed view is strided)
            row[i] = x[r, i]
        lo = hi = row[0]
        for i in range(n):
            lo = min(lo, row[i])
            hi = max(hi, row[i])
        res = _NO_STEP  # the smallest non-zero step
        for i in range(1, n):
            d = abs(row[i] - row[i - 1])
            res = min(res, d if d > 0 else _NO_STEP)
        res = 0 if res == _NO_STEP else res
        span = hi - lo + 1
        if span <= HIST_BINS:
            hist[:span] = 0
            for i in range(n):
                hist[row[i] - lo] += 1
            a, b = _ranked(hist, span, n)
            twice = 2 * lo + a + b  # 2M, an integer
            # |2x - 2M| of each value's bin, counted
            dspan = 2 * span + 1
            dhist[:dspan] = 0
            for k in range(span):
                dhist[abs(2 * (lo + k) - twice)] += hist[k]
            a, b = _ranked(dhist, dspan, n)
        else:
            a, b = _middle(row.copy())
            twice = a + b
            a, b = _middle(np.abs(2 * row - twice))
        scale = max(MAD_TO_STD * 0.5 * (0.5 * (a + b)), float(res))
        # |2x - 2M| > bound for an integer: beyond its floor, compared in integers
        bound = np.int64(min(np.floor(2.0 * threshold * scale), 2.0 ** 62))
        for i in range(n):
            fail[r, i] = abs(2 * row[i] - twice) > bound
    return fail
