"""Flap figures of Brito et al. 2020: Figs. 5b, 6b-d, 7, 8, 9 and 10 (experimental parts).

Every function reads processed flap datasets (output of :func:`flumekit.flap.analyse_run`, one
per run, or several concatenated along ``run``) and returns a matplotlib Figure built without
pyplot. Runs are grouped by the ``wave_height`` coordinate that the pipeline attaches, or else
by the incident height rounded to 5 mm.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from flumekit import signal as sig
from flumekit.figures.groups import by_height, height_of, period_of, runs_of
from flumekit.figures.style import COLOURS, figure_axes, new_figure, style

_MARKERS = ("o", "s", "^", "D", "v", "P", "X")


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


def _half_range(x: np.ndarray) -> float:
    return 0.5 * float(np.max(x) - np.min(x))


def figure_5b(flap: xr.Dataset, ax=None):
    """Full time series of the normalised flap angle θ/θ_s against t/T (Fig. 5b).

    θ_s is the amplitude θ of the quasi-steady window; the dash-dotted line marks θ/θ_s = 1 and
    the vertical line the start of the quasi-steady window.
    """
    _require(flap, "theta", "theta_amplitude", "measured_period", "steady_start")
    period = float(flap.measured_period)
    fig, ax = figure_axes(ax, figsize=(6.5, 2.4))
    with style():
        ax.plot(flap.time.values / period, flap.theta.values / float(flap.theta_amplitude),
                color=COLOURS["experiment"], lw=0.6)
        ax.axhline(1.0, color="0.3", ls="-.", lw=0.9, label="amplitude scale")
        ax.axvline(float(flap.steady_start) / period, color="tab:red", lw=0.9,
                   label="quasi-steady")
        ax.set_xlabel("t/T")
        ax.set_ylabel(r"$\theta/\theta_s$")
        ax.legend(loc="lower right", ncols=2, fontsize=7)
    return fig


def figure_6bcd(flap: xr.Dataset, start: float = 65.0, n_waves: int = 5, axes=None):
    """Normalised θ, P_int and θ̇ over ``n_waves`` periods from t/T = ``start`` (Fig. 6b-d).

    Each signal is divided by its amplitude scale (half the range of its phase average over
    the quasi-steady window; for P_int, whose suction side is clamped at the vapour pressure,
    the maximum of the phase average); dash-dotted lines mark ±1.

    Parameters
    ----------
    flap : Processed flap dataset of one run.
    start : First t/T shown [-] (the paper: 65).
    n_waves : Number of periods shown [-].
    axes : Three axes to draw into; default a new figure.
    """
    _require(flap, "theta", "chamber_pressure", "theta_dot", "theta_phase_mean",
             "chamber_pressure_phase_mean", "theta_dot_phase_mean", "measured_period")
    tt, sel, _ = _window(flap, start, n_waves)
    rows = [
        ("theta", _half_range(flap.theta_phase_mean.values), r"$\theta/\theta_s$", "(b)"),
        ("chamber_pressure", float(np.max(flap.chamber_pressure_phase_mean.values)),
         r"$P_{int}/P_s$", "(c)"),
        ("theta_dot", _half_range(flap.theta_dot_phase_mean.values),
         r"$\dot\theta/\dot\theta_s$", "(d)"),
    ]
    if axes is None:
        with style():
            fig, grid = new_figure(3, 1, figsize=(6.5, 5.5))
        axes = grid[:, 0]
        for ax in axes[1:]:
            ax.sharex(axes[0])
    fig = axes[0].figure
    with style():
        for ax, (name, scale, label, tag) in zip(axes, rows):
            ax.plot(tt[sel], flap[name].values[sel] / scale, color=COLOURS["experiment"])
            for level in (-1.0, 1.0):
                ax.axhline(level, color="0.3", ls="-.", lw=0.9)
            ax.set_ylabel(label)
            ax.set_title(tag, loc="left", fontsize=8)
        axes[-1].set_xlabel("t/T")
        axes[-1].set_xlim(start, start + n_waves)
    return fig


def figure_7(flaps, n_waves: int = 3, axes=None):
    """Measured and fitted torque of the cylinder pressure force (Fig. 7), one panel per run.

    Shows ``n_waves`` periods from the start of each run's quasi-steady window, with the R² of
    the fit of Eq. (13).
    """
    runs = runs_of(flaps)
    if axes is None:
        with style():
            fig, grid = new_figure(len(runs), 1, figsize=(6.5, 2.2 * len(runs)))
        axes = grid[:, 0]
    fig = axes[0].figure
    with style():
        for ax, ds, tag in zip(axes, runs, "abcdefgh"):
            _require(ds, "torque_pressure", "torque_pressure_fitted", "pressure_fit_r2",
                     "steady_start", "measured_period")
            t0 = float(ds.steady_start) / float(ds.measured_period)
            tt, sel, _ = _window(ds, t0, n_waves)
            ax.plot(tt[sel] - t0, ds.torque_pressure.values[sel], color=COLOURS["experiment"],
                    label="measured")
            ax.plot(tt[sel] - t0, ds.torque_pressure_fitted.values[sel],
                    color=COLOURS["analytical"], ls="--", label="fitted, Eq. (13)")
            ax.set_title(f"({tag}) T = {period_of(ds):g} s, H = {height_of(ds):g} m, "
                         f"R² = {float(ds.pressure_fit_r2):.3f}", loc="left", fontsize=8)
            ax.set_ylabel(r"$T_p$ [N m]")
            ax.legend(loc="upper right", fontsize=7)
        axes[-1].set_xlabel("t/T (from the start of the quasi-steady window)")
    return fig


def figure_8(flaps, ax=None):
    """Amplitude of the hydrodynamic torque against the wave period, per wave height (Fig. 8).

    The amplitude is half the difference of the mean per-cycle maximum and minimum of T_h over
    the quasi-steady window (``torque_amplitude``). Model curves can be added to the returned
    figure's axes.
    """
    groups = by_height(flaps, "torque_amplitude")
    fig, ax = figure_axes(ax, figsize=(4.5, 3.2))
    with style():
        for (h, (periods, v)), mk in zip(groups.items(), _MARKERS * 3):
            ax.plot(periods, v["torque_amplitude"], mk, color=COLOURS["experiment"],
                    mfc="none", label=f"H = {h:g} m (exp.)")
        ax.set_xlabel("T [s]")
        ax.set_ylabel(r"$|T_h|$ [N m]")
        ax.legend(fontsize=7)
    return fig


def figure_9(flaps, axes=None):
    """(a) Amplitude of θ and (b) capture factor C_f against the wave period (Fig. 9)."""
    groups = by_height(flaps, "theta_amplitude", "capture_factor")
    if axes is None:
        with style():
            fig, grid = new_figure(1, 2, figsize=(7.5, 3.0))
        axes = grid[0, :]
    fig = axes[0].figure
    with style():
        for (h, (periods, v)), mk in zip(groups.items(), _MARKERS * 3):
            kw = dict(color=COLOURS["experiment"], mfc="none", label=f"H = {h:g} m (exp.)")
            axes[0].plot(periods, v["theta_amplitude"] / np.pi, mk, **kw)
            axes[1].plot(periods, v["capture_factor"], mk, **kw)
        axes[0].set_ylabel(r"$|\theta|/\pi$")
        axes[1].set_ylabel(r"$C_f$")
        for ax, tag in zip(axes, "ab"):
            ax.set_xlabel("T [s]")
            ax.set_title(f"({tag})", loc="left", fontsize=8)
        axes[0].legend(fontsize=7)
    return fig


def figure_10(flap: xr.Dataset, eta: xr.DataArray | None = None, axes=None):
    """Normalised phase averages over the quasi-steady window (Fig. 10, experiment).

    Panels: (a) ⟨η⟩/H, (b) ⟨θ⟩/π, (c) ⟨W_out⟩/W_I with its mean as a dashed line, (d)
    ⟨θ̇⟩/(π ω), ω = 2π/T. The paper does not state its normalisation of θ̇; dividing by π ω gives
    a sinusoidal motion the same amplitude in (b) and (d). Cycles start at a zero up-crossing of
    θ (t/T = 0: the flap vertical and moving to the beach), as in the paper.

    Parameters
    ----------
    flap : Processed flap dataset of one run.
    eta : Surface elevation [m] on a ``time`` coordinate of the same clock (e.g. the probe
        nearest the flap from the waves dataset); phase-averaged here over the flap's window.
        Panel (a) is left empty without it.
    axes : Four axes to draw into; default a new figure.
    """
    _require(flap, "theta_phase_mean", "theta_dot_phase_mean", "power_phase_mean",
             "incident_power", "mean_power", "incident_height", "steady_start",
             "steady_cycles", "measured_period")
    phase = flap.phase.values
    period = float(flap.measured_period)
    if axes is None:
        with style():
            fig, grid = new_figure(2, 2, figsize=(7.0, 5.0))
        axes = grid.ravel()
    fig = axes[0].figure
    exp = dict(color=COLOURS["experiment"])
    with style():
        if eta is not None:
            if "time" not in eta.coords:
                raise ValueError("eta needs a 'time' coordinate")
            pa = sig.phase_average(eta.values, eta["time"].values, period,
                                   float(flap.steady_start), int(flap.steady_cycles),
                                   n_phase=phase.size)
            axes[0].plot(pa.phase, pa.mean / float(flap.incident_height), **exp)
        axes[0].set_ylabel(r"$\langle\eta\rangle/H$")
        axes[1].plot(phase, flap.theta_phase_mean.values / np.pi, **exp)
        axes[1].set_ylabel(r"$\langle\theta\rangle/\pi$")
        w_i = float(flap.incident_power)
        axes[2].plot(phase, flap.power_phase_mean.values / w_i, **exp)
        axes[2].axhline(float(flap.mean_power) / w_i, color="0.3", ls="--", lw=0.9,
                        label=rf"$\overline{{W}}_{{out}}/W_I$ = {float(flap.mean_power) / w_i:.2f}")
        axes[2].set_ylabel(r"$\langle W_{out}\rangle/W_I$")
        axes[2].legend(fontsize=7)
        omega = 2 * np.pi / period
        axes[3].plot(phase, flap.theta_dot_phase_mean.values / (np.pi * omega), **exp)
        axes[3].set_ylabel(r"$\langle\dot\theta\rangle/(\pi\omega)$")
        for ax, tag in zip(axes, "abcd"):
            ax.set_title(f"({tag})", loc="left", fontsize=8)
            ax.set_xlim(0, 1)
        for ax in axes[2:]:
            ax.set_xlabel("t/T")
    return fig
