"""Flap figures of Brito et al. 2020: Figs. 5b, 6b-d, 7, 8, 9 and 10.

Every function reads processed flap datasets (output of :func:`flumekit.flap.analyse_run`, one
per run, or several concatenated along ``run``) and returns a matplotlib Figure built without
pyplot. Runs are grouped by the ``wave_height`` coordinate that the pipeline attaches, or else
by the incident height rounded to 5 mm. Figs. 8-10 take the model curves (linear model,
simulator) as ``models``: ``{source: summaries}`` (see :mod:`flumekit.figures.simulator`).

%(references_brito2020)s.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from flumekit import signal as sig
from flumekit.docstrings import fill, filler
from flumekit.figures.groups import by_height, height_of, period_of, runs_of
from flumekit.figures.registry import register
from flumekit.figures.simulator import (
    MARKERS,
    SOURCE_LINES,
    add_figure_8,
    add_figure_9,
    add_figure_10,
    height_colours,
)
from flumekit.figures.snippets import SNIPPETS
from flumekit.figures.style import (
    COLOURS,
    ONE_COLUMN,
    TWO_COLUMNS,
    figure_axes,
    label,
    legend,
    long_name,
    new_figure,
    run_title,
    runs_title,
    thin,
    title,
    value_label,
)

__doc__ = fill(__doc__)

#: parameters that several figures of this module document alike, written once
_doc = filler(
    SNIPPETS,
    flap_run=("flap : xarray.Dataset\n"
              "    Processed flap dataset of one run (:func:`flumekit.flap.analyse_run`)."),
    regular_flaps=("flaps : xarray.Dataset or sequence of xarray.Dataset\n"
                   "    Processed flap datasets of the regular runs, or one stacked along "
                   "``run``."),
    model_summaries=("models : dict, optional\n"
                     "    {source: run summaries} of the models (``\"analytical\"``, "
                     "``\"simulator\"``)."))

_TIME_OVER_PERIOD = label(text="Time over wave period $t/T$", units="1")
_PERIOD = label("wave_period", "$T$", text="Wave period")


def _sorted_runs(data, params) -> tuple[tuple, dict]:
    """Arguments of Fig. 7: the flap datasets of its runs, in input-name order."""
    return ([data[k] for k in sorted(data)],), {}


def _experiment_and_models(data, params) -> tuple[tuple, dict]:
    """Return the arguments of Figs. 8-9 from the comparison datasets of every regular run.

    ``data["runs"]``: the comparison datasets stacked along ``run`` (in input-name order); the
    experiment's and, per model source, the model's.
    """
    comps = data["runs"]
    models = {str(s): comps.sel(source=s) for s in comps["source"].values
              if str(s) != "experiment"}
    return (comps.sel(source="experiment"),), {"models": models}


def _figure_10_data(data, params) -> tuple[tuple, dict]:
    """Return the arguments of Fig. 10 from a run's flap, waves and comparison datasets.

    The measured elevation at the probe nearest the flap over the whole record (the separated
    incident wave exists only in the waves' own steady window) and every model of the
    comparison.
    """
    eta = data["waves"]["eta"]
    comp = data["comparison"]
    models = {str(s): comp.sel(source=s) for s in comp["source"].values
              if str(s) != "experiment"}
    return (data["flap"],), {"eta": eta.isel(probe=int(np.argmin(np.abs(eta["x"].values)))),
                             "models": models}


def _require(ds: xr.Dataset, *names: str) -> None:
    missing = [n for n in names if n not in ds.variables]
    if missing:
        raise ValueError(f"the flap dataset lacks {missing}: pass the output of "
                         "flumekit.flap.analyse_run")


def _window(ds: xr.Dataset, start: float, n_waves: int) -> tuple[np.ndarray, np.ndarray, float]:
    period = float(ds.measured_period)
    tt = ds.time.values / period
    if start < tt[0] or start + n_waves > tt[-1]:
        raise ValueError(f"t/T = {start}..{start + n_waves} is outside the record "
                         f"(t/T = {tt[0]:.1f}..{tt[-1]:.1f})")
    sel = (tt >= start) & (tt <= start + n_waves)
    return tt, sel, period


def _levels(phase_mean: np.ndarray, scale: float) -> tuple[float, float]:
    """Return the crest and trough of the quasi-steady cycle (its phase average) over ``scale``.

    Where the normalised series peaks, whatever its mean (a flap leaning seaward, a clamped
    suction side).
    """
    return float(np.max(phase_mean)) / scale, float(np.min(phase_mean)) / scale


def _crest_trough(ax, levels, lab: str | None = "crest and trough of the steady cycle"):
    for k, level in enumerate(levels):
        ax.axhline(level, color="0.3", ls="-.", lw=0.9, label=lab if k == 0 else None)


@register("fig05b")
@_doc
def figure_5b(flap: xr.Dataset, ax=None):
    """Draw the full time series of the normalised flap angle θ/θ_s against t/T (Fig. 5b).

    θ_s is the amplitude of θ over the quasi-steady window (half the mean crest-to-trough
    range); the dash-dotted lines mark the crest and trough of the steady cycle, θ/θ_s =
    (θ̄ ± θ_s)/θ_s with θ̄ its centre, so they meet the steady crests and troughs even when
    the flap oscillates about a leaning mean. The vertical line is the start of the window.

    Parameters
    ----------
    %(flap_run)s
    ax : matplotlib.axes.Axes, optional
        Axes to draw into; default a new two-column figure.

    Returns
    -------
    matplotlib.figure.Figure
        θ/θ_s [-] against t/T [-].

    %(references_brito2020)s, Fig. 5b.

    Examples
    --------
    A flap leaning 0.05 rad seaward and swinging 0.2 rad about that mean, steady after 10 s:

    >>> import numpy as np
    >>> import xarray as xr
    >>> from flumekit.figures import figure_5b
    >>> t, phase = np.arange(0.0, 30.0, 0.05), np.arange(40) / 40
    >>> theta = -0.05 + 0.2 * np.minimum(t / 10.0, 1.0) * np.sin(np.pi * t)
    >>> flap = xr.Dataset({"theta": ("time", theta), "theta_amplitude": 0.2,
    ...                    "theta_phase_mean": ("phase", -0.05 + 0.2 * np.sin(2 * np.pi * phase)),
    ...                    "measured_period": 2.0, "steady_start": 10.0},
    ...                   coords={"time": t, "phase": phase})
    >>> fig = figure_5b(flap)
    >>> crest, trough = (float(line.get_ydata()[0]) for line in fig.axes[0].lines[1:3])
    >>> round(crest, 2), round(trough, 2)  # (-0.05 ± 0.2) / 0.2: off-centre like the flap
    (0.75, -1.25)
    """
    _require(flap, "theta", "theta_amplitude", "theta_phase_mean", "measured_period",
             "steady_start")
    period = float(flap.measured_period)
    scale = float(flap.theta_amplitude)
    fig, ax = figure_axes(ax, height=2.4)
    ax.plot(*thin(flap.time.values / period, flap.theta.values / scale, fig.get_figwidth()),
            color=COLOURS["experiment"], lw=0.5, label="measured")
    _crest_trough(ax, _levels(flap.theta_phase_mean.values, scale))
    ax.axvline(float(flap.steady_start) / period, color="tab:red", lw=0.9,
               label="start of the quasi-steady window")
    ax.set_xlabel(_TIME_OVER_PERIOD)
    ax.set_ylabel(label(text=r"$\theta/\theta_s$", units="1"))
    title(fig, run_title(flap, "Normalised flap rotation")
          + rf", $\theta_s$ = {np.degrees(scale):.1f}°")
    legend(fig)
    return fig


@register("fig06bcd")
@_doc
def figure_6bcd(flap: xr.Dataset, start: float = 65.0, n_waves: int = 5, axes=None):
    r"""Draw normalised θ, P_int and θ̇ over ``n_waves`` periods from t/T = ``start`` (Fig. 6b-d).

    Panels (a)-(c) of this figure are the paper's Fig. 6b-d. Each signal is divided by its
    amplitude scale (half the range of its phase average over the quasi-steady window; for
    P_int, whose suction side is clamped at the vapour pressure, the maximum of the phase
    average), stated in the panel's title; dash-dotted lines mark the crest and trough of the
    phase average, which the steady cycles meet.

    Parameters
    ----------
    %(flap_run)s
    %(fig6_window)s
    axes : sequence of matplotlib.axes.Axes, optional
        Three axes to draw θ, P_int and θ̇ into, top to bottom; default a new figure.

    Returns
    -------
    matplotlib.figure.Figure
        Normalised θ, P_int and θ̇ [-] against t/T [-].

    %(references_brito2020)s, Fig. 6b-d.

    Examples
    --------
    Each panel's scale is stated in its title; the chamber pressure, clamped at -10 kPa on its
    suction side, is scaled by its crest (40 kPa):

    >>> import numpy as np
    >>> import xarray as xr
    >>> from flumekit.figures import figure_6bcd
    >>> t, phase = np.arange(0.0, 20.0, 0.02), np.arange(40) / 40
    >>> def signals(angle):  # θ [rad], P_int [Pa], θ̇ [rad/s] of a period of 2 s
    ...     return {"theta": 0.2 * np.sin(angle), "theta_dot": 0.2 * np.pi * np.cos(angle),
    ...             "chamber_pressure": np.maximum(4e4 * np.sin(angle), -1e4)}
    >>> flap = xr.Dataset(
    ...     {**{k: ("time", v) for k, v in signals(np.pi * t).items()},
    ...      **{f"{k}_phase_mean": ("phase", v) for k, v in signals(2 * np.pi * phase).items()},
    ...      "measured_period": 2.0}, coords={"time": t, "phase": phase})
    >>> fig = figure_6bcd(flap, start=4.0, n_waves=3)
    >>> for ax in fig.axes:
    ...     print(ax.get_title(loc="left"))
    (a) Flap rotation angle, $\theta_s$ = 11.5°
    (b) Gauge pressure in the PTO cylinder chamber, $P_s$ = 40 kPa
    (c) Flap angular velocity, $\dot\theta_s$ = 0.63 rad/s
    """
    _require(flap, "theta", "chamber_pressure", "theta_dot", "theta_phase_mean",
             "chamber_pressure_phase_mean", "theta_dot_phase_mean", "measured_period")
    tt, sel, _ = _window(flap, start, n_waves)
    rows = []
    for name, sym, half, shown in (
            ("theta", r"$\theta/\theta_s$", True,
             lambda v: rf"$\theta_s$ = {np.degrees(v):.1f}°"),
            ("chamber_pressure", r"$P_{int}/P_s$", False,
             lambda v: f"$P_s$ = {v / 1e3:.0f} kPa"),
            ("theta_dot", r"$\dot\theta/\dot\theta_s$", True,
             lambda v: rf"$\dot\theta_s$ = {v:.2f} rad/s")):
        pm = flap[f"{name}_phase_mean"].values
        scale = 0.5 * float(np.ptp(pm)) if half else float(np.max(pm))
        rows.append((name, scale, sym, pm, shown(scale)))
    if axes is None:
        fig, grid = new_figure(3, 1, width=TWO_COLUMNS, row_height=1.6, sharex=True)
        axes = grid[:, 0]
    fig = axes[0].figure
    for ax, (name, scale, sym, pm, stated), tag in zip(axes, rows, "abc"):
        ax.plot(tt[sel], flap[name].values[sel] / scale, color=COLOURS["experiment"],
                label="measured")
        _crest_trough(ax, _levels(pm, scale))
        ax.set_ylabel(label(text=sym, units="1"))
        ax.set_title(f"({tag}) {long_name(name)}, {stated}")
    axes[-1].set_xlabel(_TIME_OVER_PERIOD)
    axes[-1].set_xlim(start, start + n_waves)
    title(fig, run_title(flap, "Flap rotation, chamber pressure and angular velocity"))
    legend(fig)
    return fig


@register("fig07", prepare=_sorted_runs)
@_doc
def figure_7(flaps, n_waves: int = 3, axes=None):
    """Draw the measured and fitted torque of the cylinder pressure force (Fig. 7), per run.

    Shows ``n_waves`` periods from the start of each run's quasi-steady window, with the R² of
    the fit of Eq. (13). Two columns of panels when there are more than three runs.

    Parameters
    ----------
    flaps : xarray.Dataset or sequence of xarray.Dataset
        Processed flap datasets, one per run, or one stacked along ``run``.
    n_waves : int, optional
        Number of periods shown per run [-].
    axes : sequence of matplotlib.axes.Axes, optional
        One axes per run to draw into; default a new figure.

    Returns
    -------
    matplotlib.figure.Figure
        Pressure torque [N m] against t/T [-], one panel per run.

    %(references_brito2020)s, Fig. 7 and Eq. (13).

    Examples
    --------
    Two runs whose fitted torque is 0.9 times the measured, so R² = 1 - 0.1² = 0.99:

    >>> import numpy as np
    >>> import xarray as xr
    >>> from flumekit.figures import figure_7
    >>> t = np.arange(0.0, 24.0, 0.04)
    >>> def run(period):
    ...     tp = 800.0 * np.sin(2 * np.pi * t / period)  # [N m]
    ...     return xr.Dataset({"torque_pressure": ("time", tp),
    ...                        "torque_pressure_fitted": ("time", 0.9 * tp),
    ...                        "pressure_fit_r2": 0.99, "steady_start": 4 * period,
    ...                        "measured_period": period},
    ...                       coords={"time": t, "wave_period": period, "wave_height": 0.2})
    >>> fig = figure_7([run(2.0), run(3.0)], n_waves=2)
    >>> [ax.get_title(loc="left") for ax in fig.axes]
    ['(a) T = 2 s, H = 0.2 m, R² = 0.990', '(b) T = 3 s, H = 0.2 m, R² = 0.990']
    """
    runs = runs_of(flaps)
    if axes is None:
        ncols = 1 if len(runs) <= 3 else 2
        nrows = int(np.ceil(len(runs) / ncols))
        fig, grid = new_figure(nrows, ncols, width=TWO_COLUMNS, row_height=1.7)
        axes = grid.ravel()[:len(runs)]
        for ax in grid.ravel()[len(runs):]:
            fig.delaxes(ax)
    fig = axes[0].figure
    wide = axes[0].get_position().width > 0.5
    for ax, ds, tag in zip(axes, runs, "abcdefghijklmnop"):
        _require(ds, "torque_pressure", "torque_pressure_fitted", "pressure_fit_r2",
                 "steady_start", "measured_period")
        t0 = float(ds.steady_start) / float(ds.measured_period)
        tt, sel, _ = _window(ds, t0, n_waves)
        ax.plot(tt[sel] - t0, ds.torque_pressure.values[sel], color=COLOURS["experiment"],
                label="measured")
        ax.plot(tt[sel] - t0, ds.torque_pressure_fitted.values[sel],
                color=COLOURS["analytical"], ls="--", label="fitted, Eq. (13)")
        cond = f"T = {period_of(ds):g} s, H = {height_of(ds):g} m"
        if "run" in ds.variables:  # a narrow panel names the run only (its id tells T, H)
            cond = f"run {ds['run'].values}" + (f": {cond}" if wide else "")
        ax.set_title(f"({tag}) {cond}, R² = {float(ds.pressure_fit_r2):.3f}")
        ax.set_ylabel(label("torque_pressure", "$T_p$", text="Pressure torque"))
        ax.set_xlabel(label(text="$t/T$ from the steady start", units="1"))
    title(fig, runs_title(runs, "Torque of the cylinder pressure force"))
    legend(fig)
    return fig


def _source_handles(heights: list[float], sources: list[str]):
    """Legend proxies: a colour and marker per wave height, a line style per source."""
    from matplotlib.lines import Line2D

    colours = height_colours(heights)
    handles = [Line2D([], [], color=colours[h], marker=m, ls="none", mfc="none",
                      label=f"H = {h:g} m") for h, m in zip(heights, MARKERS * 3)]
    for s in sources:
        if s == "experiment":
            handles.append(Line2D([], [], color="0.2", marker="o", mfc="none", ls="none",
                                  label=value_label(s)))
        else:
            handles.append(Line2D([], [], color="0.2", ls=SOURCE_LINES.get(s, "-."),
                                  label=value_label(s)))
    return handles


def _experiment_points(ax, groups, heights, transform=lambda v: v):
    colours = height_colours(heights)
    for (h, (periods, v)), mk in zip(groups.items(), MARKERS * 3):
        ax.plot(periods, transform(v), mk, color=colours[h], mfc="none", zorder=3)


def _heights(flaps, models) -> list[float]:
    runs = runs_of(flaps) + [r for m in (models or {}).values() for r in runs_of(m)]
    return sorted({height_of(r) for r in runs})


@register("fig08", prepare=_experiment_and_models, stacked=True)
@_doc
def figure_8(flaps, models: dict | None = None, ax=None):
    """Draw the amplitude of the hydrodynamic torque against the wave period (Fig. 8).

    One colour per wave height. The amplitude is half the difference of the mean per-cycle
    maximum and minimum of T_h over the quasi-steady window (``torque_amplitude``). Markers:
    the experiment; lines: the ``models``, one line style per source.

    Parameters
    ----------
    %(regular_flaps)s
    %(model_summaries)s
    ax : matplotlib.axes.Axes, optional
        Axes to draw into; default a new figure.

    Returns
    -------
    matplotlib.figure.Figure
        T_h amplitude [N m] against T [s].

    %(references_brito2020)s, Fig. 8.

    Examples
    --------
    Four runs stacked along ``run``, as the comparison stage gives them, and a model 10 %
    above them: one series of markers per wave height, sorted by period, then the model's
    lines:

    >>> import xarray as xr
    >>> from flumekit.figures import figure_8
    >>> runs = xr.Dataset({"torque_amplitude": ("run", [180.0, 120.0, 260.0, 150.0])},
    ...                   coords={"wave_period": ("run", [3.0, 2.0, 3.0, 2.0]),
    ...                           "wave_height": ("run", [0.1, 0.1, 0.2, 0.2])})
    >>> fig = figure_8(runs, models={"analytical": runs * 1.1})
    >>> for line in fig.axes[0].lines:
    ...     print(line.get_xdata().tolist(), line.get_ydata().round(1).tolist())
    [2.0, 3.0] [120.0, 180.0]
    [2.0, 3.0] [150.0, 260.0]
    [2.0, 3.0] [132.0, 198.0]
    [2.0, 3.0] [165.0, 286.0]
    """
    groups = by_height(flaps, "torque_amplitude")
    heights = _heights(flaps, models)
    fig, ax = figure_axes(ax, width=ONE_COLUMN, height=3.9)
    _experiment_points(ax, groups, heights, lambda v: v["torque_amplitude"])
    for source, runs in (models or {}).items():
        add_figure_8(ax, runs, label=source, heights=heights)
    ax.set_xlabel(_PERIOD)
    ax.set_ylabel(label("torque_amplitude", "$|T_h|$", text="Hydrodynamic torque"))
    title(fig, runs_title(flaps, "Torque amplitude"))
    legend(fig, _source_handles(heights, ["experiment", *(models or {})]), ncols=2)
    return fig


@register("fig09", prepare=_experiment_and_models, stacked=True)
@_doc
def figure_9(flaps, models: dict | None = None, axes=None):
    """Draw (a) the amplitude of θ and (b) the capture factor C_f against the period (Fig. 9).

    Markers: the experiment; lines: the ``models``.

    Parameters
    ----------
    %(regular_flaps)s
    %(model_summaries)s
    axes : sequence of matplotlib.axes.Axes, optional
        Two axes, for (a) the rotation and (b) the capture factor; default a new figure.

    Returns
    -------
    matplotlib.figure.Figure
        (a) θ amplitude / π [-] and (b) C_f [-] against T [s].

    %(references_brito2020)s, Fig. 9.

    Examples
    --------
    Two runs given as a list: (a) shows the amplitude of θ over π, (b) the capture factor:

    >>> import numpy as np
    >>> import xarray as xr
    >>> from flumekit.figures import figure_9
    >>> runs = [xr.Dataset({"theta_amplitude": np.pi * a, "capture_factor": cf,
    ...                     "wave_period": period, "wave_height": 0.2})
    ...         for period, a, cf in ((2.0, 0.1, 0.3), (3.0, 0.2, 0.4))]
    >>> rotation, capture = figure_9(runs).axes
    >>> rotation.lines[0].get_ydata().tolist(), capture.lines[0].get_ydata().tolist()
    ([0.1, 0.2], [0.3, 0.4])
    """
    groups = by_height(flaps, "theta_amplitude", "capture_factor")
    heights = _heights(flaps, models)
    if axes is None:
        fig, grid = new_figure(1, 2, width=TWO_COLUMNS, height=3.0)
        axes = grid[0, :]
    fig = axes[0].figure
    _experiment_points(axes[0], groups, heights, lambda v: v["theta_amplitude"] / np.pi)
    _experiment_points(axes[1], groups, heights, lambda v: v["capture_factor"])
    for source, runs in (models or {}).items():
        add_figure_9(axes, runs, label=source, heights=heights)
    axes[0].set_ylabel(label(text=r"Rotation amplitude $|\theta|/\pi$", units="1"))
    axes[1].set_ylabel(label("capture_factor", "$C_f$", text="Capture factor"))
    for ax, tag in zip(axes, "ab"):
        ax.set_xlabel(_PERIOD)
        ax.set_title(f"({tag})")
    title(fig, runs_title(flaps, "Flap rotation and capture factor"))
    handles = _source_handles(heights, ["experiment", *(models or {})])
    legend(fig, handles, where="right")
    return fig


@register("fig10", prepare=_figure_10_data)
@_doc
def figure_10(flap: xr.Dataset, eta: xr.DataArray | None = None, models: dict | None = None,
              axes=None):
    r"""Draw the normalised phase averages over the quasi-steady window (Fig. 10).

    Panels: ⟨η⟩/H (only with ``eta``), ⟨θ⟩/π, ⟨W_out⟩/W_I with its mean over the cycle
    dotted, ⟨θ̇⟩/(π ω), ω = 2π/T, lettered from (a) in the order shown; each panel's title
    states its scale (H, W_I, ω). The paper does not state its normalisation of θ̇;
    dividing by π ω gives a sinusoidal motion the same amplitude in (b) and (d). Cycles start
    at a zero up-crossing of θ (t/T = 0: the flap vertical and moving to the beach), as in the
    paper. The experiment is drawn on top (thick black) so that model curves that coincide
    with it do not hide it.

    Parameters
    ----------
    %(flap_run)s
    eta : xarray.DataArray, optional
        Surface elevation [m] on a ``time`` coordinate of the same clock (e.g. the probe
        nearest the flap from the waves dataset); phase-averaged here over the flap's window.
        Without it the figure has three panels.
    models : dict, optional
        {source: summary of that source for this run} (``"analytical"``, ``"simulator"``),
        drawn with :func:`flumekit.figures.simulator.add_figure_10`.
    axes : sequence of matplotlib.axes.Axes, optional
        Four axes (a)-(d) to draw into (``None`` for (a) to skip it); default a new figure.

    Returns
    -------
    matplotlib.figure.Figure
        The normalised phase averages [-] against t/T [-].

    %(references_brito2020)s, Fig. 10.

    Examples
    --------
    A sinusoidal motion θ = A sin 2πt/T against a linear damper P = ν θ̇²: dividing θ̇ by π ω
    gives it the amplitude of θ/π, A/π:

    >>> import numpy as np
    >>> import xarray as xr
    >>> from flumekit.figures import figure_10
    >>> period, amplitude, nu = 2.0, 0.3, 50.0  # [s], [rad], [N m s]
    >>> phase = np.arange(40) / 40
    >>> theta_dot = amplitude * 2 * np.pi / period * np.cos(2 * np.pi * phase)
    >>> flap = xr.Dataset(
    ...     {"theta_phase_mean": ("phase", amplitude * np.sin(2 * np.pi * phase)),
    ...      "theta_dot_phase_mean": ("phase", theta_dot),
    ...      "power_phase_mean": ("phase", nu * theta_dot**2),
    ...      "mean_power": nu * np.mean(theta_dot**2), "incident_power": 40.0,
    ...      "incident_height": 0.2, "steady_start": 10.0, "steady_cycles": 5,
    ...      "measured_period": period}, coords={"phase": phase})
    >>> fig = figure_10(flap)  # without eta: three panels, θ, W_out and θ̇
    >>> rotation, power, velocity = fig.axes
    >>> [round(float(max(ax.lines[0].get_ydata())), 4) for ax in (rotation, velocity)]
    [0.0955, 0.0955]
    >>> fig.legends[0].get_texts()[0].get_text()  # ν A² ω² / 2 = 22.2 W over W_I = 40 W
    'experiment, $\\overline{W}_{out}/W_I$ = 0.56'
    """
    _require(flap, "theta_phase_mean", "theta_dot_phase_mean", "power_phase_mean",
             "incident_power", "mean_power", "incident_height", "steady_start",
             "steady_cycles", "measured_period")
    phase = flap.phase.values
    period = float(flap.measured_period)
    if axes is None:
        if eta is None:
            fig, grid = new_figure(1, 3, width=TWO_COLUMNS, height=2.9)
            axes = [None, *grid[0]]
        else:
            fig, grid = new_figure(2, 2, width=TWO_COLUMNS, height=4.9)
            axes = list(grid.ravel())
    axes = list(axes)
    fig = next(ax for ax in axes if ax is not None).figure
    w_i = float(flap.incident_power)
    exp = dict(color=COLOURS["experiment"], lw=1.6, zorder=3)
    if eta is not None and axes[0] is not None:
        if "time" not in eta.coords:
            raise ValueError("eta needs a 'time' coordinate")
        pa = sig.phase_average(eta.values, eta["time"].values, period,
                               float(flap.steady_start), int(flap.steady_cycles),
                               n_phase=phase.size)
        axes[0].plot(pa.phase, pa.mean / float(flap.incident_height), **exp)
        probe = f", probe {eta['probe'].values}" if "probe" in eta.coords else ""
        axes[0].set_ylabel(label(text=r"$\langle\eta\rangle/H$" + probe, units="1"))
    axes[1].plot(phase, flap.theta_phase_mean.values / np.pi, **exp)
    axes[1].set_ylabel(label(text=r"$\langle\theta\rangle/\pi$", units="1"))
    mean = float(flap.mean_power) / w_i
    axes[2].plot(phase, flap.power_phase_mean.values / w_i,
                 label=rf"experiment, $\overline{{W}}_{{out}}/W_I$ = {mean:.2f}", **exp)
    axes[2].axhline(mean, color=COLOURS["experiment"], ls=":", lw=1.0)
    axes[2].set_ylabel(label(text=r"$\langle W_{out}\rangle/W_I$", units="1"))
    omega = 2 * np.pi / period
    axes[3].plot(phase, flap.theta_dot_phase_mean.values / (np.pi * omega), **exp)
    axes[3].set_ylabel(label(text=r"$\langle\dot\theta\rangle/(\pi\omega)$", units="1"))
    for source, summary in (models or {}).items():
        add_figure_10(axes, summary, label=source)
    h_i = float(flap.incident_height)
    scales = (f"$H$ = {h_i:.3f} m", None, f"$W_I$ = {w_i:.3g} W",
              rf"$\omega$ = {omega:.2f} rad/s")
    shown = [(ax, s) for ax, s in zip(axes, scales) if ax is not None]
    for (ax, stated), tag in zip(shown, "abcd"):
        ax.set_title(f"({tag})" + (f" {stated}" if stated else ""))
        ax.set_xlim(0, 1)
        ax.set_xlabel(_TIME_OVER_PERIOD)
    title(fig, run_title(flap, "Phase averages") + "; dotted: mean over the cycle")
    # one entry per source, with its mean power, from panel (c)
    legend(fig, *axes[2].get_legend_handles_labels(), ncols=2)
    return fig
