"""Model curves (linear model, simulator) beside the experimental ones in Figs. 8-10.

The figures are those of Brito et al. (2020).

Each function draws into given matplotlib Axes (object-oriented API, no pyplot) and returns
them; :func:`flumekit.figures.flap.figure_8` (and 9, 10) call them for their ``models``
argument. The inputs are run summaries (:func:`flumekit.flap.summary.summarise_run`, or a
comparison dataset at one ``source``), one per run or concatenated along ``run``, with the
``wave_period`` coordinate and a ``wave_height`` coordinate or the ``incident_height`` variable
to group the curves by wave height. In Figs. 8 and 9 a colour (and marker) stands for a wave
height and a line style for a source; in Fig. 10 a colour stands for a source.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from flumekit.docstrings import filler
from flumekit.figures.groups import by_height
from flumekit.figures.style import COLOURS, style, value_label

#: parameters and returns that the model curves of Figs. 8-10 share, written once
_doc = filler(
    source_line=("label : str, optional\n"
                 "    Source name (\"analytical\", \"simulator\"): its line style."),
    heights=("heights : iterable of float, optional\n"
             "    Every wave height [m] of the figure, for consistent colours; default these."),
    axes_drawn=("Returns\n"
                "-------\n"
                "sequence of matplotlib.axes.Axes\n"
                "    ``axes``."))

#: line style of each model source in Figs. 8 and 9 (the experiment is drawn as markers)
SOURCE_LINES = {"analytical": "-", "simulator": "--"}
#: marker of each wave height, in order, so the figures read in greyscale too
MARKERS = ("o", "s", "^", "D", "v", "P", "X")


def height_colours(heights) -> dict[float, tuple]:
    """Assign one colour per wave height (viridis, darkest for the lowest).

    Parameters
    ----------
    heights : iterable of float
        Wave heights [m] (duplicates ignored).

    Returns
    -------
    dict
        {height [m]: RGBA tuple}, heights ascending.

    Examples
    --------
    >>> from flumekit.figures.simulator import height_colours
    >>> list(height_colours([0.2, 0.1, 0.2]))
    [0.1, 0.2]
    """
    from matplotlib import colormaps

    heights = sorted(set(heights))
    cmap = colormaps["viridis"]
    n = len(heights)
    return {h: cmap(0.85 * i / max(n - 1, 1)) for i, h in enumerate(heights)}


def _colour(label: str) -> str:
    """Return the role colour of a source ("simulator", "analytical", ...) in Fig. 10."""
    return COLOURS.get(label, COLOURS["simulator"])


def _by_height_lines(ax, groups, label, heights, value):
    colours = height_colours(heights if heights is not None else list(groups))
    for h, (periods, v) in groups.items():
        # a small marker too: a height with one period has no line to draw
        ax.plot(periods, value(v), SOURCE_LINES.get(label, "-."), marker=".", color=colours[h],
                label=f"H = {h:g} m ({value_label(label)})")


@_doc
def add_figure_8(ax, summaries, label: str = "simulator", heights=None):
    """Draw a model's amplitude of the hydrodynamic torque T_h against T, per height (Fig. 8).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        Axes of :func:`flumekit.figures.flap.figure_8` (or any Axes).
    summaries : xarray.Dataset or sequence of xarray.Dataset
        Run summaries of the model (``torque_amplitude`` [N m]).
    %(source_line)s
    %(heights)s

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``.

    %(references_brito2020)s, Fig. 8.
    """
    with style():
        _by_height_lines(ax, by_height(summaries, "torque_amplitude"), label, heights,
                         lambda v: v["torque_amplitude"])
    return ax


@_doc
def add_figure_9(axes, summaries, label: str = "simulator", heights=None):
    """Draw a model's (a) θ amplitude / π and (b) capture factor C_f against T (Fig. 9).

    Parameters
    ----------
    axes : sequence of matplotlib.axes.Axes
        Two Axes, as in the figure of :func:`flumekit.figures.flap.figure_9`.
    summaries : xarray.Dataset or sequence of xarray.Dataset
        Run summaries of the model (``theta_amplitude`` [rad], ``capture_factor`` [-]).
    %(source_line)s
    %(heights)s

    %(axes_drawn)s

    %(references_brito2020)s, Fig. 9.
    """
    if len(axes) != 2:
        raise ValueError("figure 9 needs two axes: (a) rotation, (b) capture factor")
    groups = by_height(summaries, "theta_amplitude", "capture_factor")
    with style():
        _by_height_lines(axes[0], groups, label, heights, lambda v: v["theta_amplitude"] / np.pi)
        _by_height_lines(axes[1], groups, label, heights, lambda v: v["capture_factor"])
    return axes


@_doc
def add_figure_10(axes, summary: xr.Dataset, sim: xr.Dataset | None = None,
                  label: str = "simulator"):
    """Draw a model's phase averages in the normalisation of Fig. 10.

    Panels as :func:`flumekit.figures.flap.figure_10`: (a) ⟨η⟩/H of the incident elevation
    that drove the simulation (needs ``sim`` with ``eta_incident``), (b) ⟨θ⟩/π, (c)
    ⟨W_out⟩/W_I with the mean as a dotted line, (d) ⟨θ̇⟩/(π ω). Cycles start at a zero
    up-crossing of the simulated θ, as for the experiment. Drawn dashed under the
    experiment's solid line, so both stay visible where they coincide.

    Parameters
    ----------
    axes : sequence of matplotlib.axes.Axes
        Four Axes (a)-(d); (a) may be None.
    summary : xarray.Dataset
        Summary of one simulated run (:func:`~flumekit.flap.summary.summarise_run`).
    sim : xarray.Dataset, optional
        The simulation itself, for panel (a) (``eta_incident`` [m]).
    label : str, optional
        Source name: its colour and legend label.

    %(axes_drawn)s

    %(references_brito2020)s, Fig. 10.
    """
    from flumekit import signal as sig

    axes = list(np.ravel(np.asarray(axes, dtype=object)))
    if len(axes) != 4:
        raise ValueError("figure 10 needs four axes (a)-(d)")
    for name in ("theta_phase_mean", "theta_dot_phase_mean", "power_phase_mean",
                 "incident_power", "mean_power", "measured_period", "incident_height"):
        if name not in summary.variables:
            raise ValueError(f"the simulated summary lacks '{name}'")
    phase = summary["phase"].values
    period = float(summary["measured_period"])
    kw = {"color": _colour(label), "ls": "--" if label == "simulator" else "-", "zorder": 4}
    with style():
        if sim is not None and "eta_incident" in sim and axes[0] is not None:
            pa = sig.phase_average(sim["eta_incident"].values, sim["time"].values, period,
                                   float(summary["steady_start"]), int(summary["steady_cycles"]),
                                   n_phase=phase.size)
            axes[0].plot(pa.phase, pa.mean / float(summary["incident_height"]), **kw)
        axes[1].plot(phase, summary["theta_phase_mean"].values / np.pi, **kw)
        w_i = float(summary["incident_power"])
        mean = float(summary["mean_power"]) / w_i
        axes[2].plot(phase, summary["power_phase_mean"].values / w_i,
                     label=rf"{value_label(label)}, $\overline{{W}}_{{out}}/W_I$ = {mean:.2f}",
                     **kw)
        axes[2].axhline(mean, color=_colour(label), ls=":", lw=1.0)
        omega = 2 * np.pi / period
        axes[3].plot(phase, summary["theta_dot_phase_mean"].values / (np.pi * omega), **kw)
    return axes
