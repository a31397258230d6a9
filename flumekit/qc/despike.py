"""Phase-space despiking of velocity records (Goring and Nikora 2002, with Wahl 2003).

Goring, D. G. and Nikora, V. I. (2002), Despiking acoustic Doppler velocimeter data, J. Hydraul.
Eng. 128(1), 117-126; Wahl, T. L. (2003), Discussion, J. Hydraul. Eng. 129(6), 484-487.
"""

from __future__ import annotations

import numpy as np

from flumekit.qc.flags import FAIL


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
    ex = None if exclude is None else np.asarray(exclude, dtype=bool).reshape(u.shape)
    # every statistic is per channel (λ aside, from the longest record): channel by channel
    return (_flags(u, floor, max_iterations, ex, peaks=False) == FAIL).reshape(shape)


def despike_flags(u: np.ndarray, floor: float | np.ndarray = 0.0, max_iterations: int = 1,
                  exclude: np.ndarray | None = None) -> np.ndarray:
    """QARTOD flags of the despiking (:func:`goring_nikora`) of velocity records (channel,
    time; any layout), as bytes: FAIL at the spikes whose departure from their neighbours'
    mean, |u_n - (u_(n-1) + u_(n+1))/2|, is at least that of both neighbours (a spike moves
    the derivatives of its two neighbours too, which the method then flags with it: GN 2002,
    §4), MISSING where not finite, NOT_EVALUATED where finite and ``exclude``, else GOOD.

    Parameters are those of :func:`goring_nikora`; ``u`` is 2-D.
    """
    return _flags(np.asarray(u, dtype=float), floor, max_iterations, exclude, peaks=True)


def _flags(u: np.ndarray, floor, max_iterations: int, exclude, peaks: bool) -> np.ndarray:
    """:func:`flumekit.qc.kernels.despike_flags_rows` on the 2-D ``u``; ``floor`` one or one
    per channel [m s-1]."""
    from flumekit.qc.kernels import despike_flags_rows

    exclude = np.zeros(u.shape, dtype=bool) if exclude is None else np.asarray(exclude, bool)
    floors = np.ascontiguousarray(np.broadcast_to(np.asarray(floor, dtype=float).reshape(-1),
                                                  (u.shape[0],)))
    return despike_flags_rows(u, exclude, floors, int(max_iterations), peaks)
