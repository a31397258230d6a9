"""The per-sample loops of the UVP tests, compiled (numba): Goring-Nikora despiking and the
echo-level test, channel by channel.

Both make a handful of passes over each channel's record and keep per-channel statistics
(medians, sums); written with numpy, every pass is a temporary array, and a UVP beam (360
channels x 3000 profiles) took 13-21 ms to despike and 6 ms for the echo level. Compiled, one
channel's record stays in the CPU's cache through all passes (see ``flumekit bench qc``).
The numpy definitions they must equal are in tests/qc/test_qartod.py.

Imported only by the tests that need it, so numba (0.2 s to import) is not loaded by the
probe and flap QC or any other stage. ``cache=True``: compiled once per installation, into
this package's ``__pycache__`` (numba falls back to a user cache directory when that is not
writable).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from flumekit.qc.qartod import MAD_TO_STD

#: bins of the histogram median of whole-number records (values spanning more are sorted)
HIST_BINS = 1 << 14


@njit(cache=True)
def _ranked(hist, span, n):
    """(a, b): the bins of the values of ranks (n - 1) // 2 and n // 2 (0-based) in the
    histogram ``hist[:span]`` of n values; their mean is the median."""
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


# -- Goring-Nikora phase-space despiking (flumekit.qc.despike) ---------------------------------

@njit(cache=True)
def _fill(src, ok, unit, w):
    """w = src / unit, the samples not ``ok`` linearly interpolated between the ok ones around
    them, the nearest held before the first and after the last, 0 where none is ok
    (:func:`flumekit.qc.fill.fill_gaps` without a limit)."""
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
def _snap(w):
    """(whole, lo, hi) of the record ``w``: whether every value lies within 1e-6 of a whole
    number (a quantised record in units of its step, up to the rounding of the division),
    then snapped to it, and the extremes."""
    err = 0.0
    lo = hi = w[0]
    for i in range(w.size):
        v = w[i]
        err = max(err, abs(v - np.rint(v)))
        lo = min(lo, v)
        hi = max(hi, v)
    if err > 1e-6:
        return False, lo, hi
    for i in range(w.size):
        w[i] = np.rint(w[i])
    return True, np.rint(lo), np.rint(hi)


@njit(cache=True)
def _median(w, whole, lo, hi, hist, tmp):
    """Median of ``w``: from its histogram when its values are whole numbers of a modest span
    (O(n), exact), else by selection on the copy ``tmp``."""
    if whole and hi - lo < hist.size:
        span = int(hi - lo) + 1
        hist[:span] = 0
        for i in range(w.size):
            hist[int(w[i] - lo)] += 1
        a, b = _ranked(hist, span, w.size)
        return lo + 0.5 * (a + b)
    tmp[:] = w
    return np.median(tmp)


@njit(cache=True)
def _outside(w, whole, lo, hi, lam2, fl, c, du, d2, hist, tmp, out):
    """out[i]: sample i of the record ``w`` lies outside one of the three ellipses
    (Goring and Nikora 2002, Eqs. 2, 6-11; see :func:`flumekit.qc.despike.goring_nikora`).
    ``fl``: floor of the standard deviations, in the units of ``w``."""
    n = w.size
    med = _median(w, whole, lo, hi, hist, tmp)
    for i in range(n):
        c[i] = w[i] - med  # u, the fluctuation about the median
    # central differences, one-sided at the ends (np.gradient): Eqs. (6)-(7)
    du[0], du[n - 1] = c[1] - c[0], c[n - 1] - c[n - 2]
    for i in range(1, n - 1):
        du[i] = 0.5 * (c[i + 1] - c[i - 1])
    d2[0], d2[n - 1] = du[1] - du[0], du[n - 1] - du[n - 2]
    for i in range(1, n - 1):
        d2[i] = 0.5 * (du[i + 1] - du[i - 1])
    # sums in order (no reassociation): the same bits on every CPU
    s1 = s2 = t1 = t2 = q1 = q2 = scd = 0.0
    for i in range(n):
        x, y, z = c[i], du[i], d2[i]
        s1 += x
        s2 += x * x
        t1 += y
        t2 += y * y
        q1 += z
        q2 += z * z
        scd += x * z
    f2 = fl * fl
    su2 = max(s2 / n - (s1 / n) ** 2, f2)
    sdu2 = max(t2 / n - (t1 / n) ** 2, f2)
    sd22 = max(q2 / n - (q1 / n) ** 2, f2)
    theta = np.arctan2(scd, s2)  # Eq. (9)
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
    k_du = 1.0 / (lam2 * sdu2)
    k_u1, k_d1 = 1.0 / a1, 1.0 / b1
    k_u3 = cos2 / a2 + sin2 / b2
    k_d3 = sin2 / a2 + cos2 / b2
    k_c3 = 2.0 * sn * cs * (1.0 / a2 - 1.0 / b2)
    for i in range(n):
        x, y, z = c[i], du[i], d2[i]
        q = y * y * k_du
        xx, zz = x * x, z * z
        # bitwise |: no branch, the loop vectorises
        out[i] = ((xx * k_u1 + q > 1.0) | (zz * k_d1 + q > 1.0)
                  | (xx * k_u3 + zz * k_d3 + x * z * k_c3 > 1.0))


@njit(cache=True)
def goring_nikora_rows(u, valid, floor, lam2, max_iterations):
    """Spikes of each row of ``u`` (channel, time; any memory layout) by the phase-space
    method, iterated: a spike is replaced by linear interpolation and the row tested again
    until no new spike is found, ``max_iterations`` at most. Samples not ``valid`` are
    interpolated over and never flagged. The row is worked in units of its ``floor`` (the
    velocity resolution), where a quantised record's values are whole numbers.

    Returns the boolean spike mask, u's shape."""
    m, n = u.shape
    spikes = np.zeros((m, n), dtype=np.bool_)
    src, w, c = np.empty(n), np.empty(n), np.empty(n)
    du, d2, tmp = np.empty(n), np.empty(n), np.empty(n)
    ok = np.empty(n, dtype=np.bool_)
    out = np.empty(n, dtype=np.bool_)
    hist = np.empty(HIST_BINS, dtype=np.int64)
    for r in range(m):
        unit = floor[r] if floor[r] > 0.0 else 1.0
        fl = floor[r] / unit
        every = True
        for i in range(n):  # the row copied once: a transposed view is strided
            src[i] = u[r, i]
            ok[i] = valid[r, i]
            every &= ok[i]
        if every:
            for i in range(n):
                w[i] = src[i] / unit
        else:
            _fill(src, ok, unit, w)
        sp = spikes[r]
        for it in range(max_iterations):
            whole, lo, hi = _snap(w)
            _outside(w, whole, lo, hi, lam2, fl, c, du, d2, hist, tmp, out)
            changed = False
            for i in range(n):
                new = out[i] & ok[i]
                sp[i] |= new
                ok[i] &= ~new
                changed |= new
            if not changed or it == max_iterations - 1:
                break
            _fill(src, ok, unit, w)
    return spikes


# -- echo-level test (flumekit.qc.qartod.level_test, integer records) -------------------------

@njit(cache=True)
def level_fail_rows(x, threshold):
    """FAIL (True) where |x - median(x)| exceeds ``threshold`` robust standard deviations
    (1.4826 MAD, at least the channel's resolution: its smallest non-zero step) per row of the
    integer array ``x`` (channel, time; any layout); exact: in half steps, |2x - 2M| against
    the floor of twice the bound.

    The median and the MAD are read from the row's histogram (the deviations' histogram from
    the values'), O(n); a row spanning more values than ``HIST_BINS`` is sorted instead."""
    m, n = x.shape
    fail = np.empty((m, n), dtype=np.bool_)
    row = np.empty(n, dtype=np.int64)
    hist = np.empty(HIST_BINS, dtype=np.int64)
    dhist = np.empty(2 * HIST_BINS + 1, dtype=np.int64)
    r1, r2 = (n - 1) // 2, n // 2
    for r in range(m):
        res = 0
        lo = hi = np.int64(x[r, 0])
        for i in range(n):  # the row copied once (a transposed view is strided)
            v = np.int64(x[r, i])
            row[i] = v
            lo = min(lo, v)
            hi = max(hi, v)
            if i:
                d = abs(v - row[i - 1])
                if d > 0 and (res == 0 or d < res):
                    res = d
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
            srt = np.sort(row)
            twice = srt[r1] + srt[r2]
            dev = np.sort(np.abs(2 * row - twice))
            a, b = dev[r1], dev[r2]
        scale = max(MAD_TO_STD * 0.5 * (0.5 * (a + b)), float(res))
        bound = np.floor(2.0 * threshold * scale)
        for i in range(n):
            fail[r, i] = abs(2 * row[i] - twice) > bound
    return fail
