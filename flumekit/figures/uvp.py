"""Figures 11 and 12 of Brito et al. (2020): the phase-averaged velocity field near the flap.

Both take the field dataset of :func:`flumekit.uvp.velocity_field` (dims phase, z, x, with
``u_normalised``, ``w_normalised`` and the ``water_depth`` attribute) and return a matplotlib
``Figure`` built with the object-oriented API (no pyplot state).

%(references_brito2020)s, §4, Figs. 11-12.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from flumekit.docstrings import doc, fill
from flumekit.figures.registry import register
from flumekit.figures.style import (
    COLOURS,
    TWO_COLUMNS,
    condition,
    label,
    legend,
    new_figure,
    title,
)

__doc__ = fill(__doc__)

PHASES = (0.0, 0.06, 0.15, 0.27, 0.38, 0.44)  # t/T of Figs. 11 and 12


def _depth(field: xr.Dataset) -> float:
    h = float(field.attrs.get("water_depth", np.nan))
    if not np.isfinite(h) or h <= 0:
        raise ValueError("the field dataset needs a positive 'water_depth' attribute [m]")
    return h


def _phase_index(data: xr.Dataset | xr.DataArray, p: float) -> int:
    """Return the index of the phase of ``data`` nearest to t/T = ``p``, across the cycle's end."""
    return int(np.argmin(np.abs(((data["phase"].values - p + 0.5) % 1.0) - 0.5)))


def _at_phase(field: xr.Dataset, p: float) -> xr.Dataset:
    return field.isel(phase=_phase_index(field, p))


def _field_title(field: xr.Dataset, what: str) -> str:
    n = int(field.attrs.get("n_runs", 0))
    runs = f"{n} UVP run{'s' if n != 1 else ''}" if n else "UVP runs"
    cond = condition(field)
    return f"{what}: {runs}" + (f" ({cond})" if cond else "") + _scales(field)


def _scales(field: xr.Dataset) -> str:
    """Describe the normalising scales: U0 = πH/T (Brito et al. 2020, §4) and the depth h."""
    h = _depth(field)
    if "velocity_scale" not in field.coords and "velocity_scale" not in field:
        return "\n" + f"$h$ = {h:.3f} m"
    u0 = float(field["velocity_scale"])
    return "\n" + rf"$U_0 = \pi H/T$ = {u0:.3f} m/s, $h$ = {h:.3f} m"


def _strides(x: np.ndarray, z: np.ndarray, n_arrows: int) -> tuple[int, int, float]:
    """Return the strides in x and z for about ``n_arrows`` arrows across the field.

    Across the wider extent of the field, on a near-square lattice; also the lattice spacing
    (in the units of x and z).
    """
    dx = float(np.min(np.abs(np.diff(x)))) if x.size > 1 else 1.0
    dz = float(np.min(np.abs(np.diff(z)))) if z.size > 1 else 1.0
    extent = max(float(np.ptp(x)) if x.size > 1 else 0.0,
                 float(np.ptp(z)) if z.size > 1 else 0.0)
    target = extent / max(n_arrows - 1, 1) if extent > 0 else max(dx, dz)
    sx, sz = max(1, int(round(target / dx))), max(1, int(round(target / dz)))
    return sx, sz, min(sx * dx, sz * dz)


def _nice_levels(lim: float, n: int = 10) -> np.ndarray:
    """Return symmetric contour levels on round numbers covering [-lim, lim].

    Colour-bar ticks at values one can read, not at lim/10 multiples.
    """
    from matplotlib.ticker import MaxNLocator

    return MaxNLocator(nbins=n, symmetric=True, steps=[1, 2, 2.5, 5, 10]).tick_values(-lim, lim)


def _reference_length(vmax: float) -> float:
    """Return a round reference vector length no longer than the longest arrow."""
    if not np.isfinite(vmax) or vmax <= 0:
        return 1.0
    mag = 10 ** np.floor(np.log10(vmax))
    return float(max(s * mag for s in (1, 2, 5) if s * mag <= vmax))


@register("fig11")
@doc
def fig11(field: xr.Dataset, phases=PHASES, levels=None, n_arrows: int = 9,
          arrow: float = 0.9):
    r"""Draw the phase-averaged vector field (⟨u⟩, ⟨w⟩)/U0 and contours of ⟨u⟩/U0 (Fig. 11).

    Legible at print size: about ``n_arrows`` arrows across each panel on a near-square
    lattice, the longest no longer than ``arrow`` lattice spacings so that arrows never run
    into their neighbours, and colour levels symmetric over the largest ⟨u⟩/U0 of the shown
    phases, so that no value saturates the colour bar. The title states U0 and h.

    Parameters
    ----------
    field : xarray.Dataset
        Field dataset (phase, z, x) of :func:`flumekit.uvp.velocity_field`.
    phases : sequence of float, optional
        t/T of the panels [-] (the nearest phase of the grid is shown).
    levels : array_like, optional
        Contour levels of ⟨u⟩/U0 [-]; default symmetric, on round numbers covering the
        largest magnitude of the shown phases (the colour-bar ticks).
    n_arrows : int, optional
        Arrows across the wider extent of a panel [-].
    arrow : float, optional
        Length of the longest arrow in lattice spacings [-] (below 1: no overlap).

    Returns
    -------
    matplotlib.figure.Figure
        Two columns wide, z/h against x/h [-], with a reference arrow below the panels.

    %(references_brito2020)s, Fig. 11.

    Examples
    --------
    The orbital velocities of a deep-water wave 2 m long, over 20 phases of the cycle; each
    panel shows the grid's phase nearest to the paper's:

    >>> import numpy as np
    >>> import xarray as xr
    >>> from flumekit.figures import fig11
    >>> k = 2 * np.pi / 2.0  # wavenumber [rad/m]
    >>> phase, z, x = np.arange(20) / 20, np.linspace(-0.4, -0.1, 4), np.linspace(-0.3, 0.0, 7)
    >>> p, zz, xx = np.meshgrid(phase, z, x, indexing="ij")
    >>> orbit = np.exp(k * zz) * np.exp(1j * (k * xx - 2 * np.pi * p))  # u + i w over U0
    >>> field = xr.Dataset({"u_normalised": (("phase", "z", "x"), orbit.real),
    ...                     "w_normalised": (("phase", "z", "x"), orbit.imag)},
    ...                    coords={"phase": phase, "z": z, "x": x}, attrs={"water_depth": 0.5})
    >>> fig = fig11(field)
    >>> [ax.get_title(loc="left")[-4:] for ax in fig.axes[:6]]  # t/T of (a)-(f)
    ['0.00', '0.05', '0.15', '0.25', '0.40', '0.45']

    The colour bar covers the largest ⟨u⟩/U0 shown, exp(-0.1 k) = 0.73 at the top row, with
    round levels:

    >>> colour_bar = fig.axes[-1]
    >>> colour_bar.get_ylabel(), [float(v) for v in colour_bar.get_ylim()]
    ('$\\langle u\\rangle/U_0$ [-]', [-0.8, 0.8])
    """
    h = _depth(field)
    x, z = field["x"].values / h, field["z"].values / h
    sx, sz, spacing = _strides(x, z, n_arrows)
    shown = [_at_phase(field, p) for p in phases]
    un = np.stack([f["u_normalised"].values for f in shown])
    if levels is None:  # over what is drawn: nothing beyond the outermost level
        lim = float(np.nanmax(np.abs(un))) if np.any(np.isfinite(un)) else 1.0
        levels = _nice_levels(lim)
    # a triangle on the colour bar only where values lie beyond its levels
    big, small = np.nanmax(un) > levels[-1], np.nanmin(un) < levels[0]
    extend = {(True, True): "both", (True, False): "max", (False, True): "min"}.get(
        (bool(big), bool(small)), "neither")
    sub = (slice(None), slice(None, None, sz), slice(None, None, sx))
    speed = np.hypot(un[sub], np.stack([f["w_normalised"].values for f in shown])[sub])
    vmax = float(np.nanmax(speed)) if np.any(np.isfinite(speed)) else 1.0
    scale = vmax / (arrow * spacing)  # data units (U0) per unit of x/h
    # panels shaped like the field (equal axes): three columns when it is taller than wide
    aspect = float(np.ptp(z) / np.ptp(x)) if x.size > 1 and z.size > 1 else 1.0
    ncols = min(len(phases), 3 if aspect > 1 else 2)
    nrows = int(np.ceil(len(phases) / ncols))
    panel = float(np.clip((TWO_COLUMNS - 1.4) / ncols * aspect, 1.0, 3.0))
    fig, axes = new_figure(nrows, ncols, width=TWO_COLUMNS, height=nrows * (panel + 0.45) + 0.9,
                           sharex=True, sharey=True)
    for ax in axes.flat[len(phases):]:
        fig.delaxes(ax)
    cs = q = None
    for ax, f, tag in zip(axes.flat, shown, "abcdefgh"):
        u = f["u_normalised"].values
        w = f["w_normalised"].values
        if np.any(np.isfinite(u)):
            cs = ax.contourf(x, z, u, levels=levels, cmap="RdBu_r", extend=extend)
        sl = (slice(None, None, sz), slice(None, None, sx))
        q = ax.quiver(x[::sx], z[::sz], u[sl], w[sl], angles="xy", scale_units="xy",
                      scale=scale, width=0.007, headwidth=3.5, headlength=4,
                      headaxislength=3.5, pivot="middle")
        ax.set_title(f"({tag}) t/T = {float(f['phase']):.2f}")
        # half a lattice spacing around the field: the arrows (centred on their points)
        # of the outer rows and columns stay inside the panel
        ax.set_xlim(x.min() - spacing / 2, x.max() + spacing / 2)
        ax.set_ylim(z.min() - spacing / 2, z.max() + spacing / 2)
        ax.set_aspect("equal")
        ax.set_xlabel(label(text="$x/h$", units="1"))
        ax.set_ylabel(label(text="$z/h$", units="1"))
    for ax in axes.flat[:len(phases)]:
        ax.label_outer()
    if cs is not None:  # ticks at the contour levels: round numbers
        fig.colorbar(cs, ax=axes, shrink=0.8,
                     label=label(text=r"$\langle u\rangle/U_0$", units="1"))
    if q is not None:  # the reference arrow, in a strip kept free below the panels
        ref = _reference_length(vmax)
        strip = 0.35 / fig.get_size_inches()[1]
        fig.get_layout_engine().set(rect=(0, strip, 1, 1 - strip))
        axes.flat[0].quiverkey(q, 0.06, strip / 2, ref,
                               rf"reference arrow: velocity = {ref:g} $U_0$",
                               labelpos="E", coordinates="figure")
    title(fig, _field_title(field, "Phase-averaged velocity field in front of the flap"))
    return fig
def _column(field: xr.Dataset, name: str, x: float):
    """Return the values of ``name`` (phase, z) at x, linearly interpolated, and that x.

    Where both neighbours are not available, the nearest column with data is used and its x
    is returned.
    """
    da = field[name]
    col = da.interp(x=x)
    if np.any(np.isfinite(col.values)):
        return col, x
    ok = np.isfinite(da.values).any(axis=(0, 1))
    if not ok.any():
        return col, np.nan
    xs = field["x"].values
    k = int(np.argmin(np.where(ok, np.abs(xs - x), np.inf)))
    return da.isel(x=k), float(xs[k])


@register("fig12")
@doc
def fig12(field: xr.Dataset, x_over_h: float = -0.11, phases=PHASES,
          truth: xr.Dataset | None = None):
    r"""Draw the ⟨u⟩/U0 and ⟨w⟩/U0 profiles at x/h = ``x_over_h`` (Fig. 12).

    Where the beams do not resolve a component at that section (with the default mounting the
    inclined beams end at x ≈ -0.12 m, so ⟨w⟩ is not measured at x/h = -0.11), the nearest
    section with data is used and named in the legend. Phases at which neither component has
    data at the section get no panel (the figure sizes itself to what it has).

    Parameters
    ----------
    field : xarray.Dataset
        Field dataset (phase, z, x) of :func:`flumekit.uvp.velocity_field`.
    x_over_h : float, optional
        Section x/h [-] (negative: seaward of the hinge).
    phases : sequence of float, optional
        t/T of the profiles [-].
    truth : xarray.Dataset, optional
        A field on the same grid (e.g. the virtual flume's), drawn dashed.

    Returns
    -------
    matplotlib.figure.Figure
        z/h against ⟨u⟩/U0 and ⟨w⟩/U0 [-], one panel per phase with data.

    %(references_brito2020)s, Fig. 12.

    Examples
    --------
    The inclined beams end at x = -0.1 m: ⟨w⟩ comes from there, ⟨u⟩ from the section asked
    for (x/h = -0.11 in 0.5 m of water: x = -0.055 m); only the phases asked for are drawn:

    >>> import numpy as np
    >>> import xarray as xr
    >>> from flumekit.figures import fig12
    >>> phase = xr.DataArray(np.arange(20) / 20, dims="phase")
    >>> z = xr.DataArray(np.linspace(-0.4, -0.1, 4), dims="z")  # [m]
    >>> x = xr.DataArray(np.arange(-6, 1) * 0.05, dims="x")  # [m], the hinge at x = 0
    >>> decay = np.exp(z / 0.5) * xr.ones_like(x)
    >>> field = xr.Dataset({"u_normalised": np.cos(2 * np.pi * phase) * decay,
    ...                     "w_normalised": (np.sin(2 * np.pi * phase) * decay).where(x <= -0.1)},
    ...                    attrs={"water_depth": 0.5}).assign_coords(phase=phase, z=z, x=x)
    >>> fig = fig12(field, phases=(0.0, 0.25))
    >>> len(fig.axes), [line.get_label() for line in fig.axes[0].lines[:2]]
    (2, ['$\\langle u\\rangle/U_0$ at x/h = -0.11', '$\\langle w\\rangle/U_0$ at x/h = -0.20'])
    """
    h = _depth(field)
    x = x_over_h * h
    z = field["z"].values / h
    cols = {c: _column(field, f"{c}_normalised", x) for c in "uw"}
    tcols = {}
    if truth is not None:  # the truth at the sections actually shown
        tcols = {c: _column(truth, f"{c}_normalised", xc if np.isfinite(xc) else x)
                 for c, (_, xc) in cols.items()}

    shown = [p for p in phases if any(np.isfinite(col.values[_phase_index(col, p)]).any()
                                      for col, _ in cols.values())]
    if not shown:
        raise ValueError(f"the field has no velocity at or near x/h = {x_over_h:g} at any of "
                         f"the phases {list(phases)}")
    colour = {"u": COLOURS["experiment"], "w": "tab:purple"}
    ncols = min(3, len(shown))
    nrows = int(np.ceil(len(shown) / ncols))
    fig, axes = new_figure(nrows, ncols, width=TWO_COLUMNS, row_height=2.1, sharey=True)
    for ax in axes.flat[len(shown):]:
        fig.delaxes(ax)
    for ax, p, tag in zip(axes.flat, shown, "abcdefgh"):
        for c in "uw":
            col, xc = cols[c]
            k = _phase_index(col, p)
            ax.plot(col.values[k], z, "-o", ms=2.5, color=colour[c],
                    label=rf"$\langle {c}\rangle/U_0$ at x/h = {xc / h:.2f}")
            if c in tcols:
                tc, _ = tcols[c]
                ax.plot(tc.values[k], tc["z"].values / h, "--", color=COLOURS["truth"],
                        label="truth")
        ax.axvline(0.0, color="0.5", lw=0.6)
        ax.set_title(f"({tag}) t/T = {p:.2f}")
        ax.set_xlabel(label(text="Velocity over $U_0$", units="1"))
    for ax in axes[:, 0]:
        ax.set_ylabel(label(text="$z/h$", units="1"))
    title(fig, _field_title(field, f"Velocity profiles at x/h = {x_over_h:g}"))
    legend(fig)
    return fig
