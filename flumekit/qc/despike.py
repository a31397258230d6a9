"""Phase-space despiking of velocity records (Goring and Nikora 2002, with Wahl 2003).

Goring, D. G. and Nikora, V. I. (2002), Despiking acoustic Doppler velocimeter data, J. Hydraul.
Eng. 128(1), 117-126; Wahl, T. L. (2003), Discussion, J. Hydraul. Eng. 129(6), 484-487.
"""

from __future__ import annotations

import numpy as np

from flumekit.qc.fill import fill_gaps


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
    spikes = np.zeros(u.shape, dtype=bool)
    n = int(valid.sum(axis=-1).max()) if u.size else 0
    if n < 5:
        return spikes.reshape(shape)
    lam = np.sqrt(2.0 * np.log(n))  # universal threshold, Eq. (2)
    floor = np.broadcast_to(np.asarray(floor, dtype=float).reshape(-1, 1)
                            if np.ndim(floor) else np.asarray(floor, dtype=float), (u.shape[0], 1))
    work = u if valid.all() else fill_gaps(u, valid)
    rows = np.arange(u.shape[0])  # channels still changing: only those are iterated again
    for _ in range(max_iterations):
        w = work[rows]
        c = w - np.median(w, axis=-1, keepdims=True)
        du = np.gradient(c, axis=-1)  # (u_(i+1) - u_(i-1)) / 2, Eq. (6)
        d2 = np.gradient(du, axis=-1)  # Eq. (7)
        fl = floor[rows]
        su = np.maximum(c.std(axis=-1, keepdims=True), fl)
        sdu = np.maximum(du.std(axis=-1, keepdims=True), fl)
        sd2 = np.maximum(d2.std(axis=-1, keepdims=True), fl)
        theta = np.arctan2(np.sum(c * d2, axis=-1, keepdims=True),
                           np.sum(c * c, axis=-1, keepdims=True))  # Eq. (9)
        cos2, sin2 = np.cos(theta) ** 2, np.sin(theta) ** 2
        a1, b1 = (lam * su) ** 2, (lam * sd2) ** 2
        det = cos2 - sin2
        with np.errstate(divide="ignore", invalid="ignore"):
            a2 = (a1 * cos2 - b1 * sin2) / det  # Eqs. (10)-(11) solved for a², b²
            b2 = (b1 * cos2 - a1 * sin2) / det
        # where the system is singular or a semi-axis would be imaginary, use the unrotated axes
        ok = np.isfinite(a2) & np.isfinite(b2) & (a2 > 0) & (b2 > 0)
        a2, b2 = np.where(ok, a2, a1), np.where(ok, b2, b1)
        xr_ = c * np.cos(theta) + d2 * np.sin(theta)
        yr_ = -c * np.sin(theta) + d2 * np.cos(theta)
        out = ((c / (lam * su)) ** 2 + (du / (lam * sdu)) ** 2 > 1.0) \
            | ((du / (lam * sdu)) ** 2 + (d2 / (lam * sd2)) ** 2 > 1.0) \
            | (xr_ ** 2 / a2 + yr_ ** 2 / b2 > 1.0)
        new = out & valid[rows] & ~spikes[rows]
        changed = new.any(axis=-1)
        if not changed.any():
            break
        spikes[rows] |= new
        rows = rows[changed]
        if work is u:
            work = u.copy()
        work[rows] = fill_gaps(u[rows], valid[rows] & ~spikes[rows])
    return spikes.reshape(shape)
