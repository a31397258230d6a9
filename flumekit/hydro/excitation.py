"""Wave excitation torque from the measured incident elevation at the flap.

The separation stage gives the incident elevation η_I(t) at the hinge line x = 0; with the
excitation torque per unit amplitude F(ω) of :mod:`flumekit.hydro.coefficients` (time factor
e^{-iωt}, referenced to the incident wave at x = 0) the excitation torque is the linear filter

    T_exc(t) = Re Σ F(ω) â(ω) e^{-iωt}        (Cummins 1962; Falnes 2002, §5.9)

Method (FFT filter of a non-periodic record):

1. the mean elevation (the still-water offset) is removed and recorded; F continues to ω = 0
   (step 5: a jump of F at zero frequency would spread a slowly decaying tail over the whole
   record);
2. both ends are tapered with half-cosine ramps of ``taper`` seconds, so that the abrupt end of a
   record does not ring through the filter (the first and last ``taper`` seconds of the torque
   are therefore attenuated; a flume record starts in still water, so only its end matters);
3. the record is zero-padded by ``padding`` seconds (default: the longest period of the band
   plus 20 s), more than the spread of the filter's (non-causal) impulse response, so that the
   circular convolution of the FFT does not wrap the end of the record onto its start;
4. numpy's FFT uses e^{+iωt}, so a component â e^{+iωt} of η gives conj(F(ω)) â e^{+iωt} of the
   torque (η = Re{a e^{-iωt}} ⇔ the e^{+iωt} coefficient is conj(a)/2);
5. F is interpolated linearly (real and imaginary parts) inside the coefficients' band, held at
   F(ω₁) below the first frequency (its imaginary part ramped to zero at ω = 0) and set to zero
   above the last; the fractions of the
   elevation variance below and above the band are reported.

End effects, bounded. The torque at t needs the elevation over the filter's impulse response
k(τ) = (1/2π) ∫ F̄(ω) e^{iωτ} dω around t (causal part τ > 0: the past; the rest: the future).
From k on the FFT grid, L_past and L_future are the shortest lags beyond which the tails hold
less than ``tail_tolerance`` (1e-4) of ∫|k|; the result's ``valid_start`` = t₀ + taper + L_past
and ``valid_end`` = t_end − taper − L_future bound the window where the missing elevation
outside the record (and the tapers) changes the torque by less than that fraction of
∫|k| max|η| (measured below 1e-4 of the torque amplitude in
``tests/hydro/test_simulation.py``). A flume record starts in still water, so only the end
matters there: extend the record, or keep to ``valid_end``.

References
----------
Cummins, W. E. (1962). The impulse response function and ship motions. Schiffstechnik 9,
101-109.
Falnes, J. (2002). Ocean waves and oscillating systems. Cambridge University Press, §5.9.
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from scipy import fft as sfft

from flumekit import conventions
from flumekit.signal import uniform_step

DIM = "angular_frequency"


def transfer_function(hydro: xr.Dataset, omega) -> np.ndarray:
    """Return the excitation filter F(ω) continued to every ω ≥ 0.

    Linear inside the band, 0 above; below the first frequency ω₁ the real part is held and
    the imaginary part falls linearly to zero at ω = 0 (F of a real filter is real at zero
    frequency: a jump there would leave a 1/t tail).

    Parameters
    ----------
    hydro : xarray.Dataset
        Coefficient container with complex ``excitation_torque`` [N m m-1] over
        ``angular_frequency`` [rad s-1].
    omega : array_like
        Angular frequencies [rad s-1], ≥ 0.

    Returns
    -------
    numpy.ndarray of complex
        F(ω) [N m m-1], shape of ``omega``.

    Examples
    --------
    >>> from flumekit.hydro.coefficients import hydro_dataset
    >>> from flumekit.hydro.excitation import transfer_function
    >>> hydro = hydro_dataset([1.0, 2.0], [5.0, 5.0], [1.0, 1.0], [10 + 2j, 20 + 4j], 10.0)
    >>> transfer_function(hydro, [0.0, 0.5, 1.5, 3.0])
    array([10.+0.j, 10.+1.j, 15.+3.j,  0.+0.j])
    """
    w = hydro[DIM].values
    f = hydro["excitation_torque"].values
    om = np.asarray(omega, dtype=float)
    out = np.interp(om, w, f.real) + 1j * np.interp(om, w, f.imag)
    low = om < w[0]
    out[low] = f[0].real + 1j * f[0].imag * om[low] / w[0]
    out[om > w[-1]] = 0.0
    return out


def _effective_length(hydro: xr.Dataset, dt: float, tol: float) -> tuple[int, int]:
    """Return the lags (in steps) beyond which the filter's tails hold less than ``tol``.

    The past and future tails of the impulse response k, as fractions of ∫|k| (module notes).
    """
    w = hydro[DIM].values
    nfft = sfft.next_fast_len(max(4096, 8 * int(np.ceil(2 * np.pi / w[0] / dt))), real=True)
    f = transfer_function(hydro, 2 * np.pi * sfft.rfftfreq(nfft, dt))
    k = np.abs(sfft.irfft(np.conj(f), nfft))  # torque response to a unit elevation sample
    total = k.sum()
    half = nfft // 2
    causal, anti = k[:half], k[half:][::-1]  # lags 0, 1, ... and -1, -2, ...

    def length(part):
        tail = np.cumsum(part[::-1])[::-1]  # mass at lags >= j
        beyond = np.flatnonzero(tail > tol * total)
        return int(beyond[-1]) + 1 if beyond.size else 0

    return length(causal), length(anti) + 1


def excitation_torque(eta_incident: xr.DataArray, hydro: xr.Dataset, *, taper: float = 2.0,
                      padding: float | None = None,
                      tail_tolerance: float = 1e-4) -> xr.DataArray:
    """Compute the excitation torque time series from the incident elevation at x = 0.

    The linear filter T_exc(t) = Re Σ F(ω) â(ω) e^{-iωt}, evaluated by FFT with the end
    treatment of the module notes.

    Parameters
    ----------
    eta_incident : xarray.DataArray
        Incident elevation at the hinge line [m] over ``time`` [s], uniformly sampled, finite.
    hydro : xarray.Dataset
        Coefficient container with ``excitation_torque`` [N m m-1] (complex, per unit
        amplitude).
    taper : float, optional
        Half-cosine ramp at each end of the record [s] (0 for a periodic record).
    padding : float, optional
        Zero padding [s]; default the longest period of the band plus 20 s, extended to the
        filter's effective length (module notes).
    tail_tolerance : float, optional
        Fraction [-] of ∫|k| left outside the effective length (module notes).

    Returns
    -------
    xarray.DataArray
        ``torque_excitation`` [N m] over the same ``time``; attrs: the method, ``eta_mean``
        [m], ``variance_below_band`` and ``variance_above_band`` (fractions [-] of the
        elevation variance outside the coefficients' frequency band), ``valid_start`` and
        ``valid_end`` [s] (module notes).

    Raises
    ------
    ValueError
        The elevation is not 1-D over ``time``, not uniformly sampled, not finite, or shorter
        than twice the taper.

    References
    ----------
    Cummins, W. E. (1962). The impulse response function and ship motions. Schiffstechnik 9,
    101-109.
    Falnes, J. (2002). Ocean waves and oscillating systems. Cambridge University Press, §5.9.

    Examples
    --------
    A wave at a frequency inside the band gives abs(F) a:

    >>> import numpy as np, xarray as xr
    >>> from flumekit.hydro.coefficients import hydro_dataset
    >>> from flumekit.hydro.excitation import excitation_torque
    >>> hydro = hydro_dataset([0.5, 5.0], [5.0, 5.0], [1.0, 1.0], [100.0, 100.0], 10.0)
    >>> t = np.arange(0.0, 200.0, 0.05)
    >>> eta = xr.DataArray(0.1 * np.cos(2 * np.pi * t / 2.0), dims="time", coords={"time": t})
    >>> tq = excitation_torque(eta, hydro)
    >>> round(float(abs(tq.sel(time=slice(50, 150))).max()), 1)
    10.0
    """
    if "time" not in eta_incident.dims or eta_incident.ndim != 1:
        raise ValueError("eta_incident must be a 1-D DataArray over 'time'")
    t = eta_incident["time"].values.astype(float)
    dt = uniform_step(t, "the incident elevation", min_samples=4)
    eta = eta_incident.values.astype(float)
    if not np.all(np.isfinite(eta)):
        raise ValueError("eta_incident has non-finite samples")
    n = eta.size
    mean = float(eta.mean())
    x = eta - mean
    m = round(taper / dt)
    if m > 0:
        if 2 * m > n:
            raise ValueError(f"taper {taper} s is longer than half the record")
        ramp = 0.5 * (1 - np.cos(np.pi * (np.arange(m) + 0.5) / m))
        x[:m] *= ramp
        x[-m:] *= ramp[::-1]
    w_band = hydro[DIM].values
    if padding is None:
        padding = 2 * np.pi / w_band[0] + 20.0
    past, future = _effective_length(hydro, dt, tail_tolerance)
    padding = max(padding, (past + future) * dt)
    nfft = sfft.next_fast_len(n + int(np.ceil(padding / dt)), real=True)
    spec = sfft.rfft(x, nfft)
    omega = 2 * np.pi * sfft.rfftfreq(nfft, dt)
    f = transfer_function(hydro, omega)  # continued to ω = 0 (module notes)
    torque = sfft.irfft(np.conj(f) * spec, nfft)[:n]
    power = np.abs(spec) ** 2
    total = power[1:].sum()
    below = float(power[1:][omega[1:] < w_band[0]].sum() / total) if total > 0 else 0.0
    above = float(power[1:][omega[1:] > w_band[-1]].sum() / total) if total > 0 else 0.0
    da = xr.DataArray(torque, dims="time", coords={"time": t}, name="torque_excitation",
                      attrs={"method": "FFT filter: mean removed, half-cosine end tapers, zero "
                                       "padding, F(omega) linear in band, held below, 0 above",
                             "taper": float(taper), "padding": float(padding),
                             "valid_start": float(t[0] + taper + past * dt),
                             "valid_end": float(t[-1] - taper - future * dt),
                             "tail_tolerance": float(tail_tolerance),
                             "eta_mean": mean, "variance_below_band": below,
                             "variance_above_band": above})
    return conventions.annotate(da)
