"""Stage: incident/reflected separation and wave statistics per run, and their campaign summary."""

from __future__ import annotations

from flumekit.io.atomic import Written
from flumekit.pipeline.rules import Rule
from flumekit.stages.context import Context
from flumekit.stages.runs import run_params, write_run
from flumekit.stages.summaries import stack_runs, summary_rule

VERSION = "6"
DEFAULTS = {"method": "mansard_funke", "x_ref": 0.0, "n_harmonics": 8, "bound_harmonics": True,
            "amplitude_dispersion": True, "tolerance": 0.02, "min_cycles": 10,
            "noise_factor": 4.0, "reflection_tolerance": 0.002, "height_tolerance": 0.25,
            "height_warning": 0.1,
            "irregular_method": "zelt_skjelbreia", "gauge_weights": None, "span": None,
            "n_bins": None, "sea_state_tolerance": 0.25, "sea_state_warning": 0.05,
            "low_frequency_warning": 0.05}
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
    "noise_factor": "noise-aware quasi-steady criterion, used when 'tolerance' keeps fewer "
                    "than min_cycles periods or fewer than 80 % of its own: each probe's "
                    "tolerance becomes noise_factor x the robust relative scatter of its "
                    "crests, tested on the median of each cycle and its neighbours (4: the "
                    "heavier-than-Gaussian tail of noisy crests); 0 = the paper's criterion "
                    "only [-]",
    "reflection_tolerance": "the separated first-harmonic reflection must have settled within "
                            "the crests' window: largest change of the complex reflection "
                            "coefficient over blocks of 3 periods (or noise_factor x their "
                            "scatter) [-]; 0 = not tested",
    "height_tolerance": "declared run height vs the measured incident height: relative "
                        "difference beyond which the run is refused [-]",
    "height_warning": "relative difference beyond which a warning is recorded [-]",
    "irregular_method": "separation method of irregular runs: 'zelt_skjelbreia' (2 or more "
                        "probes, Zelt & Skjelbreia 1992), 'mansard_funke' (3) or "
                        "'goda_suzuki' (2)",
    "gauge_weights": "irregular runs: weight of each separation probe in the least squares "
                     "(Zelt & Skjelbreia 1992), in the order of [probes] separation; none: "
                     "equal",
    "span": "irregular runs: [start, end] of the analysed span [s]; none: detected (after the "
            "wavemaker's ramp and the reflection's travel to the probes)",
    "n_bins": "irregular runs: periodogram bins per band of the smoothed spectra and Kr(f) "
              "[-]; none: the bins spanning fp/16 (at least 4)",
    "sea_state_tolerance": "declared hm0 and tp (or te) vs the measured incident ones: "
                           "relative difference beyond which the run is refused [-]",
    "sea_state_warning": "relative difference beyond which a warning is recorded [-] (model-"
                         "test practice: 5 %)",
    "low_frequency_warning": "irregular runs: share of the variance below fp/2 (bound long "
                             "waves, seiching) beyond which the run is flagged [-]",
}


def rules(ctx: Context, params: dict) -> list[Rule]:
    """Return one rule per run, ``waves/<run>``, and ``waves_summary`` (:mod:`flumekit.stages`)."""
    c = ctx.campaign
    out = []
    for run in c.runs:
        p = {**params, "depth": c.flume.water_depth, "density": c.flume.density,
             "separation_probes": list(c.probes.separation), **run_params(run, c)}
        out.append(Rule(f"waves/{run.id}", "flumekit.stages.waves:build",
                        inputs={"eta": ctx.out("eta", f"{run.id}.nc"),
                                "run": run.path / "run.toml", "probes": run.file("probes")},
                        outputs={"dataset": ctx.out("waves", f"{run.id}.nc")},
                        params=p, version=VERSION, run=run.id))
    out.append(summary_rule(ctx, "waves", VERSION))
    return out


def build(inputs, outputs, params) -> Written:
    """Separate a run's incident and reflected waves, compute its statistics and write them.

    An action of :mod:`flumekit.stages`: reads ``eta``, writes ``waves/<run>.nc``; a record the
    analysis cannot use is an :class:`~flumekit.errors.InputError` naming ``probes`` (the raw
    file); a declared height or sea state off the measured one beyond its warning level is a
    recorded warning, beyond its tolerance an error naming ``run`` (run.toml). Analyses and
    references: :func:`flumekit.waves.analyse_run`, :func:`flumekit.waves.analyse_irregular_run`.
    """
    import warnings

    from flumekit.conventions import WARNINGS
    from flumekit.errors import InputError
    from flumekit.io.netcdf import read_dataset
    from flumekit.qc.checks import check_declared, check_height
    from flumekit.stages.waves_run import irregular, regular

    eta_ds = read_dataset(inputs["eta"])
    eta = eta_ds["eta"]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            ds = (irregular if params["kind"] == "irregular" else regular)(eta, params)
        except ValueError as e:  # a dead probe, a record too short: the message names the probe
            raise InputError(inputs["probes"], str(e)) from None
    # kept in the dataset, where the make summary, the summaries and the report find them
    recorded = [f"{inputs['probes']}: {w.message}" for w in caught
                if issubclass(w.category, UserWarning)]
    # the declared height (sea state) only labels the run (the analysis uses the measured one):
    # a moderate disagreement is a warning, a gross one an error; an undeclared one is unchecked
    warned = []
    if params["height"] is not None:
        warned.append(check_height(params["height"], float(ds["incident_height"]),
                                   params["height_tolerance"], params["height_warning"],
                                   inputs["run"], "incident height at the flap"))
    sea = params.get("sea_state") or {}
    for key, measured, unit, what in (
            ("hm0", "hm0", "m", "incident Hm0 at the flap"),
            ("tp", "tp", "s", "incident peak period (smoothed spectrum)"),
            ("te", "te", "s", "incident energy period Tm-1,0")):
        if sea.get(key) is not None:
            warned.append(check_declared(key, sea[key], float(ds[measured]), unit,
                                         params["sea_state_tolerance"],
                                         params["sea_state_warning"], inputs["run"], what,
                                         "sea_state_tolerance"))
    warnings_ = [w for w in (eta_ds.attrs.get(WARNINGS, ""), *recorded, *warned) if w]
    if warnings_:
        ds.attrs[WARNINGS] = "\n".join(warnings_)
    return write_run(ds, outputs, params, "Incident and reflected waves",
                     f"flumekit waves stage from {inputs['eta']}", record=eta_ds)


def summary(inputs, outputs, params) -> Written:
    """Stack every run's ``waves/<run>.nc`` along ``run`` into ``waves_summary.nc``."""
    return stack_runs(inputs, outputs, "Wave statistics of every run")
