"""Stage: incident/reflected separation and wave statistics per run, and their campaign summary."""

from __future__ import annotations

from flumekit.io.atomic import Written
from flumekit.pipeline.rules import Rule
from flumekit.stages.context import Context
from flumekit.stages.runs import run_params, stack_runs, summary_rule, write_run

VERSION = "4"
DEFAULTS = {"method": "mansard_funke", "x_ref": 0.0, "n_harmonics": 8, "bound_harmonics": True,
            "amplitude_dispersion": True, "tolerance": 0.02, "min_cycles": 10,
            "noise_factor": 3.0, "height_tolerance": 0.25, "height_warning": 0.1}
DOCS = {
    "method": "separation method: 'mansard_funke' (3 probes), 'goda_suzuki' (2) or "
              "'zelt_skjelbreia' (2 or more)",
    "x_ref": "position where the incident and reflected waves are returned [m] (the flap hinge)",
    "n_harmonics": "harmonics of the measured frequency in the analysis band [-] (8: the "
                   "harmonics beyond the 4th hold 1.5 % of the height of T = 3.5 s, H = 0.25 m)",
    "bound_harmonics": "solve harmonics n >= 2 as bound waves (wavenumber n k1)",
    "amplitude_dispersion": "separate again with the nonlinear (stream-function) wavenumbers of "
                            "the separated incident and reflected heights (a steep wave is up "
                            "to 5 % longer than linear theory says)",
    "tolerance": "quasi-steady window: largest relative deviation of a cycle's crest from the "
                 "amplitude scale [-] (Brito et al. 2020, §2.5: 0.02)",
    "min_cycles": "fewest whole periods the probes' common quasi-steady window must hold [-]",
    "noise_factor": "quasi-steady fallback when 'tolerance' leaves fewer than min_cycles "
                    "periods: each probe's tolerance becomes noise_factor x the robust relative "
                    "scatter of its crests (3: a steady cycle is rejected with probability "
                    "0.3 %); 0 = the paper's criterion only [-]",
    "height_tolerance": "declared run height vs the measured incident height: relative "
                        "difference beyond which the run is refused [-]",
    "height_warning": "relative difference beyond which a warning is recorded [-]",
}


def rules(ctx: Context, params: dict) -> list[Rule]:
    c = ctx.campaign
    out = []
    for run in c.runs:
        p = {**params, "depth": c.flume.water_depth,
             "separation_probes": list(c.probes.separation), **run_params(run)}
        out.append(Rule(f"waves/{run.id}", "flumekit.stages.waves:build",
                        inputs={"eta": ctx.out("eta", f"{run.id}.nc"),
                                "run": run.path / "run.toml", "probes": run.file("probes")},
                        outputs={"dataset": ctx.out("waves", f"{run.id}.nc")},
                        params=p, version=VERSION, run=run.id))
    out.append(summary_rule(ctx, "waves", VERSION))
    return out


def build(inputs, outputs, params) -> Written:
    import warnings

    from flumekit.errors import InputError
    from flumekit.io.netcdf import read_dataset
    from flumekit.qc.checks import check_height
    from flumekit.stages.qc import WARNINGS
    from flumekit.waves import analyse_run

    eta_ds = read_dataset(inputs["eta"])
    eta = eta_ds["eta"]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            ds = analyse_run(eta, params["depth"], params["period"], params["x_ref"],
                             method=params["method"],
                             separation_probes=params["separation_probes"],
                             n_harmonics=params["n_harmonics"],
                             bound_harmonics=params["bound_harmonics"],
                             amplitude_dispersion=params["amplitude_dispersion"],
                             tolerance=params["tolerance"], min_cycles=params["min_cycles"],
                             noise_factor=params["noise_factor"])
        except ValueError as e:  # a dead probe, a record too short: the message names the probe
            raise InputError(inputs["probes"], str(e)) from None
    for w in caught:
        if issubclass(w.category, UserWarning):
            print(f"warning: run {params['run']}: {w.message}")
    # the declared height only labels the run (the analysis uses the measured one), so a
    # moderate disagreement is a warning and a gross one an error; an undeclared one is not
    # checked
    warned = None
    if params["height"] is not None:
        warned = check_height(params["height"], float(ds["incident_height"]),
                              params["height_tolerance"], params["height_warning"],
                              inputs["run"], "incident height at the flap")
    warnings_ = [w for w in (eta_ds.attrs.get(WARNINGS, ""), warned) if w]
    if warnings_:
        ds.attrs[WARNINGS] = "\n".join(warnings_)
    return write_run(ds, outputs, params, "Incident and reflected waves",
                     f"flumekit waves stage from {inputs['eta']}", record=eta_ds)


def report(path) -> str:
    """One line of a run's wave statistics for the make summary."""
    from flumekit.io.netcdf import read_dataset

    ds = read_dataset(path)
    crit = ds["steady_tolerance"].attrs.get("criterion", "tolerance") \
        if "steady_tolerance" in ds else "tolerance"
    return (f"first-harmonic Kr = {float(ds.reflection_coefficient):.3f}, "
            f"H_I = {float(ds.incident_height):.4g} m, T = {float(ds.measured_period):.4g} s, "
            f"{int(ds.steady_cycles)} steady cycles ({crit} criterion)")


def summary(inputs, outputs, params) -> Written:
    return stack_runs(inputs, outputs, "Wave statistics of every run")
