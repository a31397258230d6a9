"""Stage: uncertainty of the results: per-run propagation, per-condition statistics and budget.

``uncertainty/<run>`` propagates the campaign's Type B components (``[uncertainty]`` of
campaign.toml) through the waves and flap analyses of a regular run, with the waves and flap
stages' own parameters (:mod:`flumekit.uncertainty.propagation`); ``conditions`` writes the
repeat statistics of every condition with their combined and expanded uncertainties
(``conditions.nc``) and the budgets (``budget.nc``); ``figure/uncertainty_budget`` draws them.
Irregular runs get repeat statistics (Type A) only.
"""

from __future__ import annotations

from flumekit.pipeline.rules import Rule
from flumekit.stages.context import Context
from flumekit.stages.runs import run_params

VERSION = "1"
DEFAULTS = {"draws": 20, "directions": 2, "seed": 2024, "linear": True}
DOCS = {
    "draws": "Monte Carlo draws per run [-]: the speed/accuracy knob (each draw reruns the "
             "waves and flap analyses; the relative standard deviation of a standard "
             "uncertainty from n draws is about 1/sqrt(2 (n - 1)): 16 % at 20, the coverage factor "
             "t_0.975(n - 1) allows for it); 0: repeat statistics only",
    "directions": "random directions of each per-sample input (noise, resolution) in the "
                  "linear propagation and budget [-]",
    "seed": "seed of the draws (with the run's name) [-]",
    "linear": "run the linear (GUM) propagation, on the first run of each condition (its "
              "repeats share the sensitivities): the budget's sensitivities and contributions",
}


def rules(ctx: Context, params: dict) -> list[Rule]:
    """Declare the per-run propagation, the conditions and the budget figure (module notes).

    Protocol: :mod:`flumekit.stages`. ``uncertainty/<run>`` per regular run (with draws), each
    with the waves and flap stages' own parameters, ``conditions`` and
    ``figure/uncertainty_budget``.
    """
    import zlib

    from flumekit.stages import flap as flap_stage
    from flumekit.stages import waves as waves_stage

    c = ctx.campaign
    has_flap = "flap" in c.instruments
    waves_p = ctx.stage_params("waves", waves_stage.DEFAULTS)
    flap_p = ctx.stage_params("flap", flap_stage.DEFAULTS) if has_flap else {}
    out = []
    regular = [r for r in c.runs if not r.irregular] if params["draws"] > 0 else []
    seen = set()
    for run in regular:
        first = (run.period, run.height) not in seen
        seen.add((run.period, run.height))
        inputs = {"eta": ctx.out("eta", f"{run.id}.nc"), "campaign": ctx.campaign_file}
        if not c.probes.calibrated:
            inputs["calibration"] = ctx.out("calibration.nc")
        if has_flap:
            inputs["flap"] = ctx.out("qc", "flap", f"{run.id}.nc")
        p = {**params, "seed": [int(params["seed"]), zlib.crc32(run.id.encode())],
             "depth": c.flume.water_depth, "separation_probes": list(c.probes.separation),
             "waves": {k: waves_p[k] for k in (
                 "method", "x_ref", "n_harmonics", "bound_harmonics", "amplitude_dispersion",
                 "tolerance", "min_cycles", "noise_factor", "reflection_tolerance")},
             "flap": {k: flap_p[k] for k in ("cutoff", "tolerance", "n_phase",
                                             "max_flagged_fraction")} if has_flap else None,
             **run_params(run, c), "linear": bool(params["linear"] and first)}
        out.append(Rule(f"uncertainty/{run.id}", "flumekit.stages.uncertainty_run:run_uncertainty",
                        inputs=inputs, outputs={"dataset": ctx.out("uncertainty",
                                                                   f"{run.id}.nc")},
                        params=p, version=VERSION, run=run.id))
    inputs = {"waves": ctx.out("waves_summary.nc")}
    if has_flap:
        inputs["flap"] = ctx.out("flap_summary.nc")
    inputs.update({f"run:{r.id}": ctx.out("uncertainty", f"{r.id}.nc") for r in regular})
    out.append(Rule("conditions", "flumekit.stages.uncertainty_run:conditions", inputs=inputs,
                    outputs={"dataset": ctx.out("conditions.nc"),
                             "budget": ctx.out("budget.nc")},
                    params={"draws": params["draws"],
                            "scale": None if c.scale is None else dict(c.scale.__dict__)},
                    version=VERSION))
    if regular and params["linear"]:
        from flumekit.stages.figures import DEFAULTS as FIG

        formats = ctx.stage_params("figures", FIG)["formats"]
        formats = [formats] if isinstance(formats, str) else list(formats)
        out.append(Rule("figure/uncertainty_budget", "flumekit.stages.figures_run:draw",
                        inputs={"budget": ctx.out("budget.nc")},
                        outputs={f: ctx.out("figures", f"uncertainty_budget.{f}")
                                 for f in formats},
                        params={"figure": "uncertainty_budget"}, version=VERSION))
    return out
