"""Opening a stage's runs (flumekit.open_processed): the dataset xarray's concatenation of the
files gives, read straight into the stacked arrays (no run held in memory beside them)."""

import tracemalloc

import numpy as np
import xarray as xr

from flumekit.io.netcdf import read_dataset
from flumekit.io.processed import open_processed

N_VARS = 8


def _run(i: int, n: int, freq: np.ndarray, with_extra: bool) -> xr.Dataset:
    """One run: records of ``n`` samples at 100 Hz, a spectrum on its own frequencies, an
    integer flag record, scalar run coordinates; ``with_extra`` adds a variable the other
    runs lack."""
    rng = np.random.default_rng(i)
    t = np.arange(n) / 100.0
    ds = xr.Dataset(
        {f"record{k}": ("time", rng.standard_normal(n), {"units": "m", "long_name": f"r{k}"})
         for k in range(N_VARS)},
        coords={"time": ("time", t, {"units": "s"}), "run": f"run{i}",
                "wave_period": 2.0 + i, "frequency": ("frequency", freq, {"units": "Hz"})})
    ds["flag"] = ("time", (rng.random(n) > 0.9).astype(np.int8), {"units": "1"})
    ds["spectrum"] = ("frequency", rng.random(freq.size), {"units": "m2 s"})
    ds["mean_power"] = ((), float(i), {"units": "W", "note": "same" if i else "first"})
    if with_extra:
        ds["extra"] = ("time", np.full(n, float(i)), {"units": "1"})
    ds.attrs = {"title": f"run {i}", "Conventions": "CF-1.8"}
    return ds


def _write_runs(folder, lengths):
    """Runs of the given record lengths; the frequencies of odd runs fall between those of
    even runs (not a contiguous stretch of their union), run 1 lacks nothing, run 2 has an
    extra variable."""
    folder.mkdir()
    files = []
    for i, n in enumerate(lengths):
        freq = np.arange(5) * 0.1 + (0.05 if i % 2 else 0.0)
        ds = _run(i, n, freq, with_extra=i == 2)
        path = folder / f"run{i}.nc"
        ds.to_netcdf(path, engine="netcdf4", encoding={
            name: {"_FillValue": None} for name in ("time", "frequency")})
        files.append(path)
    return files


def test_open_processed_is_xarrays_concatenation_of_the_runs(tmp_path):
    files = _write_runs(tmp_path / "stage", [300, 500, 400, 500])
    got = open_processed(tmp_path, "stage")
    want = xr.concat([read_dataset(f) for f in files], dim="run", join="outer",
                     combine_attrs="drop_conflicts", coords="different", compat="equals")
    xr.testing.assert_identical(got, want)
    for name in got.variables:
        assert got[name].dtype == want[name].dtype, name
    # padding where a run is shorter or lacks a variable: NaN (the 8-bit integer flags became
    # 32-bit floats, as xarray promotes them)
    assert got.sizes["time"] == 500 and got.sizes["frequency"] == 10
    assert np.isnan(got["record0"].values[0, 300:]).all()
    assert got["flag"].dtype == np.float32 and np.isnan(got["flag"].values[0, 300:]).all()
    assert np.isnan(got["extra"].values[[0, 1, 3]]).all()
    np.testing.assert_array_equal(got["extra"].values[2, :400], 2.0)
    assert "note" not in got["mean_power"].attrs  # the runs disagree: dropped


def test_runs_are_read_straight_into_the_stacked_arrays(tmp_path):
    """Memory at its peak is the stacked dataset and little more: a run's values are read and
    placed one variable at a time, not every run read first and then copied (which needs the
    records of every run twice)."""
    lengths = [20_000, 30_000, 25_000, 30_000, 15_000, 30_000]
    _write_runs(tmp_path / "stage", lengths)
    payload = sum(n * (N_VARS + 2) * 8 for n in lengths)  # the runs' records as read [bytes]
    open_processed(tmp_path, "stage")  # imports and caches warmed outside the measurement
    tracemalloc.start()
    try:
        ds = open_processed(tmp_path, "stage")
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    # beside the result: the coordinates' union (every run's time axis once) and one
    # variable of one run; every run held at once would add the whole payload
    assert peak - ds.nbytes < 0.35 * payload, (peak, ds.nbytes, payload)
