"""The simulator's curves beside the experimental and analytical ones in Figs. 8-10 of Brito et
al. (2020).

Each function draws into given matplotlib Axes (object-oriented API, no pyplot) and returns
them, so it composes with :mod:`flumekit.figures.flap` (experiment) and the linear model's
curves: e.g. ``fig = figure_8(flaps); add_figure_8(fig.axes[0], summaries)``. The inputs are
summaries of simulated runs (:func:`flumekit.flap.summary.summarise_run`), one per
run or concatenated along ``run``, with the ``wave_period`` coordinate and a ``wave_height``
coordinate or the ``incident_height`` variable to group the curves by wave height.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from flumekit.figures.groups import by_height
from flumekit.figures.style import COLOURS, style

_LINES = ("-", "--", "-.", ":")


def _colour(label: str) -> str:
    """The role colour for a label ("simulator", "analytical", ...): one look in every figure."""
    return COLOURS.get(label, COLOURS["simulator"])


def add_figure_8(ax, summaries, label: str = "simulator"):
    """Simulated amplitude of the hydrodynamic torque |T_h| against T, per wave height (Fig. 8).

    Parameters
    ----------
    ax : Axes of :func:`flumekit.figures.flap.figure_8` (or any Axes).
    summaries : Simulated run summaries (``torque_amplitude`` [N m]).
    label : Legend label prefix.
    """
    with style():
        for (h, (periods, v)), ls in zip(by_height(summaries, "torque_amplitude").items(),
                                         _LINES * 3):
            ax.plot(periods, v["torque_amplitude"], ls, color=_colour(label),
                    label=f"H = {h:g} m ({label})")
        ax.legend(fontsize=7)
    return ax


def add_figure_9(axes, summaries, label: str = "simulator"):
    """Simulated (a) |θ|/π and (b) capture factor C_f against T, per wave height (Fig. 9).

    Parameters
    ----------
    axes : Two Axes, as returned in the figure of :func:`flumekit.figures.flap.figure_9`.
    summaries : Simulated run summaries (``theta_amplitude`` [rad], ``capture_factor``).
    label : Legend label prefix.
    """
    if len(axes) != 2:
        raise ValueError("figure 9 needs two axes: (a) rotation, (b) capture factor")
    groups = by_height(summaries, "theta_amplitude", "capture_factor")
    with style():
        for (h, (periods, v)), ls in zip(groups.items(), _LINES * 3):
            kw = {"color": _colour(label), "label": f"H = {h:g} m ({label})"}
            axes[0].plot(periods, v["theta_amplitude"] / np.pi, ls, **kw)
            axes[1].plot(periods, v["capture_factor"], ls, **kw)
        axes[0].legend(fontsize=7)
    return axes


def add_figure_10(axes, summary: xr.Dataset, sim: xr.Dataset | None = None,
                  label: str = "simulator"):
    """Simulated phase averages in the normalisation of Fig. 10.

    Panels as :func:`flumekit.figures.flap.figure_10`: (a) ⟨η⟩/H of the incident elevation
    that drove the simulation (needs ``sim`` with ``eta_incident``), (b) ⟨θ⟩/π, (c)
    ⟨W_out⟩/W_I with the mean as a dotted line, (d) ⟨θ̇⟩/(π ω). Cycles start at a zero
    up-crossing of the simulated θ, as for the experiment.

    Parameters
    ----------
    axes : Four Axes (a-d).
    summary : Summary of one simulated run
        (:func:`~flumekit.flap.summary.summarise_run`).
    sim : The simulation itself, for panel (a).
    label : Legend label.
    """
    from flumekit import signal as sig

    axes = list(np.ravel(axes))
    if len(axes) != 4:
        raise ValueError("figure 10 needs four axes (a)-(d)")
    for name in ("theta_phase_mean", "theta_dot_phase_mean", "power_phase_mean",
                 "incident_power", "mean_power", "measured_period", "incident_height"):
        if name not in summary.variables:
            raise ValueError(f"the simulated summary lacks '{name}'")
    phase = summary["phase"].values
    period = float(summary["measured_period"])
    kw = {"color": _colour(label), "label": label}
    with style():
        if sim is not None and "eta_incident" in sim:
            pa = sig.phase_average(sim["eta_incident"].values, sim["time"].values, period,
                                   float(summary["steady_start"]), int(summary["steady_cycles"]),
                                   n_phase=phase.size)
            axes[0].plot(pa.phase, pa.mean / float(summary["incident_height"]), **kw)
        axes[1].plot(phase, summary["theta_phase_mean"].values / np.pi, **kw)
        w_i = float(summary["incident_power"])
        axes[2].plot(phase, summary["power_phase_mean"].values / w_i, **kw)
        axes[2].axhline(float(summary["mean_power"]) / w_i, color=_colour(label), ls=":",
                        lw=0.9, label=rf"{label}: $\overline{{W}}_{{out}}/W_I$ = "
                                      rf"{float(summary['mean_power']) / w_i:.2f}")
        omega = 2 * np.pi / period
        axes[3].plot(phase, summary["theta_dot_phase_mean"].values / (np.pi * omega), **kw)
        for ax in axes:
            if ax.get_legend_handles_labels()[0]:
                ax.legend(fontsize=7)
    return axes
