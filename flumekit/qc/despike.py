"""Phase-space despiking of velocity records (Goring and Nikora 2002, with Wahl 2003).

Goring, D. G. and Nikora, V. I. (2002), Despiking acoustic Doppler velocimeter data, J. Hydraul.
Eng. 128(1), 117-126; Wahl, T. L. (2003), Discussion, J. Hydraul. Eng. 129(6), 484-487.
"""

from __future__ import annotations

import numpy as np

from flumekit.docstrings import doc
from flumekit.qc.flags import FAIL


@doc
def goring_nikora(u: np.ndarray, floor: float | np.ndarray = 0.0, max_iterations: int = 20,
                  exclude: np.ndarray | None = None) -> np.ndarray:
    """Find the spikes of velocity records by phase-space thresholding, per channel.

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
    u : numpy.ndarray
        Velocity [m s-1], time along the last axis; NaN samples are ignored.
    floor : float or numpy.ndarray
        Lower bound of each standard deviation [m s-1] (the velocity resolution of a quantised
        instrument), so a channel in still water is not all spikes; one or one per channel.
    %(max_iterations)s
    exclude : numpy.ndarray, optional
        Samples ignored as NaN ones are (True), of u's shape; None: none.

    Returns
    -------
    numpy.ndarray
        Boolean array of u's shape, True at spikes.

    %(references_goring_nikora2002)s.

    Wahl, T. L. (2003). Discussion of "Despiking acoustic Doppler velocimeter data".
    J. Hydraul. Eng. 129(6), 484-487.

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.qc import goring_nikora
    >>> u = 0.01 * np.random.default_rng(0).standard_normal(1000)
    >>> u[200] = 0.5
    >>> np.flatnonzero(goring_nikora(u, max_iterations=1)).tolist()  # and its neighbours
    [198, 199, 200, 201, 202]
    """
    u = np.asarray(u, dtype=float)
    shape = u.shape
    u = u.reshape(-1, shape[-1])
    ex = None if exclude is None else np.asarray(exclude, dtype=bool).reshape(u.shape)
    # every statistic is per channel (λ aside, from the longest record): channel by channel
    return (_flags(u, floor, max_iterations, ex, peaks=False) == FAIL).reshape(shape)


@doc
def despike_flags(u: np.ndarray, floor: float | np.ndarray = 0.0, max_iterations: int = 1,
                  exclude: np.ndarray | None = None) -> np.ndarray:
    """Return the QARTOD flags of the despiking of velocity records, as bytes.

    :func:`goring_nikora` on (channel, time) records in any memory layout: FAIL at the spikes
    whose departure from their neighbours' mean, ``|u_n - (u_(n-1) + u_(n+1))/2|``, is at least that
    of both neighbours (a spike moves the derivatives of its two neighbours too, which the method
    then flags with it: GN 2002, §4), MISSING where not finite, NOT_EVALUATED where finite and
    ``exclude``, else GOOD.

    Parameters
    ----------
    u : numpy.ndarray
        Velocity [m s-1], (channel, time).
    floor : float or numpy.ndarray
        Lower bound of each standard deviation [m s-1]; one or one per channel.
    %(max_iterations)s
    exclude : numpy.ndarray, optional
        Samples not evaluated (True), of u's shape; None: none.

    Returns
    -------
    numpy.ndarray
        QARTOD flags (uint8) of u's shape (:mod:`flumekit.qc.flags`).

    %(references_goring_nikora2002)s.

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.qc.despike import despike_flags
    >>> u = 0.01 * np.random.default_rng(0).standard_normal((1, 1000))
    >>> u[0, 200] = 0.5
    >>> np.flatnonzero(despike_flags(u) == 4).tolist()  # FAIL at the spike only
    [200]
    """
    return _flags(np.asarray(u, dtype=float), floor, max_iterations, exclude, peaks=True)


def _flags(u: np.ndarray, floor, max_iterations: int, exclude, peaks: bool) -> np.ndarray:
    """Run :func:`flumekit.qc.kernels.despike_flags_rows` on the 2-D ``u``.

    ``floor`` is one or one per channel [m s-1].
    """
    from flumekit.qc.kernels import despike_flags_rows

    exclude = np.zeros(u.shape, dtype=bool) if exclude is None else np.asarray(exclude, bool)
    floors = np.ascontiguousarray(np.broadcast_to(np.asarray(floor, dtype=float).reshape(-1),
                                                  (u.shape[0],)))
    return despike_flags_rows(u, exclude, floors, int(max_iterations), peaks)
