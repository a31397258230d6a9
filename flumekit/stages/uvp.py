"""Stage: UVP beam records -> per-run phase averages -> the campaign's (phase, z, x) field.

The phase reference of every run is a zero up-crossing of the separated incident wave at the
flap (x = 0) (Brito et al. 2020, §2.5-2.6); the N waves averaged are the earliest whole number of
periods from it that lie in the quasi-steady part of the wave field with the UVP beams and the
flap angle clean (:mod:`flumekit.uvp.window`): a probe fault does not move them. The instruments
are taken to share one clock (the virtual flume's do; a real campaign declares offsets).
"""

from __future__ import annotations

from flumekit.io.atomic import Written
from flumekit.pipeline.rules import Rule
from flumekit.stages.context import Context
from flumekit.stages.runs import run_params

VERSION = "5"
NEEDS = "uvp"  # the instrument this stage reads (stages.build_rules)
DEFAULTS = {"n_cycles": 50, "n_phase": 100, "cutoff": 2.0, "order": 4, "margin": 0.01,
            "method": "least_squares", "dx": 0.01, "min_amplitude": None}
DOCS = {
    "n_cycles": "waves averaged per phase, N of Eq. (2) [-] (the paper: 50)",
    "n_phase": "phases per period [-]",
    "cutoff": "low-pass cut-off of the beam velocities [Hz] (the paper: 2)",
    "order": "order of the zero-phase Butterworth low-pass [-]",
    "margin": "distance from the flap face within which channels are masked [m]",
    "method": "velocity decomposition: 'least_squares' or 'paired' (Eqs. 9-10)",
    "dx": "grid spacing of the (phase, z, x) field [m]",
    "min_amplitude": "echo amplitude below which a sample is 'no echo' (above the free "
                     "surface) [counts]; none: no amplitude test",
}


def rules(ctx: Context, params: dict) -> list[Rule]:
    """Return one rule per UVP run, ``uvp/<run>``, and the campaign's field, ``uvp_field``.

    Protocol: :mod:`flumekit.stages`. A run's rule also writes the beams' QC flags,
    ``qc/uvp/<run>.nc``, with the ``[stages.qc]`` parameters of the beams; none without UVP runs.
    """
    from flumekit.stages.qc_params import DEFAULTS as QC_DEFAULTS
    from flumekit.stages.qc_params import UVP_PARAMS

    c = ctx.campaign
    runs = [r for r in c.runs if r.kind == "uvp"]
    qc_params = ctx.stage_params("qc", QC_DEFAULTS)
    qc = {k: qc_params[k] for k in UVP_PARAMS}
    out = []
    for run in runs:
        inputs = {b.name: run.path / f"{b.name}.mfprof" for b in c.uvp.beams}
        inputs.update(campaign=ctx.campaign_file, waves=ctx.out("waves", f"{run.id}.nc"),
                      flap=ctx.out("flap", f"{run.id}.nc"))
        p = {**params, **run_params(run, c), "time_offset": run.clock.get("uvp", 0.0), "qc": qc}
        # the rule checks the beams it reads before analysing them and writes their QC flags
        # too (flumekit.uvp.run_window.checked_window)
        out.append(Rule(f"uvp/{run.id}", "flumekit.stages.uvp_run:build", inputs=inputs,
                        outputs={"dataset": ctx.out("uvp", f"{run.id}.nc"),
                                 "qc": ctx.out("qc", "uvp", f"{run.id}.nc")},
                        params=p, version=VERSION, run=run.id))
    if runs:
        inputs = {r.id: ctx.out("uvp", f"{r.id}.nc") for r in runs}
        inputs["campaign"] = ctx.campaign_file
        out.append(Rule("uvp_field", "flumekit.stages.uvp:field", inputs=inputs,
                        outputs={"dataset": ctx.out("uvp_field.nc")},
                        params={**params, "height": runs[0].height, "period": runs[0].period},
                        version=VERSION))
    return out


def averaging_window(waves, qc, theta, beams, params, pad: float, span=None
                     ) -> tuple[float, float]:
    """Return the start and period [s] of a run's phase average with the rule's parameters.

    :func:`flumekit.uvp.run_window.averaging_window`, whose arguments these are, with ``params``
    of the uvp rule (``n_cycles``, ``qc``, ``time_offset``, ``run``); no clean window of
    ``n_cycles`` periods is an :class:`~flumekit.errors.InputError` naming the files of ``beams``
    (name -> path).
    """
    from flumekit.errors import InputError
    from flumekit.uvp import run_window

    try:
        return run_window.averaging_window(
            waves, qc, theta, list(beams), n_cycles=params["n_cycles"], pad=pad,
            max_gap=float(params["qc"]["max_gap"]), time_offset=float(params["time_offset"]),
            span=span, run=params["run"])
    except ValueError as e:
        raise InputError(", ".join(str(p) for p in beams.values()), str(e)) from None


def clean_beam(beam, qc, name: str, copy: bool = True):
    """Return the beam cleaned with its QC flags (:func:`flumekit.uvp.run_window.clean_beam`).

    The arguments are those of the domain function.
    """
    from flumekit.uvp.run_window import clean_beam

    return clean_beam(beam, qc, name, copy)


def field(inputs, outputs, params) -> Written:
    """Assemble the phase-averaged (phase, z, x) velocity field of every UVP run and write it.

    An action of :mod:`flumekit.stages`: reads every run's ``uvp/<run>.nc`` (keyed by run) and
    the ``campaign`` file, writes ``uvp_field.nc`` with ``method`` and grid spacing ``dx`` [m]
    (:func:`flumekit.uvp.velocity_field`; Brito et al. 2020).
    """
    from pathlib import Path

    from flumekit.campaign import load_campaign
    from flumekit.io.netcdf import read_dataset, write_product
    from flumekit.uvp import velocity_field

    campaign = load_campaign(Path(inputs["campaign"]).parent, runs=False)
    runs = [read_dataset(p) for name, p in sorted(inputs.items()) if name != "campaign"]
    ds = velocity_field(runs, campaign.uvp, height=params["height"], period=params["period"],
                        method=params["method"], dx=params["dx"],
                        water_depth=campaign.flume.water_depth)
    return write_product(ds, outputs["dataset"],
                         "Phase-averaged velocity field in front of the flap",
                         f"flumekit uvp_field stage from {len(runs)} UVP runs", params)
