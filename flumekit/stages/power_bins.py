"""The bins of the power matrix (:mod:`flumekit.stages.performance`) from the target sea states.

Unset, the bin edges give each distinct target of the irregular runs (``hm0``; ``te``, or the
Te of the JONSWAP spectrum of the declared ``tp`` and ``gamma``) its own bin.
"""

from __future__ import annotations


def target_te(target: dict) -> float:
    """Return the energy period of a target sea state.

    Parameters
    ----------
    target : dict
        ``te`` [s] when declared, else ``tp`` [s] and ``gamma`` [-] (default 3.3) of a
        JONSWAP spectrum.

    Returns
    -------
    float
        Te = m_-1 / m0 [s], the declared one or that of the JONSWAP spectrum (integrated
        to 20 fp).

    References
    ----------
    IEC TS 62600-100:2012, Marine energy - Wave, tidal and other water current converters -
    Part 100: Electricity producing wave energy converters - Power performance assessment.

    Examples
    --------
    >>> target_te({"te": 2.5})
    2.5
    >>> round(target_te({"tp": 2.0, "gamma": 3.3}) / 2.0, 2)
    0.9
    """
    import numpy as np

    from flumekit.synth.waves import jonswap

    if target.get("te"):
        return float(target["te"])
    tp = float(target["tp"])
    f = np.linspace(0.0, 20.0 / tp, 20001)[1:]  # to 20 fp: the f^-5 tail beyond is < 1e-5
    s = jonswap(f, 1.0, tp, target.get("gamma") or 3.3)
    return float(np.trapezoid(s / f, f) / np.trapezoid(s, f))


def edges_around(values) -> list[float]:
    """Return bin edges that give each distinct value its own bin.

    Inner edges lie halfway between neighbours, the outer edges as far out as the nearest
    inner one (±10 % around a lone value).

    Parameters
    ----------
    values : array_like
        The values (e.g. target Hm0 [m] or Te [s]); equal to 9 decimals counts as one.

    Returns
    -------
    list of float
        Increasing edges, one more than the distinct values.

    Examples
    --------
    >>> edges_around([1.0, 2.0, 2.0, 4.0])
    [0.5, 1.5, 3.0, 5.0]
    >>> edges_around([2.0])
    [1.8, 2.2]
    """
    import numpy as np

    v = np.unique(np.round(np.asarray(values, dtype=float), 9))
    if v.size == 1:
        return [float(v[0] * 0.9), float(v[0] * 1.1)]
    mid = 0.5 * (v[1:] + v[:-1])
    return [float(2 * v[0] - mid[0]), *map(float, mid), float(2 * v[-1] - mid[-1])]
