"""Figures 11 and 12 of Brito et al. (2020): the phase-averaged velocity field near the flap.

Both take the field dataset of :func:`flumekit.uvp.velocity_field` (dims phase, z, x, with
``u_normalised``, ``w_normalised`` and the ``water_depth`` attribute) and return a matplotlib
``Figure`` built with the object-oriented API (no pyplot state).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from flumekit.figures.style import COLOURS, new_figure, style

PHASES = (0.0, 0.06, 0.15, 0.27, 0.38, 0.44)  # t/T of Figs. 11 and 12


def _depth(field: xr.Dataset) -> float:
    h = float(field.attrs.get("water_depth", np.nan))
    if not np.isfinite(h) or h <= 0:
        raise ValueError("the field dataset needs a positive 'water_depth' attribute [m]")
    return h


def _share(axes, x: bool, y: bool) -> None:
    first = axes.flat[0]
    for ax in axes.flat[1:]:
        if x:
            ax.sharex(first)
        if y:
            ax.sharey(first)


def _at_phase(field: xr.Dataset, p: float) -> xr.Dataset:
    k = int(np.argmin(np.abs(((field["phase"].values - p + 0.5) % 1.0) - 0.5)))
    return field.isel(phase=k)


def fig11(field: xr.Dataset, phases=PHASES, levels=None, stride: int = 2,
          arrow: float = 1.5):
    """Phase-averaged vector field (⟨u⟩, ⟨w⟩)/U0 and contours of ⟨u⟩/U0 (Fig. 11).

    Parameters
    ----------
    field : Field dataset (phase, z, x).
    phases : t/T of the panels (the nearest phase of the grid is shown).
    levels : Contour levels of ⟨u⟩/U0; default symmetric, 21 levels over the field's range.
    stride : Plot every ``stride``-th vector in x and z.
    arrow : Length of the longest arrow in units of the plotted vector spacing.
    """
    h = _depth(field)
    x, z = field["x"].values / h, field["z"].values / h
    un = field["u_normalised"].values
    if levels is None:
        lim = np.nanmax(np.abs(un)) if np.any(np.isfinite(un)) else 1.0
        levels = np.linspace(-lim, lim, 21)
    speed = np.hypot(un, field["w_normalised"].values)
    vmax = np.nanmax(speed) if np.any(np.isfinite(speed)) else 1.0
    spacing = stride * min(np.min(np.abs(np.diff(x))) if x.size > 1 else 1.0,
                           np.min(np.abs(np.diff(z))) if z.size > 1 else 1.0)
    scale = vmax / (arrow * spacing)  # data units (U0) per unit of x/h
    ncols = 2
    nrows = int(np.ceil(len(phases) / ncols))
    with style():
        fig, axes = new_figure(nrows, ncols, figsize=(7.0, 2.6 * nrows))
        _share(axes, x=True, y=True)
        cs = None
        for ax, p, tag in zip(axes.flat, phases, "abcdefgh"):
            f = _at_phase(field, p)
            u = f["u_normalised"].values
            w = f["w_normalised"].values
            if np.any(np.isfinite(u)):
                cs = ax.contourf(x, z, u, levels=levels, cmap="RdBu_r", extend="both")
            sl = (slice(None, None, stride), slice(None, None, stride))
            ax.quiver(x[::stride], z[::stride], u[sl], w[sl], angles="xy", scale_units="xy",
                      scale=scale, width=0.004)
            ax.set_title(f"({tag}) t/T = {float(f['phase']):.2f}")
            ax.set_aspect("equal")
        for ax in axes[-1]:
            ax.set_xlabel("x/h")
        for ax in axes[:, 0]:
            ax.set_ylabel("z/h")
        for ax in axes.flat[len(phases):]:
            ax.set_visible(False)
        if cs is not None:
            fig.colorbar(cs, ax=axes, label=r"$\langle u\rangle/U_0$", shrink=0.8)
    return fig


def _column(field: xr.Dataset, name: str, x: float):
    """Values of ``name`` (phase, z) at x, linearly interpolated; where both neighbours are not
    available, the nearest column with data is used and its x is returned."""
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


def fig12(field: xr.Dataset, x_over_h: float = -0.11, phases=PHASES,
          truth: xr.Dataset | None = None):
    """⟨u⟩/U0 and ⟨w⟩/U0 profiles at x/h = ``x_over_h`` (Fig. 12).

    Where the beams do not resolve a component at that section (with the default mounting the
    inclined beams end at x ≈ -0.12 m, so ⟨w⟩ is not measured at x/h = -0.11), the nearest
    section with data is used and named in the legend. ``truth`` (a field on the same grid,
    e.g. the virtual flume's) is drawn dashed.
    """
    h = _depth(field)
    x = x_over_h * h
    z = field["z"].values / h
    ncols = 3
    nrows = int(np.ceil(len(phases) / ncols))
    cols = {c: _column(field, f"{c}_normalised", x) for c in "uw"}
    tcols = {}
    if truth is not None:  # the truth at the sections actually shown
        tcols = {c: _column(truth, f"{c}_normalised", xc if np.isfinite(xc) else x)
                 for c, (_, xc) in cols.items()}
    colour = {"u": COLOURS["experiment"], "w": "tab:purple"}
    with style():
        fig, axes = new_figure(nrows, ncols, figsize=(7.0, 2.8 * nrows))
        _share(axes, x=False, y=True)
        for ax, p, tag in zip(axes.flat, phases, "abcdefgh"):
            for c in "uw":
                col, xc = cols[c]
                k = int(np.argmin(np.abs(((col["phase"].values - p + 0.5) % 1.0) - 0.5)))
                ax.plot(col.values[k], z, "-o", ms=2.5, color=colour[c],
                        label=rf"$\langle {c}\rangle/U_0$, x/h = {xc / h:.2f}")
                if c in tcols:
                    tc, _ = tcols[c]
                    tz = tc["z"].values / h
                    ax.plot(tc.values[k], tz, "--", color=COLOURS["truth"],
                            label="truth" if c == "u" else None)
            ax.axvline(0.0, color="0.5", lw=0.6)
            ax.set_title(f"({tag}) t/T = {p:.2f}")
            ax.set_xlabel(r"velocity $/U_0$")
        for ax in axes[:, 0]:
            ax.set_ylabel("z/h")
        for ax in axes.flat[len(phases):]:
            ax.set_visible(False)
        axes.flat[0].legend(fontsize=7, loc="best")
    return fig
