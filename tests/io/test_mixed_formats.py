"""A campaign whose runs are written in different formats: each run declares its own dialect in
run.toml (``[files.probes]`` as a table of the campaign's keys). One virtual run written as the
campaign's CSV, as HDF5 (h5py) and as LabVIEW TDMS waveform channels (npTDMS, time from their
own wf_increment) builds to the same elevations as the CSV run."""

import shutil

import numpy as np
import xarray as xr
from virtual_run import RUN, write_one_run

from flumekit.cli import main

PROBES = ["WP1", "WP2", "WP3", "WP4"]


def test_csv_hdf5_and_tdms_runs_in_one_campaign(tmp_path):
    import h5py
    from nptdms import ChannelObject, TdmsWriter

    root = tmp_path / "lab"
    write_one_run(root)
    src = root / "runs" / RUN
    p = np.loadtxt(src / "probes.csv", delimiter=",", skiprows=1)
    run_toml = (src / "run.toml").read_text()
    for name, files in (("h5", '[files.probes]\nfile = "probes.h5"\nformat = "hdf5"\n'
                               'group = "probes"\n'),
                        ("tdms", '[files.probes]\nfile = "probes.tdms"\nformat = "tdms"\n'
                                 'group = "Wave probes"\n')):
        run = root / "runs" / f"{RUN}_{name}"
        run.mkdir()
        shutil.copy(src / "flap.csv", run / "flap.csv")
        (run / "run.toml").write_text(run_toml + "\n" + files)
    with h5py.File(root / "runs" / f"{RUN}_h5" / "probes.h5", "w") as h:
        for j, n in enumerate(["time", *PROBES]):
            h.create_dataset(f"probes/{n}", data=p[:, j]).attrs["units"] = "s" if j == 0 else "V"
    dt = float(p[1, 0] - p[0, 0])
    with TdmsWriter(root / "runs" / f"{RUN}_tdms" / "probes.tdms") as w:
        # waveform channels: their time is their own (wf_increment), no time key declared
        w.write_segment([ChannelObject("Wave probes", n, p[:, j + 1],
                                       {"unit_string": "V", "wf_increment": dt,
                                        "wf_start_offset": 0.0})
                         for j, n in enumerate(PROBES)])
    (root / "pipeline.toml").write_text('[pipeline]\nname = "lab"\nraw = "."\n'
                                        'processed = "processed"\n')
    runs = [RUN, f"{RUN}_h5", f"{RUN}_tdms"]
    assert main(["make", "--pipeline", str(root / "pipeline.toml"),
                 *(f"eta/{r}" for r in runs)]) == 0
    with xr.open_dataset(root / "processed" / "eta" / f"{RUN}.nc", decode_times=False) as a:
        for r in runs[1:]:
            with xr.open_dataset(root / "processed" / "eta" / f"{r}.nc",
                                 decode_times=False) as b:
                np.testing.assert_allclose(b["eta"].values, a["eta"].values, rtol=1e-12,
                                           err_msg=r)
                np.testing.assert_allclose(b["time"].values, a["time"].values, rtol=1e-12)


def test_a_csv_declaration_of_an_hdf5_file_names_hdf5(tmp_path, capsys):
    import h5py

    root = tmp_path / "lab"
    write_one_run(root)
    run = root / "runs" / RUN
    (run / "probes.csv").unlink()
    with h5py.File(run / "probes.csv", "w") as h:  # an HDF5 file under a CSV name
        h.create_dataset("probes/WP1", data=np.zeros(10))
    (root / "pipeline.toml").write_text('[pipeline]\nname = "lab"\nraw = "."\n'
                                        'processed = "processed"\n')
    assert main(["make", "--pipeline", str(root / "pipeline.toml"), f"eta/{RUN}"]) == 1
    err = capsys.readouterr().err
    assert "HDF5" in err and "probes.csv" in err and "Traceback" not in err
