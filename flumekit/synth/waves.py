"""The virtual flume's wave generator: incident and reflected wave fields with a known truth.

Coordinates follow the campaign: x = 0 at the flap hinge, positive towards the beach; the
wavemaker sits at ``x_wavemaker`` < 0 and the incident wave travels towards +x. Regular waves
are steady nonlinear waves of the stream-function theory (:mod:`flumekit.waves.stream_function`,
valid in the whole range of the flume, Ursell numbers up to 65) unless second-order Stokes or
linear theory is asked for. The reflected wave travels back from ``x_reflector`` (the flap) with
the reflection coefficient and phase of its first harmonic; the beach's (:class:`Beach`)
returns from further down the flume. The truth (amplitudes, Kr, wavenumbers, ...) is returned
in the dataset's ``attrs``.
"""

from __future__ import annotations

import dataclasses
import functools

import numpy as np
import xarray as xr

from flumekit import conventions
from flumekit.docstrings import doc
from flumekit.waves.spectra import jonswap
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
    """Compute the linear ramp-up envelope e(τ) = min(τ / ramp_time, 1), 0 for τ ≤ 0.

    The wavemaker's paddle stroke ramped linearly over ``ramp_time`` [s], the usual ramp of a
    paddle's control signal. A linear ramp ends at full amplitude: the 2 % quasi-steady test
    of Brito et al. (2020, §2.5) passes within a wave of the ramp's end for η and for θ alike,
    as their Fig. 5 shows (both from t/T ≈ 35). An envelope that approaches 1 asymptotically
    (e.g. critically damped) would let θ, which the flap's quadratic losses make grow more
    slowly than the wave, pass the test before η.

    Parameters
    ----------
    tau : array_like
        Time since the wave front passed [s].
    ramp_time : float
        Ramp duration [s].

    Returns
    -------
    numpy.ndarray
        e(τ) [-], in [0, 1].

    Examples
    --------
    >>> ramp_envelope([-1.0, 5.0, 20.0], 10.0).tolist()
    [0.0, 0.5, 1.0]
    """
    s = np.asarray(tau, dtype=float) / ramp_time
    return np.clip(s, 0.0, 1.0)


def first_harmonic_amplitude(height: float, k: float, depth: float, second_order: bool) -> float:
    """Return the first-harmonic amplitude a1 [m] of a wave of crest-to-trough height ``height``.

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

#: the wavemaker's linear ramp in wave periods (:func:`ramp_envelope`): with the travel from
#: the wavemaker (3.1-3.8 periods to the probes and the flap at T = 3.5 s), η and θ pass the
#: 2 % quasi-steady test from t/T ≈ 35 (Brito et al. 2020, §2.5, Fig. 5: the pipeline measures
#: 35.1 and 35.2 in each of the 15 repeats of the default campaign). The crests pass the test
#: cycle by cycle, so an onset moves by a whole period when a crest lands at the 2 % bound:
#: at 31.8 periods WP1's crest did in 4 of the 15 repeats (η 35.6), at 31.0 θ starts at 34.2
RAMP_WAVES = 31.6


@dataclasses.dataclass(frozen=True)
class Beach:
    """The flume's passive beach as a reflector of the first harmonic.

    Brito et al. (2020), §2.1 and §2.3: a porous mesh beach of slope 0.3 at the end of the
    60 m flume, with a mean reflection coefficient of about 8 % measured without the flap.

    Attributes
    ----------
    reflection : Reflection coefficient K_b of the beach for the first harmonic [-]
        (0.08, Brito et al. 2020, §2.3).
    x : Effective reflection line [m] (x = 0 at the flap hinge). The flume ends 60 - 32.7 =
        27.3 m beyond the hinge; a 0.3 slope rising from the bed to the flume's top (1.8 m) at
        the end wall crosses the still water level 0.975/0.3 = 3.25 m before it, at 24.05 m
        (the beach's toe and crest are not stated: an assumption that sets only the phase).
    phase : Phase added at the reflection line [rad].
    transmission : Amplitude transmission coefficient K_t of whatever stands between the
        probes and the beach (the flap), each way [-]; the beach's wave reaches the probes
        with K_b K_t² a1. 1 for a flume without the flap.
    """

    reflection: float = 0.08
    x: float = 24.05
    phase: float = 0.0
    transmission: float = 1.0

    def __post_init__(self) -> None:
        """Refuse coefficients outside [0, 1] and a non-finite position or phase."""
        for name in ("reflection", "transmission"):
            v = getattr(self, name)
            if not 0 <= v <= 1:
                raise ValueError(f"beach {name} must lie in [0, 1], got {v}")
        if not (np.isfinite(self.x) and np.isfinite(self.phase)):
            raise ValueError("beach x and phase must be finite")


#: harmonics of a stream-function wave kept in the virtual flume: those above this fraction of
#: the first harmonic's amplitude (the rest, < 0.015 mm in the flume's range, lie far below the
#: probes' 0.5 mm noise; about 10 of the 20 computed at T = 3.5 s, H = 0.25 m)
HARMONIC_CUTOFF = 1e-4


@functools.lru_cache(maxsize=64)
def nonlinear_wave(period: float, height: float, depth: float, g: float = G
                   ) -> StreamFunctionWave:
    """Return the flume's steady nonlinear wave (stream-function theory, cached).

    :func:`flumekit.waves.stream_function_wave` with Stokes' second definition of celerity
    (zero mean mass transport: a closed flume) and its default 20 modes; cached because a
    run's records and its UVP evaluate the same wave.

    Parameters
    ----------
    period : float
        Wave period [s].
    height : float
        Crest-to-trough wave height [m].
    depth : float
        Still water depth [m].
    %(g)s

    Returns
    -------
    flumekit.waves.stream_function.StreamFunctionWave
        The steady wave.
    """
    return stream_function_wave(period, height, depth, current="stokes", g=g)


@doc
def wave_harmonics(period: float, height: float, depth: float, reflection: float = 0.0,
                   theory: str = "stream", g: float = G, beach: float = 0.0
                   ) -> dict[str, object]:
    """Compute harmonic amplitudes and wavenumbers of the incident and reflected regular waves.

    Parameters
    ----------
    period : float
        Wave period T [s].
    height : float
        Crest-to-trough height H of the incident wave [m].
    depth : float
        Still water depth h [m].
    reflection : float, default 0
        Reflection coefficient Kr of the first harmonic [-].
    theory : str, default "stream"
        ``"stream"`` (stream function, :mod:`flumekit.waves.stream_function`),
        ``"stokes2"`` (second-order Stokes) or ``"linear"``.
    %(g)s
    beach : float, default 0
        First-harmonic amplitude of the wave returning from the beach, over a1 [-].

    Returns
    -------
    dict
        ``k_incident``, ``k_reflected``, ``k_beach`` [rad m-1] (harmonic n travels with
    n k), ``incident``, ``reflected`` and ``beach`` (amplitudes of harmonics 1, 2, ... [m];
    η = Σ a_n cos nθ), ``<wave>_velocity`` (V_n [m s-1]) and ``<wave>_current`` (c_E [m s-1])
    of the velocity in the direction of travel
    u = c_E + Σ V_n cosh(nk z_b)/cosh(nkh) cos nθ, w = Σ V_n sinh(nk z_b)/cosh(nkh) sin nθ
    (z_b above the bed, θ = kx - ωt along the direction of travel), and the incident
    ``wave`` (:class:`~flumekit.waves.stream_function.StreamFunctionWave`, or None).

    Notes
    -----
    ``"stream"``: the incident wave is the steady wave of height H, its harmonics from the
    first down to :data:`HARMONIC_CUTOFF` of the first's amplitude; a returning wave (reflected
    by the flap, or by the beach) of first-harmonic ratio r is the steady wave of height r H,
    its harmonics scaled by the one factor that makes its first harmonic exactly r a1 (Kr is
    defined, and measured by the separation, on the first harmonic), its velocities by the
    same factor and its mean current by its square. This treats it as a free steady wave of
    its own travelling away from its reflector, which it is once it has left it; the
    nonlinear interaction of the incident and returning waves (at order r (k a)², a few % of
    the second harmonic for r = 0.2) is omitted. Its wavenumber is its own (nearly the linear
    one at its small height), the incident's is smaller than the linear one by up to 5 % in the
    flume's range (amplitude dispersion).
    ``"stokes2"``: a1 from :func:`first_harmonic_amplitude`, a2 = B k a1², a returning wave
    r a1 and r² a2; all with the linear wavenumber; V1 = a1 ω / tanh kh,
    V2 = (3/4) a1² ω k cosh 2kh / sinh⁴ kh (Dean & Dalrymple 1991, §11.3), no mean current.
    """
    if theory not in THEORIES:
        raise ValueError(f"theory must be one of {THEORIES}, got {theory!r}")
    omega = 2 * np.pi / period
    if theory == "stream":
        inc = nonlinear_wave(period, height, depth, g)
        a1 = inc.elevation_coefficients[0]

        def kept(w: StreamFunctionWave, scale: float):
            a = scale * w.elevation_coefficients
            n = int(np.flatnonzero(np.abs(a) > HARMONIC_CUTOFF * a1)[-1]) + 1
            vel = scale * w.stream_coefficients[:n] * w.wavenumber * np.arange(1, n + 1)
            return w.wavenumber, a[:n], vel, scale**2 * w.eulerian_current

        def returning(ratio: float):
            if not ratio > 0:
                return inc.wavenumber, np.zeros(1), np.zeros(1), 0.0
            w = nonlinear_wave(period, ratio * height, depth, g)
            return kept(w, ratio * a1 / w.elevation_coefficients[0])

        waves = {"incident": kept(inc, 1.0), "reflected": returning(reflection),
                 "beach": returning(beach)}
    else:
        k = float(wavenumber(omega, depth, g))
        a1 = first_harmonic_amplitude(height, k, depth, theory == "stokes2")
        q = np.exp(-2.0 * k * depth)
        vel = [a1 * omega * (1 + q) / (1 - q)]  # a ω / tanh kh
        amps = [a1]
        if theory == "stokes2":
            amps.append(float(stokes2_coefficient(k, depth)) * k * a1**2)
            vel.append(0.75 * a1**2 * omega * k * 8 * q * (1 + q * q) / (1 - q) ** 4)
        amps, vel = np.array(amps), np.array(vel)
        waves = {name: (k, amps * r ** np.arange(1, amps.size + 1),
                        vel * r ** np.arange(1, amps.size + 1), 0.0)
                 for name, r in (("incident", 1.0), ("reflected", reflection),
                                 ("beach", beach))}
        inc = None
    out = {"wave": inc}
    for name, (k, a, v, c) in waves.items():
        out.update({f"k_{name}": k, name: a, f"{name}_velocity": v, f"{name}_current": c})
    return out


def harmonic_sum(amplitudes, envelope, cos_theta) -> np.ndarray:
    """Sum the harmonics Σ_n a_n eⁿ cos nθ from cos θ.

    The envelope scales harmonic n by eⁿ, as the bound harmonics of a slowly modulated Stokes
    wave; cos nθ comes from the Chebyshev recurrence (no transcendental function per
    harmonic).

    Parameters
    ----------
    amplitudes : array_like
        a_n of harmonics 1, 2, ... [m].
    envelope : numpy.ndarray
        Envelope e [-], broadcastable with ``cos_theta``.
    cos_theta : numpy.ndarray
        cos θ of the first harmonic's phase [-].

    Returns
    -------
    numpy.ndarray
        The elevation [m].

    Examples
    --------
    >>> import numpy as np
    >>> float(harmonic_sum([0.1, 0.01], 1.0, np.cos(np.array(0.0)))) == 0.11
    True
    """
    a = np.asarray(amplitudes, dtype=float)
    c_prev, c_cur = np.ones_like(cos_theta), cos_theta
    e_n = envelope
    out = a[0] * e_n * c_cur
    for n in range(1, a.size):  # the harmonics kept (about ten)
        c_prev, c_cur = c_cur, 2 * cos_theta * c_cur - c_prev
        e_n = e_n * envelope
        out = out + a[n] * e_n * c_cur
    return out


@doc
def regular_wave_field(time, x, *, period: float, height: float, depth: float,
                       reflection: float = 0.2, reflection_phase: float = 0.0,
                       x_reflector: float = 0.0, ramp_waves: float = RAMP_WAVES,
                       second_order: bool = True, x_wavemaker: float = -32.7,
                       theory: str | None = None, beach: Beach | None = None,
                       g: float = G) -> xr.Dataset:
    """Synthesise regular incident and reflected waves with a ramp-up at positions ``x``.

    Parameters
    ----------
    time : array_like
        Time since the start of wave generation [s], 1-D.
    x : array_like
        Positions along the flume [m], 1-D, between ``x_wavemaker`` and ``x_reflector``.
    period : float
        Wave period T [s].
    height : float
        Target crest-to-trough height H of the steady incident wave [m].
    depth : float
        Still water depth h [m].
    reflection : float, default 0.2
        Reflection coefficient Kr of the first harmonic [-], 0 ≤ Kr ≤ 1.
    reflection_phase : float, default 0
        Phase added to the reflected wave at the reflector [rad].
    x_reflector : float, default 0
        Position of the reflector (flap) [m].
    ramp_waves : float, default :data:`RAMP_WAVES`
        Ramp length in wave periods [-]: the envelope at the wavemaker is
        :func:`ramp_envelope` with ramp time ``ramp_waves``·T. The default with the travel
        time from the wavemaker makes the records quasi-steady (Brito et al. 2020, §2.5
        criterion) after about 35 waves at the probes and at the flap for T = 3.5 s, as in
        the paper.
    second_order : bool, default True
        Include the bound harmonics (``theory`` "stream" when True, "linear" when False,
        unless ``theory`` is given).
    x_wavemaker : float, default -32.7
        Position of the wavemaker [m] (the envelope starts there at t = 0).
    theory : str, optional
        ``"stream"`` (stream-function theory, valid in every depth up to near breaking),
        ``"stokes2"`` (second-order Stokes, valid for Ursell numbers ≲ 26) or ``"linear"``;
        see :func:`wave_harmonics`.
    beach : Beach, optional
        The wave returning from the flume's beach; None: no beach reflection (a perfect
        absorber).
    %(g)s

    Returns
    -------
    xarray.Dataset
        Over ("x", "time"): ``eta_incident``, ``eta_reflected`` (from the reflector),
        ``eta_beach`` (from the beach, 0 without one) and ``eta`` (their sum) [m]. ``attrs``
        hold the truth: ``incident_amplitude`` (first harmonic a1 [m]), ``bound_amplitude``
        (second harmonic a2 [m], 0 if linear), ``harmonic_amplitudes`` (a_n of the incident
        wave [m]), ``reflection_coefficient``: the first-harmonic amplitude of everything
        travelling towards the wavemaker (reflector and beach) over a1 at ``x_reflector``,
        which is what a separation measures; ``flap_reflection_coefficient``
        (``reflection``), ``reflection_phase``, ``beach_reflection_coefficient``,
        ``beach_transmission``, ``x_beach``, ``beach_phase``, ``wave_height`` (H),
        ``wave_period``, ``wave_number`` (of the incident wave's first harmonic: the
        nonlinear one for "stream"), ``reflected_wave_number``, ``linear_wave_number``,
        ``wavelength``, ``group_velocity``, ``ursell_number``, ``wave_theory`` and the
        geometry.

    Raises
    ------
    ValueError
        If a length or period is not positive, Kr lies outside [0, 1], the wavemaker is not
        upstream of the reflector, a position lies outside them or ``theory`` is unknown.

    Notes
    -----
    Incident, with θ_I = ωt - k(x - x_wm) and envelope e_I = e(t - (x - x_wm)/c_g):
    η_I = Σ_n a_n e_I^n cos nθ_I. Reflected, the mirror image x → 2 x_r - x with its own
    wavenumber k_R: θ_R = ωt - k_I (x_r - x_wm) - k_R (x_r - x) + φ,
    η_R = Σ_n b_n e_R^n cos nθ_R, b_1 = Kr a1 (:func:`wave_harmonics`). From the beach (at
    x_b, reflection coefficient K_b, phase ψ), after passing the reflector twice (amplitude
    transmission K_t each way): θ_B = ωt - k_I (x_b - x_wm) - k_B (x_b - x) + ψ,
    η_B = Σ_n c_n e_B^n cos nθ_B, c_1 = K_b K_t² a1, e_B = e(t - (2 x_b - x - x_wm)/c_g); the
    leg behind the reflector is taken with the incident wavenumber, and the reflections of the
    beach's wave at the reflector (order K_r K_b) are omitted. With "stokes2",
    a2 = B k a1² and b2 = Kr² a2 (Dean & Dalrymple 1991). The envelope is advected with the
    linear group velocity without dispersion; the set-down under the groups and the
    incident-reflected interaction terms are omitted, as are re-reflections at the wavemaker
    (active absorption). Second-order Stokes theory is valid for Ursell numbers
    H L² / h³ ≲ 26; the flume's longer waves reach 65, which the stream function covers.

    References
    ----------
    Dean, R. G. & Dalrymple, R. A. (1991). Water Wave Mechanics for Engineers and Scientists.
    World Scientific (§11.3).
    Brito, M. et al. (2020). Experimental investigation on the power capture of an oscillating
    wave surge converter in unidirectional waves. Energies 13, 5417 (§2.1-2.5).

    Examples
    --------
    >>> import numpy as np
    >>> ds = regular_wave_field(np.arange(0, 200, 0.04), [-2.0], period=2.0, height=0.1,
    ...                         depth=0.825, reflection=0.0, theory="linear")
    >>> round(float(ds.eta.isel(time=slice(-50, None)).max()), 4)
    0.05
    """
    _check_positive(period=period, height=height, depth=depth, ramp_waves=ramp_waves)
    if not 0 <= reflection <= 1:
        raise ValueError(f"reflection coefficient must lie in [0, 1], got {reflection}")
    if not x_wavemaker < x_reflector:
        raise ValueError("the wavemaker must lie upstream (x smaller) of the reflector")
    theory = theory if theory is not None else ("stream" if second_order else "linear")
    time, x = _check_grid(time, x, x_wavemaker, x_reflector)
    beach = Beach(reflection=0.0) if beach is None else beach
    if not beach.x > x_reflector:
        raise ValueError(f"the beach (x = {beach.x} m) must lie beyond the reflector "
                         f"(x = {x_reflector} m)")
    omega = 2 * np.pi / period
    r_beach = beach.reflection * beach.transmission**2
    harm = wave_harmonics(period, height, depth, reflection, theory, g, beach=r_beach)
    k, k_r, k_b = harm["k_incident"], harm["k_reflected"], harm["k_beach"]
    cg = float(group_velocity(period, depth, g))

    t = time[None, :]
    d_inc = (x - x_wavemaker)[:, None]  # travelled distance of the incident wave
    d_ref = (2 * x_reflector - x - x_wavemaker)[:, None]  # ... of the reflected wave
    ramp_time = ramp_waves * period
    e_i = ramp_envelope(t - d_inc / cg, ramp_time)
    e_r = ramp_envelope(t - d_ref / cg, ramp_time)
    th_i = omega * t - k * d_inc
    th_r = (omega * t - k * (x_reflector - x_wavemaker) - k_r * (x_reflector - x)[:, None]
            + reflection_phase)
    eta_i = harmonic_sum(harm["incident"], e_i, np.cos(th_i))
    eta_r = harmonic_sum(harm["reflected"], e_r, np.cos(th_r))
    eta_b = np.zeros_like(eta_i)
    if r_beach > 0:
        e_b = ramp_envelope(t - (2 * beach.x - x - x_wavemaker)[:, None] / cg, ramp_time)
        th_b = (omega * t - k * (beach.x - x_wavemaker) - k_b * (beach.x - x)[:, None]
                + beach.phase)
        eta_b = harmonic_sum(harm["beach"], e_b, np.cos(th_b))
    # the returning first harmonics at the reflector, relative to the incident one there
    total = (reflection * np.exp(1j * reflection_phase)
             + r_beach * np.exp(1j * (beach.phase - (k + k_b) * (beach.x - x_reflector))))
    L = 2 * np.pi / k
    amps = harm["incident"]
    ds = xr.Dataset(
        {"eta_incident": (("x", "time"), eta_i), "eta_reflected": (("x", "time"), eta_r),
         "eta_beach": (("x", "time"), eta_b), "eta": (("x", "time"), eta_i + eta_r + eta_b)},
        coords={"x": x, "time": time},
        attrs={"wave_period": period, "wave_height": height, "depth": depth,
               "incident_amplitude": float(amps[0]),
               "bound_amplitude": float(amps[1]) if amps.size > 1 else 0.0,
               "harmonic_amplitudes": np.asarray(amps, dtype=float),
               "reflection_coefficient": float(abs(total)),
               "total_reflection_phase": float(np.angle(total)),
               "flap_reflection_coefficient": reflection, "reflection_phase": reflection_phase,
               "beach_reflection_coefficient": beach.reflection,
               "beach_transmission": beach.transmission, "x_beach": beach.x,
               "beach_phase": beach.phase, "beach_wave_number": k_b,
               "wave_number": k, "reflected_wave_number": k_r,
               "linear_wave_number": float(wavenumber(omega, depth, g)),
               "wavelength": L, "group_velocity": cg,
               "ursell_number": height * L**2 / depth**3, "x_reflector": x_reflector,
               "x_wavemaker": x_wavemaker, "ramp_waves": ramp_waves,
               "second_order": int(theory != "linear"), "wave_theory": theory,
               "phase_reference": "incident phase zero at the wavemaker: "
                                  "theta = w t - k (x - x_wavemaker)"})
    return conventions.annotate(ds)


@doc
def random_phase_components(repeat_period: float, hm0: float, peak_period: float,
                            gamma: float, seed: int, band: tuple[float, float]
                            ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Return the wavemaker's components of a JONSWAP sea by the random-phase method.

    Parameters
    ----------
    repeat_period : float
        Repeat period T_R of the wavemaker signal [s]: the components lie on f_n = n / T_R.
    hm0 : float
        Target spectral significant height Hm0 [m].
    peak_period : float
        Target peak period Tp [s].
    gamma : float
        JONSWAP peak enhancement factor [-].
    seed : int
        Seed of the phases (``numpy.random.default_rng(seed)``): the same seed, the same sea.
    band : tuple of float
        (f_min, f_max) generated band [Hz].

    Returns
    -------
    f : numpy.ndarray
        Component frequencies [Hz] (those of the grid in ``band``).
    a : numpy.ndarray
        Amplitudes a_n = sqrt(2 S(f_n) Δf) [m], S the :func:`jonswap` of the band, so that
        Σ a_n²/2 = Hm0²/16 exactly.
    psi : numpy.ndarray
        Phases ψ_n, uniform in [0, 2π) [rad]: η = Σ a_n cos(2π f_n t + ψ_n).

    Notes
    -----
    Deterministic amplitudes and random phases (the random-phase method, e.g. Tucker et al.
    1984): the realised spectrum over one repeat period is the target exactly, and the sea is
    Gaussian by the central limit theorem over the many components.

    %(references_tucker1984)s.

    Examples
    --------
    >>> import numpy as np
    >>> f, a, psi = random_phase_components(300.0, 0.1, 2.0, 3.3, seed=11, band=(0.3, 1.5))
    >>> f.size, round(4 * float(np.sqrt(np.sum(a**2) / 2)), 9)
    (361, 0.1)
    """
    _check_positive(repeat_period=repeat_period, hm0=hm0, peak_period=peak_period,
                    gamma=gamma)
    df = 1.0 / repeat_period
    f = np.arange(int(np.floor(band[1] / df * (1 + 1e-9))) + 1) * df
    s = jonswap(f, hm0, peak_period, gamma, band=band)
    keep = s > 0
    if keep.sum() < 8:
        raise ValueError(f"fewer than 8 components in the band {band} Hz at a repeat period "
                         f"of {repeat_period} s")
    psi = np.random.default_rng(seed).uniform(0.0, 2 * np.pi, int(keep.sum()))
    return f[keep], np.sqrt(2 * s[keep] * df), psi


@doc
def irregular_wave_field(time, x, *, hm0: float, peak_period: float, depth: float,
                         gamma: float = 3.3, reflection: float = 0.2,
                         reflection_phase: float = 0.0, x_reflector: float = 0.0,
                         rng: np.random.Generator | int | None = None,
                         f_max: float | None = None, g: float = G) -> xr.Dataset:
    """Synthesise linear irregular (JONSWAP) incident and reflected waves with random phases.

    Parameters
    ----------
    time : array_like
        Uniformly sampled time [s], 1-D (N samples, step Δt).
    x : array_like
        Positions [m], 1-D, x ≤ ``x_reflector``.
    hm0 : float
        Spectral significant height of the incident wave, 4 sqrt(m0) [m].
    peak_period : float
        Peak period Tp [s].
    depth : float
        Water depth [m].
    gamma : float, default 3.3
        JONSWAP peak enhancement factor [-].
    reflection : float, default 0.2
        Frequency-independent reflection coefficient [-].
    reflection_phase : float, default 0
        Phase added at the reflector [rad].
    x_reflector : float, default 0
        Reflector position [m]; incident phases are referenced to it.
    rng : numpy.random.Generator or int, optional
        Random generator or seed of the phases (deterministic for a given seed).
    f_max : float, optional
        Highest component frequency [Hz]; default min(5/Tp, Nyquist).
    %(g)s

    Returns
    -------
    xarray.Dataset
        Over ("x", "time"): ``eta_incident``, ``eta_reflected``, ``eta`` [m]; the truth in
        ``attrs`` (``hm0`` of the incident wave exactly, ``reflection_coefficient``, ...).

    Raises
    ------
    ValueError
        If Hm0, Tp, the depth or γ is not positive, Kr lies outside [0, 1], the time is not
        uniform or holds fewer than 8 components below ``f_max``.

    Notes
    -----
    The components sit on the record's Fourier bins f_n = n / (N Δt), so every record is exactly
    periodic (no leakage), with deterministic amplitudes a_n = sqrt(2 S(f_n) Δf) and uniform
    random phases: η_I = Σ a_n cos(ω_n t - k_n (x - x_r) + ψ_n),
    η_R = Kr Σ a_n cos(ω_n t + k_n (x - x_r) + ψ_n + φ).

    %(references_random_sea)s

    Examples
    --------
    >>> import numpy as np
    >>> ds = irregular_wave_field(np.arange(0, 600, 0.04), [-2.0, 0.0], hm0=0.1,
    ...                           peak_period=2.0, depth=0.825, rng=1)
    >>> round(4 * float(ds.eta_incident.std("time")[0]), 6)
    0.1
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
