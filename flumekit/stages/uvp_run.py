"""Action of the uvp stage's per-run rule (:mod:`flumekit.stages.uvp`): the beams read once,
checked where the average reads them, their flags written, cleaned and phase-averaged."""

from __future__ import annotations

from flumekit.io.atomic import Written
from flumekit.stages.common import COMPRESS, gross_range, write_qc
from flumekit.stages.runs import write_run


def beam_checker(beams: dict, params: dict):
    """The quality control of a run's UVP beams over a span [s] (probes' clock): the flags of
    :func:`flumekit.qc.record.beam_flags` with the [stages.qc] parameters ``params["qc"]``
    (:data:`flumekit.stages.qc_params.UVP_PARAMS`) of the uvp rule; pure (nothing written)."""
    from flumekit.qc.record import Thresholds, beam_flags

    qc = params["qc"]
    th = Thresholds.from_params(qc)

    def check(span):
        return beam_flags(beams, span, th, time_offset=float(params.get("time_offset", 0.0)),
                          gross_range=gross_range(qc["velocity_range"]))

    return check


def write_beam_flags(flags, path, params: dict, sources) -> Written:
    """Write the UVP beams' QC flags (:func:`beam_checker`) to ``path`` (``qc/uvp/<run>.nc``)."""
    return write_qc(flags, {"dataset": path}, {**params, "max_gap": params["qc"]["max_gap"]},
                    "Quality-control flags of the UVP beam velocities",
                    "flumekit qc stage from " + ", ".join(map(str, sources)),
                    compress=COMPRESS["uvp"])


def build(inputs, outputs, params) -> list[Written]:
    """The run's beams read once, checked where the average reads them
    (:func:`flumekit.uvp.run_window.checked_window`, the flags written), cleaned and
    phase-averaged."""
    from pathlib import Path

    from flumekit.campaign import load_campaign
    from flumekit.errors import InputError
    from flumekit.io.mfprof import read_mfprof
    from flumekit.io.netcdf import read_dataset
    from flumekit.uvp import phase_average_beams
    from flumekit.uvp.run_window import checked_window, clean_beam, waves_span

    campaign = load_campaign(Path(inputs["campaign"]).parent)
    names = [b.name for b in campaign.uvp.beams]
    raw = {n: read_mfprof(inputs[n]) for n in names}
    waves = read_dataset(inputs["waves"])
    try:
        span = waves_span(waves)
    except ValueError as e:
        raise InputError(inputs["waves"], f"run {params['run']}: {e}") from None
    theta = read_dataset(inputs["flap"])["theta"]
    files = [inputs[n] for n in names]
    offset = float(params["time_offset"])
    try:
        start, period, qc = checked_window(
            waves, theta, raw, beam_checker(raw, params), n_cycles=params["n_cycles"],
            cutoff=params["cutoff"], max_gap=float(params["qc"]["max_gap"]), span=span,
            time_offset=offset, run=params["run"])
    except ValueError as e:
        raise InputError(", ".join(map(str, files)), str(e)) from None
    qc_file = write_beam_flags(qc, outputs["qc"], params, files)
    beams = {n: clean_beam(raw[n], qc, n, copy=False) for n in names}  # read for this rule
    if offset:  # the run file's declared clock offset of the UVP [s]
        beams = {k: v.assign_coords(time=v["time"] + offset) for k, v in beams.items()}
    ds = phase_average_beams(beams, campaign.uvp, params["uvp_elevation"], period=period,
                             start=start, n_cycles=params["n_cycles"], n_phase=params["n_phase"],
                             cutoff=params["cutoff"], order=params["order"], theta=theta,
                             flap_thickness=campaign.flap.thickness, margin=params["margin"],
                             min_amplitude=params["min_amplitude"])
    return [qc_file, write_run(ds, outputs, params, "Phase-averaged UVP beam velocities",
                               "flumekit uvp stage from " + ", ".join(str(inputs[n])
                                                                      for n in names))]
