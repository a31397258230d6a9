"""Settling of the separated reflection: where a regular run's reflected wave has stopped changing.

The paper's quasi-steady criterion (Brito et al. 2020, §2.5: each cycle's crest within 2 % of
the amplitude scale, :func:`flumekit.signal.quasi_steady_window`) watches the sum of the
incident and reflected waves at each probe. A reflected component that still grows after the
crests have settled passes it unseen: in a flume with a beach behind the device the beach's
wave returns through the device one flume length later and ramps up over the wavemaker's ramp,
adding ~6 % of the incident amplitude to the reflected wave at the probes, which moves no crest
by 2 % (it adds to or takes from the crest by the cosine of a phase that differs from probe to
probe) yet lowers the reflection coefficient of a window opened early by 0.002-0.003, larger than
its uncertainty.

The test here watches the separated first harmonic itself: the complex reflection coefficient
R = A_R / A_I of consecutive blocks of whole periods (each block's Fourier coefficient at the
measured frequency at every probe, separated by least squares as in
:func:`flumekit.waves.separate`, all blocks in one solve), compared with its value over the
second half of the window. The settled window is the longest run of consecutive blocks within
the tolerance (as the crest test keeps the longest run of steady cycles).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from flumekit.docstrings import doc
from flumekit.signal import median_rows, nanmedian
from flumekit.waves.separation import lstsq_normal
from flumekit.waves.theory import G, wavenumber

__all__ = ["BLOCK_PERIODS", "ReflectionSettling", "reflection_settling"]

#: periods per block: short enough to place the start within a few periods, long enough that
#: probe noise moves a block's R by a small fraction of the tolerance
BLOCK_PERIODS = 3
#: fewest blocks a window must hold for the test (fewer: the window is left as it is)
MIN_BLOCKS = 6


@dataclass(frozen=True)
class ReflectionSettling:
    """Where the separated first-harmonic reflection has settled within a window.

    Attributes
    ----------
    start : Start of the longest run of blocks whose R lies within ``tolerance`` of
        R_settled [s]; the window's own start when the test does not apply or no block
        settles (then ``end`` = ``start``).
    tolerance : Tolerance applied to |R - R_settled| [-] (NaN when the test does not apply).
    drift : Largest |R - R_settled| of the blocks outside that run [-] (0 when none).
    reflection : The settled complex reflection coefficient R_settled [-].
    end : End of that run [s]; the window's own end when the test does not apply.
    trend : Change of R across that run, from a least-squares line through its blocks [-]
        (NaN when the test does not apply or no block settles).
    """

    start: float
    tolerance: float
    drift: float
    reflection: complex
    end: float
    trend: float


@doc
def reflection_settling(eta: np.ndarray, time: np.ndarray, x: np.ndarray, period: float,
                        depth: float, start: float, end: float, *, tolerance: float = 0.002,
                        noise_factor: float = 4.0, g: float = G) -> ReflectionSettling:
    """Find where the separated first-harmonic reflection of a regular run has settled.

    Parameters
    ----------
    eta : numpy.ndarray
        Surface elevation of the separation probes [m], shape (probe, time).
    time : numpy.ndarray
        Uniform sample times [s].
    x : numpy.ndarray
        Probe positions along the flume [m] (towards the reflector).
    period : float
        Measured wave period [s].
    %(depth)s
    start, end : float
        The window the crests call quasi-steady [s].
    tolerance : float
        Smallest tolerance on |R - R_settled| [-]: a change of R by 0.002 moves the
        reflection coefficient of a window by less than that, well below the uncertainty of
        a flume's Kr. 0 skips the test.
    noise_factor : float
        The tolerance is at least ``noise_factor`` times the blocks' own scatter about
        R_settled (the Rayleigh scale σ of |R - R_settled| over the window's second half,
        median / sqrt(2 ln 2)), so that probe noise cuts no steady block (a block beyond 4 σ:
        probability exp(-8)) [-].
    %(g)s

    Returns
    -------
    ReflectionSettling
        The settled window (start, end), the tolerance applied, the drift outside it and
        R_settled.

    %(references_brito2020)s, §2.5.
    Mansard, E. P. D. & Funke, E. R. (1980). The measurement of incident and reflected
    spectra using a least squares method. Proc. 17th ICCE, 154-172.

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.waves.theory import wavenumber
    >>> t = np.arange(0.0, 120.0, 0.04)
    >>> x = np.array([-3.0, -2.6, -2.0])
    >>> k = float(wavenumber(2 * np.pi / 2.0, 0.8))
    >>> r = np.where(t < 40.0, 0.10, 0.15)  # the reflection grows at t = 40 s
    >>> eta = (0.05 * np.cos(np.pi * t - k * x[:, None])
    ...        + 0.05 * r * np.cos(np.pi * t + k * x[:, None]))
    >>> s = reflection_settling(eta, t, x, 2.0, 0.8, 0.0, 120.0)
    >>> s.start, round(abs(s.reflection), 3), round(s.drift, 3)
    (42.0, 0.15, 0.05)
    """
    nothing = ReflectionSettling(float(start), float("nan"), 0.0, complex("nan"), float(end),
                                 float("nan"))
    if not tolerance > 0:
        return nothing
    t = np.asarray(time, dtype=float)
    dt = (t[-1] - t[0]) / (t.size - 1)
    per_block = int(round(BLOCK_PERIODS * period / dt))
    i0 = int(np.ceil((start - t[0]) / dt - 1e-9))
    n_blocks = int((min(end, t[-1] + dt) - t[0] - i0 * dt) // (per_block * dt))
    if n_blocks < MIN_BLOCKS:
        return nothing
    stop = i0 + n_blocks * per_block
    v = np.asarray(eta, dtype=float)[:, i0:stop].reshape(-1, n_blocks, per_block)
    tb = t[i0:stop].reshape(n_blocks, per_block)
    # each block's Fourier coefficient at the measured frequency (its mean removed: a block is
    # a whole number of samples, not exactly of periods, and the mean would leak)
    omega = 2.0 * np.pi / period
    v = v - v.mean(axis=-1, keepdims=True)
    coef = (2.0 / per_block) * np.einsum("pbn,bn->pb", v, np.exp(-1j * omega * tb))
    k = float(wavenumber(omega, depth, g))
    xs = np.asarray(x, dtype=float)
    columns = np.stack([np.exp(-1j * k * xs), np.exp(1j * k * xs)], axis=-1)[None]
    sol, _, masked = lstsq_normal(columns, coef[None], max_condition=np.inf)
    if masked[0]:
        return nothing
    a_inc, a_ref = sol[0]
    with np.errstate(divide="ignore", invalid="ignore"):
        r = a_ref / a_inc
    half = r[n_blocks // 2:]
    settled = complex(nanmedian(half.real), nanmedian(half.imag))
    dev = np.abs(r - settled)
    sigma = nanmedian(dev[n_blocks // 2:]) / np.sqrt(2.0 * np.log(2.0))
    tol = max(float(tolerance), noise_factor * sigma)
    # the median of each block's deviation and its neighbours': one disturbed block (a spike
    # the crest test let through) does not cut the window
    padded = np.concatenate([dev[:1], dev, dev[-1:]])
    smooth = median_rows(np.stack([padded[:-2], padded[1:-1], padded[2:]]))
    ok = np.concatenate([[False], smooth <= tol, [False]])  # NaN (a masked block): not settled
    edges = np.flatnonzero(np.diff(ok.astype(int)))
    runs = edges.reshape(-1, 2)
    if runs.size == 0:
        return ReflectionSettling(float(start), tol, float(np.nanmax(dev)), settled,
                                  float(start), float("nan"))
    a, b = runs[int(np.argmax(runs[:, 1] - runs[:, 0]))]
    outside = np.concatenate([dev[:a], dev[b:]])
    drift = float(np.nanmax(outside)) if outside.size else 0.0
    # the change of R across the run by a least-squares line through its blocks: a reflection
    # that drifts all along widens the tolerance (its scatter) instead of leaving it
    s_b = np.arange(b - a) - 0.5 * (b - a - 1)
    trend = float(np.abs(np.sum(s_b * r[a:b])) / np.sum(s_b ** 2) * (b - a)) if b - a > 1 else 0.0
    return ReflectionSettling(float(tb[a, 0]), tol, drift, settled,
                              float(tb[b - 1, 0] + per_block * dt), trend)
