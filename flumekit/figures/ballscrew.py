"""Figures 9-18 of Senatore & De Simone 2022 (ball-screw WEC), from processed datasets only.

Each function takes the scenario dataset(s) and returns a matplotlib Figure (no pyplot):

- efficiency dataset (:func:`flumekit.ballscrew.screw.efficiency`): Figs. 11-15;
- lumped thermal dataset (:func:`flumekit.ballscrew.thermal.lumped.thermal_lumped`): Figs. 9, 16;
- FEM dataset (:func:`flumekit.ballscrew.thermal.fem.thermal_fem`): Figs. 10, 17, 18.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from flumekit.ballscrew.scenario import GENERATOR_REGIONS
from flumekit.figures.style import new_figure, style

KELVIN = 273.15
#: the paper's colours of Fig. 16: EMRG red, nut black, screw blue
COMPONENT_COLOURS = {"generator": "tab:red", "nut": "k", "screw": "tab:blue"}


def _time_series(ds: xr.Dataset, name: str, scale: float, ylabel: str, title: str):
    with style():
        fig, axes = new_figure(figsize=(5.5, 3.2))
        ax = axes[0, 0]
        ax.plot(ds["time"].values, ds[name].values * scale, color="k")
        ax.set_xlabel("time [s]")
        ax.set_ylabel(ylabel)
        ax.set_title(title)
        ax.set_xlim(ds["time"].values[0], ds["time"].values[-1])
    return fig


def figure_11(eff: xr.Dataset):
    """Fig. 11: axial force F_PTO on the nut as a function of time."""
    return _time_series(eff, "pto_force", 1e-3, "$F_{PTO}$ [kN]", "Axial force on the nut")


def figure_12(eff: xr.Dataset):
    """Fig. 12: screw rotation speed ω_screw (in rpm) as a function of time."""
    return _time_series(eff, "screw_speed", 60 / (2 * np.pi), r"$\omega_{screw}$ [rpm]",
                        "Screw rotation speed")


def figure_13(eff: xr.Dataset):
    """Fig. 13: nut velocity v_nut as a function of time."""
    return _time_series(eff, "nut_velocity", 1.0, "$v_{nut}$ [m/s]", "Nut velocity")


def figure_14(eff: xr.Dataset):
    """Fig. 14: film parameters λ_nut, λ_screw and friction coefficients f_ball-nut,
    f_ball-screw."""
    t = eff["time"].values
    panels = [("film_parameter_nut", r"(a) $\lambda_{nut}$"),
              ("film_parameter_screw", r"(b) $\lambda_{screw}$"),
              ("friction_coefficient_nut", "(c) $f_{ball-nut}$"),
              ("friction_coefficient_screw", "(d) $f_{ball-screw}$")]
    with style():
        fig, axes = new_figure(2, 2, figsize=(7.0, 4.8))
        for ax in axes.ravel()[1:]:
            ax.sharex(axes[0, 0])
        for ax, (name, label) in zip(axes.ravel(), panels):
            ax.plot(t, eff[name].values, color="k")
            ax.set_ylabel(label)
            if name.startswith("film"):
                for lim, txt in ((1.0, "boundary | mixed"), (3.0, "mixed | full film")):
                    ax.axhline(lim, color="0.5", lw=0.8, ls="--")
                    ax.text(t[0], lim, " " + txt, fontsize=7, va="bottom", color="0.4")
        for ax in axes[1]:
            ax.set_xlabel("time [s]")
        fig.suptitle("EHL model outputs")
    return fig


def figure_15(eff: xr.Dataset):
    """Fig. 15: indirect efficiency η of the ball screw as a function of time (in %)."""
    fig = _time_series(eff, "ballscrew_efficiency", 100.0, r"$\eta$ [%]", "Indirect efficiency")
    eta = eff["ballscrew_efficiency"].values * 100
    fig.axes[0].text(0.02, 0.05, f"range {eta.min():.0f}-{eta.max():.0f} %",
                     transform=fig.axes[0].transAxes)
    return fig


def figure_9(lumped: xr.Dataset):
    """Fig. 9 (our counterpart): mechanical and electrical losses over one operating cycle."""
    cycle = float(lumped.attrs.get("cycle_duration", 600.0))
    one = lumped.sel(time=slice(0.0, cycle))
    with style():
        fig, axes = new_figure(figsize=(5.5, 3.2))
        ax = axes[0, 0]
        ax.plot(one["time"].values, one["mechanical_power_loss"].values, color="k",
                label="mechanical losses $Q_{mecc}$")
        ax.plot(one["time"].values, one["electrical_power_loss"].values, color="tab:red",
                label="electrical losses $Q_{el}$")
        ax.set_xlabel("time [s]")
        ax.set_ylabel("power loss [W]")
        ax.set_title("Power losses in one operating cycle")
        ax.legend(fontsize=7)
    return fig


def figure_16(lumped: xr.Dataset):
    """Fig. 16: lumped thermal profiles (dashed) and their exponential fits (solid), in °C."""
    t = lumped["time"].values
    t0 = float(lumped.attrs.get("initial_temperature", KELVIN + 20))
    with style():
        fig, axes = new_figure(figsize=(5.5, 3.6))
        ax = axes[0, 0]
        for comp in lumped["component"].values:
            c = COMPONENT_COLOURS.get(str(comp), None)
            temp = lumped["temperature"].sel(component=comp).values
            d = float(lumped["temperature_rise_fit"].sel(component=comp))
            tau = float(lumped["time_constant_fit"].sel(component=comp))
            ax.plot(t / 60, temp - KELVIN, ls="--", color=c, label=f"{comp}")
            ax.plot(t / 60, t0 + d * (1 - np.exp(-t / tau)) - KELVIN, ls="-", color=c, lw=0.8,
                    label=f"fit: ΔT = {d:.1f} K, τ = {tau / 60:.1f} min")
        ax.set_xlabel("time [min]")
        ax.set_ylabel("temperature [°C]")
        ax.set_title("Lumped thermal model")
        ax.legend(fontsize=7)
    return fig


def _triangles(fem: xr.Dataset) -> np.ndarray:
    q = fem["cell_nodes"].values
    return np.concatenate([q[:, [0, 1, 2]], q[:, [0, 2, 3]]])


def figure_10(fem: xr.Dataset):
    """Fig. 10: the axisymmetric section of the PTO with its material regions."""
    from matplotlib import colormaps
    from matplotlib.patches import Patch

    r, z = fem["radial_coordinate"].values * 1e3, fem["axial_coordinate"].values * 1e3
    reg = fem["cell_region"].values
    names = [str(x) for x in fem["region"].values]
    cmap = colormaps["tab20"].resampled(max(len(names), 2))
    with style():
        fig, axes = new_figure(figsize=(5.5, 6.0))
        ax = axes[0, 0]
        ax.tripcolor(r, z, _triangles(fem), facecolors=np.concatenate([reg, reg]).astype(float),
                     cmap=cmap, vmin=-0.5, vmax=len(names) - 0.5, edgecolors="none")
        ax.legend(handles=[Patch(color=cmap(i), label=n) for i, n in enumerate(names)],
                  fontsize=7, loc="upper right")
        ax.set_xlabel("r [mm]")
        ax.set_ylabel("axial position [mm]")
        ax.set_aspect("equal")
        ax.set_xlim(0, max(r.max() * 2.2, 1.0))
        ax.set_title("PTO section (axis of symmetry at r = 0)")
    return fig


def _generator_cells(fem: xr.Dataset) -> np.ndarray:
    """Mask of the cells in the EMRG (stator, air gap, rotor and its hub)."""
    names = np.array([str(x) for x in fem["region"].values])
    return np.isin(names[fem["cell_region"].values], GENERATOR_REGIONS)


def figure_17(fem: xr.Dataset):
    """Fig. 17: temperature field of the EMRG (°C) at the snapshot times (641, 1840, 3225,
    6000 s), the paper's most thermally stressed component."""
    r, z = fem["radial_coordinate"].values * 1e3, fem["axial_coordinate"].values * 1e3
    q = fem["cell_nodes"].values[_generator_cells(fem)]
    tri = np.concatenate([q[:, [0, 1, 2]], q[:, [0, 2, 3]]])
    nodes = np.unique(q)
    fields = fem["temperature_field"].values - KELVIN
    vmin, vmax = float(fields[:, nodes].min()), float(fields[:, nodes].max())
    n = fields.shape[0]
    ncols = min(n, 4)
    with style():
        fig, axes = new_figure(1, ncols, figsize=(1.9 * ncols + 1.2, 3.6))
        for ax in axes.ravel()[1:]:
            ax.sharey(axes[0, 0])
        for k, ax in enumerate(axes.ravel()[:n]):
            pc = ax.tripcolor(r, z, tri, fields[k], shading="gouraud", cmap="inferno",
                              vmin=vmin, vmax=vmax)
            ax.set_title(f"({'abcdefgh'[k]}) {fem['snapshot_time'].values[k]:.0f} s")
            ax.set_xlabel("r [mm]")
            ax.set_xlim(r[nodes].min(), r[nodes].max())
            ax.set_ylim(z[nodes].min(), z[nodes].max())
            ax.set_aspect("equal")
        axes[0, 0].set_ylabel("axial position [mm]")
        fig.suptitle("EMRG (rotor, air gap, stator): temperature field")
        fig.colorbar(pc, ax=axes.ravel().tolist(), label="temperature [°C]")
    return fig


def figure_18(fem: xr.Dataset):
    """Fig. 18: time evolution of the EMRG temperature at its control points (°C)."""
    t = fem["time"].values
    inside = np.isin([str(x) for x in fem["control_region"].values], GENERATOR_REGIONS)
    with style():
        fig, axes = new_figure(figsize=(5.5, 3.6))
        ax = axes[0, 0]
        for p in fem["control_point"].values[inside]:
            pt = fem.sel(control_point=p)
            label = (f"{str(p).replace('_', ' ')} (r = {float(pt['control_radius']) * 1e3:.0f} "
                     f"mm, z = {float(pt['control_axial']) * 1e3:.0f} mm)")
            ax.plot(t / 60, pt["control_temperature"].values - KELVIN, label=label)
        ax.set_xlabel("time [min]")
        ax.set_ylabel("temperature [°C]")
        ax.set_title("EMRG temperature (FEM)")
        ax.legend(fontsize=7, loc="lower right")
    return fig


FIGURES = {9: figure_9, 10: figure_10, 11: figure_11, 12: figure_12, 13: figure_13, 14: figure_14,
           15: figure_15, 16: figure_16, 17: figure_17, 18: figure_18}
