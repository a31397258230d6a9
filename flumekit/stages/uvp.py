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
from flumekit.stages.runs import run_params, write_run

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
    from flumekit.stages import qc as qc_stage

    c = ctx.campaign
    runs = [r for r in c.runs if r.kind == "uvp"]
    qc_params = ctx.stage_params("qc", qc_stage.DEFAULTS)
    qc = {k: qc_params[k] for k in qc_stage.UVP_PARAMS}
    out = []
    for run in runs:
        inputs = {b.name: run.path / f"{b.name}.mfprof" for b in c.uvp.beams}
        inputs.update(campaign=ctx.campaign_file, waves=ctx.out("waves", f"{run.id}.nc"),
                      flap=ctx.out("flap", f"{run.id}.nc"))
        p = {**params, **run_params(run, c), "time_offset": run.clock.get("uvp", 0.0), "qc": qc}
        # the rule checks the beams it reads before analysing them and writes their QC flags
        # too (flumekit.stages.qc.check_beams)
        out.append(Rule(f"uvp/{run.id}", "flumekit.stages.uvp:build", inputs=inputs,
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


def phase_reference(waves):
    """(up-crossings, period): the zero up-crossings of the incident wave at the flap in the
    waves' analysis window (where the separation is defined) [s], and the measured period."""
    import numpy as np

    from flumekit.signal import zero_upcrossings

    t = waves["time"].values
    inside = (t >= float(waves["steady_start"])) & (t <= float(waves["steady_end"]))
    eta = waves["eta_incident"].values[inside]
    if not np.all(np.isfinite(eta)):
        eta = np.nan_to_num(eta)
    ups = zero_upcrossings(eta, t[inside])
    if ups.size == 0:
        raise ValueError("no zero up-crossing of the incident wave in the quasi-steady window")
    return ups, float(waves["measured_period"])


def clean_beam(beam, qc, name: str, copy: bool = True):
    """The beam's velocities with the samples that failed quality control masked and short
    gaps interpolated (:func:`flumekit.qc.record.clean`, the flags of the qc stage), over the
    profiles checked (``time_<name>`` of ``qc``); the others as read. ``copy=False``: the
    beam's own velocity array is cleaned (a beam read for the caller)."""
    import numpy as np

    from flumekit.conventions import MAX_GAP
    from flumekit.qc.record import clean

    flags = qc[f"beam_velocity_qc_{name}"].transpose("channel", ...).values
    t = beam["time"].values
    checked = qc[f"time_{name}"].values
    i0 = int(np.searchsorted(t, checked[0])) if checked.size else 0
    span = slice(i0, i0 + checked.size)
    if not np.array_equal(t[span], checked):
        raise ValueError(f"beam {name}: the QC flags are not of this record's profiles")
    v = beam["beam_velocity"].transpose("channel", "time").values
    out = np.array(v) if copy else v
    fs = (t.size - 1) / (t[-1] - t[0])
    cleaned = clean(out[:, span], flags, fs, float(qc.attrs[MAX_GAP]), copy=False)
    if not np.may_share_memory(cleaned, out):  # cleaned in place, as a rule
        out[:, span] = cleaned
    return beam.assign(beam_velocity=beam["beam_velocity"].copy(
        data=out.T if beam["beam_velocity"].dims[0] == "time" else out))


#: a profile most of whose channels failed quality control is a dropout of the instrument
DROPOUT_FRACTION = 0.5


def uvp_span(waves) -> tuple[float, float]:
    """The quasi-steady part of a run's wave field, probe faults bridged
    (:func:`flumekit.uvp.window.steady_span` on the waves stage's dataset) [s]."""
    from flumekit.uvp.window import steady_span

    return steady_span(waves["eta"].transpose("probe", "time").values, waves["time"].values,
                       waves["amplitude_scale"].values, waves["steady_tolerance"].values,
                       0.75 * float(waves.attrs["wave_period"]))


def qc_span(span: tuple[float, float], period: float, cutoff: float) -> tuple[float, float]:
    """The span of the UVP records quality-controlled when the average's first window is not
    clean [s]: the quasi-steady part of the waves ``span`` (:func:`uvp_span`) and, on each
    side, the low-pass filter's pad and one period [s] more (the average starts on an
    up-crossing near the span's edge): every sample the average may read."""
    from flumekit.uvp.phase import default_pad

    margin = default_pad(cutoff) + period
    return span[0] - margin, span[1] + margin


def window_span(beams, start: float, end: float, pad: float) -> tuple[float, float]:
    """The span of the UVP records that the average of the waves ``start``-``end`` reads [s]
    (probes' clock): ``pad`` either side and the profile beyond each end
    (:func:`flumekit.uvp.phase.phase_average_beams` takes the samples around its window)."""
    dt = max(float(b["time"][-1] - b["time"][0]) / max(b.sizes["time"] - 1, 1)
             for b in beams.values())
    return start - pad - 1.5 * dt, end + pad + 1.5 * dt


def beam_records(qc, names, offset: float = 0.0) -> dict:
    """Per beam, the profiles at which most channels failed QC (or were missing), as the
    average's window sees them (:class:`flumekit.uvp.window.Flagged`, probes' clock)."""
    from flumekit.qc.flags import FAIL, MISSING
    from flumekit.uvp.window import Flagged

    out = {}
    for name in names:
        f = qc[f"beam_velocity_qc_{name}"].transpose("channel", ...).values
        bad = ((f == FAIL) | (f == MISSING)).mean(axis=0) > DROPOUT_FRACTION
        out[f"UVP beam {name}"] = Flagged(qc[f"time_{name}"].values + offset, bad)
    return out


def averaging_window(waves, qc, theta, beams, params, pad: float, span=None
                     ) -> tuple[float, float]:
    """(start, period) of the run's phase average (:func:`flumekit.uvp.window.averaging_start`):
    N periods in the quasi-steady part of the waves (``span`` [s], default :func:`uvp_span`)
    with the UVP beams (their QC flags ``qc``; None: the beams not considered) and the flap
    angle clean. An error names the run, the instrument and its flagged span when there is
    none."""
    import numpy as np

    from flumekit.errors import InputError
    from flumekit.uvp.window import Flagged, averaging_start

    ups, period = phase_reference(waves)
    records = {} if qc is None else beam_records(qc, beams, float(params["time_offset"]))
    records["flap angle"] = Flagged(theta["time"].values, ~np.isfinite(theta.values))
    try:
        span = uvp_span(waves) if span is None else span
        start = averaging_start(ups, period, params["n_cycles"], pad, span, records,
                                float(params["qc"]["max_gap"]), run=params["run"])
    except ValueError as e:
        raise InputError(", ".join(str(p) for p in beams.values()), str(e)) from None
    return start, period


def build(inputs, outputs, params) -> list[Written]:
    """The run's beams read once, quality-controlled (:func:`flumekit.stages.qc.check_beams`,
    which writes their flags), cleaned and phase-averaged."""
    from pathlib import Path

    from flumekit.campaign import load_campaign
    from flumekit.errors import InputError
    from flumekit.io.mfprof import read_mfprof
    from flumekit.io.netcdf import read_dataset
    from flumekit.stages.qc import check_beams
    from flumekit.uvp import phase_average_beams
    from flumekit.uvp.phase import default_pad
    from flumekit.uvp.window import blocking

    campaign = load_campaign(Path(inputs["campaign"]).parent)
    names = [b.name for b in campaign.uvp.beams]
    raw = {n: read_mfprof(inputs[n]) for n in names}
    waves = read_dataset(inputs["waves"])
    try:
        span = uvp_span(waves)
    except ValueError as e:
        raise InputError(inputs["waves"], f"run {params['run']}: {e}") from None
    theta = read_dataset(inputs["flap"])["theta"]
    files = {n: inputs[n] for n in names}
    pad = default_pad(params["cutoff"])
    # the average takes the earliest window of N waves with every instrument it reads clean.
    # The beams are checked first over the earliest window the waves and the flap angle
    # allow, the samples the average then reads (with clean beams, the usual case, it is the
    # average's: 70 % of the quasi-steady part at the paper's 50 waves of 3.5 s), and over the
    # whole quasi-steady part, where the window may then move, only when a fault rules it out
    start, period = averaging_window(waves, None, theta, files, params, pad, span)
    end = start + params["n_cycles"] * period
    offset = float(params["time_offset"])
    qc, qc_file = check_beams(raw, window_span(raw, start, end, pad), params, outputs["qc"],
                              list(files.values()))
    if blocking(beam_records(qc, names, offset), start - pad, end + pad,
                float(params["qc"]["max_gap"]))[0]:
        qc, qc_file = check_beams(raw, qc_span(span, period, params["cutoff"]), params,
                                  outputs["qc"], list(files.values()))
        start, period = averaging_window(waves, qc, theta, files, params, pad, span)
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


def field(inputs, outputs, params) -> Written:
    from pathlib import Path

    from flumekit.campaign import load_campaign
    from flumekit.io.netcdf import read_dataset, write_product
    from flumekit.uvp import velocity_field

    campaign = load_campaign(Path(inputs["campaign"]).parent)
    runs = [read_dataset(p) for name, p in sorted(inputs.items()) if name != "campaign"]
    ds = velocity_field(runs, campaign.uvp, height=params["height"], period=params["period"],
                        method=params["method"], dx=params["dx"],
                        water_depth=campaign.flume.water_depth)
    return write_product(ds, outputs["dataset"],
                         "Phase-averaged velocity field in front of the flap",
                         f"flumekit uvp_field stage from {len(runs)} UVP runs", params)
