"""The virtual flume's UVP: along-beam velocities of a known wave field, and the true field.

Kinematics (potential flow) of the incident and reflected regular waves of
:func:`flumekit.synth.waves.regular_wave_field`, with the same wave theory (by default the
stream function, :mod:`flumekit.waves.stream_function`), phase convention and ramp-up, so that
the UVP records and the wave-probe/flap records of a virtual run describe one flow. With
θ_I = ωt - k(x - x_wm), θ_R = ωt - k(x_r - x_wm) - k_R(x_r - x) + φ and z_b = z + hinge_height
the elevation above the bed, and the coefficients V_n, c_E of
:func:`flumekit.synth.waves.wave_harmonics`:

    u = c_E e_I² + Σ V_n e_Iⁿ C_n(z_b) cos nθ_I  -  [c_E,R e_R² + same with V_R,n, θ_R]
    w = -Σ V_n e_Iⁿ S_n(z_b) sin nθ_I  -  [same with V_R,n, θ_R]

with C_n = cosh(nk z_b)/cosh(nkh), S_n = sinh(nk z_b)/cosh(nkh) (Fenton 1988, Eq. 2 in the
fixed frame; second-order Stokes velocities of Dean & Dalrymple 1991, §11.3, with
``theory="stokes2"``). Harmonic n carries the envelope to the power n, as in the elevation; the
mean (return) current c_E < 0 of a closed flume, its square. Harmonics below
:data:`flumekit.synth.waves.HARMONIC_CUTOFF` of the first are left out.

The instrument: each beam's channels (see :mod:`flumekit.uvp.geometry`) sample the velocity
projected on the beam (positive away from the transducer, the label the reader uses by default),
plus white Doppler noise, quantised to the counts of ΔV and wrapped into the raw range (aliasing).
A channel is seen only while the transducer and the whole path to it are under the free surface
and in front of the flap: beyond the free surface the echo is noise with a low amplitude; inside
or behind the flap the channel sees the flap's rigid-body velocity with a high amplitude.

Reference phase of the truth: phase p = t/T is measured from a zero up-crossing t_up of the
steady incident elevation at the flap, η_I(x = 0, t) (every harmonic),
i.e. t = t_up + p T (:func:`incident_upcrossing`). The pipeline phase-averages the measured
velocities from the up-crossings of the (separated) incident wave at x = 0; the two agree.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from flumekit import conventions
from flumekit.campaign import UVP, Campaign
from flumekit.docstrings import doc
from flumekit.io.mfprof import FILETIME_UNIX_EPOCH, velocity_range
from flumekit.synth.waves import RAMP_WAVES
from flumekit.uvp.geometry import beam_geometry, flap_face_x, inside_flap
from flumekit.waves.stream_function import depth_ratios
from flumekit.waves.theory import G, group_velocity

X_WAVEMAKER = -32.7  # [m], Brito et al. 2020, §2.1 (x = 0 at 32.7 m from the wavemaker)


def _harmonics(period: float, height: float, depth: float, theory: str, reflection: float,
               g: float = G, beach=None) -> dict:
    from flumekit.synth.waves import wave_harmonics

    if not (period > 0 and height > 0 and depth > 0):
        raise ValueError("period, height and depth must be positive")
    r_beach = 0.0 if beach is None else beach.reflection * beach.transmission**2
    return wave_harmonics(period, height, depth, reflection, theory, g, beach=r_beach)


def _theory(theory: str | None, second_order: bool) -> str:
    return theory if theory is not None else ("stream" if second_order else "linear")


def _depth_functions(k: float, n: int, depth: float, zb):
    """C_n(z_b), S_n(z_b) of the module notes for n = 1..n, shape (..., n); z_b above the bed."""
    return depth_ratios(k * np.arange(1, n + 1), np.asarray(zb, dtype=float)[..., None], depth)


@doc
def wave_kinematics(x, z, time, *, period: float, height: float, depth: float,
                    hinge_height: float = 0.10, reflection: float = 0.2,
                    reflection_phase: float = 0.0, x_reflector: float = 0.0,
                    x_wavemaker: float = X_WAVEMAKER, ramp_waves: float | None = RAMP_WAVES,
                    second_order: bool = True, theory: str | None = None, beach=None,
                    g: float = G) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Compute the velocity and free surface of incident + reflected regular waves.

    The kinematics of the module notes.

    Parameters
    ----------
    x, z, time : array_like
        Position [m] (z above the hinge) and time since wave generation started [s],
        broadcast together (``eta`` uses x and time only).
    period : float
        Wave period T [s].
    height : float
        Incident wave height H [m].
    depth : float
        Still water depth h [m].
    hinge_height : float, default 0.10
        Hinge above the bed [m] (z = 0 at the hinge).
    reflection : float, default 0.2
        Reflection coefficient Kr [-].
    reflection_phase : float, default 0
        Phase φ of the reflected wave at the reflector [rad].
    x_reflector, x_wavemaker : float
        Reflector (flap) and wavemaker positions [m].
    ramp_waves : float or None
        Ramp length in periods as in :func:`flumekit.synth.waves.regular_wave_field`;
        ``None`` for the steady state (no ramp, no travel).
    second_order : bool, default True
        With ``theory``, the wave theory as in :func:`flumekit.synth.waves.regular_wave_field`
        (default the stream function).
    theory : str, optional
        ``"stream"``, ``"stokes2"`` or ``"linear"``.
    beach : flumekit.synth.waves.Beach, optional
        The wave returning from the beach, as in
        :func:`flumekit.synth.waves.regular_wave_field`; None: none.
    %(g)s

    Returns
    -------
    u, w : numpy.ndarray
        Longitudinal and vertical velocity [m s-1].
    eta : numpy.ndarray
        Free-surface elevation [m].

    Raises
    ------
    ValueError
        If Kr lies outside [0, 1].
    """
    from flumekit.synth.kernels import wave_field

    if not 0 <= reflection <= 1:
        raise ValueError(f"reflection coefficient must lie in [0, 1], got {reflection}")
    h = _harmonics(period, height, depth, _theory(theory, second_order), reflection, g, beach)
    omega = 2 * np.pi / period
    k, k_r, k_b = h["k_incident"], h["k_reflected"], h["k_beach"]
    eta_shape = np.broadcast_shapes(np.shape(time), np.shape(x))
    x, z, t = (np.asarray(a, dtype=float) for a in (x, z, time))
    shape = np.broadcast_shapes(t.shape, x.shape, z.shape)
    nd = len(shape)
    t_ax, x_ax, z_ax = (np.array((1,) * (nd - a.ndim) + a.shape) > 1 for a in (t, x, z))
    at = np.flatnonzero(t_ax)
    ap = np.flatnonzero(x_ax | z_ax)
    # every time with every position when time varies along leading axes only and the
    # positions along the others (a record at fixed points); else point by point
    paired = not (at.size == 0 or ap.size == 0 or at[-1] < ap[0])
    if paired:
        t, x, z = (np.broadcast_to(a, shape).ravel() for a in (t, x, z))
    else:
        pos = tuple(1 if a else n for a, n in zip(t_ax, shape))
        t = t.ravel()
        x, z = (np.broadcast_to(a, pos).ravel() for a in (x, z))
    x_b = x_reflector if beach is None else beach.x
    # per wave: the distance travelled from the wavemaker, and the phase of x in
    # θ = ωt - phase (cos/sin of θ by the angle-addition rule: trigonometric functions of t
    # and of x only)
    waves = [(h["incident"], h["incident_velocity"], k, h["incident_current"],
              x - x_wavemaker, k * (x - x_wavemaker)),
             (h["reflected"], h["reflected_velocity"], k_r, h["reflected_current"],
              2 * x_reflector - x - x_wavemaker,
              k * (x_reflector - x_wavemaker) + k_r * (x_reflector - x) - reflection_phase)]
    if np.any(h["beach"]):  # the beach's wave, towards -x like the reflected one
        waves.append((h["beach"], h["beach_velocity"], k_b, h["beach_current"],
                      2 * x_b - x - x_wavemaker,
                      k * (x_b - x_wavemaker) + k_b * (x_b - x) - beach.phase))
    if ramp_waves is None:
        ramp_time, cg = 0.0, 1.0
    else:
        ramp_time, cg = ramp_waves * period, float(group_velocity(period, depth, g))
    n_h = max(wv[0].size for wv in waves)
    amps, vel = (np.zeros((len(waves), n_h)) for _ in range(2))
    ch, sh = (np.zeros((len(waves), x.size, n_h)) for _ in range(2))
    zb = z + hinge_height
    for m, (a, v, km, _, _, _) in enumerate(waves):
        amps[m, :a.size], vel[m, :v.size] = a, v
        ch[m, :, :a.size], sh[m, :, :a.size] = _depth_functions(km, a.size, depth, zb)
    phase = np.array([wv[5] for wv in waves])
    out = tuple(np.empty((1 if paired else t.size, x.size)) for _ in range(3))
    wave_field(t, np.cos(omega * t), np.sin(omega * t), np.array([wv[4] / cg for wv in waves]),
               np.cos(phase), np.sin(phase), amps, vel,
               np.array([wv[0].size for wv in waves]), ch, sh,
               np.array([wv[3] for wv in waves], dtype=float), ramp_time, paired, *out)
    u, w, eta = (a.reshape(shape) for a in out)
    # η depends on x and t only, not on the elevation above the bed
    eta = eta[tuple(slice(0, 1) if zz and not (xx or tt) else slice(None)
                    for tt, xx, zz in zip(t_ax, x_ax, z_ax))]
    return u, w, eta.reshape(eta_shape)


@doc
def incident_upcrossing(*, period: float, height: float, depth: float,
                        x_wavemaker: float = X_WAVEMAKER, second_order: bool = True,
                        theory: str | None = None, harmonics: bool = True,
                        g: float = G) -> float:
    """Return the time in [0, T) of a zero up-crossing of the steady incident elevation at x = 0.

    Solves Σ a_n cos nθ = 0 with a rising slope for θ = ωt + k x_wm (the up-crossing nearest
    θ = -π/2, the linear one), by Newton steps.

    Parameters
    ----------
    period : float
        Wave period T [s].
    height : float
        Wave height H [m].
    depth : float
        Still water depth [m].
    x_wavemaker : float
        Wavemaker position [m].
    second_order : bool, default True
        With ``theory``, the wave theory (:func:`wave_kinematics`).
    theory : str, optional
        ``"stream"``, ``"stokes2"`` or ``"linear"``.
    harmonics : bool, default True
        False keeps the first harmonic only (its wavenumber is still the theory's).
    %(g)s

    Returns
    -------
    float
        The up-crossing time [s].

    Raises
    ------
    ValueError
        If the wave is so steep that no rising zero crossing lies near the linear one.
    """
    h = _harmonics(period, height, depth, _theory(theory, second_order), 0.0, g)
    omega, k, a = 2 * np.pi / period, h["k_incident"], h["incident"]
    a = a if harmonics else a[:1]
    n = np.arange(1, a.size + 1)
    th = -np.pi / 2
    for _ in range(50):  # Newton on a smooth scalar function: a handful of iterations
        f = a @ np.cos(n * th)
        step = f / -(n * a @ np.sin(n * th))
        th -= step
        if abs(step) < 1e-14:
            break
    if not -(n * a @ np.sin(n * th)) > 0:
        raise ValueError("no rising zero crossing near the linear one (wave too steep)")
    return float(((th - k * x_wavemaker) / omega) % period)


def maximum_speed(*, period: float, height: float, depth: float, reflection: float,
                  second_order: bool = True, theory: str | None = None, beach=None,
                  g: float = G) -> float:
    """Return an upper bound of the flow speed up to the highest crest [m s-1].

    Used to choose the UVP's velocity range. The parameters are those of
    :func:`wave_kinematics`.
    """
    h = _harmonics(period, height, depth, _theory(theory, second_order), reflection, g, beach)
    sides = ("incident", "reflected", "beach")
    zb = depth + sum(np.sum(np.abs(h[side])) for side in sides)
    total = sum(abs(h[f"{side}_current"]) for side in sides)
    for side in sides:
        k = h[f"k_{side}"]
        vel = h[f"{side}_velocity"]
        ch, _ = _depth_functions(k, vel.size, depth, zb)
        total += float(np.sum(np.abs(vel) * ch))
    return float(total)


def campaign_parameters(uvp: UVP) -> dict[str, object]:
    """Return the ``.mfprof`` file parameters of the campaign's UVP settings.

    Key names and units are those of FORMAT.md §4.2.

    ``MaximumDepth`` is not a campaign setting: the writer keeps the data's value or uses the
    smallest depth covering every channel.
    """
    def plain(v: float) -> int | float:
        return int(v) if float(v).is_integer() else float(v)

    return {"Frequency": int(round(uvp.frequency)), "SoundSpeed": plain(uvp.sound_speed),
            "StartChannel": round(uvp.start_channel * 1e3, 9),
            "ChannelDistance": round(uvp.channel_distance * 1e3, 9),
            "ChannelWidth": round(uvp.channel_width * 1e3, 9),
            "SampleTime": int(round(1e3 / uvp.sampling_rate))}


def write_beam(path: str | Path, beam: xr.Dataset, uvp: UVP) -> Path:
    """Write one beam's records as ``.mfprof`` with the campaign's UVP settings.

    The campaign's settings replace the acoustic and channel parameters of ``beam``'s
    ``mfprof_*`` attributes.

    Parameters
    ----------
    path : str or pathlib.Path
        File to write.
    beam : xarray.Dataset
        One beam's records, as :func:`uvp_beams` returns them.
    uvp : flumekit.campaign.UVP
        The campaign's UVP settings.

    Returns
    -------
    pathlib.Path
        The written file.
    """
    from flumekit.io.mfprof import parameters_from_attrs, write_mfprof

    return write_mfprof(path, beam, {**parameters_from_attrs(beam.attrs),
                                     **campaign_parameters(uvp)})


def instrument_parameters(uvp: UVP, *, max_speed: float | None = None,
                          maximum_depth: float | None = None, margin: float = 1.2
                          ) -> dict[str, object]:
    """Return the ``.mfprof`` parameters of the virtual UVP (key names and units of FORMAT.md §4.2).

    The maximum depth d_max [m] sets the velocity range V_range = c² / (4 f0 d_max). By default
    it is chosen so that ±V_range/2 covers ``margin`` x ``max_speed``. With the paper's set-up
    (2 MHz, channels up to 0.29 m) the Nyquist limit at a d_max covering the channels would be
    ±0.48 m/s, below the near-surface speeds of the T = 3.5 s, H = 0.25 m wave; the virtual
    instrument does not model range ambiguity, so a smaller d_max is used.
    """
    if maximum_depth is None:
        if max_speed is None:
            raise ValueError("give max_speed or maximum_depth")
        maximum_depth = uvp.sound_speed**2 / (4 * uvp.frequency * 2 * margin * max_speed)
        maximum_depth = np.floor(maximum_depth * 1e5) / 1e5  # 0.01 mm
    return {**campaign_parameters(uvp), "MaximumDepth": round(float(maximum_depth) * 1e3, 6),
            "Angle": 90, "CyclesPerPulse": 2, "RawDataMin": -128, "RawDataMax": 127,
            "RawDataRange": 256, "Comment": "flumekit virtual flume"}


def _band_limited(rng: np.random.Generator, shape: tuple[int, ...], dt: float,
                  band: tuple[float, float]) -> np.ndarray:
    """Unit-variance Gaussian noise band-limited to ``band`` [Hz] along axis 0."""
    n = shape[0]
    spec = rng.standard_normal((n // 2 + 1, *shape[1:])) + 1j * rng.standard_normal(
        (n // 2 + 1, *shape[1:]))
    f = np.fft.rfftfreq(n, dt)
    spec[(f < band[0]) | (f > band[1])] = 0.0
    x = np.fft.irfft(spec, n=n, axis=0)
    return x / x.std(axis=0, keepdims=True)


def uvp_beams(time, uvp: UVP, uvp_elevation: float, *, period: float, height: float,
              depth: float, hinge_height: float = 0.10, reflection: float = 0.2,
              reflection_phase: float = 0.0, x_wavemaker: float = X_WAVEMAKER,
              ramp_waves: float | None = RAMP_WAVES, second_order: bool = True,
              theory: str | None = None, beach=None, noise: float = 0.005,
              turbulence: tuple[float, float, float] | None = None,
              theta=None, flap_thickness: float = 0.17, maximum_depth: float | None = None,
              rng: np.random.Generator | int | None = None) -> dict[str, xr.Dataset]:
    """Synthesise the virtual UVP records of one run, one dataset per beam.

    Each dataset is as :func:`flumekit.read_mfprof` returns it.

    Parameters
    ----------
    time : array_like
        Profile times since wave generation started [s], 1-D increasing.
    uvp : flumekit.campaign.UVP
        Campaign UVP settings (channels, beams).
    uvp_elevation : float
        Elevation of the run's UVP mounting above the hinge [m].
    period, height, depth, hinge_height, reflection, reflection_phase, x_wavemaker : float
        The wave field, see :func:`wave_kinematics` ([s], [m], [m], [m], [-], [rad], [m]).
    ramp_waves, second_order, theory, beach
        The wave field, see :func:`wave_kinematics`.
    noise : float, default 0.005
        Standard deviation of the white Doppler noise along the beam [m s-1].
    turbulence : tuple of float, optional
        (σ_u [m s-1], σ_w [m s-1], correlation ρ_uw [-]) of Gaussian velocity fluctuations
        band-limited to 0.05-1.5 Hz, independent between channels and beams (a known truth
        for the turbulence statistics).
    theta : array_like, optional
        Flap angle at ``time`` [rad] (positive towards the beach); default 0 (fixed flap).
    flap_thickness : float, default 0.17
        Flap thickness [m] (the seaward face is at x = -thickness/2 for θ = 0).
    maximum_depth : float, optional
        Instrument d_max [m]; default: chosen to cover the flow speed
        (:func:`instrument_parameters`); faster velocities alias.
    rng : numpy.random.Generator or int, optional
        Random generator or seed.

    Returns
    -------
    dict of str to xarray.Dataset
        Per beam name, dims (time, channel): ``beam_velocity`` [m s-1] (quantised,
        ``positive="away_from_transducer"``), ``amplitude`` [counts]; coordinates ``time``,
        ``channel``, ``distance``; ``.mfprof`` parameters as ``mfprof_*`` attributes (ready
        for :func:`flumekit.io.mfprof.write_mfprof`).

    Raises
    ------
    ValueError
        If ``time`` is not 1-D increasing, ``turbulence`` is out of range or ``theta`` is not
        sampled at ``time``.
    """
    from flumekit.synth.kernels import beam_counts, beam_echo

    rng = rng if isinstance(rng, np.random.Generator) else np.random.default_rng(rng)
    time = np.asarray(time, dtype=float)
    if time.ndim != 1 or time.size < 2 or np.any(np.diff(time) <= 0):
        raise ValueError("time must be 1-D and strictly increasing")
    if turbulence is not None and not (turbulence[0] >= 0 and turbulence[1] >= 0
                                       and -1 <= turbulence[2] <= 1):
        raise ValueError(f"turbulence must be (sigma_u >= 0, sigma_w >= 0, |rho| <= 1), "
                         f"got {turbulence}")
    theta = np.zeros_like(time) if theta is None else np.asarray(theta, dtype=float)
    if theta.shape != time.shape:
        raise ValueError(f"theta must be sampled at time: shape {theta.shape} != {time.shape}")
    theta_dot = np.gradient(theta, time)
    # the flap's seaward face x = z tan θ - t / (2 cos θ) (flumekit.uvp.geometry.flap_face_x)
    tan_theta, half_width = np.tan(theta), -flap_face_x(0.0, theta, flap_thickness)
    wave = dict(period=period, height=height, depth=depth, hinge_height=hinge_height,
                reflection=reflection, reflection_phase=reflection_phase,
                x_wavemaker=x_wavemaker, ramp_waves=ramp_waves, second_order=second_order,
                theory=theory, beach=beach)
    params = instrument_parameters(
        uvp, maximum_depth=maximum_depth,
        max_speed=maximum_speed(period=period, height=height, depth=depth,
                                reflection=reflection, second_order=second_order,
                                theory=theory, beach=beach))
    dv = velocity_range(params["SoundSpeed"], params["Frequency"],
                        params["MaximumDepth"] * 1e-3) / params["RawDataRange"]
    lo, n_counts = params["RawDataMin"], params["RawDataRange"]
    geo = beam_geometry(uvp, uvp_elevation)
    t = time[:, None]
    dt = float(np.median(np.diff(time)))
    # the wave field at every channel of every beam and at each transducer's face, at once
    geos = [geo.sel(beam=b.name) for b in uvp.beams]
    xs = [g["x"].values for g in geos] + [np.array([b.x for b in uvp.beams])]
    zs = [g["z"].values for g in geos] + [np.array([uvp_elevation + b.dz for b in uvp.beams])]
    u, w, eta = wave_kinematics(np.concatenate(xs)[None, :], np.concatenate(zs)[None, :], t,
                                **wave)
    starts = np.cumsum([0] + [a.size for a in xs])
    out = {}
    for i, (b, g) in enumerate(zip(uvp.beams, geos)):  # the instruments' own draws, in turn
        x, z, zf = xs[i], zs[i], zs[-1][i]
        cols = slice(starts[i], starts[i + 1])
        if turbulence is not None:
            su, sw, rho = turbulence
            n1, n2 = _band_limited(rng, (time.size, x.size, 2), dt, (0.05, 1.5)).transpose(2, 0, 1)
            u[:, cols] += su * n1
            w[:, cols] += sw * (rho * n1 + np.sqrt(1 - rho**2) * n2)
        # the echo path: transducer face and every channel up to this one under the surface,
        # in front of the flap; the draws in the instrument's order: Doppler noise, the counts
        # of the channels without echo, the echo amplitude
        draws = rng.standard_normal((time.size, x.size))
        v, state = np.empty(draws.shape), np.empty(draws.shape, dtype=np.int8)
        beam_echo(u, w, eta, starts[i], starts[-2] + i, x, z, zf, depth - hinge_height,
                  np.cos(b.angle), np.sin(b.angle), tan_theta, half_width, theta_dot, noise,
                  draws, v, state)
        no_echo = rng.integers(lo, lo + n_counts, size=int(np.count_nonzero(state == 2)))
        velocity, amplitude = np.empty(v.shape), np.empty(v.shape, dtype=np.int16)
        beam_counts(v, state, no_echo, rng.standard_normal(v.shape), dv, lo, n_counts,
                    velocity, amplitude)
        ds = xr.Dataset(
            {"beam_velocity": (("time", "channel"), velocity,
                               {"positive": "away_from_transducer",
                                "sign_convention": "virtual flume: velocity projected on the "
                                "unit vector from the transducer into the beam"}),
             "amplitude": (("time", "channel"), amplitude)},
            coords={"time": time, "channel": g["channel"].values,
                    "distance": ("channel", g["distance"].values)},
            attrs={**{f"mfprof_{k}": v for k, v in params.items()},
                   "mfprof_start_time_filetime": FILETIME_UNIX_EPOCH + 1_577_836_800 * 10**7,
                   "velocity_resolution": dv, "beam": b.name,
                   "uvp_elevation": float(uvp_elevation)})
        out[b.name] = conventions.annotate(ds)
    return out


def true_field(campaign: Campaign, *, period: float, height: float, reflection: float = 0.2,
               reflection_phase: float = 0.0, x_wavemaker: float = X_WAVEMAKER,
               second_order: bool = True, theory: str | None = None, beach=None,
               x=None, z=None, n_phase: int = 100,
               theta=None, elevations=None, reference: str = "incident") -> xr.Dataset:
    """Compute the true phase-averaged velocity field on the (phase, z, x) grid.

    The grid is that of the processed UVP field; the steady phase average equals the
    instantaneous steady field at each phase.

    Parameters
    ----------
    campaign : flumekit.campaign.Campaign
        Water depth, hinge height, flap thickness and UVP beams.
    period : float
        Wave period T [s].
    height : float
        Incident wave height H [m].
    reflection : float, default 0.2
        Reflection coefficient Kr of the flap [-].
    reflection_phase : float, default 0
        Phase of the reflected wave at the flap [rad].
    x_wavemaker : float
        Wavemaker position [m].
    second_order, theory, beach
        The wave theory and the beach's wave (:func:`wave_kinematics`).
    x, z : array_like, optional
        Grid [m]; default :func:`flumekit.uvp.field.default_grid` of the campaign's beams and
        ``elevations``.
    n_phase : int, default 100
        Number of phases t/T = 0, 1/n_phase, ...
    theta : array_like, optional
        Phase-averaged flap angle over the phase grid [rad]: points inside the flap at a
        phase are masked.
    elevations : array_like, optional
        UVP elevations above the hinge [m] of the default grid; default 0.20, 0.22, ...,
        0.72 m (Brito et al. 2020, §2.3).
    reference : str, default "incident"
        Phase 0 at the zero up-crossing of the steady incident elevation at x = 0,
        ``"incident"`` (every harmonic, as a zero-crossing analysis of the separated
        incident wave sees it) or ``"first_harmonic"`` (of its first harmonic only). With
        H = 0.25 m, T = 3.5 s the second harmonic is 0.39 of the first and the two references
        differ by about 0.05 T: the pipeline and the truth must use the same one.

    Returns
    -------
    xarray.Dataset
        Over (phase, z, x): ``u``, ``w`` [m s-1] (NaN above the free surface and inside the
        flap), ``u_normalised``, ``w_normalised`` (by U0 = πH/T) [-], ``inside_flap``,
        ``eta`` (phase, x) [m]; scalar coordinates ``velocity_scale`` [m s-1] and
        ``phase_reference`` [s] (:func:`incident_upcrossing`).

    Raises
    ------
    ValueError
        If the grid is not given and the campaign has no UVP, ``reference`` is unknown or
        ``theta`` is not given on the phases.

    References
    ----------
    Fenton, J. D. (1988). The numerical solution of steady water wave problems. Computers &
    Geosciences 14(3), 357-368.
    Brito, M. et al. (2020). Experimental investigation on the power capture of an oscillating
    wave surge converter in unidirectional waves. Energies 13, 5417 (§2.3-2.4).

    Examples
    --------
    >>> from flumekit.synth import virtual_campaign
    >>> c = virtual_campaign("raw/small", "small", 2020)
    >>> f = true_field(c, period=3.5, height=0.25, x=[-1.0, -0.5], z=[0.3], n_phase=4)
    >>> dict(f.sizes), round(float(f.velocity_scale), 4)
    ({'phase': 4, 'z': 1, 'x': 2}, 0.2244)
    """
    from flumekit.uvp.field import default_grid

    depth, hinge = campaign.flume.water_depth, campaign.flap.hinge_height
    if x is None or z is None:
        if campaign.uvp is None:
            raise ValueError("the campaign has no UVP: give the grid x, z")
        elev = np.round(np.arange(0.20, 0.7201, 0.02), 3) if elevations is None else elevations
        gx, gz = default_grid(campaign.uvp, elev)
        x = gx if x is None else x
        z = gz if z is None else z
    x, z = np.asarray(x, dtype=float), np.asarray(z, dtype=float)
    phase = np.arange(n_phase) / n_phase
    if reference not in ("incident", "first_harmonic"):
        raise ValueError(f"reference must be 'incident' or 'first_harmonic', got {reference!r}")
    t_up = incident_upcrossing(period=period, height=height, depth=depth,
                               x_wavemaker=x_wavemaker, second_order=second_order,
                               theory=theory, harmonics=reference == "incident")
    t = (t_up + phase * period)[:, None, None]
    u, w, eta = wave_kinematics(x[None, None, :], z[None, :, None], t, period=period,
                                height=height, depth=depth, hinge_height=hinge,
                                reflection=reflection, reflection_phase=reflection_phase,
                                x_wavemaker=x_wavemaker, ramp_waves=None,
                                second_order=second_order, theory=theory, beach=beach)
    eta = np.broadcast_to(eta, (n_phase, 1, x.size))[:, 0, :]
    hidden = z[None, :, None] > (eta[:, None, :] + depth - hinge)
    if theta is not None:
        theta = np.asarray(theta, dtype=float)
        if theta.shape != phase.shape:
            raise ValueError(f"theta must be given on the {n_phase} phases")
        flap = inside_flap(x[None, None, :], z[None, :, None], theta[:, None, None],
                           campaign.flap.thickness)
    else:
        flap = np.zeros(hidden.shape, dtype=bool)
    mask = hidden | flap
    u, w = np.where(mask, np.nan, u), np.where(mask, np.nan, w)
    u0 = np.pi * height / period
    ds = xr.Dataset(
        {"u": (("phase", "z", "x"), u), "w": (("phase", "z", "x"), w),
         "u_normalised": (("phase", "z", "x"), u / u0),
         "w_normalised": (("phase", "z", "x"), w / u0),
         "eta": (("phase", "x"), eta + 0.0),
         "inside_flap": (("phase", "z", "x"), flap.astype(np.int8))},
        coords={"phase": phase, "z": z, "x": x, "velocity_scale": u0,
                "phase_reference": t_up, "wave_period": period, "wave_height": height},
        attrs={"water_depth": depth, "reflection_coefficient": reflection,
               "beach_reflection_coefficient": 0.0 if beach is None else beach.reflection,
               "beach_transmission": 1.0 if beach is None else beach.transmission,
               "reflection_phase": reflection_phase, "second_order": int(second_order),
               "wave_theory": _theory(theory, second_order),
               "phase_reference_definition": "t/T = 0 at a zero up-crossing of the steady "
               + ("incident elevation" if reference == "incident" else
                  "first harmonic of the incident elevation") + " at x = 0"})
    return conventions.annotate(ds)


def write_uvp_run(directory: str | Path, beams: dict[str, xr.Dataset]) -> list[Path]:
    """Write one ``<beam>.mfprof`` per beam into ``directory`` (raw/README.md layout).

    Parameters
    ----------
    directory : str or pathlib.Path
        The run's folder.
    beams : dict of str to xarray.Dataset
        Records per beam name, as :func:`uvp_beams` returns them.

    Returns
    -------
    list of pathlib.Path
        The written files.
    """
    from flumekit.io.mfprof import write_mfprof

    directory = Path(directory)
    return [write_mfprof(directory / f"{name}.mfprof", ds) for name, ds in beams.items()]
