"""The virtual flume in irregular seas: a JONSWAP sea, its reflections and its truth.

A JONSWAP sea travels from the wavemaker to the probes and the flap, with the flap's and the
beach's reflections; the truth is the realised sea state.

The wavemaker (at ``x_wavemaker``) plays the random-phase components of a JONSWAP spectrum
(:func:`flumekit.synth.waves.random_phase_components`, phases from the run's declared seed)
repeating with period T_R, ramped up linearly as the regular runs are
(:func:`flumekit.synth.waves.ramp_envelope`, over :attr:`SeaTruth.ramp_peak_periods` peak
periods). The flume is linear and time-invariant, so every wave at every position is that
signal through a transfer function, applied in one FFT of the ramped signal and one inverse
FFT for all positions and waves (:func:`irregular_sea`): each component travels with its own
wavenumber, so the ramp's front disperses as it should. In numpy's convention
η = Re Σ c e^{+iωt}, with k(f) of linear dispersion in depth h:

* incident at x: e^{-ik (x - x_wm)};
* reflected by the flap: R(f) e^{-ik (-x_wm)} e^{-ik (0 - x)}, R of the flap's linear model
  (:func:`flumekit.synth.flap.flap_scattering`: 19 % at 3.5 s, 32 % at 2 s, 79 % at 1 s);
* from the beach: T(f)² K_b(f) e^{iψ_b} e^{-ik (2 x_b - x_wm - x)}, through the flap both ways
  (its transmission T(f) of the same model) and reflected by the beach with
  K_b(f) = K_b / (1 + (f/f_b)⁴) (:func:`beach_reflection`: the 8 % of Brito et al. 2020 at the
  regular runs' long waves, less for the shorter, steeper waves that a porous slope absorbs
  better).

What the separation measures at the flap is therefore R_eff(f) = R(f) + T(f)² K_b(f)
e^{iψ_b} e^{-2ik x_b}: everything travelling towards the wavemaker at x = 0 over the incident
wave there. Its modulus oscillates about |R(f)| with the beach's delay (±0.05 at 0.4 Hz, a
period of about 0.045 Hz); a Kr(f) smoothed over bands wider than that follows
sqrt(Σ S_R / Σ S_I) of the truth's spectra over the same bands. Waves re-reflected between the
flap and the beach (order R K_b) and at the wavemaker (active absorption), and second-order
bound waves, are omitted: the sea is linear.

The records are ``duration`` long. The analysed span is the last repeat period,
[t_s, duration): it starts once the components holding :attr:`SeaTruth.developed` of the
variance of each wave (incident at the flap, reflected and from the beach at the farthest
probe) have arrived after the ramp (:func:`analysis_start`), so over it every record is one
period of a steady random sea and its FFT grid is the components' grid.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
import xarray as xr
from scipy import fft as sfft

from flumekit import conventions
from flumekit.docstrings import doc
from flumekit.synth.waves import Beach, ramp_envelope, random_phase_components
from flumekit.waves.theory import G, group_velocity, wavenumber


@dataclass(frozen=True)
class SeaTruth:
    """The virtual flume's choices for irregular runs (module notes).

    Attributes
    ----------
    ramp_peak_periods : float
        Linear ramp of the wavemaker [Tp].
    band : tuple of float
        Generated band (f_min, f_max) [fp]: 0.6-3 fp holds all but 1 % of a γ = 3.3
        spectrum's variance (0.1 % below 0.66 fp).
    loss_damping : float
        ν_L of the flap's reflection model [N m s]
        (:func:`flumekit.synth.flap.flap_scattering`).
    beach_roll_off : float
        f_b of the beach's reflection K_b / (1 + (f/f_b)⁴) [Hz].
    developed : float
        Share of each wave's variance arrived at the flap and the probes before the
        analysed span [-].
    lead_out : float
        The flap is driven this long past the record's end [s]
        (:func:`flumekit.synth.flap.flap_record`).
    cut : tuple of float
        The flume's response tapers (cos²) from ``cut[0]`` to ``cut[1]`` times the band's
        f_max to zero [-]: no energy of the ramp's spectral spread travels so slowly that it
        would wrap round the FFT.
    probe_x : tuple of (str, float)
        Probe positions of the irregular runs [m]. WP1-WP3 are 0.2 m and 1.0 m apart:
        over 0.2-1.8 Hz (every run's band, Tp 1.6-3.0 s) their separation matrix has a
        condition number of at most 4.3, below the Goda-Suzuki limit 6.3
        (:func:`flumekit.waves.layout.check_layout`); the regular runs' L/10, L/4 layout of
        the peak wavelength reaches 60-150 in that band (spacings near L/2 at 1.1-1.6 Hz).
    """

    ramp_peak_periods: float = 10.0
    band: tuple[float, float] = (0.6, 3.0)
    loss_damping: float = 110.0
    beach_roll_off: float = 0.6
    developed: float = 0.999
    lead_out: float = 20.0
    cut: tuple[float, float] = (1.2, 1.6)
    probe_x: tuple[tuple[str, float], ...] = (("WP1", -3.2), ("WP2", -3.0), ("WP3", -2.0),
                                              ("WP4", -0.6))


def beach_reflection(frequency, beach: Beach, roll_off: float) -> np.ndarray:
    """Compute the beach's reflection coefficient K_b(f) = K_b / (1 + (f/f_b)⁴).

    Parameters
    ----------
    frequency : array_like
        Frequencies [Hz].
    beach : Beach
        Its ``reflection`` K_b at the long waves [-].
    roll_off : float
        f_b [Hz]: K_b/2 there.

    Returns
    -------
    numpy.ndarray
        K_b(f) [-].

    Notes
    -----
    Porous and sloping beaches reflect long waves most and absorb the shorter, steeper ones
    that break on them (reflection growing with the surf similarity parameter, Battjes 1974;
    Seelig & Ahrens 1981). The form is a smooth stand-in with that trend: 0.078 at 0.25 Hz,
    0.054 at 0.5 Hz, 0.009 at 1 Hz for K_b = 0.08, f_b = 0.6 Hz.

    References
    ----------
    Battjes, J. A. (1974). Surf similarity. Proc. 14th Coastal Engineering Conference, 466-480.
    Seelig, W. N. & Ahrens, J. P. (1981). Estimation of wave reflection and energy dissipation
    coefficients for beaches, revetments and breakwaters. CERC Tech. Paper 81-1.

    Examples
    --------
    >>> from flumekit.synth.waves import Beach
    >>> beach_reflection([0.25, 0.6, 1.0], Beach(), 0.6).round(4).tolist()
    [0.0777, 0.04, 0.0092]
    """
    f = np.asarray(frequency, dtype=float)
    return beach.reflection / (1.0 + (f / roll_off) ** 4)


class IrregularSea(NamedTuple):
    """The output of :func:`irregular_sea`."""

    field: xr.Dataset  # eta_incident, eta_reflected, eta_beach over (x, time) [m]
    frequency: np.ndarray  # components f_n [Hz]
    amplitude: np.ndarray  # a_n [m]
    phase: np.ndarray  # ψ_n at the wavemaker [rad]
    reflection: Callable  # f -> R_eff(f) at x = 0 (complex)
    flap: Callable  # f -> (R, T) of the flap
    beach: Callable  # f -> K_b(f)
    analysis_start: float  # [s]
    repeat_period: float  # T_R [s]


@doc
def analysis_start(frequency, amplitude, *, depth: float, x_min: float, x_wavemaker: float,
                   x_beach: float, ramp_time: float, returning, developed: float,
                   g: float = G) -> float:
    """Return the first whole second at which every wave has developed at the flap and probes.

    Parameters
    ----------
    frequency, amplitude : array_like
        The wavemaker's components f_n [Hz] and a_n [m].
    depth : float
        Water depth [m].
    x_min : float
        The probe farthest from the flap [m].
    x_wavemaker, x_beach : float
        Positions of the wavemaker and of the beach's reflection line [m].
    ramp_time : float
        Length of the wavemaker's linear ramp τ [s].
    returning : callable
        f -> (R, T² K_b e^{iψ_b - 2ik x_b}): the complex amplitudes of the flap's reflection
        and of the beach's wave at x = 0 per unit incident amplitude.
    developed : float
        Share of each wave's variance that must have arrived [-].
    %(g)s

    Returns
    -------
    float
        t_s [s], a whole second.

    Notes
    -----
    Component n of a wave that travels a distance d arrives fully ramped at τ + d / c_g(f_n);
    a wave has developed when the components holding ``developed`` of its variance have
    arrived. Waves: the incident at x = 0 (d = -x_wm), the flap's reflection and the beach's
    wave at the farthest probe (d = -x_wm - x_min and 2 x_b - x_wm - x_min).

    Examples
    --------
    >>> import numpy as np
    >>> f = np.array([0.5, 1.0])
    >>> analysis_start(f, np.ones(2), depth=0.825, x_min=-3.2, x_wavemaker=-32.7,
    ...                x_beach=24.05, ramp_time=20.0, developed=0.999,
    ...                returning=lambda f: (np.zeros(f.size), np.zeros(f.size)))
    62.0
    """
    f = np.asarray(frequency, dtype=float)
    cg = group_velocity(1.0 / f, depth, g)
    r, b = returning(f)
    waves = ((np.ones_like(f), -x_wavemaker),
             (np.abs(r), -x_wavemaker - x_min),
             (np.abs(b), 2 * x_beach - x_wavemaker - x_min))
    latest = 0.0
    for gain, path in waves:
        w = (gain * amplitude) ** 2
        if not w.sum() > 0:
            continue
        arrival = ramp_time + path / cg
        order = np.argsort(arrival)
        cum = np.cumsum(w[order]) / w.sum()
        latest = max(latest, float(arrival[order][np.searchsorted(cum, developed)]))
    return float(np.ceil(latest))


@doc
def irregular_sea(rate: float, duration: float, x, *, hm0: float, peak_period: float,
                  gamma: float, seed: int, depth: float, flap: Callable, beach: Beach,
                  x_wavemaker: float, sea: SeaTruth = SeaTruth(), g: float = G
                  ) -> IrregularSea:
    """Synthesise the incident, reflected and beach waves of a JONSWAP sea at positions ``x``.

    The flume's linear transfer functions of the module notes, applied to the wavemaker's
    ramped random-phase signal.

    Parameters
    ----------
    rate : float
        Sampling rate of the output [Hz].
    duration : float
        Record length [s], whole seconds; the field covers it and ``sea.lead_out`` beyond.
    x : array_like
        Positions [m], between the wavemaker and the flap (x ≤ 0).
    hm0, peak_period, gamma : float
        The generated JONSWAP spectrum: Hm0 [m], Tp [s], γ [-].
    seed : int
        Seed of the random phases.
    depth : float
        Water depth [m].
    flap : callable
        f [Hz] -> (R, T), the flap's complex reflection and transmission
        (:func:`flumekit.synth.flap.flap_scattering`).
    beach : Beach
        Position ``x``, phase and long-wave reflection of the beach.
    x_wavemaker : float
        Wavemaker position [m].
    sea : SeaTruth
        Ramp, band, developed share, lead-out, low-pass taper.
    %(g)s

    Returns
    -------
    IrregularSea
        The field (``eta_incident``, ``eta_reflected``, ``eta_beach`` over ("x", "time")), the
        components at the wavemaker, R_eff(f), the analysed span's start and T_R.

    Raises
    ------
    ValueError
        If a position lies outside (x_wavemaker, 0], ``duration`` is not whole seconds or
        leaves fewer than 50 peak periods after the sea has developed, the rate does not
        hold whole samples in the repeat period, or the band holds too few components.

    Notes
    -----
    One FFT of the ramped wavemaker signal and one inverse FFT of all positions and waves
    (module notes). The FFT spans the record, the lead-out, the ramp-down and the slowest
    wave's travel from the wavemaker to the beach and back to the farthest position, so
    nothing wraps round into the record.

    %(references_random_sea)s

    Examples
    --------
    >>> import numpy as np
    >>> from flumekit.synth.waves import Beach
    >>> def wall(f):  # a fixed, fully reflecting flap
    ...     return np.ones(f.size, complex), np.zeros(f.size, complex)
    >>> sea = irregular_sea(25.0, 300, [-3.0, 0.0], hm0=0.1, peak_period=2.0, gamma=3.3,
    ...                     seed=1, depth=0.825, flap=wall, beach=Beach(),
    ...                     x_wavemaker=-32.7)
    >>> round(abs(complex(sea.reflection(np.array([0.5]))[0])), 6)
    1.0
    """
    x = np.atleast_1d(np.asarray(x, dtype=float))
    if np.any(x > 0) or np.any(x <= x_wavemaker):
        raise ValueError(f"positions {x.tolist()} m must lie between the wavemaker and the flap")
    if float(duration) != round(duration):
        raise ValueError(f"duration must be whole seconds, got {duration}")
    fp = 1.0 / peak_period
    band = (sea.band[0] * fp, sea.band[1] * fp)
    ramp_time = sea.ramp_peak_periods * peak_period

    def kb(f):
        return beach_reflection(f, beach, sea.beach_roll_off)

    def returning(f):
        r, t = flap(f)
        k = wavenumber(2 * np.pi * f, depth, g)
        return r, t**2 * kb(f) * np.exp(1j * (beach.phase - 2 * k * beach.x))

    def reflection(f):
        r, b = returning(np.asarray(f, dtype=float))
        return r + b

    # the span's start from a provisional grid (it hardly depends on the grid), then the
    # components on the grid of the span itself
    f0, a0, _ = random_phase_components(duration, hm0, peak_period, gamma, seed, band)
    start = analysis_start(f0, a0, depth=depth, x_min=float(x.min()), x_wavemaker=x_wavemaker,
                           x_beach=beach.x, ramp_time=ramp_time, returning=returning,
                           developed=sea.developed, g=g)
    repeat = float(duration - start)
    if repeat < 50 * peak_period:
        raise ValueError(f"duration {duration} s leaves {repeat:.0f} s after the sea has "
                         f"developed ({start:.0f} s): fewer than 50 peak periods")
    freq, amp, psi = random_phase_components(repeat, hm0, peak_period, gamma, seed, band)

    n_rep = int(round(repeat * rate))
    if abs(n_rep - repeat * rate) > 1e-6 or abs(round(start * rate) - start * rate) > 1e-6:
        raise ValueError(f"the rate {rate} Hz must hold whole samples in {repeat} s")
    emit = float(duration) + sea.lead_out  # the wavemaker ramps down from here
    f_cut = sea.cut[1] * band[1]
    path_max = 2 * beach.x - x_wavemaker - float(x.min())
    span = emit + ramp_time + path_max / float(group_velocity(1.0 / f_cut, depth, g))
    m = sfft.next_fast_len(int(np.ceil(span * rate)), real=True)

    # the wavemaker's signal: one repeat period by inverse FFT, repeated, ramped up and down
    spec = np.zeros(n_rep // 2 + 1, complex)
    spec[np.rint(freq * repeat).astype(int)] = amp * np.exp(1j * psi) * (n_rep / 2.0)
    periodic = np.resize(sfft.irfft(spec, n_rep), m)
    t = np.arange(m) / rate
    signal = periodic * ramp_envelope(t, ramp_time) * ramp_envelope(emit + ramp_time - t,
                                                                    ramp_time)

    # the flume's transfer to every position and wave, below f_cut
    ff = sfft.rfftfreq(m, 1.0 / rate)
    n_cut = int(np.searchsorted(ff, f_cut, side="right"))
    f = ff[1:n_cut]
    k = wavenumber(2 * np.pi * f, depth, g)
    s = np.clip((f / band[1] - sea.cut[0]) / (sea.cut[1] - sea.cut[0]), 0.0, 1.0)
    taper = np.cos(0.5 * np.pi * s) ** 2
    r, b = returning(f)
    d_inc = (x - x_wavemaker)[:, None]
    h = np.stack([np.exp(-1j * k * d_inc),
                  r * np.exp(-1j * k * (-x_wavemaker - x[:, None])),
                  b * np.exp(-1j * k * (-x_wavemaker - x[:, None]))])  # (wave, x, f)
    out = np.zeros((3, x.size, m // 2 + 1), complex)
    out[..., 1:n_cut] = h * (taper * sfft.rfft(signal)[1:n_cut])
    n_out = int(round((duration + sea.lead_out) * rate))
    eta = sfft.irfft(out, m, axis=-1)[..., :n_out]
    time = np.arange(n_out) / rate
    ds = xr.Dataset({name: (("x", "time"), eta[i]) for i, name in
                     enumerate(("eta_incident", "eta_reflected", "eta_beach"))},
                    coords={"x": x, "time": time})
    return IrregularSea(conventions.annotate(ds), freq, amp, psi, reflection, flap, kb,
                        float(start), repeat)


@doc
def sea_state_truth(time, eta_incident, eta_returning, span: tuple[float, float], *,
                    depth: float, f_max: float, reflection: Callable | None = None,
                    rho: float = 1000.0, g: float = G) -> xr.Dataset:
    """Compute the realised sea state of an analysed span at the flap: spectra and parameters.

    Parameters
    ----------
    time : array_like
        Uniform times [s].
    eta_incident, eta_returning : array_like
        The incident wave and everything travelling towards the wavemaker (the flap's
        reflection and the beach's wave) at x = 0 [m], on ``time``.
    span : tuple of float
        [start, end) [s] of the analysed span.
    depth : float
        Water depth [m].
    f_max : float
        Highest frequency kept [Hz] (above it the sea holds no energy).
    reflection : callable, optional
        f -> R_eff(f), the returning wave's complex amplitude over the incident one at x = 0;
        without it the dataset has no ``reflection_*_spectrum``. (To recompute the truth of a
        virtual run over another span: the series at x = 0 are in ``truth/<run>/flap.nc``.)
    %(rho)s
    %(g)s

    Returns
    -------
    xarray.Dataset
        Over ``frequency`` (the span's FFT grid f_n = n / (end - start), 0 < f_n ≤ f_max):
        ``spectrum_incident``, ``spectrum_reflected`` (one-sided variance densities of the
        span's periodogram [m2 s]), ``incident_spectral_amplitude`` and
        ``incident_spectral_phase`` (η_I = Σ a_n cos(2π f_n (t - start) + φ_n)),
        ``reflection_coefficient_spectrum`` |R_eff(f)| and ``reflection_phase_spectrum``.
        Attributes: ``hm0`` = 4 sqrt(m0), ``energy_period`` Te = Tm-1,0 = m-1/m0,
        ``peak_period`` Tp (the periodogram's largest bin), ``mean_period`` Tm01,
        ``zero_crossing_period`` Tm02,
        ``reflection_coefficient`` (bulk, sqrt(m0R/m0I)), ``reflected_hm0``,
        ``energy_flux`` J = ρ g Σ S_I c_g Δf [W m-1], ``energy_band_low``/``_high`` (the
        band holding the central 90 % of the incident variance) [Hz], ``analysis_start``,
        ``analysis_end`` [s].

    Notes
    -----
    The periodogram of the span with a rectangular window: over a span of whole repeat
    periods of the wavemaker's signal each component falls on one bin, so the spectrum holds
    the components' exact amplitudes. Te = m-1/m0, Tm01 = m0/m1 and Tm02 = sqrt(m0/m2) with
    m_j = Σ f^j S Δf (IEC TS 62600-100, 2012); c_g of linear theory in finite depth.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(2000) / 10.0
    >>> eta = 0.05 * np.cos(2 * np.pi * 0.5 * t)
    >>> s = sea_state_truth(t, eta, 0.2 * eta, (0.0, 200.0), depth=0.825,
    ...                     reflection=lambda f: 0.2 + 0 * f, f_max=2.0)
    >>> a = s.attrs
    >>> round(a["hm0"], 4), a["peak_period"], round(a["reflection_coefficient"], 6)
    (0.1414, 2.0, 0.2)
    """
    t = np.asarray(time, dtype=float)
    inside = (t >= span[0] - 1e-9) & (t < span[1] - 1e-9)
    n = int(inside.sum())
    dt = (t[-1] - t[0]) / (t.size - 1)
    ci = sfft.rfft(np.asarray(eta_incident, dtype=float)[inside])
    cr = sfft.rfft(np.asarray(eta_returning, dtype=float)[inside])
    freq = sfft.rfftfreq(n, dt)
    keep = (freq > 0) & (freq <= f_max) & (freq < 0.5 / dt)
    f, ci, cr = freq[keep], ci[keep], cr[keep]
    df = 1.0 / (n * dt)
    a_i, a_r = 2 * np.abs(ci) / n, 2 * np.abs(cr) / n
    s_i, s_r = a_i**2 / (2 * df), a_r**2 / (2 * df)
    m0, m0r = float(s_i.sum() * df), float(s_r.sum() * df)
    cum = np.cumsum(s_i) / s_i.sum()
    cg = group_velocity(1.0 / f, depth, g)
    design = {}
    if reflection is not None:
        r_eff = reflection(f)
        design = {"reflection_coefficient_spectrum": ("frequency", np.abs(r_eff)),
                  "reflection_phase_spectrum": ("frequency", np.angle(r_eff))}
    ds = xr.Dataset(
        {"spectrum_incident": ("frequency", s_i), "spectrum_reflected": ("frequency", s_r),
         "incident_spectral_amplitude": ("frequency", a_i),
         "incident_spectral_phase": ("frequency", np.angle(ci)), **design},
        coords={"frequency": f},
        attrs={"hm0": float(4 * np.sqrt(m0)),
               "energy_period": float((s_i / f).sum() * df / m0),
               "mean_period": float(m0 / ((s_i * f).sum() * df)),
               "zero_crossing_period": float(np.sqrt(m0 / ((s_i * f**2).sum() * df))),
               "peak_period": float(1.0 / f[np.argmax(s_i)]),
               "reflection_coefficient": float(np.sqrt(m0r / m0)),
               "reflected_hm0": float(4 * np.sqrt(m0r)),
               "energy_flux": float(rho * g * (s_i * cg).sum() * df),
               "energy_band_low": float(f[np.searchsorted(cum, 0.05)]),
               "energy_band_high": float(f[np.searchsorted(cum, 0.95)]),
               "analysis_start": float(span[0]), "analysis_end": float(span[1]),
               "frequency_resolution": df, "rho": rho})
    return conventions.annotate(ds)

