"""Action of the uvp stage's per-run rule (:mod:`flumekit.stages.uvp`).

The beams are read once, checked where the average reads them, their flags written, cleaned
and phase-averaged.
"""

from __future__ import annotations

from flumekit.io.atomic import Written
from flumekit.stages.common import COMPRESS, gross_range, write_qc
from flumekit.stages.runs import write_run


def beam_checker(beams: dict, params: dict):
    """Return the quality control of a run's UVP beams over a span.

    Parameters
    ----------
    beams : dict of str to xarray.Dataset
        The run's beam records.
    params : dict
        The uvp rule's parameters: ``qc`` holds the ``[stages.qc]`` parameters of
        :data:`flumekit.stages.qc_params.UVP_PARAMS`, ``time_offset`` [s] the UVP's clock.

    Returns
    -------
    callable
        ``check(span)``: the flags of :func:`flumekit.qc.record.beam_flags` over ``span``
        [s] (probes' clock); pure (nothing written).
    """
    from flumekit.qc.record import Thresholds, beam_flags

    qc = params["qc"]
    th = Thresholds.from_params(qc)

    def check(span):
        return beam_flags(beams, span, th, time_offset=float(params.get("time_offset", 0.0)),
                          gross_range=gross_range(qc["velocity_range"]))

    return check


def write_beam_flags(flags, path, params: dict, sources) -> Written:
    """Write the UVP beams' QC flags (:func:`beam_checker`).

    Parameters
    ----------
    flags : xarray.Dataset
        The flags.
    path : pathlib.Path
        ``qc/uvp/<run>.nc``.
    params : dict
        The uvp rule's parameters.
    sources : sequence of path-like
        The beam files, named in the product.

    Returns
    -------
    flumekit.io.atomic.Written
        The file written and its content digest.
    """
    return write_qc(flags, {"dataset": path}, {**params, "max_gap": params["qc"]["max_gap"]},
                    "Quality-control flags of the UVP beam velocities",
                    "flumekit qc stage from " + ", ".join(map(str, sources)),
                    compress=COMPRESS["uvp"])


def build(inputs, outputs, params) -> list[Written]:
    """Phase-average a run's UVP beams and write them with their QC flags.

    The beams are read once, checked where the average reads them
    (:func:`flumekit.uvp.run_window.checked_window`, the flags written), cleaned and
    phase-averaged (:func:`flumekit.uvp.phase_average_beams`; Brito et al. 2020).

    An action of :mod:`flumekit.stages`: reads each beam's ``.mfprof`` file (keyed by beam), the
    run's ``waves`` and ``flap`` products and the ``campaign`` file; writes ``dataset``
    (``uvp/<run>.nc``) and ``qc`` (``qc/uvp/<run>.nc``), returning both. A waves product without
    an analysed span, or no clean window of ``n_cycles`` periods, is an
    :class:`~flumekit.errors.InputError` naming the files.
    """
    from pathlib import Path

    from flumekit.campaign import load_campaign
    from flumekit.errors import InputError
    from flumekit.io.mfprof import read_mfprof
    from flumekit.io.netcdf import read_dataset
    from flumekit.uvp import phase_average_beams
    from flumekit.uvp.run_window import checked_window, clean_beam, waves_span

    campaign = load_campaign(Path(inputs["campaign"]).parent, runs=False)
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
