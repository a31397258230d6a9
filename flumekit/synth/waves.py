"""The virtual flume's wave generator: incident and reflected wave fields with a known truth.

Coordinates follow the campaign: x = 0 at the flap hinge, positive towards the beach; the
wavemaker sits at ``x_wavemaker`` < 0 and the incident wave travels towards +x. The reflected
wave is the incident wave mirrored at ``x_reflector`` (the flap), scaled by the reflection
coefficient and shifted by the reflection phase. The truth (amplitudes, Kr, wavenumber, ...) is
returned in the dataset's ``attrs``.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from flumekit import conventions
from flumekit.waves.theory import G, group_velocity, stokes2_coefficient, wavenumber


def _check_positive(**kw: float) -> None:
    for name, value in kw.items():
        if not (np.isfinite(value) and value > 0):
            raise ValueError(f"{name} must be positive and finite, got {value}")


def _check_grid(time, x, x_low: float, x_high: float) -> tuple[np.ndarray, np.ndarray]:
    time = np.asarray(time, dtype=float)
    x = np.atleast_1d(np.asarray(x, dtype=float))
    if time.ndim != 1 or x.ndim != 1 or time.size < 2 or not np.all(np.isfinite(time)):
        raise ValueError("time must be a finite 1-D array of at least two samples and x 1-D")
    if np.any(x < x_low) or np.any(x > x_high):
        raise ValueError(f"positions x = {x.tolist()} m must lie between the wavemaker "
                         f"({x_low} m) and the reflector ({x_high} m)")
    return time, x


def ramp_envelope(tau, ramp_time: float) -> np.ndarray:
    """Smooth ramp-up envelope e(τ) = 1 - (1 + s) e^(-s), s = τ / ramp_time, 0 for τ ≤ 0 [-].

    The critically damped (two-pole) response of a wavemaker's amplitude to a step: continuous
    with a continuous slope at τ = 0, 59 % at s = 2 and within 2 % of 1 from s = 5.83 on.
    """
    s = np.maximum(np.asarray(tau, dtype=float), 0.0) / ramp_time
    return -np.expm1(-s) - s * np.exp(-s)


def first_harmonic_amplitude(height: float, k: float, depth: float, second_order: bool) -> float:
    """First-harmonic amplitude a1 [m] of a wave with crest-to-trough height ``height`` [m].

    Linear: a1 = H/2. Second-order Stokes, η = a1 cos θ + r a1 cos 2θ with r = B k a1
    (:func:`flumekit.waves.theory.stokes2_coefficient`): H = 2 a1 while 4r ≤ 1; beyond, the
    trough splits (secondary crest) and H = a1 (1 + 2r + 1/(8r)), which gives
    a1 = (sqrt(8 B k H) - 1) / (4 B k).
    """
    if not second_order:
        return height / 2.0
    bk = float(stokes2_coefficient(k, depth)) * k
    if 4 * bk * height / 2.0 <= 1.0:
        return height / 2.0
    return (np.sqrt(8 * bk * height) - 1.0) / (4 * bk)


def regular_wave_field(time, x, *, period: float, height: float, depth: float,
                       reflection: float = 0.2, reflection_phase: float = 0.0,
                       x_reflector: float = 0.0, ramp_waves: float = 10.0,
                       second_order: bool = True, x_wavemaker: float = -32.7,
                       g: float = G) -> xr.Dataset:
    """Regular incident and reflected waves with a ramp-up, at probe positions ``x``.

    Parameters
    ----------
    time : Time since the start of wave generation [s], 1-D.
    x : Positions along the flume [m], 1-D, between ``x_wavemaker`` and ``x_reflector``.
    period : Wave period T [s].
    height : Target crest-to-trough height H of the steady incident wave [m].
    depth : Still water depth h [m].
    reflection : Reflection coefficient Kr of the first harmonic [-], 0 ≤ Kr ≤ 1.
    reflection_phase : Phase added to the reflected wave at the reflector [rad].
    x_reflector : Position of the reflector (flap) [m].
    ramp_waves : Ramp length in wave periods: the envelope at the wavemaker is
        :func:`ramp_envelope` with ramp time ``ramp_waves``·T/2, so it reaches 59 % after
        ``ramp_waves`` periods and stays within 2 % of its final value after 2.9·``ramp_waves``
        periods. The default (10) with the travel time from the wavemaker makes records
        quasi-steady (Brito et al. 2020, §2.5 criterion) after about 35 waves at the flap for
        T = 3.5 s, as in the paper.
    second_order : Add the second-order Stokes bound harmonic of the incident wave and of the
        reflected wave.
    x_wavemaker : Position of the wavemaker [m] (the envelope starts there at t = 0).
    g : Gravitational acceleration [m s-2].

    Returns
    -------
    Dataset over ("x", "time") with ``eta_incident``, ``eta_reflected`` and ``eta`` (their sum)
    [m]. ``attrs`` hold the truth: ``incident_amplitude`` (first harmonic a1),
    ``bound_amplitude`` (a2 = B k a1², 0 if linear), ``reflection_coefficient``,
    ``reflection_phase``, ``wave_height`` (H), ``wave_period``, ``wave_number``, ``wavelength``,
    ``group_velocity``, ``ursell_number`` and the geometry.

    Notes
    -----
    Incident, with θ_I = ωt - k(x - x_wm) and envelope e_I = e(t - (x - x_wm)/c_g):
    η_I = a1 e_I cos θ_I + B k a1² e_I² cos 2θ_I (Stokes 2nd order, Dean & Dalrymple 1991).
    Reflected, the mirror image x → 2 x_r - x: θ_R = ωt - k(2x_r - x - x_wm) + φ,
    η_R = Kr a1 e_R cos θ_R + B k (Kr a1)² e_R² cos 2θ_R, i.e. its own bound harmonic
    (amplitude Kr² a2, phase 2φ). The envelope is advected with the group velocity without
    dispersion; the second-order set-down and the incident-reflected interaction term (at 2ω
    with wavenumber 0, of order Kr k a1²) are omitted, as are re-reflections at the wavemaker
    (active absorption). Second-order Stokes theory is valid for Ursell numbers
    H L² / h³ ≲ 26; the longer waves of the campaign exceed that.
    """
    _check_positive(period=period, height=height, depth=depth, ramp_waves=ramp_waves)
    if not 0 <= reflection <= 1:
        raise ValueError(f"reflection coefficient must lie in [0, 1], got {reflection}")
    if not x_wavemaker < x_reflector:
        raise ValueError("the wavemaker must lie upstream (x smaller) of the reflector")
    time, x = _check_grid(time, x, x_wavemaker, x_reflector)
    omega = 2 * np.pi / period
    k = float(wavenumber(omega, depth, g))
    cg = float(group_velocity(period, depth, g))
    a1 = first_harmonic_amplitude(height, k, depth, second_order)
    a2 = float(stokes2_coefficient(k, depth)) * k * a1**2 if second_order else 0.0

    t = time[None, :]
    d_inc = (x - x_wavemaker)[:, None]  # travelled distance of the incident wave
    d_ref = (2 * x_reflector - x - x_wavemaker)[:, None]  # ... of the reflected wave
    ramp_time = ramp_waves * period / 2.0
    e_i = ramp_envelope(t - d_inc / cg, ramp_time)
    e_r = ramp_envelope(t - d_ref / cg, ramp_time)
    th_i = omega * t - k * d_inc
    th_r = omega * t - k * d_ref + reflection_phase
    eta_i = a1 * e_i * np.cos(th_i) + a2 * e_i**2 * np.cos(2 * th_i)
    eta_r = (reflection * a1 * e_r * np.cos(th_r)
             + reflection**2 * a2 * e_r**2 * np.cos(2 * th_r))
    L = 2 * np.pi / k
    ds = xr.Dataset(
        {"eta_incident": (("x", "time"), eta_i), "eta_reflected": (("x", "time"), eta_r),
         "eta": (("x", "time"), eta_i + eta_r)},
        coords={"x": x, "time": time},
        attrs={"wave_period": period, "wave_height": height, "depth": depth,
               "incident_amplitude": a1, "bound_amplitude": a2,
               "reflection_coefficient": reflection, "reflection_phase": reflection_phase,
               "wave_number": k, "wavelength": L, "group_velocity": cg,
               "ursell_number": height * L**2 / depth**3, "x_reflector": x_reflector,
               "x_wavemaker": x_wavemaker, "ramp_waves": ramp_waves,
               "second_order": int(second_order),
               "phase_reference": "incident phase zero at the wavemaker: "
                                  "theta = w t - k (x - x_wavemaker)"})
    return conventions.annotate(ds)


def jonswap(frequency, hm0: float, peak_period: float, gamma: float = 3.3) -> np.ndarray:
    """JONSWAP variance density S(f) [m2 s] scaled so that ∫S df = Hm0²/16 on the given grid.

    S ∝ f⁻⁵ exp(-5/4 (fp/f)⁴) γ^exp(-(f - fp)² / (2 σ² fp²)), σ = 0.07 (f ≤ fp), 0.09 (f > fp)
    (Hasselmann et al. 1973). The scale is fixed numerically on the (uniform) ``frequency`` grid,
    so that the discrete components hold exactly Hm0²/16 of variance.
    """
    f = np.asarray(frequency, dtype=float)
    fp = 1.0 / peak_period
    sigma = np.where(f <= fp, 0.07, 0.09)
    fs = np.where(f > 0, f, fp)  # S(0) = 0: evaluate the formula at f > 0 only
    shape = (fs ** -5.0 * np.exp(-1.25 * (fp / fs) ** 4)
             * gamma ** np.exp(-((fs - fp) ** 2) / (2 * sigma**2 * fp**2)))
    shape = np.where(f > 0, shape, 0.0)
    df = f[1] - f[0]
    return shape * (hm0**2 / 16.0) / (shape.sum() * df)


def irregular_wave_field(time, x, *, hm0: float, peak_period: float, depth: float,
                         gamma: float = 3.3, reflection: float = 0.2,
                         reflection_phase: float = 0.0, x_reflector: float = 0.0,
                         rng: np.random.Generator | int | None = None,
                         f_max: float | None = None, g: float = G) -> xr.Dataset:
    """Linear irregular (JONSWAP) incident and reflected waves with random phases.

    Parameters
    ----------
    time : Uniformly sampled time [s], 1-D (N samples, step Δt).
    x : Positions [m], 1-D, x ≤ ``x_reflector``.
    hm0 : Spectral significant height of the incident wave, 4 sqrt(m0) [m].
    peak_period : Peak period Tp [s].
    depth : Water depth [m].
    gamma : JONSWAP peak enhancement factor [-].
    reflection : Frequency-independent reflection coefficient [-].
    reflection_phase : Phase added at the reflector [rad].
    x_reflector : Reflector position [m]; incident phases are referenced to it.
    rng : numpy Generator or seed (deterministic for a given seed).
    f_max : Highest component frequency [Hz]; default min(5/Tp, Nyquist).
    g : Gravitational acceleration [m s-2].

    Returns
    -------
    Dataset over ("x", "time") with ``eta_incident``, ``eta_reflected``, ``eta`` [m]; the truth in
    ``attrs`` (``hm0`` of the incident wave exactly, ``reflection_coefficient``, ...).

    Notes
    -----
    The components sit on the record's Fourier bins f_n = n / (N Δt), so every record is exactly
    periodic (no leakage), with deterministic amplitudes a_n = sqrt(2 S(f_n) Δf) and uniform
    random phases: η_I = Σ a_n cos(ω_n t - k_n (x - x_r) + ψ_n),
    η_R = Kr Σ a_n cos(ω_n t + k_n (x - x_r) + ψ_n + φ).
    """
    _check_positive(hm0=hm0, peak_period=peak_period, depth=depth, gamma=gamma)
    if not 0 <= reflection <= 1:
        raise ValueError(f"reflection coefficient must lie in [0, 1], got {reflection}")
    time, x = _check_grid(time, x, -np.inf, x_reflector)
    n = time.size
    dt = (time[-1] - time[0]) / (n - 1)
    if not np.allclose(np.diff(time), dt, rtol=1e-6, atol=1e-9 * dt):
        raise ValueError("irregular_wave_field needs uniformly sampled time")
    rng = rng if isinstance(rng, np.random.Generator) else np.random.default_rng(rng)
    freq = np.fft.rfftfreq(n, dt)
    f_max = min(5.0 / peak_period, 0.5 / dt) if f_max is None else float(f_max)
    sel = np.flatnonzero((freq > 0) & (freq < min(f_max, 0.5 / dt) + 1e-12 * freq[1]))
    if sel.size < 8:
        raise ValueError("the record is too short for an irregular wave: fewer than 8 "
                         "frequency components below f_max")
    df = freq[1]
    f = freq[sel]
    amp = np.sqrt(2 * jonswap(np.r_[0.0, f], hm0, peak_period, gamma)[1:] * df)
    psi = rng.uniform(0.0, 2 * np.pi, f.size)
    k = wavenumber(2 * np.pi * f, depth, g)
    base = amp * np.exp(1j * (psi + 2 * np.pi * f * time[0])) * (n / 2.0)
    spec = np.zeros((2, x.size, freq.size), complex)
    dx = (x - x_reflector)[:, None]
    spec[0][:, sel] = base * np.exp(-1j * k * dx)
    spec[1][:, sel] = reflection * base * np.exp(1j * (k * dx + reflection_phase))
    eta_i, eta_r = np.fft.irfft(spec, n, axis=-1)
    ds = xr.Dataset(
        {"eta_incident": (("x", "time"), eta_i), "eta_reflected": (("x", "time"), eta_r),
         "eta": (("x", "time"), eta_i + eta_r)},
        coords={"x": x, "time": time},
        attrs={"hm0": hm0, "peak_period": peak_period, "gamma": gamma, "depth": depth,
               "reflection_coefficient": reflection, "reflection_phase": reflection_phase,
               "x_reflector": x_reflector, "n_components": int(f.size),
               "f_max": float(f[-1])})
    return conventions.annotate(ds)
