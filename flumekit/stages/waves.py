"""Stage: incident/reflected separation and wave statistics per run, and their campaign summary."""

from __future__ import annotations

from flumekit.pipeline.rules import Rule
from flumekit.stages.context import Context
from flumekit.stages.runs import run_params, stack_runs, summary_rule, write_run

VERSION = "3"
DEFAULTS = {"method": "mansard_funke", "x_ref": 0.0, "n_harmonics": 4, "bound_harmonics": True,
            "tolerance": 0.02, "min_cycles": 10, "height_tolerance": 0.25,
            "height_warning": 0.1}


def rules(ctx: Context) -> list[Rule]:
    c = ctx.campaign
    params = ctx.stage_params("waves", DEFAULTS)
    out = []
    for run in c.runs:
        p = {**params, "depth": c.flume.water_depth,
             "separation_probes": list(c.probes.separation), **run_params(run)}
        out.append(Rule(f"waves/{run.id}", "flumekit.stages.waves:build",
                        inputs={"eta": ctx.out("eta", f"{run.id}.nc"),
                                "run": run.path / "run.toml"},
                        outputs={"dataset": ctx.out("waves", f"{run.id}.nc")},
                        params=p, version=VERSION, run=run.id))
    out.append(summary_rule(ctx, "waves", VERSION))
    return out


def build(inputs, outputs, params) -> None:
    import warnings

    from flumekit.io.netcdf import read_dataset
    from flumekit.qc.checks import check_height
    from flumekit.stages.qc import WARNINGS
    from flumekit.waves import analyse_run

    eta_ds = read_dataset(inputs["eta"])
    eta = eta_ds["eta"]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        ds = analyse_run(eta, params["depth"], params["period"], params["x_ref"],
                         method=params["method"], separation_probes=params["separation_probes"],
                         n_harmonics=params["n_harmonics"],
                         bound_harmonics=params["bound_harmonics"],
                         tolerance=params["tolerance"], min_cycles=params["min_cycles"])
    for w in caught:
        if issubclass(w.category, UserWarning):
            print(f"warning: run {params['run']}: {w.message}")
    # the declared height only labels the run (the analysis uses the measured one), so a
    # moderate disagreement is a warning and a gross one an error
    warned = check_height(params["height"], float(ds["incident_height"]),
                          params["height_tolerance"], params["height_warning"], inputs["run"],
                          "incident height at the flap")
    warnings_ = [w for w in (eta_ds.attrs.get(WARNINGS, ""), warned) if w]
    if warnings_:
        ds.attrs[WARNINGS] = "\n".join(warnings_)
    write_run(ds, outputs, params, "Incident and reflected waves",
              f"flumekit waves stage from {inputs['eta']}")


def summary(inputs, outputs, params) -> None:
    stack_runs(inputs, outputs, "Wave statistics of every run")
