"""A long probe fault in a UVP run (issue 13): the UVP average stays where it was, and a UVP
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


def test_uvp_dropout_without_clean_window_names_run_beam_and_span(builds, tmp_path):
    from flumekit.campaign import load_campaign
    from flumekit.qc.flags import FAIL
    from flumekit.stages import uvp as uvp_stage

    processed = builds["clean"]
    raw = processed.parents[1] / "raw" / "small"
    qc = xr.load_dataset(processed / "qc" / "uvp" / f"{RUN}.nc", decode_times=False)
    t = qc["time_UP2"].values
    # UP2 drops out (every channel fails) over 200-215 s: every window of 50 waves of the
    # quasi-steady part (from 123 s) holds it
    flags = qc["beam_velocity_qc_UP2"].values.copy()
    flags[:, (t >= 200.0) & (t <= 215.0)] = FAIL
    qc["beam_velocity_qc_UP2"] = (qc["beam_velocity_qc_UP2"].dims, flags,
                                  qc["beam_velocity_qc_UP2"].attrs)
    qc.to_netcdf(tmp_path / "qc.nc")
    campaign = load_campaign(raw)
    run = next(r for r in campaign.runs if r.id == RUN)
    inputs = {b.name: run.path / f"{b.name}.mfprof" for b in campaign.uvp.beams}
    inputs.update(campaign=raw / "campaign.toml", qc=tmp_path / "qc.nc",
                  waves=processed / "waves" / f"{RUN}.nc", flap=processed / "flap" / f"{RUN}.nc")
    params = {**uvp_stage.DEFAULTS, "run": RUN, "period": 3.5, "height": 0.25, "repeat": 0,
              "uvp_elevation": 0.3, "kind": "uvp", "time_offset": 0.0}
    with pytest.raises(InputError) as e:
        uvp_stage.build(inputs, {"dataset": tmp_path / "uvp.nc"}, params)
    msg = str(e.value)
    assert RUN in msg and "UVP beam UP2" in msg and "flagged over 200.0" in msg
    assert "UP2.mfprof" in msg  # the file
    assert not (tmp_path / "uvp.nc").exists()
