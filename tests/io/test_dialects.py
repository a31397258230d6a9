"""One virtual run exported to each declared dialect builds to the same results as the original.

The variants are written with the libraries themselves (pandas-free text for the semicolon /
decimal-comma export with a preamble and datetime stamps, npTDMS, h5py, xarray/netCDF4) from the
values of the raw campaign's own CSV; calibrated metres come from the original build's
calibration. Same numbers in, so the eta, waves and flap datasets must agree to 1e-12 relative.
"""

import shutil
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from virtual_run import RUN, write_one_run

from flumekit.cli import main

PROBES = ["WP1", "WP2", "WP3", "WP4"]


@pytest.fixture(scope="module")
def original(tmp_path_factory):
    """A one-run virtual campaign (default template) built to eta, waves and flap."""
    root = tmp_path_factory.mktemp("dialects") / "original"
    write_one_run(root)
    return build(root)


def build(root: Path) -> Path:
    (root / "pipeline.toml").write_text(
        f'[pipeline]\nname = "{root.name}"\nraw = "."\nprocessed = "../{root.name}-processed"\n')
    assert main(["make", "--pipeline", str(root / "pipeline.toml"), f"waves/{RUN}",
                 f"flap/{RUN}"]) == 0
    return root.parent / f"{root.name}-processed"


def variant(original: Path, name: str, files: str, probes_units: str = "") -> Path:
    """A copy of the original campaign with its [files] tables; run files written by caller."""
    src = original.parent / "original"
    root = original.parent / name
    (root / "runs" / RUN).mkdir(parents=True)
    shutil.copytree(src / "calibration", root / "calibration")
    text = (src / "campaign.toml").read_text()
    if probes_units:
        text = text.replace('sampling_rate = 25.0     # [Hz]',
                            f'sampling_rate = 25.0\n{probes_units}')
    (root / "campaign.toml").write_text(text + "\n" + files)
    shutil.copy(src / "runs" / RUN / "run.toml", root / "runs" / RUN / "run.toml")
    return root


def raw(original: Path):
    src = original.parent / "original" / "runs" / RUN
    p = np.loadtxt(src / "probes.csv", delimiter=",", skiprows=1)
    f = np.loadtxt(src / "flap.csv", delimiter=",", skiprows=1)
    cells = [line.split(",") for line in (src / "probes.csv").read_text().splitlines()[1:]]
    fcells = [line.split(",") for line in (src / "flap.csv").read_text().splitlines()[1:]]
    return p, f, cells, fcells


def same(original: Path, processed: Path) -> None:
    for stage in ("eta", "waves", "flap"):
        # times as seconds from the record's start: a variant with date-time stamps knows when
        # its record started, the original does not, and decoded they would differ by that
        with xr.open_dataset(original / stage / f"{RUN}.nc", decode_times=False) as a, \
                xr.open_dataset(processed / stage / f"{RUN}.nc", decode_times=False) as b:
            assert set(a.data_vars) == set(b.data_vars)
            for v in a.data_vars:
                if a[v].dtype.kind in "fiu":
                    np.testing.assert_allclose(b[v].values, a[v].values, rtol=1e-12, atol=0,
                                               err_msg=f"{stage} {v}")
            np.testing.assert_array_equal(a["time"].values, b["time"].values)


def test_semicolon_decimal_comma_preamble_datetime(original):
    _, _, cells, fcells = raw(original)
    root = variant(original, "semicolon", """
[files.probes]
file = "wellen.txt"
delimiter = ";"
decimal = ","
skip_lines = 2
comment = "#"
time = "Zeitstempel"
units = "V"
[files.flap]
file = "klappe.txt"
delimiter = ";"
decimal = ","
skip_lines = 2
columns = { encoder = "Drehgeber", pressure = "Druck" }
time = "Zeit"
units = { time = "s", pressure = "bar" }
""")
    start = np.datetime64("2024-05-01T10:00:00.000")
    stamps = start + (np.rint(np.array([float(c[0]) for c in cells]) * 1000)
                      ).astype("timedelta64[ms]")
    lines = ["LabVIEW Messung 17", "Betreiber: IMFIA", "Zeitstempel;" + ";".join(PROBES),
             "# Kanäle in Volt"]
    lines += [f"{str(s).replace('T', ' ')};" + ";".join(x.replace(".", ",") for x in c[1:])
              for s, c in zip(stamps, cells)]
    (root / "runs" / RUN / "wellen.txt").write_text("\r\n".join(lines) + "\r\n\r\n\r\n",
                                                   encoding="utf-8-sig")
    flines = ["Export", "", "Zeit;Drehgeber;Druck"]
    flines += [";".join(x.replace(".", ",") for x in c) for c in fcells]
    (root / "runs" / RUN / "klappe.txt").write_text("\n".join(flines))
    processed = build(root)
    same(original, processed)
    with xr.open_dataset(processed / "eta" / f"{RUN}.nc", decode_times=False) as ds:
        assert ds["time"].attrs["units"] == "seconds since 2024-05-01T10:00:00"  # the stamps


def test_tdms_written_with_nptdms(original):
    from nptdms import ChannelObject, TdmsWriter

    p, f, _, _ = raw(original)
    root = variant(original, "tdms", """
[files.probes]
file = "probes.tdms"
format = "tdms"
group = "Wave probes"
time = "Time"
[files.flap]
file = "flap.tdms"
format = "tdms"
columns = ["PTO/Encoder", "PTO/Pressure"]
time = "rate"
""")
    with TdmsWriter(root / "runs" / RUN / "probes.tdms") as w:
        w.write_segment([ChannelObject("Wave probes", "Time", p[:, 0], {"unit_string": "s"})]
                        + [ChannelObject("Wave probes", n, p[:, j + 1], {"unit_string": "V"})
                           for j, n in enumerate(PROBES)])
    with TdmsWriter(root / "runs" / RUN / "flap.tdms") as w:
        w.write_segment([ChannelObject("PTO", "Encoder", f[:, 1], {"unit_string": "counts"}),
                         ChannelObject("PTO", "Pressure", f[:, 2], {"unit_string": "bar"})])
    same(original, build(root))


def test_hdf5_written_with_h5py(original):
    import h5py

    p, f, _, _ = raw(original)
    root = variant(original, "hdf5", """
[files.probes]
file = "run.h5"
format = "hdf5"
group = "probes"
[files.flap]
file = "run.h5"
format = "hdf5"
group = "flap"
""")
    with h5py.File(root / "runs" / RUN / "run.h5", "w") as h:
        for j, n in enumerate(["time", *PROBES]):
            h.create_dataset(f"probes/{n}", data=p[:, j]).attrs["units"] = "s" if j == 0 else "V"
        for j, (n, u) in enumerate([("time", "s"), ("encoder", "counts"), ("pressure", "bar")]):
            h.create_dataset(f"flap/{n}", data=f[:, j]).attrs["units"] = u
    same(original, build(root))


def test_netcdf_written_with_xarray(original):
    p, f, _, _ = raw(original)
    root = variant(original, "netcdf", """
[files.probes]
file = "probes.nc"
format = "netcdf"
columns = { WP1 = "eta_v1", WP2 = "eta_v2", WP3 = "eta_v3", WP4 = "eta_v4" }
time = "t"
""")
    ds = xr.Dataset({f"eta_v{j + 1}": ("t", p[:, j + 1], {"units": "mV"}) for j in range(4)},
                    coords={"t": ("t", p[:, 0] * 1000, {"units": "ms"})})
    ds = ds.map(lambda v: v * 1000)  # mV, converted back by the reader's unit table
    ds.to_netcdf(root / "runs" / RUN / "probes.nc", encoding={"t": {"dtype": "f8"}})
    shutil.copy(original.parent / "original" / "runs" / RUN / "flap.csv",
                root / "runs" / RUN / "flap.csv")
    processed = build(root)
    # mV -> V and ms -> s are a multiplication and a division apart: 1e-12, not bitwise
    for stage in ("eta", "waves"):
        with xr.open_dataset(original / stage / f"{RUN}.nc") as a, \
                xr.open_dataset(processed / stage / f"{RUN}.nc") as b:
            for v in a.data_vars:
                if a[v].dtype.kind == "f" and v != "time":
                    atol = 1e-12 * float(np.nanmax(np.abs(a[v])))
                    if v == "harmonic_reflection_coefficient":
                        # a ratio A_R,n / A_I,n: the amplitudes' rounding (held to 1e-12 of
                        # their scale above) divided by A_I,n, which for the nonlinear waves'
                        # 4th harmonic is 4 % of the first
                        amp = a["incident_harmonic_amplitude"].values
                        atol = 1e-12 * amp.max() / amp
                    close = np.isclose(b[v].values, a[v].values, rtol=1e-12, atol=atol,
                                       equal_nan=True)
                    assert close.all(), (stage, v, b[v].values, a[v].values)


def test_calibrated_metres_skip_the_calibration(original):
    p, _, _, _ = raw(original)
    root = variant(original, "metres", "", probes_units='units = "m"\nstill_water = "none"')
    with xr.open_dataset(original / "eta" / f"{RUN}.nc") as eta:
        metres = eta["eta"].transpose("probe", "time").values
    rows = np.column_stack([p[:, 0], metres.T])
    np.savetxt(root / "runs" / RUN / "probes.csv", rows, delimiter=",", comments="",
               header="time [s]," + ",".join(f"{n} [m]" for n in PROBES),
               fmt=["%.2f"] + ["%.17g"] * 4)
    shutil.copy(original.parent / "original" / "runs" / RUN / "flap.csv",
                root / "runs" / RUN / "flap.csv")
    shutil.rmtree(root / "calibration")  # not needed: the probes are calibrated
    processed = build(root)
    assert not (processed / "calibration.nc").exists()
    same(original, processed)
