"""The record's start, from the raw file or the run, is the origin of every product's time axis
``seconds since <start>`` instead of a stand-in, which stays only when
nothing says when the record started, and then says so."""

import importlib.util
import runpy
import shutil
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from virtual_run import RUN, write_one_run

from flumekit.cli import main
from flumekit.io.dialects import Channel, Dialect, read_channels

ROOT = Path(__file__).resolve().parents[2]
PROBES = ["WP1", "WP2", "WP3", "WP4"]
# the probes' logger writes local time with its UTC offset; the flap DAQ writes UTC
PROBE_START, PROBE_START_UTC = "2024-03-05T11:12:00.250+01:00", "2024-03-05T10:12:00.25Z"
FLAP_START = "2024-03-05T10:12:01.5Z"


@pytest.fixture(scope="module")
def campaign(tmp_path_factory):
    """One virtual run whose probes CSV has date-time stamps and whose flap record is a TDMS
    file written by npTDMS (a waveform with ``wf_start_time``), as a laboratory's would be."""
    from nptdms import ChannelObject, TdmsWriter

    root = tmp_path_factory.mktemp("start") / "raw"
    template = write_one_run(root)
    run = root / "runs" / RUN
    cells = [line.split(",") for line in (run / "probes.csv").read_text().splitlines()[1:]]
    t0 = np.datetime64(PROBE_START[:-6])
    stamps = t0 + (np.rint(np.array([float(x[0]) for x in cells]) * 1000)
                   ).astype("timedelta64[ms]")
    (run / "probes.csv").write_text("time," + ",".join(f"{p} [V]" for p in PROBES) + "\n" + "".join(
        f"{s}+01:00,{','.join(x[1:])}\n" for s, x in zip(stamps, cells)))
    f = np.loadtxt(run / "flap.csv", delimiter=",", skiprows=1)
    start = np.datetime64(FLAP_START[:-1], "us")
    with TdmsWriter(run / "flap.tdms") as w:
        w.write_segment([ChannelObject("PTO", name, f[:, j], {
            "unit_string": unit, "wf_start_time": start, "wf_increment": 0.01})
            for j, name, unit in ((1, "Encoder", "counts"), (2, "Pressure", "bar"))])
    (run / "flap.csv").unlink()
    (root / "campaign.toml").write_text(template + """
[files.flap]
file = "flap.tdms"
format = "tdms"
columns = ["PTO/Encoder", "PTO/Pressure"]
time = "rate"
""")
    return root


def build(root: Path, *targets) -> Path:
    (root / "pipeline.toml").write_text(
        '[pipeline]\nname = "t"\nraw = "."\nprocessed = "../processed"\n')
    assert main(["make", "-q", "--pipeline", str(root / "pipeline.toml"), *targets]) == 0
    return root.parent / "processed"


def time_attrs(path: Path) -> dict:
    with xr.open_dataset(path, decode_times=False) as ds:
        return dict(ds["time"].attrs)


def test_every_product_with_a_time_axis_counts_from_its_record_start(campaign):
    out = build(campaign, f"waves/{RUN}", f"flap/{RUN}")
    with_time = {}
    for p in sorted(out.rglob("*.nc")):
        with xr.open_dataset(p, decode_times=False) as ds:
            if "time" in ds.variables:
                with_time[str(p.relative_to(out))] = dict(ds["time"].attrs)
    probes = {f"qc/probes/{RUN}.nc", f"eta/{RUN}.nc"}
    flap = {f"qc/flap/{RUN}.nc", f"flap/{RUN}.nc"}
    assert probes | flap <= set(with_time), with_time.keys()
    for name, attrs in with_time.items():
        start = PROBE_START_UTC if name in probes or name.startswith("waves") else FLAP_START
        assert attrs["units"] == f"seconds since {start}", name
        assert attrs["record_start"] == start and "comment" not in attrs, name
    # CF-clean (compliance-checker, tests/cf_check.py) with a real start
    if importlib.util.find_spec("compliance_checker"):
        cf = runpy.run_path(str(ROOT / "tests" / "cf_check.py"))["cf_errors"]
        errors = cf([out / "eta" / f"{RUN}.nc", out / "flap" / f"{RUN}.nc"])
        assert {k: e for k, e in errors.items() if e} == {}
    # decoded by xarray, the first probe sample is the logger's first stamp, in UTC
    with xr.open_dataset(out / "eta" / f"{RUN}.nc") as ds:
        assert ds["time"].values[0] == np.datetime64("2024-03-05T10:12:00.250")
    with xr.open_dataset(out / "flap" / f"{RUN}.nc") as ds:
        assert ds["time"].values[0] == np.datetime64("2024-03-05T10:12:01.500")


def test_run_toml_start_where_the_file_gives_none_and_refused_when_it_contradicts(
        campaign, tmp_path):
    root = tmp_path / "raw"
    shutil.copytree(campaign, root)
    run = root / "runs" / RUN
    toml = (run / "run.toml").read_text()
    # the probes file without its stamps (seconds), the run's declared start
    text = (run / "probes.csv").read_text().splitlines()
    rows = [line.split(",", 1) for line in text[1:]]
    t = (np.array([np.datetime64(r[0][:-6]) for r in rows]) - np.datetime64(PROBE_START[:-6])
         ) / np.timedelta64(1, "s")
    (run / "probes.csv").write_text("time [s]," + text[0].split(",", 1)[1] + "\n" + "".join(
        f"{x:.2f},{r[1]}\n" for x, r in zip(t, rows)))
    (run / "run.toml").write_text(toml.replace("[run]\n", "[run]\nstart = 2024-03-05T09:00:00Z\n"))
    out = build(root, f"eta/{RUN}")
    assert time_attrs(out / "eta" / f"{RUN}.nc")["units"] == "seconds since 2024-03-05T09:00:00Z"
    # the flap file gives its own start, 1 h 12 min after the declared one: refused
    assert main(["make", "-q", "--pipeline", str(root / "pipeline.toml"), f"flap/{RUN}"]) == 1
    assert not (out / "qc" / "flap" / f"{RUN}.nc").exists()
    assert not (out / "flap" / f"{RUN}.nc").exists()


def test_readers_give_the_start_their_format_carries(tmp_path):
    import h5py

    ch = [Channel("a", "voltage", "V")]
    # a netCDF time variable in CF units, decoded: times from the first sample, its instant
    ds = xr.Dataset({"a": ("t", [1.0, 2.0, 3.0], {"units": "V"})},
                    coords={"t": ("t", [0.5, 1.0, 1.5], {"units": "seconds since 2024-01-02"})})
    ds.to_netcdf(tmp_path / "a.nc")
    rec = read_channels(tmp_path / "a.nc", Dialect(format="netcdf", time="t"), ch)
    assert rec.start == "2024-01-02T00:00:00.5Z"
    np.testing.assert_array_equal(rec.time, [0.0, 0.5, 1.0])
    # an HDF5 time dataset in CF units (not decoded): its values stay, the origin is the start
    with h5py.File(tmp_path / "b.h5", "w") as h:
        h.create_dataset("a", data=[1.0, 2.0]).attrs["units"] = "V"
        h.create_dataset("time", data=[500.0, 1000.0]).attrs["units"] = \
            "ms since 2024-01-02 03:04:05"
    rec = read_channels(tmp_path / "b.h5", Dialect(format="hdf5"), ch)
    assert rec.start == "2024-01-02T03:04:05Z" and list(rec.time) == [0.5, 1.0]
    # an HDF5 file attribute; time from a column of seconds starting at 2 s
    with h5py.File(tmp_path / "a.h5", "w") as h:
        h.attrs["time_coverage_start"] = "2024-01-02T03:04:05+02:00"
        h.create_dataset("a", data=[1.0, 2.0]).attrs["units"] = "V"
        h.create_dataset("time", data=[2.0, 2.5]).attrs["units"] = "s"
    rec = read_channels(tmp_path / "a.h5", Dialect(format="hdf5"), ch)
    assert rec.start == "2024-01-02T01:04:03Z"  # the first sample (2 s) at the attribute's time
    # numbers alone: not known
    (tmp_path / "a.csv").write_text("time [s],a [V]\n0.0,1\n0.5,2\n")
    assert read_channels(tmp_path / "a.csv", Dialect(), ch).start is None
    # date-times without a zone: the logger's clock, no Z
    (tmp_path / "b.csv").write_text("time,a [V]\n2024-01-02 03:04:05.5,1\n2024-01-02 03:04:06,2\n")
    rec = read_channels(tmp_path / "b.csv", Dialect(), ch)
    assert rec.start == "2024-01-02T03:04:05.5" and list(rec.time) == [0.0, 0.5]


def test_the_stand_in_says_it_is_one(campaign, tmp_path):
    from flumekit.io.netcdf import read_dataset, write_dataset

    ds = xr.Dataset({"eta": (("time",), [0.0, 1.0])}, coords={"time": [0.0, 0.04]},
                    attrs={"Conventions": "CF-1.8", "title": "t", "source": "s", "history": "h"})
    write_dataset(ds, tmp_path / "x.nc")
    attrs = time_attrs(tmp_path / "x.nc")
    assert attrs["units"] == "seconds since 1970-01-01T00:00:00Z"
    assert attrs["record_start"] == "unknown" and "not known" in attrs["comment"]
    # read back and written again: still unknown, one comment
    write_dataset(read_dataset(tmp_path / "x.nc"), tmp_path / "y.nc")
    assert time_attrs(tmp_path / "y.nc") == attrs
