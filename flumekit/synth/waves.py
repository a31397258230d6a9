"""The virtual flume's wave generator: incident and reflected wave fields with a known truth.

Coordinates follow the campaign: x = 0 at the flap hinge, positive towards the beach; the
wavemaker sits at ``x_wavemaker`` < 0 and the incident wave travels towards +x. The reflected
wave is the incident wave mirrored at ``x_reflector`` (the flap), scaled by the reflection
coefficient and shifted by the reflection phase. The truth (amplitudes, Kr, wavenumber, ...) is
returned in the dataset's ``attrs``.
"""

from __future__ import annotations

import functools

import numpy as np
import xarray as xr

from flumekit import conventions
from flumekit.waves.stream_function import StreamFunctionWave, stream_function_wave
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


THEORIES = ("stream", "stokes2", "linear")
#: harmonics of a stream-function wave kept in the virtual flume: those above this fraction of
#: the first harmonic's amplitude (the rest, < 0.015 mm in the flume's range, lie far below the
#: probes' 0.5 mm noise; about 10 of the 20 computed at T = 3.5 s, H = 0.25 m)
HARMONIC_CUTOFF = 1e-4


@functools.lru_cache(maxsize=64)
def nonlinear_wave(period: float, height: float, depth: float, g: float = G
                   ) -> StreamFunctionWave:
    """The flume's steady nonlinear wave: :func:`flumekit.waves.stream_function_wave` with
    Stokes' second definition of celerity (zero mean mass transport: a closed flume) and its
    default 20 modes, cached (a run's records and its UVP evaluate the same wave)."""
    return stream_function_wave(period, height, depth, current="stokes", g=g)


def wave_harmonics(period: float, height: float, depth: float, reflection: float = 0.0,
                   theory: str = "stream", g: float = G) -> dict[str, object]:
    """Harmonic amplitudes and wavenumbers of the incident and reflected regular waves.

    Parameters
    ----------
    period : Wave period T [s].
    height : Crest-to-trough height H of the incident wave [m].
    depth : Still water depth h [m].
    reflection : Reflection coefficient Kr of the first harmonic [-].
    theory : ``"stream"`` (stream function, :mod:`flumekit.waves.stream_function`),
        ``"stokes2"`` (second-order Stokes) or ``"linear"``.
    g : Gravitational acceleration [m s-2].

    Returns
    -------
    dict with ``k_incident``, ``k_reflected`` [rad m-1] (harmonic n travels with n k),
    ``incident`` and ``reflected`` (amplitudes of harmonics 1, 2, ... [m]; η = Σ a_n cos nθ),
    ``incident_velocity`` and ``reflected_velocity`` (V_n [m s-1]) and ``incident_current``,
    ``reflected_current`` (c_E [m s-1]) of the velocity in the direction of travel
    u = c_E + Σ V_n cosh(nk z_b)/cosh(nkh) cos nθ, w = Σ V_n sinh(nk z_b)/cosh(nkh) sin nθ
    (z_b above the bed, θ = kx - ωt along the direction of travel), and the incident
    ``wave`` (:class:`~flumekit.waves.stream_function.StreamFunctionWave`, or None).

    Notes
    -----
    ``"stream"``: the incident wave is the steady wave of height H, its harmonics from the
    first down to :data:`HARMONIC_CUTOFF` of the first's amplitude; the reflected wave is the
    steady wave of height Kr H, its harmonics scaled by the one factor that makes its first
    harmonic exactly Kr a1 (Kr is defined, and measured by the separation, on the first
    harmonic). This treats the reflected wave as a free steady wave of its own travelling
    away from the reflector, which it is once it has left the flap; the nonlinear interaction
    of the incident and reflected waves (at order Kr (k a)², a few % of the second harmonic for
    Kr = 0.2) is omitted. Its wavenumber is its own (nearly the linear one at its small
    height), the incident's is smaller than the linear one by up to 5 % in the flume's range
    (amplitude dispersion).
    Its velocities are scaled by the same factor and its mean current by its square.
    ``"stokes2"``: a1 from :func:`first_harmonic_amplitude`, a2 = B k a1², the reflected wave
    Kr a1 and Kr² a2; both with the linear wavenumber; V1 = a1 ω / tanh kh,
    V2 = (3/4) a1² ω k cosh 2kh / sinh⁴ kh (Dean & Dalrymple 1991, §11.3), no mean current.
    """
    if theory not in THEORIES:
        raise ValueError(f"theory must be one of {THEORIES}, got {theory!r}")
    omega = 2 * np.pi / period
    if theory == "stream":
        inc = nonlinear_wave(period, height, depth, g)
        a_inc = inc.elevation_coefficients
        n_kept = int(np.flatnonzero(np.abs(a_inc) > HARMONIC_CUTOFF * a_inc[0])[-1]) + 1
        a_inc = a_inc[:n_kept]
        v_inc = (inc.stream_coefficients * inc.wavenumber
                 * np.arange(1, inc.n_modes + 1))[:n_kept]
        out = {"k_incident": inc.wavenumber, "incident": a_inc, "incident_velocity": v_inc,
               "incident_current": inc.eulerian_current, "wave": inc,
               "k_reflected": inc.wavenumber, "reflected": 0 * a_inc[:1],
               "reflected_velocity": 0 * v_inc[:1], "reflected_current": 0.0}
        if reflection > 0:
            ref = nonlinear_wave(period, reflection * height, depth, g)
            scale = reflection * a_inc[0] / ref.elevation_coefficients[0]
            a_ref = scale * ref.elevation_coefficients
            n_kept = int(np.flatnonzero(np.abs(a_ref) > HARMONIC_CUTOFF * a_inc[0])[-1]) + 1
            n = np.arange(1, n_kept + 1)
            out.update(k_reflected=ref.wavenumber, reflected=a_ref[:n_kept],
                       reflected_velocity=scale * ref.stream_coefficients[:n_kept]
                       * ref.wavenumber * n,
                       reflected_current=scale**2 * ref.eulerian_current)
        return out
    k = float(wavenumber(omega, depth, g))
    a1 = first_harmonic_amplitude(height, k, depth, theory == "stokes2")
    q = np.exp(-2.0 * k * depth)
    vel = [a1 * omega * (1 + q) / (1 - q)]  # a ω / tanh kh
    amps = [a1]
    if theory == "stokes2":
        amps.append(float(stokes2_coefficient(k, depth)) * k * a1**2)
        vel.append(0.75 * a1**2 * omega * k * 8 * q * (1 + q * q) / (1 - q) ** 4)
    amps, vel = np.array(amps), np.array(vel)
    kr_n = reflection ** np.arange(1, amps.size + 1)
    return {"k_incident": k, "k_reflected": k, "incident": amps, "reflected": amps * kr_n,
            "incident_velocity": vel, "reflected_velocity": vel * kr_n,
            "incident_current": 0.0, "reflected_current": 0.0, "wave": None}


def harmonic_sum(amplitudes, envelope, cos_theta, sin_theta=None):
    """Σ_n a_n eⁿ cos nθ (and Σ_n a_n eⁿ sin nθ) [m] from cos θ and sin θ.

    The envelope scales harmonic n by eⁿ, as the bound harmonics of a slowly modulated Stokes
    wave; cos nθ, sin nθ come from the Chebyshev recurrences (no transcendental function per
    harmonic). ``amplitudes`` may hold depth-dependent factors as a last axis of length N.
    """
    a = np.asarray(amplitudes, dtype=float)
    c_prev, c_cur = np.ones_like(cos_theta), cos_theta
    s_prev, s_cur = np.zeros_like(cos_theta), sin_theta
    e_n = envelope
    out_c = a[..., 0] * e_n * c_cur
    out_s = None if sin_theta is None else a[..., 0] * e_n * s_cur
    for n in range(1, a.shape[-1]):  # a few tens of harmonics
        c_prev, c_cur = c_cur, 2 * cos_theta * c_cur - c_prev
        e_n = e_n * envelope
        out_c = out_c + a[..., n] * e_n * c_cur
        if sin_theta is not None:
            s_prev, s_cur = s_cur, 2 * cos_theta * s_cur - s_prev
            out_s = out_s + a[..., n] * e_n * s_cur
    return out_c if sin_theta is None else (out_c, out_s)


def regular_wave_field(time, x, *, period: float, height: float, depth: float,
                       reflection: float = 0.2, reflection_phase: float = 0.0,
                       x_reflector: float = 0.0, ramp_waves: float = 10.0,
                       second_order: bool = True, x_wavemaker: float = -32.7,
                       theory: str | None = None, g: float = G) -> xr.Dataset:
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
    second_order : Include the bound harmonics (``theory`` "stream" when True, "linear" when
        False, unless ``theory`` is given).
    x_wavemaker : Position of the wavemaker [m] (the envelope starts there at t = 0).
    theory : ``"stream"`` (stream-function theory, valid in every depth up to near breaking),
        ``"stokes2"`` (second-order Stokes, valid for Ursell numbers ≲ 26) or ``"linear"``;
        see :func:`wave_harmonics`.
    g : Gravitational acceleration [m s-2].

    Returns
    -------
    Dataset over ("x", "time") with ``eta_incident``, ``eta_reflected`` and ``eta`` (their sum)
    [m]. ``attrs`` hold the truth: ``incident_amplitude`` (first harmonic a1),
    ``bound_amplitude`` (second harmonic a2, 0 if linear), ``harmonic_amplitudes`` (a_n of the
    incident wave), ``reflection_coefficient`` (of the first harmonic), ``reflection_phase``,
    ``wave_height`` (H), ``wave_period``, ``wave_number`` (of the incident wave's first
    harmonic: the nonlinear one for "stream"), ``reflected_wave_number``,
    ``linear_wave_number``, ``wavelength``,
    ``group_velocity``, ``ursell_number``, ``wave_theory`` and the geometry.

    Notes
    -----
    Incident, with θ_I = ωt - k(x - x_wm) and envelope e_I = e(t - (x - x_wm)/c_g):
    η_I = Σ_n a_n e_I^n cos nθ_I. Reflected, the mirror image x → 2 x_r - x with its own
    wavenumber k_R: θ_R = ωt - k_I (x_r - x_wm) - k_R (x_r - x) + φ,
    η_R = Σ_n b_n e_R^n cos nθ_R, b_1 = Kr a1 (:func:`wave_harmonics`). With "stokes2",
    a2 = B k a1² and b2 = Kr² a2 (Dean & Dalrymple 1991). The envelope is advected with the
    linear group velocity without dispersion; the set-down under the groups and the
    incident-reflected interaction terms are omitted, as are re-reflections at the wavemaker
    (active absorption). Second-order Stokes theory is valid for Ursell numbers
    H L² / h³ ≲ 26; the flume's longer waves reach 65, which the stream function covers.
    """
    _check_positive(period=period, height=height, depth=depth, ramp_waves=ramp_waves)
    if not 0 <= reflection <= 1:
        raise ValueError(f"reflection coefficient must lie in [0, 1], got {reflection}")
    if not x_wavemaker < x_reflector:
        raise ValueError("the wavemaker must lie upstream (x smaller) of the reflector")
    theory = theory if theory is not None else ("stream" if second_order else "linear")
    time, x = _check_grid(time, x, x_wavemaker, x_reflector)
    omega = 2 * np.pi / period
    harm = wave_harmonics(period, height, depth, reflection, theory, g)
    k, k_r = harm["k_incident"], harm["k_reflected"]
    cg = float(group_velocity(period, depth, g))

    t = time[None, :]
    d_inc = (x - x_wavemaker)[:, None]  # travelled distance of the incident wave
    d_ref = (2 * x_reflector - x - x_wavemaker)[:, None]  # ... of the reflected wave
    ramp_time = ramp_waves * period / 2.0
    e_i = ramp_envelope(t - d_inc / cg, ramp_time)
    e_r = ramp_envelope(t - d_ref / cg, ramp_time)
    th_i = omega * t - k * d_inc
    th_r = (omega * t - k * (x_reflector - x_wavemaker) - k_r * (x_reflector - x)[:, None]
            + reflection_phase)
    eta_i = harmonic_sum(harm["incident"], e_i, np.cos(th_i))
    eta_r = harmonic_sum(harm["reflected"], e_r, np.cos(th_r))
    L = 2 * np.pi / k
    amps = harm["incident"]
    ds = xr.Dataset(
        {"eta_incident": (("x", "time"), eta_i), "eta_reflected": (("x", "time"), eta_r),
         "eta": (("x", "time"), eta_i + eta_r)},
        coords={"x": x, "time": time},
        attrs={"wave_period": period, "wave_height": height, "depth": depth,
               "incident_amplitude": float(amps[0]),
               "bound_amplitude": float(amps[1]) if amps.size > 1 else 0.0,
               "harmonic_amplitudes": np.asarray(amps, dtype=float),
               "reflection_coefficient": reflection, "reflection_phase": reflection_phase,
               "wave_number": k, "reflected_wave_number": k_r,
               "linear_wave_number": float(wavenumber(omega, depth, g)),
               "wavelength": L, "group_velocity": cg,
               "ursell_number": height * L**2 / depth**3, "x_reflector": x_reflector,
               "x_wavemaker": x_wavemaker, "ramp_waves": ramp_waves,
               "second_order": int(theory != "linear"), "wave_theory": theory,
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
