"""A measured flume run beside the linear model and the time-domain simulator.

The experiment (:func:`flumekit.flap.analysis.analyse_run`), the linear model (Brito et al.
2020, Eq. A1) and the simulator (:func:`flumekit.flap.simulator.simulate_run`) side by side
along a ``source`` dimension, from one hydrodynamic coefficient container
(:func:`flumekit.flap.renzi_dias.model.channel_container`, or :func:`bem_container`).

The linear model's PTO damping ν_pto (``linear_pto_damping``, :data:`LINEAR_PTO_DAMPING`):

* ``"energy_equivalent"`` (default): from the measured PTO by energy equivalence over the steady
  window, ν_pto = W̄_out / mean(θ̇²), so that it absorbs the same mean power at the measured
  motion;
* ``"optimal"``: the damping that maximises the linear model's mean power at the run's period,
  ν_opt = √((C − ω²(I + μ))²/ω² + ν²) (Renzi & Dias 2012, Eq. 2.40;
  :func:`flumekit.hydro.response.optimal_pto_damping`).

Brito et al. (2020, App. A) say only that ν_PTO was "calculated following [14]" (Renzi & Dias
2012). On the virtual flume's T = 3.5 s, H = 0.25 m run the optimal damping
(≈ 150 N m s: the flap is near resonance, so ν_opt ≈ ν) gives C_f ≈ 0.57, the channel's bound
b/(2w), and a linear θ 4.5 times the measured one (78 % below), far from the paper's 0.33 and
37 %; the energy-equivalent damping (≈ 450 N m s: C_f 0.43, 54 % below) is closer, hence the
default. With these coefficients the paper's pair (0.33, 37 %) needs ν_pto ≈ 700 N m s, more
than the energy-equivalent damping of a motion of the measured size: the paper's linear
model did not take its ν_PTO from the measured power either (with one ν for both, 0.33/0.12
would equal (1/0.63)² for a harmonic motion).

The simulator uses the fitted hydraulic model (K_p, I_p) and the campaign's LuGre
friction, driven by the separated incident wave at x = 0, and is summarised as the measured run
is (:func:`flumekit.flap.summary.summary`).

An irregular run (:func:`compare_irregular_run`) has no window or phase: the linear model is
the spectral sum of Eq. (A1) over the incident spectrum (:func:`spectral_response`), the
simulator is driven by the separated incident wave over the analysed span, and the three give
the mean power, capture width and capture width ratio with the same J.

%(references_brito2020)s, Appendix A.
%(renzi_dias2012)s (RD12).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import xarray as xr

from flumekit import conventions
from flumekit.campaign import PTO, Flap
from flumekit.docstrings import fill, filler
from flumekit.signal import uniform_step

#: docstring text that several functions of this module share
_doc = filler(
    returns_damping=("Returns\n"
                     "-------\n"
                     "float\n"
                     "    ν_pto [N m s]."),
    returns_incident=("Returns\n"
                      "-------\n"
                      "xarray.DataArray\n"
                      "    ``eta_incident`` [m] over the extended ``time`` [s]."),
    simulator_dt=("dt : float\n"
                  "    Simulator time step [s]."),
    simulator_dt_optional=("dt : float, optional\n"
                           "    Simulator time step [s]."),
    flap_params=("flap_params : flumekit.campaign.Flap\n"
                 "    The flap (inertia, width)."),
    flap_params_compared=("flap_params : flumekit.campaign.Flap\n"
                          "    The flap (inertia, buoyancy stiffness, width)."),
    friction=("friction : bool, optional\n"
              "    Include the LuGre friction."),
    with_friction=("friction : bool, optional\n"
                   "    Include the LuGre friction in the simulator."),
    linear_pto_damping=("linear_pto_damping : {\"energy_equivalent\", \"optimal\"}, optional\n"
                        "    How the linear model's ν_pto is set (:data:`LINEAR_PTO_DAMPING`, "
                        "module notes)."),
    hydro_written=("hydro : xarray.Dataset\n"
                   "    Coefficient container as written (real and imaginary parts)."),
    hydro_stored=("hydro : xarray.Dataset\n"
                  "    Coefficient container as stored (:func:`stored_container`)."),
    inertia=("inertia : float\n"
             "    Flap moment of inertia about the hinge [kg m2]."),
    pto=("pto : flumekit.campaign.PTO\n"
         "    The PTO (anchors, bore, pressures, LuGre friction)."),
    simulator=("simulator : bool, optional\n"
               "    Run the simulator (else experiment and linear model only)."),
    spin_up_periods=("spin_up_periods : int, optional\n"
                     "    Periods of ramped spin-up before the steady incident wave."),
    stiffness=("stiffness : float\n"
               "    Hydrostatic stiffness C [N m rad-1]."))

__doc__ = fill(__doc__)

#: scalars and phase averages compared along ``source``
SCALARS = ("theta_amplitude", "torque_amplitude", "mean_power", "capture_factor")
PHASED = ("theta_phase_mean", "theta_dot_phase_mean", "power_phase_mean")
#: ways of setting the linear model's PTO damping (module notes), the default first
LINEAR_PTO_DAMPING = ("energy_equivalent", "optimal")
_DAMPING_COMMENT = {
    "energy_equivalent": "linear-model PTO damping from the measured PTO by energy equivalence: "
                         "mean power / mean(theta_dot^2)",
    "optimal": "linear-model PTO damping maximising its mean power at the run's period, "
               "Renzi & Dias (2012) Eq. (2.40)"}


@_doc
def bem_container(depth: float, flap_width: float, hinge_height: float, thickness: float,
                  hydrostatic_stiffness: float, omega: tuple[float, float, int],
                  panel_size: float) -> xr.Dataset:
    """Build the coefficient container of the thick flap on its foundation by BEM, with A∞.

    Open water: the channel walls are not modelled. Capytaine's finite-depth Green function
    needs kh above about 0.15: the low-frequency end is held constant by the impulse response
    (:mod:`flumekit.hydro.radiation`).

    Parameters
    ----------
    %(depth)s
    %(flap_width)s
    hinge_height : float
        Hinge height above the bed [m].
    thickness : float
        Flap thickness [m].
    hydrostatic_stiffness : float
        C [N m rad-1].
    omega : tuple of (float, float, int)
        (ω_min [rad s-1], ω_max [rad s-1], n) of evenly spaced angular frequencies.
    panel_size : float
        Panel size of the mesh [m].

    Returns
    -------
    xarray.Dataset
        The container of :func:`flumekit.hydro.coefficients.hydro_dataset` with
        ``added_inertia_infinite`` [kg m2] from the Ogilvie relation (median, spread not
        checked).

    Raises
    ------
    flumekit.errors.FlumekitError
        Capytaine is not installed.
    """
    from flumekit.errors import FlumekitError
    from flumekit.flap import bem
    from flumekit.hydro import coefficients as hy

    if not bem.available():
        raise FlumekitError("[stages.models] coefficients = 'bem' needs Capytaine: "
                            "pip install 'flumekit[bem]'")
    w = np.linspace(*omega)
    coeffs = bem.coefficients(2 * np.pi / w[::-1], depth, flap_width, hinge_height,
                              thickness, panel_size=panel_size)
    return hy.with_infinite_frequency_inertia(hy.from_renzi_dias(coeffs, hydrostatic_stiffness),
                                              max_spread=None)


def stored_container(container: xr.Dataset, irf_duration: float = 30.0) -> xr.Dataset:
    """Return the coefficient container as the comparison stores it, with the radiation model.

    Real and imaginary parts, and the simulator's radiation model fitted once for every run:
    the radiation kernel K(t) over ``irf_duration`` (sampled at 0.01 s) is fitted by the
    state-space model of :func:`flumekit.hydro.radiation.fit_state_space`, stored by
    :func:`flumekit.hydro.radiation.state_space_dataset` (read back by :func:`simulated`).

    Parameters
    ----------
    container : xarray.Dataset
        Coefficient container (:mod:`flumekit.hydro.coefficients`) with
        ``added_inertia_infinite``.
    irf_duration : float, optional
        Length of the fitted impulse response [s].

    Returns
    -------
    xarray.Dataset
        The container with complex variables split and the state-space poles [s-1] and
        residues [N m] over ``radiation_mode``.
    """
    from flumekit.hydro.coefficients import split_complex
    from flumekit.hydro.radiation import fit_state_space, impulse_response, state_space_dataset

    radiation = state_space_dataset(fit_state_space(impulse_response(container, irf_duration,
                                                                     0.01)))
    return split_complex(container).merge(radiation, combine_attrs="no_conflicts")


@_doc
def energy_equivalent_damping(flap: xr.Dataset,
                              window: tuple[str, str] = ("steady_start", "steady_end")) -> float:
    """Return the PTO damping that absorbs the measured mean power at the measured θ̇.

    ν_pto = W̄_out / mean(θ̇²) over the steady window.

    Parameters
    ----------
    flap : xarray.Dataset
        A regular run's flap product: ``theta_dot`` [rad s-1] over ``time`` [s],
        ``mean_power`` [W], ``steady_start`` and ``steady_end`` [s].
    window : tuple of str
        The names of the window's start and end [s] in ``flap``.

    %(returns_damping)s

    Examples
    --------
    >>> import numpy as np, xarray as xr
    >>> from flumekit.flap.comparison import energy_equivalent_damping
    >>> t = np.arange(0.0, 10.0, 0.01)
    >>> flap = xr.Dataset({"theta_dot": ("time", 0.2 * np.sin(2 * np.pi * t)),
    ...                    "mean_power": 2.0, "steady_start": 0.0, "steady_end": 9.99},
    ...                   coords={"time": t})
    >>> round(energy_equivalent_damping(flap), 3)  # 2 W / (0.2² / 2)
    100.0
    """
    t = flap["time"].values
    inside = (t >= float(flap[window[0]])) & (t <= float(flap[window[1]]))
    return float(flap["mean_power"]) / float(np.mean(flap["theta_dot"].values[inside] ** 2))


def coefficients_at(hydro: xr.Dataset, period) -> xr.Dataset:
    """Interpolate the coefficient container to one period or an array of periods.

    Cubic interpolation over the frequency grid, into the layout of
    :func:`flumekit.hydro.response.response`.

    Parameters
    ----------
    hydro : xarray.Dataset
        Coefficient container as written (real and imaginary parts over
        ``angular_frequency`` [rad s-1]).
    period : float or array_like
        Wave period(s) [s].

    Returns
    -------
    xarray.Dataset
        ``added_inertia`` [kg m2], ``radiation_damping`` [N m s] and
        ``excitation_torque_real``/``_imag`` [N m m-1] over ``period`` [s], with the
        container's attributes.
    """
    names = ["added_inertia", "radiation_damping", "excitation_torque_real",
             "excitation_torque_imag"]
    periods = np.atleast_1d(np.asarray(period, dtype=float))
    at = hydro[names].interp(angular_frequency=2 * np.pi / periods, method="cubic")
    at = at.assign_coords(period=("angular_frequency", periods)).swap_dims(
        angular_frequency="period").drop_vars("angular_frequency")
    at.attrs = dict(hydro.attrs)
    return at


@_doc
def linear_model(flap: xr.Dataset, waves: xr.Dataset, hydro: xr.Dataset, inertia: float,
                 stiffness: float, pto_damping: str = "energy_equivalent"
                 ) -> tuple[dict, xr.Dataset]:
    """Compute the linear model's response (Brito Eq. A1) at the run's period.

    Parameters
    ----------
    flap : xarray.Dataset
        The run's flap product (steady window, ``theta_dot``, ``mean_power``, phase grid).
    waves : xarray.Dataset
        The run's waves product (``measured_period`` [s], ``incident_height`` [m]).
    %(hydro_written)s
    %(inertia)s
    %(stiffness)s
    pto_damping : str, optional
        How ν_pto is set, one of :data:`LINEAR_PTO_DAMPING` (module notes).

    Returns
    -------
    values : dict
        The :data:`SCALARS` (θ amplitude [rad], torque amplitude [N m], mean power [W],
        capture factor [-]) and :data:`PHASED` phase averages (θ [rad], θ̇ [rad s-1],
        power [W]) of the linear model.
    extra : xarray.Dataset
        ``pto_damping`` [N m s]; its ``method`` attribute says how it was set.

    Raises
    ------
    ValueError
        An unknown ``pto_damping``.

    %(references_brito2020)s, Eq. (A1).
    %(renzi_dias2012)s, Eq. (2.40).
    """
    from flumekit.hydro.response import optimal_pto_damping, response

    if pto_damping not in LINEAR_PTO_DAMPING:
        raise ValueError(f"linear_pto_damping must be one of {LINEAR_PTO_DAMPING}, "
                         f"got {pto_damping!r}")
    period = float(waves["measured_period"])
    rd = coefficients_at(hydro, period)
    nu = (energy_equivalent_damping(flap) if pto_damping == "energy_equivalent"
          else float(optimal_pto_damping(rd, inertia, stiffness).values[0]))
    r = response(rd, float(waves["incident_height"]) / 2, inertia, stiffness, nu).isel(period=0)
    # phase averages with t/T = 0 at the up-crossing of θ, as for the experiment
    phase = flap["phase"].values
    amp = float(r["theta_amplitude"])
    omega = 2 * np.pi / period
    out = {name: float(r[name]) for name in SCALARS}
    out["theta_phase_mean"] = amp * np.sin(2 * np.pi * phase)
    out["theta_dot_phase_mean"] = amp * omega * np.cos(2 * np.pi * phase)
    out["power_phase_mean"] = nu * out["theta_dot_phase_mean"] ** 2
    return out, xr.Dataset({"pto_damping": ((), nu, {"method": pto_damping,
                                                      "comment": _DAMPING_COMMENT[pto_damping]})})


@_doc
def periodic_extension(eta: xr.DataArray, period: float, before: int,
                       after: int) -> xr.DataArray:
    """Continue the steady incident wave periodically by whole periods before and after.

    Parameters
    ----------
    eta : xarray.DataArray
        Incident elevation [m] over ``time`` [s], finite in the steady window, uniformly
        sampled.
    %(period)s
    before : int
        Number of periods added before the window (ramped from rest).
    after : int
        Number of periods added after the window.

    %(returns_incident)s

    Notes
    -----
    The separation defines the incident wave only in the quasi-steady window (NaN elsewhere)
    and the simulator starts from rest, so the record is continued backwards under a
    half-cosine ramp (spin-up to the steady state before the window) and forwards unramped (so
    that the simulator's end taper falls after the window). Periodic continuation is exact for
    the regular waves of the window.

    Examples
    --------
    >>> import numpy as np, xarray as xr
    >>> from flumekit.flap.comparison import periodic_extension
    >>> t = np.arange(0.0, 4.0, 0.1)
    >>> eta = xr.DataArray(np.cos(np.pi * t), dims="time", coords={"time": t})
    >>> periodic_extension(eta, 2.0, before=1, after=1).sizes["time"]
    80
    """
    ok = np.flatnonzero(np.isfinite(eta.values))
    t, v = eta["time"].values[ok], eta.values[ok]
    dt = uniform_step(t, "the steady incident wave")
    n_b, n_a = round(before * period / dt), round(after * period / dt)
    tb = t[0] - dt * np.arange(n_b, 0, -1)
    ta = t[-1] + dt * np.arange(1, n_a + 1)
    fold = lambda tt: t[0] + np.mod(tt - t[0], period)  # noqa: E731 - one-line map
    ramp = 0.5 * (1 - np.cos(np.pi * np.arange(n_b) / max(n_b, 1)))
    values = np.concatenate([ramp * np.interp(fold(tb), t, v), v, np.interp(fold(ta), t, v)])
    return xr.DataArray(values, dims="time", coords={"time": np.concatenate([tb, t, ta])},
                        name="eta_incident")


class _Device(NamedTuple):
    # simulate_run reads flap.inertia and pto only, so it gets just these two
    flap: Flap
    pto: PTO


@_doc
def simulated(flap: xr.Dataset, waves: xr.Dataset, hydro: xr.Dataset, *, flap_params: Flap,
              pto: PTO, depth: float, dt: float, friction: bool = True,
              spin_up_periods: int = 20) -> tuple[dict, float]:
    """Run the simulator on the run's separated incident wave and summarise it as measured.

    Parameters
    ----------
    flap : xarray.Dataset
        The run's flap product (steady window, fitted hydraulic parameters, phase grid).
    waves : xarray.Dataset
        The run's waves product (``eta_incident`` [m], ``measured_period`` [s],
        ``incident_height`` [m], steady window).
    %(hydro_stored)s
    %(flap_params)s
    %(pto)s
    %(depth)s
    %(simulator_dt)s
    %(friction)s
    %(spin_up_periods)s

    Returns
    -------
    values : dict
        The :data:`SCALARS` and :data:`PHASED` values of the simulation.
    theta_difference : float
        :func:`time_domain_difference` of the simulated and measured θ [-].
    """
    from flumekit.flap.simulator import simulate_run
    from flumekit.flap.summary import summarise_run
    from flumekit.hydro.coefficients import merge_complex
    from flumekit.hydro.radiation import state_space_from_dataset

    eta = periodic_extension(waves["eta_incident"], float(waves["measured_period"]),
                             before=spin_up_periods, after=5)
    # restoring C sin(theta): the torque balance of the flap stage (flumekit.flap.torque);
    # the campaign's radiation model, fitted once (stored_container)
    sim = simulate_run(merge_complex(hydro.drop_dims("radiation_mode")), eta,
                       _Device(flap_params, pto), radiation=state_space_from_dataset(hydro),
                       pressure_loss_coefficient=float(flap["pressure_loss_coefficient"]),
                       fluid_inertia=float(flap["fluid_inertia"]), friction=friction,
                       restoring="sine", dt=dt)
    s = summarise_run(sim, period=float(waves["measured_period"]),
                      incident_height=float(waves["incident_height"]), depth=depth,
                      flap_width=flap_params.width, n_phase=flap.sizes["phase"])
    out = {name: s[name].values for name in (*SCALARS, *PHASED)}
    window = (max(float(flap["steady_start"]), float(waves["steady_start"])),
              min(float(flap["steady_end"]), float(waves["steady_end"])))
    return out, time_domain_difference(sim["theta"], flap, window)


def time_domain_difference(theta_sim: xr.DataArray, flap: xr.Dataset,
                           window: tuple[float, float]) -> float:
    """Compute the RMS of θ_sim(t) − θ(t) over a window, as a fraction of the θ amplitude.

    Both are on the flume's clock (the simulator is driven by the separated incident wave), so
    no phase reference is involved. The window is where both the flap and the separated
    incident wave are quasi-steady: before the latter the simulator still runs on the spin-up
    extension.

    Parameters
    ----------
    theta_sim : xarray.DataArray
        Simulated θ [rad] over ``time`` [s].
    flap : xarray.Dataset
        The measured run's ``theta`` [rad] over ``time`` [s] and ``theta_amplitude`` [rad].
    window : tuple of float
        (start, end) [s].

    Returns
    -------
    float
        The relative RMS difference [-].

    Examples
    --------
    >>> import numpy as np, xarray as xr
    >>> from flumekit.flap.comparison import time_domain_difference
    >>> t = np.linspace(0.0, 10.0, 1001)
    >>> flap = xr.Dataset({"theta": ("time", 0.1 * np.sin(t)), "theta_amplitude": 0.1},
    ...                   coords={"time": t})
    >>> sim = xr.DataArray(0.1 * np.sin(t) + 0.01, dims="time", coords={"time": t})
    >>> round(time_domain_difference(sim, flap, (0.0, 10.0)), 6)
    0.1
    """
    t = flap["time"].values
    inside = (t >= window[0]) & (t <= window[1])
    sim = np.interp(t[inside], theta_sim["time"].values, theta_sim.values)
    diff = sim - flap["theta"].values[inside]
    return float(np.sqrt(np.mean(diff**2)) / float(flap["theta_amplitude"]))


@_doc
def compare_run(flap: xr.Dataset, waves: xr.Dataset, hydro: xr.Dataset, *, flap_params: Flap,
                pto: PTO, depth: float, dt: float = 0.04, simulator: bool = True,
                friction: bool = True, spin_up_periods: int = 20,
                linear_pto_damping: str = "energy_equivalent") -> xr.Dataset:
    """Compare a regular run with the linear model and (optionally) the simulator.

    Parameters
    ----------
    flap : xarray.Dataset
        The run's flap product (:func:`flumekit.flap.analysis.analyse_run`): the experiment's
        :data:`SCALARS` and :data:`PHASED`, ``phase`` and ``incident_power`` [W].
    waves : xarray.Dataset
        The run's waves product: ``eta_incident`` [m], ``measured_period`` [s] and
        ``incident_height`` [m].
    %(hydro_stored)s
    %(flap_params_compared)s
    %(pto)s
    %(depth)s
    %(simulator_dt_optional)s
    %(simulator)s
    %(with_friction)s
    %(spin_up_periods)s
    %(linear_pto_damping)s

    Returns
    -------
    xarray.Dataset
        The :data:`SCALARS` over ``source`` (experiment, analytical, simulator), the
        :data:`PHASED` over (``source``, ``phase``), ``pto_damping`` [N m s] of the linear
        model (its ``method`` attribute, and the dataset's ``linear_pto_damping`` attribute,
        say how it was set) and, with the simulator, ``theta_relative_rms_difference`` [-].

    Raises
    ------
    ValueError
        An unknown ``linear_pto_damping``; with the simulator, an incident wave that is not
        sampled uniformly over the steady window.

    %(references_brito2020)s, Eq. (A1).
    %(renzi_dias2012)s, Eq. (2.40).

    Examples
    --------
    A flap that moves exactly as the linear model predicts is matched by it. With coefficients
    constant in frequency (μ = 80 kg m2, ν = 100 N m s, excitation 1600 N m per metre of
    amplitude), I = 20 kg m2 and C = 400 N m/rad, the flap resonates at ω = 2 rad/s
    (C = ω²(I + μ)); a PTO of ν_pto = 300 N m s then gives Θ = F A / (ω (ν + ν_pto)) = 0.2 rad
    in waves of A = 0.1 m, absorbing ½ ν_pto ω² Θ² = 24 W. The run below moves so, with
    T_h = (C − ω² I) θ + ν_pto θ̇ (Eq. 11); the linear model recovers ν_pto from it by energy
    equivalence:

    >>> import numpy as np, xarray as xr
    >>> from flumekit.campaign import Flap
    >>> from flumekit.flap.comparison import compare_run
    >>> from flumekit.flap.summary import summarise_run
    >>> omega = np.linspace(1.0, 4.0, 7)
    >>> constant = lambda value: ("angular_frequency", np.full(omega.size, value))
    >>> hydro = xr.Dataset({"added_inertia": constant(80.0), "radiation_damping": constant(100.0),
    ...                     "excitation_torque_real": constant(1600.0),
    ...                     "excitation_torque_imag": constant(0.0)},
    ...                    coords={"angular_frequency": omega},
    ...                    attrs={"depth": 0.8, "flap_width": 1.0, "rho": 1000.0, "g": 9.81})
    >>> t = np.arange(0.0, 20 * np.pi, 0.01)  # 20 periods of T = π s
    >>> theta, theta_dot = 0.2 * np.sin(2 * t), 0.4 * np.cos(2 * t)
    >>> run = xr.Dataset({"theta": ("time", theta), "theta_dot": ("time", theta_dot),
    ...                   "power": ("time", 300.0 * theta_dot**2),
    ...                   "torque_hydrodynamic": ("time", 320.0 * theta + 300.0 * theta_dot)},
    ...                  coords={"time": t})
    >>> flap = summarise_run(run, period=np.pi, incident_height=0.2, depth=0.8,
    ...                      flap_width=1.0).merge(run.theta_dot)
    >>> waves = xr.Dataset({"measured_period": np.pi, "incident_height": 0.2})
    >>> device = Flap(width=1.0, thickness=0.1, inertia=20.0, hinge_height=0.1,
    ...               buoyancy_stiffness=400.0)
    >>> ds = compare_run(flap, waves, hydro, flap_params=device, pto=None, depth=0.8,
    ...                  simulator=False)  # the PTO is read by the simulator only
    >>> ds.source.values.tolist(), round(float(ds.pto_damping), 1)
    (['experiment', 'analytical'], 300.0)
    >>> ds.theta_amplitude.round(4).values.tolist(), ds.mean_power.round(2).values.tolist()
    ([0.2, 0.2], [24.0, 24.0])
    >>> ds.torque_amplitude.round(1).values.tolist()  # abs(C − ω² I − i ω ν_pto) Θ
    [136.0, 136.0]
    """
    sources = {"experiment": {n: flap[n].values for n in (*SCALARS, *PHASED)}}
    sources["analytical"], extra = linear_model(flap, waves, hydro, flap_params.inertia,
                                                flap_params.buoyancy_stiffness,
                                                linear_pto_damping)
    if simulator:
        sources["simulator"], theta_error = simulated(
            flap, waves, hydro, flap_params=flap_params, pto=pto, depth=depth, dt=dt,
            friction=friction, spin_up_periods=spin_up_periods)
        extra["theta_relative_rms_difference"] = theta_error
    names = list(sources)
    data = {n: ("source", np.array([float(sources[s][n]) for s in names])) for n in SCALARS}
    data.update({n: (("source", "phase"), np.stack([np.asarray(sources[s][n], dtype=float)
                                                    for s in names])) for n in PHASED})
    ds = xr.Dataset(data, coords={"source": names, "phase": flap["phase"].values,
                                  "incident_height": float(waves["incident_height"]),
                                  "measured_period": float(waves["measured_period"]),
                                  "incident_power": float(flap["incident_power"])})
    ds = ds.merge(extra)
    ds.attrs["linear_pto_damping"] = linear_pto_damping
    return ds


# --- irregular seas ---------------------------------------------------------------------------

#: scalars compared along ``source`` for an irregular run
IRREGULAR_SCALARS = ("mean_power", "capture_width", "capture_width_ratio",
                     "theta_significant_amplitude", "torque_significant_amplitude")


def spectral_bins(spectrum: xr.DataArray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Return the frequencies, widths and variance densities of a band-averaged spectrum.

    Each bin reaches halfway to its neighbours (the end bins as far outwards as inwards), so a
    uniform grid gets Δf = its step.

    Parameters
    ----------
    spectrum : xarray.DataArray
        One-sided variance density [m2 s] over increasing ``frequency`` [Hz].

    Returns
    -------
    frequency : numpy.ndarray
        Bin centres [Hz].
    width : numpy.ndarray
        Bin widths Δf [Hz].
    density : numpy.ndarray
        Variance densities [m2 s], NaN as 0.

    Raises
    ------
    ValueError
        Fewer than two frequencies, or frequencies not increasing.

    Examples
    --------
    >>> import xarray as xr
    >>> from flumekit.flap.comparison import spectral_bins
    >>> s = xr.DataArray([1.0, 2.0, 4.0], dims="frequency", coords={"frequency": [0.1, 0.2, 0.4]})
    >>> spectral_bins(s)[1].round(3).tolist()
    [0.1, 0.15, 0.2]
    """
    f = np.asarray(spectrum["frequency"].values, dtype=float)
    s = np.asarray(spectrum.values, dtype=float)
    if f.ndim != 1 or f.size < 2 or np.any(np.diff(f) <= 0):
        raise ValueError("the incident spectrum needs at least two increasing frequencies")
    mid = 0.5 * (f[1:] + f[:-1])
    edges = np.concatenate([[f[0] - (mid[0] - f[0])], mid, [f[-1] + (f[-1] - mid[-1])]])
    return f, np.diff(edges), np.where(np.isfinite(s), s, 0.0)


@_doc
def spectral_response(hydro: xr.Dataset, spectrum: xr.DataArray, inertia: float,
                      stiffness: float, pto_damping: float) -> dict:
    """Compute the linear flap response to an irregular sea as a sum over its spectrum.

    The regular-wave responses (Eq. A1) summed over the bins of the incident spectrum.

    Each bin of the one-sided spectrum S_I(f) is a regular component of amplitude
    a² = 2 S_I(f) Δf with random phase, so the mean power is Σ 2 S_I(f) Δf P_1(f), with
    P_1 = ½ ν_pto ω² |Θ/a|² the mean power per unit amplitude² (RD12 Eq. 2.37), and the
    variance of θ is Σ S_I(f) Δf |Θ/a|².

    Parameters
    ----------
    hydro : xarray.Dataset
        Coefficient container as written (real and imaginary parts over
        ``angular_frequency``, attributes ``depth``, ``flap_width``, ``rho``, ``g``).
    spectrum : xarray.DataArray
        One-sided incident variance density at the flap [m2 s] over ``frequency`` [Hz]
        (band-averaged; bins as :func:`spectral_bins`).
    %(inertia)s
    %(stiffness)s
    pto_damping : float
        Linear PTO damping ν_pto [N m s].

    Returns
    -------
    dict
        ``mean_power`` [W], ``theta_significant_amplitude`` 2 sqrt(m0_θ) [rad],
        ``torque_significant_amplitude`` [N m] (of the wave torque on the moving flap, as
        :func:`flumekit.hydro.response.response`), ``variance_outside`` [-] (the fraction of
        the incident variance at frequencies outside the coefficients' grid, left out) and
        ``nan_bins`` (bins of the spectrum that are NaN, masked by the separation: counted as
        empty, their number said).

    Raises
    ------
    ValueError
        The spectrum holds no variance, or has fewer than two increasing frequencies.

    %(references_renzi_dias2012)s, Eq. (2.37).
    """
    from flumekit.hydro.response import response

    f, df, s = spectral_bins(spectrum)
    w = hydro["angular_frequency"].values
    inside = (2 * np.pi * f >= w.min()) & (2 * np.pi * f <= w.max()) & (f > 0)
    var = s * df
    total = float(var.sum())
    if not total > 0:
        raise ValueError("the incident spectrum holds no variance")
    r = response(coefficients_at(hydro, 1.0 / f[inside]), 1.0, inertia, stiffness,
                 pto_damping)
    v = var[inside]
    return {"nan_bins": int((~np.isfinite(spectrum.values)).sum()),
            "mean_power": float(np.sum(2 * v * r["mean_power"].values)),
            "theta_significant_amplitude": float(
                2 * np.sqrt(np.sum(v * r["theta_amplitude"].values ** 2))),
            "torque_significant_amplitude": float(
                2 * np.sqrt(np.sum(v * r["torque_amplitude"].values ** 2))),
            "variance_outside": 1.0 - float(v.sum()) / total}


@_doc
def span_equivalent_damping(flap: xr.Dataset) -> float:
    """Return the PTO damping that absorbs the measured mean power over an irregular run.

    Same as :func:`energy_equivalent_damping`, over the analysed span: ν_pto = P̄ / mean(θ̇²)
    between ``analysis_start`` and ``analysis_end``.

    Parameters
    ----------
    flap : xarray.Dataset
        An irregular run's flap product: ``theta_dot`` [rad s-1] over ``time`` [s],
        ``mean_power`` [W], ``analysis_start`` and ``analysis_end`` [s].

    %(returns_damping)s
    """
    return energy_equivalent_damping(flap, ("analysis_start", "analysis_end"))


@_doc
def linear_model_irregular(flap: xr.Dataset, waves: xr.Dataset, hydro: xr.Dataset,
                           inertia: float, stiffness: float,
                           pto_damping: str = "energy_equivalent") -> tuple[dict, xr.Dataset]:
    """Compute the linear model (Eq. A1) of an irregular run, summed over its spectrum.

    :func:`spectral_response` over the waves product's ``spectrum_incident``.

    Parameters
    ----------
    flap : xarray.Dataset
        The run's flap product (analysed span, ``theta_dot``, ``mean_power``).
    waves : xarray.Dataset
        The run's waves product (``spectrum_incident`` [m2 s], ``energy_flux`` [W m-1]).
    %(hydro_written)s
    %(inertia)s
    %(stiffness)s
    pto_damping : {"energy_equivalent", "optimal"}, optional
        ν = P̄ / mean(θ̇²) over the analysed span (:func:`span_equivalent_damping`), or the
        single damping that maximises the spectral mean power of this sea state (bounded
        scalar search; the irregular counterpart of RD12 Eq. 2.40).

    Returns
    -------
    values : dict
        The :data:`IRREGULAR_SCALARS` (mean power [W], capture width [m], CWR [-] with the
        waves product's J and the flap width of ``hydro``, significant amplitudes [rad],
        [N m]).
    extra : xarray.Dataset
        ``pto_damping`` [N m s] with how it was set and the variance left out.

    Raises
    ------
    ValueError
        An unknown ``pto_damping``, or an empty spectrum.

    %(references_renzi_dias2012)s, Eqs. (2.37), (2.40).
    """
    from scipy.optimize import minimize_scalar

    if pto_damping not in LINEAR_PTO_DAMPING:
        raise ValueError(f"linear_pto_damping must be one of {LINEAR_PTO_DAMPING}, "
                         f"got {pto_damping!r}")
    spec = waves["spectrum_incident"]
    if pto_damping == "energy_equivalent":
        nu = span_equivalent_damping(flap)
    else:
        from flumekit.hydro.response import optimal_pto_damping

        # the optimum of the sum lies between the smallest and largest single-frequency
        # optima of the band (each term rises below and falls above its own)
        f, _, s = spectral_bins(spec)
        band = f[(s > 0.01 * s.max()) & (f > 0)]
        opt = optimal_pto_damping(coefficients_at(hydro, 1.0 / band), inertia, stiffness).values
        if np.ptp(opt) == 0:  # one frequency: RD12 Eq. (2.40) itself
            nu = float(opt[0])
        else:
            res = minimize_scalar(lambda x: -spectral_response(hydro, spec, inertia, stiffness,
                                                               x)["mean_power"],
                                  bounds=(float(opt.min()), float(opt.max())),
                                  method="bounded", options={"xatol": 1e-4 * float(opt.max())})
            nu = float(res.x)
    out = spectral_response(hydro, spec, inertia, stiffness, nu)
    outside = out.pop("variance_outside")
    nan_bins = out.pop("nan_bins")
    _capture(out, float(waves["energy_flux"]), float(hydro.attrs["flap_width"]))
    return out, xr.Dataset({"pto_damping": ((), nu, {
        "method": pto_damping,
        "comment": {"energy_equivalent": "linear-model PTO damping from the measured PTO by "
                    "energy equivalence over the analysed span: mean power / "
                    "mean(theta_dot^2)", "optimal": "the linear-model PTO damping that "
                    "maximises the spectral mean power of the sea state"}[pto_damping],
        "incident_variance_outside_coefficients": outside,
        "incident_spectrum_nan_bins": nan_bins})})


def _capture(values: dict, flux: float, width: float) -> None:
    from flumekit.performance import capture_width, capture_width_ratio

    values["capture_width"] = float(capture_width(values["mean_power"], flux))
    values["capture_width_ratio"] = float(capture_width_ratio(values["mean_power"], flux, width))


@_doc
def mirrored_extension(eta: xr.DataArray, before: float, after: float) -> xr.DataArray:
    """Continue the incident wave by its mirror image before and after its finite span.

    A random sea has no period to continue, but its time reverse has the same spectrum:
    η(t₀ − s) = η(t₀ + s) before the first finite sample (under a half-cosine ramp from rest,
    the simulator's spin-up) and η(t₁ + s) = η(t₁ − s) after the last (unramped, so that the
    excitation filter's end taper falls after the analysed span).

    Parameters
    ----------
    eta : xarray.DataArray
        Incident elevation [m] over ``time`` [s], uniformly sampled where finite.
    before : float
        Duration added before the first finite sample [s] (at most the record's length).
    after : float
        Duration added after the last finite sample [s] (at most the record's length).

    %(returns_incident)s

    Examples
    --------
    >>> import numpy as np, xarray as xr
    >>> from flumekit.flap.comparison import mirrored_extension
    >>> t = np.arange(5.0)
    >>> eta = xr.DataArray([0.0, 1.0, 2.0, 3.0, 4.0], dims="time", coords={"time": t})
    >>> mirrored_extension(eta, before=0.0, after=2.0).values.tolist()
    [0.0, 1.0, 2.0, 3.0, 4.0, 3.0, 2.0]
    """
    ok = np.flatnonzero(np.isfinite(eta.values))
    t, v = eta["time"].values[ok], eta.values[ok]
    dt = uniform_step(t, "the incident wave")
    n_b = min(round(before / dt), t.size - 1)
    n_a = min(round(after / dt), t.size - 1)
    tb = t[0] - dt * np.arange(n_b, 0, -1)
    ta = t[-1] + dt * np.arange(1, n_a + 1)
    ramp = 0.5 * (1 - np.cos(np.pi * np.arange(n_b) / max(n_b, 1)))
    values = np.concatenate([ramp * v[n_b:0:-1], v, v[-2:-n_a - 2:-1]])
    return xr.DataArray(values, dims="time", coords={"time": np.concatenate([tb, t, ta])},
                        name="eta_incident")


@_doc
def simulated_irregular(flap: xr.Dataset, waves: xr.Dataset, hydro: xr.Dataset, *,
                        flap_params: Flap, pto: PTO, dt: float, friction: bool = True,
                        spin_up: float = 60.0) -> tuple[dict, float]:
    """Run the simulator on an irregular run's separated incident wave over its analysed span.

    The incident elevation is used where it is finite; where it does not reach ``spin_up``
    seconds before the span (or 30 s past it), it is continued by
    :func:`mirrored_extension`. The simulated PTO power is averaged over the same span as the
    measured one, and θ and the hydrodynamic torque get the statistics of
    :func:`flumekit.performance.motion_statistics`.

    Parameters
    ----------
    flap : xarray.Dataset
        The run's flap product (analysed span, ``theta`` [rad], fitted hydraulic parameters).
    waves : xarray.Dataset
        The run's waves product (``eta_incident`` [m] at x = 0, ``energy_flux`` [W m-1]).
    %(hydro_stored)s
    %(flap_params)s
    %(pto)s
    %(simulator_dt)s
    %(friction)s
    spin_up : float, optional
        Seconds of incident wave run before the analysed span [s].

    Returns
    -------
    values : dict
        The :data:`IRREGULAR_SCALARS` of the simulation (CWR with the waves product's J).
    theta_difference : float
        RMS of θ_sim(t) − θ(t) over the span as a fraction of the measured θ's RMS [-].

    Raises
    ------
    ValueError
        The separated incident wave does not cover the analysed span.
    """
    from flumekit.flap.power import window_mean
    from flumekit.flap.simulator import simulate_run
    from flumekit.hydro.coefficients import merge_complex
    from flumekit.hydro.radiation import state_space_from_dataset
    from flumekit.performance import motion_statistics

    start, end = float(flap["analysis_start"]), float(flap["analysis_end"])
    eta = waves["eta_incident"]
    finite = eta["time"].values[np.isfinite(eta.values)]
    if finite.size < 2 or finite[0] > start or finite[-1] < end:
        raise ValueError(f"the separated incident wave does not cover the analysed span "
                         f"[{start}, {end}] s")
    eta = mirrored_extension(eta, before=max(0.0, spin_up - (start - finite[0])),
                             after=max(0.0, 30.0 - (finite[-1] - end)))
    sim = simulate_run(merge_complex(hydro.drop_dims("radiation_mode")), eta,
                       _Device(flap_params, pto), radiation=state_space_from_dataset(hydro),
                       pressure_loss_coefficient=float(flap["pressure_loss_coefficient"]),
                       fluid_inertia=float(flap["fluid_inertia"]), friction=friction,
                       restoring="sine", dt=dt)
    ts = sim["time"].values
    inside = (ts >= start) & (ts <= end)
    out = {"mean_power": window_mean(sim["power"].values, ts, start, end)}
    out["theta_significant_amplitude"] = float(motion_statistics(
        sim["theta"].values[inside], time=ts[inside])["theta_significant_amplitude"])
    out["torque_significant_amplitude"] = float(motion_statistics(
        sim["torque_hydrodynamic"].values[inside], time=ts[inside],
        name="torque")["torque_significant_amplitude"])
    _capture(out, float(waves["energy_flux"]), flap_params.width)
    t = flap["time"].values
    span = (t >= start) & (t <= end)
    theta = flap["theta"].values[span]
    diff = np.interp(t[span], ts, sim["theta"].values) - theta
    return out, float(np.sqrt(np.mean(diff**2)) / np.std(theta))


@_doc
def compare_irregular_run(flap: xr.Dataset, waves: xr.Dataset, hydro: xr.Dataset, *,
                          flap_params: Flap, pto: PTO, dt: float = 0.04,
                          simulator: bool = True, friction: bool = True,
                          spin_up: float = 60.0,
                          linear_pto_damping: str = "energy_equivalent") -> xr.Dataset:
    """Compare an irregular run with the linear model and (optionally) the simulator.

    The experiment, the linear model (spectral sum of Eq. A1) and the simulator (driven by the
    measured incident wave) along ``source``.

    Parameters
    ----------
    flap : xarray.Dataset
        The run's flap product (:func:`flumekit.flap.analysis.analyse_irregular_run`).
    waves : xarray.Dataset
        The run's waves product (``spectrum_incident``, ``eta_incident``, ``energy_flux``).
    %(hydro_stored)s
    %(flap_params_compared)s
    %(pto)s
    %(simulator_dt_optional)s
    %(simulator)s
    %(with_friction)s
    spin_up : float, optional
        Seconds of incident wave the simulator runs before the analysed span [s].
    %(linear_pto_damping)s

    Returns
    -------
    xarray.Dataset
        The :data:`IRREGULAR_SCALARS` over ``source`` (experiment, analytical, simulator), the
        linear model's ``pto_damping``, with the simulator ``theta_relative_rms_difference``
        (over the span, relative to the measured θ's RMS), ``energy_flux`` (J of the waves
        product, the CWR's denominator for every source), and the scalar coordinates of a
        regular run's comparison: ``incident_power`` J w [W], ``incident_height`` and
        ``measured_period`` NaN (no single height or period).

    Raises
    ------
    ValueError
        An unknown ``linear_pto_damping``, an empty spectrum, or an incident wave that does
        not cover the analysed span.

    %(references_renzi_dias2012)s, Eqs. (2.33), (2.37).
    Babarit, A. (2015). A database of capture width ratio of wave energy converters.
    Renewable Energy 80, 610-628.

    Examples
    --------
    >>> ds = compare_irregular_run(flap, waves, hydro, flap_params=c.flap,  # doctest: +SKIP
    ...                            pto=c.pto)
    >>> ds.capture_width_ratio.sel(source="simulator")  # doctest: +SKIP
    """
    sources = {"experiment": {n: float(flap[n]) for n in IRREGULAR_SCALARS}}
    sources["analytical"], extra = linear_model_irregular(
        flap, waves, hydro, flap_params.inertia, flap_params.buoyancy_stiffness,
        linear_pto_damping)
    if simulator:
        sources["simulator"], theta_error = simulated_irregular(
            flap, waves, hydro, flap_params=flap_params, pto=pto, dt=dt, friction=friction,
            spin_up=spin_up)
        extra["theta_relative_rms_difference"] = ((), theta_error, {
            "long_name": "RMS of simulated minus measured theta over the analysed span, over "
                         "the RMS of the measured theta"})
    names = list(sources)
    data = {n: ("source", np.array([sources[s][n] for s in names])) for n in IRREGULAR_SCALARS}
    flux = float(waves["energy_flux"])
    # the scalar coordinates of a regular run's comparison, so that the campaign summary
    # stacks both kinds: no single height or period, W_I = J w across the flap
    ds = xr.Dataset(data, coords={"source": names, "incident_height": np.nan,
                                  "measured_period": np.nan,
                                  "incident_power": flux * flap_params.width}).merge(extra)
    ds["energy_flux"] = ((), flux, {"long_name": "spectral energy flux of the incident wave per "
                                    "unit crest width, rho g int S_I(f) c_g(f, h) df"})
    ds["mean_power"].attrs["long_name"] = "mean PTO power over the analysed span"
    ds.attrs["linear_pto_damping"] = linear_pto_damping
    return conventions.annotate(ds)
