"""Stage: the flume's runs against the linear model and the time-domain simulator.

``models/hydro``: the hydrodynamic coefficients of the campaign's flap over a frequency grid,
as one container (with A∞ from the Ogilvie relation) used by both the linear model and the
simulator: the Renzi–Dias thin plate in the flume's channel (default), or, with
``[stages.models] coefficients = "bem"`` and Capytaine installed, the real thick flap on its
foundation by BEM (open water: the channel walls are not modelled).
``comparison/<run>``: the experiment, the linear model (Eq. A1) and the simulator side by side
along a ``source`` dimension. The linear model's PTO damping is set from the measured PTO by
energy equivalence over the steady window, ν_pto = W̄_out / mean(θ̇²), so that it absorbs the
same mean power at the measured motion; the simulator uses the fitted hydraulic model
(K_p, I_p) and the campaign's LuGre friction, driven by the separated incident wave at x = 0.
"""

from __future__ import annotations

from flumekit.pipeline.rules import Rule
from flumekit.stages.context import Context
from flumekit.stages.runs import run_params, stack_runs, summary_rule, write_run

VERSION = "5"
DEFAULTS = {"coefficients": "renzi_dias", "omega_min": 0.4, "omega_max": 25.0, "n_omega": 400,
            "bem_omega_min": 1.0, "bem_omega_max": 12.0, "bem_n_omega": 40,
            "bem_panel_size": 0.05, "dt": 0.04, "simulator": True, "friction": True,
            "spin_up_periods": 20, "irf_duration": 30.0}
SCALARS = ("theta_amplitude", "torque_amplitude", "mean_power", "capture_factor")
PHASED = ("theta_phase_mean", "theta_dot_phase_mean", "power_phase_mean")


def rules(ctx: Context) -> list[Rule]:
    c = ctx.campaign
    p = ctx.stage_params("models", DEFAULTS)
    if p["coefficients"] not in ("renzi_dias", "bem"):
        from flumekit.errors import FlumekitError

        raise FlumekitError(f"pipeline: [stages.models] coefficients must be 'renzi_dias' or "
                            f"'bem', got {p['coefficients']!r}")
    geometry = {"depth": c.flume.water_depth, "flap_width": c.flap.width,
                "hinge_height": c.flap.hinge_height, "channel_width": c.flume.width,
                "stiffness": c.flap.buoyancy_stiffness, "inertia": c.flap.inertia}
    hydro = ctx.out("models", "hydro.nc")
    keys = (("coefficients", "omega_min", "omega_max", "n_omega") if p["coefficients"] ==
            "renzi_dias" else ("coefficients", "bem_omega_min", "bem_omega_max",
                               "bem_n_omega", "bem_panel_size"))
    out = [Rule("models/hydro", "flumekit.stages.models:hydro", inputs={},
                outputs={"dataset": hydro},
                params={**geometry, "thickness": c.flap.thickness,
                        **{k: p[k] for k in (*keys, "irf_duration")}},
                version=VERSION)]
    for run in c.runs:
        params = {**geometry, "dt": p["dt"], "simulator": p["simulator"],
                  "friction": p["friction"], "spin_up_periods": p["spin_up_periods"],
                  **run_params(run)}
        out.append(Rule(f"comparison/{run.id}", "flumekit.stages.models:compare",
                        inputs={"flap": ctx.out("flap", f"{run.id}.nc"),
                                "waves": ctx.out("waves", f"{run.id}.nc"),
                                "hydro": hydro, "campaign": ctx.campaign_file},
                        outputs={"dataset": ctx.out("comparison", f"{run.id}.nc")},
                        params=params, version=VERSION, run=run.id))
    out.append(summary_rule(ctx, "comparison", VERSION, module="models"))
    return out


def hydro(inputs, outputs, params) -> None:
    import numpy as np

    from flumekit import conventions
    from flumekit.flap.renzi_dias.model import coefficients
    from flumekit.hydro import coefficients as hy
    from flumekit.io.netcdf import write_dataset

    if params["coefficients"] == "bem":
        from flumekit.errors import FlumekitError
        from flumekit.flap import bem

        if not bem.available():
            raise FlumekitError("[stages.models] coefficients = 'bem' needs Capytaine: "
                                "pip install 'flumekit[bem]'")
        # Capytaine's finite-depth Green function needs kh above about 0.15: the low-frequency
        # end is held constant by the impulse response (flumekit.hydro.radiation)
        omega = np.linspace(params["bem_omega_min"], params["bem_omega_max"],
                            params["bem_n_omega"])
        # the real, thick flap on its fixed foundation, in open water (no channel walls)
        coeffs = bem.coefficients(2 * np.pi / omega[::-1], params["depth"],
                                  params["flap_width"], params["hinge_height"],
                                  params["thickness"], panel_size=params["bem_panel_size"])
        title = "BEM (Capytaine) coefficients of the thick flap, open water"
    else:
        omega = np.linspace(params["omega_min"], params["omega_max"], params["n_omega"])
        coeffs = coefficients(2 * np.pi / omega[::-1], params["depth"], params["flap_width"],
                              params["hinge_height"], channel_width=params["channel_width"])
        title = "Renzi-Dias coefficients of the thin flap in the flume's channel (RD12)"
    ds = hy.with_infinite_frequency_inertia(hy.from_renzi_dias(coeffs, params["stiffness"]),
                                            max_spread=None)
    # the simulator's radiation model, fitted once here and shared by every run's comparison
    from flumekit.hydro.radiation import fit_state_space, impulse_response, state_space_dataset

    radiation = state_space_dataset(fit_state_space(impulse_response(
        ds, params["irf_duration"], 0.01)))
    ds = hy.split_complex(ds).merge(radiation, combine_attrs="no_conflicts")
    ds.attrs.update(conventions.global_attrs(title, "flumekit models/hydro stage", params))
    ds.attrs.update(depth=params["depth"], flap_width=params["flap_width"], rho=1000.0, g=9.81)
    write_dataset(ds, outputs["dataset"])


def energy_equivalent_damping(flap) -> float:
    """ν_pto [N m s] absorbing the measured mean power at the measured θ̇ (steady window)."""
    import numpy as np

    t = flap["time"].values
    inside = (t >= float(flap["steady_start"])) & (t <= float(flap["steady_end"]))
    return float(flap["mean_power"]) / float(np.mean(flap["theta_dot"].values[inside] ** 2))


def coefficients_at(hydro, period: float):
    """The campaign's coefficient container at one period, in the layout of
    :func:`flumekit.hydro.response.response` (cubic interpolation over the frequency grid)."""
    import numpy as np

    names = ["added_inertia", "radiation_damping", "excitation_torque_real",
             "excitation_torque_imag"]
    at = hydro[names].interp(angular_frequency=[2 * np.pi / period], method="cubic")
    at = at.assign_coords(period=("angular_frequency", [period])).swap_dims(
        angular_frequency="period").drop_vars("angular_frequency")
    at.attrs = dict(hydro.attrs)
    return at


def _analytical(params, flap, waves, hydro):
    """Eq. (A1) response at the run's period with the energy-equivalent PTO damping."""
    import numpy as np
    import xarray as xr

    from flumekit.hydro.response import response

    period = float(waves["measured_period"])
    rd = coefficients_at(hydro, period)
    nu = energy_equivalent_damping(flap)
    r = response(rd, float(waves["incident_height"]) / 2, params["inertia"], params["stiffness"],
                 nu).isel(period=0)
    # phase averages with t/T = 0 at the up-crossing of θ, as for the experiment
    phase = flap["phase"].values
    amp = float(r["theta_amplitude"])
    omega = 2 * np.pi / period
    out = {name: float(r[name]) for name in SCALARS}
    out["theta_phase_mean"] = amp * np.sin(2 * np.pi * phase)
    out["theta_dot_phase_mean"] = amp * omega * np.cos(2 * np.pi * phase)
    out["power_phase_mean"] = nu * out["theta_dot_phase_mean"] ** 2
    return out, xr.Dataset({"pto_damping": nu})


def periodic_extension(eta, period: float, before: int, after: int):
    """The steady incident wave continued periodically ``before``/``after`` periods [-].

    The separation defines the incident wave only in the quasi-steady window (NaN elsewhere);
    the simulator starts from rest, so the record is continued backwards under a half-cosine
    ramp (spin-up to the steady state before the window) and forwards unramped (so that the
    simulator's end taper falls after the window). Periodic continuation is exact for the
    regular waves of the window.
    """
    import numpy as np
    import xarray as xr

    ok = np.flatnonzero(np.isfinite(eta.values))
    t, v = eta["time"].values[ok], eta.values[ok]
    dt = float(np.median(np.diff(t)))
    n_b, n_a = round(before * period / dt), round(after * period / dt)
    tb = t[0] - dt * np.arange(n_b, 0, -1)
    ta = t[-1] + dt * np.arange(1, n_a + 1)
    fold = lambda tt: t[0] + np.mod(tt - t[0], period)  # noqa: E731 - one-line map
    ramp = 0.5 * (1 - np.cos(np.pi * np.arange(n_b) / max(n_b, 1)))
    values = np.concatenate([ramp * np.interp(fold(tb), t, v), v, np.interp(fold(ta), t, v)])
    return xr.DataArray(values, dims="time", coords={"time": np.concatenate([tb, t, ta])},
                        name="eta_incident")


def _simulated(params, flap, waves, hydro, campaign):
    from flumekit.flap.simulator import simulate_run
    from flumekit.flap.summary import summarise_run
    from flumekit.hydro.coefficients import merge_complex
    from flumekit.hydro.radiation import state_space_from_dataset

    eta = periodic_extension(waves["eta_incident"], float(waves["measured_period"]),
                             before=params["spin_up_periods"], after=5)
    # restoring C sin(theta): the torque balance of the flap stage (flumekit.flap.torque);
    # the campaign's radiation model, fitted once by models/hydro
    radiation = state_space_from_dataset(hydro)
    sim = simulate_run(merge_complex(hydro.drop_dims("radiation_mode")), eta, campaign,
                       radiation=radiation,
                       pressure_loss_coefficient=float(flap["pressure_loss_coefficient"]),
                       fluid_inertia=float(flap["fluid_inertia"]), friction=params["friction"],
                       restoring="sine", dt=params["dt"])
    s = summarise_run(sim, period=float(waves["measured_period"]),
                      incident_height=float(waves["incident_height"]), depth=params["depth"],
                      flap_width=params["flap_width"], n_phase=flap.sizes["phase"])
    out = {name: s[name].values for name in (*SCALARS, *PHASED)}
    window = (max(float(flap["steady_start"]), float(waves["steady_start"])),
              min(float(flap["steady_end"]), float(waves["steady_end"])))
    return out, time_domain_difference(sim["theta"], flap, window)


def time_domain_difference(theta_sim, flap, window: tuple[float, float]) -> float:
    """RMS of θ_sim(t) - θ(t) over ``window`` [s], as a fraction of the θ amplitude.

    Both are on the flume's clock (the simulator is driven by the separated incident wave), so
    no phase reference is involved (issue 7's acceptance measure). The window is where both
    the flap and the separated incident wave are quasi-steady: before the latter the simulator
    still runs on the spin-up extension.
    """
    import numpy as np

    t = flap["time"].values
    inside = (t >= window[0]) & (t <= window[1])
    sim = np.interp(t[inside], theta_sim["time"].values, theta_sim.values)
    diff = sim - flap["theta"].values[inside]
    return float(np.sqrt(np.mean(diff**2)) / float(flap["theta_amplitude"]))


def compare(inputs, outputs, params) -> None:
    from pathlib import Path

    import numpy as np
    import xarray as xr

    from flumekit.campaign import load_campaign
    from flumekit.io.netcdf import read_dataset

    flap, waves = read_dataset(inputs["flap"]), read_dataset(inputs["waves"])
    hydro = read_dataset(inputs["hydro"])
    sources = {"experiment": {n: flap[n].values for n in (*SCALARS, *PHASED)}}
    sources["analytical"], extra = _analytical(params, flap, waves, hydro)
    if params["simulator"]:
        campaign = load_campaign(Path(inputs["campaign"]).parent)
        sources["simulator"], theta_error = _simulated(params, flap, waves, hydro, campaign)
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
    ds["pto_damping"].attrs["comment"] = ("linear-model PTO damping from the measured PTO by "
                                          "energy equivalence: mean power / mean(theta_dot^2)")
    write_run(ds, outputs, params, "Experiment, linear model and simulator",
              f"flumekit comparison stage from {inputs['flap']} and {inputs['waves']}")


def summary(inputs, outputs, params) -> None:
    stack_runs(inputs, outputs, "Experiment, linear model and simulator for every run",
               keep=lambda ds: list(ds.data_vars), drop_dims=("phase",))
