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
from flumekit.stages.runs import run_params, write_run

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
                 "tolerance", "min_cycles", "noise_factor")},
             "flap": {k: flap_p[k] for k in ("cutoff", "tolerance", "n_phase",
                                             "max_flagged_fraction")} if has_flap else None,
             **run_params(run, c), "linear": bool(params["linear"] and first)}
        out.append(Rule(f"uncertainty/{run.id}", "flumekit.stages.uncertainty:run_uncertainty",
                        inputs=inputs, outputs={"dataset": ctx.out("uncertainty",
                                                                   f"{run.id}.nc")},
                        params=p, version=VERSION, run=run.id))
    inputs = {"waves": ctx.out("waves_summary.nc")}
    if has_flap:
        inputs["flap"] = ctx.out("flap_summary.nc")
    inputs.update({f"run:{r.id}": ctx.out("uncertainty", f"{r.id}.nc") for r in regular})
    out.append(Rule("conditions", "flumekit.stages.uncertainty:conditions", inputs=inputs,
                    outputs={"dataset": ctx.out("conditions.nc"),
                             "budget": ctx.out("budget.nc")},
                    params={"draws": params["draws"],
                            "scale": None if c.scale is None else dict(c.scale.__dict__)},
                    version=VERSION))
    if regular and params["linear"]:
        from flumekit.stages.figures import DEFAULTS as FIG

        formats = ctx.stage_params("figures", FIG)["formats"]
        formats = [formats] if isinstance(formats, str) else list(formats)
        out.append(Rule("figure/uncertainty_budget", "flumekit.stages.figures:draw",
                        inputs={"budget": ctx.out("budget.nc")},
                        outputs={f: ctx.out("figures", f"uncertainty_budget.{f}")
                                 for f in formats},
                        params={"figure": "uncertainty_budget"}, version=VERSION))
    return out


def run_uncertainty(inputs, outputs, params) -> None:
    """Monte Carlo and linear propagation of one run (:func:`~flumekit.uncertainty.
    propagation.propagate`)."""
    import warnings
    from pathlib import Path

    from flumekit.campaign import load_campaign
    from flumekit.conventions import WARNINGS
    from flumekit.io.netcdf import read_dataset
    from flumekit.uncertainty.propagation import RunModel, propagate, resolve_inputs

    campaign = load_campaign(Path(inputs["campaign"]).parent)
    cal = read_dataset(inputs["calibration"]) if "calibration" in inputs else None
    eta = read_dataset(inputs["eta"])["eta"]
    if cal is not None and list(cal.probe.values) != list(eta.probe.values):
        cal = cal.sel(probe=list(eta.probe.values))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        comps = resolve_inputs(campaign.uncertainty, calibration=cal,
                               counts_per_metre=(campaign.encoder.counts_per_metre
                                                 if campaign.encoder else None),
                               flap="flap" in inputs)
    recorded = [f"{inputs['campaign']}: {w.message}" for w in caught
                if issubclass(w.category, UserWarning)]
    for w in recorded:
        print(f"warning: run {params['run']}: {w}")
    record = kw = None
    if "flap" in inputs:
        raw = read_dataset(inputs["flap"])
        record = {k: raw[k].values for k in ("time", "encoder_counts", "chamber_pressure")}
        kw = {"flap": campaign.flap, "pto": campaign.pto, "encoder": campaign.encoder,
              **params["flap"]}
    model = RunModel(eta, params["depth"], params["period"],
                     {**params["waves"], "separation_probes": params["separation_probes"]},
                     record, kw)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        ds = propagate(model, comps, draws=int(params["draws"]), seed=params["seed"],
                       directions=int(params["directions"]),
                       linear_check=bool(params["linear"]))
    recorded += [f"run {params['run']}: {w.message}" for w in caught
                 if issubclass(w.category, UserWarning)]
    if recorded:
        ds.attrs[WARNINGS] = "\n".join(recorded)
    write_run(ds, outputs, params, "Uncertainty of the results",
              f"flumekit uncertainty stage from {inputs['eta']}")


def conditions(inputs, outputs, params) -> None:
    """Repeat statistics per condition with the runs' propagated uncertainties, and the
    budget."""
    import xarray as xr

    from flumekit.io.netcdf import read_dataset, write_product
    from flumekit.uncertainty import condition_statistics
    from flumekit.uncertainty.combine import combine

    summary = read_dataset(inputs["waves"])
    if "flap" in inputs:
        f = read_dataset(inputs["flap"])
        summary = xr.merge([summary, f[[v for v in f.data_vars if v not in summary]]],
                           compat="override", join="exact")
    cond = condition_statistics(summary)
    runs = sorted(k for k in inputs if k.startswith("run:"))
    budget = xr.Dataset(coords=cond.coords)
    if runs:
        stacked = xr.concat([read_dataset(inputs[k]).expand_dims("run") for k in runs],
                            dim="run", coords="all", compat="override", join="outer")
        cond, budget = combine(cond, stacked)
    if params.get("scale"):  # full-scale values in the report (flumekit.scale)
        sc = params["scale"]
        cond.attrs.update({"froude_scale": sc["factor"], "model_density": sc["model_density"],
                           "prototype_density": sc["prototype_density"]})
    source = f"flumekit conditions stage from {len(summary.run)} runs"
    write_product(cond, outputs["dataset"], "Repeat statistics and uncertainty per condition",
                  source, params)
    write_product(budget, outputs["budget"], "Uncertainty budget per condition", source,
                  params)
