"""Stage: the flume's runs against the linear model and the time-domain simulator.

``models/hydro``: the hydrodynamic coefficients of the campaign's flap over a frequency grid,
as one container (with A∞ from the Ogilvie relation) used by both the linear model and the
simulator: the Renzi–Dias thin plate in the flume's channel (default,
:func:`flumekit.flap.renzi_dias.model.channel_container`), or, with
``[stages.models] coefficients = "bem"`` and Capytaine installed, the real thick flap on its
foundation by BEM (:func:`flumekit.flap.comparison.bem_container`).
``comparison/<run>``: the experiment, the linear model (Eq. A1) and the simulator side by side
along a ``source`` dimension (:func:`flumekit.flap.comparison.compare_run`); for an irregular
run the spectral sum of the linear model and the simulator driven by the measured incident wave
over the analysed span (:func:`flumekit.flap.comparison.compare_irregular_run`).
"""

from __future__ import annotations

from flumekit.io.atomic import Written
from flumekit.pipeline.rules import Rule
from flumekit.stages.context import Context
from flumekit.stages.runs import run_params, stack_runs, summary_rule, write_run

VERSION = "6"
NEEDS = "flap"  # the instrument this stage reads (stages.build_rules)
DEFAULTS = {"coefficients": "renzi_dias", "omega_min": 0.4, "omega_max": 25.0, "n_omega": 400,
            "bem_omega_min": 1.0, "bem_omega_max": 12.0, "bem_n_omega": 40,
            "bem_panel_size": 0.05, "dt": 0.04, "simulator": True, "friction": True,
            "spin_up_periods": 20, "irf_duration": 30.0,
            "linear_pto_damping": "energy_equivalent"}
DOCS = {
    "coefficients": "hydrodynamic coefficients: 'renzi_dias' (thin plate in the channel) or "
                    "'bem' (Capytaine, thick flap, open water)",
    "omega_min": "Renzi-Dias frequency grid: lowest angular frequency [rad s-1]",
    "omega_max": "Renzi-Dias frequency grid: highest angular frequency [rad s-1]",
    "n_omega": "Renzi-Dias frequency grid: number of frequencies [-]",
    "bem_omega_min": "BEM frequency grid: lowest angular frequency [rad s-1]",
    "bem_omega_max": "BEM frequency grid: highest angular frequency [rad s-1]",
    "bem_n_omega": "BEM frequency grid: number of frequencies [-]",
    "bem_panel_size": "BEM panel size [m]",
    "dt": "time step of the time-domain simulator [s]",
    "simulator": "run the time-domain simulator beside the linear model",
    "friction": "include the campaign's LuGre PTO friction in the simulator",
    "spin_up_periods": "periods of the incident wave the simulator runs before the compared "
                       "window [-]",
    "irf_duration": "length of the radiation impulse response K(t) of the simulator [s]",
    "linear_pto_damping": "PTO damping of the linear model (Eq. A1): 'energy_equivalent' "
                          "(measured mean power / mean(theta_dot^2)) or 'optimal' (maximum "
                          "power at the run's period, Renzi & Dias 2012 Eq. 2.40)",
}


#: the choices of ``linear_pto_damping``: :data:`flumekit.flap.comparison.LINEAR_PTO_DAMPING`,
#: repeated here so that planning does not import flumekit.flap (numpy, scipy, xarray), which
#: would cost planning more than the rules themselves (tests/stages checks that the two agree)
LINEAR_PTO_DAMPING = ("energy_equivalent", "optimal")


def rules(ctx: Context, p: dict) -> list[Rule]:
    """Return the rules of the models stage.

    Parameters
    ----------
    ctx : flumekit.stages.context.Context
        The campaign, the processed folder and the pipeline's parameters.
    p : dict
        The stage's ``[stages.<stage>]`` parameters over its ``DEFAULTS``.

    Returns
    -------
    list of flumekit.pipeline.Rule
        ``models/hydro``, one ``comparison/<run>`` per run and ``comparison_summary``.

    Raises
    ------
    flumekit.errors.FlumekitError
        For an unknown ``coefficients`` or ``linear_pto_damping`` choice.
    """
    from flumekit.errors import FlumekitError

    c = ctx.campaign
    if p["coefficients"] not in ("renzi_dias", "bem"):
        raise FlumekitError(f"pipeline: [stages.models] coefficients must be 'renzi_dias' or "
                            f"'bem', got {p['coefficients']!r}")
    if p["linear_pto_damping"] not in LINEAR_PTO_DAMPING:
        raise FlumekitError(f"pipeline: [stages.models] linear_pto_damping must be one of "
                            f"{', '.join(map(repr, LINEAR_PTO_DAMPING))}, got "
                            f"{p['linear_pto_damping']!r}")
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
                  "linear_pto_damping": p["linear_pto_damping"], **run_params(run, c)}
        out.append(Rule(f"comparison/{run.id}", "flumekit.stages.models:compare",
                        inputs={"flap": ctx.out("flap", f"{run.id}.nc"),
                                "waves": ctx.out("waves", f"{run.id}.nc"),
                                "hydro": hydro, "campaign": ctx.campaign_file},
                        outputs={"dataset": ctx.out("comparison", f"{run.id}.nc")},
                        params=params, version=VERSION, run=run.id))
    out.append(summary_rule(ctx, "comparison", VERSION, module="models"))
    return out


def hydro(inputs, outputs, params) -> Written:
    """Compute the flap's hydrodynamic coefficients over a frequency grid and write them.

    The Renzi–Dias thin plate in the flume's channel, or the thick flap by BEM
    (Capytaine); stored with the radiation impulse response and A∞ from the Ogilvie
    relation (:func:`flumekit.flap.comparison.stored_container`).

    Parameters
    ----------
    inputs : dict of str to pathlib.Path
        None.
    outputs : dict of str to pathlib.Path
        ``dataset``: ``models/hydro.nc``.
    params : dict
        The flume and flap geometry (``depth``, ``flap_width``, ``hinge_height``,
        ``channel_width``, ``thickness`` [m]; ``stiffness`` [N m rad-1], ``inertia``
        [kg m2]), ``coefficients`` and its frequency grid [rad s-1], ``irf_duration`` [s].

    Returns
    -------
    flumekit.io.atomic.Written
        The file written and its content digest, for the engine.

    References
    ----------
    Renzi, E. and Dias, F. (2012). Resonant behaviour of an oscillating wave energy
    converter in a channel. J. Fluid Mech. 701, 482-510.

    Ogilvie, T. F. (1964). Recent progress toward the understanding and prediction of ship
    motions. 5th Symposium on Naval Hydrodynamics.
    """
    from flumekit.flap.comparison import stored_container
    from flumekit.io.netcdf import write_product

    if params["coefficients"] == "bem":
        from flumekit.flap.comparison import bem_container

        ds = bem_container(params["depth"], params["flap_width"], params["hinge_height"],
                           params["thickness"], params["stiffness"],
                           (params["bem_omega_min"], params["bem_omega_max"],
                            params["bem_n_omega"]), params["bem_panel_size"])
        title = "BEM (Capytaine) coefficients of the thick flap, open water"
    else:
        from flumekit.flap.renzi_dias.model import channel_container

        ds = channel_container(params["depth"], params["flap_width"], params["hinge_height"],
                               params["channel_width"], params["stiffness"],
                               omega=(params["omega_min"], params["omega_max"],
                                      params["n_omega"]))
        title = "Renzi-Dias coefficients of the thin flap in the flume's channel (RD12)"
    ds = stored_container(ds, params["irf_duration"])
    ds.attrs.update(depth=params["depth"], flap_width=params["flap_width"], rho=1000.0, g=9.81)
    return write_product(ds, outputs["dataset"], title, "flumekit models/hydro stage", params)


def compare(inputs, outputs, params) -> Written:
    """Compare a run's experiment with the linear model and the simulator and write it.

    Parameters
    ----------
    inputs : dict of str to pathlib.Path
        ``flap``, ``waves``: the run's products; ``hydro``: ``models/hydro.nc``;
        ``campaign``: ``campaign.toml``.
    outputs : dict of str to pathlib.Path
        ``dataset``: ``comparison/<run>.nc``.
    params : dict
        ``dt`` [s], ``simulator``, ``friction``, ``spin_up_periods`` [-],
        ``linear_pto_damping`` and the run's parameters.

    Returns
    -------
    flumekit.io.atomic.Written
        The file written and its content digest, for the engine.
    """
    from pathlib import Path

    from flumekit.campaign import load_campaign
    from flumekit.flap.comparison import compare_irregular_run, compare_run
    from flumekit.io.netcdf import read_dataset

    campaign = load_campaign(Path(inputs["campaign"]).parent)
    flap, waves, hydro = (read_dataset(inputs[k]) for k in ("flap", "waves", "hydro"))
    shared = {"flap_params": campaign.flap, "pto": campaign.pto, "dt": params["dt"],
              "simulator": params["simulator"], "friction": params["friction"],
              "linear_pto_damping": params["linear_pto_damping"]}
    if params.get("kind") == "irregular":
        # the simulator's spin-up: as many energy periods as a regular run's wave periods
        ds = compare_irregular_run(flap, waves, hydro, **shared,
                                   spin_up=params["spin_up_periods"] * float(waves["te"]))
        title = "Experiment, linear model and simulator in irregular seas"
    else:
        ds = compare_run(flap, waves, hydro, depth=campaign.flume.water_depth, **shared,
                         spin_up_periods=params["spin_up_periods"])
        title = "Experiment, linear model and simulator"
    return write_run(ds, outputs, params, title, f"flumekit comparison stage from "
                     f"{inputs['flap']} and {inputs['waves']}")


def summary(inputs, outputs, params) -> Written:
    """Stack the comparisons of every run along ``run`` (phase-resolved variables dropped).

    Parameters
    ----------
    inputs : dict of str to pathlib.Path
        Run -> its ``comparison/<run>.nc``.
    outputs : dict of str to pathlib.Path
        ``dataset``: ``comparison_summary.nc``.
    params : dict
        Unused.

    Returns
    -------
    flumekit.io.atomic.Written
        The file written and its content digest, for the engine.
    """
    return stack_runs(inputs, outputs, "Experiment, linear model and simulator for every run",
                      keep=lambda ds: list(ds.data_vars), drop_dims=("phase",))
