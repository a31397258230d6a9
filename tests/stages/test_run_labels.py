"""Run labels are never truncated: names of lengths 1 to 40, unicode and dots keep their
identity through every per-run product and every summary stacked along ``run``."""

import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import xarray as xr

from flumekit.io.netcdf import read_dataset
from flumekit.stages.runs import write_run
from flumekit.stages.summaries import stack_runs

# 1 to 40 characters; a name that is another's prefix (run1, run10), unicode, dots
NAMES = ["r", "run1", "run10", "T3.50_H0.250_r1", "uvp_z0.05", "uvp_z0.125", "Welle_ÄÖÜ_ß",
         "波浪_1", "a.b.c.d", "x" * 40]


def test_stacked_summary_keeps_every_name(tmp_path):
    """The first file read has the shortest name: its string width must not cut the rest."""
    inputs = {}
    for i, name in enumerate(NAMES):
        ds = xr.Dataset({"reflection_coefficient": ((), 0.1 * i)})
        params = {"run": name, "period": 2.0, "height": 0.1, "repeat": 0, "uvp_elevation": None}
        path = tmp_path / f"{i:02d}.nc"
        write_run(ds, {"dataset": path}, params, "Test", "test")
        assert read_dataset(path)["run"].item() == name
        inputs[f"{i:02d}"] = path
    stack_runs(inputs, {"dataset": tmp_path / "summary.nc"}, "Summary")
    out = read_dataset(tmp_path / "summary.nc")
    assert list(out["run"].values) == NAMES
    assert len(set(out["run"].values)) == len(NAMES)
    np.testing.assert_allclose(out["reflection_coefficient"], 0.1 * np.arange(len(NAMES)))


def test_make_keeps_run_names_of_a_lab_campaign(tmp_path):
    """A lab campaign whose runs are named run1 and run10 (and a long unicode name): the
    waves summary, built by `flumekit make`, names each run as its folder does."""
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "io"))
    from virtual_run import RUN, write_one_run

    raw = tmp_path / "raw"
    write_one_run(raw)
    names = ["run1", "run10", "run1.Welle_Ä_long_name_of_thirty_chars"]  # run1 sorts first
    for name in names:
        shutil.copytree(raw / "runs" / RUN, raw / "runs" / name)
    shutil.rmtree(raw / "runs" / RUN)
    pipe = tmp_path / "pipeline.toml"
    pipe.write_text('[pipeline]\nname = "labels"\nraw = "raw"\nprocessed = "processed"\n')
    r = subprocess.run([sys.executable, "-m", "flumekit.cli", "make", "--pipeline", str(pipe),
                        "waves_summary"], cwd=tmp_path, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    summary = read_dataset(tmp_path / "processed" / "waves_summary.nc")
    assert sorted(summary["run"].values) == sorted(names)
