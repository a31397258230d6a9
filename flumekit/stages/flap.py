"""Stage: flap angle, PTO forces, torque-balance inversion and power per run, and their summary.

A regular-wave run is analysed over its quasi-steady window (:func:`flumekit.flap.analyse_run`),
an irregular one (``kind = "irregular"``) over the span its waves stage analysed, with the
spectral energy flux J of that stage (:func:`flumekit.flap.analyse_irregular_run`).
"""

from __future__ import annotations

from flumekit.io.atomic import Written
from flumekit.pipeline.rules import Rule
from flumekit.stages.context import Context
from flumekit.stages.runs import run_params, write_run
from flumekit.stages.summaries import stack_runs, summary_rule

VERSION = "5"
NEEDS = "flap"  # the instrument this stage reads (stages.build_rules)
DEFAULTS = {"cutoff": 4.0, "tolerance": 0.02, "n_phase": 100, "max_flagged_fraction": 0.0,
            "record_length_tolerance": 0.2}
DOCS = {
    "cutoff": "cut-off of the zero-phase 4th-order Butterworth low-pass applied to theta before "
              "differentiation [Hz]",
    "tolerance": "quasi-steady window of the flap motion: relative crest tolerance [-] (0.02)",
    "n_phase": "phase points per cycle of the phase averages [-]",
    "max_flagged_fraction": "largest fraction of encoder samples outside the domain of Eq. (1) "
                            "that is interpolated over instead of refused [-]",
    "record_length_tolerance": "the flap and probe records of a run may differ in duration by "
                               "this share of the longer one; beyond it the shorter is refused "
                               "(cut short, or another run's) [-]",
}


def rules(ctx: Context, params: dict) -> list[Rule]:
    """Return one rule per run, ``flap/<run>``, and ``flap_summary`` (:mod:`flumekit.stages`)."""
    c = ctx.campaign
    out = []
    for run in c.runs:
        p = {**params, **run_params(run, c), "sampling_rate": c.encoder.sampling_rate}
        out.append(Rule(f"flap/{run.id}", "flumekit.stages.flap:build",
                        inputs={"flap": ctx.out("qc", "flap", f"{run.id}.nc"),
                                "campaign": ctx.campaign_file,
                                "waves": ctx.out("waves", f"{run.id}.nc"),
                                # named, not read: the probe record the waves come from
                                "probes": run.file("probes")},
                        outputs={"dataset": ctx.out("flap", f"{run.id}.nc")},
                        params=p, version=VERSION, run=run.id))
    out.append(summary_rule(ctx, "flap", VERSION))
    return out


def _span(t) -> float:
    """Duration of a time axis [s] (seconds, or datetimes as decoded from CF units)."""
    import numpy as np

    d = t[-1] - t[0]
    return float(d / np.timedelta64(1, "s")) if np.asarray(t).dtype.kind == "M" else float(d)


def build(inputs, outputs, params) -> Written:
    """Analyse a run's flap angle, PTO forces, torque balance and power and write them.

    An action of :mod:`flumekit.stages`: reads the QC'd encoder and pressure record ``flap``,
    the run's ``waves`` product and the ``campaign`` file, writes ``flap/<run>.nc``;
    ``probes`` (the raw probe file) is only named in messages. Records whose durations
    disagree, an irregular run's waves product without the analysed span or energy flux, and
    an encoder record that cannot be analysed are an :class:`~flumekit.errors.InputError`.
    The analyses and their references are :func:`flumekit.flap.analyse_run` and
    :func:`flumekit.flap.analyse_irregular_run`.
    """
    from pathlib import Path

    from flumekit.campaign import load_campaign
    from flumekit.conventions import SOURCE_FILE
    from flumekit.errors import InputError
    from flumekit.flap import analyse_irregular_run, analyse_run
    from flumekit.io.netcdf import read_dataset
    from flumekit.qc import checks

    campaign = load_campaign(Path(inputs["campaign"]).parent, runs=False)
    raw = read_dataset(inputs["flap"])  # quality-controlled encoder counts and pressure
    waves = read_dataset(inputs["waves"])
    checks.check_durations(
        {"flap": _span(raw["time"].values), "probe": _span(waves["time"].values)},
        {"flap": raw.attrs.get(SOURCE_FILE, inputs["flap"]),
         "probe": inputs.get("probes", inputs["waves"])},
        params["record_length_tolerance"])
    irregular = params.get("kind") == "irregular"
    missing = [k for k in ("analysis_start", "analysis_end", "energy_flux") if k not in waves]
    if irregular and missing:
        raise InputError(inputs["waves"], f"the waves product of irregular run {params['run']} "
                         f"lacks {', '.join(missing)}")
    if irregular and not float(waves["energy_flux"]) > 0:  # no incident wave: no capture width
        raise InputError(inputs["waves"], f"energy_flux = {float(waves['energy_flux'])} W m-1: "
                         "the incident spectrum of the separation holds no energy")
    try:
        if irregular:  # over the span the waves stage analysed, with its spectral flux J
            ds = analyse_irregular_run(
                raw["time"].values, raw["encoder_counts"].values,
                raw["chamber_pressure"].values, flap=campaign.flap, pto=campaign.pto,
                encoder=campaign.encoder, analysis_start=float(waves["analysis_start"]),
                analysis_end=float(waves["analysis_end"]),
                energy_flux=float(waves["energy_flux"]), cutoff=params["cutoff"],
                max_flagged_fraction=params["max_flagged_fraction"])
        else:
            ds = analyse_run(raw["time"].values, raw["encoder_counts"].values,
                             raw["chamber_pressure"].values, flap=campaign.flap,
                             pto=campaign.pto, encoder=campaign.encoder,
                             depth=campaign.flume.water_depth,
                             period=float(waves["measured_period"]),
                             incident_height=float(waves["incident_height"]),
                             cutoff=params["cutoff"], tolerance=params["tolerance"],
                             n_phase=params["n_phase"],
                             max_flagged_fraction=params["max_flagged_fraction"])
    except ValueError as e:  # a stuck encoder, a record too short: name the file
        raise InputError(raw.attrs.get(SOURCE_FILE, inputs["flap"]),
                         f"encoder and pressure record: {e}") from None
    # stored as they are: these dense float records (computed from measured noise) deflate by
    # a third only, and inflating them would be most of the cost of opening the stage's runs
    # (open_processed reads every run's records)
    return write_run(ds, outputs, params, "Flap dynamics, PTO and power",
                     f"flumekit flap stage from {inputs['flap']} and {inputs['waves']}", record=raw,
                     compress=False)


def summary(inputs, outputs, params) -> Written:
    """Stack every run's ``flap/<run>.nc`` along ``run`` into ``flap_summary.nc``."""
    return stack_runs(inputs, outputs, "Flap amplitudes, torques and power of every run")
