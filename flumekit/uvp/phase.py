"""Per-run UVP processing: filter and phase-average every beam's along-beam velocity.

One call per run turns the three raw beam records (thousands of profiles x 360 channels) into a
small dataset over (beam, channel, phase): the phase-averaged along-beam velocity (Eq. (2) in
Brito et al. 2020 applied to each beam), its fluctuation RMS and the 95 % confidence interval,
with channels masked where they are not seen (out of the water, inside the flap). Runs are
independent, so the pipeline runs this once per run in parallel and :mod:`flumekit.uvp.field`
assembles the results.

Only the window needed is processed: the ``n_cycles`` periods from ``start`` plus ``pad``
seconds on each side for the zero-phase filter's edge transients; memory and time per run are
therefore bounded by the averaging window, not the record length.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import xarray as xr

from flumekit import conventions
from flumekit.campaign import UVP
from flumekit.docstrings import doc
from flumekit.qc.fill import fill_gaps
from flumekit.signal import lowpass, phase_average, resample_cycles
from flumekit.uvp.geometry import channel_distances, channel_positions, inside_flap


def _window(time: np.ndarray, t0: float, t1: float, what: str) -> slice:
    if t0 < time[0] - 1e-9 or t1 > time[-1] + 1e-9:
        raise ValueError(f"{what}: the record [{time[0]:g}, {time[-1]:g}] s does not cover the "
                         f"averaging window [{t0:g}, {t1:g}] s (start, n_cycles, pad)")
    i0 = max(int(np.searchsorted(time, t0, side="right")) - 1, 0)
    i1 = min(int(np.searchsorted(time, t1, side="left")) + 1, time.size)
    return slice(i0, i1)


def uniform(time: np.ndarray, values: np.ndarray, axis: int = 0
            ) -> tuple[np.ndarray, np.ndarray]:
    """Values on a uniform time grid with the same first/last time and number of samples.

    Profile times are stored in 100 ns ticks (FORMAT.md §3.1), so a nominal rate such as
    11.6 Hz jitters by up to 100 ns. Jitter below 0.1 % of the step is snapped to the grid;
    larger irregularities are linearly interpolated (vectorised over the other axes).
    """
    time = np.asarray(time, dtype=float)
    grid = np.linspace(time[0], time[-1], time.size)
    step = (time[-1] - time[0]) / (time.size - 1)
    if np.max(np.abs(time - grid)) <= 1e-3 * step:
        return grid, values
    if np.any(np.diff(time) <= 0):
        raise ValueError("profile times are not strictly increasing")
    pos = np.interp(grid, time, np.arange(time.size))
    i0 = np.clip(np.floor(pos).astype(int), 0, time.size - 2)
    frac = pos - i0
    v = np.moveaxis(values, axis, 0)
    shape = (-1,) + (1,) * (v.ndim - 1)
    out = v[i0] * (1 - frac).reshape(shape) + v[i0 + 1] * frac.reshape(shape)
    return grid, np.moveaxis(out, 0, axis)


def default_pad(cutoff: float | None) -> float:
    """Return the seconds filtered on each side of the averaging window [s].

    max(3 s, 6 / cutoff) holds the edge transient of the zero-phase Butterworth low-pass;
    0 without a filter.
    """
    return max(3.0, 6.0 / cutoff) if cutoff else 0.0


def _dilate(keep: np.ndarray, seconds: float, period: float) -> np.ndarray:
    """Shrink the kept phases by ``seconds`` on each side (periodic in phase)."""
    n_phase = keep.shape[-1]
    half = int(np.ceil(seconds / period * n_phase))
    if half <= 0:
        return keep
    from scipy.ndimage import minimum_filter1d  # imported where used: keeps `import` light

    return minimum_filter1d(keep.astype(np.uint8), 2 * half + 1, axis=-1, mode="wrap") > 0


@doc
def phase_average_beams(beams: Mapping[str, xr.Dataset], uvp: UVP, uvp_elevation: float, *,
                        period: float, start: float, n_cycles: int = 50, n_phase: int = 100,
                        cutoff: float | None = 2.0, order: int = 4, pad: float | None = None,
                        min_amplitude: float | None = None, theta: xr.DataArray | None = None,
                        flap_thickness: float | None = None, x_max: float | None = None,
                        margin: float = 0.01, mask_seconds: float | None = None,
                        interpolation: str = "cubic") -> xr.Dataset:
    """Filter and phase-average the along-beam velocities of one UVP run.

    Parameters
    ----------
    beams : Mapping[str, xarray.Dataset]
        ``{beam name: dataset}`` as :func:`flumekit.io.mfprof.read_mfprof` returns (dims
        time, channel; ``beam_velocity`` with its ``positive`` attribute; optional
        ``amplitude``). Every beam named in ``uvp`` must be present.
    uvp : UVP
        Campaign UVP settings: beam mountings and angles.
    uvp_elevation : float
        The run's UVP elevation above the hinge [m].
    period : float
        Wave period used for phase averaging [s] (the measured period of the
        quasi-steady window).
    start : float
        Time of the zero up-crossing of the incident wave at x = 0 that starts the average
        [s], on the UVP records' clock (Brito et al. 2020, §2.5-2.6).
    n_cycles : int
        Number N of waves averaged (Eq. (2); N = 50 in the paper).
    n_phase : int
        Phases per period.
    cutoff : float, optional
        Low-pass cut-off [Hz] of the 4th-order zero-phase Butterworth filter (2 Hz in
        §2.3); ``None`` for no filter.
    order : int
        Filter order.
    pad : float, optional
        Seconds of record filtered on each side of the averaging window (edge transients of
        the zero-phase filter); default max(3 s, 6 / cutoff).
    min_amplitude : float, optional
        Echo amplitude [counts] below which a sample is "no echo" (out of the
        water); a channel is masked at the phases where any averaged cycle had no echo.
        ``None``: no amplitude test.
    theta : xarray.DataArray, optional
        Flap angle [rad] as a DataArray over ``time`` (same clock). Its phase average masks
        channels inside the flap (within ``margin``) at each phase. Needs ``flap_thickness``.
    flap_thickness : float, optional
        Flap thickness [m]. Without ``theta`` the flap is masked at θ = 0.
    x_max : float, optional
        Static limit: channels with x > x_max [m] are masked at every phase.
    margin : float
        Distance from the flap face within which channels are masked [m] (the sampling
        volume is about 2 cm wide near the flap, §2.3).
    mask_seconds : float, optional
        Masks are widened by this many seconds on each side in phase, because the
        filter spreads what the instrument saw there; default 0.5/cutoff.
    interpolation : str
        Between samples, ``"cubic"`` (default) or ``"linear"``
        (:func:`flumekit.signal.resample_cycles`; linear biases the phase average low by about
        (ω dt)²/12 of each harmonic).

    Returns
    -------
    xarray.Dataset
        Dataset over (beam, channel, phase): ``beam_velocity`` (phase average, positive away from
        the transducer), ``beam_velocity_std`` (fluctuation RMS about it, over the cycles),
        ``beam_velocity_ci`` (95 % CI half-width) [m s-1], NaN where masked; coordinates ``x``,
        ``z``, ``distance`` (beam, channel) [m], ``beam_angle`` [rad]; scalars ``uvp_elevation``,
        ``wave_period``, ``phase_reference`` [s] and ``n_cycles``.

    References
    ----------
    %(brito2020)s, §2.3 and Eq. (2).

    Examples
    --------
    A horizontal beam (40 channels 1 cm apart, 11.6 profiles/s) 0.30 m above the hinge sees
    the flow u = 0.2 sin(2πt/T) m/s, T = 2 s. Averaged over 10 waves from the up-crossing at
    t = 4 s, the velocity is 0.2 m/s at phase 1/4 and -0.2 m/s at phase 3/4; with the upright
    0.17 m flap, the channels beyond x = -0.095 m (1 cm in front of its face) are masked.

    >>> import numpy as np
    >>> import xarray as xr
    >>> from flumekit.campaign import UVP, Beam
    >>> from flumekit.uvp import phase_average_beams
    >>> uvp = UVP(2e6, 11.6, 40, 0.02, 0.01, 0.01, 1480.0, (Beam("UP2", -0.37, 0.0, 0.0),))
    >>> t = np.arange(0.0, 30.0, 1 / 11.6)  # profile times [s]
    >>> v = np.outer(0.2 * np.sin(2 * np.pi * t / 2.0), np.ones(40))  # (time, channel)
    >>> up2 = xr.Dataset({"beam_velocity": (("time", "channel"), v,
    ...                                     {"positive": "away_from_transducer"})},
    ...                  coords={"time": t})
    >>> pa = phase_average_beams({"UP2": up2}, uvp, 0.30, period=2.0, start=4.0,
    ...                          n_cycles=10, flap_thickness=0.17).sel(beam="UP2")
    >>> pa.beam_velocity.sel(channel=0, phase=[0.25, 0.75]).round(3).values.tolist()
    [0.2, -0.2]
    >>> seen = pa.beam_velocity.notnull().all("phase")
    >>> int(seen.sum()), round(float(pa.x.where(seen).max()), 3)  # channels, last x [m]
    (26, -0.1)
    """
    if period <= 0 or n_cycles < 2:
        raise ValueError("phase averaging needs period > 0 and at least two cycles")
    if theta is not None and flap_thickness is None:
        raise ValueError("theta given without flap_thickness")
    missing = [b.name for b in uvp.beams if b.name not in beams]
    if missing:
        raise ValueError(f"beam record(s) missing: {missing} (have {sorted(beams)})")
    if pad is None:
        pad = default_pad(cutoff)
    if mask_seconds is None:
        mask_seconds = 0.5 / cutoff if cutoff else 0.0
    t_end = start + n_cycles * period
    phase = np.arange(n_phase) / n_phase

    theta_p = None
    if theta is not None:
        tt = np.asarray(theta["time"], dtype=float)
        sl = _window(tt, start, t_end, "theta")
        tg, th = uniform(tt[sl], np.asarray(theta, dtype=float)[sl])
        theta_p = phase_average(th, tg, period, start, n_cycles, n_phase).mean

    n_ch = {beams[b.name].sizes["channel"] for b in uvp.beams}
    if len(n_ch) != 1:
        raise ValueError(f"beams have different numbers of channels: {sorted(n_ch)}")
    mean, std, ci, xs, zs, rs = [], [], [], [], [], []
    for b in uvp.beams:  # a handful of beams; each is processed as one (channel, time) block
        ds = beams[b.name]
        what = f"beam {b.name}"
        sign = {"away_from_transducer": 1.0, "towards_transducer": -1.0}.get(
            ds["beam_velocity"].attrs.get("positive"))
        if sign is None:
            raise ValueError(f"{what}: beam_velocity needs a 'positive' attribute "
                             "('away_from_transducer' or 'towards_transducer')")
        time = np.asarray(ds["time"], dtype=float)
        sl = _window(time, start - pad, t_end + pad, what)
        t, v = uniform(time[sl], np.asarray(ds["beam_velocity"].values[sl], dtype=float))
        v = sign * v.T  # (channel, time), a copy: filter and averaging run along the last axis
        fs = (t.size - 1) / (t[-1] - t[0])
        keep = np.ones((v.shape[0], n_phase), dtype=bool)
        # samples masked by quality control (NaN) and, with min_amplitude, samples without echo
        echo = np.isfinite(v)  # (channel, time)
        if min_amplitude is not None and "amplitude" in ds:
            _, amp = uniform(time[sl], np.asarray(ds["amplitude"].values[sl], dtype=float))
            echo &= amp.T >= min_amplitude
        lost = np.flatnonzero(~echo.all(axis=-1))  # treat only the channels with gaps
        if lost.size:
            v[lost] = fill_gaps(v[lost], echo[lost])
            seen = resample_cycles(echo[lost].astype(float), t, period, start, n_cycles,
                                   n_phase)
            keep[lost] &= seen.min(axis=-2) >= 1.0
        if cutoff:
            v = lowpass(v, fs, cutoff, order=order, axis=-1)
        pa = phase_average(v, t, period, start, n_cycles, n_phase, kind=interpolation)
        r = np.asarray(ds["distance"], dtype=float) if "distance" in ds.coords else \
            channel_distances(uvp)
        x, z = channel_positions(r, b.x, uvp_elevation + b.dz, b.angle)
        if theta_p is not None:
            keep &= ~inside_flap(x[:, None], z[:, None], theta_p[None, :], flap_thickness,
                                 margin)
        elif flap_thickness is not None:
            keep &= ~inside_flap(x[:, None], z[:, None], 0.0, flap_thickness, margin)
        if x_max is not None:
            keep &= (x <= x_max)[:, None]
        keep = _dilate(keep, mask_seconds, period)
        mean.append(np.where(keep, pa.mean, np.nan))
        std.append(np.where(keep, pa.std, np.nan))
        ci.append(np.where(keep, pa.ci95, np.nan))
        xs.append(x)
        zs.append(z)
        rs.append(r)
    dims = ("beam", "channel", "phase")
    out = xr.Dataset(
        {"beam_velocity": (dims, np.stack(mean), {"positive": "away_from_transducer"}),
         "beam_velocity_std": (dims, np.stack(std)),
         "beam_velocity_ci": (dims, np.stack(ci))},
        coords={"beam": [b.name for b in uvp.beams], "channel": np.arange(n_ch.pop()),
                "phase": phase, "x": (("beam", "channel"), np.stack(xs)),
                "z": (("beam", "channel"), np.stack(zs)),
                "distance": (("beam", "channel"), np.stack(rs)),
                "beam_angle": ("beam", [b.angle for b in uvp.beams]),
                "beam_x": ("beam", [b.x for b in uvp.beams]),
                "beam_dz": ("beam", [b.dz for b in uvp.beams]),
                "uvp_elevation": float(uvp_elevation), "wave_period": float(period),
                "phase_reference": float(start), "n_cycles": int(n_cycles)},
        attrs={"cutoff_hz": float(cutoff) if cutoff else 0.0, "filter_order": int(order),
               "pad_s": float(pad), "mask_seconds": float(mask_seconds),
               "min_amplitude": -1.0 if min_amplitude is None else float(min_amplitude),
               "flap_mask": "theta" if theta is not None else (
                   "static" if flap_thickness is not None or x_max is not None else "none")})
    return conventions.annotate(out)
