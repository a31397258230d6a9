"""The phase-averaged velocity field over (phase, z, x) from the per-run beam averages.

Brito et al. (2020, §2.3) repeat the test 78 times with the UVP mounting at elevations 0.20 to
0.72 m (steps of 2 cm), so each elevation has two or three repeats. :func:`combine_repeats`
averages the repeats of each elevation (streaming: one run in memory at a time);
:func:`velocity_field` maps every beam onto common (x, z) points and decomposes:

* ``method="least_squares"`` (default): a beam's family of parallel lines (one per elevation) is
  a sheared grid in (elevation, distance); each beam's phase average is interpolated bilinearly
  on it at the grid points, and (u, w) solve the beams' equations by least squares
  (:func:`flumekit.uvp.decomposition.least_squares_velocity`).
* ``method="paired"``: Eqs. (9)-(10) of the paper on the inclined beam pair of each elevation at
  the same channel, placed at the pair's mid-point (x_b + r cos α, elevation), then interpolated
  to the grid along x.

On the virtual flume (bench ``flumekit.bench.uvp``) the least-squares field is the more accurate
one, because Eqs. (9)-(10) assume the flow uniform over the 2 r sin α (up to 0.29 m) between the
two channels they combine; hence the default.
Velocities are normalised by U0 = πH/T, the deep-water maximum orbital velocity (§4).
"""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np
import xarray as xr

from flumekit import conventions
from flumekit.campaign import UVP
from flumekit.docstrings import filler
from flumekit.uvp.decomposition import combine_ci, least_squares_velocity, paired_velocity
from flumekit.uvp.geometry import inside_flap
from flumekit.uvp.turbulence import reynolds_stresses, turbulent_kinetic_energy

_STATS = ("beam_velocity", "beam_velocity_std", "beam_velocity_ci")

#: docstring text that several functions of this module share
_doc = filler(
    # three beams of one mounting see a uniform flow; its records phase-averaged per run
    example_runs=(
        "The beams at -30°, 0 and +30° of Brito et al. (2020), 20 channels 1 cm apart, see the\n"
        "uniform flow u = 0.2 sin ωt, w = 0.1 cos ωt m/s (T = 2 s); each beam measures\n"
        "u cos a + w sin a. Runs at the elevations 0.20, 0.25 and 0.30 m (the last twice) are\n"
        "phase-averaged:\n"
        "\n"
        ">>> import numpy as np\n"
        ">>> import xarray as xr\n"
        ">>> from flumekit.campaign import UVP, Beam\n"
        ">>> from flumekit.uvp import phase_average_beams\n"
        ">>> beams = tuple(Beam(name, -0.37, 0.0, np.radians(deg))\n"
        "...               for name, deg in ((\"UP1\", -30), (\"UP2\", 0), (\"UP3\", 30)))\n"
        ">>> uvp = UVP(2e6, 11.6, 20, 0.02, 0.01, 0.01, 1480.0, beams)\n"
        ">>> t = np.arange(0.0, 30.0, 1 / 11.6)  # profile times [s]\n"
        ">>> u, w = 0.2 * np.sin(np.pi * t), 0.1 * np.cos(np.pi * t)  # ω = π rad/s\n"
        ">>> records = {\n"
        "...     b.name: xr.Dataset(\n"
        "...         {\"beam_velocity\": ((\"time\", \"channel\"),\n"
        "...                            np.outer(u * np.cos(b.angle) + w * np.sin(b.angle),\n"
        "...                                     np.ones(20)),\n"
        "...                            {\"positive\": \"away_from_transducer\"})},\n"
        "...         coords={\"time\": t})\n"
        "...     for b in beams}\n"
        ">>> runs = [phase_average_beams(records, uvp, e, period=2.0, start=4.0, n_cycles=10)\n"
        "...         for e in (0.20, 0.25, 0.30, 0.30)]"))


def default_grid(uvp: UVP, elevations, dx: float = 0.01) -> tuple[np.ndarray, np.ndarray]:
    """Grid (x, z) [m] covered by the beams.

    z at the elevations of the horizontal beam, x on multiples of ``dx`` between the nearest
    and the farthest channel of any beam.

    Parameters
    ----------
    uvp : UVP
        Campaign UVP settings (beams and channels).
    elevations : array_like
        UVP elevations of the runs [m].
    dx : float
        Grid spacing in x [m].

    Returns
    -------
    x, z : numpy.ndarray
        Grid coordinates [m].

    Examples
    --------
    The campaign's beams (faces at x = -0.37 m, channels 0.02 to 0.28566 m along the beam)
    cover x from -0.37 + 0.02 cos 30° = -0.3527 m to -0.37 + 0.28566 = -0.0843 m: on 1 cm
    multiples, -0.35 to -0.09 m. z holds each elevation once.

    >>> import numpy as np
    >>> from flumekit.campaign import UVP, Beam
    >>> from flumekit.uvp import default_grid
    >>> beams = (Beam("UP1", -0.37, 0.0, -np.pi / 6), Beam("UP2", -0.37, 0.0, 0.0),
    ...          Beam("UP3", -0.37, 0.0, np.pi / 6))
    >>> x, z = default_grid(UVP(2e6, 11.6, 360, 0.02, 0.00074, 0.00074, 1480.0, beams),
    ...                     elevations=[0.22, 0.20, 0.22])
    >>> x.size, x[[0, -1]].tolist(), z.tolist()
    (27, [-0.35, -0.09], [0.2, 0.22])
    """
    if dx <= 0:
        raise ValueError("dx must be positive")
    e = np.unique(np.round(np.asarray(elevations, dtype=float), 9))
    r0 = uvp.start_channel
    r1 = uvp.start_channel + (uvp.n_channels - 1) * uvp.channel_distance
    x0 = min(b.x + r0 * np.cos(b.angle) for b in uvp.beams)
    x1 = max(b.x + r1 * np.cos(b.angle) for b in uvp.beams)
    x = np.arange(np.ceil(x0 / dx - 1e-9), np.floor(x1 / dx + 1e-9) + 1) * dx
    ref = min(uvp.beams, key=lambda b: abs(b.angle))
    return np.round(x, 12), np.round(e + ref.dz, 12)


@_doc
def combine_repeats(runs: Iterable[xr.Dataset]) -> xr.Dataset:
    """Average the per-run beam phase averages of repeats at the same UVP elevation.

    Parameters
    ----------
    runs : Iterable[xarray.Dataset]
        Datasets of :func:`flumekit.uvp.phase.phase_average_beams` (any order; an iterator
        of lazily opened files keeps one run in memory at a time).

    Returns
    -------
    xarray.Dataset
        Dataset over (uvp_elevation, beam, channel, phase): ``beam_velocity`` (mean of the repeat
        means), ``beam_velocity_std`` (pooled within-run fluctuation RMS), ``beam_velocity_ci``
        (CI of the mean of independent repeats, sqrt(Σ ci²)/n), ``n_repeats`` (per elevation).
        NaN (masked) values are left out of each mean.

    Examples
    --------
    %(example_runs)s

    The two runs at 0.30 m become one elevation, and the CI of the mean of two repeats
    is 1/√2 that of one:

    >>> from flumekit.uvp import combine_repeats
    >>> c = combine_repeats(runs)
    >>> c["n_repeats"].values.tolist(), dict(c["beam_velocity"].sizes)
    ([1, 1, 2], {'uvp_elevation': 3, 'beam': 3, 'channel': 20, 'phase': 100})
    >>> ratio = c["beam_velocity_ci"].sel(uvp_elevation=0.30) / runs[-1]["beam_velocity_ci"]
    >>> round(float(ratio.median()), 4)  # 1/√2
    0.7071
    """
    acc: dict[float, list] = {}
    ref = None
    for ds in runs:  # one run at a time: memory is bounded by one run plus the accumulators
        if ref is None:
            ref = ds
        else:
            for c in ("beam", "channel", "phase"):
                if not np.array_equal(ds[c].values, ref[c].values):
                    raise ValueError(f"run at elevation {float(ds['uvp_elevation'])} m has other "
                                     f"'{c}' values than the first run")
            if not np.allclose(ds["distance"].values, ref["distance"].values, atol=1e-9):
                raise ValueError(f"run at elevation {float(ds['uvp_elevation'])} m has other "
                                 "channel distances than the first run")
        key = round(float(ds["uvp_elevation"]), 6)
        m = ds["beam_velocity"].values
        ok = np.isfinite(m)
        terms = (np.where(ok, m, 0.0), ok.astype(np.int32),
                 np.where(ok, ds["beam_velocity_std"].values ** 2, 0.0),
                 np.where(ok, ds["beam_velocity_ci"].values ** 2, 0.0))
        if key in acc:
            for a, t in zip(acc[key][:4], terms):
                a += t
            acc[key][4] += 1
        else:
            acc[key] = [*terms, 1]
    if ref is None:
        raise ValueError("no run to combine")
    keys = sorted(acc)
    with np.errstate(invalid="ignore", divide="ignore"):
        n = np.stack([acc[k][1] for k in keys]).astype(float)
        n = np.where(n > 0, n, np.nan)
        mean = np.stack([acc[k][0] for k in keys]) / n
        std = np.sqrt(np.stack([acc[k][2] for k in keys]) / n)
        ci = np.sqrt(np.stack([acc[k][3] for k in keys])) / n
    dims = ("uvp_elevation", "beam", "channel", "phase")
    coords = {c: ref[c] for c in ("beam", "channel", "phase", "distance", "beam_angle",
                                  "beam_x", "beam_dz")}
    out = xr.Dataset(
        {"beam_velocity": (dims, mean, {"positive": "away_from_transducer"}),
         "beam_velocity_std": (dims, std), "beam_velocity_ci": (dims, ci),
         "n_repeats": ("uvp_elevation", [acc[k][4] for k in keys])},
        coords={"uvp_elevation": np.array(keys), **coords,
                "wave_period": ref["wave_period"], "n_cycles": ref["n_cycles"]},
        attrs=dict(ref.attrs))
    return conventions.annotate(out)


def _interp_index(grid: np.ndarray, q: np.ndarray, tol: float = 1e-9):
    """Lower index, fraction and validity of linear interpolation of sorted ``grid`` at ``q``."""
    if grid.size == 1:
        return np.zeros(q.shape, int), np.zeros(q.shape), np.abs(q - grid[0]) <= tol
    i = np.clip(np.searchsorted(grid, q, side="right") - 1, 0, grid.size - 2)
    f = (q - grid[i]) / (grid[i + 1] - grid[i])
    valid = (q >= grid[0] - tol) & (q <= grid[-1] + tol)
    return i, np.clip(f, 0.0, 1.0), valid


def beam_to_grid(values, elevations, distance, beam_x: float, beam_dz: float, angle: float,
                 x, z) -> np.ndarray:
    """Bilinear interpolation of one beam's data from its lines onto (z, x) points.

    Parameters
    ----------
    values : array_like
        Beam data over (elevation, channel, ...) (e.g. phase last).
    elevations : array_like
        UVP elevation of each line [m], increasing.
    distance : array_like
        Channel distances from the transducer [m], increasing.
    beam_x, beam_dz, angle : float
        Transducer face x [m], its offset from the elevation [m] and the
        beam angle [rad].
    x, z : array_like
        Target grid [m], 1-D.

    Returns
    -------
    numpy.ndarray
        Array over (z, x, ...), NaN outside the lines' coverage or next to a NaN sample.

    Notes
    -----
    A point (x, z) lies at distance r = (x - x_b)/cos a on the line of elevation
    e = z - dz - (x - x_b) tan a; interpolation is linear in e between the two nearest lines and
    in r between the two nearest channels.

    Examples
    --------
    The upward beam (+30°) at three elevations, 20 channels 1 cm apart from 2 cm off the
    face; as data, the height of each channel, z = e + r sin 30°. Bilinear interpolation of
    this linear field gives back the grid's z wherever the lines reach (x = -0.1 m lies
    beyond the last channel, 0.21 m along the beam):

    >>> import numpy as np
    >>> from flumekit.uvp import beam_to_grid
    >>> e, r, a = np.array([0.20, 0.25, 0.30]), 0.02 + 0.01 * np.arange(20), np.pi / 6
    >>> height = e[:, None] + r * np.sin(a)  # (elevation, channel) [m]
    >>> beam_to_grid(height, e, r, -0.37, 0.0, a, x=[-0.3, -0.25, -0.1], z=[0.3]).round(12)
    array([[0.3, 0.3, nan]])
    """
    values = np.asarray(values, dtype=float)
    e = np.asarray(elevations, dtype=float)
    r = np.asarray(distance, dtype=float)
    X, Z = np.meshgrid(np.asarray(x, dtype=float), np.asarray(z, dtype=float))
    rq = (X - beam_x) / np.cos(angle)
    eq = Z - beam_dz - (X - beam_x) * np.tan(angle)
    ie, fe, ve = _interp_index(e, eq)
    ic, fc, vc = _interp_index(r, rq)
    ie1 = np.minimum(ie + 1, e.size - 1)
    ic1 = np.minimum(ic + 1, r.size - 1)
    tail = (slice(None),) * 2 + (None,) * (values.ndim - 2)
    out = 0.0
    for ii, wi in ((ie, 1 - fe), (ie1, fe)):  # the four corners of the bilinear cell
        for jj, wj in ((ic, 1 - fc), (ic1, fc)):
            wt = (wi * wj)[tail]
            out = out + np.where(wt > 0, wt * values[ii, jj], 0.0)
    return np.where((ve & vc)[tail], out, np.nan)


def _pair(uvp: UVP):
    """Find the inclined pair (lower, upper) at ∓α with the same mounting, for Eqs. (9)-(10)."""
    for lo in uvp.beams:
        for up in uvp.beams:
            if (lo.angle < 0 < up.angle and np.isclose(lo.angle, -up.angle)
                    and np.isclose(lo.x, up.x) and np.isclose(lo.dz, up.dz)):
                return lo, up
    raise ValueError("Eqs. (9)-(10) need two beams at -alpha and +alpha with the same mounting")


def _to_beams(ds: xr.Dataset) -> dict:
    return {"x": ds["beam_x"].values, "dz": ds["beam_dz"].values, "angle": ds["beam_angle"].values,
            "names": list(ds["beam"].values)}


@_doc
def velocity_field(runs: Iterable[xr.Dataset] | xr.Dataset, uvp: UVP, *, height: float,
                   period: float, method: str = "least_squares", x=None, z=None,
                   dx: float = 0.01, water_depth: float | None = None, theta=None,
                   flap_thickness: float | None = None, margin: float = 0.01) -> xr.Dataset:
    """Phase-averaged ⟨u⟩, ⟨w⟩ and turbulence statistics over (phase, z, x).

    Parameters
    ----------
    runs : Iterable[xarray.Dataset] | xarray.Dataset
        Per-run datasets of :func:`flumekit.uvp.phase.phase_average_beams` (an iterable,
        combined by :func:`combine_repeats`), or an already combined dataset.
    uvp : UVP
        Campaign UVP settings (for the default grid).
    height, period : float
        Target wave height H [m] and period T [s], for U0 = πH/T.
    method : str
        ``"least_squares"`` (default) or ``"paired"`` (Eqs. (9)-(10)).
    x, z : array_like
        Grid [m]; default :func:`default_grid` with spacing ``dx`` [m].
    water_depth : float, optional
        Still water depth h [m], stored for x/h, z/h in figures.
    theta : array_like
        Optional phase-averaged flap angle on the phase grid [rad]; with
        ``flap_thickness`` [m], points within ``margin`` [m] of the flap or inside it are masked
        at each phase.

    Returns
    -------
    xarray.Dataset
        Dataset over (phase, z, x): ``u``, ``w`` [m s-1], ``u_ci``, ``w_ci`` (95 % CI half-widths),
        ``u_rms``, ``w_rms`` [m s-1] (from variances clipped at 0), ``uu``, ``ww``, ``uw``,
        ``tke`` [m2 s-2] (unclipped: sampling noise makes single estimates of a small variance
        negative, and clipping would bias averages), ``u_normalised``, ``w_normalised``,
        ``n_beams``; scalar coordinates ``velocity_scale`` (U0), ``wave_period``, ``wave_height``.

    References
    ----------
    %(brito2020)s, §2.3, Eqs. (9)-(10) and §4.

    Examples
    --------
    %(example_runs)s

    The field gives back the uniform flow: u = 0.2 m/s at phase 1/4 and w = 0.1 m/s at phase
    0, wherever the beams see the point (w needs an inclined beam there: 39 of the 60 points):

    >>> from flumekit.uvp import velocity_field
    >>> f = velocity_field(runs, uvp, height=0.1, period=2.0)
    >>> dict(f.sizes), f.attrs["n_runs"]
    ({'phase': 100, 'z': 3, 'x': 20}, 4)
    >>> u_peak, w_peak = f.u.sel(phase=0.25), f.w.sel(phase=0)
    >>> [round(float(q), 3) for q in (u_peak.min(), u_peak.max(), w_peak.min(), w_peak.max())]
    [0.2, 0.2, 0.1, 0.1]
    >>> int(u_peak.notnull().sum()), int(w_peak.notnull().sum())
    (60, 39)
    """
    if method not in ("least_squares", "paired"):
        raise ValueError(f"method must be 'least_squares' or 'paired', got {method!r}")
    if height <= 0 or period <= 0:
        raise ValueError("height and period must be positive")
    comb = runs if isinstance(runs, xr.Dataset) and "uvp_elevation" in runs.dims \
        else combine_repeats([runs] if isinstance(runs, xr.Dataset) else runs)
    elev = comb["uvp_elevation"].values
    if x is None or z is None:
        gx, gz = default_grid(uvp, elev, dx)
        x = gx if x is None else np.asarray(x, dtype=float)
        z = gz if z is None else np.asarray(z, dtype=float)
    x, z = np.asarray(x, dtype=float), np.asarray(z, dtype=float)
    b = _to_beams(comb)
    dist = comb["distance"].values  # (beam, channel)
    vals = {s: comb[s].values for s in _STATS}  # (elevation, beam, channel, phase)

    def grid(stat, k, values=None, r=None, angle=None):
        v = vals[stat][:, k] if values is None else values
        return beam_to_grid(v, elev, dist[k] if r is None else r, b["x"][k], b["dz"][k],
                            b["angle"][k] if angle is None else angle, x, z)

    if method == "least_squares":
        nb = len(b["names"])
        V = np.stack([grid("beam_velocity", k) for k in range(nb)], axis=-1)
        # variances (not RMS values) are interpolated: linear interpolation of an unbiased
        # variance estimate stays unbiased, while squaring interpolated RMS values biases
        # them low, and ⟨w'²⟩, a small difference of beam variances, amplifies that ~8 times
        S2 = np.stack([grid(None, k, values=vals["beam_velocity_std"][:, k] ** 2)
                       for k in range(nb)], axis=-1)
        C = np.stack([grid("beam_velocity_ci", k) for k in range(nb)], axis=-1)
        u, w, cu, cw = least_squares_velocity(V, b["angle"])
        u_ci, w_ci = combine_ci(cu, C), combine_ci(cw, C)
        uu, ww, uw = reynolds_stresses(S2, b["angle"])
        n_beams = np.isfinite(V).sum(-1)
    else:
        names = b["names"]
        lo, up = _pair(uvp)
        k1, k3 = names.index(lo.name), names.index(up.name)
        alpha = up.angle
        v1, v3 = vals["beam_velocity"][:, k1], vals["beam_velocity"][:, k3]
        uq, wq = paired_velocity(v1, v3, alpha)
        c1, c3 = vals["beam_velocity_ci"][:, k1], vals["beam_velocity_ci"][:, k3]
        s1, s3 = vals["beam_velocity_std"][:, k1] ** 2, vals["beam_velocity_std"][:, k3] ** 2
        r_mid = dist[k1] * np.cos(alpha)  # pair mid-points lie on the horizontal line

        def mid(values):
            return grid(None, k1, values=values, r=r_mid, angle=0.0)

        u, w = mid(uq), mid(wq)
        u_ci = mid(np.sqrt(c1**2 + c3**2) / (2 * np.cos(alpha)))
        w_ci = mid(np.sqrt(c1**2 + c3**2) / (2 * np.sin(alpha)))
        horizontal = [k for k, a in enumerate(b["angle"]) if np.isclose(a, 0.0)]
        if horizontal:
            uu = grid(None, horizontal[0], values=vals["beam_velocity_std"][:, horizontal[0]] ** 2)
        else:
            uu = np.full(u.shape, np.nan)
        ww = (mid(s1 + s3) - 2 * np.cos(alpha) ** 2 * uu) / (2 * np.sin(alpha) ** 2)
        uw = mid((s3 - s1) / (4 * np.sin(alpha) * np.cos(alpha)))
        n_beams = 2 * (np.isfinite(u) & np.isfinite(w))

    phase = comb["phase"].values
    if theta is not None:
        if flap_thickness is None:
            raise ValueError("theta given without flap_thickness")
        theta = np.asarray(theta, dtype=float)
        if theta.shape != phase.shape:
            raise ValueError(f"theta must be given on the {phase.size} phases")
        flap = inside_flap(x[None, :, None], z[:, None, None], theta[None, None, :],
                           flap_thickness, margin)
    else:
        flap = np.zeros(u.shape, dtype=bool)

    def out(a):  # (z, x, phase) -> (phase, z, x), masked inside the flap
        return np.moveaxis(np.where(flap, np.nan, a), -1, 0)

    u0 = np.pi * height / period
    dims = ("phase", "z", "x")
    ds = xr.Dataset(
        {"u": (dims, out(u)), "w": (dims, out(w)), "u_ci": (dims, out(u_ci)),
         "w_ci": (dims, out(w_ci)), "u_rms": (dims, out(np.sqrt(np.clip(uu, 0, None)))),
         "w_rms": (dims, out(np.sqrt(np.clip(ww, 0, None)))), "uw": (dims, out(uw)),
         "uu": (dims, out(uu)), "ww": (dims, out(ww)),
         "tke": (dims, out(turbulent_kinetic_energy(uu, ww))),
         "u_normalised": (dims, out(u) / u0), "w_normalised": (dims, out(w) / u0),
         "n_beams": (dims, np.moveaxis(np.where(flap, 0, n_beams), -1, 0).astype(np.int8)),
         "inside_flap": (dims, np.moveaxis(flap, -1, 0).astype(np.int8))},
        coords={"phase": phase, "z": z, "x": x, "velocity_scale": u0,
                "wave_period": float(period), "wave_height": float(height),
                "n_cycles": comb["n_cycles"]},
        attrs={"method": method, "n_runs": int(comb["n_repeats"].sum()),
               "water_depth": float("nan") if water_depth is None else float(water_depth),
               "u_rms_note": "rms from variances clipped at 0 (sampling noise can make an "
                             "estimated variance slightly negative); tke is not clipped"})
    return conventions.annotate(ds)
