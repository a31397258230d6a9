"""Stage: the flume's runs against the linear model and the time-domain simulator.

``models/hydro``: the flap's hydrodynamic coefficients over a frequency grid, one container
(with A∞ from the Ogilvie 1964 relation) for the linear model and the simulator: the Renzi &
Dias (2012) thin plate in the flume's channel (default,
:func:`flumekit.flap.renzi_dias.model.channel_container`), or with ``coefficients = "bem"``
and Capytaine installed the thick flap on its foundation by BEM
(:func:`flumekit.flap.comparison.bem_container`). ``comparison/<run>``: the experiment, the
linear model (Eq. A1) and the simulator side by side along ``source``
(:func:`flumekit.flap.comparison.compare_run`); for an irregular run the spectral sum of the
linear model and the simulator driven by the measured incident wave over the analysed span
(:func:`flumekit.flap.comparison.compare_irregular_run`).
"""

from __future__ import annotations

from flumekit.io.atomic import Written
from flumekit.pipeline.rules import Rule
from flumekit.stages.context import Context

# the parameters (DEFAULTS, DOCS) and the choices of linear_pto_damping, in their own module
from flumekit.stages.models_params import DEFAULTS, DOCS, LINEAR_PTO_DAMPING  # noqa: F401
from flumekit.stages.runs import run_params, write_run
from flumekit.stages.summaries import stack_runs, summary_rule

VERSION = "6"
NEEDS = "flap"  # the instrument this stage reads (stages.build_rules)


def rules(ctx: Context, p: dict) -> list[Rule]:
    """Return ``models/hydro``, one ``comparison/<run>`` per run and ``comparison_summary``.

    Protocol: :mod:`flumekit.stages`. An unknown ``coefficients`` or ``linear_pto_damping``
    choice is a :class:`~flumekit.errors.FlumekitError`.
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

    An action of :mod:`flumekit.stages` writing ``models/hydro.nc`` (module notes) from the
    geometry ``depth``, ``flap_width``, ``hinge_height``, ``channel_width``, ``thickness`` [m]
    and ``stiffness`` [N m rad-1], with a radiation impulse response of ``irf_duration`` [s].
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

    An action of :mod:`flumekit.stages`: reads the run's ``flap`` and ``waves`` products,
    ``hydro`` (``models/hydro.nc``) and the ``campaign`` file, writes ``comparison/<run>.nc``.
    """
    from pathlib import Path

    from flumekit.campaign import load_campaign
    from flumekit.flap.comparison import compare_irregular_run, compare_run
    from flumekit.io.netcdf import read_dataset

    campaign = load_campaign(Path(inputs["campaign"]).parent, runs=False)
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
    """Stack every run's ``comparison/<run>.nc`` along ``run`` (without ``phase``), the summary."""
    return stack_runs(inputs, outputs, "Experiment, linear model and simulator for every run",
                      keep=lambda ds: list(ds.data_vars), drop_dims=("phase",))
