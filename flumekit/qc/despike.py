"""Phase-space despiking of velocity records (Goring and Nikora 2002, with Wahl 2003).

Goring, D. G. and Nikora, V. I. (2002), Despiking acoustic Doppler velocimeter data, J. Hydraul.
Eng. 128(1), 117-126; Wahl, T. L. (2003), Discussion, J. Hydraul. Eng. 129(6), 484-487.
"""

from __future__ import annotations

import numpy as np


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
    from flumekit.qc.kernels import goring_nikora_rows

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
    floor = np.broadcast_to(np.asarray(floor, dtype=float).reshape(-1), (u.shape[0],))
    # every statistic is per channel (λ aside, from the longest record): channel by channel
    return goring_nikora_rows(u, valid, np.ascontiguousarray(floor), lam2,
                              int(max_iterations)).reshape(shape)
