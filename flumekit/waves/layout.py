"""Wave-probe layout for incident/reflected separation: spacing advice and conditioning check.

The separation of incident and reflected waves solves, per frequency, the least-squares system
B_p = A_I e^(-i k x_p) + A_R e^(+i k x_p) over the probes p (see :mod:`flumekit.waves.separation`).
Its two columns become parallel, and the system singular, when every probe spacing is a multiple
of half a wavelength (k Δx = nπ for all pairs). Near such frequencies noise is amplified by the
condition number computed here.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from flumekit import conventions
from flumekit.docstrings import doc
from flumekit.waves.theory import G, wavelength, wavenumber

#: Default largest condition number accepted: that of a two-probe layout at the Goda & Suzuki
#: (1976) limits Δx/L = 0.05 and 0.45, cot(π/20) ≈ 6.31.
MAX_CONDITION = float(1.0 / np.tan(np.pi / 20))


@doc
def probe_spacing(period, depth, g: float = G) -> tuple[np.ndarray, np.ndarray]:
    """Probe spacings x12 = L/10 and x23 = L/4 of Table 1 in Brito et al. 2020 [m].

    Parameters
    ----------
    period : array_like
        Design wave period [s].
    depth : array_like
        Water depth [m].
    %(g)s

    Returns
    -------
    x12 : numpy.ndarray
        Spacing between probes 1 and 2 [m].
    x23 : numpy.ndarray
        Spacing between probes 2 and 3 [m].

    Notes
    -----
    Table 1 of Brito et al. (2020) lists x12 = 0.49 ... 1.10 m and x23 = 1.23 ... 2.75 m for
    T = 2 ... 4 s in h = 0.825 m, which are L/10 and L/4 of the local linear wavelength. The
    method they cite (Mansard & Funke 1980) recommends x12 = L/10 and L/6 < x13 < L/3 with
    x13 ≠ L/5, 3L/10; the paper's x13 = 0.35 L lies just beyond L/3, which is still
    well-conditioned at the design period (condition number √2, see :func:`condition_number`).

    Examples
    --------
    Table 1 of Brito et al. (2020), T = 2, 3 and 4 s in 0.825 m:

    >>> import numpy as np
    >>> from flumekit.waves import probe_spacing
    >>> x12, x23 = probe_spacing([2.0, 3.0, 4.0], 0.825)
    >>> np.round(x12, 2).tolist(), np.round(x23, 2).tolist()
    ([0.49, 0.8, 1.1], [1.23, 2.0, 2.75])
    """
    L = wavelength(period, depth, g)
    return L / 10.0, L / 4.0


@doc
def condition_number(x, frequency, depth, g: float = G) -> np.ndarray:
    """2-norm condition number of the separation matrix [e^(-ikx_p), e^(+ikx_p)] [-].

    Parameters
    ----------
    x : array_like
        Probe positions [m], shape (P,), P ≥ 2.
    frequency : array_like
        Frequencies [Hz], any shape, > 0.
    %(depth)s
    %(g)s

    Returns
    -------
    numpy.ndarray
        Condition number [-], shape of ``frequency``; ``inf`` where the layout is exactly
        singular.

    Notes
    -----
    With M = [a, conj(a)], a_p = e^(-ikx_p), the Gram matrix MᴴM = [[P, S], [S*, P]] with
    S = Σ_p e^(2ikx_p) has eigenvalues P ± abs(S), so
    cond(M) = sqrt((P + abs(S)) / (P - abs(S))). For three probes
    P² - abs(S)² = 4 Σ_pairs sin²(k Δx), the denominator of Mansard & Funke (1980).

    Examples
    --------
    Two probes a quarter of a wavelength apart are the best two-probe layout (condition
    number 1); at the Goda & Suzuki limit Δx = L/20 the condition number is
    :data:`MAX_CONDITION`, and half a wavelength apart the probes cannot tell the two waves
    apart:

    >>> import numpy as np
    >>> from flumekit.waves import MAX_CONDITION, condition_number, wavelength
    >>> L = float(wavelength(3.0, 0.825))  # T = 3 s in 0.825 m
    >>> cond = [float(condition_number([0.0, dx], 1 / 3.0, 0.825)) for dx in (L / 4, L / 20)]
    >>> np.round(cond, 3).tolist(), round(MAX_CONDITION, 3)
    ([1.0, 6.314], 6.314)
    >>> float(condition_number([0.0, L / 2], 1 / 3.0, 0.825))
    inf

    The paper's three probes (x12 = L/10, x13 = 0.35 L) at the design period: √2.

    >>> round(float(condition_number([0.0, L / 10, 0.35 * L], 1 / 3.0, 0.825)), 4)
    1.4142
    """
    x = np.asarray(x, dtype=float)
    f = np.asarray(frequency, dtype=float)
    k = wavenumber(2 * np.pi * f, depth, g)
    s = np.abs(np.exp(2j * k[..., None] * x).sum(axis=-1))
    p = x.size
    with np.errstate(divide="ignore"):
        return np.sqrt((p + s) / np.maximum(p - s, 0.0))


@doc
def check_layout(x, depth, band: tuple[float, float], max_condition: float = MAX_CONDITION,
                 n_frequencies: int = 200, g: float = G) -> xr.Dataset:
    """Condition number of a probe layout over an analysis band and the ill-conditioned bins.

    Parameters
    ----------
    x : array_like
        Probe positions [m], shape (P,), P ≥ 2, distinct.
    %(depth)s
    band : tuple of float
        (f_min, f_max) analysis band [Hz].
    max_condition : float
        Largest acceptable condition number [-] (default: two-probe Goda–Suzuki limits).
    n_frequencies : int
        Number of frequencies sampled uniformly across the band.
    %(g)s

    Returns
    -------
    xarray.Dataset
        Over ``frequency``: ``condition_number``, ``masked`` (1 where the condition number
        exceeds ``max_condition``), ``wave_number``; over ``pair``: the spacing of each probe
        pair; attrs ``ill_conditioned_fraction`` (fraction of the band that would be masked)
        and a human-readable ``advice``.

    Raises
    ------
    ValueError
        Fewer than two or repeated probe positions, or an empty band.

    Examples
    --------
    Two probes 1 m apart cannot separate the waves whose half wavelength is 1 m (L = 2 m at
    0.88 Hz in 0.825 m): a tenth of the band 0.3-1.2 Hz is masked. A third probe at 0.3 m
    mends it.

    >>> from flumekit.waves import check_layout
    >>> ds = check_layout([0.0, 1.0], 0.825, band=(0.3, 1.2))
    >>> ds.attrs["ill_conditioned_fraction"]
    0.1
    >>> print(ds.attrs["advice"])  # doctest: +NORMALIZE_WHITESPACE
    ill-conditioned between 0.834 and 0.92 Hz (k·Δx/π of the pairs near [1.0]); move a probe
    so that not all spacings are near multiples of L/2
    >>> ds3 = check_layout([0.0, 0.3, 1.0], 0.825, band=(0.3, 1.2))
    >>> ds3.attrs["ill_conditioned_fraction"], ds3.probe_spacing.values.tolist()
    (0.0, [0.3, 1.0, 0.7])
    """
    x = np.asarray(x, dtype=float)
    if x.ndim != 1 or x.size < 2:
        raise ValueError("a probe layout needs at least two probe positions")
    if np.unique(x).size != x.size:
        raise ValueError(f"probe positions must be distinct, got {x.tolist()}")
    f0, f1 = (float(b) for b in band)
    if not 0 < f0 < f1:
        raise ValueError(f"band must satisfy 0 < f_min < f_max, got {band}")
    f = np.linspace(f0, f1, n_frequencies)
    cond = condition_number(x, f, depth, g)
    bad = cond > max_condition
    k = wavenumber(2 * np.pi * f, depth, g)
    i, j = np.triu_indices(x.size, 1)
    dx = np.abs(x[j] - x[i])
    worst = ""
    if bad.any():
        fb = f[bad]
        kdx = k[bad][:, None] * dx / np.pi
        worst = (f"ill-conditioned between {fb.min():.3g} and {fb.max():.3g} Hz "
                 f"(k·Δx/π of the pairs near {np.round(kdx[np.argmax(cond[bad])], 2).tolist()}); "
                 "move a probe so that not all spacings are near multiples of L/2")
    ds = xr.Dataset(
        {"condition_number": ("frequency", cond), "masked": ("frequency", bad.astype(np.int8)),
         "wave_number": ("frequency", k), "probe_spacing": ("pair", dx)},
        coords={"frequency": f, "pair": [f"{a}-{b}" for a, b in zip(i, j, strict=True)]},
        attrs={"ill_conditioned_fraction": float(bad.mean()), "max_condition": max_condition,
               "advice": worst or "well-conditioned over the whole band"})
    return conventions.annotate(ds)
