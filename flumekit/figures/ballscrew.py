"""Figures 9-18 of Senatore & De Simone 2022 (ball-screw WEC), from processed datasets only.

Each function takes the scenario dataset(s) and returns a matplotlib Figure (no pyplot):

- efficiency dataset (:func:`flumekit.ballscrew.screw.efficiency`): Figs. 11-15;
- lumped thermal dataset (:func:`flumekit.ballscrew.thermal.lumped.thermal_lumped`): Figs. 9, 16;
- FEM dataset (:func:`flumekit.ballscrew.thermal.fem.thermal_fem`): Figs. 10, 17, 18.

%(references_senatore2022)s.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from flumekit.ballscrew.scenario import GENERATOR_REGIONS
from flumekit.docstrings import fill, filler
from flumekit.figures.registry import register
from flumekit.figures.style import (
    ONE_COLUMN,
    TWO_COLUMNS,
    label,
    legend,
    new_figure,
    style,
    title,
    value_label,
)

__doc__ = fill(__doc__)

#: the datasets the figures are drawn from and what the thermal figures return, written once
_doc = filler(
    efficiency=("eff : xarray.Dataset\n"
                "    Efficiency dataset of :func:`flumekit.ballscrew.screw.efficiency`."),
    lumped=("lumped : xarray.Dataset\n"
            "    Lumped thermal dataset of\n"
            "    :func:`flumekit.ballscrew.thermal.lumped.thermal_lumped`."),
    fem=("fem : xarray.Dataset\n"
         "    FEM dataset of :func:`flumekit.ballscrew.thermal.fem.thermal_fem`."),
    efficiency_only="Parameters\n----------\n%(efficiency)s",
    lumped_only="Parameters\n----------\n%(lumped)s",
    fem_only="Parameters\n----------\n%(fem)s",
    temperatures=("Returns\n-------\nmatplotlib.figure.Figure\n"
                  "    Temperatures [°C] against time [min]."))

KELVIN = 273.15
#: the paper's colours of Fig. 16: EMRG red, nut black, screw blue
COMPONENT_COLOURS = {"generator": "tab:red", "nut": "k", "screw": "tab:blue"}


_TIME = label(text="Time $t$", units="s")
_MINUTES = label(text="Time $t$", units="min")
_TEMPERATURE = label(text="Temperature", units="°C")


def _scenario(ds: xr.Dataset, what: str) -> str:
    """Compose the figure title: what is shown and the operating condition of the WEC."""
    cond = []
    if "wave_period" in ds.attrs:
        cond.append(f"regular wave T = {float(ds.attrs['wave_period']):g} s")
    if "cycle_duration" in ds.attrs:
        cond.append(f"{float(ds.attrs['cycle_duration']):g} s operating cycles")
    if "time" in ds.coords and ds["time"].size > 1 and "wave_period" not in ds.attrs:
        cond.append(f"{float(ds['time'][-1] - ds['time'][0]) / 60:g} min")
    return f"{what}: ball-screw WEC" + (f", {', '.join(cond)}" if cond else "")


def _time_series(ds: xr.Dataset, name: str, scale: float, ylabel: str, what: str):
    values = ds[name].values * scale
    fig, axes = new_figure(width=ONE_COLUMN, height=2.6)
    ax = axes[0, 0]
    with style():
        ax.plot(ds["time"].values, values, color="k")
        ax.set_xlabel(_TIME)
        ax.set_ylabel(ylabel)
        ax.set_xlim(ds["time"].values[0], ds["time"].values[-1])
        title(fig, _scenario(ds, what.format(low=np.nanmin(values), high=np.nanmax(values))))
    return fig


#: the figures of one variable of the efficiency dataset against time: figure number ->
#: (what it shows, the symbol and units of its y axis, variable, factor to those units, y-axis
#: label, title opening, in which ``{low}`` and ``{high}`` stand for the extremes drawn)
_TIME_SERIES = {
    11: ("the axial force F_PTO on the nut", "F_PTO [kN]", "pto_force", 1e-3,
         label("pto_force", "$F_{PTO}$", units="kN", text="Axial force"),
         "Axial force on the nut"),
    12: ("the screw rotation speed ω_screw", "ω_screw [rpm]", "screw_speed", 60 / (2 * np.pi),
         label(text=r"Screw speed $\omega_{screw}$", units="rpm"), "Screw rotation speed"),
    13: ("the nut velocity v_nut", "v_nut [m s-1]", "nut_velocity", 1.0,
         label("nut_velocity", "$v_{nut}$", text="Nut velocity"), "Nut velocity"),
    15: ("the indirect efficiency η of the ball screw", "η [%]", "ballscrew_efficiency", 100.0,
         label(text=r"Indirect efficiency $\eta$", units="%"),
         "Efficiency ({low:.0f}-{high:.0f} %)"),
}


def _time_series_figure(number: int):
    """Make the function that draws Fig. ``number`` of :data:`_TIME_SERIES`, documented."""
    shows, axis, name, scale, ylabel, what = _TIME_SERIES[number]

    def figure(eff: xr.Dataset):
        return _time_series(eff, name, scale, ylabel, what)

    figure.__name__ = figure.__qualname__ = f"figure_{number}"
    figure.__doc__ = f"""Draw Fig. {number}: {shows} as a function of time.

    %(efficiency_only)s

    Returns
    -------
    matplotlib.figure.Figure
        {axis} against time [s].

    %(references_senatore2022)s, Fig. {number}.
    """
    return _doc(figure)


figure_11, figure_12, figure_13, figure_15 = map(_time_series_figure, (11, 12, 13, 15))


#: lubrication regimes by film parameter λ (Senatore & De Simone 2022, §3.2)
REGIMES = ((0.0, 1.0, "boundary", "tab:red"), (1.0, 3.0, "mixed", "tab:olive"),
           (3.0, np.inf, "full film", "tab:green"))


@_doc
def figure_14(eff: xr.Dataset):
    """Draw Fig. 14: the film parameters and friction coefficients against time.

    The film parameters λ_nut, λ_screw (lubrication regimes shaded) and the friction
    coefficients f_ball-nut, f_ball-screw.

    %(efficiency_only)s

    Returns
    -------
    matplotlib.figure.Figure
        λ [-] and f [-] against time [s].

    %(references_senatore2022)s, Fig. 14.
    """
    from matplotlib.patches import Patch

    t = eff["time"].values
    panels = [("film_parameter_nut", r"$\lambda_{nut}$", "(a) ball-nut film parameter"),
              ("film_parameter_screw", r"$\lambda_{screw}$", "(b) ball-screw film parameter"),
              ("friction_coefficient_nut", "$f_{ball-nut}$", "(c) ball-nut friction"),
              ("friction_coefficient_screw", "$f_{ball-screw}$", "(d) ball-screw friction")]
    fig, axes = new_figure(2, 2, width=TWO_COLUMNS, row_height=2.0, sharex=True)
    with style():
        for ax, (name, sym, tag) in zip(axes.ravel(), panels):
            ax.plot(t, eff[name].values, color="k")
            text = "Film parameter" if name.startswith("film") else "Friction coefficient"
            ax.set_ylabel(label(text=f"{text} {sym}", units="1"))
            ax.set_title(tag)
            if name.startswith("film"):
                top = max(float(np.nanmax(eff[name].values)), 3.0) * 1.05
                for lo, hi, _, colour in REGIMES:
                    ax.axhspan(lo, min(hi, top), color=colour, alpha=0.12, lw=0)
                ax.set_ylim(0, top)
        for ax in axes[1]:
            ax.set_xlabel(_TIME)
        title(fig, _scenario(eff, "Lubrication (EHL model)"))
        legend(fig, [Patch(color=c, alpha=0.25, label=f"{r} lubrication")
                     for _, _, r, c in REGIMES])
    return fig


@_doc
def figure_9(lumped: xr.Dataset, zoom: float = 20.0):
    """Draw Fig. 9 (our counterpart): mechanical and electrical losses over one operating cycle.

    The operating cycle of the paper lasts 600 s (``cycle_duration``); (a) shows it whole,
    (b) its first ``zoom`` seconds with the samples of the model marked, where the
    instantaneous losses can be read.

    Parameters
    ----------
    %(lumped)s
    zoom : float, optional
        Duration shown in (b) [s].

    Returns
    -------
    matplotlib.figure.Figure
        Power losses [W] against time [s].

    %(references_senatore2022)s, Fig. 9.
    """
    cycle = float(lumped.attrs.get("cycle_duration", 600.0))
    one = lumped.sel(time=slice(0.0, cycle))
    t = one["time"].values
    first = t <= t[0] + zoom
    fig, axes = new_figure(1, 2, width=TWO_COLUMNS, height=2.8, sharey=True)
    with style():
        for ax, sel, tag in ((axes[0, 0], slice(None), f"(a) the whole {cycle:g} s cycle"),
                             (axes[0, 1], first, f"(b) its first {zoom:g} s")):
            style_ = "-" if tag.startswith("(a)") else ".-"  # (b): the samples of the model
            ax.plot(t[sel], one["mechanical_power_loss"].values[sel], style_, color="k", lw=0.6,
                    label="mechanical losses $Q_{mecc}$")
            ax.plot(t[sel], one["electrical_power_loss"].values[sel], style_, color="tab:red",
                    lw=0.6, label="electrical losses $Q_{el}$")
            ax.set_xlabel(_TIME)
            ax.set_title(tag)
            ax.set_xlim(t[sel][0], t[sel][-1])
        axes[0, 0].set_ylabel(label(text="Power loss", units="W"))
        title(fig, f"Power losses over one {cycle:g} s operating cycle of the ball-screw WEC")
        legend(fig)
    return fig


def _temperatures(ds: xr.Dataset, curves, what: str):
    """Draw temperature histories against time in minutes, page-wide, legend on the right.

    ``curves`` holds one (temperature [K] over ``ds``'s time, keyword arguments of ``plot``)
    pair per line; ``what`` opens the title.
    """
    t = ds["time"].values
    fig, axes = new_figure(width=TWO_COLUMNS, height=3.0)
    ax = axes[0, 0]
    with style():
        for temperature, kw in curves:
            ax.plot(t / 60, temperature - KELVIN, **kw)
        ax.set_xlabel(_MINUTES)
        ax.set_ylabel(_TEMPERATURE)
        title(fig, _scenario(ds, what))
        legend(fig, where="right")
    return fig


@_doc
def figure_16(lumped: xr.Dataset):
    """Draw Fig. 16: lumped thermal profiles (dashed) and their exponential fits (solid).

    One colour per component; a fit reads T(t) = T_0 + ΔT (1 - exp(-t/τ)), its ΔT and τ in
    the legend.

    %(lumped_only)s

    %(temperatures)s

    %(references_senatore2022)s, Fig. 16.
    """
    t = lumped["time"].values
    t0 = float(lumped.attrs.get("initial_temperature", KELVIN + 20))
    curves = []
    for comp in lumped["component"].values:
        c = COMPONENT_COLOURS.get(str(comp), None)
        d = float(lumped["temperature_rise_fit"].sel(component=comp))
        tau = float(lumped["time_constant_fit"].sel(component=comp))
        curves += [(lumped["temperature"].sel(component=comp).values,
                    {"ls": "--", "color": c, "label": f"{value_label(comp)}, model"}),
                   (t0 + d * (1 - np.exp(-t / tau)),
                    {"ls": "-", "color": c, "lw": 0.8, "label": f"{value_label(comp)}, fit: "
                     f"ΔT = {d:.1f} K, τ = {tau / 60:.1f} min"})]
    return _temperatures(lumped, curves, "Lumped thermal model")


def _triangles(quads: np.ndarray) -> np.ndarray:
    """Split quadrilateral cells (node indices, shape (n, 4)) into triangles for tripcolor."""
    return np.concatenate([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]])


@_doc
def figure_10(fem: xr.Dataset):
    """Draw Fig. 10: the axisymmetric section of the PTO with its material regions.

    Drawn with the axis of symmetry horizontal (axial position along x, radius up), so the
    long, slender section fills a page-wide figure.

    %(fem_only)s

    Returns
    -------
    matplotlib.figure.Figure
        Radius [mm] against axial position [mm].

    %(references_senatore2022)s, Fig. 10.
    """
    from matplotlib import colormaps
    from matplotlib.patches import Patch

    r, z = fem["radial_coordinate"].values * 1e3, fem["axial_coordinate"].values * 1e3
    reg = fem["cell_region"].values
    names = [str(x) for x in fem["region"].values]
    cmap = colormaps["tab20"].resampled(max(len(names), 2))
    aspect = (r.max() - r.min()) / max(z.max() - z.min(), 1e-9)
    fig, axes = new_figure(width=TWO_COLUMNS, height=min(1.3 + 6.3 * aspect, 6.0))
    ax = axes[0, 0]
    with style():
        ax.tripcolor(z, r, _triangles(fem["cell_nodes"].values),
                     facecolors=np.concatenate([reg, reg]).astype(float), cmap=cmap,
                     vmin=-0.5, vmax=len(names) - 0.5, edgecolors="none")
        ax.set_xlabel(label(text="Axial position", units="mm"))
        ax.set_ylabel(label(text="Radius $r$", units="mm"))
        ax.set_aspect("equal")
        ax.set_ylim(0, r.max() * 1.05)
        title(fig, "PTO section of the ball-screw WEC (axis of symmetry at r = 0)")
        legend(fig, [Patch(color=cmap(i), label=value_label(n)) for i, n in enumerate(names)],
               ncols=4)
    return fig


def _generator_cells(fem: xr.Dataset) -> np.ndarray:
    """Mask of the cells in the EMRG (stator, air gap, rotor and its hub)."""
    names = np.array([str(x) for x in fem["region"].values])
    return np.isin(names[fem["cell_region"].values], GENERATOR_REGIONS)


@_doc
def figure_17(fem: xr.Dataset):
    """Draw Fig. 17: the temperature field of the EMRG at the snapshot times.

    The snapshots at 641, 1840, 3225 and 6000 s of the generator (EMRG), the paper's most
    thermally stressed component.

    %(fem_only)s

    Returns
    -------
    matplotlib.figure.Figure
        Temperature [°C] over the section, axial position against r [mm].

    %(references_senatore2022)s, Fig. 17.
    """
    r, z = fem["radial_coordinate"].values * 1e3, fem["axial_coordinate"].values * 1e3
    q = fem["cell_nodes"].values[_generator_cells(fem)]
    tri = _triangles(q)
    nodes = np.unique(q)
    fields = fem["temperature_field"].values - KELVIN
    vmin, vmax = float(fields[:, nodes].min()), float(fields[:, nodes].max())
    n = fields.shape[0]
    fig, axes = new_figure(1, n, width=TWO_COLUMNS, height=3.6, sharey=True)
    with style():
        for k, ax in enumerate(axes.ravel()):
            pc = ax.tripcolor(r, z, tri, fields[k], shading="gouraud", cmap="inferno",
                              vmin=vmin, vmax=vmax)
            ax.set_title(f"({'abcdefgh'[k]}) t = {fem['snapshot_time'].values[k]:.0f} s")
            ax.set_xlabel(label(text="$r$", units="mm"))
            ax.set_xlim(r[nodes].min(), r[nodes].max())
            ax.set_ylim(z[nodes].min(), z[nodes].max())
            ax.set_aspect("equal")
        axes[0, 0].set_ylabel(label(text="Axial position", units="mm"))
        fig.colorbar(pc, ax=axes.ravel().tolist(), label=_TEMPERATURE)
        title(fig, _scenario(fem, "FEM temperature field of the EMRG (rotor, air gap, stator)"))
    return fig


@_doc
def figure_18(fem: xr.Dataset):
    """Draw Fig. 18: the time evolution of the EMRG temperature at its control points.

    Only the control points inside the generator (stator, air gap, rotor and its hub) are
    drawn, each labelled with its radius r and axial position z.

    %(fem_only)s

    %(temperatures)s

    %(references_senatore2022)s, Fig. 18.
    """
    inside = np.isin([str(x) for x in fem["control_region"].values], GENERATOR_REGIONS)
    points = [(p, fem.sel(control_point=p)) for p in fem["control_point"].values[inside]]
    return _temperatures(fem, [
        (pt["control_temperature"].values,
         {"label": f"{value_label(p)} (r = {float(pt['control_radius']) * 1e3:.0f} mm, "
                   f"z = {float(pt['control_axial']) * 1e3:.0f} mm)"}) for p, pt in points],
        "EMRG temperature at its control points (FEM)")


FIGURES = {9: figure_9, 10: figure_10, 11: figure_11, 12: figure_12, 13: figure_13, 14: figure_14,
           15: figure_15, 16: figure_16, 17: figure_17, 18: figure_18}
for _number, _function in FIGURES.items():  # drawn from the step's dataset (stages.ballscrew)
    register(f"bs_fig{_number:02d}")(_function)
