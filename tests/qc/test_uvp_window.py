"""A long probe fault in a UVP run: the UVP average stays where it was, and a UVP
dropout with no clean window left is an error naming the run, the beam and the span.

One UVP run of the small virtual campaign is built twice, clean and with a 1 s dropout on WP1
and an 8 s flat line on WP3 in the middle of the 50 waves averaged. Before, the probes' common
window restarted after the faults and the 50 waves no longer fitted the record: the uvp stage
failed.
"""

import shutil
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from flumekit.errors import InputError

ROOT = Path(__file__).resolve().parents[2]
RUN = "uvp_z0.300_r0"


def _make(project: Path, *targets: str) -> None:
    from flumekit.cli import main

    code = main(["-q", "make", "--pipeline", str(project / "pipelines" / "small.toml"),
                 *targets])
    assert code == 0


def _inject_probe_faults(run: Path, t0: float) -> None:
    from flumekit.io.tables import read_text, write_table

    tx = read_text(run / "probes.csv")
    data = np.column_stack(tx.columns)
    fs = 1.0 / (data[1, 0] - data[0, 0])
    i0 = int(t0 * fs)
    data[i0:i0 + int(fs), 1] = 0.0  # WP1: 1 s dropout to 0 V
    j0 = i0 + int(20 * fs)
    data[j0:j0 + int(8 * fs), 3] = data[j0, 3]  # WP3: 8 s flat line (the value held)
    write_table(run / "probes.csv", list(zip(tx.labels, tx.units, strict=True)), data)


@pytest.fixture(scope="module")
def builds(tmp_path_factory):
    from flumekit.synth.campaign import write_virtual_base, write_virtual_run

    raw = tmp_path_factory.mktemp("raw") / "small"
    write_virtual_base(raw, "small", seed=11)
    write_virtual_run(raw, RUN)
    out = {}
    for label in ("clean", "faulty"):
        project = tmp_path_factory.mktemp(label)
        shutil.copytree(ROOT / "pipelines", project / "pipelines")
        shutil.copytree(raw, project / "raw" / "small")
        if label == "faulty":
            _inject_probe_faults(project / "raw" / "small" / "runs" / RUN, 180.0)
        _make(project, f"uvp/{RUN}")
        out[label] = project / "processed" / "small"
    return out


def test_probe_fault_does_not_move_the_uvp_average(builds):
    from flumekit.io.netcdf import read_dataset

    w = read_dataset(builds["faulty"] / "waves" / f"{RUN}.nc")
    # the probes' analysis window restarts after the faults: 50 waves from there would end
    # beyond the record (364 s)
    assert float(w.steady_start) > 190.0
    assert float(w.steady_start) + 50 * float(w.measured_period) > float(w.time[-1])
    with xr.open_dataset(builds["clean"] / "uvp" / f"{RUN}.nc") as c, \
            xr.open_dataset(builds["faulty"] / "uvp" / f"{RUN}.nc") as f:
        # the same waves averaged: the reference extrapolated over ~25 periods moves < 5 ms
        assert float(f.phase_reference) == pytest.approx(float(c.phase_reference), abs=5e-3)
        scale = float(np.nanmax(np.abs(c.beam_velocity.values)))
        d = np.abs(f.beam_velocity.values - c.beam_velocity.values)
        assert np.nanmax(d) < 0.005 * scale  # 0.26 % measured
        # the flap mask moves with the phase by a bin here and there
        same = np.isfinite(f.beam_velocity.values) == np.isfinite(c.beam_velocity.values)
        assert same.mean() > 0.995


def test_uvp_dropout_without_clean_window_names_run_beam_and_span(builds):
    """The uvp rule's window of N waves with the beams clean, from their QC flags
    (flumekit.stages.uvp.averaging_window, which the rule calls after checking the beams)."""
    from flumekit.campaign import load_campaign
    from flumekit.io.netcdf import read_dataset
    from flumekit.qc.flags import FAIL
    from flumekit.stages import qc as qc_stage
    from flumekit.stages import uvp as uvp_stage
    from flumekit.uvp.phase import default_pad

    processed = builds["clean"]
    raw = processed.parents[1] / "raw" / "small"
    qc = read_dataset(processed / "qc" / "uvp" / f"{RUN}.nc")
    t = qc["time_UP2"].values
    # UP2 drops out (every channel fails) over 200-215 s: every window of 50 waves of the
    # quasi-steady part (from 123 s) holds it
    flags = qc["beam_velocity_qc_UP2"].values.copy()
    flags[:, (t >= 200.0) & (t <= 215.0)] = FAIL
    qc["beam_velocity_qc_UP2"] = (qc["beam_velocity_qc_UP2"].dims, flags,
                                  qc["beam_velocity_qc_UP2"].attrs)
    run = next(r for r in load_campaign(raw).runs if r.id == RUN)
    beams = {b: run.path / f"{b}.mfprof" for b in ("UP1", "UP2", "UP3")}
    params = {**uvp_stage.DEFAULTS, "run": RUN, "time_offset": 0.0, "qc": qc_stage.DEFAULTS}
    waves = read_dataset(processed / "waves" / f"{RUN}.nc")
    theta = read_dataset(processed / "flap" / f"{RUN}.nc")["theta"]
    # the clean flags leave a window
    uvp_stage.averaging_window(waves, read_dataset(processed / "qc" / "uvp" / f"{RUN}.nc"),
                               theta, beams, params, default_pad(params["cutoff"]))
    with pytest.raises(InputError) as e:
        uvp_stage.averaging_window(waves, qc, theta, beams, params,
                                   default_pad(params["cutoff"]))
    msg = str(e.value)
    assert RUN in msg and "UVP beam UP2" in msg and "flagged over 200.0" in msg
    assert "UP2.mfprof" in msg  # the file


def test_uvp_rule_checks_the_beams_it_reads(builds):
    """The uvp rule checks the beams it has read (flumekit.stages.qc.check_beams) instead of
    reading the flags of a qc rule that read them too: its flag product is the Goring-Nikora
    and echo-level flags of each beam over the evaluated span (the aggregate with the gap test;
    the profiles outside are neither checked nor stored), that span is the samples its
    average reads, and its phase average is the one computed from that product read back
    (within 1e-12 relative; equal on this run)."""
    from flumekit.campaign import load_campaign
    from flumekit.io.mfprof import read_mfprof
    from flumekit.io.netcdf import read_dataset
    from flumekit.qc.flags import FAIL, aggregate
    from flumekit.qc.record import Thresholds, check_beam
    from flumekit.stages import qc as qc_stage
    from flumekit.stages import uvp as uvp_stage
    from flumekit.uvp import phase_average_beams
    from flumekit.uvp.phase import default_pad

    processed = builds["clean"]
    raw = processed.parents[1] / "raw" / "small"
    campaign = load_campaign(raw)
    run = next(r for r in campaign.runs if r.id == RUN)
    qc = read_dataset(processed / "qc" / "uvp" / f"{RUN}.nc")
    lo, hi = qc["evaluated_span"].values
    beams = {b.name: read_mfprof(run.path / f"{b.name}.mfprof") for b in campaign.uvp.beams}
    for name, b in beams.items():
        t = b["time"].values
        inside = (t >= lo) & (t <= hi)
        v = b["beam_velocity"].transpose("channel", "time").values[:, inside]
        a = b["amplitude"].transpose("channel", "time").values[:, inside]
        per = check_beam(v, t[inside], (t.size - 1) / (t[-1] - t[0]), Thresholds(),
                         floor=float(b.attrs["velocity_resolution"]), amplitude=a)
        f = qc[f"beam_velocity_qc_{name}"].transpose("channel", ...).values
        np.testing.assert_array_equal(qc[f"time_{name}"].values, t[inside])
        np.testing.assert_array_equal(f, aggregate(per["gap"], per["goring_nikora"]))
    # the analysis from the flag product read back
    params = {**uvp_stage.DEFAULTS, "run": RUN, "time_offset": 0.0, "qc": qc_stage.DEFAULTS}
    waves = read_dataset(processed / "waves" / f"{RUN}.nc")
    theta = read_dataset(processed / "flap" / f"{RUN}.nc")["theta"]
    start, period = uvp_stage.averaging_window(
        waves, qc, theta, {b: run.path / f"{b}.mfprof" for b in beams}, params,
        default_pad(params["cutoff"]))
    as_read = {n: b["beam_velocity"].values.copy() for n, b in beams.items()}
    cleaned = {n: uvp_stage.clean_beam(b, qc, n) for n, b in beams.items()}
    for n, b in beams.items():  # a copy cleaned (where a sample failed), the beam untouched
        np.testing.assert_array_equal(b["beam_velocity"].values, as_read[n])
        failed = bool((qc[f"beam_velocity_qc_{n}"] == FAIL).any())
        assert np.array_equal(cleaned[n]["beam_velocity"].values, as_read[n]) != failed
    ds = phase_average_beams(cleaned,
                             campaign.uvp, run.uvp_elevation, period=period, start=start,
                             n_cycles=params["n_cycles"], n_phase=params["n_phase"],
                             cutoff=params["cutoff"], order=params["order"], theta=theta,
                             flap_thickness=campaign.flap.thickness, margin=params["margin"],
                             min_amplitude=params["min_amplitude"])
    built = read_dataset(processed / "uvp" / f"{RUN}.nc")
    # what was checked is what the average reads: its N waves, the filter's pad either side
    # and the profile beyond (0.086 s apart)
    pad = default_pad(params["cutoff"])
    assert float(built.phase_reference) == start
    assert start - pad - 0.2 < lo < start - pad - 0.086
    assert start + params["n_cycles"] * period + pad + 0.086 < hi
    assert hi < start + params["n_cycles"] * period + pad + 0.2
    for v in ("beam_velocity", "beam_velocity_std", "beam_velocity_ci"):
        np.testing.assert_allclose(built[v].values, ds[v].values, rtol=1e-12, atol=0)
    assert np.isfinite(built["beam_velocity"].values).any()


def test_uvp_fault_in_the_first_window_checks_the_steady_part_and_moves_the_average(
        builds, tmp_path, monkeypatch):
    """The uvp rule checks the beams over the first window the waves and the flap angle allow;
    when a beam fails there (UP2 missing over 150-165 s, inside it), it checks the whole
    quasi-steady part and the average moves to the first clean window after the fault."""
    import flumekit.io.mfprof as mfprof
    from flumekit.io.netcdf import read_dataset

    clean = builds["clean"]
    project = clean.parents[1]
    copy = tmp_path / "project"
    shutil.copytree(project / "pipelines", copy / "pipelines")
    shutil.copytree(project / "raw", copy / "raw")
    read = mfprof.read_mfprof

    def faulty(path, **kw):
        b = read(path, **kw)
        if Path(path).name == "UP2.mfprof":
            t = b["time"].values
            v = b["beam_velocity"].values.copy()
            v[(t >= 150.0) & (t <= 165.0)] = np.nan  # (time, channel)
            b = b.assign(beam_velocity=b["beam_velocity"].copy(data=v))
        return b

    monkeypatch.setattr(mfprof, "read_mfprof", faulty)
    _make(copy, f"uvp/{RUN}")
    got = copy / "processed" / "small"
    first = read_dataset(clean / "qc" / "uvp" / f"{RUN}.nc")["evaluated_span"].values
    qc = read_dataset(got / "qc" / "uvp" / f"{RUN}.nc")
    span = qc["evaluated_span"].values
    assert span[0] < first[0] - 3.0 and span[1] > first[1] + 20.0  # the steady part, + margins
    start = float(read_dataset(got / "uvp" / f"{RUN}.nc").phase_reference)
    pad = 3.0  # the low-pass filter's (flumekit.uvp.phase.default_pad at 2 Hz)
    assert 165.0 < start - pad < 165.0 + 3.6  # the first start after the fault, 1 period on
    before = float(read_dataset(clean / "uvp" / f"{RUN}.nc").phase_reference)
    assert before < 150.0
