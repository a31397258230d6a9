"""The uncertainty stage's actions: the propagation of one run, the conditions and budgets.

:mod:`flumekit.stages.uncertainty` declares the rules.
"""

from __future__ import annotations

from flumekit.stages.runs import write_run


def run_uncertainty(inputs, outputs, params) -> None:
    """Propagate the uncertainty of one run by Monte Carlo and linearly, and write it.

    :func:`flumekit.uncertainty.propagation.propagate` (JCGM 101:2008 Monte Carlo, JCGM
    100:2008 linear propagation) of the campaign's Type B components through the run's waves
    and flap analyses. An action of :mod:`flumekit.stages`: reads ``campaign``, ``eta`` and
    optionally ``calibration`` and the raw ``flap`` record; its parameters carry the waves and
    flap stages' own beside ``draws``, ``seed``, ``directions`` and ``linear``.
    """
    import warnings
    from pathlib import Path

    from flumekit.campaign import load_campaign
    from flumekit.conventions import WARNINGS
    from flumekit.io.netcdf import read_dataset
    from flumekit.uncertainty.propagation import RunModel, propagate, resolve_inputs

    campaign = load_campaign(Path(inputs["campaign"]).parent, runs=False)
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
    # recorded in the dataset, where the make summary reads them (a worker prints nothing)
    recorded = [f"{inputs['campaign']}: {w.message}" for w in caught
                if issubclass(w.category, UserWarning)]
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
    """Write the repeat statistics per condition with the runs' uncertainties, and the budget.

    An action of :mod:`flumekit.stages`: reads the ``waves`` (and ``flap``) summaries and each
    run's ``run:<id>`` uncertainty dataset, writes ``dataset`` (conditions.nc) and ``budget``
    (budget.nc); optional ``scale``: the Froude scale of the report.
    """
    import xarray as xr

    from flumekit.io.netcdf import read_dataset, write_product
    from flumekit.io.processed import stack_files
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
        stacked = stack_files([inputs[k] for k in runs], coords="all")
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
